//! Texture files: PNG (or any format the `image` build supports) decoded to the renderer's
//! [`Texture`].

use std::path::Path;

use mblur::texture::{Texture, srgb_to_linear};

use crate::error::{Error, Result};

/// Loads a PNG (or any format the `image` build supports), decoding sRGB to linear.
pub fn load(path: &Path) -> Result<Texture> {
    let reader = image::ImageReader::open(path).map_err(|e| Error::read(path, e))?;
    let reader = reader
        .with_guessed_format()
        .map_err(|e| Error::read(path, e))?;
    let img = reader
        .decode()
        .map_err(|e| Error::format(path, format!("cannot decode image: {e}")))?
        .into_rgba8();
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
