//! Screen-space bounds of the bounding cylinder (Heinzle 2010, §4.3, Fig. 5): the exact
//! axis-aligned boxes of the two projected cut-off ellipses and their convex hull as an
//! octagon, built by comparing corresponding corners.

use arrayvec::ArrayVec;
use glam::{DMat4, DVec2, DVec3};

/// An axis-aligned box in pixel coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb2 {
    /// Minimum corner.
    pub min: DVec2,
    /// Maximum corner.
    pub max: DVec2,
}

impl Aabb2 {
    /// Smallest box containing both.
    pub fn union(&self, o: &Aabb2) -> Aabb2 {
        Aabb2 {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }
}

/// Exact screen AABB of the projected 3D ellipse `c + cos θ a + sin θ b` (\[SWBG06\], §4.3).
///
/// `screen` maps world points to 2DH pixel coordinates (rows 0, 1, 3 = x, y, w). The extreme
/// x (and y) are the two roots k of `(Cx - k Cw)² = (Ax - k Aw)² + (Bx - k Bw)²`, the lines
/// x = k w tangent to the ellipse. `None` when the ellipse reaches w <= 0 (it crosses the
/// eye plane and its projection is unbounded).
pub fn ellipse_aabb(screen: &DMat4, c: DVec3, a: DVec3, b: DVec3) -> Option<Aabb2> {
    let cc = *screen * c.extend(1.0);
    let aa = *screen * a.extend(0.0);
    let bb = *screen * b.extend(0.0);
    let lead = cc.w * cc.w - aa.w * aa.w - bb.w * bb.w;
    if !(cc.w > 0.0 && lead > 1e-12 * cc.w * cc.w) {
        return None;
    }
    let range = |cx: f64, ax: f64, bx: f64| -> Option<(f64, f64)> {
        let half_b = cx * cc.w - ax * aa.w - bx * bb.w;
        let c0 = cx * cx - ax * ax - bx * bx;
        let disc = (half_b * half_b - lead * c0).max(0.0);
        let sq = disc.sqrt();
        let (r0, r1) = ((half_b - sq) / lead, (half_b + sq) / lead);
        (r0.is_finite() && r1.is_finite()).then_some((r0, r1))
    };
    let (x0, x1) = range(cc.x, aa.x, bb.x)?;
    let (y0, y1) = range(cc.y, aa.y, bb.y)?;
    Some(Aabb2 {
        min: DVec2::new(x0, y0),
        max: DVec2::new(x1, y1),
    })
}

/// Convex hull of two axis-aligned boxes as a polygon of at most 8 vertices (§4.3, Fig. 5).
///
/// The four corner pairs are visited in the order (min x, min y), (max x, min y),
/// (max x, max y), (min x, max y) — counter-clockwise with y up. For each pair, a corner
/// inside the other's inside quadrant (the quadrant bounded by the two box lines through
/// the other corner) is dropped; otherwise both are kept, in boundary order.
pub fn octagon(p: &Aabb2, q: &Aabb2) -> ArrayVec<DVec2, 8> {
    let mut out = ArrayVec::new();
    // (corner of p, corner of q, inward direction signs (sx, sy), x-first?)
    let corners = [
        (
            DVec2::new(p.min.x, p.min.y),
            DVec2::new(q.min.x, q.min.y),
            1.0,
            1.0,
            true,
        ),
        (
            DVec2::new(p.max.x, p.min.y),
            DVec2::new(q.max.x, q.min.y),
            -1.0,
            1.0,
            false,
        ),
        (
            DVec2::new(p.max.x, p.max.y),
            DVec2::new(q.max.x, q.max.y),
            -1.0,
            -1.0,
            true,
        ),
        (
            DVec2::new(p.min.x, p.max.y),
            DVec2::new(q.min.x, q.max.y),
            1.0,
            -1.0,
            false,
        ),
    ];
    for (u, v, sx, sy, x_first) in corners {
        let inside = |c: DVec2, of: DVec2| (c.x - of.x) * sx >= 0.0 && (c.y - of.y) * sy >= 0.0;
        if inside(v, u) {
            out.push(u);
        } else if inside(u, v) {
            out.push(v);
        } else {
            // Neither dominates: the one further out along x comes first on the edge we
            // arrive by at corners 0 and 2 (the x-edges), the one further out along y at 1, 3.
            let u_first = if x_first {
                (u.x - v.x) * sx < 0.0
            } else {
                (u.y - v.y) * sy < 0.0
            };
            if u_first {
                out.push(u);
                out.push(v);
            } else {
                out.push(v);
                out.push(u);
            }
        }
    }
    out
}

/// Whether `pt` lies inside (or on) the convex polygon `poly` given counter-clockwise with y
/// up (as [`octagon`] returns it), with a tolerance relative to the polygon size.
pub fn polygon_contains(poly: &[DVec2], pt: DVec2) -> bool {
    let n = poly.len();
    if n == 0 {
        return false;
    }
    let scale = poly
        .iter()
        .fold(1.0f64, |m, v| m.max(v.x.abs()).max(v.y.abs()));
    let tol = 1e-12 * scale * scale;
    for i in 0..n {
        let a = poly[i];
        let b = poly[(i + 1) % n];
        let e = b - a;
        if e == DVec2::ZERO {
            continue;
        }
        if e.perp_dot(pt - a) < -tol {
            return false;
        }
    }
    true
}

/// The x range of the convex polygon on the horizontal line at `y` (for row rasterisation).
pub fn polygon_row_span(poly: &[DVec2], y: f64) -> Option<(f64, f64)> {
    let n = poly.len();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..n {
        let a = poly[i];
        let b = poly[(i + 1) % n];
        if (a.y <= y && y <= b.y) || (b.y <= y && y <= a.y) {
            if a.y == b.y {
                lo = lo.min(a.x.min(b.x));
                hi = hi.max(a.x.max(b.x));
            } else {
                let x = a.x + (b.x - a.x) * ((y - a.y) / (b.y - a.y));
                lo = lo.min(x);
                hi = hi.max(x);
            }
        }
    }
    (lo <= hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dominated_box_gives_rectangle() {
        let p = Aabb2 {
            min: DVec2::new(0.0, 0.0),
            max: DVec2::new(10.0, 10.0),
        };
        let q = Aabb2 {
            min: DVec2::new(2.0, 2.0),
            max: DVec2::new(5.0, 5.0),
        };
        let o = octagon(&p, &q);
        assert_eq!(o.len(), 4);
        assert!(polygon_contains(&o, DVec2::new(9.9, 0.1)));
    }

    #[test]
    fn diagonal_boxes_give_hexagon() {
        let p = Aabb2 {
            min: DVec2::new(0.0, 0.0),
            max: DVec2::new(2.0, 2.0),
        };
        let q = Aabb2 {
            min: DVec2::new(5.0, 5.0),
            max: DVec2::new(7.0, 7.0),
        };
        let o = octagon(&p, &q);
        assert_eq!(o.len(), 6);
        assert!(polygon_contains(&o, DVec2::new(3.5, 3.5)));
        assert!(!polygon_contains(&o, DVec2::new(6.0, 1.0)));
        assert!(!polygon_contains(&o, DVec2::new(1.0, 6.0)));
    }
}
