//! Texture files: PNG (or any format the `image` build supports) decoded to the renderer's
//! [`Texture`].

use std::path::Path;

use mblur::texture::{Texture, srgb_to_linear};

use crate::error::{Error, Result};
use crate::image_io::{DecodeLimits, decode_bounded};

/// Most texels one texture file may decode to (4096 x 4096): each is stored as four f64
/// (32 bytes), so this bounds a texture at 512 MiB. Checked from the file's header before
/// anything is decoded.
pub const MAX_TEXELS: u64 = 1 << 24;

/// Loads a PNG (or any format the `image` build supports), decoding sRGB to linear. The file
/// must be a regular file of at most [`MAX_TEXTURE_BYTES`](crate::input::MAX_TEXTURE_BYTES)
/// bytes whose header declares at most [`MAX_TEXELS`] texels.
pub fn load(path: &Path) -> Result<Texture> {
    let limits = DecodeLimits {
        bytes: crate::input::MAX_TEXTURE_BYTES,
        pixels: MAX_TEXELS,
        what: "texture",
        unit: "texel",
    };
    let img = decode_bounded(path, limits)?.into_rgba8();
    let (w, h) = img.dimensions();
    if w == 0 || h == 0 {
        return Err(Error::format(path, "image is empty"));
    }
    let texels = img
        .pixels()
        .map(|p| {
            let c = |v: u8| srgb_to_linear(f64::from(v) / 255.0);
            [c(p[0]), c(p[1]), c(p[2]), f64::from(p[3]) / 255.0]
        })
        .collect();
    Ok(Texture::from_straight(w, h, texels))
}
