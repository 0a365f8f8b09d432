//! The `stochastic` method: hierarchical stochastic motion-blur rasterisation (raster-hier,
//! Munkberg et al. 2011, §3-4, §7) with time-ordered (0, m, 3)-net samples (tmsnet,
//! Munkberg 2011 §5) — S samples per pixel, each at its own sub-pixel position and time.
//!
//! Every opaque triangle becomes an edge-eqn `MovingTriangle` from its 2DH corners at the
//! start and end of its span with the view depths as depth attribute, over that span of the
//! shutter (raster-hier's `RasterTriangle::span`): the segments of curved motion
//! ([`crate::PreparedTriangle::span`]) each take only the samples whose time they hold, so
//! the samples follow the arc through the segments' ends. Static triangles are rasterised
//! first with the OUR traversal (their tile test is an ordinary static one; INTERLEAVE would
//! visit them once per sample time), moving ones then with the chosen [`TraversalChoice`];
//! both passes write the same multisampled depth / id buffer (LESS_EQUAL, later triangle
//! wins an exact tie). The pixel is the mean of its samples (box filter, weighted by the
//! shutter response w(t) of each sample's time when the response is not a box), where a
//! sample takes the colour of the nearest triangle it hit — flat materials directly, textured
//! ones at the perspective-correct UV from edge-eqn's `barycentrics_at(x, y, t)` — and the
//! background where it hit nothing or only geometry beyond the far plane.
//!
//! Limits (each a clear [`Error::MethodNotApplicable`], never a silent substitute):
//! transparent materials (the buffer keeps one surface per sample), and moving triangles
//! that cross the near plane during the shutter (static ones are clipped by the static
//! path's clipper, [`crate::static_path::clip`]). Splats are drawn as the same oriented
//! 16-sided discs `accum` draws ([`crate::static_path::splats_as_discs`]). A scene where
//! nothing moves, sampled at the pixel centres, takes the static path
//! ([`crate::static_path::render`]).
//!
//! The options (traversal, samples per pixel, sample passes) are in `options.rs`; the
//! triangles handed to raster-hier and the shading of their samples in `triangles.rs`.

mod filter;
mod options;
mod triangles;

use raster_hier::{
    Counters, EdgeTest, Footprint, RasterConfig, RasterTriangle, SampleBuffer, Traversal, rasterise,
};

use self::filter::SampleFilter;
pub use self::options::{StochasticOptions, TraversalChoice, buffer_pixels, passes};
use self::triangles::{Input, inputs, raster_triangle, resolve, shading};
use crate::effects::{Effects, Pipeline};
use crate::error::{Error, Result};
use crate::image::Image;
use crate::prepared::PreparedScene;
use crate::progress::Progress;
use crate::static_path::splats_as_discs;

/// Samples per pixel when `--spp` is not given.
pub const DEFAULT_SPP: u32 = 16;
/// Largest accepted `--spp`.
pub const MAX_SPP: u32 = 1024;
/// Largest sample buffer (padded width × padded height × spp per pass, see
/// [`buffer_pixels`]): 2^27 samples, 1.5 GiB of f64 depth and u32 id. More samples are
/// taken in several passes ([`passes`]).
pub const MAX_SAMPLES: u64 = 1 << 27;
/// Finest tile (and sample-pattern tile) in pixels (Munkberg 2011, §7: 16 → 8 → 4).
pub const TILE: u32 = 4;
/// Coarsest tile (the bin one thread owns) in pixels.
pub const BIN: u32 = 16;
/// Time slices of the z-max per finest tile (Munkberg 2011, §7 time-dependent occlusion).
pub const ZMAX_SLICES: u32 = 8;

/// What one stochastic render did: the image and the cost counters of both passes.
#[derive(Debug, Clone)]
pub struct StochasticRender {
    /// The linear RGB image.
    pub image: Image,
    /// Samples per pixel used (over all passes).
    pub spp: u32,
    /// Sample passes the samples were split into (1 unless the buffer would exceed
    /// [`MAX_SAMPLES`]).
    pub passes: u32,
    /// Cost of the static pass (static triangles, OUR traversal).
    pub static_counters: Counters,
    /// Cost of the moving pass (moving triangles, the chosen traversal).
    pub moving_counters: Counters,
    /// Static triangles handed to the rasteriser (after near-plane clipping).
    pub static_triangles: usize,
    /// Moving triangles handed to the rasteriser.
    pub moving_triangles: usize,
}

fn not_applicable(reason: String) -> Error {
    Error::MethodNotApplicable {
        method: "stochastic".into(),
        reason,
    }
}

/// Checks that the stochastic method can render `scene`: no transparent surface (the sample
/// buffer keeps one nearest surface per sample). The error names the transparent objects.
pub fn check(scene: &PreparedScene) -> Result<()> {
    let effects = Effects::analyse(scene);
    let transparent: Vec<&str> = effects
        .objects
        .iter()
        .filter(|o| o.transparent)
        .map(|o| o.name.as_str())
        .collect();
    if transparent.is_empty() {
        Ok(())
    } else {
        Err(not_applicable(format!(
            "transparency is not supported (one nearest surface per sample; the analytic, \
             prism and accum methods render it); transparent objects: {}",
            transparent.join(", ")
        )))
    }
}

fn raster_error(e: raster_hier::Error) -> Error {
    not_applicable(format!("rasteriser configuration: {e}"))
}

/// Renders `scene` with S samples per pixel and returns the image and the cost counters.
/// With [`Footprint::Area`] and a filter wider than the pixel's box, every sample counts in
/// each pixel whose filter support holds it (`filter.rs`), the scene rendered into a buffer
/// grown by the filter's reach.
///
/// When W x H x S exceeds [`MAX_SAMPLES`], the samples are taken in P passes of S / P each
/// (P the smallest power of two that fits), pass k with its own pattern scramble (seed
/// `seed + k`), and the P images are averaged: the same unbiased estimator with S samples
/// per pixel, each pass stratified on its own. Reports three progress steps per pass
/// (static triangles, moving triangles, resolve).
pub fn render(
    scene: &PreparedScene,
    opts: &StochasticOptions,
    progress: &dyn Progress,
) -> Result<StochasticRender> {
    opts.validate()?;
    let spp = opts.spp()?;
    check(scene)?;
    let out = (scene.width, scene.height);
    // A filter wider than the pixel's box reads samples beyond the image's border.
    let filter = SampleFilter::new(opts.filter, opts.filter_radius(), scene);
    let padded;
    let scene = match &filter {
        Some(f) => {
            padded = f.padded(scene);
            &padded
        }
        None => scene,
    };
    let passes = opts.passes(scene.width, scene.height)?;
    let scene = &splats_as_discs(scene);
    let (fixed, moving) = inputs(scene)?;
    // Per pass: the static triangles, the moving triangles, the resolve.
    progress.start(3 * u64::from(passes), "raster stages");
    let mut shade = Vec::with_capacity(fixed.len() + moving.len());
    let tris = |list: &[Input], base: usize| -> Vec<RasterTriangle<f64>> {
        list.iter()
            .enumerate()
            .map(|(i, t)| raster_triangle(t, (base + i) as u32))
            .collect()
    };
    let fixed_tris = tris(&fixed, 0);
    let moving_tris = tris(&moving, fixed.len());
    for (t, r) in fixed
        .iter()
        .zip(&fixed_tris)
        .chain(moving.iter().zip(&moving_tris))
    {
        shade.push(shading(scene, t, r));
    }
    let (mut static_counters, mut moving_counters) = (Counters::default(), Counters::default());
    // The sum of the passes' images (0 + x is x exactly: one pass keeps its bits).
    let mut image = Image::filled(out.0, out.1, [0.0; 3]);
    for pass in 0..passes {
        let mut buf = SampleBuffer::<f64>::new(
            scene.width,
            scene.height,
            spp / passes,
            TILE,
            BIN,
            ZMAX_SLICES,
            opts.seed.wrapping_add(u64::from(pass)),
        )
        .map_err(raster_error)?
        .with_footprint(opts.footprint);
        let mut draw = |tris: &[RasterTriangle<f64>], config: RasterConfig| -> Result<Counters> {
            let c = if tris.is_empty() {
                Counters::default()
            } else {
                rasterise(&mut buf, tris, &config).map_err(raster_error)?
            };
            progress.advance(1);
            Ok(c)
        };
        static_counters += draw(
            &fixed_tris,
            RasterConfig::new(Traversal::Our(EdgeTest::LinearisedSetup)),
        )?;
        moving_counters += draw(&moving_tris, opts.traversal.config())?;
        let pass_image = resolve(scene, &buf, &shade, filter.as_ref());
        progress.advance(1);
        for (a, p) in image.pixels.iter_mut().zip(&pass_image.pixels) {
            for (ac, pc) in a.iter_mut().zip(p) {
                *ac += pc;
            }
        }
    }
    progress.finish();
    if passes > 1 {
        let inv = 1.0 / passes as f32;
        for c in image.pixels.iter_mut().flatten() {
            *c *= inv;
        }
    }
    Ok(StochasticRender {
        image,
        spp,
        passes,
        static_counters,
        moving_counters,
        static_triangles: fixed.len(),
        moving_triangles: moving.len(),
    })
}

/// One line per pass with the raster-hier cost counters (Munkberg 2011, §8, Table 2).
pub fn counters_summary(r: &StochasticRender) -> String {
    let line = |name: &str, n: usize, c: &Counters| {
        format!(
            "{name}: {n} triangles ({} set up, {} culled, {} fallbacks), {} tile tests, {} sample \
             tests, {} depth tests, {} samples written, {} z-max culls, ~{} ops",
            c.triangles_set_up,
            c.frustum_culled + c.backface_culled,
            c.fallbacks,
            c.tile_tests,
            c.sample_tests,
            c.depth_tests,
            c.samples_written,
            c.zmax_culls,
            c.arithmetic
        )
    };
    let passes = if r.passes > 1 {
        format!(
            "\nsamples taken in {} passes of {} per pixel (counters summed over them)",
            r.passes,
            r.spp / r.passes
        )
    } else {
        String::new()
    };
    format!(
        "{}\n{}{passes}",
        line("static pass", r.static_triangles, &r.static_counters),
        line("moving pass", r.moving_triangles, &r.moving_counters)
    )
}

impl StochasticOptions {
    /// True when this render is exactly the static path: nothing moves (and nothing is
    /// transparent) and every sample sits at its pixel centre ([`Footprint::Centre`]), so
    /// all S samples of a pixel see the same surface. Mission 3: a static scene costs what
    /// the static rasteriser costs, at any `spp`. (With [`Footprint::Area`] the samples
    /// spread over the pixel and the image is the box-filtered one: no shortcut.) The image
    /// is then the static rasteriser's, with the tie rules accum and analytic use (a pixel
    /// centre exactly on a shared edge goes to one triangle, zero-area triangles draw
    /// nothing); the sampled path counts a centre on an edge as inside, so the two differ
    /// only on such exact ties.
    fn takes_static_path(&self, pipeline: &Pipeline) -> bool {
        self.footprint == Footprint::Centre && !pipeline.interval_storage
    }

    /// One line saying what the method will do for this pipeline.
    pub fn describe(&self, scene: &PreparedScene, pipeline: &Pipeline) -> String {
        let spp = self.spp.unwrap_or(DEFAULT_SPP);
        if self.takes_static_path(pipeline) {
            return format!(
                "stochastic: nothing moves and the samples sit at the pixel centre, so all {spp} \
                 sample{} of a pixel would see the same surface: the static path (no sample \
                 buffer)",
                if spp == 1 { "" } else { "s" }
            );
        }
        let mut parts = vec![format!(
            "stochastic: {spp} sample{} per pixel (tmsnet, seed {}, {}), {} traversal for \
             moving triangles",
            if spp == 1 { "" } else { "s" },
            self.seed,
            match self.footprint {
                Footprint::Area => "spread over the pixel",
                Footprint::Centre => "at the pixel centre",
            },
            self.traversal
        )];
        if scene
            .objects
            .iter()
            .chain(&scene.splat_objects)
            .any(|o| o.segments > 1)
        {
            parts.push(
                "curved motion as segments, each a raster triangle over its own part of the \
                 shutter"
                    .to_string(),
            );
        }
        if self.footprint == Footprint::Area
            && SampleFilter::new(self.filter, self.filter_radius(), scene).is_some()
        {
            parts.push(format!(
                "{} filter of radius {} px over the samples of neighbouring pixels",
                self.filter,
                self.filter_radius()
            ));
        }
        if let Ok(p) = self.passes(scene.width, scene.height)
            && p > 1
        {
            parts.push(format!(
                "{p} passes of {} samples per pixel (a pass holds at most {} samples)",
                spp / p,
                self.pass_limit()
            ));
        }
        if pipeline.static_path {
            parts.push("static triangles through the OUR static tile test".into());
        }
        if pipeline.textures {
            parts.push("perspective-correct texture lookups per sample".into());
        }
        if !scene.shutter.is_box() {
            parts.push("samples weighted by the shutter response".into());
        }
        if pipeline.splats {
            parts.push("splats drawn as 16-sided discs".into());
        }
        parts.join("; ")
    }

    /// Renders with these options and says what it cost (raster-hier's counters, or that the
    /// static path took no samples).
    pub fn run(
        &self,
        scene: &PreparedScene,
        pipeline: &Pipeline,
        progress: &dyn Progress,
    ) -> Result<(Image, String)> {
        if self.takes_static_path(pipeline) {
            // The options are checked as the sampled path checks them.
            self.passes(scene.width, scene.height)?;
            let image = crate::static_path::render(scene, progress);
            return Ok((image, "static path: no samples taken".into()));
        }
        let r = render(scene, self, progress)?;
        let summary = counters_summary(&r);
        Ok((r.image, summary))
    }
}
