//! The static rasteriser: one instant of the shutter, rendered the ordinary way.
//!
//! Each triangle is placed at time t (linear 2DH motion, Gribel 2010 Eq. 2), clipped against
//! the near plane (view depth >= near), divided by w and scan-converted by evaluating its
//! three edge functions at pixel centres (i + 0.5, j + 0.5). Edges are evaluated with their
//! endpoints in a canonical order and ties (a centre exactly on an edge) go to the triangle
//! whose inward edge normal points right (or up when vertical): a top-left-equivalent rule,
//! so two triangles sharing an edge never both cover, nor both miss, a centre on it.
//! Attributes (depth, UV) are interpolated perspective-correctly. Opaque fragments use a
//! LESS_EQUAL depth test (the later triangle wins an exact tie); transparent fragments are
//! kept per pixel, sorted and blended front to back with premultiplied OVER.

use glam::DVec2;

use crate::camera::Vertex2dh;
use crate::prepared::{PreparedScene, PreparedTriangle};

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

#[derive(Clone, Copy)]
struct ClipVertex {
    v: Vertex2dh,
    b: [f64; 3],
}

fn key(v: &Vertex2dh) -> [f64; 4] {
    [v.x, v.y, v.w, v.depth]
}

/// Intersection of edge (a, b) with depth = near, computed from the endpoints in a canonical
/// order so that a shared edge yields the identical point in both triangles.
fn cut(a: &ClipVertex, b: &ClipVertex, near: f64) -> ClipVertex {
    let (p, q) = if key(&a.v) <= key(&b.v) {
        (a, b)
    } else {
        (b, a)
    };
    let s = (near - p.v.depth) / (q.v.depth - p.v.depth);
    let s = if s.is_finite() {
        s.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut v = p.v.lerp(q.v, s);
    v.depth = near;
    let b = std::array::from_fn(|k| p.b[k] + (q.b[k] - p.b[k]) * s);
    ClipVertex { v, b }
}

/// Places, clips and sets up one triangle at time `t`; appends 0, 1 or 2 screen triangles.
/// `opaque` says the material has alpha 1 everywhere (see [`PreparedScene::is_opaque`]).
pub fn setup(
    tri: &PreparedTriangle,
    t: f64,
    order: u32,
    opaque: bool,
    target: &Target,
    out: &mut Vec<ScreenTriangle>,
) {
    let Target {
        width,
        height,
        near,
    } = *target;
    let verts = tri.at(t);
    let ident = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let input: [ClipVertex; 3] = [0, 1, 2].map(|k| ClipVertex {
        v: verts[k],
        b: ident[k],
    });
    let mut poly: arrayvec::ArrayVec<ClipVertex, 4> = arrayvec::ArrayVec::new();
    for k in 0..3 {
        let (a, b) = (&input[k], &input[(k + 1) % 3]);
        let (ina, inb) = (a.v.depth >= near, b.v.depth >= near);
        if ina {
            poly.push(*a);
        }
        if ina != inb {
            poly.push(cut(a, b, near));
        }
    }
    for k in 1..poly.len().saturating_sub(1) {
        let c = [poly[0], poly[k], poly[k + 1]];
        if let Some(st) = screen_triangle(&c, tri, order, opaque, width, height) {
            out.push(st);
        }
    }
}

fn screen_triangle(
    c: &[ClipVertex; 3],
    tri: &PreparedTriangle,
    order: u32,
    opaque: bool,
    width: u32,
    height: u32,
) -> Option<ScreenTriangle> {
    if c.iter().any(|v| v.v.w <= 0.0 || v.v.w.is_nan()) {
        return None;
    }
    let s = c.map(|v| DVec2::new(v.v.x / v.v.w, v.v.y / v.v.w));
    if s.iter().any(|p| !p.is_finite()) {
        return None;
    }
    let (lo, hi) = (s[0].min(s[1]).min(s[2]), s[0].max(s[1]).max(s[2]));
    // Pixel i is a candidate when lo <= i + 0.5 <= hi.
    let first = |v: f64, n: u32| (v - 0.5).ceil().clamp(0.0, f64::from(n)) as u32;
    let last = |v: f64, n: u32| (v - 0.5).floor().clamp(-1.0, f64::from(n) - 1.0) as i64;
    let (x0, y0) = (first(lo.x, width), first(lo.y, height));
    let (x1, y1) = (last(hi.x, width), last(hi.y, height));
    if x1 < i64::from(x0) || y1 < i64::from(y0) {
        return None;
    }
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
    // The edge whose inward normal (a, b) has a > 0, or a = 0 and b > 0, owns the centres
    // exactly on it; the neighbour across a shared edge has the exactly negated normal.
    let tie = edges.map(|e| e[0] > 0.0 || (e[0] == 0.0 && e[1] > 0.0));
    Some(ScreenTriangle {
        opaque,
        edges,
        tie,
        inv_area: 1.0 / area.abs(),
        s,
        inv_w: c.map(|v| 1.0 / v.v.w),
        depth: c.map(|v| v.v.depth),
        bary: c.map(|v| v.b),
        uv: tri.uv,
        material: tri.material,
        order,
        x0,
        x1: x1 as u32,
        y0,
        y1: y1 as u32,
    })
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
                for j in 0..3 {
                    let bj =
                        mu[0] * self.bary[0][j] + mu[1] * self.bary[1][j] + mu[2] * self.bary[2][j];
                    uv += self.uv[j] * bj;
                }
                f(x, y, Fragment { depth, uv });
            }
        }
    }
}

/// Per-pixel fragment storage for a band of rows: an opaque depth buffer and, per pixel, the
/// transparent fragments.
#[derive(Debug, Clone)]
pub struct FragmentBuffer {
    width: u32,
    row0: u32,
    rows: u32,
    opaque_depth: Vec<f64>,
    opaque_order: Vec<u32>,
    opaque_color: Vec<[f64; 3]>,
    transparent: Vec<Vec<(f64, u32, [f64; 4])>>,
}

impl FragmentBuffer {
    /// An empty buffer for rows `row0..row0 + rows` of a `width`-pixel image.
    pub fn new(width: u32, row0: u32, rows: u32) -> Self {
        let n = (width * rows) as usize;
        FragmentBuffer {
            width,
            row0,
            rows,
            opaque_depth: vec![f64::INFINITY; n],
            opaque_order: vec![0; n],
            opaque_color: vec![[0.0; 3]; n],
            transparent: vec![Vec::new(); n],
        }
    }

    /// Makes this buffer a copy of `base` (same band), reusing allocations.
    pub fn reset_from(&mut self, base: &FragmentBuffer) {
        self.opaque_depth.copy_from_slice(&base.opaque_depth);
        self.opaque_order.copy_from_slice(&base.opaque_order);
        self.opaque_color.copy_from_slice(&base.opaque_color);
        for (t, b) in self.transparent.iter_mut().zip(&base.transparent) {
            t.clear();
            t.extend_from_slice(b);
        }
    }

    /// Clears all fragments.
    pub fn clear(&mut self) {
        self.opaque_depth.fill(f64::INFINITY);
        for t in &mut self.transparent {
            t.clear();
        }
    }

    /// Rasterises `tri` into the band, shading with `scene`; fragments beyond `far` are
    /// dropped.
    pub fn draw(&mut self, scene: &PreparedScene, tri: &ScreenTriangle) {
        let (row0, row1) = (self.row0, self.row0 + self.rows);
        let far = scene.far;
        tri.rasterise(row0, row1, |x, y, frag| {
            if frag.depth > far {
                return;
            }
            let i = ((y - row0) * self.width + x) as usize;
            let (od, oo) = (self.opaque_depth[i], self.opaque_order[i]);
            // LESS_EQUAL in insertion order: an exact tie goes to the later triangle, whatever
            // order the triangles are drawn in (static ones are drawn once, first).
            let passes = frag.depth < od || (frag.depth == od && tri.order >= oo);
            if tri.opaque && !passes {
                return;
            }
            let c = scene.shade(tri.material, frag.uv);
            if c[3] >= 1.0 {
                if passes {
                    self.opaque_depth[i] = frag.depth;
                    self.opaque_order[i] = tri.order;
                    self.opaque_color[i] = [c[0], c[1], c[2]];
                }
            } else if c[3] > 0.0 {
                self.transparent[i].push((frag.depth, tri.order, c));
            }
        });
    }

    /// Resolves every pixel: transparent fragments in front of the opaque surface, sorted
    /// nearest first (later order first on ties), blended front to back with premultiplied
    /// OVER, then the opaque colour or the background. Calls `f(index_in_band, rgb)`.
    pub fn resolve(&self, background: [f64; 3], mut f: impl FnMut(usize, [f64; 3])) {
        let mut list: Vec<(f64, u32, [f64; 4])> = Vec::new();
        for i in 0..self.opaque_depth.len() {
            let (od, oo) = (self.opaque_depth[i], self.opaque_order[i]);
            let base = if od.is_finite() {
                self.opaque_color[i]
            } else {
                background
            };
            if self.transparent[i].is_empty() {
                f(i, base);
                continue;
            }
            list.clear();
            list.extend(
                self.transparent[i]
                    .iter()
                    .copied()
                    .filter(|&(d, o, _)| d < od || (d == od && o > oo)),
            );
            list.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
            let mut acc = [0.0; 4];
            for &(_, _, c) in list.iter() {
                let k = 1.0 - acc[3];
                for j in 0..4 {
                    acc[j] += k * c[j];
                }
            }
            let k = 1.0 - acc[3];
            f(
                i,
                [
                    acc[0] + k * base[0],
                    acc[1] + k * base[1],
                    acc[2] + k * base[2],
                ],
            );
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
}
