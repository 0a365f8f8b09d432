//! Rendered images: linear RGB pixels, row 0 at the top (`mblur-scene` writes them as PNG,
//! EXR or PFM).

use crate::texture::linear_to_srgb;

/// A linear RGB image, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major linear RGB pixels.
    pub pixels: Vec<[f32; 3]>,
}

impl Image {
    /// An image filled with one colour.
    pub fn filled(width: u32, height: u32, rgb: [f32; 3]) -> Self {
        Image {
            width,
            height,
            pixels: vec![rgb; width as usize * height as usize],
        }
    }

    /// Root-mean-square difference from `other` over all RGB channels, in linear units
    /// (None when the sizes differ or the image is empty). The error metric the method tests
    /// and tables report against the accum reference.
    pub fn rmse(&self, other: &Image) -> Option<f64> {
        if (self.width, self.height) != (other.width, other.height) || self.pixels.is_empty() {
            return None;
        }
        let sum: f64 = self
            .pixels
            .iter()
            .zip(&other.pixels)
            .flat_map(|(p, q)| (0..3).map(move |k| (f64::from(p[k]) - f64::from(q[k])).powi(2)))
            .sum();
        Some((sum / (3 * self.pixels.len()) as f64).sqrt())
    }

    /// The pixel at column `x`, row `y` (None outside the image).
    pub fn get(&self, x: u32, y: u32) -> Option<[f32; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.pixels
            .get(y as usize * self.width as usize + x as usize)
            .copied()
    }

    /// 8-bit sRGB bytes (RGB), rounded, clamped to [0, 1].
    pub fn to_srgb8(&self) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|p| {
                p.map(|c| (linear_to_srgb(f64::from(c).clamp(0.0, 1.0)) * 255.0).round() as u8)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rmse_of_known_differences() {
        let a = Image::filled(2, 1, [0.0, 0.0, 0.0]);
        let mut b = a.clone();
        b.pixels[0] = [1.0, 0.0, 0.0];
        b.pixels[1] = [0.0, 1.0, 1.0];
        // Three of six channels differ by 1: sqrt(3 / 6).
        assert_eq!(a.rmse(&b), Some(0.5f64.sqrt()));
        assert_eq!(a.rmse(&a), Some(0.0));
        assert_eq!(a.rmse(&Image::filled(1, 2, [0.0; 3])), None);
        assert_eq!(
            Image::filled(0, 0, [0.0; 3]).rmse(&Image::filled(0, 0, [0.0; 3])),
            None
        );
    }
}
