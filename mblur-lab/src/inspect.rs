//! The temporal pixel visualiser's picture (Gribel 2010, §5.2.1): one pixel's intervals
//! from [`mblur::inspect::pixel_intervals`], exact and compressed to K, drawn as depth over
//! shutter time with the resolved colour strips, as SVG.

use std::fmt::Write as _;
use std::path::Path;

use mblur::inspect::{PixelIntervals, PixelList};
use mblur::texture::linear_to_srgb;
use mblur_scene::{Error, Result};

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
    mblur_scene::atomic::write_atomic(path, svg.as_bytes())
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

/// The depth range drawn: both lists, padded; `[0, 1]` when there are no intervals.
fn depth_range(p: &PixelIntervals) -> (f64, f64) {
    let zs = p
        .exact
        .intervals
        .iter()
        .chain(&p.compressed.intervals)
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
pub fn to_svg(p: &PixelIntervals, scene: &str) -> String {
    let h = TOP + 2.0 * PANEL + 30.0;
    let mut s = String::new();
    let _ = write!(
        s,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{W}\" height=\"{h}\" viewBox=\"0 0 {W} {h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{W}\" height=\"{h}\" fill=\"white\"/>\n"
    );
    let pl = &p.pipeline;
    let (n, m) = (p.exact.intervals.len(), p.compressed.intervals.len());
    let _ = writeln!(
        s,
        "<text x=\"{LEFT}\" y=\"24\" font-size=\"15\" font-weight=\"bold\">{}: pixel ({}, {}) of {} x {}, {n} interval{} exact, {m} after compression to K = {}</text>",
        esc(scene),
        p.x,
        p.y,
        p.width,
        p.height,
        if n == 1 { "" } else { "s" },
        p.k
    );
    let _ = writeln!(
        s,
        "<text x=\"{LEFT}\" y=\"44\" fill=\"#444\">Temporal pixel visualiser (Gribel 2010, 5.2.1) of the analytic method: {} resolve{}{}, paper's oracle (window {})</text>",
        if pl.transparency {
            "transparent"
        } else {
            "opaque"
        },
        if pl.intersection {
            " with intersections"
        } else {
            ""
        },
        if pl.textures { ", textured" } else { "" },
        p.oracle_window,
    );
    let _ = writeln!(
        s,
        "<text x=\"{LEFT}\" y=\"60\" fill=\"#444\">Lines: intervals, depth over shutter time (dashed outline: merged, Eq. 20). Strips: resolved colour over time. Hover for numbers.</text>"
    );
    let range = depth_range(p);
    for (i, (label, list)) in [
        ("exact interval list".to_string(), &p.exact),
        (format!("compressed to K = {}", p.k), &p.compressed),
    ]
    .iter()
    .enumerate()
    {
        panel(&mut s, TOP + i as f64 * PANEL, label, list, range);
    }
    s.push_str("</svg>\n");
    s
}

/// The plot area of a panel and the depth range it shows.
#[derive(Clone, Copy)]
struct Frame {
    /// Left and right edges (shutter open and close).
    x0: f64,
    x1: f64,
    /// Top and bottom edges (depths `z0` and `z1`).
    y0: f64,
    y1: f64,
    /// The depth range (nearer at the top).
    z0: f64,
    z1: f64,
}

impl Frame {
    /// The x coordinate of shutter time `t`.
    fn tx(&self, t: f64) -> f64 {
        self.x0 + (self.x1 - self.x0) * t
    }

    /// The y coordinate of depth `z`.
    fn zy(&self, z: f64) -> f64 {
        self.y0 + (self.y1 - self.y0) * (z - self.z0) / (self.z1 - self.z0)
    }
}

fn panel(s: &mut String, top: f64, label: &str, list: &PixelList, (z0, z1): (f64, f64)) {
    let (x0, x1) = (LEFT, W - RIGHT);
    let (y0, y1) = (top + 14.0, top + 14.0 + PLOT);
    let f = Frame {
        x0,
        x1,
        y0,
        y1,
        z0,
        z1,
    };
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
    axes(s, &f, list);
    interval_lines(s, &f, list);
    colour_strip(s, &f, list);
}

/// Draws a panel's time and depth ticks, grid and axis labels (and a note when there are
/// no intervals).
fn axes(s: &mut String, f: &Frame, list: &PixelList) {
    let Frame {
        x0,
        x1,
        y0,
        y1,
        z0,
        z1,
    } = *f;
    // Time ticks and grid.
    for j in 0..=10 {
        let t = f64::from(j) / 10.0;
        let x = f.tx(t);
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
        let y = f.zy(z);
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
}

/// Draws a panel's intervals: a dark outline (dashed when merged) under the coloured line.
fn interval_lines(s: &mut String, f: &Frame, list: &PixelList) {
    let Frame { x0, x1, y0, .. } = *f;
    // The intervals: a dark outline (dashed when merged) under the coloured line.
    let _ = writeln!(
        s,
        "<svg x=\"{x0}\" y=\"{y0}\" width=\"{}\" height=\"{PLOT}\" viewBox=\"{x0} {y0} {} {PLOT}\" overflow=\"hidden\">",
        x1 - x0,
        x1 - x0
    );
    for iv in &list.intervals {
        let (ax, ay) = (f.tx(f64::from(iv.t0)), f.zy(f64::from(iv.z0)));
        let (bx, by) = (f.tx(f64::from(iv.t1)), f.zy(f64::from(iv.z1)));
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
}

/// Draws a panel's strip of the resolved colour over time and the resolved pixel colour,
/// and closes the panel group.
fn colour_strip(s: &mut String, f: &Frame, list: &PixelList) {
    let Frame { x0, x1, y1, .. } = *f;
    // The resolved colour over time, and the pixel colour.
    let sy = y1 + 36.0;
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">resolve</text>",
        x0 - 6.0,
        sy + 15.0
    );
    for sp in &list.spans {
        let (a, b) = (f.tx(f64::from(sp.t0)), f.tx(f64::from(sp.t1)));
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
