//! The compact storage form of a flat-colour interval (Gribel 2010 §6: 12 bytes).

use half::f16;
use num_traits::Float;

use crate::{Error, Interval, Rgba};

/// An unsigned fixed-point time in [0, 1]: `t = q / MAX`.
pub trait QuantisedTime: Copy + core::fmt::Debug + PartialEq + Eq + PartialOrd + Ord {
    /// The code of t = 1.
    const MAX: u32;
    /// The code from a value already in `0..=MAX`.
    fn from_code(code: u32) -> Self;
    /// The code as `u32`.
    fn code(self) -> u32;
}

impl QuantisedTime for u8 {
    const MAX: u32 = u8::MAX as u32;
    fn from_code(code: u32) -> Self {
        code.min(<Self as QuantisedTime>::MAX) as u8
    }
    fn code(self) -> u32 {
        u32::from(self)
    }
}

impl QuantisedTime for u16 {
    const MAX: u32 = u16::MAX as u32;
    fn from_code(code: u32) -> Self {
        code.min(<Self as QuantisedTime>::MAX) as u16
    }
    fn code(self) -> u32 {
        u32::from(self)
    }
}

/// A flat-colour interval in compact storage: fixed-point times, f32 depth at the
/// (quantised) start, f16 slope and 8-bit linear RGBA.
///
/// With `T = u8` it is Gribel 2010 §6's 12-byte interval (one byte per time, 16-bit float
/// slope, 32-bit depth, 32-bit RGBA); with `T = u16` it is 16 bytes and its times are 257
/// times finer. Conversion from the full form re-bases the depth at the rounded start
/// time, saturates the slope at the f16 range (±65504) and the depth at the f32 range, and
/// clamps colour to [0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompactInterval<T> {
    /// Start time code, `ts = code / T::MAX`.
    pub ts: T,
    /// End time code.
    pub te: T,
    /// Depth slope dz/dt in half precision.
    pub k: f16,
    /// Depth at the quantised start time.
    pub z: f32,
    /// Linear RGBA, 8 bits per channel (`c = code / 255`).
    pub rgba: [u8; 4],
}

/// Gribel's 12-byte interval.
pub type CompactInterval8 = CompactInterval<u8>;
/// The 16-byte interval with 16-bit times.
pub type CompactInterval16 = CompactInterval<u16>;

fn quantise_time<F: Float, T: QuantisedTime>(t: F) -> T {
    let max = F::from(T::MAX).unwrap_or_else(F::one);
    let code = (t * max).round().to_u32().unwrap_or(0);
    T::from_code(code)
}

fn unit_code<F: Float>(c: F) -> u8 {
    let v = (c.max(F::zero()).min(F::one()) * F::from(255.0).unwrap_or_else(F::one)).round();
    v.to_u8().unwrap_or(0)
}

impl<T: QuantisedTime> CompactInterval<T> {
    /// Bytes per compact interval.
    pub const BYTES: usize = size_of::<Self>();

    /// The compact form of `iv`.
    ///
    /// # Errors
    /// [`Error::InvalidInterval`] for non-finite parameters or `ts > te`;
    /// [`Error::TimeOutOfRange`] when a time lies outside [0, 1].
    pub fn from_interval<F: Float>(iv: &Interval<F, Rgba<F>>) -> Result<Self, Error> {
        if !iv.is_valid() {
            return Err(Error::InvalidInterval);
        }
        let (zero, one) = (F::zero(), F::one());
        if iv.ts < zero || iv.te > one {
            return Err(Error::TimeOutOfRange);
        }
        let ts: T = quantise_time(iv.ts);
        let te: T = quantise_time(iv.te);
        let max = F::from(T::MAX).unwrap_or_else(F::one);
        let tq = F::from(ts.code()).unwrap_or_else(F::zero) / max;
        let z = iv.depth_at(tq).to_f64().unwrap_or(0.0);
        let z = z.clamp(f64::from(f32::MIN), f64::from(f32::MAX)) as f32;
        let k = iv.k.to_f64().unwrap_or(0.0).clamp(-65504.0, 65504.0);
        let c = iv.payload;
        Ok(CompactInterval {
            ts,
            te,
            k: f16::from_f64(k),
            z,
            rgba: [
                unit_code(c.r),
                unit_code(c.g),
                unit_code(c.b),
                unit_code(c.a),
            ],
        })
    }

    /// The full-precision form.
    pub fn to_interval<F: Float>(&self) -> Interval<F, Rgba<F>> {
        let max = F::from(T::MAX).unwrap_or_else(F::one);
        let time = |q: T| F::from(q.code()).unwrap_or_else(F::zero) / max;
        let c255 = F::from(255.0).unwrap_or_else(F::one);
        let col = |b: u8| F::from(b).unwrap_or_else(F::zero) / c255;
        Interval {
            ts: time(self.ts),
            te: time(self.te),
            z: F::from(self.z).unwrap_or_else(F::zero),
            k: F::from(self.k.to_f32()).unwrap_or_else(F::zero),
            payload: Rgba::new(
                col(self.rgba[0]),
                col(self.rgba[1]),
                col(self.rgba[2]),
                col(self.rgba[3]),
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_match_gribel() {
        assert_eq!(CompactInterval8::BYTES, 12);
        assert_eq!(CompactInterval16::BYTES, 16);
    }

    #[test]
    fn round_trip_within_quantisation() {
        let iv = Interval::new(0.3_f64, 0.71, 2.5, -1.25, Rgba::new(0.2, 0.4, 0.6, 1.0));
        let c = CompactInterval16::from_interval(&iv).expect("compact");
        let back: Interval<f64, Rgba<f64>> = c.to_interval();
        assert!((back.ts - 0.3).abs() <= 0.5 / 65535.0 + 1e-12);
        assert!((back.te - 0.71).abs() <= 0.5 / 65535.0 + 1e-12);
        assert_eq!(back.k, -1.25);
        // Depth is re-based at the quantised start: same depth function.
        assert!((back.depth_at(0.5) - iv.depth_at(0.5)).abs() < 1e-6);
        assert!((back.payload.g - 0.4).abs() <= 0.5 / 255.0);
        let c8 = CompactInterval8::from_interval(&iv).expect("compact");
        assert_eq!((c8.ts, c8.te), (77, 181));
    }

    #[test]
    fn rejects_out_of_range_and_saturates_slope() {
        let bad = Interval::new(-0.1_f32, 0.5, 1.0, 0.0, Rgba::opaque(1.0, 1.0, 1.0));
        assert_eq!(
            CompactInterval8::from_interval(&bad),
            Err(Error::TimeOutOfRange)
        );
        let steep = Interval::new(0.0_f32, 0.5, 1.0, 1e9, Rgba::opaque(1.0, 1.0, 1.0));
        let c = CompactInterval8::from_interval(&steep).expect("compact");
        assert_eq!(c.k.to_f32(), 65504.0);
    }
}
