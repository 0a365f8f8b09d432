//! The colours this thread computed last, kept for shading that asks for the same colour
//! again, in two places:
//!
//! - Lit partitions: the sweep shades a surface over consecutive partitions, each starting
//!   where the one before ended (Gribel 2010 §5.1), so the first sample adaptive Simpson
//!   takes of a partition is often the last one it took of the partition before, of the
//!   same interval or of the next piece of the same span.
//! - Static textured surfaces: a surface whose UV does not change over its interval (a
//!   static backdrop) shows one texture tap at the same UV in every partition it is seen
//!   in, for instance between the moving objects that pass in front of it.
//!
//! A colour is keyed by everything it is a function of, bit for bit: for a lit sample the
//! shader (its scene and lights), the triangle, the instant, the barycentric weights and
//! which function of time the corners follow
//! ([`crate::surface_track::SurfaceTrack::corners_key`]); for a texture tap the shader, the
//! material and the UV. A reused colour is the colour computing it again would give, so
//! images do not change, whichever thread shaded what before.

use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, Ordering};

/// Samples remembered per thread: the layers of a partition that the transparent sweep
/// shades front to back (a cloth fold over a ball takes three).
const SLOTS: usize = 4;

/// What the colour of a lit surface point is a function of (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct SampleKey([u64; 6]);

impl SampleKey {
    /// The key of the colour `shader` (an [`EndSamples::shader_id`]) gives triangle `tri`
    /// at instant `t`, weights `bary` of corners 1 and 2, corners following `corners`.
    pub(crate) fn new(shader: u64, tri: u32, t: f64, bary: [f64; 2], corners: u64) -> Self {
        SampleKey([
            shader,
            u64::from(tri),
            t.to_bits(),
            bary[0].to_bits(),
            bary[1].to_bits(),
            corners,
        ])
    }

    /// The key of the texture tap `shader` (an [`EndSamples::shader_id`] of a shader that
    /// keeps no lit samples) takes of `material` at `uv`.
    pub(crate) fn tap(shader: u64, material: u32, uv: [f64; 2]) -> Self {
        SampleKey([
            shader,
            u64::from(material),
            uv[0].to_bits(),
            uv[1].to_bits(),
            0,
            0,
        ])
    }
}

/// This thread's samples, replaced round robin.
struct Slots {
    slots: [([u64; 6], [f64; 4]); SLOTS],
    next: usize,
}

thread_local! {
    static SAMPLES: RefCell<Slots> = const {
        RefCell::new(Slots {
            // No shader has id u64::MAX (see `shader_id`), so empty slots never match.
            slots: [([u64::MAX; 6], [0.0; 4]); SLOTS],
            next: 0,
        })
    };
}

/// The source of [`EndSamples::shader_id`].
static SHADERS: AtomicU64 = AtomicU64::new(0);

/// Access to this thread's remembered samples.
pub(crate) struct EndSamples;

impl EndSamples {
    /// A number no other shader of this process has (below `u64::MAX`): part of every
    /// key, so that a thread shading one scene after another never reuses a colour of the
    /// other.
    pub(crate) fn shader_id() -> u64 {
        SHADERS.fetch_add(1, Ordering::Relaxed).min(u64::MAX - 1)
    }

    /// The colour remembered for `key`, if any.
    #[inline]
    pub(crate) fn find(key: &SampleKey) -> Option<[f64; 4]> {
        let key = &key.0;
        SAMPLES.with_borrow(|s| {
            s.slots
                .iter()
                // The third word first (the instant of a lit sample, the u of a tap): it
                // settles almost every miss. The whole key is then compared word by word
                // without branches (`==` on the arrays compiles to a call to `memcmp`).
                .find(|(k, _)| {
                    k[2] == key[2] && k.iter().zip(key).fold(0, |d, (a, b)| d | (a ^ b)) == 0
                })
                .map(|&(_, colour)| colour)
        })
    }

    /// Remembers `colour` for `key`, in place of the slot filled longest ago.
    #[inline]
    pub(crate) fn keep(key: &SampleKey, colour: [f64; 4]) {
        SAMPLES.with_borrow_mut(|s| {
            let i = s.next;
            s.next = (i + 1) % SLOTS;
            s.slots[i] = (key.0, colour);
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(tri: u32) -> SampleKey {
        SampleKey::new(7, tri, 0.5, [0.1, 0.2], u64::MAX)
    }

    #[test]
    fn keeps_the_last_samples() {
        // Nothing is remembered before a sample is kept; a fifth sample takes the slot
        // filled first.
        assert_eq!(EndSamples::find(&key(0)), None);
        for tri in 0..SLOTS as u32 {
            EndSamples::keep(&key(tri), [f64::from(tri); 4]);
        }
        EndSamples::keep(&key(9), [9.0; 4]);
        let found: Vec<_> = [0, 1, 2, 3, 9]
            .map(|tri| EndSamples::find(&key(tri)).map(|c| c[0]))
            .into();
        assert_eq!(found, [None, Some(1.0), Some(2.0), Some(3.0), Some(9.0)]);
        // The key holds every input's bits: another shader, instant, weight (or zero's
        // sign) or corner function misses.
        for other in [
            SampleKey::new(8, 1, 0.5, [0.1, 0.2], u64::MAX),
            SampleKey::new(7, 1, 0.25, [0.1, 0.2], u64::MAX),
            SampleKey::new(7, 1, 0.5, [0.1, 0.3], u64::MAX),
            SampleKey::new(7, 1, 0.5, [0.1, 0.2], 0),
        ] {
            assert!(EndSamples::find(&other).is_none(), "{other:?}");
        }
        EndSamples::keep(&SampleKey::new(7, 1, 0.5, [0.0, 0.2], 0), [1.0; 4]);
        assert!(EndSamples::find(&SampleKey::new(7, 1, 0.5, [-0.0, 0.2], 0)).is_none());
        // A tap's key holds its material and both UV coordinates.
        EndSamples::keep(&SampleKey::tap(7, 2, [0.25, 0.5]), [2.0; 4]);
        assert_eq!(
            EndSamples::find(&SampleKey::tap(7, 2, [0.25, 0.5])),
            Some([2.0; 4])
        );
        for other in [
            SampleKey::tap(8, 2, [0.25, 0.5]),
            SampleKey::tap(7, 3, [0.25, 0.5]),
            SampleKey::tap(7, 2, [0.5, 0.5]),
            SampleKey::tap(7, 2, [0.25, 0.25]),
        ] {
            assert!(EndSamples::find(&other).is_none(), "{other:?}");
        }
        assert_ne!(EndSamples::shader_id(), EndSamples::shader_id());
    }
}
