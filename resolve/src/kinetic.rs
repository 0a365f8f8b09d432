//! The kinetic sweep ([`crate::Sweep::Kinetic`]): Rønnow 2021, Algorithm 1 with per-event
//! cost O(log n + visible layers) instead of O(active).
//!
//! - End events come from a min-heap of the active intervals' end times.
//! - With intersection handling, the active intervals are split in two: the *view*, a short
//!   vector of the nearest ones in exact depth order, just long enough that early
//!   termination is certain after it (its cumulative transmittance from
//!   [`crate::Shader::min_alpha`] is `<= threshold`; one interval for opaque blending), and
//!   the *hidden* rest in a kinetic tournament ([`crate::tournament`]), which knows the
//!   nearest hidden interval at all times. Crossing events are those between
//!   depth-adjacent intervals of the view, and the nearest hidden interval overtaking the
//!   deepest one of the view; crossings among hidden intervals only update the tournament
//!   (no partition, O(log n) each). While at most `SMALL_HIDDEN` intervals are hidden they
//!   are a plain list scanned at each event instead (cheaper for a few). At an event the
//!   view is re-sorted (insertion sort:
//!   linear when sorted, so any number of simultaneous crossings reorder correctly),
//!   hidden intervals that became nearer than its deepest one enter it, and intervals no
//!   longer needed for termination leave it.
//! - Without intersection handling, the active list is a treap in rank order
//!   ([`crate::rank_list`]): insert, remove and front in O(log m).
//!
//! Shading a partition walks the view (or the rank list) front to back until the
//! transmittance threshold: O(layers until termination). When the threshold is never
//! reached (threshold 0, or many layers with alpha near 0) every active interval is
//! visible and each partition needs O(active) work — the colour itself depends on all of
//! them — and every crossing between any two active intervals is a visible event.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use num_traits::Float;

use crate::Shader;
use crate::depth_order::Line;
use crate::rank_list::RankList;
use crate::sweep::{Compositor, NextCrossing, Partition, Settings};
use crate::tournament::Tournament;

/// Where an interval of the pixel is during the sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Place {
    /// Not active (not started, ended, or zero length).
    Out,
    /// In the view (intersection handling on).
    View,
    /// In the tournament of hidden intervals (intersection handling on).
    Hidden,
    /// In the rank list (intersection handling off).
    Ranked,
}

/// An end event: an active interval's clamped end time (ordered for a min-heap).
#[derive(Clone, Copy, Debug)]
struct End<F>(F, u32);

impl<F: Float> PartialEq for End<F> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl<F: Float> Eq for End<F> {}

impl<F: Float> PartialOrd for End<F> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<F: Float> Ord for End<F> {
    /// Reversed (earliest end is the greatest), so `BinaryHeap` pops the earliest. End
    /// times are finite (validated input), so `partial_cmp` never fails.
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .0
            .partial_cmp(&self.0)
            .unwrap_or(Ordering::Equal)
            .then(other.1.cmp(&self.1))
    }
}

/// Hidden active intervals at most this many are kept in a plain list (scanned at each
/// event, like Algorithm 1); one more moves them into the kinetic tournament for the rest
/// of the pixel. A scan of a few lines is cheaper than tournament updates (measured: the
/// sparse benchmark scenes, ~8 active, stay in the list).
const SMALL_HIDDEN: usize = 24;

/// The hidden active intervals (see the module docs).
#[derive(Clone, Debug)]
struct Hidden<F> {
    small: Vec<usize>,
    tree: Tournament<F>,
    in_tree: bool,
    n: usize,
}

impl<F: Float> Hidden<F> {
    fn reset(&mut self, n: usize) {
        self.small.clear();
        self.in_tree = false;
        self.n = n;
    }

    fn insert(&mut self, i: usize, t: F, lines: &[Line<F>]) {
        if self.in_tree {
            self.tree.insert(i, t, lines);
        } else if self.small.len() < SMALL_HIDDEN {
            self.small.push(i);
        } else {
            self.tree.reset(self.n);
            for j in self.small.drain(..) {
                self.tree.insert(j, t, lines);
            }
            self.tree.insert(i, t, lines);
            self.in_tree = true;
        }
    }

    fn remove(&mut self, i: usize, t: F, lines: &[Line<F>]) {
        if self.in_tree {
            self.tree.remove(i, t, lines);
        } else if let Some(pos) = self.small.iter().position(|&j| j == i) {
            self.small.swap_remove(pos);
        }
    }

    /// The nearest hidden interval just after `t` (every crossing up to `t` processed).
    fn min(&self, t: F, lines: &[Line<F>]) -> Option<usize> {
        if self.in_tree {
            return self.tree.min();
        }
        self.small.iter().copied().reduce(|a, b| {
            if lines[b].nearer_after(&lines[a], t) {
                b
            } else {
                a
            }
        })
    }

    /// Processes the earliest crossing among hidden intervals before `limit` (or at it,
    /// `inclusive`); the plain list has none to process (it is scanned instead).
    fn pop_due(&mut self, limit: F, inclusive: bool, lines: &[Line<F>]) -> Option<F> {
        if self.in_tree {
            self.tree.pop_due(limit, inclusive, lines)
        } else {
            None
        }
    }
}

/// Working memory of the kinetic sweep.
#[derive(Clone, Debug)]
pub(crate) struct KineticScratch<F> {
    lines: Vec<Line<F>>,
    place: Vec<Place>,
    ends: BinaryHeap<End<F>>,
    view: Vec<usize>,
    entering: Vec<usize>,
    hidden: Hidden<F>,
    ranks: RankList,
}

impl<F> KineticScratch<F> {
    pub fn new() -> Self {
        Self {
            lines: Vec::new(),
            place: Vec::new(),
            ends: BinaryHeap::new(),
            view: Vec::new(),
            entering: Vec::new(),
            hidden: Hidden {
                small: Vec::new(),
                tree: Tournament::new(),
                in_tree: false,
                n: 0,
            },
            ranks: RankList::default(),
        }
    }
}

/// Where the sweep starts: time `r`, the next list position to start, the shutter cursor,
/// and the intervals already active at `r` (in rank order without intersection handling).
pub(crate) struct Start<'a, F> {
    pub r: F,
    pub next: usize,
    pub cursor: usize,
    pub active: &'a [Line<F>],
}

/// Sweeps one pixel (see the module docs) from `start` to t = 1, reporting each partition
/// to `sink`.
pub(crate) fn sweep<F: Float, P, S: Shader<F, P>>(
    scratch: &mut KineticScratch<F>,
    compositor: &mut Compositor<'_, F, P, S>,
    settings: &Settings<F>,
    sink: &mut impl FnMut(&Partition<F>),
    start: Start<'_, F>,
) {
    let (zero, one) = (F::zero(), F::one());
    let clamp01 = |t: F| t.max(zero).min(one);
    let intervals = compositor.intervals;
    let shutter = compositor.shutter;
    let crossings = settings.intersections;
    let n = intervals.len();
    let KineticScratch {
        lines,
        place,
        ends,
        view,
        entering,
        hidden,
        ranks,
    } = scratch;
    lines.clear();
    lines.extend(intervals.iter().enumerate().map(|(index, iv)| Line {
        c: iv.z - iv.k * iv.ts,
        k: iv.k,
        te: clamp01(iv.te),
        index,
    }));
    place.clear();
    place.resize(n, Place::Out);
    ends.clear();
    view.clear();
    entering.clear();
    if crossings {
        hidden.reset(n);
    } else {
        ranks.reset(n);
    }
    for l in start.active {
        let i = l.index;
        if i < n {
            ends.push(End(l.te, i as u32));
            if crossings {
                entering.push(i);
            } else {
                // Appending keeps the rank order handed over.
                ranks.insert(i, |_| false);
                place[i] = Place::Ranked;
            }
        }
    }
    // How many of the view's intervals early termination certainly needs (None: all).
    let opaque = compositor.opaque;
    let threshold = compositor.threshold;
    let shader = compositor.shader;
    let needed = |view: &[usize]| -> Option<usize> {
        if opaque {
            return (!view.is_empty()).then_some(1);
        }
        let mut transmittance = one;
        for (k, &i) in view.iter().enumerate() {
            let alpha = intervals
                .get(i)
                .map_or(zero, |iv| shader.min_alpha(iv).max(zero).min(one));
            transmittance = transmittance * (one - alpha);
            if transmittance <= threshold {
                return Some(k + 1);
            }
        }
        None
    };

    let Start {
        mut r,
        mut next,
        mut cursor,
        ..
    } = start;
    while r < one {
        // Ends at or before r.
        while let Some(&End(te, i)) = ends.peek() {
            if te > r {
                break;
            }
            ends.pop();
            let i = i as usize;
            match place[i] {
                Place::View => {
                    if let Some(pos) = view.iter().position(|&v| v == i) {
                        view.remove(pos);
                    }
                }
                Place::Hidden => hidden.remove(i, r, lines),
                Place::Ranked => ranks.remove(i),
                Place::Out => {}
            }
            place[i] = Place::Out;
        }
        if crossings {
            // Crossings among hidden intervals up to r.
            while hidden.pop_due(r, true, lines).is_some() {}
        }
        // Starts at or before r.
        while let Some(iv) = intervals.get(next) {
            if clamp01(iv.ts) > r {
                break;
            }
            let line = lines[next];
            if line.te > r {
                ends.push(End(line.te, next as u32));
                if crossings {
                    entering.push(next);
                } else {
                    ranks.insert(next, |e| line.nearer_after(&lines[e], r));
                    place[next] = Place::Ranked;
                }
            }
            next += 1;
        }
        shutter.advance(&mut cursor, r);

        // The partition ends at the next start, end, shutter knot or visible crossing.
        let mut re = one;
        if let Some(iv) = intervals.get(next) {
            re = re.min(clamp01(iv.ts));
        }
        if let Some(knot) = shutter.next_knot(cursor) {
            re = re.min(knot);
        }
        if let Some(&End(te, _)) = ends.peek() {
            re = re.min(te);
        }
        let p = if crossings {
            refresh_view(view, entering, hidden, place, lines, r, &needed);
            let mut within = NextCrossing::new(r, re);
            for pair in view.windows(2) {
                if let [a, b] = *pair {
                    within.consider(&lines[a], &lines[b]);
                }
            }
            re = next_view_change(view, hidden, lines, r, within.time());
            compositor.partition(cursor, r, re, view.iter().copied())
        } else {
            compositor.partition(cursor, r, re, ranks.iter())
        };
        sink(&p);
        r = re;
    }
}

/// Brings the view into depth order just after `t`, adds the intervals starting at `t`
/// (`entering`, emptied) and makes the view exactly the nearest intervals that early
/// termination needs (all active ones if it never terminates).
fn refresh_view<F: Float>(
    view: &mut Vec<usize>,
    entering: &mut Vec<usize>,
    hidden: &mut Hidden<F>,
    place: &mut [Place],
    lines: &[Line<F>],
    t: F,
    needed: &impl Fn(&[usize]) -> Option<usize>,
) {
    // Insertion sort: linear when nothing crossed, one swap per crossing otherwise.
    for i in 1..view.len() {
        let mut j = i;
        while j > 0 && lines[view[j]].nearer_after(&lines[view[j - 1]], t) {
            view.swap(j, j - 1);
            j -= 1;
        }
    }
    // New intervals go straight where they belong (no detour through the tournament).
    for i in entering.drain(..) {
        let enters = match (needed(view), view.last()) {
            (Some(_), Some(&deepest)) => lines[i].nearer_after(&lines[deepest], t),
            _ => true,
        };
        if enters {
            insert_sorted(view, i, lines, t);
            place[i] = Place::View;
        } else {
            hidden.insert(i, t, lines);
            place[i] = Place::Hidden;
        }
    }
    loop {
        let need = needed(view);
        if let Some(k) = need {
            while view.len() > k {
                if let Some(i) = view.pop() {
                    hidden.insert(i, t, lines);
                    place[i] = Place::Hidden;
                }
            }
        }
        let Some(m) = hidden.min(t, lines) else {
            break;
        };
        let enters = match (need, view.last()) {
            (Some(_), Some(&deepest)) => lines[m].nearer_after(&lines[deepest], t),
            _ => true,
        };
        if !enters {
            break;
        }
        hidden.remove(m, t, lines);
        place[m] = Place::View;
        insert_sorted(view, m, lines, t);
    }
}

/// Inserts `i` into the depth-sorted `view` after every interval nearer than it at `t`.
fn insert_sorted<F: Float>(view: &mut Vec<usize>, i: usize, lines: &[Line<F>], t: F) {
    let at = view
        .iter()
        .rposition(|&v| !lines[i].nearer_after(&lines[v], t))
        .map_or(0, |p| p + 1);
    view.insert(at, i);
}

/// The end of the partition starting at `t`: `end` (the next start, end, knot or crossing
/// inside the view), or earlier when the nearest hidden interval overtakes the view's
/// deepest one. Crossings among hidden intervals before then are processed on the way
/// (they may change which hidden interval is nearest).
fn next_view_change<F: Float>(
    view: &[usize],
    hidden: &mut Hidden<F>,
    lines: &[Line<F>],
    t: F,
    end: F,
) -> F {
    let Some(&deepest) = view.last() else {
        return end;
    };
    let deepest = &lines[deepest];
    if !hidden.in_tree {
        // Algorithm 1: the first of the hidden intervals to overtake the deepest visible.
        let mut next = NextCrossing::new(t, end);
        for &i in &hidden.small {
            next.consider(deepest, &lines[i]);
        }
        return next.time();
    }
    let mut now = t;
    loop {
        let entry = match hidden.tree.min() {
            Some(m) => {
                let mut next = NextCrossing::new(now, end);
                next.consider(deepest, &lines[m]);
                next.time()
            }
            None => end,
        };
        match hidden.pop_due(entry, false, lines) {
            None => return entry,
            Some(tau) => {
                now = now.max(tau);
                if let Some(m) = hidden.tree.min()
                    && tau > t
                    && lines[m].nearer_after(deepest, tau)
                {
                    // Already in front of the view's deepest (a tie at tau): stop here.
                    return tau;
                }
            }
        }
    }
}
