//! The screen-space bound of a moving triangle over its frustum interval (Munkberg 2011,
//! §3): the six projected vertices when it stays in front of the eye, the whole screen
//! otherwise.

use num_traits::Float;

use crate::interval::{TimeInterval, lit};

/// An axis-aligned rectangle `[x0, x1] x [y0, y1]` in pixel units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect<F> {
    /// Left.
    pub x0: F,
    /// Top.
    pub y0: F,
    /// Right.
    pub x1: F,
    /// Bottom.
    pub y1: F,
}

impl<F: Float> Rect<F> {
    /// `[x0, x1] x [y0, y1]`.
    #[inline]
    pub fn new(x0: F, y0: F, x1: F, y1: F) -> Self {
        Rect { x0, y0, x1, y1 }
    }

    /// True when the rectangle contains no point.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.x0
            .partial_cmp(&self.x1)
            .is_none_or(|o| o == core::cmp::Ordering::Greater)
            || self
                .y0
                .partial_cmp(&self.y1)
                .is_none_or(|o| o == core::cmp::Ordering::Greater)
    }

    /// The intersection.
    #[inline]
    pub fn intersect(&self, o: &Self) -> Self {
        Rect {
            x0: self.x0.max(o.x0),
            y0: self.y0.max(o.y0),
            x1: self.x1.min(o.x1),
            y1: self.y1.min(o.y1),
        }
    }
}

/// Where a screen bound came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenBound<F> {
    /// The bound, clipped to the screen `[0, width] x [0, height]`.
    pub rect: Rect<F>,
    /// True when it bounds the six projected vertices (all w > 0 at t_s and t_e); false for
    /// the conservative whole-screen fallback of a triangle crossing w = 0.
    pub projected: bool,
}

/// The vertices at time t, p(t) = (1 − t) q + t r.
#[inline]
pub fn vertices_at<F: Float>(q: &[[F; 3]; 3], r: &[[F; 3]; 3], t: F) -> [[F; 3]; 3] {
    core::array::from_fn(|i| core::array::from_fn(|c| q[i][c] + t * (r[i][c] - q[i][c])))
}

/// Bound of projected points `(x / w, y / w)`, or `None` if some w ≤ 0 or a projection is
/// not finite. Padded by a rounding margin of `64 ε` times the coordinate magnitude.
pub fn projected_bound<F: Float>(points: &[[F; 3]]) -> Option<Rect<F>> {
    let inf = F::infinity();
    let mut r = Rect::new(inf, inf, -inf, -inf);
    let mut mag = F::one();
    for p in points {
        if p[2].partial_cmp(&F::zero()) != Some(core::cmp::Ordering::Greater) {
            return None;
        }
        let (x, y) = (p[0] / p[2], p[1] / p[2]);
        if !(x.is_finite() && y.is_finite()) {
            return None;
        }
        r = Rect::new(r.x0.min(x), r.y0.min(y), r.x1.max(x), r.y1.max(y));
        mag = mag.max(x.abs()).max(y.abs());
    }
    let pad = mag * F::epsilon() * lit(64.0);
    Some(Rect::new(r.x0 - pad, r.y0 - pad, r.x1 + pad, r.y1 + pad))
}

/// The screen bound of a moving triangle during `iv` (its frustum interval): if the six
/// vertices p_i(t_s), p_i(t_e) all have w > 0 the triangle stays in front of the eye during
/// `iv` (w is linear in t) and its projection stays inside the bound of the six projected
/// vertices (Munkberg 2011, §3). Otherwise the triangle crosses w = 0; its in-front part can
/// project anywhere, so the bound is the whole screen (the conservative fallback McGuire et
/// al. 2010 also use for such triangles). Never NaN.
pub fn screen_bound<F: Float>(
    q: &[[F; 3]; 3],
    r: &[[F; 3]; 3],
    iv: TimeInterval<F>,
    width: F,
    height: F,
) -> ScreenBound<F> {
    let screen = Rect::new(F::zero(), F::zero(), width, height);
    let a = vertices_at(q, r, iv.lo);
    let b = vertices_at(q, r, iv.hi);
    let six = [a[0], a[1], a[2], b[0], b[1], b[2]];
    match projected_bound(&six) {
        Some(rect) => ScreenBound {
            rect: rect.intersect(&screen),
            projected: true,
        },
        None => ScreenBound {
            rect: screen,
            projected: false,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn six_vertices_bound_a_translating_triangle() {
        let q = [[2.0f64, 2.0, 1.0], [6.0, 2.0, 1.0], [2.0, 6.0, 1.0]];
        let r = q.map(|[x, y, w]| [x + 10.0, y, w]);
        let b = screen_bound(&q, &r, TimeInterval::full(), 64.0, 64.0);
        assert!(b.projected);
        assert!((b.rect.x0 - 2.0).abs() < 1e-9 && (b.rect.x1 - 16.0).abs() < 1e-9);
        assert!((b.rect.y1 - 6.0).abs() < 1e-9);
    }

    #[test]
    fn crossing_w_zero_falls_back_to_screen() {
        let q = [[2.0f32, 2.0, 1.0], [6.0, 2.0, 1.0], [2.0, 6.0, 1.0]];
        let mut r = q;
        r[0][2] = -1.0;
        let b = screen_bound(&q, &r, TimeInterval::full(), 32.0, 16.0);
        assert!(!b.projected);
        assert_eq!(b.rect, Rect::new(0.0, 0.0, 32.0, 16.0));
    }
}
