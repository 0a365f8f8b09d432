//! A-buffer visibility for motion-blurred kernels (Heinzle 2010, §4.4) with normalisation by
//! the kernel weights (§5.4) and the background blend by the covered-time integral, extended
//! with external surface intervals (triangles; [`SurfaceInterval`]).
//!
//! The fragments of one pixel carry time intervals [t_start, t_end] and depths that are
//! linear in time along the ray. The exposure is cut at every interval end; on each piece
//! the ternary depth test runs against the nearest active fragment (at the piece's middle):
//! fragments within the depth tolerance belong to the same surface and are accumulated,
//! weighted by their line integrals over the piece and normalised; farther fragments are
//! occluded for that piece (their occluded time is removed). The pieces are summed with the
//! shutter weight (Eq. 1), and the background fills the time no surface covers.
//!
//! **External surfaces.** When the pixel also has surface intervals, the exposure is cut at
//! their ends too, and at every time where a surface interval and a splat fragment, or two
//! surface intervals, swap depth (both depths are linear in time, so each pair crosses at
//! most once), so that no pair changes order inside a piece and the order taken at the
//! piece's middle holds for the whole piece. On a piece the splat surface (the group of the
//! ternary test, at the depth of its nearest fragment, with the normalised colour and alpha
//! as coverage — the same rule as its blend over the background) and the active surface
//! intervals are sorted by depth (a surface interval before the splat surface on a tie) and
//! composited front to back: an opaque layer hides everything behind it. Splat fragments
//! behind the nearest one by more than the tolerance stay hidden, as without surfaces.
//! Pixels without surface intervals take exactly the arithmetic of the splat-only resolve.

use crate::erf::ErfMethod;
use crate::fragment::Fragment;
use crate::shutter::Shutter;
use crate::surface::SurfaceInterval;

/// Reusable per-thread scratch space.
#[derive(Default)]
pub(crate) struct Scratch {
    times: Vec<f64>,
    group: Vec<usize>,
    /// (depth, premultiplied colour, is a surface interval) of a piece's layers.
    layers: Vec<(f64, [f64; 4], bool)>,
}

/// The time in (a, b) at which `f(t)` and `g(t)`, linear on [a, b], cross, if they swap
/// order strictly inside.
fn crossing(a: f64, b: f64, fa: f64, fb: f64, ga: f64, gb: f64) -> Option<f64> {
    if a.partial_cmp(&b) != Some(std::cmp::Ordering::Less) {
        return None;
    }
    let (da, db) = (fa - ga, fb - gb);
    if !((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
        return None;
    }
    let t = a + (b - a) * (da / (da - db));
    (t > a && t < b && t.is_finite()).then_some(t)
}

/// Pushes the cut times of the surface intervals: their ends and the depth swaps with every
/// fragment and every other surface interval.
fn surface_cuts(frags: &[Fragment], surfaces: &[SurfaceInterval], times: &mut Vec<f64>) {
    for (i, s) in surfaces.iter().enumerate() {
        let (s0, s1) = (s.t0.clamp(0.0, 1.0), s.t1.clamp(0.0, 1.0));
        times.push(s0);
        times.push(s1);
        for f in frags {
            let a = s0.max(f.t_start().clamp(0.0, 1.0));
            let b = s1.min(f.t_end().clamp(0.0, 1.0));
            let d = (s.depth_at(a), s.depth_at(b), f.depth_at(a), f.depth_at(b));
            times.extend(crossing(a, b, d.0, d.1, d.2, d.3));
        }
        for o in surfaces.get(i + 1..).unwrap_or(&[]) {
            let a = s0.max(o.t0.clamp(0.0, 1.0));
            let b = s1.min(o.t1.clamp(0.0, 1.0));
            let d = (s.depth_at(a), s.depth_at(b), o.depth_at(a), o.depth_at(b));
            times.extend(crossing(a, b, d.0, d.1, d.2, d.3));
        }
    }
}

/// Resolves one pixel from its splat fragments and surface intervals; `colours` are
/// premultiplied RGBA per splat, `bg` premultiplied.
#[allow(clippy::too_many_arguments)]
pub(crate) fn resolve(
    frags: &[Fragment],
    surfaces: &[SurfaceInterval],
    colours: &[[f64; 4]],
    bg: [f64; 4],
    delta: f64,
    method: ErfMethod,
    shutter: Shutter,
    scratch: &mut Scratch,
    integrals: &mut u64,
) -> [f64; 4] {
    let total = shutter.integral(0.0, 1.0);
    let Scratch {
        times,
        group,
        layers,
    } = scratch;
    times.clear();
    times.push(0.0);
    times.push(1.0);
    for f in frags {
        times.push(f.t_start().clamp(0.0, 1.0));
        times.push(f.t_end().clamp(0.0, 1.0));
    }
    surface_cuts(frags, surfaces, times);
    times.sort_unstable_by(f64::total_cmp);
    times.dedup();

    let mut out = [0.0f64; 4];
    let mut covered_alpha = 0.0;
    for w in times.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        if t1 <= t0 {
            continue;
        }
        let tm = 0.5 * (t0 + t1);
        let s = shutter.integral(t0, t1);
        let active = |v: &&SurfaceInterval| v.t0 <= t0 && v.t1 >= t1;
        let any_surface = surfaces.iter().any(|v| active(&v));
        let splat = match splat_front(frags, (t0, t1)) {
            None => None,
            // An opaque surface interval at or in front of the splat surface hides it: its
            // kernels need no line integrals on this piece.
            Some(front)
                if any_surface
                    && surfaces
                        .iter()
                        .filter(active)
                        .any(|v| v.alpha() >= 1.0 && v.depth_at(tm) <= front.0) =>
            {
                None
            }
            Some(front) => {
                let (acc, wsum) = splat_group(
                    frags,
                    colours,
                    front,
                    (t0, t1),
                    delta,
                    method,
                    group,
                    integrals,
                );
                if !any_surface {
                    // Splats only: the arithmetic of the splat-only resolve.
                    for k in 0..4 {
                        out[k] += s * acc[k] / wsum;
                    }
                    covered_alpha += s * acc[3] / wsum;
                    continue;
                }
                Some((front.0, acc.map(|a| a / wsum)))
            }
        };
        if any_surface {
            composite(
                surfaces,
                splat,
                (t0, t1, s),
                layers,
                &mut out,
                &mut covered_alpha,
            );
        }
    }
    let rest = (total - covered_alpha).max(0.0);
    for k in 0..4 {
        out[k] = (out[k] + rest * bg[k]) / total;
    }
    out
}

/// Composites the layers of the piece [t0, t1] (shutter weight `s`) front to back: the
/// active surface intervals at the piece's middle and the splat surface `(depth,
/// premultiplied colour)`; adds the colour to `out` and the covered alpha to `covered`.
fn composite(
    surfaces: &[SurfaceInterval],
    splat: Option<(f64, [f64; 4])>,
    (t0, t1, s): (f64, f64, f64),
    layers: &mut Vec<(f64, [f64; 4], bool)>,
    out: &mut [f64; 4],
    covered: &mut f64,
) {
    let tm = 0.5 * (t0 + t1);
    layers.clear();
    layers.extend(
        surfaces
            .iter()
            .filter(|v| v.t0 <= t0 && v.t1 >= t1)
            .map(|v| (v.depth_at(tm), v.colour, true)),
    );
    if let Some((d, c)) = splat {
        layers.push((d, c, false));
    }
    // Nearest first; a surface interval before the splat surface on a tie; stable among
    // surface intervals of equal depth (their given order).
    layers.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.2.cmp(&a.2)));
    let mut transmit = 1.0f64;
    for (_, c, _) in layers.iter() {
        for k in 0..4 {
            out[k] += s * transmit * c[k];
        }
        transmit *= 1.0 - c[3].clamp(0.0, 1.0);
        if transmit <= 0.0 {
            transmit = 0.0;
            break;
        }
    }
    *covered += s * (1.0 - transmit);
}

/// The nearest fragment active over the whole piece [t0, t1], at the piece's middle:
/// `(depth, depth tolerance)`, or `None` when no fragment is active.
fn splat_front(frags: &[Fragment], (t0, t1): (f64, f64)) -> Option<(f64, f64)> {
    let tm = 0.5 * (t0 + t1);
    let mut front: Option<(f64, f64)> = None;
    for f in frags {
        if f.t_start() <= t0 && f.t_end() >= t1 {
            let d = f.depth_at(tm);
            if front.is_none_or(|(fd, _)| d < fd) {
                front = Some((d, f.eps));
            }
        }
    }
    front
}

/// The splat surface of the piece [t0, t1] in front at `(fd, feps)`: the fragments within
/// the depth tolerance of it (the ternary depth test) accumulated with their line integrals
/// over the piece; returns the premultiplied sum and the weight sum (> 0) to normalise by.
#[allow(clippy::too_many_arguments)]
fn splat_group(
    frags: &[Fragment],
    colours: &[[f64; 4]],
    (fd, feps): (f64, f64),
    (t0, t1): (f64, f64),
    delta: f64,
    method: ErfMethod,
    group: &mut Vec<usize>,
    integrals: &mut u64,
) -> ([f64; 4], f64) {
    let tm = 0.5 * (t0 + t1);
    // Ternary depth test: same surface within the tolerance, occluded beyond it.
    group.clear();
    for (i, f) in frags.iter().enumerate() {
        if f.t_start() <= t0 && f.t_end() >= t1 && f.depth_at(tm) <= fd + feps.max(f.eps) {
            group.push(i);
        }
    }
    let mut acc = [0.0f64; 4];
    let mut wsum = 0.0;
    for &i in group.iter() {
        let Some(f) = frags.get(i) else { continue };
        let wgt = f.weight(method, delta, t0, t1);
        *integrals += 1;
        let c = colours.get(f.splat as usize).copied().unwrap_or([0.0; 4]);
        for k in 0..4 {
            acc[k] += wgt * c[k];
        }
        wsum += wgt;
    }
    if wsum.is_nan() || wsum <= 0.0 {
        // All weights underflowed: fall back to the plain average of the surface.
        wsum = 0.0;
        acc = [0.0; 4];
        for &i in group.iter() {
            let Some(f) = frags.get(i) else { continue };
            let c = colours.get(f.splat as usize).copied().unwrap_or([0.0; 4]);
            for k in 0..4 {
                acc[k] += c[k];
            }
            wsum += 1.0;
        }
    }
    (acc, wsum)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against bisection on the difference of the two lines.
    #[test]
    fn crossing_matches_bisection_and_ignores_touching_or_parallel_lines() {
        let cases = [
            (0.0, 1.0, 2.0, 6.0, 3.0, 3.0),
            (0.2, 0.7, 1.0, -1.0, -0.5, 0.5),
            (0.0, 1.0, 5.0, 1.0, 1.0, 5.0),
        ];
        for (a, b, fa, fb, ga, gb) in cases {
            let t = crossing(a, b, fa, fb, ga, gb).unwrap();
            let d = |t: f64| {
                let s = (t - a) / (b - a);
                (fa + (fb - fa) * s) - (ga + (gb - ga) * s)
            };
            let (mut lo, mut hi) = (a, b);
            for _ in 0..200 {
                let m = 0.5 * (lo + hi);
                if (d(m) < 0.0) == (d(lo) < 0.0) {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            assert!((t - 0.5 * (lo + hi)).abs() < 1e-12, "{t} vs {lo}");
        }
        // Touching at an end, parallel, equal, empty span: no cut.
        assert_eq!(crossing(0.0, 1.0, 1.0, 2.0, 1.0, 3.0), None);
        assert_eq!(crossing(0.0, 1.0, 1.0, 2.0, 2.0, 3.0), None);
        assert_eq!(crossing(0.0, 1.0, 1.0, 2.0, 1.0, 2.0), None);
        assert_eq!(crossing(0.5, 0.5, 1.0, 2.0, 2.0, 1.0), None);
        assert_eq!(crossing(0.0, 1.0, f64::NAN, 2.0, 2.0, 1.0), None);
    }
}
