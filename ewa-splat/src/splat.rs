//! Surface splats with their motion over the exposure (Heinzle 2010, §3.3, §4, §5.5).

use glam::DVec3;

/// A splat's geometry at one instant: centre and the two tangent axes a1, a2 of its
/// elliptical Gaussian (the axes reach the cut-off, value `exp(-δ)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplatKey {
    /// Centre in world space.
    pub centre: DVec3,
    /// First tangent axis a1.
    pub axis_u: DVec3,
    /// Second tangent axis a2.
    pub axis_v: DVec3,
}

impl SplatKey {
    /// A circular splat of the given radius around `normal` (any orthonormal tangent pair).
    pub fn disc(centre: DVec3, normal: DVec3, radius: f64) -> Self {
        let n = normal.try_normalize().unwrap_or(DVec3::Z);
        let (u, v) = n.any_orthonormal_pair();
        Self {
            centre,
            axis_u: u * radius,
            axis_v: v * radius,
        }
    }

    fn lerp(&self, o: &SplatKey, s: f64) -> SplatKey {
        SplatKey {
            centre: self.centre.lerp(o.centre, s),
            axis_u: self.axis_u.lerp(o.axis_u, s),
            axis_v: self.axis_v.lerp(o.axis_v, s),
        }
    }

    pub(crate) fn is_finite(&self) -> bool {
        self.centre.is_finite() && self.axis_u.is_finite() && self.axis_v.is_finite()
    }
}

/// A surface splat: its motion path as keys equally spaced over its span of the exposure
/// (one key: static; two: linear motion from the span's start to its end; more: a
/// piecewise-linear path resampled by the renderer's subframes, §5.5) and its colour
/// (linear RGB, straight alpha).
///
/// The span `[t0, t1]` is the part of the exposure t in \[0, 1\] the splat exists in:
/// \[0, 1\] for a splat over the whole exposure, or one piece of a longer path (a curved
/// path cut into straight pieces whose ends lie on it, each piece a splat over its own
/// span, so one pixel's fragments hold every piece). Kernels are built over the span's
/// intersection with each subframe and their fragments are clipped to the span.
#[derive(Clone, Debug, PartialEq)]
pub struct Splat {
    /// Keys at t = t0 + (t1 - t0) i / (len - 1); must not be empty.
    pub keys: Vec<SplatKey>,
    /// Linear RGBA with straight alpha.
    pub colour: [f32; 4],
    /// The part `[t0, t1]` of the exposure the splat exists in (0 <= t0 < t1 <= 1).
    pub span: [f64; 2],
}

impl Splat {
    /// A splat that does not move.
    pub fn fixed(key: SplatKey, colour: [f32; 4]) -> Self {
        Self {
            keys: vec![key],
            colour,
            span: [0.0, 1.0],
        }
    }

    /// A splat moving linearly from `open` (t = 0) to `close` (t = 1).
    pub fn linear(open: SplatKey, close: SplatKey, colour: [f32; 4]) -> Self {
        Self {
            keys: vec![open, close],
            colour,
            span: [0.0, 1.0],
        }
    }

    /// The same splat over the part `[t0, t1]` of the exposure only: its keys are then
    /// spaced over the span.
    pub fn over(self, span: [f64; 2]) -> Self {
        Self { span, ..self }
    }

    /// A circular splat translating by `motion` over the exposure.
    pub fn moving_disc(
        centre_open: DVec3,
        motion: DVec3,
        normal: DVec3,
        radius: f64,
        colour: [f32; 4],
    ) -> Self {
        let open = SplatKey::disc(centre_open, normal, radius);
        let close = SplatKey {
            centre: centre_open + motion,
            ..open
        };
        Self::linear(open, close, colour)
    }

    /// True when the span lies in \[0, 1\] and is not empty.
    pub(crate) fn span_is_valid(&self) -> bool {
        let [t0, t1] = self.span;
        (0.0..=1.0).contains(&t0) && (0.0..=1.0).contains(&t1) && t0 < t1
    }

    /// The splat's geometry at exposure time t (clamped to its span), interpolating the
    /// keys linearly. `None` when there are no keys.
    pub fn key_at(&self, t: f64) -> Option<SplatKey> {
        let n = self.keys.len();
        let first = self.keys.first()?;
        if n == 1 {
            return Some(*first);
        }
        let [t0, t1] = self.span;
        let u = if t0 == 0.0 && t1 == 1.0 {
            t
        } else {
            (t - t0) / (t1 - t0)
        };
        let x = u.clamp(0.0, 1.0) * (n - 1) as f64;
        let i = (x.floor() as usize).min(n - 2);
        let a = self.keys.get(i)?;
        let b = self.keys.get(i + 1)?;
        Some(a.lerp(b, x - i as f64))
    }
}
