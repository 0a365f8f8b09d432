//! What an interval carries besides time and depth, and how two of them merge.

use num_traits::Float;

/// The part of an interval that compression must be able to blend and compare.
///
/// Gribel 2010 merges the colours of two intervals by linear interpolation (Eq. 20) and
/// prefers to merge intervals of similar colour (the fifth term of the oracle, Eq. 19).
/// Any payload that supports both can live in an interval buffer.
pub trait Payload<F: Float>: Copy {
    /// Blend towards `other` by `alpha` in [0, 1]: `(1 - alpha) self + alpha other`
    /// (Gribel 2010, Eq. 20, last line).
    fn blend(&self, other: &Self, alpha: F) -> Self;

    /// A non-negative dissimilarity, zero for equal payloads (Gribel 2010, Eq. 19: the sum
    /// of absolute RGB differences for colours).
    fn distance(&self, other: &Self) -> F;

    /// Whether the surface hides everything behind it. The opaque insertion optimisations
    /// (Gribel 2010, Fig. 7, bottom) and the opaque resolve are only valid when it does.
    fn is_opaque(&self) -> bool;

    /// The payload of the same surface restricted to the part `[s0, s1]` (fractions of the
    /// interval's duration, `0 <= s0 <= s1 <= 1`) of its interval, used when the opaque
    /// insertion clips an occluded interval in time (Gribel 2010, Fig. 7, second from bottom).
    ///
    /// The default keeps the payload unchanged, which is exact for flat colours; payloads
    /// that vary over the interval (texture coordinates) override it.
    fn restrict(&self, s0: F, s1: F) -> Self {
        let _ = (s0, s1);
        *self
    }

    /// The coverage opacity (straight alpha) in [0, 1], read by the coverage-preserving
    /// merge ([`crate::Oracle::keep_coverage`]). The default is 1 (fully covering).
    fn coverage(&self) -> F {
        F::one()
    }

    /// The payload with coverage opacity `alpha`, set by the coverage-preserving merge.
    /// The default keeps the payload unchanged (no coverage to set).
    fn with_coverage(&self, alpha: F) -> Self {
        let _ = alpha;
        *self
    }
}

/// A flat linear-RGB colour with straight (not premultiplied) alpha.
///
/// The default is transparent black.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rgba<F> {
    /// Red, linear.
    pub r: F,
    /// Green, linear.
    pub g: F,
    /// Blue, linear.
    pub b: F,
    /// Coverage opacity in [0, 1]; 1 is opaque.
    pub a: F,
}

impl<F: Float> Rgba<F> {
    /// A colour from its four straight-alpha components.
    pub fn new(r: F, g: F, b: F, a: F) -> Self {
        Self { r, g, b, a }
    }

    /// An opaque colour.
    pub fn opaque(r: F, g: F, b: F) -> Self {
        Self::new(r, g, b, F::one())
    }

    /// The premultiplied components `[a r, a g, a b, a]`, as used inside blending.
    pub fn premultiplied(&self) -> [F; 4] {
        [self.a * self.r, self.a * self.g, self.a * self.b, self.a]
    }
}

impl<F: Float> Payload<F> for Rgba<F> {
    fn blend(&self, other: &Self, alpha: F) -> Self {
        let one = F::one();
        let mix = |a: F, b: F| (one - alpha) * a + alpha * b;
        Rgba::new(
            mix(self.r, other.r),
            mix(self.g, other.g),
            mix(self.b, other.b),
            mix(self.a, other.a),
        )
    }

    fn distance(&self, other: &Self) -> F {
        (self.r - other.r).abs() + (self.g - other.g).abs() + (self.b - other.b).abs()
    }

    fn is_opaque(&self) -> bool {
        self.a >= F::one()
    }

    fn coverage(&self) -> F {
        self.a
    }

    fn with_coverage(&self, alpha: F) -> Self {
        Rgba { a: alpha, ..*self }
    }
}

/// A textured surface sample: texture coordinates at the interval's start and end, a
/// material and the material's straight alpha (Rønnow 2021, Fig. 6, without the normal:
/// lit surfaces carry their own payload in the renderer). 24 bytes in f32.
///
/// The resolve interpolates `uv_start` → `uv_end` linearly over the interval's time and shades
/// each partition through the caller's texture lookup (Rønnow 2021, §4.3).
///
/// The default is all zeros (material 0, transparent).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Textured<F> {
    /// Texture coordinates at the interval's start time `ts`.
    pub uv_start: [F; 2],
    /// Texture coordinates at the interval's end time `te`.
    pub uv_end: [F; 2],
    /// Index of the material (texture and alpha) in the caller's material table.
    pub material: u32,
    /// Straight alpha of the material; 1 is opaque.
    pub alpha: F,
}

impl<F: Float> Payload<F> for Textured<F> {
    /// Linear blend of coordinates and alpha; the material of the heavier side
    /// (`alpha < 0.5` keeps `self`'s) since material ids cannot be interpolated.
    fn blend(&self, other: &Self, alpha: F) -> Self {
        let one = F::one();
        let mix = |a: F, b: F| (one - alpha) * a + alpha * b;
        let half = one / (one + one);
        Textured {
            uv_start: [
                mix(self.uv_start[0], other.uv_start[0]),
                mix(self.uv_start[1], other.uv_start[1]),
            ],
            uv_end: [
                mix(self.uv_end[0], other.uv_end[0]),
                mix(self.uv_end[1], other.uv_end[1]),
            ],
            material: if alpha < half {
                self.material
            } else {
                other.material
            },
            alpha: mix(self.alpha, other.alpha),
        }
    }

    /// L1 distance of the four texture coordinates, plus 1 when the materials differ.
    fn distance(&self, other: &Self) -> F {
        let d = (self.uv_start[0] - other.uv_start[0]).abs()
            + (self.uv_start[1] - other.uv_start[1]).abs()
            + (self.uv_end[0] - other.uv_end[0]).abs()
            + (self.uv_end[1] - other.uv_end[1]).abs();
        if self.material == other.material {
            d
        } else {
            d + F::one()
        }
    }

    fn is_opaque(&self) -> bool {
        self.alpha >= F::one()
    }

    /// Texture coordinates interpolated linearly to the new start and end; material and
    /// alpha are kept.
    fn restrict(&self, s0: F, s1: F) -> Self {
        let one = F::one();
        let at = |s: F, i: usize| (one - s) * self.uv_start[i] + s * self.uv_end[i];
        Textured {
            uv_start: [at(s0, 0), at(s0, 1)],
            uv_end: [at(s1, 0), at(s1, 1)],
            ..*self
        }
    }

    fn coverage(&self) -> F {
        self.alpha
    }

    fn with_coverage(&self, alpha: F) -> Self {
        Textured { alpha, ..*self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blend_endpoints_and_midpoint() {
        let a = Rgba::new(1.0_f64, 0.0, 0.0, 1.0);
        let b = Rgba::new(0.0_f64, 1.0, 0.0, 0.5);
        assert_eq!(a.blend(&b, 0.0), a);
        assert_eq!(a.blend(&b, 1.0), b);
        assert_eq!(a.blend(&b, 0.5), Rgba::new(0.5, 0.5, 0.0, 0.75));
    }

    #[test]
    fn distance_is_l1_over_rgb_only() {
        let a = Rgba::new(1.0_f32, 0.25, 0.0, 1.0);
        let b = Rgba::new(0.5_f32, 0.5, 0.5, 0.0);
        assert_eq!(a.distance(&b), 1.25);
        assert_eq!(a.distance(&a), 0.0);
    }

    #[test]
    fn textured_blend_keeps_heavier_material_and_lerps_uv() {
        let a = Textured {
            uv_start: [0.0_f64, 0.0],
            uv_end: [1.0, 0.0],
            material: 3,
            alpha: 1.0,
        };
        let b = Textured {
            uv_start: [1.0, 1.0],
            uv_end: [1.0, 1.0],
            material: 7,
            ..a
        };
        let m = a.blend(&b, 0.25);
        assert_eq!(m.material, 3);
        assert_eq!(m.uv_start, [0.25, 0.25]);
        assert_eq!(m.uv_end, [1.0, 0.25]);
        assert_eq!(a.blend(&b, 0.75).material, 7);
        assert_eq!(a.distance(&b), 1.0 + 1.0 + 0.0 + 1.0 + 1.0);
        assert_eq!(a.distance(&a), 0.0);
    }

    #[test]
    fn restrict_interpolates_uv_and_keeps_flat_colour() {
        let a = Textured {
            uv_start: [0.0_f64, 1.0],
            uv_end: [1.0, 0.0],
            material: 2,
            alpha: 1.0,
        };
        let r = a.restrict(0.25, 0.5);
        assert_eq!(r.uv_start, [0.25, 0.75]);
        assert_eq!(r.uv_end, [0.5, 0.5]);
        assert_eq!(r.material, 2);
        let c = Rgba::opaque(0.1_f32, 0.2, 0.3);
        assert_eq!(c.restrict(0.3, 0.4), c);
    }

    #[test]
    fn opacity_and_premultiplication() {
        assert!(Rgba::opaque(0.1_f64, 0.2, 0.3).is_opaque());
        let c = Rgba::new(1.0_f64, 0.5, 0.25, 0.5);
        assert!(!c.is_opaque());
        assert_eq!(c.premultiplied(), [0.5, 0.25, 0.125, 0.5]);
    }
}
