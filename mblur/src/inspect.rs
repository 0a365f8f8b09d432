//! The temporal pixel visualiser (Gribel 2010, §5.2.1): the intervals the `analytic`
//! method stores for one pixel, drawn as depth over shutter time, before and after the
//! compression to K intervals per pixel with the paper's oracle (§5.2, Eq. 19-20).
//!
//! [`pixel_intervals`] runs the analytic method's own primitive set-up and interval
//! emission for one pixel (the interval chain, [`crate::chain`], with edge-eqn, so the lists
//! are exactly what a render stores there), then builds both lists with the row pipeline a
//! render uses ([`crate::chain::row`]): the exact list (interval-buffer's counted, sorted
//! exact lists, Rønnow 2021 §4.1-4.2) and the bounded buffer of K slots with oracle
//! compression (Gribel 2010 §5.2), and resolves each with the render's resolve settings
//! (Eq. 17), keeping every partition of the sweep (the colour over time). `mblur-lab` draws
//! both panels with the resolved colour strips as SVG.
//!
//! Each interval carries the index of the triangle that left it (a tag that rides along
//! in the payload and never changes the colour, the oracle's distance or the opacity), so
//! the compressed list can say which intervals are merges of several.

use interval_buffer::Oracle;
use interval_buffer::{Interval, Payload};
use resolve::{Scratch, Shader};

use crate::chain::payload::{MakePayload, WithPayloads, with_payloads};
use crate::chain::prim::Sweep;
use crate::chain::row::{self, Buffering, Resolver, RowScratch};
use crate::chain::{self, MAX_INTERVALS};
use crate::effects::{Effects, Pipeline};
use crate::error::{Error, Result};
use crate::lighting::ShadingSamples;
use crate::prepared::PreparedScene;

/// The method whose lists are drawn (named in errors).
const METHOD: &str = "analytic";

/// The default number of intervals per pixel after compression (the paper's K = 4).
pub const DEFAULT_INTERVALS: u32 = 4;

/// One interval of a pixel, as drawn: Gribel 2010 Eq. 16 (linear depth over `[t0, t1]`).
#[derive(Debug, Clone, PartialEq)]
pub struct PixelInterval {
    /// Start time in the shutter, `[0, 1]`.
    pub t0: f32,
    /// End time (`>= t0`).
    pub t1: f32,
    /// View depth at `t0` (smaller is nearer).
    pub z0: f32,
    /// View depth at `t1`.
    pub z1: f32,
    /// Straight-alpha linear RGBA the resolve's shader gives at the middle of the interval
    /// (the flat colour, or the texture there).
    pub colour: [f32; 4],
    /// Index into [`PreparedScene::triangles`] of the triangle that left it (after
    /// compression: the first of the merged ones).
    pub triangle: u32,
    /// The object that triangle belongs to.
    pub object: String,
    /// Formed by the compression merging intervals (Gribel 2010, Eq. 20).
    pub merged: bool,
}

/// One partition Δ_k of the resolve sweep (Gribel 2010, §5.1): what the pixel shows over
/// `[t0, t1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ResolvedSpan {
    /// Start of the span.
    pub t0: f32,
    /// End of the span.
    pub t1: f32,
    /// Its shutter weight ∫ w dt (zero-weight spans are not shaded).
    pub weight: f32,
    /// Straight linear RGB shown over the span, background included.
    pub colour: [f32; 3],
    /// Intervals shaded for the span (0: background only or zero weight).
    pub layers: usize,
}

/// One list of a pixel and its resolve.
#[derive(Debug, Clone, PartialEq)]
pub struct PixelList {
    /// The intervals, in buffer order (sorted by start time).
    pub intervals: Vec<PixelInterval>,
    /// The partitions of the resolve sweep, in time order.
    pub spans: Vec<ResolvedSpan>,
    /// The resolved pixel colour, linear RGB (Gribel 2010, Eq. 17).
    pub colour: [f32; 3],
}

/// The exact and the compressed interval lists of one pixel (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct PixelIntervals {
    /// Pixel column.
    pub x: u32,
    /// Pixel row (0 at the top).
    pub y: u32,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Intervals per pixel of the compressed list (K).
    pub k: u32,
    /// The stages the scene calls for (opaque or transparent resolve, intersections, ...).
    pub pipeline: Pipeline,
    /// The exact unbounded list: what `--method analytic --intervals 0` resolves.
    pub exact: PixelList,
    /// The list after compression to K: what `--method analytic --intervals K` resolves.
    pub compressed: PixelList,
    /// The window of the oracle that compressed the list (Gribel 2010, Eq. 19-20: how many
    /// neighbouring intervals it considers merging).
    pub oracle_window: usize,
}

/// The interval payload with the index of the triangle that left it. Every [`Payload`]
/// operation acts on the inner payload alone, so buffering and compression decide exactly
/// as for the untagged payload; a blend (a merge, Eq. 20) marks the result as merged.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Tagged<P> {
    inner: P,
    triangle: u32,
    merged: bool,
}

impl<P: Payload<f32>> Payload<f32> for Tagged<P> {
    fn blend(&self, other: &Self, alpha: f32) -> Self {
        Tagged {
            inner: self.inner.blend(&other.inner, alpha),
            triangle: self.triangle,
            merged: true,
        }
    }
    fn distance(&self, other: &Self) -> f32 {
        self.inner.distance(&other.inner)
    }
    fn is_opaque(&self) -> bool {
        self.inner.is_opaque()
    }
    fn restrict(&self, s0: f32, s1: f32) -> Self {
        Tagged {
            inner: self.inner.restrict(s0, s1),
            ..*self
        }
    }
    fn coverage(&self) -> f32 {
        self.inner.coverage()
    }
    fn with_coverage(&self, alpha: f32) -> Self {
        Tagged {
            inner: self.inner.with_coverage(alpha),
            ..*self
        }
    }
}

fn untag<P: Copy>(iv: &Interval<f32, Tagged<P>>) -> Interval<f32, P> {
    Interval::new(iv.ts, iv.te, iv.z, iv.k, iv.payload.inner)
}

/// A shader of tagged payloads: the inner shader on the inner payload.
struct TagShader<'a, S>(&'a S);

impl<P: Copy, S: Shader<f32, P>> Shader<f32, Tagged<P>> for TagShader<'_, S> {
    fn shade(&self, iv: &Interval<f32, Tagged<P>>, t0: f32, t1: f32, w0: f32, w1: f32) -> [f32; 4] {
        self.0.shade(&untag(iv), t0, t1, w0, w1)
    }
    fn shade_at(&self, iv: &Interval<f32, Tagged<P>>, t: f32) -> [f32; 4] {
        self.0.shade_at(&untag(iv), t)
    }
    fn min_alpha(&self, iv: &Interval<f32, Tagged<P>>) -> f32 {
        self.0.min_alpha(&untag(iv))
    }
}

/// Straight alpha from premultiplied (black for alpha 0), non-finite values as 0.
fn straight(p: [f32; 4]) -> [f32; 4] {
    let p = p.map(|v| if v.is_finite() { v } else { 0.0 });
    if p[3] > 0.0 {
        [p[0] / p[3], p[1] / p[3], p[2] / p[3], p[3]]
    } else {
        [0.0; 4]
    }
}

/// Resolves one list, keeping the partitions, and converts it for drawing.
fn resolve_list<P: Copy, S: Shader<f32, P>>(
    scene: &PreparedScene,
    list: &[Interval<f32, Tagged<P>>],
    resolver: &Resolver<'_, f32, TagShader<'_, S>>,
    scratch: &mut Scratch<f32>,
    pixel: (u32, u32),
) -> Result<PixelList> {
    let mut spans = Vec::new();
    let c = resolver.pixel(scratch, list, pixel, |p| {
        let s = straight(p.colour);
        spans.push(ResolvedSpan {
            t0: p.t0,
            t1: p.t1,
            weight: p.weight,
            colour: [s[0], s[1], s[2]],
            layers: p.layers,
        })
    })?;
    let object = |tri: u32| {
        scene
            .objects
            .iter()
            .find(|o| o.range.contains(&(tri as usize)))
            .map_or_else(String::new, |o| o.name.clone())
    };
    let intervals = list
        .iter()
        .map(|iv| PixelInterval {
            t0: iv.ts,
            t1: iv.te,
            z0: iv.z,
            z1: iv.end_depth(),
            colour: straight(resolver.shader.shade_at(iv, 0.5 * (iv.ts + iv.te))),
            triangle: iv.payload.triangle,
            object: object(iv.payload.triangle),
            merged: iv.payload.merged,
        })
        .collect();
    Ok(PixelList {
        intervals,
        spans,
        colour: [c.r, c.g, c.b].map(|v| if v.is_finite() { v } else { 0.0 }),
    })
}

/// The exact and the compressed list of pixel (x, y) with K = `k`, once the payloads are
/// chosen.
struct Lists<'a> {
    scene: &'a PreparedScene,
    pipeline: &'a Pipeline,
    pixel: (u32, u32),
    k: u32,
}

impl WithPayloads<f32> for Lists<'_> {
    type Output = Result<(PixelList, PixelList)>;

    fn run<M: MakePayload<f32>, S: Shader<f32, M::P> + Sync>(
        self,
        mk: &M,
        shader: &S,
    ) -> Self::Output {
        let Lists {
            scene,
            pipeline,
            pixel,
            k,
        } = self;
        // The pixel's intervals in the order a render's buffers receive them, tagged.
        let mut emitted = Vec::new();
        chain::pixel_intervals(scene, Sweep::EdgeEqn, mk, pixel, |triangle, iv| {
            let payload = Tagged {
                inner: iv.payload,
                triangle,
                merged: false,
            };
            let iv = Interval::new(iv.ts, iv.te, iv.z, iv.k, payload);
            emitted.push(iv);
        })?;
        let settings = row::settings::<f32>(scene, pipeline, METHOD)?;
        let resolver = Resolver {
            shader: &TagShader(shader),
            settings: &settings,
            method: METHOD,
        };
        let opaque = !pipeline.transparency;
        // Both lists through the row pipeline's buffering, as a one-pixel row: the exact
        // lists, then the bounded buffer with the paper's oracle fed in the render's order.
        let mut scratch = RowScratch::<f32, Tagged<M::P>>::new();
        let mut list = |intervals: u32| -> Result<PixelList> {
            let mut out = None;
            let how = Buffering::unlimited(intervals, opaque);
            scratch.begin(1, pixel.1, how, METHOD)?;
            for &iv in &emitted {
                scratch.push(0, iv)?;
            }
            scratch.finish(|_, list, resolve| {
                out = Some(resolve_list(scene, list, &resolver, resolve, pixel)?);
                Ok(())
            })?;
            out.ok_or_else(|| Error::internal("inspect", "the one-pixel row has no list"))
        };
        Ok((list(0)?, list(k)?))
    }
}

/// The exact and compressed (K intervals, the paper's oracle) interval lists of pixel
/// (x, y) as the `analytic` method builds them, each resolved (Gribel 2010, §5.2.1).
///
/// Errors: the pixel outside the image or K outside `1..=`[`MAX_INTERVALS`]
/// ([`Error::Setting`] naming `pixel` / `intervals`); a scene with splats, which the
/// analytic method does not render ([`Error::MethodNotApplicable`]).
///
pub fn pixel_intervals(scene: &PreparedScene, x: u32, y: u32, k: u32) -> Result<PixelIntervals> {
    if x >= scene.width || y >= scene.height {
        return Err(Error::Setting {
            method: "inspect",
            setting: "pixel",
            message: format!(
                "({x}, {y}) is outside the {} x {} image (x must be below {}, y below {})",
                scene.width, scene.height, scene.width, scene.height
            ),
        });
    }
    if k == 0 || k > MAX_INTERVALS {
        return Err(Error::Setting {
            method: "inspect",
            setting: "intervals",
            message: format!(
                "must be between 1 and {MAX_INTERVALS} (the exact list is always drawn), got {k}"
            ),
        });
    }
    if !scene.splats.is_empty() {
        let what = if scene.triangles.is_empty() {
            "the scene has only splats"
        } else {
            "the scene has splats"
        };
        return Err(Error::MethodNotApplicable {
            method: METHOD.into(),
            reason: format!(
                "{what}; inspect draws the analytic method's coverage intervals, which exist only for triangles"
            ),
        });
    }
    let pipeline = Effects::analyse(scene).pipeline();
    let lists = Lists {
        scene,
        pipeline: &pipeline,
        pixel: (x, y),
        k,
    };
    let (exact, compressed) =
        with_payloads(scene, pipeline.textures, ShadingSamples::default(), lists)?;
    Ok(PixelIntervals {
        x,
        y,
        width: scene.width,
        height: scene.height,
        k,
        pipeline,
        exact,
        compressed,
        oracle_window: Oracle::<f32>::paper_for(!pipeline.transparency).window,
    })
}
