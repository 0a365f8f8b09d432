//! The active list without intersection handling: intervals in the depth rank they got
//! when they became active, as a treap (a randomized balanced binary search tree; Seidel &
//! Aragon 1996) so that insertion, removal and finding the front cost O(log m) for m
//! active intervals, and walking front to back costs O(1) amortized per layer.
//!
//! Without intersection handling an interval keeps its rank for its whole life (Rønnow
//! 2021, Fig. 11, left), so the order is fixed by the insertions: a new interval is placed
//! by a binary search (a descent of the tree) comparing its depth just after its start
//! time with the intervals met on the way. Nodes are the pixel's list positions, so no
//! allocation happens per insertion; the heap priorities are a fixed hash of the position.
//! The in-order sequence is also threaded as a doubly linked list (rotations do not change
//! it), so the front and the walk front to back are pointer loads.

const NONE: u32 = u32::MAX;

/// The treap over list positions `0..n` (see the module docs).
#[derive(Clone, Debug, Default)]
pub(crate) struct RankList {
    left: Vec<u32>,
    right: Vec<u32>,
    parent: Vec<u32>,
    /// In-order neighbours.
    prev: Vec<u32>,
    next: Vec<u32>,
    root: u32,
    head: u32,
}

/// Heap priority of a node: a fixed mix of its position (splitmix32-style finaliser).
fn priority(i: u32) -> u32 {
    let mut x = i.wrapping_add(0x9e37_79b9);
    x = (x ^ (x >> 16)).wrapping_mul(0x85eb_ca6b);
    x = (x ^ (x >> 13)).wrapping_mul(0xc2b2_ae35);
    x ^ (x >> 16)
}

impl RankList {
    /// An empty list over list positions `0..n`.
    pub fn reset(&mut self, n: usize) {
        for v in [
            &mut self.left,
            &mut self.right,
            &mut self.parent,
            &mut self.prev,
            &mut self.next,
        ] {
            v.clear();
            v.resize(n, NONE);
        }
        self.root = NONE;
        self.head = NONE;
    }

    /// Inserts `i` (not in the list) before the first element `e`, in a binary search,
    /// for which `before(e)` holds.
    pub fn insert(&mut self, i: usize, mut before: impl FnMut(usize) -> bool) {
        let id = i as u32;
        self.left[i] = NONE;
        self.right[i] = NONE;
        if self.root == NONE {
            self.root = id;
            self.head = id;
            self.parent[i] = NONE;
            self.prev[i] = NONE;
            self.next[i] = NONE;
            return;
        }
        let mut x = self.root;
        let (prev, next) = loop {
            let xi = x as usize;
            if before(xi) {
                if self.left[xi] == NONE {
                    self.left[xi] = id;
                    break (self.prev[xi], x);
                }
                x = self.left[xi];
            } else {
                if self.right[xi] == NONE {
                    self.right[xi] = id;
                    break (x, self.next[xi]);
                }
                x = self.right[xi];
            }
        };
        self.prev[i] = prev;
        self.next[i] = next;
        if prev == NONE {
            self.head = id;
        } else {
            self.next[prev as usize] = id;
        }
        if next != NONE {
            self.prev[next as usize] = id;
        }
        self.parent[i] = x;
        while self.parent[i] != NONE && priority(id) > priority(self.parent[i]) {
            self.rotate_up(id);
        }
    }

    /// Removes `i` (in the list).
    pub fn remove(&mut self, i: usize) {
        let id = i as u32;
        let (prev, next) = (self.prev[i], self.next[i]);
        if prev == NONE {
            self.head = next;
        } else {
            self.next[prev as usize] = next;
        }
        if next != NONE {
            self.prev[next as usize] = prev;
        }
        loop {
            let (l, r) = (self.left[i], self.right[i]);
            if l == NONE || r == NONE {
                break;
            }
            self.rotate_up(if priority(l) > priority(r) { l } else { r });
        }
        let child = if self.left[i] == NONE {
            self.right[i]
        } else {
            self.left[i]
        };
        let p = self.parent[i];
        if child != NONE {
            self.parent[child as usize] = p;
        }
        if p == NONE {
            self.root = child;
        } else if self.left[p as usize] == id {
            self.left[p as usize] = child;
        } else {
            self.right[p as usize] = child;
        }
    }

    /// The front of the list.
    pub fn first(&self) -> Option<usize> {
        (self.head != NONE).then_some(self.head as usize)
    }

    /// The element after `i`.
    pub fn next(&self, i: usize) -> Option<usize> {
        self.next
            .get(i)
            .copied()
            .filter(|&x| x != NONE)
            .map(|x| x as usize)
    }

    /// Front to back.
    pub fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        std::iter::successors(self.first(), |&i| self.next(i))
    }

    /// Rotates `x` above its parent, keeping the in-order sequence.
    fn rotate_up(&mut self, x: u32) {
        let xi = x as usize;
        let p = self.parent[xi];
        let pi = p as usize;
        let g = self.parent[pi];
        if self.left[pi] == x {
            let b = self.right[xi];
            self.left[pi] = b;
            if b != NONE {
                self.parent[b as usize] = p;
            }
            self.right[xi] = p;
        } else {
            let b = self.left[xi];
            self.right[pi] = b;
            if b != NONE {
                self.parent[b as usize] = p;
            }
            self.left[xi] = p;
        }
        self.parent[pi] = x;
        self.parent[xi] = g;
        if g == NONE {
            self.root = x;
        } else if self.left[g as usize] == p {
            self.left[g as usize] = x;
        } else {
            self.right[g as usize] = x;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn in_order(l: &RankList, x: u32, out: &mut Vec<usize>) {
        if x != NONE {
            in_order(l, l.left[x as usize], out);
            out.push(x as usize);
            in_order(l, l.right[x as usize], out);
        }
    }

    /// Against a Vec with `partition_point` insertion and `retain` removal, for a fixed
    /// total order (keys), under random insertions and removals.
    #[test]
    fn matches_a_sorted_vec() {
        let mut x = 99u64;
        let mut rnd = |m: u64| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 33) % m
        };
        for n in [1usize, 2, 5, 64, 300] {
            let keys: Vec<u64> = (0..n).map(|_| rnd(50)).collect();
            let mut list = RankList::default();
            list.reset(n);
            let mut reference: Vec<usize> = Vec::new();
            let mut present = vec![false; n];
            for _ in 0..4 * n {
                let i = rnd(n as u64) as usize;
                if present[i] {
                    list.remove(i);
                    reference.retain(|&e| e != i);
                } else {
                    let before = |e: usize| keys[i] < keys[e];
                    list.insert(i, before);
                    let at = reference.partition_point(|&e| !before(e));
                    reference.insert(at, i);
                }
                present[i] = !present[i];
                let got: Vec<usize> = list.iter().collect();
                // The threaded list is the in-order walk of the tree.
                let mut walk = Vec::new();
                in_order(&list, list.root, &mut walk);
                assert_eq!(walk, got);
                let want_keys: Vec<u64> = reference.iter().map(|&e| keys[e]).collect();
                let got_keys: Vec<u64> = got.iter().map(|&e| keys[e]).collect();
                assert_eq!(got_keys, want_keys);
                assert_eq!(got.len(), reference.len());
                assert_eq!(list.first(), got.first().copied());
            }
        }
    }
}
