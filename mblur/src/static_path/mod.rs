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
pub use self::fragments::FragmentBuffer;
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
    exposure.add(&all, t, 1.0, None);
    exposure.image()
}

/// Static renders summed with weights (`accum`'s sub-frames): the frame's fragment buffers,
/// one per band of rows, reused from render to render, and the weighted sum of the resolved
/// renders. The scene's splats must already be discs ([`splats_as_discs`]).
pub struct Exposure<'a> {
    scene: &'a PreparedScene,
    bands: Vec<FragmentBuffer>,
    sum: Vec<[f64; 3]>,
}

impl<'a> Exposure<'a> {
    /// An empty exposure of `scene`'s image.
    pub fn new(scene: &'a PreparedScene) -> Self {
        Exposure {
            scene,
            bands: make_bands(scene),
            sum: vec![[0.0f64; 3]; scene.width as usize * scene.height as usize],
        }
    }

    /// Fresh fragment buffers holding triangles `which` at time `t`: a base layer that
    /// renders may start from ([`Exposure::add`]), so triangles that never move are
    /// rasterised once.
    pub fn layer(&self, which: &[u32], t: f64) -> Vec<FragmentBuffer> {
        let mut bands = make_bands(self.scene);
        draw(self.scene, which, t, &mut bands, None);
        bands
    }

    /// Renders triangles `which` at time `t` over `base` (or over nothing) and adds the
    /// resolved render times `weight`.
    pub fn add(&mut self, which: &[u32], t: f64, weight: f64, base: Option<&[FragmentBuffer]>) {
        draw(self.scene, which, t, &mut self.bands, base);
        let band_pixels = (self.scene.width * BAND_ROWS) as usize;
        let background = self.scene.background;
        self.bands
            .par_iter()
            .zip(self.sum.par_chunks_mut(band_pixels))
            .for_each(|(band, out)| {
                band.resolve(background, |i, c| {
                    if let Some(o) = out.get_mut(i) {
                        for k in 0..3 {
                            o[k] += weight * c[k];
                        }
                    }
                });
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

fn make_bands(scene: &PreparedScene) -> Vec<FragmentBuffer> {
    (0..scene.height.div_ceil(BAND_ROWS))
        .map(|b| {
            let row0 = b * BAND_ROWS;
            FragmentBuffer::new(scene.width, row0, BAND_ROWS.min(scene.height - row0))
        })
        .collect()
}

/// Resets every band (to `base` or empty) and rasterises triangles `which` at time `t`.
fn draw(
    scene: &PreparedScene,
    which: &[u32],
    t: f64,
    bands: &mut [FragmentBuffer],
    base: Option<&[FragmentBuffer]>,
) {
    let (tris, bins) = screen_triangles(scene, which, t);
    bands
        .par_iter_mut()
        .zip(bins.all().par_iter())
        .enumerate()
        .for_each(|(k, (band, bin))| {
            match base.and_then(|b| b.get(k)) {
                Some(b) => band.reset_from(b),
                None => band.clear(),
            }
            for &i in bin {
                band.draw(scene, &tris[i as usize], t);
            }
        });
}

/// Triangles `which` placed at time `t`, clipped and set up (each screen triangle's
/// `order` is its triangle index), and the screen triangles of each band of
/// [`BAND_ROWS`] rows.
pub(crate) fn screen_triangles(
    scene: &PreparedScene,
    which: &[u32],
    t: f64,
) -> (Vec<ScreenTriangle>, Bins) {
    let target = Target::of(scene);
    let tris: Vec<ScreenTriangle> = which
        .par_iter()
        .fold(Vec::new, |mut v, &i| {
            let tri = scene.triangles.get(i as usize);
            debug_assert!(tri.is_some(), "triangle {i} out of range");
            if let Some(tri) = tri.filter(|tri| tri.exists_at(t)) {
                let corners = scene.corners_at(tri, t);
                setup_corners(
                    tri,
                    corners,
                    i,
                    scene.is_opaque(tri.material),
                    &target,
                    &mut v,
                );
            }
            v
        })
        .reduce(Vec::new, |mut a, mut b| {
            a.append(&mut b);
            a
        });
    let bins = Bins::new(
        scene.height,
        BAND_ROWS,
        tris.iter().map(|st| (st.y0, st.y1)),
    );
    (tris, bins)
}
