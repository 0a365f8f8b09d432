//! Cutting an A-buffer piece where its visible splat surface changes (Heinzle 2010, §4.4:
//! "the depth interval of the later time interval is adjusted accordingly by removing the
//! occluded interval from it"), exactly.
//!
//! On a piece [t0, t1] of the exposure the same fragments are active, and each fragment's
//! depth is linear in t. The visible splat surface at an instant is the group of the
//! ternary depth test: the fragments within `max(eps_front, eps)` of the nearest one. It
//! changes only where a fragment f crosses the nearest fragment g (`d_f - d_g = 0`: the
//! nearest one changes) or the edge of g's tolerance (`d_f - d_g = max(eps_f, eps_g)`).
//! Both are crossings of a line with a level, in closed form. The piece is cut at the
//! events of the fragment nearest at its middle, then each sub-piece likewise with its own
//! nearest fragment, until no sub-piece has an event inside; the events are computed once
//! per pair and level from the depths at t0 and t1, so they are finitely many fixed times
//! and the cutting ends. On every sub-piece left, the nearest fragment never changes and
//! no fragment crosses its tolerance edge, so the group is the same at every instant.
//! Neighbouring sub-pieces with the same group are merged again (two fragments of one
//! surface swapping depth change nothing): a piece whose visible surface never changes is
//! returned whole and keeps the arithmetic it had without these cuts.

use crate::abuffer::{crossing, hidden};
use crate::fragment::Fragment;
use crate::surface::SurfaceInterval;

/// A fragment of the pixel: its depth `c0 + c1 t`, its depth tolerance, and the terms of
/// [`Fragment::depth_at`] (to find the nearest fragment at a piece's middle bit for bit as
/// the resolve does, [`Line::depth_at`]).
#[derive(Clone, Copy, Debug)]
struct Line {
    c0: f64,
    c1: f64,
    eps: f64,
    s0: f64,
    ds_dz: f64,
    time_mid: f64,
    time_half: f64,
}

impl Line {
    /// [`Fragment::depth_at`]: the same operations in the same order.
    fn depth_at(&self, t: f64) -> f64 {
        self.s0 + ((t - self.time_mid) / self.time_half) * self.ds_dz
    }
}

/// A fragment active over the piece being split: its depths at the piece's ends and its
/// depth tolerance.
#[derive(Clone, Copy, Debug)]
struct Active {
    d0: f64,
    d1: f64,
    eps: f64,
}

/// Reusable scratch space of [`split_piece`]; `pieces` holds its result.
#[derive(Default)]
pub(crate) struct Split {
    /// The sub-pieces of the last piece split, in time order, covering it exactly.
    pub pieces: Vec<(f64, f64)>,
    /// When the last piece was left whole: its nearest fragment at the middle,
    /// `(depth, depth tolerance)`, computed as the resolve's `splat_front` does.
    pub front: Option<(f64, f64)>,
    /// The active time spans `[t_start, t_end]` of the pixel's fragments
    /// ([`Split::prepare`]; apart from `lines` so that finding the active ones reads little).
    spans: Vec<[f64; 2]>,
    /// The pixel's fragments, in the same order.
    lines: Vec<Line>,
    /// Fragment indices by start time, and how many of them have started.
    by_start: Vec<usize>,
    started: usize,
    /// The fragments active over the current piece, in fragment order.
    current: Vec<usize>,
    /// The current piece (pieces come in time order).
    at: (f64, f64),
    /// The fragments active over the piece, in fragment order.
    active: Vec<Active>,
    /// Sub-pieces still to examine.
    stack: Vec<(f64, f64)>,
    /// Sub-pieces without an event inside, in time order.
    raw: Vec<(f64, f64)>,
    /// Event times of one nearest fragment.
    events: Vec<f64>,
    /// Ternary-test groups (indices into `active`) of the last merged sub-piece and of the
    /// next one.
    groups: [Vec<usize>; 2],
}

impl Split {
    /// Takes the fragments of the pixel whose pieces [`split_piece`] will cut.
    pub(crate) fn prepare(&mut self, frags: &[Fragment]) {
        self.spans.clear();
        self.spans
            .extend(frags.iter().map(|f| [f.t_start(), f.t_end()]));
        self.lines.clear();
        self.lines.extend(frags.iter().map(|f| {
            // depth(z) = s0 + z ds_dz with z = (t - time_mid) / time_half.
            let c1 = f.line.ds_dz / f.time_half;
            Line {
                c0: f.line.s0 - c1 * f.time_mid,
                c1,
                eps: f.eps,
                s0: f.line.s0,
                ds_dz: f.line.ds_dz,
                time_mid: f.time_mid,
                time_half: f.time_half,
            }
        }));
        self.by_start.clear();
        self.by_start.extend(0..frags.len());
        let spans = &self.spans;
        self.by_start.sort_unstable_by(|&a, &b| {
            let (sa, sb) = (
                spans.get(a).map_or(0.0, |s| s[0]),
                spans.get(b).map_or(0.0, |s| s[0]),
            );
            sa.total_cmp(&sb)
        });
        self.started = 0;
        self.current.clear();
        self.at = (f64::NEG_INFINITY, f64::NEG_INFINITY);
    }

    /// The indices of the fragments active over the last piece given to [`split_piece`]
    /// (`t_start <= t0` and `t_end >= t1`), ascending.
    pub(crate) fn active(&self) -> &[usize] {
        &self.current
    }

    /// Moves to the piece [t0, t1]: `current` becomes the fragments active over it
    /// (`t_start <= t0` and `t_end >= t1`, as the resolve tests), in fragment order. Pieces
    /// come in time order, so a fragment is added once when it starts and removed once
    /// when it ends; a piece out of order starts again from the first fragment.
    fn advance(&mut self, (t0, t1): (f64, f64)) {
        if t0 < self.at.0 || t1 < self.at.1 {
            self.started = 0;
            self.current.clear();
        }
        self.at = (t0, t1);
        let spans = &self.spans;
        while let Some(&i) = self.by_start.get(self.started) {
            if !spans.get(i).is_some_and(|s| s[0] <= t0) {
                break;
            }
            let at = self.current.partition_point(|&j| j < i);
            self.current.insert(at, i);
            self.started += 1;
        }
        self.current
            .retain(|&i| spans.get(i).is_some_and(|s| s[1] >= t1));
    }
}

/// The depths of the active fragments at time `t` of the piece [t0, t1], by linear
/// interpolation of their end depths.
fn depths_at<'a>(
    active: &'a [Active],
    (t0, t1): (f64, f64),
    t: f64,
) -> impl Iterator<Item = f64> + 'a {
    let s = (t - t0) / (t1 - t0);
    active.iter().map(move |a| a.d0 + (a.d1 - a.d0) * s)
}

/// The index and depth of the nearest active fragment at time `t` (the first on a tie).
fn nearest(active: &[Active], span: (f64, f64), t: f64) -> Option<(usize, f64)> {
    let mut front: Option<(usize, f64)> = None;
    for (i, d) in depths_at(active, span, t).enumerate() {
        if front.is_none_or(|(_, fd)| d < fd) {
            front = Some((i, d));
        }
    }
    front
}

/// The ternary depth test at time `t` (Heinzle 2010, §4.4): into `group`, the indices of
/// the active fragments within `max(eps_front, eps)` of the nearest one.
fn group_at(active: &[Active], span: (f64, f64), t: f64, group: &mut Vec<usize>) {
    group.clear();
    let Some((g, fd)) = nearest(active, span, t) else {
        return;
    };
    let feps = active.get(g).map_or(0.0, |a| a.eps);
    for (i, (d, a)) in depths_at(active, span, t).zip(active).enumerate() {
        if d <= fd + feps.max(a.eps) {
            group.push(i);
        }
    }
}

/// The time inside the piece at which `d_i - d_j` crosses `level`, computed from the pair
/// in index order so that an event is the same time whichever of the two is the nearest.
fn pair_event(
    active: &[Active],
    (i, j): (usize, usize),
    level: f64,
    (t0, t1): (f64, f64),
) -> Option<f64> {
    let (p, q, level) = if i < j { (i, j, level) } else { (j, i, -level) };
    let (a, b) = (active.get(p)?, active.get(q)?);
    crossing(t0, t1, a.d0 - b.d0, a.d1 - b.d1, level, level)
}

/// Cuts the piece `span` = [t0, t1] of a pixel (on which the same fragments and surface
/// intervals are active) where its visible splat surface changes, into `split.pieces`
/// (Heinzle 2010, §4.4; see the module documentation); the fragments are those given to
/// [`Split::prepare`]. Pieces with fewer than two active fragments, or whose splats an
/// opaque surface interval hides, are returned whole.
pub(crate) fn split_piece(surfaces: &[SurfaceInterval], span: (f64, f64), split: &mut Split) {
    split.advance(span);
    let Split {
        pieces,
        front: front_out,
        lines,
        current,
        active,
        stack,
        raw,
        events,
        groups,
        ..
    } = split;
    let (t0, t1) = span;
    let tm = 0.5 * (t0 + t1);
    pieces.clear();
    active.clear();
    // The active fragments and the nearest one at the middle, in one pass.
    let mut near: Option<(usize, f64, f64)> = None;
    for f in current.iter().filter_map(|&i| lines.get(i)) {
        let dm = f.depth_at(tm);
        if near.is_none_or(|(_, fd, _)| dm < fd) {
            near = Some((active.len(), dm, f.eps));
        }
        active.push(Active {
            d0: f.c0 + f.c1 * t0,
            d1: f.c0 + f.c1 * t1,
            eps: f.eps,
        });
    }
    *front_out = near.map(|(_, d, e)| (d, e));
    let front = near.map(|(g, d, _)| (g, d));
    let whole = match front {
        Some((_, d)) => active.len() < 2 || hidden(surfaces, span, d),
        None => true,
    };
    if whole {
        pieces.push(span);
        return;
    }
    raw.clear();
    stack.clear();
    stack.push(span);
    while let Some((a, b)) = stack.pop() {
        let near = if (a, b) == span {
            front
        } else {
            nearest(active, span, 0.5 * (a + b))
        };
        let Some((g, _)) = near else {
            raw.push((a, b));
            continue;
        };
        let Some(&fg) = active.get(g) else { continue };
        events.clear();
        for (i, f) in active.iter().enumerate() {
            let e = f.eps.max(fg.eps);
            let (x0, x1) = (f.d0 - fg.d0, f.d1 - fg.d1);
            // Neither level is crossed over the whole piece (the usual case): no event.
            if i == g || ((x0 > 0.0) == (x1 > 0.0) && (x0 > e) == (x1 > e)) {
                continue;
            }
            for level in [0.0, e] {
                let t = pair_event(active, (i, g), level, span);
                events.extend(t.filter(|t| *t > a && *t < b));
            }
        }
        if events.is_empty() {
            raw.push((a, b));
            continue;
        }
        events.sort_unstable_by(f64::total_cmp);
        events.dedup();
        // Latest first on the stack, so that `raw` fills in time order.
        let mut hi = b;
        for &t in events.iter().rev() {
            stack.push((t, hi));
            hi = t;
        }
        stack.push((a, hi));
    }
    if raw.len() < 2 {
        pieces.push(span);
        return;
    }
    merge(active, span, raw, groups, pieces);
}

/// Merges neighbouring sub-pieces of `raw` (in time order, tiling `span`) on which the
/// ternary test picks the same group into `pieces`.
fn merge(
    active: &[Active],
    span: (f64, f64),
    raw: &[(f64, f64)],
    [last, next]: &mut [Vec<usize>; 2],
    pieces: &mut Vec<(f64, f64)>,
) {
    let mut merged: Option<(f64, f64)> = None;
    for &(a, b) in raw {
        group_at(active, span, 0.5 * (a + b), next);
        match merged {
            Some((ma, _)) if next == last => merged = Some((ma, b)),
            _ => {
                pieces.extend(merged);
                merged = Some((a, b));
                std::mem::swap(last, next);
            }
        }
    }
    pieces.extend(merged);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::RayLine;
    use glam::DVec3;

    /// A fragment active over [ts, te] at depth `d0 + k t` with depth tolerance `eps`.
    fn frag(ts: f64, te: f64, d0: f64, k: f64, eps: f64) -> Fragment {
        // time_mid 0.5, time_half 0.5: z = 2t - 1, depth(z) = d(0.5) + z k / 2.
        Fragment {
            pixel: 0,
            splat: 0,
            subframe: 0,
            line: RayLine {
                b: DVec3::ZERO,
                f: DVec3::Z,
                s0: d0 + 0.5 * k,
                ds_dz: 0.5 * k,
            },
            za: 2.0 * ts - 1.0,
            zb: 2.0 * te - 1.0,
            time_mid: 0.5,
            time_half: 0.5,
            eps,
        }
    }

    /// The ternary test at one instant, written out from its definition with the
    /// fragments' own depths: those active at t within `max(eps_front, eps)` of the
    /// nearest one (fragment indices).
    fn group_of(frags: &[Fragment], t: f64) -> Vec<usize> {
        let on: Vec<usize> = (0..frags.len())
            .filter(|&i| frags[i].t_start() < t && t < frags[i].t_end())
            .collect();
        let Some(&g) = on
            .iter()
            .min_by(|&&a, &&b| frags[a].depth_at(t).total_cmp(&frags[b].depth_at(t)))
        else {
            return Vec::new();
        };
        let (fd, fe) = (frags[g].depth_at(t), frags[g].eps);
        on.into_iter()
            .filter(|&i| frags[i].depth_at(t) - fd <= fe.max(frags[i].eps))
            .collect()
    }

    proptest::proptest! {
        /// Heinzle 2010, §4.4: every sub-piece shows one group at 40 instants inside it,
        /// and neighbouring sub-pieces show different groups (the cuts are where the
        /// visible surface changes, and only there); the sub-pieces tile the piece.
        #[test]
        fn sub_pieces_have_one_group_and_neighbours_differ(
            spec in proptest::collection::vec(
                (0.0f64..1.0, 0.0f64..1.0, 0.0f64..4.0, -6.0f64..6.0, 0.05f64..1.0),
                1..7,
            ),
        ) {
            let frags: Vec<Fragment> = spec
                .iter()
                .map(|&(a, b, d0, k, eps)| frag(a.min(b), a.max(b) + 1e-3, d0, k, eps))
                .collect();
            let mut times = vec![0.0, 1.0];
            for f in &frags {
                times.push(f.t_start().clamp(0.0, 1.0));
                times.push(f.t_end().clamp(0.0, 1.0));
            }
            times.sort_by(f64::total_cmp);
            times.dedup();
            let mut split = Split::default();
            split.prepare(&frags);
            for w in times.windows(2) {
                split_piece(&[], (w[0], w[1]), &mut split);
                let pieces = split.pieces.clone();
                proptest::prop_assert_eq!(pieces.first().map(|p| p.0), Some(w[0]));
                proptest::prop_assert_eq!(pieces.last().map(|p| p.1), Some(w[1]));
                let mut last: Option<Vec<usize>> = None;
                for (k, &(a, b)) in pieces.iter().enumerate() {
                    proptest::prop_assert!(a < b);
                    if let Some(&(_, end)) = k.checked_sub(1).and_then(|j| pieces.get(j)) {
                        proptest::prop_assert_eq!(end, a);
                    }
                    let g = group_of(&frags, a + (b - a) / 80.0);
                    for i in 1..40 {
                        let t = a + (b - a) * (2 * i + 1) as f64 / 80.0;
                        proptest::prop_assert_eq!(&group_of(&frags, t), &g, "[{}, {}] at {}", a, b, t);
                    }
                    proptest::prop_assert!(last.as_ref() != Some(&g), "same group both sides of {}", a);
                    last = Some(g);
                }
            }
        }
    }

    /// Two fragments of one surface swapping depth (A = 1 - 0.2 t and B = 0.9 cross at
    /// t = 0.5, tolerance 0.2) and a third far behind: nothing visible changes, so the
    /// piece stays whole. A fragment C = 1.5 - t passing through them instead, by hand:
    /// it enters B's band (1.5 - t = 0.9 + 0.2) at 0.4, becomes the nearest at 0.625
    /// (no cut: the group stays {A, B, C}), B leaves C's band (0.9 = 1.5 - t + 0.2) at 0.8
    /// and A leaves it (1 - 0.2 t = 1.5 - t + 0.2) at 0.875.
    #[test]
    fn same_surface_swaps_stay_whole_and_a_passing_fragment_cuts_at_band_edges() {
        let mut frags = [
            frag(0.0, 1.0, 1.0, -0.2, 0.2),
            frag(0.0, 1.0, 0.9, 0.0, 0.2),
            frag(0.0, 1.0, 5.0, 0.0, 0.2),
        ];
        let mut split = Split::default();
        split.prepare(&frags);
        split_piece(&[], (0.0, 1.0), &mut split);
        assert_eq!(split.pieces, [(0.0, 1.0)]);
        frags[2] = frag(0.0, 1.0, 1.5, -1.0, 0.2);
        split.prepare(&frags);
        split_piece(&[], (0.0, 1.0), &mut split);
        let want = [0.0, 0.4, 0.8, 0.875, 1.0];
        assert_eq!(split.pieces.len(), 4, "{:?}", split.pieces);
        for (p, w) in split.pieces.iter().zip(want.windows(2)) {
            assert!(
                (p.0 - w[0]).abs() < 1e-12 && (p.1 - w[1]).abs() < 1e-12,
                "{:?}",
                split.pieces
            );
        }
    }

    /// The nearest fragment of a piece left whole is handed to the resolve, so the depth
    /// at the middle must be `Fragment::depth_at`'s bit for bit.
    #[test]
    fn line_depth_is_fragment_depth_bit_for_bit() {
        let frags: Vec<Fragment> = (0..50)
            .map(|i| {
                let x = f64::from(i);
                let mut f = frag(0.0, 1.0, 1.0 + 0.37 * x, (x * 0.77).sin() * 5.0, 0.1);
                f.time_mid = 0.1 + 0.013 * x;
                f.time_half = 0.05 + 0.021 * x;
                f
            })
            .collect();
        let mut split = Split::default();
        split.prepare(&frags);
        for (l, f) in split.lines.iter().zip(&frags) {
            for t in [0.0, 0.123_456_789, 0.5, 0.987, 1.0 / 3.0] {
                assert_eq!(l.depth_at(t).to_bits(), f.depth_at(t).to_bits());
            }
        }
    }
}
