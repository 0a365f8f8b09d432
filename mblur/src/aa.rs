//! Spatial antialiasing: where in (and around) a pixel the image is sampled, and with what
//! weight. Every method point-samples a pixel centre over the shutter; with N positions the
//! pixel's value is the weighted sum of N such samples, each taken at the centre offset by
//! one position of a (0, 2)-sequence spread over the reconstruction filter's support
//! (Gribel 2010 §4: "Extensions to multi-sampling and super-sampling just increase the
//! sampling rate").
//!
//! The positions are the first N points of the two-dimensional Sobol sequence, a
//! (0, 2)-sequence in base 2, each moved to the centre of its 1/N stratum: for N a power of
//! two every elementary box of area 1/N holds exactly one point, so the positions are
//! stratified in x, in y and jointly, and their mean is the pixel centre. They are the same
//! in every pixel (scrambled per pixel they measured no better on straight edges, see
//! `mblur/tests/antialiasing.rs`). The weights are the filter's values at the positions, normalised to
//! sum to one, so a box filter of radius 1/2 averages the positions over the pixel square.

use std::fmt;
use std::str::FromStr;

use crate::camera::{CameraFrame, Vertex2dh};
use crate::error::{Error, Result};
use crate::image::Image;
use crate::prepared::PreparedScene;
use crate::progress::{NoProgress, Progress};

/// Most sample positions per pixel.
pub const MAX_SAMPLES: u32 = 1024;

/// Smallest accepted filter support radius in pixels (the box's pixel square).
pub const MIN_RADIUS: f64 = 0.5;

/// Largest accepted filter support radius in pixels.
pub const MAX_RADIUS: f64 = 8.0;

/// Sample positions per pixel of the default render (`--method auto`, [`Antialiasing::auto`]):
/// the N of the error-vs-time table in docs/BENCHMARKS.md ("Spatial antialiasing") past
/// which more positions buy less error per unit of time on the built-in scenes.
pub const AUTO_SAMPLES: u32 = 4;

/// A pixel reconstruction filter, separable: `w(x, y) = f(x) f(y)` with offsets in pixels
/// from the pixel centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Filter {
    /// 1 inside the support: with radius 1/2, the average over the pixel square.
    #[default]
    Box,
    /// `1 - |x| / r`.
    Tent,
    /// `exp(-x² / (2 σ²))` with σ = r / 3, minus its value at r (so it reaches 0 there).
    Gaussian,
    /// The four-term Blackman-Harris window over `[-r, r]`.
    BlackmanHarris,
}

impl Filter {
    /// Every filter, in the order the CLI lists them.
    pub const ALL: [Filter; 4] = [
        Filter::Box,
        Filter::Tent,
        Filter::Gaussian,
        Filter::BlackmanHarris,
    ];

    /// The filter's name (`box`, `tent`, `gaussian`, `blackman-harris`).
    pub fn name(self) -> &'static str {
        match self {
            Filter::Box => "box",
            Filter::Tent => "tent",
            Filter::Gaussian => "gaussian",
            Filter::BlackmanHarris => "blackman-harris",
        }
    }

    /// The usual support radius in pixels: 1/2 for the box (the pixel square), 1 for the
    /// tent, 3/2 for the Gaussian and 2 for Blackman-Harris.
    pub fn default_radius(self) -> f64 {
        match self {
            Filter::Box => 0.5,
            Filter::Tent => 1.0,
            Filter::Gaussian => 1.5,
            Filter::BlackmanHarris => 2.0,
        }
    }

    /// The one-dimensional profile at offset `x` for support radius `r` (0 outside).
    pub fn profile(self, x: f64, r: f64) -> f64 {
        let a = x.abs();
        if a > r {
            return 0.0;
        }
        match self {
            Filter::Box => 1.0,
            Filter::Tent => 1.0 - a / r,
            Filter::Gaussian => {
                let s = r / 3.0;
                let g = |v: f64| (-v * v / (2.0 * s * s)).exp();
                (g(a) - g(r)).max(0.0)
            }
            Filter::BlackmanHarris => {
                // The window over [0, 1], centred: x = -r at 0, x = r at 1 (of |x|, so the
                // profile is even to the last bit).
                let u = (a + r) / (2.0 * r);
                let tau = std::f64::consts::TAU;
                (0.35875 - 0.48829 * (tau * u).cos() + 0.14128 * (2.0 * tau * u).cos()
                    - 0.01168 * (3.0 * tau * u).cos())
                .max(0.0)
            }
        }
    }
}

impl fmt::Display for Filter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Filter {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        crate::names::parse_by_name(s, &Filter::ALL, Filter::name, "filter")
    }
}

/// The spatial sampling of a render: positions per pixel and the reconstruction filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Antialiasing {
    /// Sample positions per pixel: 1 = the pixel centre alone (no antialiasing); more must
    /// be a power of two, at most [`MAX_SAMPLES`].
    pub samples: u32,
    /// The reconstruction filter.
    pub filter: Filter,
    /// Its support radius in pixels (`None`: [`Filter::default_radius`]).
    pub radius: Option<f64>,
}

impl Default for Antialiasing {
    fn default() -> Self {
        Antialiasing {
            samples: 1,
            filter: Filter::Box,
            radius: None,
        }
    }
}

/// One sample position: its offset from the pixel centre in pixels and its weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tap {
    /// Offset (x right, y down) from the pixel centre, in pixels.
    pub offset: [f64; 2],
    /// Weight; the taps of a pattern sum to 1.
    pub weight: f64,
}

impl Antialiasing {
    /// The default render's sampling: [`AUTO_SAMPLES`] positions, box filter over the pixel.
    pub fn auto() -> Self {
        Antialiasing {
            samples: AUTO_SAMPLES,
            ..Antialiasing::default()
        }
    }

    /// The support radius in use.
    pub fn radius(&self) -> f64 {
        self.radius.unwrap_or(self.filter.default_radius())
    }

    /// Checks the settings: `samples` 1 or a power of two up to [`MAX_SAMPLES`], `radius`
    /// finite in [`MIN_RADIUS`, `MAX_RADIUS`].
    pub fn validate(&self) -> Result<()> {
        let s = self.samples;
        if s == 0 || s > MAX_SAMPLES || !s.is_power_of_two() {
            return Err(Error::Setting {
                method: "antialiasing",
                setting: "aa",
                message: format!("must be a power of two from 1 to {MAX_SAMPLES}, got {s}"),
            });
        }
        let r = self.radius();
        if !(MIN_RADIUS..=MAX_RADIUS).contains(&r) {
            return Err(Error::Setting {
                method: "antialiasing",
                setting: "filter_radius",
                message: format!("must be between {MIN_RADIUS} and {MAX_RADIUS} pixels, got {r}"),
            });
        }
        Ok(())
    }

    /// The taps: one at the centre with weight 1 for a single sample; else the first
    /// `samples` points of the Sobol (0, 2)-sequence, each at the centre of its stratum,
    /// mapped onto `[-r, r]²` around the centre, weighted by the filter and normalised. Taps of weight 0 (outside the filter's
    /// nonzero part) are left out.
    pub fn taps(&self) -> Vec<Tap> {
        if self.samples <= 1 {
            return vec![Tap {
                offset: [0.0, 0.0],
                weight: 1.0,
            }];
        }
        let r = self.radius();
        // The first N = 2^m points have their coordinates on multiples of 1/N (the net's
        // strata); each is moved to the centre of its stratum, so the pattern's mean is the
        // pixel centre (unshifted, the first points' mean is (N - 1) / 2N: 1/8 px off at
        // N = 4).
        let m = self.samples.trailing_zeros();
        let n = f64::from(self.samples);
        let mut taps: Vec<Tap> = (0..self.samples)
            .map(|i| {
                let [u, v] = sobol_02_bits(i).map(|b| (f64::from(b >> (32 - m)) + 0.5) / n);
                let offset = [(2.0 * u - 1.0) * r, (2.0 * v - 1.0) * r];
                let weight = self.filter.profile(offset[0], r) * self.filter.profile(offset[1], r);
                Tap { offset, weight }
            })
            .filter(|t| t.weight > 0.0)
            .collect();
        let total: f64 = taps.iter().map(|t| t.weight).sum();
        for t in &mut taps {
            t.weight /= total;
        }
        taps
    }
}

/// `scene` as seen by a sampler at pixel centre + `offset` (pixels, x right, y down): every
/// 2DH vertex and camera (keys included) moved by `-offset` on screen, so sampling the shifted scene at a
/// pixel centre samples `scene` at the offset position (x' = x - dx w, y' = y - dy w).
pub fn shifted(scene: &PreparedScene, [dx, dy]: [f64; 2]) -> PreparedScene {
    let shift = |v: Vertex2dh| Vertex2dh {
        x: v.x - dx * v.w,
        y: v.y - dy * v.w,
        ..v
    };
    let camera = |c: &CameraFrame| {
        let mut c = *c;
        c.pixel_from_clip.w_axis.x -= dx;
        c.pixel_from_clip.w_axis.y -= dy;
        c
    };
    let mut out = scene.clone();
    for t in &mut out.triangles {
        t.open = t.open.map(shift);
        t.close = t.close.map(shift);
    }
    for s in &mut out.splats {
        s.open = shift(s.open);
        s.close = shift(s.close);
    }
    out.camera_open = camera(&scene.camera_open);
    out.camera_close = camera(&scene.camera_close);
    // Curved paths are placed through the camera keys: shifting their frames shifts them.
    for k in &mut out.camera_keys {
        k.frame = camera(&k.frame);
    }
    out
}

/// Renders `scene` once per tap of `aa` with `render` (each on the scene shifted to the
/// tap's position, [`shifted`]) and sums the images with the taps' weights; one progress
/// step per tap. With one sample it is `render(scene)` itself, bit for bit.
pub fn render_taps(
    scene: &PreparedScene,
    aa: &Antialiasing,
    progress: &dyn Progress,
    render: impl Fn(&PreparedScene, &dyn Progress) -> Result<Image>,
) -> Result<Image> {
    aa.validate()?;
    if aa.samples <= 1 {
        return render(scene, progress);
    }
    let taps = aa.taps();
    progress.start(taps.len() as u64, "sample positions");
    let mut sum = vec![[0.0f64; 3]; scene.width as usize * scene.height as usize];
    for tap in &taps {
        let image = render(&shifted(scene, tap.offset), &NoProgress)?;
        for (s, p) in sum.iter_mut().zip(&image.pixels) {
            for k in 0..3 {
                s[k] += tap.weight * f64::from(p[k]);
            }
        }
        progress.advance(1);
    }
    progress.finish();
    Ok(Image {
        width: scene.width,
        height: scene.height,
        pixels: sum.iter().map(|p| p.map(|c| c as f32)).collect(),
    })
}

/// Point `i` of the two-dimensional Sobol sequence, shifted by half a cell of the first
/// 2^32 points (so no coordinate is exactly 0): the first coordinate is the base-2 radical
/// inverse of `i` (van der Corput), the second the Sobol dimension whose generator matrix
/// is Pascal's triangle mod 2. Together a (0, 2)-sequence in base 2.
pub fn sobol_02(i: u32) -> [f64; 2] {
    let unit = |b: u32| (f64::from(b) + 0.5) / 4_294_967_296.0;
    sobol_02_bits(i).map(unit)
}

/// Point `i` of [`sobol_02`] as 32-bit fractions (`x = bits / 2^32`), unshifted: for
/// `i < 2^m` only the top m bits can be set.
pub fn sobol_02_bits(i: u32) -> [u32; 2] {
    let x = i.reverse_bits();
    let mut y = 0u32;
    let mut v = 1u32 << 31;
    let mut k = i;
    while k != 0 {
        if k & 1 != 0 {
            y ^= v;
        }
        k >>= 1;
        v ^= v >> 1;
    }
    [x, y]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sobol_points_are_a_0_m_2_net_for_every_m() {
        // For N = 2^m, every elementary box [a 2^-j, (a+1) 2^-j) x [b 2^-(m-j), ...) holds
        // exactly one of the first N points: counted exhaustively.
        for m in 0..=10u32 {
            let n = 1u32 << m;
            let pts: Vec<[f64; 2]> = (0..n).map(sobol_02).collect();
            for j in 0..=m {
                let (nx, ny) = (1u32 << j, 1u32 << (m - j));
                let mut count = vec![0u32; n as usize];
                for p in &pts {
                    let (a, b) = ((p[0] * f64::from(nx)) as u32, (p[1] * f64::from(ny)) as u32);
                    count[(b * nx + a) as usize] += 1;
                }
                assert!(count.iter().all(|&c| c == 1), "m = {m}, j = {j}");
            }
        }
    }

    #[test]
    fn filters_are_even_peak_at_the_centre_and_vanish_outside() {
        for f in Filter::ALL {
            let r = f.default_radius();
            for k in 0..=100 {
                let x = r * f64::from(k) / 100.0;
                assert_eq!(f.profile(x, r), f.profile(-x, r), "{f} at {x}");
                assert!(f.profile(x, r) <= f.profile(0.0, r) + 1e-15, "{f} at {x}");
            }
            assert_eq!(f.profile(r * 1.0001, r), 0.0, "{f}");
            assert!(f.profile(0.0, r) > 0.0);
            assert_eq!(f.name().parse::<Filter>(), Ok(f));
        }
        // Blackman-Harris: 1.0 at the centre (the coefficients sum to 1), ~0 at the ends.
        let bh = Filter::BlackmanHarris;
        assert!((bh.profile(0.0, 2.0) - 1.0).abs() < 1e-12);
        assert!(bh.profile(2.0, 2.0) < 1e-4);
        assert_eq!(Filter::Tent.profile(0.5, 1.0), 0.5);
    }

    #[test]
    fn box_taps_are_the_pixel_square_equally_weighted() {
        let aa = Antialiasing {
            samples: 16,
            ..Antialiasing::default()
        };
        let taps = aa.taps();
        assert_eq!(taps.len(), 16);
        for t in &taps {
            assert_eq!(t.weight, 1.0 / 16.0);
            assert!(t.offset.iter().all(|o| o.abs() < 0.5));
        }
        // One tap per quarter of the pixel in each direction (the net's strata).
        for q in 0..4 {
            let lo = -0.5 + 0.25 * f64::from(q);
            let in_column = taps
                .iter()
                .filter(|t| (lo..lo + 0.25).contains(&t.offset[0]));
            assert_eq!(in_column.count(), 4);
        }
        // Centred: the mean offset is the pixel centre for every N, and N = 2 takes the
        // two diagonal quarter points.
        for n in [2u32, 4, 8, 16, 64, 1024] {
            let taps = Antialiasing {
                samples: n,
                ..Antialiasing::default()
            }
            .taps();
            let mean = [0, 1].map(|k| taps.iter().map(|t| t.offset[k]).sum::<f64>());
            assert_eq!(mean, [0.0, 0.0], "N = {n}");
        }
        let two = Antialiasing {
            samples: 2,
            ..Antialiasing::default()
        }
        .taps();
        assert_eq!(two[0].offset, [-0.25, -0.25]);
        assert_eq!(two[1].offset, [0.25, 0.25]);
        let one = Antialiasing::default().taps();
        assert_eq!(
            one,
            [Tap {
                offset: [0.0, 0.0],
                weight: 1.0
            }]
        );
    }

    #[test]
    fn weights_sum_to_one_and_settings_are_checked() {
        for f in Filter::ALL {
            for n in [2, 4, 16, 64, 1024] {
                let aa = Antialiasing {
                    samples: n,
                    filter: f,
                    radius: None,
                };
                aa.validate().unwrap();
                let sum: f64 = aa.taps().iter().map(|t| t.weight).sum();
                assert!((sum - 1.0).abs() < 1e-12, "{f} x {n}: {sum}");
            }
        }
        for samples in [0, 3, 2048] {
            let aa = Antialiasing {
                samples,
                ..Antialiasing::default()
            };
            assert!(matches!(
                aa.validate(),
                Err(Error::Setting { setting: "aa", .. })
            ));
        }
        for radius in [0.25, 9.0, f64::NAN] {
            let aa = Antialiasing {
                radius: Some(radius),
                ..Antialiasing::default()
            };
            assert!(aa.validate().is_err(), "{radius}");
        }
    }
}
