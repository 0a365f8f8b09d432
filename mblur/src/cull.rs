//! Exact time-dependent back-face culling for the interval methods (Rønnow 2021 §4.4 culls
//! back-facing triangles of opaque geometry; Munkberg and Akenine-Möller 2011, "Backface
//! culling for motion blur and depth of field", give the time-dependent test), restricted
//! so that it never changes the image.
//!
//! A triangle's intervals are clipped to the times it may face the eye ([`Culling::windows`])
//! only when all of these hold:
//! - its object is opaque ([`PreparedScene::is_opaque`]) and its mesh is *closed*: every
//!   edge of a non-degenerate triangle is shared by exactly one other triangle of the object
//!   with the opposite direction (vertices matched on their world position at shutter open,
//!   snapped to a grid of 1e-9 of the object's size);
//! - every vertex of every triangle of the object is in front of the near plane at shutter
//!   open and close (so, with linear motion in 2DH, the eye is outside the mesh and nothing
//!   is clipped during the whole shutter).
//!
//! Which times are removed: those at which the triangle provably faces away. Its 2DH
//! orientation det[p₀(t); p₁(t); p₂(t)] is a cubic in the time local to its span
//! ([`PreparedTriangle::span`]; vertices linear in 2DH between the span's ends).
//! [`raster_hier::facing_windows`] decides most triangles with the Bernstein bound of
//! [`raster_hier::facing`] (facing away during the whole span: culled, no primitive;
//! facing the eye: kept whole) and otherwise cuts the span at the cubic's roots and removes
//! the pieces the Bernstein bound proves turned away (with the rounding margin of f64
//! input, 2⁻²⁰ of the span left on each side of a root); the chain clips each coverage
//! interval of the triangle to the remaining windows before it is cut into pieces and given
//! depth and payload (`chain::emit`). The prism sweep moves screen positions linearly
//! ([`Motion::Screen`]); its triangle's orientation is the same determinant of the vertices
//! (x/w, y/w, 1), a quadratic, and it is clipped with that.
//!
//! Why nothing visible is lost: at any time t a ray from the eye first meets a closed mesh
//! where it enters it, on a face whose outward side faces the eye; a face turned away at t
//! is where a ray leaves the mesh, so a nearer face of the same mesh covers it at t. The
//! argument holds at each instant, so removing exactly the instants a triangle is turned
//! away keeps the image; it assumes the mesh does not pass through itself at that instant
//! (each segment of a path interpolates the vertices linearly, and a long rotation in one
//! segment could fold a mesh). Which sign of the determinant means "turned away" depends on
//! the mesh's winding and on the projection's handedness: it is the sign of the mesh's
//! signed volume seen from the eye, Σ det over its triangles (each det is 6 times the
//! signed volume of the tetrahedron (eye, p₀, p₁, p₂) up to the fixed factor of the
//! projection; faces turned away contribute with the sign of the enclosed volume). The sum
//! must have the same clear sign at open and close (beyond [`SIGN_MARGIN`]), else nothing
//! is culled. Dividing
//! (x, y, w) by w > 0 keeps the sign, so the screen orientation of [`Motion::Screen`] uses
//! the same rule.

mod closed;

pub use raster_hier::{Facing, FacingWindows};

use crate::corners::{in_front, xyw};
use crate::prepared::{PreparedScene, PreparedTriangle};

/// The signed volume Σ det of a closed mesh decides which winding is turned away only when
/// it exceeds this fraction of the sum of the magnitudes of its terms. Rounding of the sum
/// of N determinants stays below about N ε of that sum (10⁻⁹ at N = 4.5 M); a small mesh far
/// from the eye has a small ratio (2·10⁻⁷ to 10⁻⁶ for the balls of `billiards`, 3·10⁻⁶ to
/// 10⁻⁵ for `pills` and `clothball-ronnow`), a flat two-sided closed sheet a ratio at the
/// rounding level.
pub const SIGN_MARGIN: f64 = 1e-9;

/// Which straight motion between the ends of a triangle's span a sweep renders, so which
/// orientation polynomial decides when the triangle faces the eye.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    /// Vertices linear in 2DH (edge-eqn, Gribel 2010 Eq. 2): the orientation is a cubic.
    Homogeneous,
    /// Screen positions linear (the bilinear-patch prism, Rønnow 2021 §3): the orientation
    /// of the screen triangle (x/w, y/w, 1) is a quadratic.
    Screen,
}

/// The back-face culling of one scene: per triangle, the winding turned away from the eye
/// when its object may be culled (see the module documentation).
#[derive(Debug, Clone)]
pub struct Culling {
    /// Per triangle: the [`Facing`] whose times may be removed; `Facing::Mixed` for
    /// triangles of objects that are not culled.
    hidden: Vec<Facing>,
}

impl Culling {
    /// The culling of `scene`: which objects are opaque, closed and in front of the near
    /// plane, and which winding their triangles show when turned away.
    pub fn of(scene: &PreparedScene) -> Self {
        let mut hidden = vec![Facing::Mixed; scene.triangles.len()];
        for obj in &scene.objects {
            let Some(tris) = scene.triangles.get(obj.range.clone()) else {
                continue;
            };
            if tris.is_empty()
                || !tris.iter().all(|t| scene.is_opaque(t.material))
                || !tris.iter().all(|t| all_in_front(t, scene.near))
                || !closed::is_closed(tris, |t| t.world_open)
            {
                continue;
            }
            let Some(h) = hidden_facing(tris) else {
                continue;
            };
            if let Some(dst) = hidden.get_mut(obj.range.clone()) {
                dst.fill(h);
            }
        }
        Culling { hidden }
    }

    /// The times local to the span of triangle `i` of `scene` ([`PreparedTriangle::span`],
    /// u ∈ \[0, 1\]) at which it may face the eye under `motion`: all of \[0, 1\] for a
    /// triangle that is not culled, none for one turned away during its whole span.
    pub fn windows(&self, scene: &PreparedScene, i: usize, motion: Motion) -> FacingWindows {
        let (Some(&hidden), Some(t)) = (self.hidden.get(i), scene.triangles.get(i)) else {
            return FacingWindows::all();
        };
        if hidden == Facing::Mixed {
            return FacingWindows::all();
        }
        let w = match motion {
            Motion::Homogeneous => {
                raster_hier::facing_windows(&xyw(&t.open), &xyw(&t.close), hidden)
            }
            Motion::Screen => {
                let s = |v: &[crate::camera::Vertex2dh; 3]| {
                    v.map(|p| {
                        let (x, y) = p.screen();
                        [x, y, 1.0]
                    })
                };
                raster_hier::facing_windows(&s(&t.open), &s(&t.close), hidden)
            }
        };
        // A static triangle's orientation is constant: culled whole or kept whole.
        if !t.is_moving() && !w.is_empty() {
            return FacingWindows::all();
        }
        w
    }

    /// The winding whose times may be removed from triangle `i` ([`Facing::Front`]: the
    /// 2DH determinant det[p0; p1; p2] > 0), or [`Facing::Mixed`] when its object is not
    /// culled.
    pub fn hidden(&self, i: usize) -> Facing {
        self.hidden.get(i).copied().unwrap_or(Facing::Mixed)
    }

    /// How many triangles of `scene` are culled whole and how many clipped to part of
    /// their span under `motion`.
    pub fn counts(&self, scene: &PreparedScene, motion: Motion) -> CullCounts {
        let mut c = CullCounts::default();
        for i in 0..self.hidden.len() {
            let w = self.windows(scene, i, motion);
            if w.is_empty() {
                c.culled += 1;
            } else if !w.is_all() {
                c.clipped += 1;
            }
        }
        c
    }
}

/// What [`Culling`] does to a scene's triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CullCounts {
    /// Triangles turned away during their whole span: no primitive at all.
    pub culled: u64,
    /// Triangles turned away during part of their span: intervals clipped to the rest.
    pub clipped: u64,
}

/// Per triangle: true when it is turned away during its whole span and culled (edge-eqn's
/// [`Motion::Homogeneous`]; see the module documentation).
pub fn backface_mask(scene: &PreparedScene) -> Vec<bool> {
    let c = Culling::of(scene);
    (0..scene.triangles.len())
        .map(|i| c.windows(scene, i, Motion::Homogeneous).is_empty())
        .collect()
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
        if !(sum.is_finite() && mag.is_finite()) || sum.abs() <= SIGN_MARGIN * mag {
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
