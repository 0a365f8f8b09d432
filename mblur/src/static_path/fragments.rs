//! Per-pixel fragment storage of the static path for a band of rows: an opaque depth buffer
//! with a LESS_EQUAL depth test (the later triangle wins an exact tie) and, per pixel, the
//! transparent fragments, sorted and blended front to back with premultiplied OVER.
//!
//! What the buffer holds after [`FragmentBuffer::commit`] (or, before any commit, the empty
//! buffer) is its base layer. Each row keeps the span of columns that draws changed since
//! then ([`FragmentBuffer::dirty`]); [`FragmentBuffer::restore`] returns those spans to the
//! base layer, so a buffer drawn over and restored costs what was drawn, not the band's
//! size, and a row drawn over everywhere costs one copy of the row. This is how `accum`
//! draws its moving triangles over the static ones once per sub-frame.

use super::raster::ScreenTriangle;
use crate::prepared::PreparedScene;
use crate::surface_track::SurfaceTrack;

/// A transparent fragment: depth, insertion order, premultiplied RGBA.
pub type Transparent = (f64, u32, [f64; 4]);

/// Columns `start..end` of one row (empty when `start >= end`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Span {
    /// First column.
    pub start: u32,
    /// One past the last column.
    pub end: u32,
}

impl Span {
    const EMPTY: Span = Span {
        start: u32::MAX,
        end: 0,
    };

    /// The span's columns (`0..0` when empty).
    pub fn columns(self) -> std::ops::Range<usize> {
        if self.start < self.end {
            self.start as usize..self.end as usize
        } else {
            0..0
        }
    }
}

/// The committed base layer: opaque surface and number of transparent fragments per pixel
/// (a pixel's base fragments stay the first of its list: draws only append).
#[derive(Debug, Clone, Default)]
struct BaseLayer {
    depth: Vec<f64>,
    order: Vec<u32>,
    color: Vec<[f64; 3]>,
    transparent: Vec<u32>,
}

/// Per-pixel fragment storage for a band of rows: an opaque depth buffer and, per pixel, the
/// transparent fragments, over a base layer it can be restored to.
#[derive(Debug, Clone)]
pub struct FragmentBuffer {
    width: u32,
    row0: u32,
    rows: u32,
    opaque_depth: Vec<f64>,
    opaque_order: Vec<u32>,
    opaque_color: Vec<[f64; 3]>,
    transparent: Vec<Vec<Transparent>>,
    /// Per row: the columns changed since the last commit or restore.
    dirty: Vec<Span>,
    /// The base layer; empty vectors stand for the empty buffer.
    base: BaseLayer,
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
            dirty: vec![Span::EMPTY; rows as usize],
            base: BaseLayer::default(),
        }
    }

    /// Makes what the buffer holds its base layer ([`FragmentBuffer::restore`] returns to
    /// it).
    pub fn commit(&mut self) {
        self.base = BaseLayer {
            depth: self.opaque_depth.clone(),
            order: self.opaque_order.clone(),
            color: self.opaque_color.clone(),
            transparent: self.transparent.iter().map(|t| t.len() as u32).collect(),
        };
        self.dirty.fill(Span::EMPTY);
    }

    /// Per row of the band (top to bottom), the columns changed since the last commit or
    /// restore: every pixel outside them holds its base layer.
    pub fn dirty(&self) -> &[Span] {
        &self.dirty
    }

    /// Returns every changed span to the base layer (a row span at a time).
    pub fn restore(&mut self) {
        let w = self.width as usize;
        for (r, span) in self.dirty.iter_mut().enumerate() {
            let cols = span.columns();
            *span = Span::EMPTY;
            if cols.is_empty() {
                continue;
            }
            let px = r * w + cols.start..r * w + cols.end;
            let base = &self.base;
            if base.depth.is_empty() {
                self.opaque_depth[px.clone()].fill(f64::INFINITY);
                self.opaque_order[px.clone()].fill(0);
                self.opaque_color[px.clone()].fill([0.0; 3]);
                for t in &mut self.transparent[px] {
                    t.clear();
                }
            } else {
                self.opaque_depth[px.clone()].copy_from_slice(&base.depth[px.clone()]);
                self.opaque_order[px.clone()].copy_from_slice(&base.order[px.clone()]);
                self.opaque_color[px.clone()].copy_from_slice(&base.color[px.clone()]);
                for (t, &n) in self.transparent[px.clone()]
                    .iter_mut()
                    .zip(&base.transparent[px])
                {
                    t.truncate(n as usize);
                }
            }
        }
    }

    /// Rasterises `tri` (placed at normalised time `t`) into the band, shading with `scene`
    /// at `t`; fragments beyond `far` are dropped. The pixels it changes join their row's
    /// dirty span.
    pub fn draw(&mut self, scene: &PreparedScene, tri: &ScreenTriangle, t: f64) {
        let lit = scene
            .triangles
            .get(tri.order as usize)
            .filter(|p| scene.is_lit(p.material));
        // Set up on the first lit fragment, for all of them ([`PreparedScene::shade_surface`]
        // with the track shared).
        let mut track = None;
        let (row0, row1) = (self.row0, self.row0 + self.rows);
        let far = scene.far;
        tri.rasterise(row0, row1, |x, y, frag| {
            if frag.depth > far {
                return;
            }
            let r = (y - row0) as usize;
            let i = r * self.width as usize + x as usize;
            let (od, oo) = (self.opaque_depth[i], self.opaque_order[i]);
            // LESS_EQUAL in insertion order: an exact tie goes to the later triangle, whatever
            // order the triangles are drawn in (static ones are drawn once, first).
            let passes = frag.depth < od || (frag.depth == od && tri.order >= oo);
            if tri.opaque && !passes {
                return;
            }
            let c = match lit {
                Some(p) => track
                    .get_or_insert_with(|| SurfaceTrack::new(scene, p, [t, t]))
                    .colour(frag.bary, t),
                None => scene.shade(tri.material, frag.uv),
            };
            if c[3] >= 1.0 {
                if !passes {
                    return;
                }
                self.opaque_depth[i] = frag.depth;
                self.opaque_order[i] = tri.order;
                self.opaque_color[i] = [c[0], c[1], c[2]];
            } else if c[3] > 0.0 {
                self.transparent[i].push((frag.depth, tri.order, c));
            } else {
                return;
            }
            let span = &mut self.dirty[r];
            span.start = span.start.min(x);
            span.end = span.end.max(x + 1);
        });
    }

    /// Resolves every pixel ([`FragmentBuffer::resolve_pixel`]); calls
    /// `f(index_in_band, rgb)`.
    pub fn resolve(&self, background: [f64; 3], mut f: impl FnMut(usize, [f64; 3])) {
        let mut list = Vec::new();
        for i in 0..self.opaque_depth.len() {
            f(i, self.resolve_pixel(i, background, &mut list));
        }
    }

    /// Resolves pixel `i` (index in the band): transparent fragments in front of the opaque
    /// surface, sorted nearest first (later order first on ties), blended front to back with
    /// premultiplied OVER, then the opaque colour or the background. `list` is scratch
    /// space.
    #[inline]
    pub fn resolve_pixel(
        &self,
        i: usize,
        background: [f64; 3],
        list: &mut Vec<Transparent>,
    ) -> [f64; 3] {
        let base = if self.opaque_depth[i].is_finite() {
            self.opaque_color[i]
        } else {
            background
        };
        if self.transparent[i].is_empty() {
            base
        } else {
            self.blend(i, base, list)
        }
    }

    /// [`FragmentBuffer::resolve_pixel`] of a pixel with transparent fragments over `base`.
    #[inline(never)]
    fn blend(&self, i: usize, base: [f64; 3], list: &mut Vec<Transparent>) -> [f64; 3] {
        let (od, oo) = (self.opaque_depth[i], self.opaque_order[i]);
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
        [
            acc[0] + k * base[0],
            acc[1] + k * base[1],
            acc[2] + k * base[2],
        ]
    }
}
