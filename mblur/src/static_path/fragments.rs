//! Per-pixel fragment storage of the static path for a band of rows: an opaque depth buffer
//! with a LESS_EQUAL depth test (the later triangle wins an exact tie) and, per pixel, the
//! transparent fragments, sorted and blended front to back with premultiplied OVER.

use super::raster::ScreenTriangle;
use crate::prepared::PreparedScene;

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

    /// Rasterises `tri` (placed at normalised time `t`) into the band, shading with `scene`
    /// at `t`; fragments beyond `far` are dropped.
    pub fn draw(&mut self, scene: &PreparedScene, tri: &ScreenTriangle, t: f64) {
        let lit = scene
            .triangles
            .get(tri.order as usize)
            .filter(|p| scene.is_lit(p.material));
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
            let c = match lit {
                Some(p) => scene.shade_surface(p, frag.bary, t),
                None => scene.shade(tri.material, frag.uv),
            };
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
