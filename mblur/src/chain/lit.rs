//! Lit intervals: the payload that lets the resolve shade an interval at any instant of its
//! life, and the shader with the per-interval accuracy knob ([`ShadingSamples`]).
//!
//! A lit interval carries its triangle and the triangle's barycentric weights at the
//! interval's start and end (Rønnow 2021, Fig. 6 stores barycentrics and the start normal);
//! the resolve interpolates the weights linearly over the interval's time, as the textured
//! payload does its UVs, and [`PreparedScene::surface_point`] turns them into position,
//! normal and UV on the triangle at that instant. One record is 24 bytes in f32 (40 with
//! the interval's time and depth), as a textured interval.

use glam::DVec2;
use interval_buffer::{Interval, Payload};
use resolve::Shader;

use super::Real;
use super::cf;
use super::end_samples::{EndSamples, SampleKey};
use super::payload::{MakePayload, TapCount};
use crate::lighting::{LightTerms, ShadingSamples};
use crate::prepared::PreparedScene;
use crate::surface_track::SurfaceTrack;

/// Cells per unit of barycentric weight at which a lit span's barycentric path must stay
/// within [`super::TEXTURE_TOLERANCE`] of its chord: a span whose path bends more (a pixel
/// under perspective or a turning segment) is cut into pieces, as textured spans are for
/// their UV path (`pieces::pieces_within`).
pub const BARY_CELLS: f64 = 16.0;

/// Deepest bisection of [`ShadingSamples::Adaptive`]: at most 2^8 sub-spans per partition.
pub const ADAPTIVE_DEPTH: u32 = 8;

/// The payload of a lit interval: its triangle, the barycentric weights of corners 1 and 2
/// at the interval's start and end, and the coverage alpha.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Lit<F> {
    /// Index of the triangle in [`PreparedScene::triangles`].
    pub tri: u32,
    /// Weights of corners 1 and 2 at the interval's start (corner 0 takes the rest).
    pub bary_start: [F; 2],
    /// Weights of corners 1 and 2 at the interval's end.
    pub bary_end: [F; 2],
    /// Straight coverage alpha (the material's; compression may lower it).
    pub alpha: F,
}

impl<F: Real> Payload<F> for Lit<F> {
    /// Linear blend of the weights and alpha; the triangle of the heavier side.
    fn blend(&self, other: &Self, alpha: F) -> Self {
        let mix = |a: F, b: F| (F::one() - alpha) * a + alpha * b;
        let half = cf::<F>(0.5);
        Lit {
            tri: if alpha < half { self.tri } else { other.tri },
            bary_start: [0, 1].map(|k| mix(self.bary_start[k], other.bary_start[k])),
            bary_end: [0, 1].map(|k| mix(self.bary_end[k], other.bary_end[k])),
            alpha: mix(self.alpha, other.alpha),
        }
    }

    /// L1 distance of the weights, plus 1 when the triangles differ.
    fn distance(&self, other: &Self) -> F {
        let d = (0..2).fold(F::zero(), |acc, k| {
            acc + (self.bary_start[k] - other.bary_start[k]).abs()
                + (self.bary_end[k] - other.bary_end[k]).abs()
        });
        if self.tri == other.tri {
            d
        } else {
            d + F::one()
        }
    }

    fn is_opaque(&self) -> bool {
        self.alpha >= F::one()
    }

    fn restrict(&self, s0: F, s1: F) -> Self {
        let at =
            |s: F| [0, 1].map(|k| self.bary_start[k] + (self.bary_end[k] - self.bary_start[k]) * s);
        Lit {
            bary_start: at(s0),
            bary_end: at(s1),
            ..*self
        }
    }

    fn coverage(&self) -> F {
        self.alpha
    }

    fn with_coverage(&self, alpha: F) -> Self {
        Lit { alpha, ..*self }
    }
}

/// Makes [`Lit`] payloads: per material its straight alpha and, when textured, the texture
/// size in texels (textured spans are cut where their UV path bends, as for unlit ones).
pub(crate) struct LitPayload<F>(pub Vec<F>, pub Vec<Option<DVec2>>);

impl<F: Real> MakePayload<F> for LitPayload<F> {
    type P = Lit<F>;
    fn texels(&self, material: u32) -> Option<DVec2> {
        self.1.get(material as usize).copied().flatten()
    }
    fn bary_cells(&self, _: u32) -> Option<f64> {
        Some(BARY_CELLS)
    }
    fn make(&self, material: u32, _: DVec2, _: DVec2) -> Lit<F> {
        Lit {
            alpha: self
                .0
                .get(material as usize)
                .copied()
                .unwrap_or_else(F::zero),
            ..Lit::default()
        }
    }
    fn make_at(&self, tri: u32, material: u32, _: [DVec2; 2], bary: [[f64; 3]; 2]) -> Lit<F> {
        Lit {
            tri,
            bary_start: [cf(bary[0][1]), cf(bary[0][2])],
            bary_end: [cf(bary[1][1]), cf(bary[1][2])],
            alpha: self
                .0
                .get(material as usize)
                .copied()
                .unwrap_or_else(F::zero),
        }
    }
}

/// Payloads for a scene with lit materials.
pub(crate) fn lit_payloads<F: Real>(scene: &PreparedScene) -> LitPayload<F> {
    let tex = super::payload::tex_payloads::<F>(scene);
    LitPayload(tex.0, tex.1)
}

/// Shades [`Lit`] intervals through [`PreparedScene::shade_surface`] with `samples` per
/// partition. Adaptive sampling takes the colour at a partition's start from the end of
/// the partition before when this thread shaded that same point there (`end_samples`).
pub(crate) struct LitShader<'a> {
    scene: &'a PreparedScene,
    samples: ShadingSamples,
    /// Texture taps per partition.
    count: TapCount,
    /// This shader's part of the keys of its end samples.
    id: u64,
}

impl<'a> LitShader<'a> {
    pub(crate) fn new(scene: &'a PreparedScene, samples: ShadingSamples) -> Self {
        LitShader {
            scene,
            samples,
            count: TapCount::new(scene),
            id: EndSamples::shader_id(),
        }
    }
}

/// One interval's surface over time: its triangle set up for shading and its weights as
/// f64.
struct Track<'a> {
    surface: SurfaceTrack<'a>,
    tri: &'a crate::prepared::PreparedTriangle,
    /// The index of `tri`.
    tri_index: u32,
    ts: f64,
    len: f64,
    b0: [f64; 2],
    b1: [f64; 2],
    /// Payload alpha over material alpha (1 unless compression merged coverage).
    alpha_scale: f64,
}

impl<'a> Track<'a> {
    /// `f` of the track of `iv` for instants in `times` (`None` for a triangle or material
    /// out of range). The track is handed by reference, built where it stays: it is a few
    /// hundred bytes, and returning it moved it once per partition.
    fn with<F: Real, R>(
        scene: &'a PreparedScene,
        iv: &Interval<F, Lit<F>>,
        times: [f64; 2],
        f: impl FnOnce(&Track<'_>) -> R,
    ) -> Option<R> {
        let p = &iv.payload;
        let tri = scene.triangles.get(p.tri as usize)?;
        let m_alpha = scene.materials.get(tri.material as usize)?.color[3].clamp(0.0, 1.0);
        let to = |v: F| v.to_f64().unwrap_or(0.0);
        let pa = to(p.alpha);
        let alpha_scale = if m_alpha > 0.0 && pa != m_alpha {
            pa / m_alpha
        } else {
            1.0
        };
        let track = Track {
            surface: SurfaceTrack::new(scene, tri, times),
            tri,
            tri_index: p.tri,
            ts: to(iv.ts),
            len: to(iv.te) - to(iv.ts),
            b0: p.bary_start.map(to),
            b1: p.bary_end.map(to),
            alpha_scale,
        };
        Some(f(&track))
    }

    fn bary(&self, t: f64) -> [f64; 3] {
        let s = if self.len > 0.0 {
            ((t - self.ts) / self.len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let b1 = self.b0[0] + (self.b1[0] - self.b0[0]) * s;
        let b2 = self.b0[1] + (self.b1[1] - self.b0[1]) * s;
        [1.0 - b1 - b2, b1, b2]
    }

    fn colour(&self, t: f64) -> [f64; 4] {
        self.surface.colour(self.bary(t), t)
    }

    /// The key of [`Track::colour`] at `t` among the end samples of `shader`, and the
    /// barycentric weights there.
    fn sample_key(&self, shader: u64, t: f64) -> (SampleKey, [f64; 3]) {
        let bary = self.bary(t);
        let corners = self.surface.corners_key();
        let key = SampleKey::new(shader, self.tri_index, t, [bary[1], bary[2]], corners);
        (key, bary)
    }

    fn terms(&self, t: f64) -> LightTerms {
        let p = self.surface.surface_point(self.bary(t), t);
        self.surface.light_terms(&p, t)
    }

    fn albedo(&self, t: f64) -> [f64; 4] {
        self.surface.albedo(self.bary(t))
    }
}

/// The midpoint rule with `n` taps over `[t0, t1]`, shutter weight linear `w0` → `w1`.
fn midpoint(
    n: usize,
    [t0, t1]: [f64; 2],
    [w0, w1]: [f64; 2],
    f: impl Fn(f64) -> [f64; 4],
) -> [f64; 4] {
    let mut sum = [0.0; 4];
    let mut weights = 0.0;
    for i in 0..n {
        let s = (i as f64 + 0.5) / n as f64;
        let w = w0 + (w1 - w0) * s;
        let c = f(t0 + (t1 - t0) * s);
        for (a, c) in sum.iter_mut().zip(c) {
            *a += w * c;
        }
        weights += w;
    }
    if weights > 0.0 {
        sum.map(|v| v / weights)
    } else {
        sum
    }
}

/// Adaptive Simpson over `[a, b]` of `w(t) c(t)`: a sub-span is accepted when the colour at
/// its midpoint is within `tol` of the chord through its ends (every channel), or at
/// [`ADAPTIVE_DEPTH`]. Returns the integral of `w c` (not normalised).
fn simpson(
    f: &impl Fn(f64) -> [f64; 4],
    w: &impl Fn(f64) -> f64,
    (a, ca): (f64, [f64; 4]),
    (b, cb): (f64, [f64; 4]),
    tol: f64,
    depth: u32,
) -> [f64; 4] {
    let m = 0.5 * (a + b);
    let cm = f(m);
    let chord = (0..4).fold(0.0f64, |e, k| e.max((cm[k] - 0.5 * (ca[k] + cb[k])).abs()));
    // A NaN chord (a NaN colour) is accepted: splitting cannot make it finite.
    if chord <= tol || chord.is_nan() || depth >= ADAPTIVE_DEPTH {
        let (wa, wm, wb) = (w(a), w(m), w(b));
        let h = (b - a) / 6.0;
        return std::array::from_fn(|k| h * (wa * ca[k] + 4.0 * wm * cm[k] + wb * cb[k]));
    }
    let l = simpson(f, w, (a, ca), (m, cm), tol, depth + 1);
    let r = simpson(f, w, (m, cm), (b, cb), tol, depth + 1);
    std::array::from_fn(|k| l[k] + r[k])
}

impl LitShader<'_> {
    /// Texture taps for the partition `[t0, t1]` of `tr` (1 when untextured).
    fn texture_taps(&self, tr: &Track<'_>, t0: f64, t1: f64) -> usize {
        let d = tr.tri.uv_at(tr.bary(t1)) - tr.tri.uv_at(tr.bary(t0));
        self.count.taps(tr.tri.material, d.x, d.y)
    }

    fn shade_f64(&self, tr: &Track<'_>, t0: f64, t1: f64, w0: f64, w1: f64) -> [f64; 4] {
        let (w0, w1) = if w0 + w1 > 0.0 { (w0, w1) } else { (1.0, 1.0) };
        let taps = || self.texture_taps(tr, t0, t1);
        let c = match self.samples {
            ShadingSamples::Start | ShadingSamples::Mid => {
                let at = if self.samples == ShadingSamples::Start {
                    tr.ts
                } else {
                    0.5 * (t0 + t1)
                };
                let albedo = midpoint(taps(), [t0, t1], [w0, w1], |t| tr.albedo(t));
                tr.terms(at).apply(albedo)
            }
            ShadingSamples::Fixed(n) => {
                midpoint(taps().max(n as usize), [t0, t1], [w0, w1], |t| tr.colour(t))
            }
            ShadingSamples::Adaptive { tolerance } => {
                if t1 > t0 {
                    let f = |t: f64| tr.colour(t);
                    let w = |t: f64| w0 + (w1 - w0) * (t - t0) / (t1 - t0);
                    // The start is often where this thread's partition before ended; the
                    // end is kept for the partition after.
                    let (key, bary) = tr.sample_key(self.id, t0);
                    let c0 = EndSamples::find(&key).unwrap_or_else(|| tr.surface.colour(bary, t0));
                    let (key, bary) = tr.sample_key(self.id, t1);
                    let c1 = tr.surface.colour(bary, t1);
                    EndSamples::keep(&key, c1);
                    let sum = simpson(&f, &w, (t0, c0), (t1, c1), tolerance, 0);
                    let norm = 0.5 * (w0 + w1) * (t1 - t0);
                    sum.map(|v| v / norm)
                } else {
                    tr.colour(t0)
                }
            }
        };
        c.map(|v| v * tr.alpha_scale)
    }
}

impl<F: Real> Shader<F, Lit<F>> for LitShader<'_> {
    fn shade(&self, iv: &Interval<F, Lit<F>>, t0: F, t1: F, w0: F, w1: F) -> [F; 4] {
        let f = |v: F| v.to_f64().unwrap_or(0.0);
        let (t0, t1) = (f(t0), f(t1));
        let (w0, w1) = (f(w0), f(w1));
        Track::with(self.scene, iv, [t0.min(t1), t1.max(t0)], |tr| {
            self.shade_f64(tr, t0, t1, w0, w1).map(cf)
        })
        .unwrap_or([F::zero(); 4])
    }

    fn shade_at(&self, iv: &Interval<F, Lit<F>>, t: F) -> [F; 4] {
        let t = t.to_f64().unwrap_or(0.0);
        Track::with(self.scene, iv, [t, t], |tr| {
            tr.colour(t).map(|v| cf(v * tr.alpha_scale))
        })
        .unwrap_or([F::zero(); 4])
    }

    fn min_alpha(&self, iv: &Interval<F, Lit<F>>) -> F {
        let scene = self.scene;
        let texel_alpha = scene
            .triangles
            .get(iv.payload.tri as usize)
            .and_then(|t| scene.materials.get(t.material as usize))
            .and_then(|m| scene.texture_of(m))
            .is_some_and(|t| t.has_alpha());
        if texel_alpha {
            F::zero()
        } else {
            iv.payload.alpha.max(F::zero()).min(F::one())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lit_interval_is_40_bytes_in_f32() {
        // 4 (triangle) + 2 x 8 (barycentrics at both ends) + 4 (alpha); the interval adds
        // its start, end, depth and slope.
        assert_eq!(std::mem::size_of::<Lit<f32>>(), 24);
        assert_eq!(std::mem::size_of::<Interval<f32, Lit<f32>>>(), 40);
        assert_eq!(
            std::mem::size_of::<Interval<f32, interval_buffer::Textured<f32>>>(),
            40
        );
    }

    #[test]
    fn restrict_and_blend_interpolate_the_barycentrics() {
        let a = Lit {
            tri: 3,
            bary_start: [0.0f64, 0.0],
            bary_end: [1.0, 0.0],
            alpha: 1.0,
        };
        let r = a.restrict(0.25, 0.5);
        assert_eq!(
            (r.bary_start, r.bary_end, r.tri),
            ([0.25, 0.0], [0.5, 0.0], 3)
        );
        let b = Lit {
            tri: 7,
            bary_start: [0.0, 1.0],
            ..a
        };
        assert_eq!(a.blend(&b, 0.25).tri, 3);
        assert_eq!(a.blend(&b, 0.75).tri, 7);
        assert_eq!(a.blend(&b, 0.5).bary_start, [0.0, 0.5]);
        assert_eq!(a.distance(&b), 2.0);
    }

    #[test]
    fn adaptive_simpson_integrates_a_cubic_exactly_and_stops_on_a_line() {
        // Simpson's rule is exact for cubics; a line is accepted at the first level.
        let calls = std::cell::Cell::new(0);
        let line = |t: f64| {
            calls.set(calls.get() + 1);
            [t, 2.0 * t, 0.0, 1.0]
        };
        let one = |_: f64| 1.0;
        let s = simpson(&line, &one, (0.0, line(0.0)), (1.0, line(1.0)), 1e-9, 0);
        assert!((s[0] - 0.5).abs() < 1e-15 && (s[1] - 1.0).abs() < 1e-15);
        assert_eq!(calls.get(), 3);
        let cubic = |t: f64| [t * t * t, 0.0, 0.0, 1.0];
        let s = simpson(&cubic, &one, (0.0, cubic(0.0)), (1.0, cubic(1.0)), 1e-12, 0);
        assert!((s[0] - 0.25).abs() < 1e-12, "{}", s[0]);
    }
}
