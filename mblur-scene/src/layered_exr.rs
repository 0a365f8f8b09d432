//! Multi-channel OpenEXR: the image and its AOVs ([`mblur::Aovs`]) in one file, written
//! atomically. Channels follow the OpenEXR layer naming convention (`layer.channel`, one
//! part): the image is `R`, `G`, `B`; the AOVs are `depth.Z`, `motion.X`, `motion.Y`,
//! `sharp.R`, `sharp.G`, `sharp.B`, `id.X` and `coverage.X`, all 32-bit float (object ids are
//! exact below 2^24).

use std::path::Path;

use exr::prelude::{AnyChannel, AnyChannels, Encoding, FlatSamples, Image, Layer, LayerAttributes};
use exr::prelude::{ReadChannels, ReadLayers, WritableImage};
use mblur::{Aovs, Image as Rgb};
use smallvec::SmallVec;

use crate::error::{Error, Result};

/// One named channel of `width * height` samples, row-major from the top row.
pub type Channel = (String, Vec<f32>);

/// The image's `R`, `G`, `B` and the channels of every AOV present, in that order.
pub fn channels(image: &Rgb, aovs: Option<&Aovs>) -> Vec<Channel> {
    let rgb = |prefix: &str, im: &Rgb| -> Vec<Channel> {
        ["R", "G", "B"]
            .iter()
            .enumerate()
            .map(|(k, c)| {
                (
                    format!("{prefix}{c}"),
                    im.pixels.iter().map(|p| p[k]).collect(),
                )
            })
            .collect()
    };
    let mut out = rgb("", image);
    let Some(aovs) = aovs else {
        return out;
    };
    if let Some(d) = &aovs.depth {
        out.push(("depth.Z".into(), d.clone()));
    }
    if let Some(m) = &aovs.motion {
        out.push(("motion.X".into(), m.iter().map(|v| v[0]).collect()));
        out.push(("motion.Y".into(), m.iter().map(|v| v[1]).collect()));
    }
    if let Some(s) = &aovs.sharp {
        out.extend(rgb("sharp.", s));
    }
    if let Some(ids) = &aovs.id {
        out.push(("id.X".into(), ids.iter().map(|&i| i as f32).collect()));
    }
    if let Some(c) = &aovs.coverage {
        out.push(("coverage.X".into(), c.clone()));
    }
    out
}

/// Writes `image` and `aovs` to the EXR file `path` (lossless ZIP compression), atomically.
pub fn save(image: &Rgb, aovs: &Aovs, path: &Path) -> Result<()> {
    let bytes = encode(image, Some(aovs)).map_err(|message| Error::Write {
        path: path.to_path_buf(),
        message,
    })?;
    crate::atomic::write_atomic(path, &bytes)
}

/// The EXR file of `image` and its `aovs` (if any), ZIP-compressed: the one EXR writer of
/// the crate (a plain image is its `R`, `G`, `B` alone).
pub(crate) fn encode(image: &Rgb, aovs: Option<&Aovs>) -> std::result::Result<Vec<u8>, String> {
    if let Some(aovs) = aovs
        && (image.width, image.height) != (aovs.width, aovs.height)
    {
        return Err(format!(
            "the AOVs are {} x {}, the image {} x {}",
            aovs.width, aovs.height, image.width, image.height
        ));
    }
    let size = (image.width as usize, image.height as usize);
    let list: SmallVec<[AnyChannel<FlatSamples>; 4]> = channels(image, aovs)
        .into_iter()
        .map(|(name, samples)| AnyChannel::new(name.as_str(), FlatSamples::F32(samples)))
        .collect();
    let layer = Layer::new(
        size,
        LayerAttributes::default(),
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(list),
    );
    let mut bytes = std::io::Cursor::new(Vec::new());
    Image::from_layer(layer)
        .write()
        .to_buffered(&mut bytes)
        .map_err(|e| e.to_string())?;
    Ok(bytes.into_inner())
}

/// Reads every channel of the first part of an EXR file (at most
/// [`MAX_IMAGE_BYTES`](crate::input::MAX_IMAGE_BYTES)), with its size, as f32, channels
/// sorted by name.
pub fn read(path: &Path) -> Result<((u32, u32), Vec<Channel>)> {
    let bytes = crate::input::read_bounded(path, crate::input::MAX_IMAGE_BYTES, "image file")?;
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| Error::format(path, format!("not a readable EXR file: {e}")))?;
    let layer = image.layer_data;
    let size = layer.size;
    let dims = (
        u32::try_from(size.0).map_err(|_| Error::format(path, "image too wide"))?,
        u32::try_from(size.1).map_err(|_| Error::format(path, "image too tall"))?,
    );
    let channels = layer
        .channel_data
        .list
        .iter()
        .map(|c| {
            let samples = c.sample_data.values_as_f32().collect();
            (c.name.to_string(), samples)
        })
        .collect();
    Ok((dims, channels))
}
