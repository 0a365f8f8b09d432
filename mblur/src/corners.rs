//! A prepared triangle's 2DH corners as the primitive crates take them, and the near-plane
//! test the interval chain and the back-face culling route triangles by.
//!
//! Corners move linearly in homogeneous clip space (Gribel 2010, Eq. 2), so a property of
//! all six corners (three at shutter open, three at close) that is convex in the corner
//! holds for the whole triangle during the whole shutter.

use crate::camera::Vertex2dh;
use crate::prepared::PreparedTriangle;

/// The corners as `(x, y, w)` (edge-eqn's and raster-hier's 2DH vertices).
pub(crate) fn xyw(v: &[Vertex2dh; 3]) -> [[f64; 3]; 3] {
    v.map(|p| [p.x, p.y, p.w])
}

/// True when all six corners are strictly in front of the eye and at or beyond the near
/// plane, so linear motion keeps the whole triangle there for the whole shutter: edge-eqn
/// can sweep it unclipped, and its projected corners bound it on screen
/// ([`raster_hier::SweptHull`]).
pub(crate) fn in_front(tri: &PreparedTriangle, near: f64) -> bool {
    tri.open
        .iter()
        .chain(&tri.close)
        .all(|v| v.w > 0.0 && v.depth >= near)
}
