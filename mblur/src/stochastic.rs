//! The `stochastic` method: hierarchical stochastic motion-blur rasterisation (raster-hier,
//! Munkberg et al. 2011, §3-4, §7) with time-ordered (0, m, 3)-net samples (tmsnet,
//! Munkberg 2011 §5) — S samples per pixel, each at its own sub-pixel position and time.
//!
//! Every opaque triangle becomes an edge-eqn `MovingTriangle` from its 2DH corners at shutter
//! open and close with the view depths as depth attribute. Static triangles are rasterised
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
//! that cross the near plane during the shutter (static ones are clipped like `accum` clips
//! them). Splats are drawn as the same oriented 16-sided discs `accum` draws
//! ([`crate::accum::splats_as_discs`]).

use std::fmt;
use std::str::FromStr;
use std::sync::Mutex;

use edge_eqn::{MovingTriangle, TriangleSetup};
use glam::DVec2;
use raster_hier::{
    Counters, EdgeTest, Footprint, NO_HIT, RasterConfig, RasterTriangle, SampleBuffer, Traversal,
    rasterise,
};

use crate::accum::{self, splats_as_discs};
use crate::camera::Vertex2dh;
use crate::effects::{Effects, Pipeline};
use crate::error::{Error, Result};
use crate::image::Image;
use crate::prepared::PreparedScene;
use crate::progress::Progress;

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

/// The traversal of moving triangles, as chosen with `--traversal` (Munkberg 2011, Table 1).
/// All produce bit-identical images for the same seed; only their cost differs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum TraversalChoice {
    /// OUR: tile tests with temporal bounds, linearised edge test with γ at setup (Eq. 4-9).
    Our,
    /// OUR with the exact edge test (a quadratic per tile corner).
    OurExact,
    /// OUR with the linearised edge test, γ per coarse tile.
    OurPerTile,
    /// OUR with the linearised edge test re-derived per tile at every level, down to 2x2
    /// quads and single pixels below the 4x4 sample-pattern tile (raster-hier's
    /// `RasterConfig::fine()`): the fewest sample tests, more tile tests.
    OurFine,
    /// BBOX: every sample in the swept bounding box.
    Bbox,
    /// CONVEX: tiles against the convex hull of the six projected vertices.
    Convex,
    /// HIERARCHICAL INTERLEAVE: one static traversal per unique sample time.
    Interleave,
    /// OUR (linearised at setup) with the §7 fallback to INTERLEAVE for small, fast
    /// triangles (the default).
    #[default]
    Fallback,
}

impl TraversalChoice {
    /// All choices, in the order `--help` lists them.
    pub const ALL: [TraversalChoice; 8] = [
        TraversalChoice::Our,
        TraversalChoice::OurExact,
        TraversalChoice::OurPerTile,
        TraversalChoice::OurFine,
        TraversalChoice::Bbox,
        TraversalChoice::Convex,
        TraversalChoice::Interleave,
        TraversalChoice::Fallback,
    ];

    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            TraversalChoice::Our => "our",
            TraversalChoice::OurExact => "our-exact",
            TraversalChoice::OurPerTile => "our-per-tile",
            TraversalChoice::OurFine => "our-fine",
            TraversalChoice::Bbox => "bbox",
            TraversalChoice::Convex => "convex",
            TraversalChoice::Interleave => "interleave",
            TraversalChoice::Fallback => "fallback",
        }
    }

    /// The raster-hier traversal.
    pub fn traversal(self) -> Traversal {
        match self {
            TraversalChoice::Our => Traversal::Our(EdgeTest::LinearisedSetup),
            TraversalChoice::OurExact => Traversal::Our(EdgeTest::Exact),
            TraversalChoice::OurPerTile => Traversal::Our(EdgeTest::LinearisedPerTile),
            TraversalChoice::OurFine => Traversal::Our(EdgeTest::LinearisedPerLevel),
            TraversalChoice::Bbox => Traversal::Bbox,
            TraversalChoice::Convex => Traversal::Convex,
            TraversalChoice::Interleave => Traversal::Interleave,
            TraversalChoice::Fallback => Traversal::OurFallback(EdgeTest::LinearisedSetup),
        }
    }

    /// The raster-hier configuration: [`TraversalChoice::traversal`] over the levels
    /// 16 → 8 → 4, or 16 → 8 → 4 → 2 → 1 for [`TraversalChoice::OurFine`].
    pub fn config(self) -> RasterConfig {
        match self {
            TraversalChoice::OurFine => RasterConfig::fine(),
            other => RasterConfig::new(other.traversal()),
        }
    }
}

impl fmt::Display for TraversalChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for TraversalChoice {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        crate::method::parse_by_name(s, &TraversalChoice::ALL, TraversalChoice::name, "traversal")
    }
}

/// Options of the stochastic method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct StochasticOptions {
    /// Samples per pixel, a power of two in 1..=[`MAX_SPP`]; `None` = [`DEFAULT_SPP`].
    pub spp: Option<u32>,
    /// Traversal of the moving triangles.
    pub traversal: TraversalChoice,
    /// Seed of the per-tile sample-pattern scrambling.
    pub seed: u64,
    /// Where the samples lie in their pixel: spread over its area (spatial antialiasing,
    /// the default) or at its centre (the pixel-centre quantity accum, analytic and prism
    /// compute; `mblur compare` uses it so that errors measure the same thing).
    pub footprint: Footprint,
    /// Most samples one pass may hold, over [`buffer_pixels`] (its buffer costs 12 bytes a
    /// sample); `None` =
    /// [`MAX_SAMPLES`], larger values are capped to it. More samples per pixel than fit are
    /// taken in several passes ([`passes`]).
    pub max_pass_samples: Option<u64>,
}

impl StochasticOptions {
    /// The samples per pixel, checked: a power of two in 1..=[`MAX_SPP`].
    pub fn spp(&self) -> Result<u32> {
        let spp = self.spp.unwrap_or(DEFAULT_SPP);
        if spp == 0 || !spp.is_power_of_two() || spp > MAX_SPP {
            return Err(Error::Option {
                option: "--spp".into(),
                message: format!("must be a power of two between 1 and {MAX_SPP}, got {spp}"),
            });
        }
        Ok(spp)
    }

    /// The most samples one pass may hold: [`StochasticOptions::max_pass_samples`] capped
    /// to [`MAX_SAMPLES`].
    pub fn pass_limit(&self) -> u64 {
        self.max_pass_samples
            .map_or(MAX_SAMPLES, |l| l.min(MAX_SAMPLES))
    }

    /// The sample passes a `width` x `height` render takes with these options: [`passes`]
    /// with the checked [`StochasticOptions::spp`] and [`StochasticOptions::pass_limit`].
    pub fn passes(&self, width: u32, height: u32) -> Result<u32> {
        passes(width, height, self.spp()?, self.pass_limit())
    }
}

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

/// How a raster id is shaded.
enum Shading {
    /// Opaque flat colour (premultiplied = straight, alpha 1).
    Flat([f64; 3]),
    /// Textured: perspective-correct barycentrics from the setup, then the UV.
    Textured {
        setup: Box<TriangleSetup<f64>>,
        uv: [DVec2; 3],
        material: u32,
    },
}

/// A triangle ready for raster-hier: 2DH corners and depths at open and close, UVs, material.
struct Input {
    open: [Vertex2dh; 3],
    close: [Vertex2dh; 3],
    uv: [DVec2; 3],
    material: u32,
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
            "transparency is not supported (one nearest surface per sample); transparent \
             objects: {}",
            transparent.join(", ")
        )))
    }
}

/// Clips a static triangle to view depth >= near (the polygon of `accum`'s clipper,
/// interpolated in 2DH, which is linear in the world position), fanned into triangles.
fn clip_static(t: &Input, near: f64, out: &mut Vec<Input>) {
    let mut poly: arrayvec::ArrayVec<(Vertex2dh, DVec2), 4> = arrayvec::ArrayVec::new();
    for k in 0..3 {
        let (a, b) = (
            (t.open[k], t.uv[k]),
            (t.open[(k + 1) % 3], t.uv[(k + 1) % 3]),
        );
        let (ina, inb) = (a.0.depth >= near, b.0.depth >= near);
        if ina {
            poly.push(a);
        }
        if ina != inb {
            // Endpoints in a canonical order, so that a shared edge is cut at the identical
            // point in both triangles (no crack along the near plane).
            let key = |v: &Vertex2dh| [v.x, v.y, v.w, v.depth];
            let (p, q) = if key(&a.0) <= key(&b.0) {
                (a, b)
            } else {
                (b, a)
            };
            let s = (near - p.0.depth) / (q.0.depth - p.0.depth);
            let s = if s.is_finite() {
                s.clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut v = p.0.lerp(q.0, s);
            v.depth = near;
            poly.push((v, p.1 + (q.1 - p.1) * s));
        }
    }
    for k in 1..poly.len().saturating_sub(1) {
        let c = [poly[0], poly[k], poly[k + 1]];
        let open = c.map(|p| p.0);
        out.push(Input {
            open,
            close: open,
            uv: c.map(|p| p.1),
            material: t.material,
        });
    }
}

/// The opaque triangles of the scene split into static and moving lists, near-plane
/// handled: triangles entirely nearer than `near` or entirely beyond `far` during the whole
/// shutter are dropped, static triangles crossing `near` are clipped, moving ones crossing
/// it are an error naming the object.
fn inputs(scene: &PreparedScene) -> Result<(Vec<Input>, Vec<Input>)> {
    let (mut fixed, mut moving) = (Vec::new(), Vec::new());
    for tri in &scene.triangles {
        let depths = tri.open.iter().chain(&tri.close).map(|v| v.depth);
        let (lo, hi) = depths.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        });
        if hi < scene.near || lo > scene.far {
            continue;
        }
        let input = Input {
            open: tri.open,
            close: tri.close,
            uv: tri.uv,
            material: tri.material,
        };
        let is_moving = tri.is_moving();
        if lo >= scene.near {
            if is_moving {
                moving.push(input);
            } else {
                fixed.push(input);
            }
        } else if !is_moving {
            clip_static(&input, scene.near, &mut fixed);
        } else {
            let name = scene
                .objects
                .get(tri.object as usize)
                .map_or("?", |o| o.name.as_str());
            return Err(not_applicable(format!(
                "object \"{name}\" crosses the near plane (depth {lo} < near {}) while moving; \
                 moving triangles are rasterised unclipped",
                scene.near
            )));
        }
    }
    Ok((fixed, moving))
}

fn raster_triangle(t: &Input, id: u32) -> RasterTriangle<f64> {
    let xyw = |v: &Vertex2dh| [v.x, v.y, v.w];
    let triangle = MovingTriangle::new(t.open.each_ref().map(xyw), t.close.each_ref().map(xyw))
        .with_depth(t.open.map(|v| v.depth), t.close.map(|v| v.depth));
    RasterTriangle { triangle, id }
}

fn shading(scene: &PreparedScene, t: &Input, r: &RasterTriangle<f64>) -> Shading {
    let textured = scene
        .materials
        .get(t.material as usize)
        .is_some_and(|m| m.texture.is_some());
    if textured {
        Shading::Textured {
            setup: Box::new(r.triangle.setup()),
            uv: t.uv,
            material: t.material,
        }
    } else {
        let c = scene.shade(t.material, DVec2::ZERO);
        Shading::Flat([c[0], c[1], c[2]])
    }
}

fn raster_error(e: raster_hier::Error) -> Error {
    not_applicable(format!("rasteriser configuration: {e}"))
}

/// Renders `scene` with S samples per pixel and returns the image and the cost counters.
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
    let spp = opts.spp()?;
    let passes = opts.passes(scene.width, scene.height)?;
    check(scene)?;
    let scene = &splats_as_discs(scene);
    let (fixed, moving) = inputs(scene)?;
    progress.start(3 * u64::from(passes));
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
    let mut image = Image::filled(scene.width, scene.height, [0.0; 3]);
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
        let pass_image = resolve(scene, &buf, &shade);
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

/// The pixels a W x H sample buffer holds: raster-hier allocates whole [`BIN`] x [`BIN`]
/// bins, so each side is rounded up to a multiple of [`BIN`].
pub fn buffer_pixels(width: u32, height: u32) -> u64 {
    let padded = |n: u32| u64::from(n).div_ceil(u64::from(BIN)) * u64::from(BIN);
    padded(width) * padded(height)
}

/// Sample passes for W x H pixels at S samples (a power of two) with at most `limit`
/// samples a pass, counting the samples the buffer really holds (N = [`buffer_pixels`]):
/// 1 when N x S fits, else the smallest power of two P with N x S / P within it. An error
/// when even one sample per pixel does not fit.
pub fn passes(width: u32, height: u32, spp: u32, limit: u64) -> Result<u32> {
    let pixels = buffer_pixels(width, height);
    if pixels > limit || spp == 0 {
        // Below MAX_SAMPLES the limit was lowered by --max-pass-samples.
        let option = if limit < MAX_SAMPLES {
            "--max-pass-samples"
        } else {
            "--spp"
        };
        return Err(Error::Option {
            option: option.into(),
            message: format!(
                "{width} x {height} pixels ({pixels} in the sample buffer's whole \
                 {BIN}-pixel bins) x {spp} samples: a pass holds at most {limit} samples, not \
                 even 1 sample per pixel fits"
            ),
        });
    }
    let mut passes = 1u32;
    while pixels * u64::from(spp / passes) > limit {
        passes *= 2;
    }
    Ok(passes)
}

/// Box-filter resolve: per pixel the mean of its samples' colours (weighted by w(t) for a
/// non-box shutter response); background for samples that hit nothing or only geometry
/// beyond the far plane.
fn resolve(scene: &PreparedScene, buf: &SampleBuffer<f64>, shade: &[Shading]) -> Image {
    let (w, h) = (scene.width as usize, scene.height as usize);
    // Per pixel: weighted sum, weight, unweighted sum (fallback when all weights are zero).
    let mut acc = vec![([0.0f64; 3], 0.0f64, [0.0f64; 3]); w * h];
    let weighted = !scene.shutter.is_box();
    let far = scene.far;
    buf.for_each_sample(|px, py, x, y, t, depth, id| {
        let c = if id == NO_HIT || depth > far {
            scene.background
        } else {
            match shade.get(id as usize) {
                Some(Shading::Flat(c)) => *c,
                Some(Shading::Textured {
                    setup,
                    uv,
                    material,
                }) => {
                    let l = setup.barycentrics_at(x, y, t);
                    let st = uv[0] * l[0] + uv[1] * l[1] + uv[2] * l[2];
                    let c = scene.shade(*material, st);
                    [c[0], c[1], c[2]]
                }
                None => scene.background,
            }
        };
        let wt = if weighted {
            scene.shutter.weight(t)
        } else {
            1.0
        };
        if let Some(p) = acc.get_mut(py as usize * w + px as usize) {
            for ((sum, plain), ck) in p.0.iter_mut().zip(&mut p.2).zip(c) {
                *sum += wt * ck;
                *plain += ck;
            }
            p.1 += wt;
        }
    });
    let n = f64::from(buf.spp());
    Image {
        width: scene.width,
        height: scene.height,
        pixels: acc
            .iter()
            .map(|(sum, wsum, plain)| {
                let c: [f64; 3] = if *wsum > 0.0 {
                    sum.map(|v| v / wsum)
                } else {
                    plain.map(|v| v / n)
                };
                c.map(|v| if v.is_finite() { v as f32 } else { 0.0 })
            })
            .collect(),
    }
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

/// The `stochastic` method as a [`crate::Renderer`]; keeps the counters of its last render
/// for [`crate::Renderer::statistics`].
#[derive(Debug, Default)]
pub struct StochasticRenderer {
    /// Its options.
    pub options: StochasticOptions,
    last: Mutex<Option<String>>,
}

impl StochasticRenderer {
    /// A renderer with these options (checked: `--spp`).
    pub fn new(options: StochasticOptions) -> Result<Self> {
        options.spp()?;
        Ok(StochasticRenderer {
            options,
            last: Mutex::new(None),
        })
    }

    /// True when this render is exactly the static path: nothing moves (and nothing is
    /// transparent) and every sample sits at its pixel centre ([`Footprint::Centre`]), so
    /// all S samples of a pixel see the same surface. Mission 3: a static scene costs what
    /// the static rasteriser costs, at any `--spp`. (With [`Footprint::Area`] the samples
    /// spread over the pixel and the image is the box-filtered one: no shortcut.) The image
    /// is then the static rasteriser's, with the tie rules accum and analytic use (a pixel
    /// centre exactly on a shared edge goes to one triangle, zero-area triangles draw
    /// nothing); the sampled path counts a centre on an edge as inside, so the two differ
    /// only on such exact ties.
    fn takes_static_path(&self, pipeline: &Pipeline) -> bool {
        self.options.footprint == Footprint::Centre && !pipeline.interval_storage
    }
}

impl crate::method::Renderer for StochasticRenderer {
    fn name(&self) -> &'static str {
        "stochastic"
    }

    fn describe(&self, scene: &PreparedScene, pipeline: &Pipeline) -> String {
        let spp = self.options.spp.unwrap_or(DEFAULT_SPP);
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
            self.options.seed,
            match self.options.footprint {
                Footprint::Area => "spread over the pixel",
                Footprint::Centre => "at the pixel centre",
            },
            self.options.traversal
        )];
        if let Ok(p) = self.options.passes(scene.width, scene.height)
            && p > 1
        {
            parts.push(format!(
                "{p} passes of {} samples per pixel (a pass holds at most {} samples)",
                spp / p,
                self.options.pass_limit()
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

    fn render(
        &self,
        scene: &PreparedScene,
        pipeline: &Pipeline,
        progress: &dyn Progress,
    ) -> Result<Image> {
        if self.takes_static_path(pipeline) {
            // The options are checked as the sampled path checks them.
            self.options.passes(scene.width, scene.height)?;
            let image = accum::static_path(scene, progress)?;
            if let Ok(mut last) = self.last.lock() {
                *last = Some("static path: no samples taken".into());
            }
            return Ok(image);
        }
        let r = render(scene, &self.options, progress)?;
        if let Ok(mut last) = self.last.lock() {
            *last = Some(counters_summary(&r));
        }
        Ok(r.image)
    }

    fn statistics(&self) -> Option<String> {
        self.last.lock().ok().and_then(|l| l.clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn traversal_names_round_trip() {
        for t in TraversalChoice::ALL {
            assert_eq!(t.name().parse::<TraversalChoice>(), Ok(t));
        }
        assert!("zigzag".parse::<TraversalChoice>().is_err());
    }

    #[test]
    fn spp_must_be_a_power_of_two_in_range() {
        let o = |spp| StochasticOptions {
            spp: Some(spp),
            ..Default::default()
        };
        assert_eq!(StochasticOptions::default().spp().ok(), Some(DEFAULT_SPP));
        assert_eq!(o(64).spp().ok(), Some(64));
        for bad in [0, 3, 12, 2 * MAX_SPP] {
            assert!(o(bad).spp().is_err(), "{bad}");
        }
    }

    #[test]
    fn passes_split_only_what_does_not_fit() {
        // The compare scenes at 1024 spp: 640 x 360 (640 x 368 in whole bins) needs two
        // passes, 512 x 256 fits exactly.
        assert_eq!(passes(640, 360, 1024, MAX_SAMPLES).ok(), Some(2));
        assert_eq!(passes(512, 256, 1024, MAX_SAMPLES).ok(), Some(1));
        assert_eq!(passes(640, 360, 256, MAX_SAMPLES).ok(), Some(1));
        // The count is what raster-hier allocates.
        for (w, h, spp) in [(1u32, 1u32, 1u32), (17, 17, 4), (640, 360, 2), (4096, 1, 8)] {
            let b = SampleBuffer::<f64>::new(w, h, spp, TILE, BIN, ZMAX_SLICES, 0).unwrap();
            let held = buffer_pixels(w, h) * u64::from(spp);
            assert_eq!(b.depths().len() as u64, held, "{w}x{h}x{spp}");
            assert_eq!(b.ids().len() as u64, held, "{w}x{h}x{spp}");
        }
        // Exhaustively on small limits: the smallest power of two that fits.
        for limit in 1..=600u64 {
            for (w, h) in [(1u32, 1u32), (3, 5), (16, 16), (7, 20)] {
                let px = u64::from(w.div_ceil(16) * 16 * h.div_ceil(16) * 16);
                for spp in (0..=10).map(|k| 1u32 << k) {
                    match passes(w, h, spp, limit) {
                        Ok(p) => {
                            assert!(p.is_power_of_two() && p <= spp);
                            assert!(px * u64::from(spp / p) <= limit);
                            assert!(p == 1 || px * u64::from(spp / (p / 2)) > limit);
                        }
                        Err(e) => {
                            assert!(px > limit, "{w}x{h} {spp} {limit}");
                            assert!(e.to_string().contains("--max-pass-samples"), "{e}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn static_clip_keeps_the_part_beyond_near() {
        let v = |x: f64, depth: f64| Vertex2dh {
            x: x * depth,
            y: depth,
            w: depth,
            depth,
        };
        let t = Input {
            open: [v(0.0, 0.5), v(10.0, 2.0), v(0.0, 2.0)],
            close: [v(0.0, 0.5), v(10.0, 2.0), v(0.0, 2.0)],
            uv: [DVec2::ZERO, DVec2::X, DVec2::Y],
            material: 0,
        };
        let mut out = Vec::new();
        clip_static(&t, 1.0, &mut out);
        assert_eq!(out.len(), 2);
        for o in &out {
            assert!(o.open.iter().all(|v| v.depth >= 1.0));
            assert_eq!(o.open, o.close);
        }
        // Edge 0 -> 1 is cut at s = 1/3 (depth 0.5 -> 2 reaches 1), so uv = (1/3, 0); edge
        // 2 -> 0 at 1/3 of the way from vertex 0, uv = (0, 1/3).
        let cuts: Vec<DVec2> = out
            .iter()
            .flat_map(|o| o.open.iter().zip(o.uv))
            .filter(|(v, _)| v.depth == 1.0)
            .map(|(_, uv)| uv)
            .collect();
        assert!(
            cuts.iter()
                .any(|uv| (*uv - DVec2::new(1.0 / 3.0, 0.0)).length() < 1e-12)
        );
        assert!(
            cuts.iter()
                .any(|uv| (*uv - DVec2::new(0.0, 1.0 / 3.0)).length() < 1e-12)
        );
    }
}
