//! Texture files: PNG (or any format the `image` build supports) decoded to the renderer's
//! [`Texture`].

use std::path::Path;

use mblur::texture::Texture;

use crate::error::{Error, Result};
use crate::image_io::{DecodeLimits, decode_bounded, decode_bytes_bounded};

/// Most texels one texture file may decode to (8192 x 8192): each is stored as 4 bytes
/// (8-bit sRGB RGBA), so this bounds a texture at 256 MiB (a file of another pixel type is
/// converted, holding at most twice that while it is). Checked from the file's header before
/// anything is decoded.
pub const MAX_TEXELS: u64 = 1 << 26;

/// The limits of a texture image.
const LIMITS: DecodeLimits = DecodeLimits {
    bytes: crate::input::MAX_TEXTURE_BYTES,
    pixels: MAX_TEXELS,
    what: "texture",
    unit: "texel",
};

/// Decodes a texture image held in memory (PNG, or any format the `image` build supports;
/// `label` names it in messages) to its size and 8-bit sRGB RGBA texels, refusing one
/// whose header declares more than [`MAX_TEXELS`] texels.
pub fn decode_rgba8(label: &Path, bytes: &[u8]) -> Result<(u32, u32, Vec<u8>)> {
    if bytes.len() as u64 > crate::input::MAX_TEXTURE_BYTES {
        return Err(Error::format(label, "texture image exceeds 256 MiB"));
    }
    let img = decode_bytes_bounded(label, bytes, LIMITS)?.into_rgba8();
    let (w, h) = img.dimensions();
    if w == 0 || h == 0 {
        return Err(Error::format(label, "image is empty"));
    }
    Ok((w, h, img.into_raw()))
}

/// Loads a PNG (or any format the `image` build supports) as 8-bit sRGB texels. The file
/// must be a regular file of at most [`MAX_TEXTURE_BYTES`](crate::input::MAX_TEXTURE_BYTES)
/// bytes whose header declares at most [`MAX_TEXELS`] texels.
pub fn load(path: &Path) -> Result<Texture> {
    let img = decode_bounded(path, LIMITS)?.into_rgba8();
    let (w, h) = img.dimensions();
    if w == 0 || h == 0 {
        return Err(Error::format(path, "image is empty"));
    }
    Texture::from_srgb8(w, h, img.into_raw())
        .ok_or_else(|| Error::format(path, "decoded texel count does not match the header"))
}
