//! The static rasteriser: one triangle at one instant of the shutter, scan-converted the
//! ordinary way.
//!
//! Each triangle is placed at time t (linear 2DH motion, Gribel 2010 Eq. 2), clipped against
//! the near plane ([`super::clip`]), divided by w and scan-converted by evaluating its three
//! edge functions at pixel centres (i + 0.5, j + 0.5). Edges are evaluated with their
//! endpoints in a canonical order and ties (a centre exactly on an edge) go to the triangle
//! whose inward edge normal points right (or up when vertical): a top-left-equivalent rule,
//! so two triangles sharing an edge never both cover, nor both miss, a centre on it.
//! Attributes (depth, UV) are interpolated perspective-correctly.

use glam::DVec2;

use super::clip::{ClipCorner, clip_near};
use crate::camera::Vertex2dh;
use crate::prepared::{PreparedScene, PreparedTriangle};
use crate::texture::floor;

/// A clipped triangle at one instant, in screen space, ready to scan-convert.
#[derive(Debug, Clone)]
pub struct ScreenTriangle {
    /// Screen positions (x / w, y / w) in pixels.
    pub s: [DVec2; 3],
    /// 1 / w at the corners.
    pub inv_w: [f64; 3],
    /// View depth at the corners.
    pub depth: [f64; 3],
    /// Barycentric weights of each corner with respect to the unclipped triangle.
    pub bary: [[f64; 3]; 3],
    /// UVs of the unclipped triangle.
    pub uv: [DVec2; 3],
    /// Material index.
    pub material: u32,
    /// Insertion order (the later one wins an exact depth tie).
    pub order: u32,
    /// The material is opaque everywhere (alpha 1, no texture alpha): depth-test first.
    pub opaque: bool,
    /// Edge functions (a, b, c), positive inside, edge k opposite corner k.
    pub edges: [[f64; 3]; 3],
    /// Whether a centre exactly on edge k is inside (the tie rule).
    pub tie: [bool; 3],
    /// 1 / (twice the screen area).
    pub inv_area: f64,
    /// Pixel bounds: columns `x0..=x1`, rows `y0..=y1` (pixel centres inside the bounds).
    pub x0: u32,
    /// See `x0`.
    pub x1: u32,
    /// See `x0`.
    pub y0: u32,
    /// See `x0`.
    pub y1: u32,
}

/// The image a triangle is set up for: size in pixels and the near clipping depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Target {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Near clipping depth (view space).
    pub near: f64,
}

impl Target {
    /// The scene's image and near plane.
    pub fn of(scene: &PreparedScene) -> Self {
        Target {
            width: scene.width,
            height: scene.height,
            near: scene.near,
        }
    }
}

/// Pixel bounds: columns `x0..=x1`, rows `y0..=y1`, all inside the image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PixelBounds {
    /// First column.
    pub x0: u32,
    /// Last column.
    pub x1: u32,
    /// First row.
    pub y0: u32,
    /// Last row.
    pub y1: u32,
}

/// The pixels whose centres (i + 0.5, j + 0.5) lie inside the screen box `[lo, hi]`,
/// clamped to a `width` x `height` image, or `None` when there are none: the candidate
/// pixels of a static triangle and of a moving primitive's swept box.
pub fn pixel_bounds(lo: DVec2, hi: DVec2, width: u32, height: u32) -> Option<PixelBounds> {
    // Pixel i is a candidate when lo <= i + 0.5 <= hi; ceil(v) = -floor(-v) exactly.
    let first = |v: f64, n: u32| (-floor(-(v - 0.5))).clamp(0.0, f64::from(n)) as u32;
    let last = |v: f64, n: u32| floor(v - 0.5).clamp(-1.0, f64::from(n) - 1.0) as i64;
    let (x0, y0) = (first(lo.x, width), first(lo.y, height));
    let (x1, y1) = (last(hi.x, width), last(hi.y, height));
    if x1 < i64::from(x0) || y1 < i64::from(y0) {
        None
    } else {
        Some(PixelBounds {
            x0,
            x1: x1 as u32,
            y0,
            y1: y1 as u32,
        })
    }
}

/// Places, clips and sets up one triangle at time `u` local to its span ([`PreparedTriangle::at`]);
/// appends 0, 1 or 2 screen triangles. `opaque` says the material has alpha 1 everywhere
/// (see [`PreparedScene::is_opaque`]).
pub fn setup(
    tri: &PreparedTriangle,
    u: f64,
    order: u32,
    opaque: bool,
    target: &Target,
    out: &mut Vec<ScreenTriangle>,
) {
    setup_corners(tri, tri.at(u), order, opaque, target, out);
}

/// As [`setup`], with the triangle's corners given (e.g. on its true curved path,
/// [`PreparedScene::corners_at`]).
pub fn setup_corners(
    tri: &PreparedTriangle,
    verts: [Vertex2dh; 3],
    order: u32,
    opaque: bool,
    target: &Target,
    out: &mut Vec<ScreenTriangle>,
) {
    let ident = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let corners = [0, 1, 2].map(|k| (verts[k], ident[k]));
    let placed = Placed {
        tri,
        order,
        opaque,
        target,
    };
    for c in clip_near(&corners, target.near) {
        if let Some(st) = placed.screen_triangle(&c) {
            out.push(st);
        }
    }
}

/// What [`setup`] knows of the triangle besides its clipped corners.
struct Placed<'a> {
    tri: &'a PreparedTriangle,
    order: u32,
    opaque: bool,
    target: &'a Target,
}

impl Placed<'_> {
    /// The screen triangle of clipped corners `c` (2DH vertex and barycentrics with respect
    /// to the unclipped triangle), or `None` when it is behind the eye, degenerate or off
    /// the image.
    fn screen_triangle(&self, c: &[ClipCorner<[f64; 3]>; 3]) -> Option<ScreenTriangle> {
        if c.iter().any(|v| v.0.w <= 0.0 || v.0.w.is_nan()) {
            return None;
        }
        let s = c.map(|v| DVec2::new(v.0.x / v.0.w, v.0.y / v.0.w));
        if s.iter().any(|p| !p.is_finite()) {
            return None;
        }
        let (lo, hi) = (s[0].min(s[1]).min(s[2]), s[0].max(s[1]).max(s[2]));
        let b = pixel_bounds(lo, hi, self.target.width, self.target.height)?;
        let [s0, s1, s2] = s;
        let mut edges = [
            edge_coefficients(s1, s2),
            edge_coefficients(s2, s0),
            edge_coefficients(s0, s1),
        ];
        let area = eval(&edges[2], s2);
        if area == 0.0 || !area.is_finite() {
            return None; // degenerate: covers nothing
        }
        if area < 0.0 {
            for e in &mut edges {
                *e = e.map(|v| -v);
            }
        }
        // The edge whose inward normal (a, b) has a > 0, or a = 0 and b > 0, owns the
        // centres exactly on it; the neighbour across a shared edge has the exactly negated
        // normal.
        let tie = edges.map(|e| e[0] > 0.0 || (e[0] == 0.0 && e[1] > 0.0));
        Some(ScreenTriangle {
            opaque: self.opaque,
            edges,
            tie,
            inv_area: 1.0 / area.abs(),
            s,
            inv_w: c.map(|v| 1.0 / v.0.w),
            depth: c.map(|v| v.0.depth),
            bary: c.map(|v| v.1),
            uv: self.tri.uv,
            material: self.tri.material,
            order: self.order,
            x0: b.x0,
            x1: b.x1,
            y0: b.y0,
            y1: b.y1,
        })
    }
}

/// Coefficients (a, b, c) of the edge function e(s) = a x + b y + c = (q - p) x (s - p) of
/// the directed edge p -> q, computed with
/// the endpoints in a canonical (lexicographic) order and negated when reversed, so the
/// reversed edge evaluates to exactly the negated value at every point.
fn edge_coefficients(p: DVec2, q: DVec2) -> [f64; 3] {
    let f = |p: DVec2, q: DVec2| [p.y - q.y, q.x - p.x, p.x * q.y - p.y * q.x];
    if (p.x, p.y) <= (q.x, q.y) {
        f(p, q)
    } else {
        f(q, p).map(|v| -v)
    }
}

fn eval(e: &[f64; 3], s: DVec2) -> f64 {
    e[0] * s.x + e[1] * s.y + e[2]
}

/// A covered sample: depth, perspective-correct UV, material and order.
#[derive(Debug, Clone, Copy)]
pub struct Fragment {
    /// View depth.
    pub depth: f64,
    /// Texture coordinate.
    pub uv: DVec2,
    /// Perspective-correct barycentric weights of the unclipped triangle's corners: the
    /// surface point, which keeps its weights as the corners move (Gribel 2010, Eq. 2).
    pub bary: [f64; 3],
}

impl ScreenTriangle {
    /// Calls `f(x, y, fragment)` for every covered pixel centre in rows `row0..row1`.
    pub fn rasterise(&self, row0: u32, row1: u32, mut f: impl FnMut(u32, u32, Fragment)) {
        let ys = self.y0.max(row0);
        let ye = self.y1.min(row1.saturating_sub(1));
        if ys > ye {
            return;
        }
        for y in ys..=ye {
            let sy = f64::from(y) + 0.5;
            'pixels: for x in self.x0..=self.x1 {
                let sp = DVec2::new(f64::from(x) + 0.5, sy);
                let mut lam = [0.0; 3];
                for ((l, edge), tie) in lam.iter_mut().zip(&self.edges).zip(self.tie) {
                    let e = eval(edge, sp);
                    if e < 0.0 || (e == 0.0 && !tie) {
                        continue 'pixels;
                    }
                    *l = e * self.inv_area;
                }
                let pw = [
                    lam[0] * self.inv_w[0],
                    lam[1] * self.inv_w[1],
                    lam[2] * self.inv_w[2],
                ];
                let sum = pw[0] + pw[1] + pw[2];
                if sum <= 0.0 || sum.is_nan() {
                    continue;
                }
                let mu = pw.map(|p| p / sum);
                let depth = mu[0] * self.depth[0] + mu[1] * self.depth[1] + mu[2] * self.depth[2];
                let mut uv = DVec2::ZERO;
                let mut bary = [0.0; 3];
                for (j, b) in bary.iter_mut().enumerate() {
                    *b =
                        mu[0] * self.bary[0][j] + mu[1] * self.bary[1][j] + mu[2] * self.bary[2][j];
                    uv += self.uv[j] * *b;
                }
                f(x, y, Fragment { depth, uv, bary });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edge_is_antisymmetric_bit_for_bit() {
        let p = DVec2::new(0.1, 7.3);
        let q = DVec2::new(3.7, -1.9);
        for s in [
            DVec2::new(0.5, 0.5),
            DVec2::new(1e3, -2.2),
            DVec2::new(2.5, 1.5),
        ] {
            assert_eq!(
                eval(&edge_coefficients(p, q), s),
                -eval(&edge_coefficients(q, p), s)
            );
        }
    }

    #[test]
    fn pixel_bounds_take_the_centres_inside() {
        let b = pixel_bounds(DVec2::new(0.5, 1.2), DVec2::new(3.5, 2.4), 10, 10);
        assert_eq!(
            b,
            Some(PixelBounds {
                x0: 0,
                x1: 3,
                y0: 1,
                y1: 1
            })
        );
        assert_eq!(
            pixel_bounds(DVec2::new(1.6, 0.0), DVec2::new(2.4, 5.0), 10, 10),
            None
        );
        assert_eq!(
            pixel_bounds(DVec2::new(-5.0, -5.0), DVec2::new(-1.0, 3.0), 10, 10),
            None
        );
    }
}
