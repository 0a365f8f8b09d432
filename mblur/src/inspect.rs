//! The temporal pixel visualiser (Gribel 2010, §5.2.1): the intervals the `analytic`
//! method stores for one pixel, drawn as depth over shutter time, before and after the
//! compression to K intervals per pixel with the paper's oracle (§5.2, Eq. 19-20).
//!
//! [`pixel_intervals`] runs the analytic method's own primitive set-up and interval
//! emission for one pixel (through [`crate::analytic`], so the lists are exactly what a
//! render stores there), then builds both lists with the interval buffers a render uses:
//! the exact list (interval-buffer's counted, sorted exact lists, Rønnow 2021 §4.1-4.2) and
//! the bounded buffer of K slots with oracle compression (Gribel 2010 §5.2), and resolves
//! each with the render's resolve settings (Eq. 17), keeping every partition of the sweep
//! (the colour over time). [`PixelIntervals::to_svg`] draws both panels with the resolved
//! colour strips; [`save_svg`] writes the file atomically.
//!
//! Each interval carries the index of the triangle that left it (a tag that rides along
//! in the payload and never changes the colour, the oracle's distance or the opacity), so
//! the compressed list can say which intervals are merges of several.

use std::fmt::Write as _;
use std::path::Path;

use interval_buffer::{BoundedBuffer, Insertion, Interval, IntervalCounts, Oracle, Payload};
use resolve::{Flat, Scratch, Settings, Shader};

use crate::analytic::{
    self, MAX_INTERVALS, MakePayload, Sweep, flat_payloads, tex_payloads, texture_fn,
};
use crate::effects::{Effects, Pipeline};
use crate::error::{Error, Result};
use crate::prepare::PreparedScene;
use crate::texture::linear_to_srgb;

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

fn buffer_error(e: interval_buffer::Error) -> Error {
    Error::MethodNotApplicable {
        method: "analytic".into(),
        reason: format!("interval buffer: {e}"),
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
    shader: &S,
    settings: &Settings<f32>,
) -> Result<PixelList> {
    let shader = TagShader(shader);
    let mut spans = Vec::new();
    let c = resolve::resolve_with(&mut Scratch::new(), list, &shader, settings, |p| {
        let s = straight(p.colour);
        spans.push(ResolvedSpan {
            t0: p.t0,
            t1: p.t1,
            weight: p.weight,
            colour: [s[0], s[1], s[2]],
            layers: p.layers,
        })
    })
    .map_err(|e| Error::MethodNotApplicable {
        method: "analytic".into(),
        reason: format!("resolve: {e}"),
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
            colour: straight(shader.shade_at(iv, 0.5 * (iv.ts + iv.te))),
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

fn lists<M: MakePayload, S: Shader<f32, M::P>>(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    (mk, shader): (&M, &S),
    (x, y, k): (u32, u32, u32),
) -> Result<(PixelList, PixelList)> {
    let mut emitted: Vec<Interval<f32, Tagged<M::P>>> = Vec::new();
    analytic::pixel_intervals(scene, Sweep::EdgeEqn, mk, (x, y), |triangle, iv| {
        let payload = Tagged {
            inner: iv.payload,
            triangle,
            merged: false,
        };
        emitted.push(Interval::new(iv.ts, iv.te, iv.z, iv.k, payload));
    })?;
    // The exact list, through the same count / fill / sort as a render.
    let mut counts = IntervalCounts::new(1, 1).map_err(buffer_error)?;
    for _ in &emitted {
        counts.count(0).map_err(buffer_error)?;
    }
    let mut fill = counts.finish::<f32, Tagged<M::P>>().map_err(buffer_error)?;
    for iv in &emitted {
        fill.push(0, *iv).map_err(buffer_error)?;
    }
    let exact = fill.finish().map_err(buffer_error)?;
    // The bounded buffer with the paper's oracle, fed in the render's order.
    let opaque = !pipeline.transparency;
    let mut bounded = BoundedBuffer::new(
        1,
        1,
        k as usize,
        Insertion {
            oracle: Oracle::paper_for(opaque),
            opaque,
        },
    )
    .map_err(buffer_error)?;
    for iv in &emitted {
        bounded.insert(0, 0, *iv).map_err(buffer_error)?;
    }
    let settings = analytic::settings(scene, pipeline)?;
    Ok((
        resolve_list(scene, exact.pixel_index(0), shader, &settings)?,
        resolve_list(scene, bounded.pixel_index(0), shader, &settings)?,
    ))
}

/// The exact and compressed (K intervals, the paper's oracle) interval lists of pixel
/// (x, y) as the `analytic` method builds them, each resolved (Gribel 2010, §5.2.1).
///
/// Errors: the pixel outside the image or K outside `1..=`[`MAX_INTERVALS`]
/// ([`Error::Option`] naming `--pixel` / `--intervals`); a scene with splats, which the
/// analytic method does not render ([`Error::MethodNotApplicable`]).
///
/// ```
/// let mut scene = mblur::Scene::builtin("crossing-quads")?;
/// scene.set_size(Some(32), Some(18))?;
/// let p = mblur::inspect::pixel_intervals(&scene.prepare()?, 16, 9, 4)?;
/// assert!(p.compressed.intervals.len() <= 4);
/// let svg = p.to_svg("crossing-quads");
/// assert!(svg.starts_with("<?xml"));
/// # Ok::<(), mblur::Error>(())
/// ```
pub fn pixel_intervals(scene: &PreparedScene, x: u32, y: u32, k: u32) -> Result<PixelIntervals> {
    if x >= scene.width || y >= scene.height {
        return Err(Error::Option {
            option: "--pixel".into(),
            message: format!(
                "({x}, {y}) is outside the {} x {} image (x must be below {}, y below {})",
                scene.width, scene.height, scene.width, scene.height
            ),
        });
    }
    if k == 0 || k > MAX_INTERVALS {
        return Err(Error::Option {
            option: "--intervals".into(),
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
            method: "analytic".into(),
            reason: format!(
                "{what}; inspect draws the analytic method's coverage intervals, which exist only for triangles"
            ),
        });
    }
    let pipeline = Effects::analyse(scene).pipeline();
    let (exact, compressed) = if pipeline.textures {
        let tex = texture_fn(scene);
        let shader = analytic::AdaptiveTaps::new(&tex, scene);
        lists(scene, &pipeline, (&tex_payloads(scene), &shader), (x, y, k))?
    } else {
        lists(scene, &pipeline, (&flat_payloads(scene), &Flat), (x, y, k))?
    };
    Ok(PixelIntervals {
        x,
        y,
        width: scene.width,
        height: scene.height,
        k,
        pipeline,
        exact,
        compressed,
    })
}

/// Parses a pixel given as `X,Y` (the `--pixel` option).
pub fn parse_pixel(s: &str) -> std::result::Result<(u32, u32), String> {
    let bad = || format!("expected a pixel as X,Y (e.g. 120,64), got `{s}`");
    let (a, b) = s.split_once(',').ok_or_else(bad)?;
    let x = a.trim().parse::<u32>().map_err(|_| bad())?;
    let y = b.trim().parse::<u32>().map_err(|_| bad())?;
    Ok((x, y))
}

/// Writes an SVG document to `path` atomically (a temporary file in the same folder,
/// renamed), so a failure leaves no partial file. The extension must be `.svg`.
pub fn save_svg(path: &Path, svg: &str) -> Result<()> {
    let werr = |m: String| Error::Write {
        path: path.to_path_buf(),
        message: m,
    };
    if !path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"))
    {
        return Err(werr(
            "the pixel visualiser writes SVG: use a .svg file name".into(),
        ));
    }
    crate::atomic::write_atomic(path, svg.as_bytes())
}

// ---- drawing ----

const W: f64 = 1000.0;
const LEFT: f64 = 80.0;
const RIGHT: f64 = 40.0;
const TOP: f64 = 78.0;
const PANEL: f64 = 310.0;
const PLOT: f64 = 200.0;
const STRIP: f64 = 22.0;

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// `rgb(...)` of a linear colour, sRGB-encoded and clamped.
fn css(c: [f32; 3]) -> String {
    let [r, g, b] = c.map(|v| (linear_to_srgb(f64::from(v).clamp(0.0, 1.0)) * 255.0).round() as u8);
    format!("rgb({r},{g},{b})")
}

/// A "nice" tick step (1, 2 or 5 times a power of ten) for about `n` ticks over `span`.
fn nice_step(span: f64, n: f64) -> f64 {
    let raw = span / n;
    let p = 10f64.powf(raw.log10().floor());
    let m = raw / p;
    let f = if m < 1.5 {
        1.0
    } else if m < 3.5 {
        2.0
    } else if m < 7.5 {
        5.0
    } else {
        10.0
    };
    f * p
}

impl PixelIntervals {
    /// The depth range drawn: both lists, padded; `[0, 1]` when there are no intervals.
    fn depth_range(&self) -> (f64, f64) {
        let zs = self
            .exact
            .intervals
            .iter()
            .chain(&self.compressed.intervals)
            .flat_map(|i| [i.z0, i.z1])
            .map(f64::from)
            .filter(|z| z.is_finite());
        let (lo, hi) = zs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), z| {
            (lo.min(z), hi.max(z))
        });
        if !lo.is_finite() {
            return (0.0, 1.0);
        }
        let pad = ((hi - lo) * 0.08).max(1e-3 * lo.abs().max(hi.abs()).max(1e-3));
        (lo - pad, hi + pad)
    }

    /// The picture as a standalone SVG document: a title with the scene, pixel and
    /// interval counts, then one panel per list (exact, then compressed to K), each with
    /// every interval as a line from (t0, z0) to (t1, z1) in its colour (nearer at the
    /// top), time and depth axes, and under it a strip of the resolved colour over time
    /// with the resolved pixel colour beside it.
    pub fn to_svg(&self, scene: &str) -> String {
        let h = TOP + 2.0 * PANEL + 30.0;
        let mut s = String::new();
        let _ = write!(
            s,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{W}\" height=\"{h}\" viewBox=\"0 0 {W} {h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{W}\" height=\"{h}\" fill=\"white\"/>\n"
        );
        let p = &self.pipeline;
        let (n, m) = (self.exact.intervals.len(), self.compressed.intervals.len());
        let _ = writeln!(
            s,
            "<text x=\"{LEFT}\" y=\"24\" font-size=\"15\" font-weight=\"bold\">{}: pixel ({}, {}) of {} x {}, {n} interval{} exact, {m} after compression to K = {}</text>",
            esc(scene),
            self.x,
            self.y,
            self.width,
            self.height,
            if n == 1 { "" } else { "s" },
            self.k
        );
        let _ = writeln!(
            s,
            "<text x=\"{LEFT}\" y=\"44\" fill=\"#444\">Temporal pixel visualiser (Gribel 2010, 5.2.1) of the analytic method: {} resolve{}{}, paper's oracle (window {})</text>",
            if p.transparency {
                "transparent"
            } else {
                "opaque"
            },
            if p.intersection {
                " with intersections"
            } else {
                ""
            },
            if p.textures { ", textured" } else { "" },
            Oracle::<f32>::paper_for(!p.transparency).window,
        );
        let _ = writeln!(
            s,
            "<text x=\"{LEFT}\" y=\"60\" fill=\"#444\">Lines: intervals, depth over shutter time (dashed outline: merged, Eq. 20). Strips: resolved colour over time. Hover for numbers.</text>"
        );
        let range = self.depth_range();
        for (i, (label, list)) in [
            ("exact interval list".to_string(), &self.exact),
            (format!("compressed to K = {}", self.k), &self.compressed),
        ]
        .iter()
        .enumerate()
        {
            self.panel(&mut s, TOP + i as f64 * PANEL, label, list, range);
        }
        s.push_str("</svg>\n");
        s
    }

    fn panel(&self, s: &mut String, top: f64, label: &str, list: &PixelList, (z0, z1): (f64, f64)) {
        let (x0, x1) = (LEFT, W - RIGHT);
        let (y0, y1) = (top + 14.0, top + 14.0 + PLOT);
        let tx = |t: f64| x0 + (x1 - x0) * t;
        let zy = |z: f64| y0 + (y1 - y0) * (z - z0) / (z1 - z0);
        let _ = writeln!(
            s,
            "<g class=\"panel\">\n<text x=\"{x0}\" y=\"{}\" font-size=\"14\" font-weight=\"bold\">{}: {} interval{}, resolved {}</text>",
            top + 6.0,
            esc(label),
            list.intervals.len(),
            if list.intervals.len() == 1 { "" } else { "s" },
            css(list.colour),
        );
        let _ = writeln!(
            s,
            "<rect x=\"{x0}\" y=\"{y0}\" width=\"{}\" height=\"{PLOT}\" fill=\"#eeeeee\" stroke=\"#888\"/>",
            x1 - x0
        );
        // Time ticks and grid.
        for j in 0..=10 {
            let t = f64::from(j) / 10.0;
            let x = tx(t);
            let _ = writeln!(
                s,
                "<line class=\"grid\" x1=\"{x:.2}\" y1=\"{y0}\" x2=\"{x:.2}\" y2=\"{y1}\" stroke=\"#d8d8d8\"/><line class=\"tick\" x1=\"{x:.2}\" y1=\"{y1}\" x2=\"{x:.2}\" y2=\"{}\" stroke=\"#555\"/><text x=\"{x:.2}\" y=\"{}\" text-anchor=\"middle\">{t:.1}</text>",
                y1 + 4.0,
                y1 + 16.0
            );
        }
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"end\" fill=\"#444\">shutter time t</text>",
            x1,
            y1 + 30.0
        );
        // Depth ticks.
        let step = nice_step(z1 - z0, 4.0);
        let decimals = (-step.log10().floor()).clamp(0.0, 6.0) as usize;
        let mut z = (z0 / step).ceil() * step;
        while z <= z1 + 1e-9 * step.abs() {
            let y = zy(z);
            let _ = writeln!(
                s,
                "<line class=\"grid\" x1=\"{x0}\" y1=\"{y:.2}\" x2=\"{x1}\" y2=\"{y:.2}\" stroke=\"#d8d8d8\"/><line class=\"tick\" x1=\"{}\" y1=\"{y:.2}\" x2=\"{x0}\" y2=\"{y:.2}\" stroke=\"#555\"/><text x=\"{}\" y=\"{:.2}\" text-anchor=\"end\">{z:.decimals$}</text>",
                x0 - 4.0,
                x0 - 6.0,
                y + 4.0
            );
            z += step;
        }
        let _ = writeln!(
            s,
            "<text transform=\"translate({} {}) rotate(-90)\" text-anchor=\"middle\" fill=\"#444\">depth (nearer up)</text>",
            x0 - 56.0,
            0.5 * (y0 + y1)
        );
        if list.intervals.is_empty() {
            let _ = writeln!(
                s,
                "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" fill=\"#666\">no intervals: the background shows all shutter long</text>",
                0.5 * (x0 + x1),
                0.5 * (y0 + y1)
            );
        }
        // The intervals: a dark outline (dashed when merged) under the coloured line.
        let _ = writeln!(
            s,
            "<svg x=\"{x0}\" y=\"{y0}\" width=\"{}\" height=\"{PLOT}\" viewBox=\"{x0} {y0} {} {PLOT}\" overflow=\"hidden\">",
            x1 - x0,
            x1 - x0
        );
        for iv in &list.intervals {
            let (ax, ay) = (tx(f64::from(iv.t0)), zy(f64::from(iv.z0)));
            let (bx, by) = (tx(f64::from(iv.t1)), zy(f64::from(iv.z1)));
            let [r, g, b, a] = iv.colour;
            let dash = if iv.merged {
                "butt\" stroke-dasharray=\"5 3"
            } else {
                "round"
            };
            let _ = writeln!(
                s,
                "<line class=\"outline\" x1=\"{ax:.2}\" y1=\"{ay:.2}\" x2=\"{bx:.2}\" y2=\"{by:.2}\" stroke=\"#222\" stroke-width=\"7\" stroke-linecap=\"{dash}\"/>"
            );
            let _ = writeln!(
                s,
                "<line class=\"interval\" x1=\"{ax:.2}\" y1=\"{ay:.2}\" x2=\"{bx:.2}\" y2=\"{by:.2}\" stroke=\"{}\" stroke-opacity=\"{:.3}\" stroke-width=\"3.5\" stroke-linecap=\"round\"><title>triangle {} ({}){}: t {:.4} to {:.4}, depth {:.4} to {:.4}, rgba {:.3} {:.3} {:.3} {:.3}</title></line>",
                css([r, g, b]),
                a.clamp(0.2, 1.0),
                iv.triangle,
                esc(&iv.object),
                if iv.merged { ", merged" } else { "" },
                iv.t0,
                iv.t1,
                iv.z0,
                iv.z1,
                r,
                g,
                b,
                a
            );
        }
        s.push_str("</svg>\n");
        // The resolved colour over time, and the pixel colour.
        let sy = y1 + 36.0;
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">resolve</text>",
            x0 - 6.0,
            sy + 15.0
        );
        for sp in &list.spans {
            let (a, b) = (tx(f64::from(sp.t0)), tx(f64::from(sp.t1)));
            let fill = if sp.weight > 0.0 {
                css(sp.colour)
            } else {
                "#bbbbbb".to_string()
            };
            let _ = writeln!(
                s,
                "<rect class=\"span\" x=\"{a:.2}\" y=\"{sy}\" width=\"{:.2}\" height=\"{STRIP}\" fill=\"{fill}\"><title>t {:.4} to {:.4}: {} layer{}, weight {:.4}</title></rect>",
                (b - a).max(0.0),
                sp.t0,
                sp.t1,
                sp.layers,
                if sp.layers == 1 { "" } else { "s" },
                sp.weight
            );
        }
        let _ = writeln!(
            s,
            "<rect x=\"{x0}\" y=\"{sy}\" width=\"{}\" height=\"{STRIP}\" fill=\"none\" stroke=\"#888\"/>",
            x1 - x0
        );
        let _ = writeln!(
            s,
            "<rect x=\"{}\" y=\"{sy}\" width=\"{}\" height=\"{STRIP}\" fill=\"{}\" stroke=\"#222\"><title>resolved pixel: linear rgb {:.4} {:.4} {:.4}</title></rect>\n</g>",
            x1 + 8.0,
            RIGHT - 14.0,
            css(list.colour),
            list.colour[0],
            list.colour[1],
            list.colour[2]
        );
    }
}
