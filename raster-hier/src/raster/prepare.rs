//! Culling and setup of one triangle of a frame (Munkberg 2011, §3, §7): temporal
//! view-frustum culling, motion back-face culling, the screen bound, the tile tester (§4),
//! the convex hull of CONVEX and the §7 decision to fall back to INTERLEAVE.

use edge_eqn::TriangleSetup;
use num_traits::Float;

use super::{RasterConfig, RasterTriangle, Traversal};
use crate::bound::{Rect, projected_bound, screen_bound, vertices_at};
use crate::convex::ConvexHull;
use crate::counters::{Counters, cost};
use crate::cull::{Facing, facing, frustum_interval};
use crate::interval::{TimeInterval, lit};
use crate::tile_test::TileTester;

/// A triangle after culling and setup.
#[derive(Clone, Debug)]
pub(super) struct Prepared<F> {
    pub(super) setup: TriangleSetup<F>,
    pub(super) id: u32,
    /// The triangle's span (every time interval of its traversal lies inside it).
    pub(super) span: TimeInterval<F>,
    pub(super) q: [[F; 3]; 3],
    pub(super) r: [[F; 3]; 3],
    zq: [F; 3],
    zr: [F; 3],
    pub(super) all_front: bool,
    pub(super) tester: TileTester<F>,
    pub(super) bound: Rect<F>,
    pub(super) hull: Option<ConvexHull>,
    pub(super) interleave: bool,
}

impl<F: Float> Prepared<F> {
    /// Lower bound of the triangle's depth over `iv`: the perspective-correct depth is a
    /// convex combination of the vertex depths, each linear in t. Lowered by a rounding margin.
    pub(super) fn zmin(&self, iv: TimeInterval<F>) -> F {
        let mut m = F::infinity();
        for k in 0..3 {
            for t in [iv.lo, iv.hi] {
                m = m.min(self.zq[k] + t * (self.zr[k] - self.zq[k]));
            }
        }
        m - m.abs() * F::epsilon() * lit(16.0)
    }
}

/// Culls and sets up `tri` for a `width` x `height` frame with `unique_times` sample times
/// (Munkberg 2011, §3, §7), counting into `c`; `None` when the triangle is culled (unusable
/// span, invalid setup, outside the frustum over its span, off screen, or back-facing with
/// back-face culling on).
pub(super) fn prepare<F: Float>(
    tri: &RasterTriangle<F>,
    width: F,
    height: F,
    cfg: &RasterConfig,
    unique_times: u32,
    c: &mut Counters,
) -> Option<Prepared<F>> {
    c.triangles_in += 1;
    let Some(whole) = tri.over_shutter() else {
        c.frustum_culled += 1;
        return None;
    };
    let (q, r) = (whole.q, whole.r);
    let setup = whole.setup();
    c.arithmetic += cost::SETUP;
    let frustum = frustum_interval(&q, &r, width, height).intersect(tri.span);
    if !setup.is_valid() || frustum.is_empty() {
        c.frustum_culled += 1;
        return None;
    }
    // Over the span, which is the whole motion given (its orientation outside the span
    // does not matter).
    let face = facing(&tri.triangle.q, &tri.triangle.r);
    if cfg.cull_backfaces && face == Facing::Back {
        c.backface_culled += 1;
        return None;
    }
    let bound = screen_bound(&q, &r, frustum, width, height);
    if bound.rect.is_empty() {
        c.frustum_culled += 1;
        return None;
    }
    c.triangles_set_up += 1;
    c.arithmetic += cost::LINEARISE;
    // w is linear in t: positive at the span's ends, positive over it.
    let (given_q, given_r) = (tri.triangle.q, tri.triangle.r);
    let all_front = given_q
        .iter()
        .chain(given_r.iter())
        .all(|v| v[2] > F::zero());
    let tester = TileTester::new(&q, &r, *setup.edges(), face, frustum, bound.rect);
    let (a, b) = (
        vertices_at(&q, &r, frustum.lo),
        vertices_at(&q, &r, frustum.hi),
    );
    let (ba, bb) = (projected_bound(&a), projected_bound(&b));
    let hull = match (cfg.traversal, bound.projected) {
        (Traversal::Convex, true) => {
            let f = |v: F| v.to_f64().unwrap_or(0.0);
            let pts: [[f64; 2]; 6] = core::array::from_fn(|i| {
                let p = if i < 3 { a[i] } else { b[i - 3] };
                [f(p[0] / p[2]), f(p[1] / p[2])]
            });
            let mag = pts.iter().flatten().fold(1.0f64, |m, v| m.max(v.abs()));
            let eps = F::epsilon().to_f64().unwrap_or(1e-7);
            Some(ConvexHull::new(&pts, 1e-6 + 256.0 * eps * mag))
        }
        _ => None,
    };
    let interleave = match cfg.traversal {
        Traversal::Interleave => true,
        Traversal::OurFallback(_) => match (ba, bb) {
            (Some(ba), Some(bb)) => {
                let n: F = lit(f64::from(unique_times));
                let (w0, h0) = (ba.x1 - ba.x0, ba.y1 - ba.y0);
                let (w1, h1) = (bb.x1 - bb.x0, bb.y1 - bb.y0);
                let (ws, hs) = (
                    ba.x1.max(bb.x1) - ba.x0.min(bb.x0),
                    ba.y1.max(bb.y1) - ba.y0.min(bb.y0),
                );
                w0.min(w1) < ws / n || h0.min(h1) < hs / n
            }
            _ => false,
        },
        _ => false,
    };
    if interleave && cfg.traversal != Traversal::Interleave {
        c.fallbacks += 1;
    }
    let (zq, zr) = setup.depths();
    Some(Prepared {
        setup,
        id: tri.id,
        span: tri.span,
        q,
        r,
        zq,
        zr,
        all_front,
        tester,
        bound: bound.rect,
        hull,
        interleave,
    })
}
