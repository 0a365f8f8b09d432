//! What colour an active interval shows during one partition of the sweep.
//!
//! Flat intervals ([`Rgba`] payloads) have one colour for their whole life (Gribel 2010,
//! Eq. 16, c_i). Textured intervals ([`Textured`] payloads) carry UV at their start and end;
//! a partition [t0, t1] of the sweep sees the UV segment lerped at its two ends and its
//! colour is the texture filtered along that segment (Rønnow 2021, §4.3, Fig. 7-8). Two
//! filters with an accuracy knob are provided: [`TapFilter`] (N point taps along the
//! segment) and [`ExactFilter`] (the exact segment integral of a texture that can compute
//! one, e.g. [`crate::BilinearTexture`]).

use interval_buffer::{Interval, Rgba, Textured};
use num_traits::Float;

use crate::texture::{SegmentTexture, Texture};

/// Gives the sweep the colour of an interval over one time partition.
///
/// Colours are premultiplied `[a r, a g, a b, a]` (ARCHITECTURE.md: straight alpha in
/// payloads, premultiplied in blending).
///
/// Transparent blending composites the partition *averages* of the layers (as Rønnow 2021
/// does). That equals the time average of the composite whenever each layer's alpha is
/// constant over the partition (flat colours, or textures whose alpha is the constant
/// material alpha); a texel alpha that varies inside a partition makes it an approximation
/// (the covariance of one layer's alpha and the colours behind it is lost).
pub trait Shader<F: Float, P> {
    /// The premultiplied colour of `interval` averaged over the partition `[t0, t1]`
    /// (inside the interval's life), weighted by the shutter response, which is linear
    /// on the partition from `w0` at `t0` to `w1` at `t1` (`w0 + w1 > 0`).
    ///
    /// Gribel 2010, Eq. 17 with a time-varying c_k: the sweep multiplies the result by
    /// ∫ w over the partition.
    fn shade(&self, interval: &Interval<F, P>, t0: F, t1: F, w0: F, w1: F) -> [F; 4];

    /// The premultiplied colour of `interval` at the single time `t` (what a point sample
    /// of the shutter sees; used by [`crate::reference`]).
    fn shade_at(&self, interval: &Interval<F, P>, t: F) -> [F; 4];

    /// A lower bound of the alpha [`Shader::shade`] can return for `interval` over any
    /// partition. The transparent sweep uses it to find the layers that early termination
    /// certainly hides and skips depth crossings among them. The default, 0, never prunes.
    fn min_alpha(&self, interval: &Interval<F, P>) -> F {
        let _ = interval;
        F::zero()
    }
}

/// The shader for flat-coloured intervals: the payload's colour, premultiplied, with alpha
/// clamped to [0, 1].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Flat;

fn flat_premultiplied<F: Float>(c: &Rgba<F>) -> [F; 4] {
    let a = c.a.max(F::zero()).min(F::one());
    [a * c.r, a * c.g, a * c.b, a]
}

impl<F: Float> Shader<F, Rgba<F>> for Flat {
    fn shade(&self, interval: &Interval<F, Rgba<F>>, _: F, _: F, _: F, _: F) -> [F; 4] {
        flat_premultiplied(&interval.payload)
    }

    fn shade_at(&self, interval: &Interval<F, Rgba<F>>, _: F) -> [F; 4] {
        flat_premultiplied(&interval.payload)
    }

    fn min_alpha(&self, interval: &Interval<F, Rgba<F>>) -> F {
        interval.payload.a.max(F::zero()).min(F::one())
    }
}

/// Texture coordinates of a textured interval at time `t`: the lerp of `uv_start` →
/// `uv_end` over `[ts, te]` (Rønnow 2021, §4.3, UV_t^I).
pub fn uv_at<F: Float>(interval: &Interval<F, Textured<F>>, t: F) -> [F; 2] {
    let span = interval.te - interval.ts;
    let s = if span > F::zero() {
        (t - interval.ts) / span
    } else {
        F::zero()
    };
    let [u0, v0] = interval.payload.uv_start;
    let [u1, v1] = interval.payload.uv_end;
    [u0 + (u1 - u0) * s, v0 + (v1 - v0) * s]
}

fn scale<F: Float>(c: [F; 4], s: F) -> [F; 4] {
    [c[0] * s, c[1] * s, c[2] * s, c[3] * s]
}

/// The shutter weights at a segment's ends, (1, 1) where both are zero (a partition of
/// zero shutter weight still gets its colour).
#[inline]
fn shutter_weights<F: Float>(w0: F, w1: F) -> [F; 2] {
    if w0 + w1 > F::zero() {
        [w0, w1]
    } else {
        [F::one(), F::one()]
    }
}

/// One tap at the segment's midpoint with premultiplied colour `c`, weighted by the shutter
/// response there and normalised, times `alpha`: [`TapFilter`] with one tap.
#[inline]
fn midpoint_tap<F: Float>(c: [F; 4], alpha: F, w0: F, w1: F) -> [F; 4] {
    let half = F::one() / (F::one() + F::one());
    let w = w0 + (w1 - w0) * half;
    let sum = c.map(|c| F::zero() + w * c);
    scale(sum, alpha / (F::zero() + w))
}

/// What [`TapFilter`] with one tap returns for a material whose premultiplied lookup is
/// `c` at every UV (an untextured material): the same bits without the UV or the lookup,
/// for a caller that knows the colour does not depend on UV.
pub fn uniform_colour<F: Float>(c: [F; 4], alpha: F, w0: F, w1: F) -> [F; 4] {
    let [w0, w1] = shutter_weights(w0, w1);
    midpoint_tap(c, alpha, w0, w1)
}

/// Textured shading by `taps` point samples along the partition's UV segment, at the
/// midpoints of `taps` equal steps, each weighted by the shutter response there (the
/// midpoint rule; Rønnow 2021 uses 2 × 16 anisotropic taps for the same integral).
///
/// The texel colour is multiplied by the payload's material alpha. Cost: `taps` texture
/// lookups per active interval per partition; error O(1/taps²) for smooth textures and
/// O(1/taps) across texel discontinuities.
#[derive(Debug)]
pub struct TapFilter<'a, T: ?Sized> {
    texture: &'a T,
    taps: usize,
}

impl<T: ?Sized> Clone for TapFilter<'_, T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T: ?Sized> Copy for TapFilter<'_, T> {}

impl<'a, T: ?Sized> TapFilter<'a, T> {
    /// A tap filter over `texture` with `taps` samples per segment (at least 1).
    pub fn new(texture: &'a T, taps: usize) -> Self {
        Self {
            texture,
            taps: taps.max(1),
        }
    }

    /// The number of taps per segment (the accuracy knob).
    pub fn taps(&self) -> usize {
        self.taps
    }
}

impl<T: ?Sized> TapFilter<'_, T> {
    /// The filtered premultiplied colour along the UV segment `uv0` → `uv1` of `material`,
    /// with the shutter weight linear from `w0` to `w1` along it, times the material alpha
    /// `alpha`: what [`Shader::shade`] returns once it has the partition's UV ends (for a
    /// caller that already computed them, e.g. to choose the number of taps).
    #[inline]
    pub fn shade_segment<F: Float>(
        &self,
        (material, alpha): (u32, F),
        [u0, v0]: [F; 2],
        [u1, v1]: [F; 2],
        w0: F,
        w1: F,
    ) -> [F; 4]
    where
        T: Texture<F>,
    {
        let n = F::from(self.taps).unwrap_or_else(F::one);
        let half = F::one() / (F::one() + F::one());
        let [w0, w1] = shutter_weights(w0, w1);
        if self.taps == 1 {
            // The midpoint alone: s = (0 + 1/2) / 1.
            let c = self
                .texture
                .sample_premultiplied(material, [u0 + (u1 - u0) * half, v0 + (v1 - v0) * half]);
            return midpoint_tap(c, alpha, w0, w1);
        }
        let mut sum = [F::zero(); 4];
        let mut weights = F::zero();
        let mut i = F::zero();
        for _ in 0..self.taps {
            let s = (i + half) / n;
            let w = w0 + (w1 - w0) * s;
            let c = self
                .texture
                .sample_premultiplied(material, [u0 + (u1 - u0) * s, v0 + (v1 - v0) * s]);
            for (acc, c) in sum.iter_mut().zip(c) {
                *acc = *acc + w * c;
            }
            weights = weights + w;
            i = i + F::one();
        }
        scale(sum, alpha / weights)
    }
}

impl<F: Float, T: Texture<F> + ?Sized> Shader<F, Textured<F>> for TapFilter<'_, T> {
    fn shade(&self, interval: &Interval<F, Textured<F>>, t0: F, t1: F, w0: F, w1: F) -> [F; 4] {
        let p = &interval.payload;
        let (uv0, uv1) = (uv_at(interval, t0), uv_at(interval, t1));
        self.shade_segment((p.material, p.alpha), uv0, uv1, w0, w1)
    }

    fn shade_at(&self, interval: &Interval<F, Textured<F>>, t: F) -> [F; 4] {
        let c = self
            .texture
            .sample_premultiplied(interval.payload.material, uv_at(interval, t));
        scale(c, interval.payload.alpha)
    }
}

/// Textured shading by the exact weighted integral of the texture along the partition's
/// UV segment ([`SegmentTexture::segment_average`]), times the material alpha.
///
/// For [`crate::BilinearTexture`] this is the box-filtered (over time) bilinear texture,
/// exact up to rounding; its cost grows with the number of texel cells the segment crosses.
#[derive(Debug)]
pub struct ExactFilter<'a, T: ?Sized> {
    texture: &'a T,
}

impl<T: ?Sized> Clone for ExactFilter<'_, T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T: ?Sized> Copy for ExactFilter<'_, T> {}

impl<'a, T: ?Sized> ExactFilter<'a, T> {
    /// The exact filter over `texture`.
    pub fn new(texture: &'a T) -> Self {
        Self { texture }
    }
}

impl<F: Float, T: SegmentTexture<F> + ?Sized> Shader<F, Textured<F>> for ExactFilter<'_, T> {
    fn shade(&self, interval: &Interval<F, Textured<F>>, t0: F, t1: F, w0: F, w1: F) -> [F; 4] {
        let c = self.texture.segment_average(
            interval.payload.material,
            uv_at(interval, t0),
            uv_at(interval, t1),
            w0,
            w1,
        );
        scale(c, interval.payload.alpha)
    }

    fn shade_at(&self, interval: &Interval<F, Textured<F>>, t: F) -> [F; 4] {
        let c = self
            .texture
            .sample_premultiplied(interval.payload.material, uv_at(interval, t));
        scale(c, interval.payload.alpha)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn textured(uv_start: [f64; 2], uv_end: [f64; 2]) -> Interval<f64, Textured<f64>> {
        Interval::new(
            0.2,
            0.6,
            1.0,
            0.0,
            Textured {
                uv_start,
                uv_end,
                material: 0,
                alpha: 0.5,
            },
        )
    }

    #[test]
    fn uv_is_lerped_over_the_interval_life() {
        let iv = textured([0.0, 1.0], [1.0, 0.0]);
        let uv = uv_at(&iv, 0.3);
        assert!((uv[0] - 0.25).abs() < 1e-15 && (uv[1] - 0.75).abs() < 1e-15);
    }

    #[test]
    fn taps_integrate_a_linear_ramp_exactly_with_weights() {
        // Texture red = u; the partition sees u from 0.25 to 0.5; weight linear 1 -> 3.
        let ramp = |_: u32, uv: [f64; 2]| Rgba::opaque(uv[0], 0.0, 0.0);
        let iv = textured([0.0, 0.0], [1.0, 0.0]);
        let c = TapFilter::new(&ramp, 1).shade(&iv, 0.3, 0.4, 1.0, 3.0);
        // Midpoint rule is exact for the constant weight * linear colour only when w0 = w1;
        // with 1 tap the answer is the value at s = 0.5.
        assert!((c[0] - 0.5 * 0.375).abs() < 1e-12);
        // Many taps approach the weighted mean: ∫(1+2s)(0.25+0.25s)ds / 2 = 0.3958333...
        let c = TapFilter::new(&ramp, 4096).shade(&iv, 0.3, 0.4, 1.0, 3.0);
        let exact = (0.25 + 0.125 + 0.25 + 2.0 * 0.25 / 3.0) / 2.0;
        assert!((c[0] - 0.5 * exact).abs() < 1e-7, "{}", c[0]);
        assert!((c[3] - 0.5).abs() < 1e-12);
    }

    #[test]
    fn segment_shading_is_the_interval_shading_at_the_partition_uvs() {
        // Red = u, green = v: the midpoint rule is exact for a linear texture with a
        // constant weight, so the segment (0.1, 0.9) -> (0.5, 0.1) averages to its midpoint.
        let ramp = |_: u32, uv: [f64; 2]| Rgba::opaque(uv[0], uv[1], 0.0);
        let f = TapFilter::new(&ramp, 4);
        let c = f.shade_segment((0, 0.5), [0.1, 0.9], [0.5, 0.1], 1.0, 1.0);
        assert!((c[0] - 0.5 * 0.3).abs() < 1e-15 && (c[1] - 0.5 * 0.5).abs() < 1e-15);
        assert!((c[3] - 0.5).abs() < 1e-15);
        // And `shade` is exactly `shade_segment` at the UVs lerped to the partition ends.
        let iv = textured([0.0, 1.0], [1.0, 0.0]);
        let (t0, t1) = (0.3, 0.45);
        let seg = f.shade_segment((0, 0.5), uv_at(&iv, t0), uv_at(&iv, t1), 0.5, 2.0);
        assert_eq!(f.shade(&iv, t0, t1, 0.5, 2.0), seg);
    }
}
