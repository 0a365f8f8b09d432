//! The active-list sweep: Rønnow 2021, Algorithm 1 as written (Gribel 2010, §5.1) — one
//! list of the active intervals, scanned at every event. O(active) per event, so O(n²)
//! for a pixel whose n intervals all overlap; kept as [`crate::Sweep::ActiveList`], a
//! second implementation the kinetic sweep is tested and benchmarked against.

use interval_buffer::Interval;
use num_traits::Float;

use crate::Shader;
use crate::depth_order::Line;
use crate::sweep::{Compositor, NextCrossing, Partition, Settings};

/// Sweeps one pixel: at each event the active list is brought into depth order for the
/// span that follows: fully re-sorted (insertion sort, linear when nearly sorted) for
/// transparent blending, so any number of simultaneous crossings reorder correctly; only
/// the nearest found for opaque blending. Without intersection handling each interval is
/// inserted at its depth rank when it starts and keeps it. The next crossing is the
/// earliest one that changes what is visible: between depth-adjacent intervals down to the
/// deepest layer early termination can reach (from [`Shader::min_alpha`]) or into that
/// layer (transparent), or between the nearest interval and any other (opaque).
///
/// If more than `handover` intervals become active, the sweep stops before the partition
/// at that time and returns where it stopped (time, next list position, shutter cursor);
/// `active` then holds the active intervals (in rank order without intersection handling)
/// for the kinetic sweep to continue from. `None`: the sweep reached t = 1.
pub(crate) fn sweep<F: Float, P, S: Shader<F, P>>(
    active: &mut Vec<Line<F>>,
    compositor: &mut Compositor<'_, F, P, S>,
    settings: &Settings<F>,
    sink: &mut impl FnMut(&Partition<F>),
    handover: usize,
) -> Option<(F, usize, usize)> {
    let (zero, one) = (F::zero(), F::one());
    let clamp01 = |t: F| t.max(zero).min(one);
    let intervals = compositor.intervals;
    let shader = compositor.shader;
    let shutter = compositor.shutter;
    let (opaque, threshold) = (compositor.opaque, compositor.threshold);
    active.clear();
    let mut next = 0;
    let mut cursor = 0;
    let mut r = zero;
    while r < one {
        active.retain(|l| l.te > r);
        while let Some(iv) = intervals.get(next) {
            if clamp01(iv.ts) > r {
                break;
            }
            let te = clamp01(iv.te);
            if te > r {
                let line = Line {
                    c: iv.z - iv.k * iv.ts,
                    k: iv.k,
                    te,
                    index: next,
                };
                if settings.intersections {
                    active.push(line);
                } else {
                    let at = active.partition_point(|e| !line.nearer_after(e, r));
                    active.insert(at, line);
                }
            }
            next += 1;
        }
        shutter.advance(&mut cursor, r);
        if active.len() > handover {
            return Some((r, next, cursor));
        }

        // The partition ends at the next start, end, shutter knot or crossing.
        let mut re = one;
        if let Some(iv) = intervals.get(next) {
            re = re.min(clamp01(iv.ts));
        }
        if let Some(knot) = shutter.next_knot(cursor) {
            re = re.min(knot);
        }
        for l in active.iter() {
            re = re.min(l.te);
        }
        if settings.intersections && !active.is_empty() {
            re = if opaque {
                nearest_to_front(active, r);
                first_crossing_with_front(active, r, re)
            } else {
                sort_by_depth_after(active, r);
                let last = last_visible_layer(active, intervals, shader, threshold);
                first_crossing_in_view(active, r, re, last)
            };
        }
        let p = compositor.partition(cursor, r, re, active.iter().map(|l| l.index));
        sink(&p);
        r = re;
    }
    None
}

/// Moves the interval nearest just after `t` to the front (opaque resolve: nothing behind
/// it needs an order).
fn nearest_to_front<F: Float>(active: &mut [Line<F>], t: F) {
    let mut best = 0;
    for (i, l) in active.iter().enumerate().skip(1) {
        if let Some(b) = active.get(best)
            && l.nearer_after(b, t)
        {
            best = i;
        }
    }
    active.swap(0, best);
}

/// Earliest time in (t, end) at which another interval becomes nearer than the front one.
fn first_crossing_with_front<F: Float>(active: &[Line<F>], t: F, end: F) -> F {
    let mut next = NextCrossing::new(t, end);
    if let Some((front, rest)) = active.split_first() {
        for l in rest {
            next.consider(front, l);
        }
    }
    next.time()
}
/// Insertion sort of the active list into depth order just after `t`: linear for a list
/// that was sorted at the previous event, plus one swap per crossing since.
fn sort_by_depth_after<F: Float>(active: &mut [Line<F>], t: F) {
    for i in 1..active.len() {
        let mut j = i;
        while j > 0 && active[j].nearer_after(&active[j - 1], t) {
            active.swap(j, j - 1);
            j -= 1;
        }
    }
}

/// Index of the deepest layer that transparent blending can reach: with the shader's alpha
/// lower bounds, transmittance is certainly `<= threshold` after it (the last layer if
/// never).
fn last_visible_layer<F: Float, P, S: Shader<F, P>>(
    active: &[Line<F>],
    intervals: &[Interval<F, P>],
    shader: &S,
    threshold: F,
) -> usize {
    let mut transmittance = F::one();
    for (i, l) in active.iter().enumerate() {
        if let Some(iv) = intervals.get(l.index) {
            let alpha = shader.min_alpha(iv).max(F::zero()).min(F::one());
            transmittance = transmittance * (F::one() - alpha);
            if transmittance <= threshold {
                return i;
            }
        }
    }
    active.len().saturating_sub(1)
}

/// Earliest time in (t, end) at which the depth-sorted layers `0..=last` change: a crossing
/// between two of them, which is first between neighbours (Rønnow 2021, Algorithm 1,
/// FindNearestIntervalIntersection), or a deeper interval crossing layer `last` to enter.
/// Crossings among the layers behind are not events; the next re-sort fixes their order.
fn first_crossing_in_view<F: Float>(active: &[Line<F>], t: F, end: F, last: usize) -> F {
    let mut next = NextCrossing::new(t, end);
    for pair in active.get(..=last).unwrap_or(active).windows(2) {
        if let [a, b] = pair {
            next.consider(a, b);
        }
    }
    if let Some(deepest) = active.get(last) {
        for behind in active.get(last + 1..).unwrap_or(&[]) {
            next.consider(deepest, behind);
        }
    }
    next.time()
}
