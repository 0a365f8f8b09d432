//! Textures: premultiplied linear RGBA texel arrays in f32 (what images and checkerboards of
//! up to [`DECODED_TEXELS`] texels are decoded to once), and, above that size, 8-bit sRGB
//! images (4 bytes a texel, decoded to linear on fetch) and procedural checkerboards
//! (computed on fetch); sampled bilinearly with wrap-around ([`Texture::sample`]), or
//! averaged exactly along a UV segment (`segment`, [`Texture::segment_average`]), which
//! crosses the flat regions of decoded textures in one step each (`flat`).

mod flat;
mod grid;
mod segment;

use std::sync::LazyLock;

use glam::DVec2;

use flat::FlatCells;
use grid::{bilinear, split, wrap};
pub(crate) use grid::{ceil, floor};

/// A texture, row 0 at the top of the image; samples are premultiplied linear RGBA.
/// Read-only once built: decoded textures keep a map of their flat regions that must
/// match the texels.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// Width in texels.
    width: u32,
    /// Height in texels.
    height: u32,
    /// Texels, row-major from the top row.
    texels: Texels,
    /// True when some texel has alpha < 1.
    has_alpha: bool,
    /// The flat regions of [`Texels::Linear`] texels; empty for the compact forms.
    flat: FlatCells,
}

/// Images and checkerboards of at most this many texels are decoded once to
/// [`Texels::Linear`] (16 bytes a texel and one of the flat-region map: 68 MiB at the
/// limit), so that a sample fetches four
/// texels and blends them, with no decoding; larger ones keep their compact form
/// ([`Texels::Srgb8`], 4 bytes a texel; [`Texels::Checker`], one byte a texel column) and
/// decode on fetch. The decoded values are the compact form's rounded to f32 (a relative
/// difference below 6e-8, far under the 1/255 step of 8-bit texels).
pub const DECODED_TEXELS: u64 = 1 << 22;

/// The texels of a [`Texture`], row-major from the top row.
#[derive(Debug, Clone, PartialEq)]
pub enum Texels {
    /// 8-bit sRGB colour with 8-bit linear straight alpha, as in an 8-bit PNG: 4 bytes a
    /// texel (R, G, B, A), decoded on fetch through a 256-entry table to the same f64 values
    /// as [`srgb_to_linear`]`(v / 255)` premultiplied by `a / 255`.
    Srgb8(Vec<u8>),
    /// Premultiplied linear RGBA in f32, 16 bytes a texel.
    Linear(Vec<[f32; 4]>),
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

/// Premultiplied linear RGBA rounded to f32, the [`Texels::Linear`] form.
fn to_f32(c: [f64; 4]) -> [f32; 4] {
    c.map(|v| v as f32)
}

impl Texture {
    /// Builds a texture from straight-alpha linear texels (premultiplies them).
    pub fn from_straight(width: u32, height: u32, texels: Vec<[f64; 4]>) -> Self {
        let has_alpha = texels.iter().any(|t| t[3] < 1.0);
        let mut texture = Texture {
            width,
            height,
            texels: Texels::Linear(texels.into_iter().map(|t| to_f32(premultiply(t))).collect()),
            has_alpha,
            flat: FlatCells::default(),
        };
        texture.map_flat_cells();
        texture
    }

    /// Builds a texture from 8-bit sRGB RGBA bytes with straight alpha (4 per texel,
    /// row-major from the top row), decoded to [`Texels::Linear`] up to [`DECODED_TEXELS`]
    /// texels and stored as they are above; `None` unless `rgba` holds exactly
    /// `width * height` texels.
    pub fn from_srgb8(width: u32, height: u32, rgba: Vec<u8>) -> Option<Self> {
        Self::from_srgb8_decoding(width, height, rgba, DECODED_TEXELS)
    }

    /// [`Texture::from_srgb8`], decoding up to `limit` texels.
    fn from_srgb8_decoding(width: u32, height: u32, rgba: Vec<u8>, limit: u64) -> Option<Self> {
        let texels = u64::from(width) * u64::from(height);
        if rgba.len() as u64 != texels.checked_mul(4)? {
            return None;
        }
        let has_alpha = rgba.chunks_exact(4).any(|p| p[3] < 255);
        let mut texture = Texture {
            width,
            height,
            texels: Texels::Srgb8(rgba),
            has_alpha,
            flat: FlatCells::default(),
        };
        if texels <= limit {
            texture.decode();
        }
        Some(texture)
    }

    /// Replaces compact texels by [`Texels::Linear`] ones with the same samples (rounded
    /// to f32), and maps their flat regions.
    fn decode(&mut self) {
        let n = self.width as usize * self.height as usize;
        let linear = (0..n)
            .map(|i| {
                let (x, y) = (i % self.width as usize, i / self.width as usize);
                to_f32(self.texel(x as i64, y as i64))
            })
            .collect();
        self.texels = Texels::Linear(linear);
        self.map_flat_cells();
    }

    /// Maps the flat cells of [`Texels::Linear`] texels (one byte a texel; see `flat`).
    fn map_flat_cells(&mut self) {
        if let Texels::Linear(t) = &self.texels {
            let (w, h) = (self.width as usize, self.height as usize);
            let at = |x: usize, y: usize| t.get(y * w + x).map(|c| c.map(f32::to_bits));
            self.flat = FlatCells::new(self.width, self.height, |x, y| {
                let (xn, yn) = ((x + 1) % w, (y + 1) % h);
                let c = at(x, y);
                c.is_some() && at(xn, y) == c && at(x, yn) == c && at(xn, yn) == c
            });
        }
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The texels, row-major from the top row.
    pub fn texels(&self) -> &Texels {
        &self.texels
    }

    /// True when some texel has alpha < 1.
    pub fn has_alpha(&self) -> bool {
        self.has_alpha
    }

    /// Bytes the texels occupy, with the map of their flat regions for decoded textures
    /// (one byte a texel).
    pub fn texel_bytes(&self) -> usize {
        let texels = match &self.texels {
            Texels::Srgb8(b) => b.len(),
            Texels::Linear(t) => t.len() * std::mem::size_of::<[f32; 4]>(),
            Texels::Checker { odd, .. } => odd.len(),
        };
        texels + self.flat.bytes()
    }

    /// A `squares` x `squares` checkerboard, `texels_per_square` texels per cell; cell (0, 0)
    /// (top left) has colour `a`. Colours are straight linear RGBA. Decoded to
    /// [`Texels::Linear`] up to [`DECODED_TEXELS`] texels, computed on fetch above.
    pub fn checker(squares: u32, texels_per_square: u32, a: [f64; 4], b: [f64; 4]) -> Self {
        Self::checker_decoding(squares, texels_per_square, a, b, DECODED_TEXELS)
    }

    /// [`Texture::checker`], decoding up to `limit` texels.
    fn checker_decoding(squares: u32, tps: u32, a: [f64; 4], b: [f64; 4], limit: u64) -> Self {
        let tps = tps.max(1);
        let n = squares.max(1).saturating_mul(tps);
        let mut texture = Texture {
            width: n,
            height: n,
            texels: Texels::Checker {
                odd: (0..n).map(|x| (x / tps) % 2 == 1).collect(),
                a: premultiply(a),
                b: premultiply(b),
            },
            has_alpha: a[3] < 1.0 || b[3] < 1.0,
            flat: FlatCells::default(),
        };
        if u64::from(n) * u64::from(n) <= limit {
            texture.decode();
        }
        texture
    }

    /// The premultiplied texel at column `x`, row `y` (indices inside the texture;
    /// transparent black outside).
    #[inline(always)]
    fn texel(&self, x: i64, y: i64) -> [f64; 4] {
        let i = (y * i64::from(self.width) + x) as usize;
        match &self.texels {
            Texels::Srgb8(bytes) => match bytes.get(4 * i..4 * i + 4) {
                // Alpha 1 everywhere: the premultiplication by 1.0 changes nothing.
                Some(&[r, g, b, _]) if !self.has_alpha => {
                    let lut = &*SRGB8_TO_LINEAR;
                    [
                        lut[usize::from(r)],
                        lut[usize::from(g)],
                        lut[usize::from(b)],
                        1.0,
                    ]
                }
                Some(&[r, g, b, a]) => {
                    let (lut, a) = (&*SRGB8_TO_LINEAR, ALPHA8[usize::from(a)]);
                    [
                        lut[usize::from(r)] * a,
                        lut[usize::from(g)] * a,
                        lut[usize::from(b)] * a,
                        a,
                    ]
                }
                _ => [0.0; 4],
            },
            Texels::Linear(t) => t.get(i).map_or([0.0; 4], |c| c.map(f64::from)),
            Texels::Checker { odd, a, b } => {
                let cell = |v: i64| odd.get(v as usize).copied().unwrap_or(false);
                if cell(x) == cell(y) { *a } else { *b }
            }
        }
    }

    /// Bilinear sample at `uv` (v up, wrap-around), premultiplied RGBA. Texel centres are at
    /// ((i + 0.5) / width, 1 - (j + 0.5) / height). Non-finite `uv` gives transparent black.
    pub fn sample(&self, uv: DVec2) -> [f64; 4] {
        if !uv.is_finite() {
            return [0.0; 4];
        }
        let (x, y) = self.texel_space(uv);
        let ((x0, fx), (y0, fy)) = (split(x), split(y));
        bilinear(fx, fy, self.cell(x0, y0))
    }

    /// Texel-space position of `uv`: texel centres at integers, x right, y down.
    #[inline(always)]
    fn texel_space(&self, uv: DVec2) -> (f64, f64) {
        (
            uv.x * f64::from(self.width) - 0.5,
            (1.0 - uv.y) * f64::from(self.height) - 0.5,
        )
    }

    /// The four premultiplied texels `[t00, t10, t01, t11]` of the bilinear cell whose top
    /// left texel is (x0, y0), wrapped.
    #[inline(always)]
    fn cell(&self, x0: i64, y0: i64) -> [[f64; 4]; 4] {
        let ((xi, xn), (yi, yn)) = (wrap(x0, self.width), wrap(y0, self.height));
        match &self.texels {
            // The common case, written out: four f32 texels, no decoding.
            Texels::Linear(t) => {
                let w = i64::from(self.width);
                let fetch = |x: i64, y: i64| {
                    t.get((y * w + x) as usize)
                        .map_or([0.0; 4], |c| c.map(f64::from))
                };
                [fetch(xi, yi), fetch(xn, yi), fetch(xi, yn), fetch(xn, yn)]
            }
            _ => [
                self.texel(xi, yi),
                self.texel(xn, yi),
                self.texel(xi, yn),
                self.texel(xn, yn),
            ],
        }
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

    /// Asserts that `compact` (decoding on fetch, f64) samples as `decoded` (f32 texels) up
    /// to the f32 rounding of the texels, at every texel centre, between centres and across
    /// the wrap.
    fn assert_same_samples(compact: &Texture, decoded: &Texture) {
        let (w, h) = (f64::from(compact.width), f64::from(compact.height));
        for i in -3..=2 * compact.width as i32 {
            for j in -3..=2 * compact.height as i32 {
                let centre = DVec2::new((f64::from(i) + 0.5) / w, 1.0 - (f64::from(j) + 0.5) / h);
                let c = compact.sample(centre);
                assert_eq!(
                    c.map(|v| v as f32),
                    decoded.sample(centre).map(|v| v as f32)
                );
                let between = centre + DVec2::new(0.3 / w, 0.2 / h);
                let (c, d) = (compact.sample(between), decoded.sample(between));
                for k in 0..4 {
                    assert!((c[k] - d[k]).abs() <= 1e-7 * c[k].abs(), "{c:?} vs {d:?}");
                }
            }
        }
    }

    #[test]
    fn srgb8_texels_decode_to_the_straight_texels_premultiplied() {
        // Every 8-bit code in every channel, with alpha codes 0, 1, 128, 254, 255: a texel
        // decoded from bytes samples bit for bit as the same texel decoded to f64 and
        // premultiplied up front, and the bytes kept as they are (decoded on fetch) sample
        // as both up to the f32 rounding of the decoded texels.
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
        let compact = Texture::from_srgb8_decoding(w, h, rgba.clone(), 0).unwrap();
        assert!(bytes.has_alpha && linear.has_alpha && compact.has_alpha);
        assert_eq!(bytes.texel_bytes(), (16 + 1) * 256 * 5);
        assert_eq!(compact.texel_bytes(), 4 * 256 * 5);
        assert_same_samples(&compact, &bytes);
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
        // A checker samples bit for bit as the same board written out texel by texel
        // (cell (0, 0) top left), including alpha, wrap and cell borders; computed on fetch
        // it samples as both up to the f32 rounding of the decoded texels.
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
            let computed = Texture::checker_decoding(squares, tps, a, b, 0);
            assert_eq!((board.width, board.height), (n, n));
            assert_eq!(board.has_alpha, array.has_alpha);
            assert_eq!(board.texel_bytes(), (16 + 1) * (n * n) as usize);
            assert_eq!(computed.texel_bytes(), n as usize);
            assert_same_samples(&computed, &board);
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
