//! Image files: PNG (sRGB 8-bit), EXR (linear 32-bit float) and PFM (linear 32-bit float,
//! for exact comparisons), chosen by extension and written atomically — to a temporary file
//! in the target folder, then renamed — so an error never leaves a partial or empty file
//! behind.

use std::io::Read;
use std::path::Path;

use mblur::Image;

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
        Format::Exr => {
            let data: Vec<f32> = image.pixels.iter().flatten().copied().collect();
            let buf = image::Rgb32FImage::from_raw(image.width, image.height, data)
                .ok_or_else(|| werr("image size mismatch".into()))?;
            let mut bytes = std::io::Cursor::new(Vec::new());
            image::DynamicImage::ImageRgb32F(buf)
                .write_to(&mut bytes, image::ImageFormat::OpenExr)
                .map_err(|e| werr(e.to_string()))?;
            bytes.into_inner()
        }
    };
    crate::atomic::write_atomic(path, &bytes)
}

/// Reads a PFM file written by [`save`] (or any RGB `PF` file).
pub fn read_pfm(path: &Path) -> Result<Image> {
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|mut f| f.read_to_end(&mut bytes))
        .map_err(|e| Error::read(path, e))?;
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
