//! Conservative back-face culling for the interval methods (Rønnow 2021 §4.4: back-facing
//! triangles of opaque geometry are culled), restricted so that it never changes the image.
//!
//! A triangle is culled only when all of these hold:
//! - its object is opaque ([`PreparedScene::is_opaque`]) and its mesh is *closed*: every
//!   edge of a non-degenerate triangle is shared by exactly one other triangle of the object
//!   with the opposite direction (vertices matched on their world position at shutter open,
//!   snapped to a grid of 1e-9 of the object's size);
//! - every vertex of every triangle of the object is in front of the near plane at shutter
//!   open and close (so, with linear motion in 2DH, the eye is outside the mesh and nothing
//!   is clipped during the whole shutter);
//! - the triangle faces away from the eye during the WHOLE shutter
//!   ([`raster_hier::facing`], a Bernstein bound on the orientation cubic with a rounding
//!   margin).
//!
//! Why nothing visible is lost: at any time t a ray from the eye first meets a closed mesh
//! where it enters it, on a face whose outward side faces the eye; a face turned away at t
//! is where a ray leaves the mesh, so a nearer face of the same mesh covers it at t. Which
//! sign of the 2DH determinant det[p₀; p₁; p₂] means "turned away" depends on the mesh's
//! winding and on the projection's handedness: it is the sign of the mesh's signed volume
//! seen from the eye, Σ det over its triangles (each det is 6 times the signed volume of the
//! tetrahedron (eye, p₀, p₁, p₂) up to the fixed factor of the projection; faces turned away
//! contribute with the sign of the enclosed volume). The sum must have the same clear sign
//! at open and close, else nothing is culled.

use std::collections::HashMap;

use raster_hier::Facing;

use crate::corners::{in_front, xyw};
use crate::prepared::{PreparedScene, PreparedTriangle};

/// Per triangle: true when it may be culled (see the module documentation).
pub fn backface_mask(scene: &PreparedScene) -> Vec<bool> {
    let mut mask = vec![false; scene.triangles.len()];
    for obj in &scene.objects {
        let Some(tris) = scene.triangles.get(obj.range.clone()) else {
            continue;
        };
        if tris.is_empty()
            || !tris.iter().all(|t| scene.is_opaque(t.material))
            || !tris.iter().all(|t| all_in_front(t, scene.near))
            || !is_closed(tris)
        {
            continue;
        }
        let Some(hidden) = hidden_facing(tris) else {
            continue;
        };
        for (k, t) in tris.iter().enumerate() {
            if facing(t) == hidden
                && let Some(m) = mask.get_mut(obj.range.start + k)
            {
                *m = true;
            }
        }
    }
    mask
}

/// The number of triangles [`backface_mask`] culls.
pub fn backface_count(scene: &PreparedScene) -> usize {
    backface_mask(scene).iter().filter(|&&c| c).count()
}

/// In front of the near plane for the whole shutter ([`in_front`]) with finite corners.
fn all_in_front(t: &PreparedTriangle, near: f64) -> bool {
    in_front(t, near)
        && t.open
            .iter()
            .chain(&t.close)
            .all(|v| v.x.is_finite() && v.y.is_finite())
}

fn facing(t: &PreparedTriangle) -> Facing {
    raster_hier::facing(&xyw(&t.open), &xyw(&t.close))
}

fn det(p: [[f64; 3]; 3]) -> (f64, f64) {
    let [a, b, c] = p;
    let terms = [
        a[0] * (b[1] * c[2] - b[2] * c[1]),
        a[1] * (b[2] * c[0] - b[0] * c[2]),
        a[2] * (b[0] * c[1] - b[1] * c[0]),
    ];
    let mag = a[0].abs() * (b[1] * c[2]).abs().max((b[2] * c[1]).abs())
        + a[1].abs() * (b[2] * c[0]).abs().max((b[0] * c[2]).abs())
        + a[2].abs() * (b[0] * c[1]).abs().max((b[1] * c[0]).abs());
    (terms.iter().sum(), mag)
}

/// The [`Facing`] of the triangles turned away from the eye, from the sign of Σ det at open
/// and at close; `None` when the sign is unclear or differs.
fn hidden_facing(tris: &[PreparedTriangle]) -> Option<Facing> {
    let sign = |pick: fn(&PreparedTriangle) -> &[crate::camera::Vertex2dh; 3]| {
        let (sum, mag) = tris.iter().fold((0.0, 0.0), |(s, m), t| {
            let (d, a) = det(xyw(pick(t)));
            (s + d, m + a)
        });
        if !(sum.is_finite() && mag.is_finite()) || sum.abs() <= 1e-6 * mag {
            None
        } else {
            Some(sum > 0.0)
        }
    };
    let open = sign(|t| &t.open)?;
    let close = sign(|t| &t.close)?;
    if open != close {
        return None;
    }
    // raster-hier's `Front` is det > 0 throughout.
    Some(if open { Facing::Front } else { Facing::Back })
}

/// Every directed edge of a non-degenerate triangle has exactly one reversed partner.
fn is_closed(tris: &[PreparedTriangle]) -> bool {
    let (lo, hi) = tris.iter().flat_map(|t| t.world_open).fold(
        (
            glam::DVec3::splat(f64::INFINITY),
            glam::DVec3::splat(f64::NEG_INFINITY),
        ),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    );
    let size = (hi - lo).max_element();
    if !(size.is_finite() && size > 0.0) {
        return false;
    }
    let cell = size * 1e-9;
    let key = |p: glam::DVec3| {
        let q = (p - lo) / cell;
        [q.x.round() as i64, q.y.round() as i64, q.z.round() as i64]
    };
    let mut edges: HashMap<([i64; 3], [i64; 3]), i32> = HashMap::with_capacity(tris.len() * 3);
    for t in tris {
        let k = t.world_open.map(key);
        if k[0] == k[1] || k[1] == k[2] || k[0] == k[2] {
            continue; // zero area for the whole shutter (rigid per-vertex transforms)
        }
        for (a, b) in [(k[0], k[1]), (k[1], k[2]), (k[2], k[0])] {
            // +1 for a -> b, -1 for b -> a, on the ordered key pair.
            let (e, s) = if a < b { ((a, b), 1) } else { ((b, a), -1) };
            let c = edges.entry(e).or_insert(0);
            *c += s * 1000 + 1;
        }
    }
    // Each undirected edge must be used exactly twice, once per direction: +1000+1 and
    // -1000+1 sum to 2.
    !edges.is_empty() && edges.values().all(|&c| c == 2)
}
