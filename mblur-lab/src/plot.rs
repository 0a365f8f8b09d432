//! The error-vs-time plot of `mblur compare`: PSNR against the reference (dB) over the
//! median wall time (ms, log axis), one curve per method (per traversal for stochastic),
//! points in ladder order, drawn with plotters to `plot.svg` and `plot.png`. Text uses the
//! bundled DejaVu Sans (`assets/DejaVuSans.ttf`, Bitstream Vera licence in
//! `assets/DejaVuSans-LICENSE.txt`), so no system font library is needed. Runs with an
//! infinite PSNR (identical to the reference) cannot be placed and are left out.

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::record::{Outcome, Reference, RunRecord, SceneInfo};
use mblur_scene::{Error, Result};

/// The bundled font (DejaVu Sans).
pub static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Plot size in pixels.
pub const PLOT_SIZE: (u32, u32) = (1000, 650);

/// One colour per series, the same in every plot: a method keeps its colour whichever
/// methods ran (stochastic traversals in related shades).
const SERIES_COLOURS: [(&str, RGBColor); 12] = [
    ("analytic", RGBColor(31, 119, 180)),
    ("prism", RGBColor(148, 103, 189)),
    ("accum", RGBColor(0, 0, 0)),
    ("ewa", RGBColor(44, 160, 44)),
    ("stochastic/fallback", RGBColor(214, 39, 40)),
    ("stochastic/our", RGBColor(255, 127, 14)),
    ("stochastic/our-exact", RGBColor(227, 119, 194)),
    ("stochastic/our-per-tile", RGBColor(188, 189, 34)),
    ("stochastic/our-fine", RGBColor(140, 86, 75)),
    ("stochastic/bbox", RGBColor(127, 127, 127)),
    ("stochastic/convex", RGBColor(23, 190, 207)),
    ("stochastic/interleave", RGBColor(255, 187, 120)),
];

/// The colour of a series (grey for a name not in [`SERIES_COLOURS`]).
fn colour(series: &str) -> RGBColor {
    SERIES_COLOURS
        .iter()
        .find(|(name, _)| *name == series)
        .map_or(RGBColor(90, 90, 90), |(_, c)| *c)
}

/// A time in milliseconds as an axis label: `0.5 ms`, `20 ms`, `1.5 s`.
fn time_label(ms: f64) -> String {
    if ms >= 1000.0 {
        format!("{} s", trim(ms / 1000.0))
    } else {
        format!("{} ms", trim(ms))
    }
}

/// A number with at most two significant decimals and no trailing zeros.
fn trim(v: f64) -> String {
    let s = if v >= 10.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.2}")
    };
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

fn register_font() -> std::result::Result<(), String> {
    static DONE: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
            .map_err(|_| "the bundled font is not a valid TrueType font".to_string())
    })
    .clone()
}

/// One point of a curve: wall time in ms, PSNR in dB, and the setting it was run with
/// (`K=4`, `16 spp`), drawn next to it.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Median wall time in milliseconds.
    pub ms: f64,
    /// PSNR against the reference, dB.
    pub psnr: f64,
    /// The setting of the run.
    pub setting: String,
}

/// One curve: the series name and its points in ladder order.
pub type Curve = (String, Vec<Point>);

/// The curves of the finished runs: per series in order of first appearance, the runs that
/// rendered with a finite PSNR and a positive time.
pub fn curves(records: &[RunRecord]) -> Vec<Curve> {
    let mut out: Vec<Curve> = Vec::new();
    for r in records {
        let Outcome::Done(s) = &r.outcome else {
            continue;
        };
        let p = Point {
            ms: s.seconds * 1e3,
            psnr: s.metrics.psnr,
            setting: r.entry.setting.clone(),
        };
        if !(p.ms > 0.0 && p.ms.is_finite() && p.psnr.is_finite()) {
            continue;
        }
        match out.iter_mut().find(|c| c.0 == r.entry.series) {
            Some(c) => c.1.push(p),
            None => out.push((r.entry.series.clone(), vec![p])),
        }
    }
    out
}

/// Width of the legend panel on the right, pixels.
const LEGEND_WIDTH: u32 = 210;

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    curves: &[Curve],
) -> std::result::Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = root
        .margin(10, 0, 0, 0)
        .titled(title, ("sans-serif", 20))
        .map_err(e)?;
    let (w, _) = root.dim_in_pixel();
    let (plot, legend) = root.split_horizontally(w.saturating_sub(LEGEND_WIDTH));
    let all = curves
        .iter()
        .flat_map(|c| c.1.iter().map(|p| (p.ms, p.psnr)));
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if x0 > x1 {
        (x0, x1, y0, y1) = (1.0, 1000.0, 10.0, 50.0);
    }
    let (x0, x1) = (x0 / 1.6, x1 * 1.6);
    let pad = ((y1 - y0) * 0.08).max(1.0);
    let (y0, y1) = ((y0 - pad).floor(), (y1 + pad).ceil());
    let mut chart = ChartBuilder::on(&plot)
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d((x0..x1).log_scale(), y0..y1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("median wall time (log scale)")
        .y_desc("PSNR against the reference (dB)")
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .x_labels(8)
        .x_label_formatter(&|v| time_label(*v))
        .y_label_formatter(&|v| format!("{v:.0} dB"))
        .draw()
        .map_err(e)?;
    for (name, pts) in curves {
        let color = colour(name);
        let xy = || pts.iter().map(|p| (p.ms, p.psnr));
        chart
            .draw_series(LineSeries::new(xy(), color.stroke_width(2)))
            .map_err(e)?;
        chart
            .draw_series(xy().map(|p| Circle::new(p, 4, color.filled())))
            .map_err(e)?;
        let label = ("sans-serif", 11).into_font().color(&color);
        chart
            .draw_series(pts.iter().map(|p| {
                Text::new(
                    p.setting.clone(),
                    (p.ms * 1.08, p.psnr + 0.4),
                    label.clone(),
                )
            }))
            .map_err(e)?;
    }
    // The legend: one line per curve, in the panel right of the chart.
    for (i, (name, _)) in curves.iter().enumerate() {
        let color = colour(name);
        let y = 30 + 24 * i as i32;
        legend
            .draw(&PathElement::new(
                vec![(8, y), (34, y)],
                color.stroke_width(3),
            ))
            .map_err(e)?;
        legend
            .draw(&Circle::new((21, y), 4, color.filled()))
            .map_err(e)?;
        legend
            .draw(&Text::new(
                name.as_str(),
                (42, y - 8),
                ("sans-serif", 14).into_font().color(&BLACK),
            ))
            .map_err(e)?;
    }
    root.present().map_err(e)?;
    Ok(())
}

/// The plot title for a scene and reference.
pub fn title(info: &SceneInfo, reference: &Reference) -> String {
    let how = reference
        .description
        .split(':')
        .next()
        .unwrap_or("reference");
    format!(
        "{} {}x{}: error vs time (reference: {how}, {} threads)",
        info.name, info.width, info.height, info.threads
    )
}

/// SVG text of the plot.
pub fn svg(title: &str, curves: &[Curve]) -> std::result::Result<String, String> {
    register_font()?;
    let mut s = String::new();
    {
        let root = SVGBackend::with_string(&mut s, PLOT_SIZE).into_drawing_area();
        draw(&root, title, curves)?;
    }
    Ok(s)
}

/// RGB bytes of the plot, `PLOT_SIZE` pixels.
pub fn rgb(title: &str, curves: &[Curve]) -> std::result::Result<Vec<u8>, String> {
    register_font()?;
    let mut buf = vec![255u8; PLOT_SIZE.0 as usize * PLOT_SIZE.1 as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buf, PLOT_SIZE).into_drawing_area();
        draw(&root, title, curves)?;
    }
    Ok(buf)
}

/// Writes `plot.svg` and `plot.png` into `dir`.
pub fn write_plots(
    dir: &Path,
    info: &SceneInfo,
    reference: &Reference,
    records: &[RunRecord],
) -> Result<()> {
    let title = title(info, reference);
    let curves = curves(records);
    let (svg_path, png_path) = (dir.join("plot.svg"), dir.join("plot.png"));
    let werr = |path: &Path, message: String| Error::Write {
        path: path.to_path_buf(),
        message,
    };
    let text = svg(&title, &curves).map_err(|m| werr(&svg_path, m))?;
    mblur_scene::atomic::write_atomic(&svg_path, text.as_bytes())?;
    let bytes = rgb(&title, &curves).map_err(|m| werr(&png_path, m))?;
    let png = crate::report::png_bytes(PLOT_SIZE.0, PLOT_SIZE.1, bytes, &png_path)?;
    mblur_scene::atomic::write_atomic(&png_path, &png)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_labels_read_as_times() {
        assert_eq!(time_label(0.5), "0.5 ms");
        assert_eq!(time_label(0.25), "0.25 ms");
        assert_eq!(time_label(20.0), "20 ms");
        assert_eq!(time_label(999.0), "999 ms");
        assert_eq!(time_label(1500.0), "1.5 s");
        assert_eq!(time_label(12_000.0), "12 s");
    }

    #[test]
    fn every_series_keeps_one_distinct_colour() {
        for (i, (a, ca)) in SERIES_COLOURS.iter().enumerate() {
            assert_eq!(colour(a), *ca);
            for (b, cb) in &SERIES_COLOURS[i + 1..] {
                assert!(a != b && ca != cb, "{a} / {b}");
            }
        }
        for t in mblur::TraversalChoice::ALL {
            let series = format!("stochastic/{}", t.name());
            assert!(
                SERIES_COLOURS.iter().any(|(n, _)| *n == series),
                "{series} has no colour"
            );
        }
    }
}
