//! The static path: the scene at one instant of the shutter, rendered the ordinary way —
//! one rasteriser ([`raster`]: placement at time t by linear 2DH motion, Gribel 2010 Eq. 2,
//! coverage at pixel centres with a shared-edge tie rule, perspective-correct attributes),
//! one near-plane clipper ([`clip`]), and per band of rows a fragment buffer
//! ([`fragments`]: LESS_EQUAL opaque depth, transparent fragments sorted and blended front
//! to back with premultiplied OVER). Splats are drawn as oriented discs ([`discs`]).
//!
//! It is the whole of a method's work for a scene where nothing moves ([`render`], taken by
//! `analytic`, `prism` and `stochastic` when nothing moves and nothing is transparent), one
//! sub-frame of `accum` ([`Exposure`] sums them with the shutter weights), and the
//! rasteriser the interval chain uses for static triangles and time slices
//! ([`crate::chain`]).

pub mod clip;
pub mod discs;
pub mod fragments;
pub mod raster;

use rayon::prelude::*;

pub use self::discs::{SPLAT_DISC_SIDES, splats_as_discs};
pub use self::fragments::{FragmentBuffer, Span, Transparent};
pub use self::raster::{
    Fragment, PixelBounds, ScreenTriangle, Target, pixel_bounds, setup, setup_corners,
};
use crate::bands::Bins;
use crate::image::Image;
use crate::prepared::PreparedScene;
use crate::progress::Progress;

/// Rows per parallel band.
pub(crate) const BAND_ROWS: u32 = 8;

/// The static path as the methods take it for a scene where nothing moves: one static
/// render at mid-shutter ([`render_at`]), reported as one progress step.
pub fn render(scene: &PreparedScene, progress: &dyn Progress) -> Image {
    progress.start(1, "static frames");
    let image = render_at(scene, 0.5);
    progress.advance(1);
    progress.finish();
    image
}

/// One static render at time `t`, as linear RGB (splats drawn as discs).
pub fn render_at(scene: &PreparedScene, t: f64) -> Image {
    let scene = splats_as_discs(scene);
    let all: Vec<u32> = (0..scene.triangles.len() as u32).collect();
    let mut exposure = Exposure::new(&scene);
    exposure.add(&all, t, 1.0);
    exposure.image()
}

/// One band of rows of an [`Exposure`]: its fragments (the base layer between renders),
/// the base layer's resolved colour per pixel and the resolve's scratch list.
struct Band {
    fragments: FragmentBuffer,
    base: Vec<[f64; 3]>,
    list: Vec<Transparent>,
}

/// Static renders summed with weights (`accum`'s sub-frames) over a base layer drawn once
/// ([`Exposure::set_base`]; empty unless set): per band of rows, a fragment buffer holding
/// the base layer and the base layer's resolved colours. A render draws its triangles over
/// the base, resolves only each row's dirty span (the columns its triangles changed; the
/// other pixels keep the base colour), adds the weighted colours to the sum and returns the
/// dirty spans to the base ([`FragmentBuffer::restore`]): where the triangles cover little
/// of a row this costs what they cover, where they cover a whole row one copy of it. The
/// screen triangles and their bins are set up in buffers reused from render to render
/// (`FrameTriangles`). The scene's splats must already be discs ([`splats_as_discs`]).
pub struct Exposure<'a> {
    scene: &'a PreparedScene,
    bands: Vec<Band>,
    sum: Vec<[f64; 3]>,
    frame: FrameTriangles,
}

impl<'a> Exposure<'a> {
    /// An empty exposure of `scene`'s image over an empty base layer.
    pub fn new(scene: &'a PreparedScene) -> Self {
        let bands = (0..scene.height.div_ceil(BAND_ROWS))
            .map(|b| {
                let row0 = b * BAND_ROWS;
                let rows = BAND_ROWS.min(scene.height - row0);
                let pixels = (scene.width * rows) as usize;
                Band {
                    fragments: FragmentBuffer::new(scene.width, row0, rows),
                    base: vec![scene.background; pixels],
                    list: Vec::new(),
                }
            })
            .collect();
        Exposure {
            scene,
            bands,
            sum: vec![[0.0f64; 3]; scene.width as usize * scene.height as usize],
            frame: FrameTriangles::default(),
        }
    }

    /// Draws triangles `which` at time `t` into the base layer every later render starts
    /// from ([`Exposure::add`]), so triangles that never move are rasterised and resolved
    /// once.
    pub fn set_base(&mut self, which: &[u32], t: f64) {
        let scene = self.scene;
        self.frame.set_up(scene, which, t);
        draw(scene, &self.frame, t, &mut self.bands);
        self.bands.par_iter_mut().for_each(|band| {
            band.fragments.commit();
            let Band {
                fragments, base, ..
            } = band;
            fragments.resolve(scene.background, |i, c| {
                if let Some(b) = base.get_mut(i) {
                    *b = c;
                }
            });
        });
    }

    /// Renders triangles `which` at time `t` over the base layer and adds the resolved
    /// render times `weight`.
    pub fn add(&mut self, which: &[u32], t: f64, weight: f64) {
        let scene = self.scene;
        self.frame.set_up(scene, which, t);
        draw(scene, &self.frame, t, &mut self.bands);
        let w = scene.width as usize;
        let band_pixels = w * BAND_ROWS as usize;
        self.bands
            .par_iter_mut()
            .zip(self.sum.par_chunks_mut(band_pixels))
            // One band per job, as in `draw`.
            .with_max_len(1)
            .for_each(|(band, out)| {
                let Band {
                    fragments,
                    base,
                    list,
                } = band;
                let rows = out.chunks_mut(w).zip(base.chunks(w));
                for (r, ((out, base), span)) in rows.zip(fragments.dirty()).enumerate() {
                    // Outside the dirty span the pixels hold the base layer.
                    let (a, b) = (span.columns().start, span.columns().end);
                    let (out, tail) = out.split_at_mut(b);
                    let (head, dirty) = out.split_at_mut(a);
                    add_weighted(head, &base[..a], weight);
                    for (x, o) in (a..b).zip(dirty) {
                        let c = fragments.resolve_pixel(r * w + x, scene.background, list);
                        for k in 0..3 {
                            o[k] += weight * c[k];
                        }
                    }
                    add_weighted(tail, &base[b..], weight);
                }
                fragments.restore();
            });
    }

    /// The sum as an image (non-finite values as 0).
    pub fn image(&self) -> Image {
        Image {
            width: self.scene.width,
            height: self.scene.height,
            pixels: self
                .sum
                .iter()
                .map(|p| p.map(|c| if c.is_finite() { c as f32 } else { 0.0 }))
                .collect(),
        }
    }
}

/// `out += weight * colours`, pixel by pixel.
fn add_weighted(out: &mut [[f64; 3]], colours: &[[f64; 3]], weight: f64) {
    for (o, c) in out
        .as_flattened_mut()
        .iter_mut()
        .zip(colours.as_flattened())
    {
        *o += weight * c;
    }
}

/// Rasterises `frame`'s triangles (placed at time `t`) into the bands, over what they hold.
fn draw(scene: &PreparedScene, frame: &FrameTriangles, t: f64, bands: &mut [Band]) {
    bands
        .par_iter_mut()
        .zip(frame.bins().all().par_iter())
        // One band per job: bands cost very different amounts (moving triangles crowd a
        // few), and a thread that runs out of work can only steal whole jobs.
        .with_max_len(1)
        .for_each(|(band, bin)| {
            for &i in bin {
                if let Some(st) = frame.get(i) {
                    band.fragments.draw(scene, st, t);
                }
            }
        });
}

/// Source triangles per chunk of [`FrameTriangles::set_up`]'s parallel setup.
const SETUP_CHUNK: usize = 512;

/// The screen triangles of one instant and the bands of [`BAND_ROWS`] rows each touches, in
/// buffers reused from instant to instant (`accum` sets up its moving triangles once per
/// sub-frame). Items are numbered in setup order: by source triangle in the order given,
/// then by clipped piece.
#[derive(Debug, Default)]
pub(crate) struct FrameTriangles {
    /// The screen triangles of each [`SETUP_CHUNK`] source triangles.
    chunks: Vec<Vec<ScreenTriangle>>,
    /// Per item: its chunk and place in the chunk.
    index: Vec<(u32, u32)>,
    bins: Bins,
}

impl FrameTriangles {
    /// Triangles `which` set up at time `t` ([`FrameTriangles::set_up`]).
    pub(crate) fn of(scene: &PreparedScene, which: &[u32], t: f64) -> Self {
        let mut frame = FrameTriangles::default();
        frame.set_up(scene, which, t);
        frame
    }

    /// Triangles `which` placed at time `t` on their true paths (each object's path
    /// transform computed once, [`PreparedScene::corners_at_instant`]), clipped and set up
    /// (each screen triangle's `order` is its triangle index), and binned by band; the
    /// buffers' allocations are reused.
    pub(crate) fn set_up(&mut self, scene: &PreparedScene, which: &[u32], t: f64) {
        let target = Target::of(scene);
        let instant = scene.instant(t);
        self.chunks
            .resize_with(which.len().div_ceil(SETUP_CHUNK), Vec::new);
        self.chunks
            .par_iter_mut()
            .zip(which.par_chunks(SETUP_CHUNK))
            .for_each(|(out, ids)| {
                out.clear();
                for &i in ids {
                    let tri = scene.triangles.get(i as usize);
                    debug_assert!(tri.is_some(), "triangle {i} out of range");
                    if let Some(tri) = tri.filter(|tri| tri.exists_at(t)) {
                        let corners = scene.corners_at_instant(tri, &instant);
                        let opaque = scene.is_opaque(tri.material);
                        setup_corners(tri, corners, i, opaque, &target, out);
                    }
                }
            });
        self.index.clear();
        for (c, chunk) in self.chunks.iter().enumerate() {
            self.index
                .extend((0..chunk.len() as u32).map(|k| (c as u32, k)));
        }
        let chunks = &self.chunks;
        self.bins.refill(
            scene.height,
            BAND_ROWS,
            chunks.iter().flatten().map(|st| (st.y0, st.y1)),
        );
    }

    /// Screen triangle number `item` (setup order).
    pub(crate) fn get(&self, item: u32) -> Option<&ScreenTriangle> {
        let &(c, k) = self.index.get(item as usize)?;
        self.chunks.get(c as usize)?.get(k as usize)
    }

    /// The items of each band of [`BAND_ROWS`] rows.
    pub(crate) fn bins(&self) -> &Bins {
        &self.bins
    }
}
