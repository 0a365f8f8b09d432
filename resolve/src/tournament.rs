//! A kinetic tournament: the nearest of a changing set of linear depth functions, kept up
//! to date by certificates (Basch, Guibas & Hershberger 1999, "Data structures for mobile
//! data"; Agarwal et al. 2008, "Kinetic and dynamic data structures for closest pair and
//! all nearest neighbors" — the kinetic tournament tree).
//!
//! A complete binary tree over the pixel's list positions: a leaf holds its interval while
//! that interval is in the set, every internal node the nearer (by [`Line::nearer_after`])
//! of its two children's winners, and a *certificate*: the time at which the losing winner
//! overtakes (from [`Line::crossing_estimate`], nudged lazily with
//! [`Line::nudge_past_crossing`] only when it becomes the earliest). Each node also keeps the
//! earliest certificate in its subtree, so the next failure is found from the root without
//! a separate heap and never goes stale. Insert, remove and one certificate failure each
//! recompute one leaf-to-root path: O(log n). For lines (at most one crossing per pair) a
//! node over s leaves changes winner at most O(s α(s)) times (the lower envelope of s
//! segments), so all failures of a sweep are O(n α(n) log n) in the worst case — and far
//! fewer for random depths.
//!
//! The resolve keeps the visible layers in a short sorted prefix and the hidden rest of
//! the active intervals in this tree: only the nearest hidden one can enter the view next.

use num_traits::Float;

use crate::depth_order::Line;

const NONE: u32 = u32::MAX;

/// The tournament tree (see the module docs). Node 1 is the root, node `leaves + i` the leaf
/// of list position `i`.
#[derive(Clone, Debug)]
pub(crate) struct Tournament<F> {
    leaves: usize,
    /// Winner (list position) of each node's subtree, `NONE` if empty.
    win: Vec<u32>,
    /// The other child's winner at internal nodes where both children are non-empty.
    lose: Vec<u32>,
    /// When `lose` overtakes `win` (infinity if never).
    cert: Vec<F>,
    /// Whether `cert` has been nudged to where the exact order has flipped.
    exact: Vec<bool>,
    /// Earliest certificate in the node's subtree.
    next: Vec<F>,
    len: usize,
}

impl<F> Tournament<F> {
    /// An empty tournament over no positions.
    pub fn new() -> Self {
        Self {
            leaves: 0,
            win: Vec::new(),
            lose: Vec::new(),
            cert: Vec::new(),
            exact: Vec::new(),
            next: Vec::new(),
            len: 0,
        }
    }
}

impl<F: Float> Tournament<F> {
    /// An empty tournament over list positions `0..n`.
    pub fn reset(&mut self, n: usize) {
        self.leaves = n.max(1).next_power_of_two();
        let nodes = 2 * self.leaves;
        for v in [&mut self.win, &mut self.lose] {
            v.clear();
            v.resize(nodes, NONE);
        }
        for v in [&mut self.cert, &mut self.next] {
            v.clear();
            v.resize(nodes, F::infinity());
        }
        self.exact.clear();
        self.exact.resize(nodes, false);
        self.len = 0;
    }

    /// Number of intervals in the set.
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.len
    }

    /// The nearest interval of the set just after the time of the last update.
    pub fn min(&self) -> Option<usize> {
        self.win
            .get(1)
            .copied()
            .filter(|&w| w != NONE)
            .map(|w| w as usize)
    }

    /// Adds list position `i` at time `t` (every certificate up to `t` processed).
    pub fn insert(&mut self, i: usize, t: F, lines: &[Line<F>]) {
        self.set_leaf(i, i as u32, t, lines);
    }

    /// Removes list position `i` at time `t`.
    pub fn remove(&mut self, i: usize, t: F, lines: &[Line<F>]) {
        self.set_leaf(i, NONE, t, lines);
    }

    fn set_leaf(&mut self, i: usize, value: u32, t: F, lines: &[Line<F>]) {
        let leaf = self.leaves + i;
        if let Some(w) = self.win.get_mut(leaf) {
            let was = *w;
            *w = value;
            match (was == NONE, value == NONE) {
                (true, false) => self.len += 1,
                (false, true) => self.len -= 1,
                _ => {}
            }
            self.update_path(leaf / 2, t, lines, false);
        }
    }

    /// Earliest pending certificate (its raw estimate until it has been nudged).
    pub fn next_time(&self) -> F {
        self.next.get(1).copied().unwrap_or_else(F::infinity)
    }

    /// Processes the earliest certificate if it fails before `limit` (or at `limit` when
    /// `inclusive`), returning its time; `None` if there is none that early.
    pub fn pop_due(&mut self, limit: F, inclusive: bool, lines: &[Line<F>]) -> Option<F> {
        loop {
            let tau = self.next_time();
            if !(tau < limit || (inclusive && tau == limit)) {
                return None;
            }
            let v = self.node_of_next();
            let (Some(&w), Some(&l)) = (self.win.get(v), self.lose.get(v)) else {
                return None;
            };
            let (Some(a), Some(b)) = (lines.get(w as usize), lines.get(l as usize)) else {
                return None;
            };
            if !self.exact[v] {
                // Only the earliest certificate pays for the exact check.
                self.cert[v] = a.nudge_past_crossing(b, tau);
                self.exact[v] = true;
                self.refresh_next(v);
                continue;
            }
            self.update_path(v, tau, lines, true);
            return Some(tau);
        }
    }

    /// The internal node whose certificate is the subtree minimum at the root.
    fn node_of_next(&self) -> usize {
        let mut v = 1;
        while v < self.leaves {
            let target = self.next[v];
            if self.cert[v] == target {
                return v;
            }
            v = if self.next[2 * v] == target {
                2 * v
            } else {
                2 * v + 1
            };
        }
        v
    }

    /// Recomputes `next` from `v` to the root after a certificate time changed.
    fn refresh_next(&mut self, mut v: usize) {
        while v >= 1 {
            self.next[v] = self.cert[v].min(self.next[2 * v]).min(self.next[2 * v + 1]);
            v /= 2;
        }
    }

    /// Recomputes winners and certificates from internal node `v` to the root at time `t`.
    /// `failed`: `v`'s certificate has failed, so its pair must swap (or be dropped if the
    /// exact order did not flip after all).
    fn update_path(&mut self, mut v: usize, t: F, lines: &[Line<F>], mut failed: bool) {
        while v >= 1 {
            let (a, b) = (self.win[2 * v], self.win[2 * v + 1]);
            let (w, l) = match (a == NONE, b == NONE) {
                (true, _) => (b, NONE),
                (_, true) => (a, NONE),
                _ => {
                    let (la, lb) = (&lines[a as usize], &lines[b as usize]);
                    if la.nearer_after(lb, t) {
                        (a, b)
                    } else {
                        (b, a)
                    }
                }
            };
            let old = (self.win[v], self.lose[v], self.next[v]);
            if (w, l) != (old.0, old.1) {
                self.win[v] = w;
                self.lose[v] = l;
                self.exact[v] = false;
                self.cert[v] = if l == NONE {
                    F::infinity()
                } else {
                    lines[w as usize]
                        .crossing_estimate(&lines[l as usize])
                        .unwrap_or_else(F::infinity)
                };
            } else if failed {
                // The exact order did not flip where the nudge said it would: drop it
                // rather than fail again at the same time.
                self.cert[v] = F::infinity();
            }
            failed = false;
            self.next[v] = self.cert[v].min(self.next[2 * v]).min(self.next[2 * v + 1]);
            if (self.win[v], self.lose[v], self.next[v]) == old {
                // Nothing above changes.
                return;
            }
            v /= 2;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(c: f64, k: f64, index: usize) -> Line<f64> {
        Line {
            c,
            k,
            te: 1.0,
            index,
        }
    }

    /// The tournament minimum equals a linear scan at every certificate time and between.
    #[test]
    fn minimum_follows_the_lower_envelope() {
        let mut x = 12345u64;
        let mut rnd = || {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        for n in [1, 2, 3, 7, 16, 33] {
            let lines: Vec<_> = (0..n).map(|i| line(rnd(), 2.0 * rnd() - 1.0, i)).collect();
            let mut t = Tournament::new();
            t.reset(n);
            for i in 0..n {
                t.insert(i, 0.0, &lines);
            }
            let scan = |now: f64, set: &[bool]| {
                (0..n).filter(|&i| set[i]).reduce(|a, b| {
                    if lines[a].nearer_after(&lines[b], now) {
                        a
                    } else {
                        b
                    }
                })
            };
            let mut set = vec![true; n];
            let mut now = 0.0;
            let mut events = 0;
            while let Some(tau) = t.pop_due(1.0, false, &lines) {
                assert!(tau >= now);
                now = tau;
                events += 1;
                assert_eq!(t.min(), scan(now, &set), "n {n} at {now}");
                if events % 3 == 0 {
                    let i = (rnd() * n as f64) as usize;
                    if set[i] {
                        t.remove(i, now, &lines);
                    } else {
                        t.insert(i, now, &lines);
                    }
                    set[i] = !set[i];
                    assert_eq!(t.len(), set.iter().filter(|&&s| s).count());
                    assert_eq!(t.min(), scan(now, &set));
                }
            }
            assert_eq!(t.min(), scan(now, &set));
        }
    }
}
