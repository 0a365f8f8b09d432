//! How a covered span is cut into pieces: textured spans into as few equal pieces as keep
//! each piece's linear UV close to the true UV path at the pixel, each piece with its own
//! depth chord (Gribel 2010, Eq. 16 per piece).
//!
//! The resolve interpolates UV linearly over an interval (Rønnow 2021, Fig. 6), while at a
//! pixel the UV path of a rotating or perspective-moving triangle is a ratio of quadratics
//! in t (Gribel 2010, Eq. 11-12).

use glam::DVec2;

use super::{Real, cf};
use crate::texture::ceil;

/// Textured moving spans are cut into at most this many pieces per shutter length, each
/// with its own UVs at both ends: the resolve interpolates UV linearly over an interval
/// (Rønnow 2021 Fig. 6), while the true UV path at a pixel under rotation or perspective is
/// curved. How many pieces a span actually gets is decided by [`TEXTURE_TOLERANCE`].
pub const TEXTURE_PIECES: u32 = 32;

/// Texels the linear UV of a piece may stray from the true UV path at the pixel: a
/// textured span is cut into n equal pieces with n the smallest count whose estimated
/// deviation (the span's deviation from its chord at 1/4, 1/2 and 3/4, divided by n²)
/// is at most this, capped by [`TEXTURE_PIECES`]. A span whose UV path is straight (pure
/// translation parallel to the image plane, or a static pixel) stays one interval.
///
/// The colour error is at most the texture's colour step per texel times this. On the
/// rotating `textured-quad` (a hard-edged checker, 8 texels per square) at 64x36 the RMSE
/// against accum at 512 times is 1.39e-3 with 1/16 texel, 3.96e-4 with 1/64, 1.55e-4 with
/// 1/256, against 1.26e-4 when every span takes the full [`TEXTURE_PIECES`] cut; a nearly
/// static textured clothball at 1024² keeps 0.6 M of its 16.5 M intervals, and one
/// translating by 0.06 of its radius 6.0 M of 19.5 M.
pub const TEXTURE_TOLERANCE: f64 = 1.0 / 256.0;

/// End of piece `j` of `n` equal pieces of [t0, t1] (`j = n` gives `t1` exactly): how a
/// covered span is split so that each textured piece carries its own UV and depth chord.
#[inline]
pub(crate) fn piece_end<F: Real>(t0: F, t1: F, j: u32, n: u32) -> F {
    if j == n {
        t1
    } else if j == 0 {
        // The general formula's value without its division: (t1 - t0) * 0 is +0 for the
        // t1 >= t0 of a span.
        t0 + F::zero()
    } else {
        t0 + (t1 - t0) * (cf::<F>(f64::from(j)) / cf::<F>(f64::from(n)))
    }
}

/// The most pieces the span [t0, t1] may be cut into, `ceil(len TEXTURE_PIECES)` capped at
/// [`TEXTURE_PIECES`]; `None` when that is one (also for a NaN length): the span stays
/// whole, however its paths bend.
#[inline]
pub(crate) fn piece_cap<F: Real>(t0: F, t1: F) -> Option<u32> {
    let len = (t1 - t0).to_f64().unwrap_or(0.0);
    let cap = ceil(len * f64::from(TEXTURE_PIECES));
    if cap.is_nan() || cap <= 1.0 {
        return None;
    }
    Some(cap.min(f64::from(TEXTURE_PIECES)) as u32)
}

/// Fractions of a span at which its path is compared with its chord.
const PROBES: [f64; 3] = [0.25, 0.5, 0.75];

/// The instants of [`PROBES`] in the span [t0, t1]: where a caller evaluates each path
/// [`pieces_within`] measures (once for all of them).
#[inline]
pub(crate) fn probe_times<F: Real>(t0: F, t1: F) -> [F; 3] {
    PROBES.map(|s| t0 + (t1 - t0) * cf::<F>(s))
}

/// Number of equal pieces a span is cut into for one path it follows (see
/// [`TEXTURE_TOLERANCE`]): the path's ends `[a, b]` and its points `probes` at
/// [`probe_times`], `texels` cells per unit of the path (texels per unit of UV for the
/// texture coordinate at the pixel; [`super::lit::BARY_CELLS`] for barycentrics), at most
/// `cap` pieces ([`piece_cap`]). The UV path is a ratio of quadratics in t (Gribel 2010,
/// Eq. 11-12); over a short piece it is close to a parabola, whose deviation from its
/// chord falls as 1/n² with n pieces: the fewest pieces whose estimated deviation is
/// within the tolerance; the cap when the estimate is not finite. A span cut for several
/// paths takes the most pieces any of them needs, its probes evaluated once for all.
pub(crate) fn pieces_within(
    cap: u32,
    texels: DVec2,
    [a, b]: [DVec2; 2],
    probes: [DVec2; 3],
) -> u32 {
    let mut dev: f64 = 0.0;
    for (s, p) in PROBES.into_iter().zip(probes) {
        let d = ((p - a.lerp(b, s)) * texels).length();
        dev = if d.is_finite() {
            dev.max(d)
        } else {
            f64::INFINITY
        };
    }
    if !dev.is_finite() {
        return cap;
    }
    (ceil((dev / TEXTURE_TOLERANCE).sqrt()) as u32).clamp(1, cap)
}

/// Depth slope of the chord from (ta, za) to (tb, zb); zero for an empty or non-finite chord.
#[inline]
pub(crate) fn chord_slope<F: Real>(ta: F, tb: F, za: F, zb: F) -> F {
    let k = if tb > ta {
        (zb - za) / (tb - ta)
    } else {
        F::zero()
    };
    if k.is_finite() { k } else { F::zero() }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The smallest piece count n >= 1 with `dev / n²` within [`TEXTURE_TOLERANCE`], found
    /// by counting up (the cap when none is).
    fn fewest(dev: f64) -> u32 {
        (1..=TEXTURE_PIECES)
            .find(|&n| dev / f64::from(n * n) <= TEXTURE_TOLERANCE)
            .unwrap_or(TEXTURE_PIECES)
    }

    /// The pieces of span [t0, t1] for the one path `uv`, as the emitters compose them.
    fn texture_pieces<F: Real>(t0: F, t1: F, texels: DVec2, uv: impl Fn(F) -> DVec2) -> u32 {
        piece_cap(t0, t1).map_or(1, |cap| {
            pieces_within(cap, texels, [uv(t0), uv(t1)], probe_times(t0, t1).map(uv))
        })
    }

    #[test]
    fn pieces_are_the_fewest_that_keep_the_bend_within_the_tolerance() {
        let tol = TEXTURE_TOLERANCE;
        // A parabola bulging `dev` texels from its chord at the middle (less at 1/4, 3/4):
        // on both sides of each count's boundary, the boundaries themselves included.
        let devs = [
            0.0,
            0.5 * tol,
            tol,
            tol * (1.0 + 1e-12),
            4.0 * tol,
            4.0 * tol * (1.0 + 1e-12),
            9.0 * tol * (1.0 - 1e-12),
            30.0 * tol,
            2000.0 * tol,
        ];
        for dev in devs {
            let c = 4.0 * dev;
            let uv = |t: f64| DVec2::new(t, c * t * (1.0 - t));
            assert_eq!(
                texture_pieces(0.0, 1.0, DVec2::ONE, uv),
                fewest(dev),
                "{dev}"
            );
            let uv32 = |t: f32| uv(f64::from(t));
            assert_eq!(texture_pieces(0.0f32, 1.0, DVec2::ONE, uv32), fewest(dev));
        }
    }

    #[test]
    fn short_straight_and_broken_spans() {
        let bent = |t: f64| DVec2::new(t, 100.0 * t * (1.0 - t));
        // Shorter than one piece of the cap: one piece however it bends.
        assert_eq!(texture_pieces(0.5, 0.5 + 1.0 / 64.0, DVec2::ONE, bent), 1);
        // Straight: one piece however long.
        assert_eq!(texture_pieces(0.0, 1.0, DVec2::splat(1e6), DVec2::splat), 1);
        // A non-finite path takes the cap of the span's length.
        let nan = |_: f64| DVec2::splat(f64::NAN);
        assert_eq!(
            texture_pieces(0.0, 0.5, DVec2::ONE, nan),
            TEXTURE_PIECES / 2
        );
        let inf = |t: f64| DVec2::new(t, if t == 0.5 { f64::INFINITY } else { 0.0 });
        assert_eq!(texture_pieces(0.0, 1.0, DVec2::ONE, inf), TEXTURE_PIECES);
    }
}
