//! Textures: PNG files (sRGB decoded to linear) and procedural checkerboards, stored as
//! premultiplied linear RGBA and sampled bilinearly with wrap-around.

use glam::DVec2;

/// A texture in premultiplied linear RGBA, row 0 at the top of the image.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Texels, row-major from the top row, premultiplied linear RGBA.
    pub texels: Vec<[f64; 4]>,
    /// True when some texel has alpha < 1.
    pub has_alpha: bool,
}

/// sRGB transfer function, decode (IEC 61966-2-1).
pub fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// sRGB transfer function, encode (IEC 61966-2-1).
pub fn linear_to_srgb(c: f64) -> f64 {
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

fn premultiply(c: [f64; 4]) -> [f64; 4] {
    [c[0] * c[3], c[1] * c[3], c[2] * c[3], c[3]]
}

impl Texture {
    /// Builds a texture from straight-alpha linear texels (premultiplies them).
    pub fn from_straight(width: u32, height: u32, texels: Vec<[f64; 4]>) -> Self {
        let has_alpha = texels.iter().any(|t| t[3] < 1.0);
        Texture {
            width,
            height,
            texels: texels.into_iter().map(premultiply).collect(),
            has_alpha,
        }
    }

    /// A `squares` x `squares` checkerboard, `texels_per_square` texels per cell; cell (0, 0)
    /// (top left) has colour `a`. Colours are straight linear RGBA.
    pub fn checker(squares: u32, texels_per_square: u32, a: [f64; 4], b: [f64; 4]) -> Self {
        let n = squares.max(1) * texels_per_square.max(1);
        let tps = texels_per_square.max(1);
        let texels = (0..n * n)
            .map(|k| {
                let (x, y) = (k % n, k / n);
                if (x / tps + y / tps).is_multiple_of(2) {
                    a
                } else {
                    b
                }
            })
            .collect();
        Texture::from_straight(n, n, texels)
    }

    /// Texel (x, y) of a texel grid position already wrapped into the texture.
    fn texel(&self, x: i64, y: i64) -> [f64; 4] {
        self.texels
            .get((y * i64::from(self.width) + x) as usize)
            .copied()
            .unwrap_or([0.0; 4])
    }

    /// Bilinear sample at `uv` (v up, wrap-around), premultiplied RGBA. Texel centres are at
    /// ((i + 0.5) / width, 1 - (j + 0.5) / height). Non-finite `uv` gives transparent black.
    pub fn sample(&self, uv: DVec2) -> [f64; 4] {
        if !uv.is_finite() {
            return [0.0; 4];
        }
        let x = uv.x * f64::from(self.width) - 0.5;
        let y = (1.0 - uv.y) * f64::from(self.height) - 0.5;
        let (x0, y0) = (floor(x), floor(y));
        let (fx, fy) = (x - x0, y - y0);
        // Integer wrap: `as` saturates huge coordinates into range, and an integer remainder
        // is much cheaper than the float one. A texel index already inside the texture (uv
        // in [0, 1)) needs no remainder at all, and the next texel wraps by one comparison
        // (a remainder per texel, ten per lookup, was most of the lookup's cost).
        let wrap = |v: f64, n: u32| {
            let n = i64::from(n.max(1));
            let i = v as i64;
            let i = if (0..n).contains(&i) {
                i
            } else {
                i.rem_euclid(n)
            };
            (i, if i + 1 == n { 0 } else { i + 1 })
        };
        let ((xi, xn), (yi, yn)) = (wrap(x0, self.width), wrap(y0, self.height));
        let t00 = self.texel(xi, yi);
        let t10 = self.texel(xn, yi);
        let t01 = self.texel(xi, yn);
        let t11 = self.texel(xn, yn);
        std::array::from_fn(|k| {
            (1.0 - fy) * ((1.0 - fx) * t00[k] + fx * t10[k])
                + fy * ((1.0 - fx) * t01[k] + fx * t11[k])
        })
    }
}

/// `v.floor()` without the library call (baseline x86-64 has no rounding instruction, and
/// `f64::floor` is a call there): the integer conversion truncates exactly for |v| < 2^52,
/// one is subtracted below zero; larger magnitudes (already integers) and NaN take `floor`.
#[inline]
fn floor(v: f64) -> f64 {
    const EXACT: f64 = 4_503_599_627_370_496.0; // 2^52
    if v.abs() < EXACT {
        let i = v as i64 as f64;
        if i > v { i - 1.0 } else { i }
    } else {
        v.floor()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trip() {
        for i in 0..=255 {
            let c = f64::from(i) / 255.0;
            assert!((linear_to_srgb(srgb_to_linear(c)) - c).abs() < 1e-12);
        }
    }

    #[test]
    fn floor_matches_the_library_floor() {
        let mut v = vec![0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 2.5, -2.5, 1e300, -1e300];
        v.extend([
            f64::INFINITY,
            f64::NEG_INFINITY,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
        ]);
        v.extend([
            4_503_599_627_370_496.0,
            9_007_199_254_740_993.0,
            f64::MIN_POSITIVE,
        ]);
        v.extend([
            -f64::MIN_POSITIVE,
            1.0 - f64::EPSILON / 2.0,
            -1.0 + f64::EPSILON / 2.0,
        ]);
        let mut seed = 7u64;
        for _ in 0..10_000 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let x = f64::from_bits(seed);
            v.push(x);
            v.push((seed >> 11) as f64 / (1u64 << 40) as f64 - 4096.0);
        }
        for x in v {
            let (got, want) = (floor(x), x.floor());
            // Equal (both NaN for NaN); -0.0 may come back as +0.0, which is the same floor.
            assert!(
                got == want || (got.is_nan() && want.is_nan()),
                "{x}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn wrapped_neighbours_match_per_texel_wrapping() {
        // A 3 x 2 texture of distinct texels: every bilinear sample, including across the
        // right and top edges and far outside [0, 1], equals the blend of the four texels
        // wrapped one by one with `rem_euclid` (the old per-texel wrap).
        let texels: Vec<[f64; 4]> = (0..6).map(|i| [f64::from(i), 0.5, 0.25, 1.0]).collect();
        let t = Texture::from_straight(3, 2, texels);
        let reference = |uv: DVec2| {
            let x = uv.x * 3.0 - 0.5;
            let y = (1.0 - uv.y) * 2.0 - 0.5;
            let (x0, y0) = (x.floor(), y.floor());
            let (fx, fy) = (x - x0, y - y0);
            let at = |i: i64, j: i64| t.texels[(j.rem_euclid(2) * 3 + i.rem_euclid(3)) as usize];
            let (xi, yi) = (x0 as i64, y0 as i64);
            let (t00, t10, t01, t11) = (
                at(xi, yi),
                at(xi + 1, yi),
                at(xi, yi + 1),
                at(xi + 1, yi + 1),
            );
            std::array::from_fn::<f64, 4, _>(|k| {
                (1.0 - fy) * ((1.0 - fx) * t00[k] + fx * t10[k])
                    + fy * ((1.0 - fx) * t01[k] + fx * t11[k])
            })
        };
        for i in -40..=40 {
            for j in -40..=40 {
                let uv = DVec2::new(f64::from(i) * 0.0625 + 0.01, f64::from(j) * 0.0625 - 0.003);
                assert_eq!(t.sample(uv), reference(uv), "{uv}");
            }
        }
    }

    #[test]
    fn bilinear_hits_texel_centres_exactly() {
        let t = Texture::checker(2, 1, [1.0; 4], [0.0, 0.0, 0.0, 1.0]);
        // Texel (0, 0) is the top-left: centre uv = (0.25, 0.75).
        assert_eq!(t.sample(DVec2::new(0.25, 0.75)), [1.0; 4]);
        assert_eq!(t.sample(DVec2::new(0.75, 0.75)), [0.0, 0.0, 0.0, 1.0]);
        // Halfway between two texel centres: the mean.
        let m = t.sample(DVec2::new(0.5, 0.75));
        assert!((m[0] - 0.5).abs() < 1e-12 && (m[3] - 1.0).abs() < 1e-12);
        // Wrap-around: u = 1.25 is u = 0.25.
        assert_eq!(
            t.sample(DVec2::new(1.25, 0.75)),
            t.sample(DVec2::new(0.25, 0.75))
        );
    }
}
