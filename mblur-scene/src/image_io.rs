//! Image files: PNG (sRGB 8-bit), EXR (linear 32-bit float) and PFM (linear 32-bit float,
//! for exact comparisons), chosen by extension and written atomically — to a temporary file
//! in the target folder, then renamed — so an error never leaves a partial or empty file
//! behind.

use std::path::Path;

use mblur::Image;
use mblur::texture::srgb_to_linear;

use crate::error::{Error, Result};

/// Output file formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// 8-bit sRGB PNG.
    Png,
    /// Linear float OpenEXR.
    Exr,
    /// Linear float portable float map.
    Pfm,
}

impl Format {
    /// The format for a file name's extension (case-insensitive).
    pub fn from_path(path: &Path) -> Result<Format> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("png") => Ok(Format::Png),
            Some("exr") => Ok(Format::Exr),
            Some("pfm") => Ok(Format::Pfm),
            _ => Err(Error::Write {
                path: path.to_path_buf(),
                message: "unsupported extension (use .png, .exr or .pfm)".into(),
            }),
        }
    }
}

/// Reads an image file as linear RGB: PFM (any `PF` file), EXR (linear float) or PNG and
/// the other 8/16-bit formats the `image` build reads (sRGB decoded to linear), chosen by
/// content for PNG/EXR and by the `.pfm` extension for PFM. The file must be a regular file
/// of at most [`MAX_IMAGE_BYTES`](crate::input::MAX_IMAGE_BYTES) bytes holding at most
/// [`MAX_PIXELS`](crate::validate::MAX_PIXELS) pixels (checked from its header before
/// decoding); alpha is dropped.
pub fn read(path: &Path) -> Result<Image> {
    if Format::from_path(path).ok() == Some(Format::Pfm) {
        return read_pfm(path);
    }
    let decoded = decode_bounded(
        path,
        DecodeLimits {
            bytes: crate::input::MAX_IMAGE_BYTES,
            pixels: crate::validate::MAX_PIXELS,
            what: "image",
            unit: "pixel",
        },
    )?;
    let (w, h) = (decoded.width(), decoded.height());
    let linear = is_linear(&decoded);
    let rgb = decoded.into_rgb32f();
    let pixels = rgb
        .pixels()
        .map(|p| {
            if linear {
                p.0
            } else {
                p.0.map(|c| srgb_to_linear(f64::from(c)) as f32)
            }
        })
        .collect();
    Ok(Image {
        width: w,
        height: h,
        pixels,
    })
}

/// The limits [`decode_bounded`] checks before decoding an image file.
#[derive(Debug, Clone, Copy)]
pub struct DecodeLimits {
    /// Largest file, in bytes.
    pub bytes: u64,
    /// Most pixels the header may declare.
    pub pixels: u64,
    /// What the file is, for messages (`texture`, `image`).
    pub what: &'static str,
    /// What a pixel of it is called, for messages (`texel`, `pixel`).
    pub unit: &'static str,
}

/// Decodes the image file at `path` (format guessed from its content), refusing before
/// decoding a file that is not a regular file, is larger than `limits.bytes`, or whose
/// header declares more than `limits.pixels` pixels.
pub fn decode_bounded(path: &Path, limits: DecodeLimits) -> Result<image::DynamicImage> {
    let what = limits.what;
    let bytes = crate::input::read_bounded(path, limits.bytes, &format!("{what} file"))?;
    decode_bytes_bounded(path, &bytes, limits)
}

/// Decodes an image held in memory (format guessed from its content; `path` names it in
/// messages: its file, or the file embedding it), refusing before decoding one whose header
/// declares more than `limits.pixels` pixels.
pub fn decode_bytes_bounded(
    path: &Path,
    bytes: &[u8],
    limits: DecodeLimits,
) -> Result<image::DynamicImage> {
    let what = limits.what;
    let reader = || {
        image::ImageReader::new(std::io::Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| Error::read(path, e))
    };
    let bad = |e: image::ImageError| Error::format(path, format!("cannot decode image: {e}"));
    let (w, h) = reader()?.into_dimensions().map_err(bad)?;
    let (n, max, unit) = (u64::from(w) * u64::from(h), limits.pixels, limits.unit);
    if n > max {
        return Err(Error::format(
            path,
            format!("a {w} x {h} {what} has {n} {unit}s, more than the limit of {max}"),
        ));
    }
    reader()?.decode().map_err(bad)
}

/// True for float images (EXR), whose values are linear; 8/16-bit images are sRGB.
fn is_linear(image: &image::DynamicImage) -> bool {
    matches!(
        image,
        image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_)
    )
}

/// Checks, before a long render, that an image can be written to `path`: a known extension
/// and an existing, writable folder (a temporary file is created there and removed). The
/// error names `path`, never the temporary file.
pub fn check_writable(path: &Path) -> Result<()> {
    Format::from_path(path)?;
    crate::atomic::temp_file_beside(path).map(drop)
}

/// PFM bytes: header `PF`, little-endian scale -1, rows bottom to top.
pub fn to_pfm(image: &Image) -> Vec<u8> {
    let mut out = format!("PF\n{} {}\n-1.0\n", image.width, image.height).into_bytes();
    for row in (0..image.height as usize).rev() {
        let w = image.width as usize;
        for p in &image.pixels[row * w..(row + 1) * w] {
            for c in p {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
    }
    out
}

/// Writes the image to `path` in the format of its extension, atomically.
pub fn save(image: &Image, path: &Path) -> Result<()> {
    let format = Format::from_path(path)?;
    let werr = |m: String| Error::Write {
        path: path.to_path_buf(),
        message: m,
    };
    let bytes = match format {
        Format::Pfm => to_pfm(image),
        Format::Png => {
            let mut bytes = std::io::Cursor::new(Vec::new());
            image::DynamicImage::ImageRgb8(
                image::RgbImage::from_raw(image.width, image.height, image.to_srgb8())
                    .ok_or_else(|| werr("image size mismatch".into()))?,
            )
            .write_to(&mut bytes, image::ImageFormat::Png)
            .map_err(|e| werr(e.to_string()))?;
            bytes.into_inner()
        }
        Format::Exr => crate::layered_exr::encode(image, None).map_err(werr)?,
    };
    crate::atomic::write_atomic(path, &bytes)
}

/// Reads a PFM file written by [`save`] (or any RGB `PF` file).
pub fn read_pfm(path: &Path) -> Result<Image> {
    let bytes = crate::input::read_bounded(path, crate::input::MAX_IMAGE_BYTES, "image file")?;
    let bad = |m: &str| Error::format(path, format!("not a PFM file: {m}"));
    // Header: three whitespace-separated tokens lines.
    let mut fields = Vec::new();
    let mut pos = 0;
    while fields.len() < 4 && pos < bytes.len() {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        fields.push(String::from_utf8_lossy(&bytes[start..pos]).to_string());
    }
    pos += 1; // the single whitespace after the scale
    if fields.len() < 4 || fields[0] != "PF" {
        return Err(bad("header"));
    }
    let w: u32 = fields[1].parse().map_err(|_| bad("width"))?;
    let h: u32 = fields[2].parse().map_err(|_| bad("height"))?;
    let scale: f64 = fields[3].parse().map_err(|_| bad("scale"))?;
    let n = w as usize * h as usize;
    let data = bytes.get(pos..).ok_or_else(|| bad("truncated"))?;
    if data.len() < n * 12 {
        return Err(bad("truncated"));
    }
    let mut pixels = vec![[0.0f32; 3]; n];
    for (k, chunk) in data.chunks_exact(4).take(n * 3).enumerate() {
        let b = [chunk[0], chunk[1], chunk[2], chunk[3]];
        let v = if scale < 0.0 {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        };
        let (p, c) = (k / 3, k % 3);
        let (row, col) = (p / w as usize, p % w as usize);
        let dst = (h as usize - 1 - row) * w as usize + col;
        pixels[dst][c] = v;
    }
    Ok(Image {
        width: w,
        height: h,
        pixels,
    })
}
