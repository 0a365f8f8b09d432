//! Textures: 8-bit sRGB images (PNG files, 4 bytes a texel, decoded to linear on fetch),
//! procedural checkerboards (computed on fetch) and premultiplied linear RGBA texel arrays,
//! sampled bilinearly with wrap-around.

use std::sync::LazyLock;

use glam::DVec2;

/// A texture, row 0 at the top of the image; samples are premultiplied linear RGBA.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Texels, row-major from the top row.
    pub texels: Texels,
    /// True when some texel has alpha < 1.
    pub has_alpha: bool,
}

/// The texels of a [`Texture`], row-major from the top row.
#[derive(Debug, Clone, PartialEq)]
pub enum Texels {
    /// 8-bit sRGB colour with 8-bit linear straight alpha, as in an 8-bit PNG: 4 bytes a
    /// texel (R, G, B, A), decoded on fetch through a 256-entry table to the same f64 values
    /// as [`srgb_to_linear`]`(v / 255)` premultiplied by `a / 255`.
    Srgb8(Vec<u8>),
    /// Premultiplied linear RGBA, 32 bytes a texel.
    Linear(Vec<[f64; 4]>),
    /// A square checkerboard, cell (0, 0) (top left) `a`, its neighbours `b`; premultiplied
    /// linear RGBA. One byte per texel column: texel (x, y) is `b` when `odd[x] != odd[y]`.
    Checker {
        /// Per texel column (and row): true when it lies in an odd-numbered cell.
        odd: Vec<bool>,
        /// Colour of cell (0, 0) and of every cell an even number of steps from it.
        a: [f64; 4],
        /// Colour of the other cells.
        b: [f64; 4],
    },
}

/// [`srgb_to_linear`] of every 8-bit code, `i / 255`.
static SRGB8_TO_LINEAR: LazyLock<[f64; 256]> =
    LazyLock::new(|| std::array::from_fn(|i| srgb_to_linear(i as f64 / 255.0)));

/// Every 8-bit alpha code as a fraction, `i / 255`.
static ALPHA8: LazyLock<[f64; 256]> = LazyLock::new(|| std::array::from_fn(|i| i as f64 / 255.0));

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
            texels: Texels::Linear(texels.into_iter().map(premultiply).collect()),
            has_alpha,
        }
    }

    /// Builds a texture from 8-bit sRGB RGBA bytes with straight alpha (4 per texel,
    /// row-major from the top row), stored as they are; `None` unless `rgba` holds exactly
    /// `width * height` texels.
    pub fn from_srgb8(width: u32, height: u32, rgba: Vec<u8>) -> Option<Self> {
        let texels = u64::from(width) * u64::from(height);
        if rgba.len() as u64 != texels.checked_mul(4)? {
            return None;
        }
        let has_alpha = rgba.chunks_exact(4).any(|p| p[3] < 255);
        Some(Texture {
            width,
            height,
            texels: Texels::Srgb8(rgba),
            has_alpha,
        })
    }

    /// Bytes the texels occupy.
    pub fn texel_bytes(&self) -> usize {
        match &self.texels {
            Texels::Srgb8(b) => b.len(),
            Texels::Linear(t) => t.len() * std::mem::size_of::<[f64; 4]>(),
            Texels::Checker { odd, .. } => odd.len(),
        }
    }

    /// A `squares` x `squares` checkerboard, `texels_per_square` texels per cell; cell (0, 0)
    /// (top left) has colour `a`. Colours are straight linear RGBA.
    pub fn checker(squares: u32, texels_per_square: u32, a: [f64; 4], b: [f64; 4]) -> Self {
        let tps = texels_per_square.max(1);
        let n = squares.max(1).saturating_mul(tps);
        Texture {
            width: n,
            height: n,
            texels: Texels::Checker {
                odd: (0..n).map(|x| (x / tps) % 2 == 1).collect(),
                a: premultiply(a),
                b: premultiply(b),
            },
            has_alpha: a[3] < 1.0 || b[3] < 1.0,
        }
    }

    /// Bilinear sample at `uv` (v up, wrap-around), premultiplied RGBA. Texel centres are at
    /// ((i + 0.5) / width, 1 - (j + 0.5) / height). Non-finite `uv` gives transparent black.
    pub fn sample(&self, uv: DVec2) -> [f64; 4] {
        if !uv.is_finite() {
            return [0.0; 4];
        }
        let x = uv.x * f64::from(self.width) - 0.5;
        let y = (1.0 - uv.y) * f64::from(self.height) - 0.5;
        let ((x0, fx), (y0, fy)) = (split(x), split(y));
        // Integer wrap: `as` saturated huge coordinates into range, and an integer remainder
        // is much cheaper than the float one; a power-of-two size wraps by a mask (two's
        // complement makes it the Euclidean remainder for negative indices too). A texel
        // index already inside the texture (uv in [0, 1)) needs no remainder at all, and
        // the next texel wraps by one comparison.
        let wrap = |i: i64, n: u32| {
            let n = i64::from(n.max(1));
            let i = if n & (n - 1) == 0 {
                i & (n - 1)
            } else if (0..n).contains(&i) {
                i
            } else {
                i.rem_euclid(n)
            };
            (i, if i + 1 == n { 0 } else { i + 1 })
        };
        let ((xi, xn), (yi, yn)) = (wrap(x0, self.width), wrap(y0, self.height));
        let w = i64::from(self.width);
        let at = |x: i64, y: i64| (y * w + x) as usize;
        let (i00, i10, i01, i11) = (at(xi, yi), at(xn, yi), at(xi, yn), at(xn, yn));
        // One match per sample; each arm fetches its four texels inline.
        let texels = match &self.texels {
            Texels::Srgb8(bytes) => {
                let (lut, alpha) = (&*SRGB8_TO_LINEAR, &*ALPHA8);
                let opaque = !self.has_alpha;
                let fetch = |i: usize| match bytes.get(4 * i..4 * i + 4) {
                    // Alpha 1 everywhere: the premultiplication by 1.0 changes nothing.
                    Some(&[r, g, b, _]) if opaque => [
                        lut[usize::from(r)],
                        lut[usize::from(g)],
                        lut[usize::from(b)],
                        1.0,
                    ],
                    Some(&[r, g, b, a]) => {
                        let a = alpha[usize::from(a)];
                        [
                            lut[usize::from(r)] * a,
                            lut[usize::from(g)] * a,
                            lut[usize::from(b)] * a,
                            a,
                        ]
                    }
                    _ => [0.0; 4],
                };
                [fetch(i00), fetch(i10), fetch(i01), fetch(i11)]
            }
            Texels::Linear(t) => {
                let fetch = |i: usize| t.get(i).copied().unwrap_or([0.0; 4]);
                [fetch(i00), fetch(i10), fetch(i01), fetch(i11)]
            }
            Texels::Checker { odd, a, b } => {
                let cell = |v: i64| odd.get(v as usize).copied().unwrap_or(false);
                let (x0, x1, y0, y1) = (cell(xi), cell(xn), cell(yi), cell(yn));
                let pick = |cx: bool, cy: bool| if cx == cy { *a } else { *b };
                [pick(x0, y0), pick(x1, y0), pick(x0, y1), pick(x1, y1)]
            }
        };
        bilinear(fx, fy, texels)
    }
}

/// The bilinear blend of four premultiplied texels `[t00, t10, t01, t11]` (columns x0, x1
/// of rows y0, y1) with weights `fx`, `fy` toward the second column and row.
#[inline(always)]
fn bilinear(fx: f64, fy: f64, [t00, t10, t01, t11]: [[f64; 4]; 4]) -> [f64; 4] {
    std::array::from_fn(|k| {
        (1.0 - fy) * ((1.0 - fx) * t00[k] + fx * t10[k]) + fy * ((1.0 - fx) * t01[k] + fx * t11[k])
    })
}

/// The integer part `floor(v)` (saturated to the range of `i64`) and the fraction
/// `v - floor(v)` of a finite `v`, with one integer conversion: the conversion truncates
/// exactly for |v| < 2^52 and one is subtracted below zero; larger magnitudes are already
/// integers (fraction 0).
#[inline]
fn split(v: f64) -> (i64, f64) {
    const EXACT: f64 = 4_503_599_627_370_496.0; // 2^52
    let i = v as i64;
    if v.abs() < EXACT {
        let f = i as f64;
        if f > v {
            (i - 1, v - (f - 1.0))
        } else {
            (i, v - f)
        }
    } else {
        (i, v - floor(v))
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
        // Textures of distinct texels, sizes that are and are not powers of two (mask and
        // remainder wraps): every bilinear sample, including across the edges and far outside
        // [0, 1], equals the blend of the four texels wrapped one by one with `rem_euclid`
        // and the library's `floor`.
        for (w, h) in [(3u32, 2u32), (4, 2), (1, 8), (5, 7)] {
            let n = (w * h) as usize;
            let texels: Vec<[f64; 4]> = (0..n).map(|i| [i as f64, 0.5, 0.25, 1.0]).collect();
            let t = Texture::from_straight(w, h, texels.clone());
            let (wi, hi) = (i64::from(w), i64::from(h));
            let reference = |uv: DVec2| {
                let x = uv.x * f64::from(w) - 0.5;
                let y = (1.0 - uv.y) * f64::from(h) - 0.5;
                let (x0, y0) = (x.floor(), y.floor());
                let (fx, fy) = (x - x0, y - y0);
                let at =
                    |i: i64, j: i64| texels[(j.rem_euclid(hi) * wi + i.rem_euclid(wi)) as usize];
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
                    let uv =
                        DVec2::new(f64::from(i) * 0.0625 + 0.01, f64::from(j) * 0.0625 - 0.003);
                    assert_eq!(t.sample(uv), reference(uv), "{w}x{h} {uv}");
                }
            }
            // Huge coordinates: already integers, the fraction is 0 and the index saturates.
            for u in [1e17, -1e17, 3e300, -3e300] {
                assert!(t.sample(DVec2::new(u, 0.3)).iter().all(|c| c.is_finite()));
            }
        }
    }

    #[test]
    fn split_is_floor_and_fraction() {
        let mut seed = 99u64;
        let mut v = vec![0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 2.5, -2.5, 1e300, -1e300];
        v.extend([
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            9e15,
            -9e15,
        ]);
        for _ in 0..10_000 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            v.push((seed >> 11) as f64 / (1u64 << 40) as f64 - 4096.0);
            let x = f64::from_bits(seed);
            if x.is_finite() {
                v.push(x);
            }
        }
        for x in v {
            let (i, f) = split(x);
            let want = x.floor();
            assert_eq!(f, x - want, "{x}");
            assert!(
                want.abs() >= 9.2e18 || i as f64 == want,
                "{x}: {i} vs {want}"
            );
        }
    }

    #[test]
    fn srgb8_texels_decode_to_the_straight_texels_premultiplied() {
        // Every 8-bit code in every channel, with alpha codes 0, 1, 128, 254, 255: a texel
        // stored as bytes samples bit for bit as the same texel decoded to f64 up front.
        let mut rgba = Vec::new();
        for (i, a) in [0u8, 1, 128, 254, 255].into_iter().enumerate() {
            for v in 0..=255u8 {
                rgba.extend([v, v.wrapping_add(85), v.wrapping_add(170 + i as u8), a]);
            }
        }
        let (w, h) = (256, 5);
        let bytes = Texture::from_srgb8(w, h, rgba.clone()).unwrap();
        let decoded: Vec<[f64; 4]> = rgba
            .chunks_exact(4)
            .map(|p| {
                let c = |v: u8| srgb_to_linear(f64::from(v) / 255.0);
                [c(p[0]), c(p[1]), c(p[2]), f64::from(p[3]) / 255.0]
            })
            .collect();
        let linear = Texture::from_straight(w, h, decoded);
        assert!(bytes.has_alpha && linear.has_alpha);
        assert_eq!(bytes.texel_bytes(), 4 * 256 * 5);
        for j in 0..h {
            for i in 0..w {
                let uv = DVec2::new(
                    (f64::from(i) + 0.5) / f64::from(w),
                    1.0 - (f64::from(j) + 0.5) / f64::from(h),
                );
                assert_eq!(bytes.sample(uv), linear.sample(uv), "texel ({i}, {j})");
                let between = uv + DVec2::new(0.3 / f64::from(w), 0.2 / f64::from(h));
                assert_eq!(bytes.sample(between), linear.sample(between));
            }
        }
        assert!(Texture::from_srgb8(2, 2, vec![0; 15]).is_none());
        assert!(Texture::from_srgb8(u32::MAX, u32::MAX, vec![]).is_none());
    }

    #[test]
    fn checkers_sample_as_their_texel_arrays() {
        // A checker computed on fetch samples bit for bit as the same board written out
        // texel by texel (cell (0, 0) top left), including alpha, wrap and cell borders.
        let (a, b) = ([0.9, 0.2, 0.1, 0.5], [0.05, 0.6, 0.7, 1.0]);
        for (squares, tps) in [(1, 1), (2, 1), (3, 2), (4, 3)] {
            let n = squares * tps;
            let texels = (0..n * n)
                .map(|k| {
                    if ((k % n) / tps + (k / n) / tps) % 2 == 0 {
                        a
                    } else {
                        b
                    }
                })
                .collect();
            let array = Texture::from_straight(n, n, texels);
            let board = Texture::checker(squares, tps, a, b);
            assert_eq!((board.width, board.height), (n, n));
            assert_eq!(board.has_alpha, array.has_alpha);
            assert_eq!(board.texel_bytes(), n as usize);
            for i in -20..=40 {
                for j in -20..=40 {
                    let uv = DVec2::new(f64::from(i) * 0.071, f64::from(j) * 0.043);
                    assert_eq!(
                        board.sample(uv),
                        array.sample(uv),
                        "{squares} x {tps}: {uv}"
                    );
                }
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
