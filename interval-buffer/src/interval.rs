//! The time interval of Gribel 2010, Eq. 16.

use num_traits::Float;

use crate::Payload;

/// A span of shutter time during which one surface covers a sample, with a linear depth.
///
/// Gribel 2010, Eq. 16: start time `ts`, end time `te`, depth `z` at `ts`, depth slope `k`
/// (depth units per unit of normalised shutter time) and a payload (colour, or texture
/// coordinates and material). Depth at time t is `z + k (t - ts)`; smaller is nearer.
///
/// Times are in the normalised shutter interval [0, 1]. A valid interval has
/// `ts <= te`; zero-length intervals (`ts == te`) are allowed and cover no time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval<F, P> {
    /// Time at which the interval begins, t_s.
    pub ts: F,
    /// Time at which the interval ends, t_e (>= `ts`).
    pub te: F,
    /// Depth at `ts`.
    pub z: F,
    /// Slope of the linear depth function, dz/dt.
    pub k: F,
    /// What the surface shows during the interval.
    pub payload: P,
}

impl<F: Float, P> Interval<F, P> {
    /// Creates an interval from its Eq. 16 parameters.
    pub fn new(ts: F, te: F, z: F, k: F, payload: P) -> Self {
        Self {
            ts,
            te,
            z,
            k,
            payload,
        }
    }

    /// Length of the interval in shutter time, `te - ts`.
    pub fn duration(&self) -> F {
        self.te - self.ts
    }

    /// Linear depth at time `t`: `z + k (t - ts)` (Gribel 2010, Eq. 16).
    pub fn depth_at(&self, t: F) -> F {
        self.z + self.k * (t - self.ts)
    }

    /// Depth at the end of the interval, z̄ = z + k (te - ts) (Gribel 2010, Eq. 19).
    pub fn end_depth(&self) -> F {
        self.depth_at(self.te)
    }

    /// Whether the interval covers time `t` (closed at both ends).
    pub fn contains_time(&self, t: F) -> bool {
        self.ts <= t && t <= self.te
    }

    /// Whether every parameter is finite and `ts <= te`.
    pub fn is_valid(&self) -> bool {
        self.ts.is_finite()
            && self.te.is_finite()
            && self.z.is_finite()
            && self.k.is_finite()
            && self.ts <= self.te
    }

    /// The same interval with another payload.
    pub fn with_payload<Q>(self, payload: Q) -> Interval<F, Q> {
        Interval {
            ts: self.ts,
            te: self.te,
            z: self.z,
            k: self.k,
            payload,
        }
    }
}

impl<F: Float, P: Payload<F>> Interval<F, P> {
    /// The same surface over the sub-span `[ts, te]` (clamped to this interval's span):
    /// depth re-based at the new start, payload restricted with [`Payload::restrict`].
    ///
    /// This is the time clipping of Gribel 2010, Fig. 7 (second from bottom).
    pub fn clipped(&self, ts: F, te: F) -> Self {
        let ts = ts.max(self.ts).min(self.te);
        let te = te.min(self.te).max(ts);
        let len = self.duration();
        let (s0, s1) = if len > F::zero() {
            ((ts - self.ts) / len, (te - self.ts) / len)
        } else {
            (F::zero(), F::one())
        };
        Interval {
            ts,
            te,
            z: self.depth_at(ts),
            k: self.k,
            payload: self.payload.restrict(s0, s1),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_is_linear_from_start() {
        let iv = Interval::new(0.5_f64, 1.0, 3.0, 2.0, ());
        assert_eq!(iv.depth_at(0.5), 3.0);
        assert_eq!(iv.depth_at(0.75), 3.5);
        assert_eq!(iv.end_depth(), 4.0);
        assert_eq!(iv.duration(), 0.5);
    }

    #[test]
    fn validity_rejects_reversed_and_non_finite() {
        assert!(Interval::new(0.0_f32, 0.0, 1.0, 0.0, ()).is_valid());
        assert!(!Interval::new(0.6_f32, 0.5, 1.0, 0.0, ()).is_valid());
        assert!(!Interval::new(0.0_f32, 0.5, f32::NAN, 0.0, ()).is_valid());
        assert!(!Interval::new(0.0_f32, 0.5, 1.0, f32::INFINITY, ()).is_valid());
    }

    #[test]
    fn clipped_rebases_depth_and_clamps() {
        let iv = Interval::new(0.0_f64, 1.0, 2.0, 4.0, crate::Rgba::opaque(1.0, 0.0, 0.0));
        let c = iv.clipped(0.25, 0.5);
        assert_eq!((c.ts, c.te, c.z, c.k), (0.25, 0.5, 3.0, 4.0));
        let d = iv.clipped(-1.0, 2.0);
        assert_eq!((d.ts, d.te, d.z), (0.0, 1.0, 2.0));
    }

    #[test]
    fn contains_time_is_closed() {
        let iv = Interval::new(0.25_f64, 0.5, 0.0, 0.0, ());
        assert!(iv.contains_time(0.25) && iv.contains_time(0.5));
        assert!(!iv.contains_time(0.5 + 1e-12));
    }
}
