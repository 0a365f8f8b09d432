//! A-buffer visibility for motion-blurred kernels (Heinzle 2010, §4.4) with normalisation by
//! the kernel weights (§5.4) and the background blend by the covered-time integral, extended
//! with external surface intervals (triangles; [`SurfaceInterval`]).
//!
//! The fragments of one pixel carry time intervals [t_start, t_end] and depths that are
//! linear in time along the ray. The exposure is cut at every interval end, and each such
//! piece is cut again wherever its visible splat surface changes (below); on each final
//! piece the ternary depth test runs against the nearest active fragment: fragments within
//! the depth tolerance belong to the same surface and are accumulated, weighted by their
//! line integrals over the piece and normalised; farther fragments are occluded for that
//! piece (their occluded time is removed). The pieces are summed with the shutter weight
//! (Eq. 1), and the background fills the time no surface covers.
//!
//! **Splat surfaces passing through each other.** §4.4 removes the occluded part of the
//! later interval. Between two fragments f, g the depth difference `d_f(t) - d_g(t)` is
//! linear in t, so the times at which f crosses the nearest fragment g (level 0) or the
//! edge of its depth tolerance (level `max(eps_f, eps_g)`) are closed form. A piece is cut
//! at those events of its nearest fragment, recursively on the sub-pieces (each with its
//! own nearest fragment), until no sub-piece has an event inside; on each sub-piece the
//! nearest fragment and the ternary test's group are then the same at every instant, so the
//! group found at the middle is the one visible over the whole sub-piece. Neighbouring
//! sub-pieces with the same group are merged again: a piece whose visible surface does not
//! change stays whole and takes exactly the arithmetic it took without these cuts.
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
use crate::split::{Split, split_piece};
use crate::surface::SurfaceInterval;

/// Reusable per-thread scratch space.
#[derive(Default)]
pub(crate) struct Scratch {
    times: Vec<f64>,
    group: Vec<usize>,
    /// (depth, premultiplied colour, is a surface interval) of a piece's layers.
    layers: Vec<(f64, [f64; 4], bool)>,
    split: Split,
}

/// The time in (a, b) at which `f(t)` and `g(t)`, linear on [a, b], cross, if they swap
/// order strictly inside.
pub(crate) fn crossing(a: f64, b: f64, fa: f64, fb: f64, ga: f64, gb: f64) -> Option<f64> {
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

/// What one pixel is resolved from: its splat fragments and surface intervals, the
/// premultiplied colours per splat and the integration settings.
struct Pixel<'a> {
    frags: &'a [Fragment],
    surfaces: &'a [SurfaceInterval],
    colours: &'a [[f64; 4]],
    delta: f64,
    method: ErfMethod,
    shutter: Shutter,
}

/// Resolves one pixel from its splat fragments and surface intervals; `colours` are
/// premultiplied RGBA per splat, `bg` premultiplied (Heinzle 2010, §4.4 and §5.4).
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
    let px = Pixel {
        frags,
        surfaces,
        colours,
        delta,
        method,
        shutter,
    };
    let total = shutter.integral(0.0, 1.0);
    let Scratch {
        times,
        group,
        layers,
        split,
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
    split.prepare(frags);

    let mut out = [0.0f64; 4];
    let mut covered_alpha = 0.0;
    for w in times.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        if t1 <= t0 {
            continue;
        }
        split_piece(surfaces, (t0, t1), split);
        // The fragments active over [t0, t1] and so over each of its sub-pieces (no
        // fragment starts or ends inside it), in fragment order.
        let on = split.active();
        let whole = split.pieces.len() == 1;
        for &piece in &split.pieces {
            // A piece left whole comes with its nearest fragment (as `splat_front`).
            let front = if whole {
                split.front
            } else {
                splat_front(frags, on, piece)
            };
            resolve_piece(
                &px,
                Piece {
                    span: piece,
                    on,
                    front,
                },
                group,
                layers,
                (&mut out, &mut covered_alpha),
                integrals,
            );
        }
    }
    let rest = (total - covered_alpha).max(0.0);
    for k in 0..4 {
        out[k] = (out[k] + rest * bg[k]) / total;
    }
    out
}

/// True when an opaque surface interval active over [t0, t1] lies at or in front of depth
/// `depth` at the piece's middle (it hides the splat surface there).
pub(crate) fn hidden(surfaces: &[SurfaceInterval], (t0, t1): (f64, f64), depth: f64) -> bool {
    let tm = 0.5 * (t0 + t1);
    surfaces
        .iter()
        .filter(|v| v.t0 <= t0 && v.t1 >= t1)
        .any(|v| v.alpha() >= 1.0 && v.depth_at(tm) <= depth)
}

/// A piece of the exposure on which the same fragments and surface intervals are active
/// and the visible splat surface does not change.
struct Piece<'a> {
    /// [t0, t1].
    span: (f64, f64),
    /// The indices of the fragments active over it, ascending.
    on: &'a [usize],
    /// Its nearest fragment at the middle, `(depth, depth tolerance)` ([`splat_front`]).
    front: Option<(f64, f64)>,
}

/// Adds a piece to the pixel's premultiplied colour and covered alpha (Heinzle 2010,
/// §4.4).
fn resolve_piece(
    px: &Pixel<'_>,
    Piece {
        span: (t0, t1),
        on,
        front,
    }: Piece<'_>,
    group: &mut Vec<usize>,
    layers: &mut Vec<(f64, [f64; 4], bool)>,
    (out, covered_alpha): (&mut [f64; 4], &mut f64),
    integrals: &mut u64,
) {
    let s = px.shutter.integral(t0, t1);
    let any_surface = px.surfaces.iter().any(|v| v.t0 <= t0 && v.t1 >= t1);
    let splat = match front {
        None => None,
        // An opaque surface interval at or in front of the splat surface hides it: its
        // kernels need no line integrals on this piece.
        Some(front) if any_surface && hidden(px.surfaces, (t0, t1), front.0) => None,
        Some(front) => {
            let (acc, wsum) = splat_group(px, on, front, (t0, t1), group, integrals);
            if !any_surface {
                // Splats only: the arithmetic of the splat-only resolve.
                for k in 0..4 {
                    out[k] += s * acc[k] / wsum;
                }
                *covered_alpha += s * acc[3] / wsum;
                return;
            }
            Some((front.0, acc.map(|a| a / wsum)))
        }
    };
    if any_surface {
        composite(px.surfaces, splat, (t0, t1, s), layers, out, covered_alpha);
    }
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
fn splat_front(frags: &[Fragment], on: &[usize], (t0, t1): (f64, f64)) -> Option<(f64, f64)> {
    let tm = 0.5 * (t0 + t1);
    let mut front: Option<(f64, f64)> = None;
    for f in on.iter().filter_map(|&i| frags.get(i)) {
        let d = f.depth_at(tm);
        if front.is_none_or(|(fd, _)| d < fd) {
            front = Some((d, f.eps));
        }
    }
    front
}

/// The splat surface of the piece [t0, t1] in front at `(fd, feps)`: the fragments within
/// the depth tolerance of it (the ternary depth test) accumulated with their line integrals
/// over the piece (Heinzle 2010, §4.4, §5.4); returns the premultiplied sum and the weight
/// sum (> 0) to normalise by.
fn splat_group(
    px: &Pixel<'_>,
    on: &[usize],
    (fd, feps): (f64, f64),
    (t0, t1): (f64, f64),
    group: &mut Vec<usize>,
    integrals: &mut u64,
) -> ([f64; 4], f64) {
    let (frags, colours) = (px.frags, px.colours);
    let tm = 0.5 * (t0 + t1);
    // Ternary depth test: same surface within the tolerance, occluded beyond it.
    group.clear();
    for &i in on {
        if frags
            .get(i)
            .is_some_and(|f| f.depth_at(tm) <= fd + feps.max(f.eps))
        {
            group.push(i);
        }
    }
    let mut acc = [0.0f64; 4];
    let mut wsum = 0.0;
    for &i in group.iter() {
        let Some(f) = frags.get(i) else { continue };
        let wgt = f.weight(px.method, px.delta, t0, t1);
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
