//! The colour at the end of a lit partition, kept for the next partition of the same
//! interval.
//!
//! The lit resolve integrates each partition of an interval's life with Simpson's rule
//! ([`super::lit`]), which shades the surface at both ends of the partition. Consecutive
//! partitions of one interval meet: the end of one is the start of the next. The colour
//! there is a pure function of the interval's payload, the instant and how the track finds
//! the triangle's corners (`CornersSource`), so each thread keeps the last `KEPT` ends it
//! shaded (one per interval a partition shades: a transparent surface and the ones behind
//! it), keyed by all of these bit for bit, and the next partition takes them instead of
//! shading the surface again. A kept colour is therefore bit-identical to a fresh one.

use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::surface_track::CornersSource;

/// Every input of a lit colour evaluation but the instant, bit for bit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NodeKey {
    /// The shader that shades it ([`shader_id`]): its scene and settings.
    pub shader: u64,
    /// The triangle's index in the scene.
    pub tri: u32,
    /// The interval's weights at its start and end, its start time and length (bits).
    pub track: [u64; 6],
    /// How the track finds the triangle's corners.
    pub corners: CornersSource,
}

/// A kept colour: its key, its instant (bits) and the colour.
#[derive(Debug, Clone, Copy)]
struct Node {
    key: NodeKey,
    t: u64,
    colour: [f64; 4],
}

/// How many partition ends a thread keeps.
pub(crate) const KEPT: usize = 8;

/// The last [`KEPT`] partition ends a thread shaded, and the slot the next one replaces.
#[derive(Debug, Clone, Copy)]
struct Kept {
    nodes: [Option<Node>; KEPT],
    next: usize,
}

thread_local! {
    /// The partition ends this thread keeps.
    static KEPT_NODES: RefCell<Kept> = const {
        RefCell::new(Kept {
            nodes: [None; KEPT],
            next: 0,
        })
    };
}

/// Identifiers of shaders, so that a kept colour never outlives the scene it was shaded in.
static NEXT_SHADER: AtomicU64 = AtomicU64::new(0);

/// A new shader identifier, distinct from every earlier one in the process.
pub(crate) fn shader_id() -> u64 {
    NEXT_SHADER.fetch_add(1, Ordering::Relaxed)
}

/// The colour of `key` at instant `t`: one this thread kept when it is for the same key and
/// instant, else `shade(t)`.
#[inline]
pub(crate) fn start(key: &NodeKey, t: f64, shade: impl FnOnce(f64) -> [f64; 4]) -> [f64; 4] {
    let t_bits = t.to_bits();
    let kept = KEPT_NODES.with_borrow(|k| {
        k.nodes
            .iter()
            .flatten()
            .find(|n| n.t == t_bits && n.key == *key)
            .map(|n| n.colour)
    });
    kept.unwrap_or_else(|| shade(t))
}

/// Keeps `colour`, the colour of `key` at instant `t`, for a later [`start`] on this
/// thread, in place of the oldest kept one.
#[inline]
pub(crate) fn keep(key: NodeKey, t: f64, colour: [f64; 4]) {
    KEPT_NODES.with_borrow_mut(|k| {
        let slot = k.next % KEPT;
        k.nodes[slot] = Some(Node {
            key,
            t: t.to_bits(),
            colour,
        });
        k.next = (slot + 1) % KEPT;
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(shader: u64) -> NodeKey {
        NodeKey {
            shader,
            tri: 3,
            track: [1, 2, 3, 4, 5, 6],
            corners: CornersSource::Arc([7, 8]),
        }
    }

    #[test]
    fn a_kept_colour_serves_only_its_key_and_instant() {
        let k = key(shader_id());
        let fresh = |_: f64| [9.0; 4];
        keep(k, 0.25, [1.0, 2.0, 3.0, 4.0]);
        assert_eq!(start(&k, 0.25, fresh), [1.0, 2.0, 3.0, 4.0]);
        // Another instant (also -0.0 against +0.0), shader, triangle, weight or corner source
        // shades afresh.
        assert_eq!(start(&k, 0.5, fresh), [9.0; 4]);
        keep(k, 0.0, [1.0; 4]);
        assert_eq!(start(&k, -0.0, fresh), [9.0; 4]);
        let others = [
            key(shader_id()),
            NodeKey { tri: 4, ..k },
            NodeKey {
                track: [1, 2, 3, 4, 5, 7],
                ..k
            },
            NodeKey {
                corners: CornersSource::Path,
                ..k
            },
            NodeKey {
                corners: CornersSource::Arc([7, 9]),
                ..k
            },
        ];
        for other in others {
            assert_eq!(start(&other, 0.0, fresh), [9.0; 4], "{other:?}");
        }
        assert_eq!(start(&k, 0.0, fresh), [1.0; 4]);
    }

    #[test]
    fn the_oldest_kept_colour_gives_way() {
        let k = key(shader_id());
        let fresh = |_: f64| [9.0; 4];
        for i in 0..=KEPT {
            keep(NodeKey { tri: i as u32, ..k }, 0.5, [i as f64; 4]);
        }
        assert_eq!(start(&NodeKey { tri: 0, ..k }, 0.5, fresh), [9.0; 4]);
        for i in 1..=KEPT {
            let want = [i as f64; 4];
            assert_eq!(start(&NodeKey { tri: i as u32, ..k }, 0.5, fresh), want);
        }
    }

    #[test]
    fn each_thread_keeps_its_own() {
        let k = key(shader_id());
        keep(k, 0.5, [1.0; 4]);
        let other = std::thread::spawn(move || start(&k, 0.5, |_| [2.0; 4]))
            .join()
            .unwrap();
        assert_eq!(other, [2.0; 4]);
        assert_eq!(start(&k, 0.5, |_| [2.0; 4]), [1.0; 4]);
    }
}
