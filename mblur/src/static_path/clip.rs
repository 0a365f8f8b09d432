//! The near-plane clipper of the static path: a triangle at one instant cut to view depth
//! >= near, the kept polygon fanned into triangles.
//!
//! Depth is affine in the world position, and so are the 2DH coordinates (x, y, w) of a
//! point, so the cut point of an edge is found by interpolating its two 2DH corners linearly
//! to depth = near, and every per-corner attribute (barycentrics, UV) by the same
//! interpolation. The edge is always interpolated from its endpoints in a canonical order,
//! so that two triangles sharing an edge cut it at the identical point (no crack along the
//! near plane). Used by the static rasteriser ([`super::setup`]) and by the stochastic
//! method's static triangles.

use arrayvec::ArrayVec;
use glam::DVec2;

use crate::camera::Vertex2dh;

/// A per-corner attribute the clipper carries along: at a cut, `a + (b - a) s` for each
/// component, with `a` the canonical first endpoint's value.
pub trait ClipAttribute: Copy {
    /// The attribute a fraction `s` of the way from `self` to `other`.
    fn lerp_to(self, other: Self, s: f64) -> Self;
}

impl ClipAttribute for [f64; 3] {
    fn lerp_to(self, other: Self, s: f64) -> Self {
        std::array::from_fn(|k| self[k] + (other[k] - self[k]) * s)
    }
}

impl ClipAttribute for DVec2 {
    fn lerp_to(self, other: Self, s: f64) -> Self {
        self + (other - self) * s
    }
}

/// Two attributes clipped together, each as it would be alone.
impl<A: ClipAttribute, B: ClipAttribute> ClipAttribute for (A, B) {
    fn lerp_to(self, other: Self, s: f64) -> Self {
        (self.0.lerp_to(other.0, s), self.1.lerp_to(other.1, s))
    }
}

/// One corner: its 2DH vertex and its attribute.
pub type ClipCorner<A> = (Vertex2dh, A);

fn key(v: &Vertex2dh) -> [f64; 4] {
    [v.x, v.y, v.w, v.depth]
}

/// Intersection of edge (a, b) with depth = near, computed from the endpoints in a canonical
/// order so that a shared edge yields the identical point in both triangles.
fn cut<A: ClipAttribute>(a: &ClipCorner<A>, b: &ClipCorner<A>, near: f64) -> ClipCorner<A> {
    let (p, q) = if key(&a.0) <= key(&b.0) {
        (a, b)
    } else {
        (b, a)
    };
    let s = (near - p.0.depth) / (q.0.depth - p.0.depth);
    let s = if s.is_finite() {
        s.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut v = p.0.lerp(q.0, s);
    v.depth = near;
    (v, p.1.lerp_to(q.1, s))
}

/// The part of triangle `corners` at view depth >= `near`, as 0, 1 or 2 triangles (the
/// kept polygon of 0, 3 or 4 corners fanned from its first corner).
pub fn clip_near<A: ClipAttribute>(
    corners: &[ClipCorner<A>; 3],
    near: f64,
) -> ArrayVec<[ClipCorner<A>; 3], 2> {
    let mut poly: ArrayVec<ClipCorner<A>, 4> = ArrayVec::new();
    for k in 0..3 {
        let (a, b) = (&corners[k], &corners[(k + 1) % 3]);
        let (ina, inb) = (a.0.depth >= near, b.0.depth >= near);
        if ina {
            poly.push(*a);
        }
        if ina != inb {
            poly.push(cut(a, b, near));
        }
    }
    (1..poly.len().saturating_sub(1))
        .map(|k| [poly[0], poly[k], poly[k + 1]])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clip_keeps_the_part_beyond_near_with_its_attributes() {
        let v = |x: f64, depth: f64| Vertex2dh {
            x: x * depth,
            y: depth,
            w: depth,
            depth,
        };
        let corners = [
            (v(0.0, 0.5), DVec2::ZERO),
            (v(10.0, 2.0), DVec2::X),
            (v(0.0, 2.0), DVec2::Y),
        ];
        let out = clip_near(&corners, 1.0);
        assert_eq!(out.len(), 2);
        assert!(out.iter().flatten().all(|c| c.0.depth >= 1.0));
        // Edge 0 -> 1 is cut at s = 1/3 (depth 0.5 -> 2 reaches 1), so uv = (1/3, 0); edge
        // 2 -> 0 at 1/3 of the way from vertex 0, uv = (0, 1/3).
        let cuts: Vec<DVec2> = out
            .iter()
            .flatten()
            .filter(|c| c.0.depth == 1.0)
            .map(|c| c.1)
            .collect();
        let near = |a: DVec2, b: DVec2| (a - b).length() < 1e-12;
        assert!(cuts.iter().any(|&uv| near(uv, DVec2::new(1.0 / 3.0, 0.0))));
        assert!(cuts.iter().any(|&uv| near(uv, DVec2::new(0.0, 1.0 / 3.0))));
    }

    #[test]
    fn a_shared_edge_is_cut_at_the_identical_point() {
        let v = |x: f64, depth: f64| Vertex2dh {
            x,
            y: 0.3 * depth,
            w: depth,
            depth,
        };
        let (a, b) = (
            (v(1.0, 0.2), [1.0, 0.0, 0.0]),
            (v(-2.0, 3.0), [0.0, 1.0, 0.0]),
        );
        let c = (v(4.0, 5.0), [0.0, 0.0, 1.0]);
        let d = (v(-4.0, 0.1), [0.0, 0.0, 1.0]);
        let cut_points = |t: [ClipCorner<[f64; 3]>; 3]| -> Vec<[f64; 4]> {
            let mut p: Vec<[f64; 4]> = clip_near(&t, 1.0)
                .iter()
                .flatten()
                .filter(|c| c.0.depth == 1.0)
                .map(|c| key(&c.0))
                .collect();
            p.sort_by(|x, y| x.partial_cmp(y).unwrap());
            p
        };
        let one = cut_points([a, b, c]);
        let other = cut_points([b, a, d]);
        assert!(
            one.iter().any(|p| other.contains(p)),
            "{one:?} vs {other:?}"
        );
    }
}
