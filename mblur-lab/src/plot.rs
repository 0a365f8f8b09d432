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

use crate::compare::{Outcome, Reference, RunRecord, SceneInfo};
use mblur_scene::{Error, Result};

/// The bundled font (DejaVu Sans).
pub static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Plot size in pixels.
pub const PLOT_SIZE: (u32, u32) = (1000, 650);

const PALETTE: [RGBColor; 12] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
    RGBColor(0, 0, 0),
    RGBColor(255, 187, 120),
];

fn register_font() -> std::result::Result<(), String> {
    static DONE: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
            .map_err(|_| "the bundled font is not a valid TrueType font".to_string())
    })
    .clone()
}

/// One curve: the series name and its (wall time in ms, PSNR in dB) points in ladder order.
pub type Curve = (String, Vec<(f64, f64)>);

/// The curves of the finished runs: per series in order of first appearance, the runs that
/// rendered with a finite PSNR and a positive time.
pub fn curves(records: &[RunRecord]) -> Vec<Curve> {
    let mut out: Vec<Curve> = Vec::new();
    for r in records {
        let Outcome::Done(s) = &r.outcome else {
            continue;
        };
        let p = (s.seconds * 1e3, s.metrics.psnr);
        if !(p.0 > 0.0 && p.0.is_finite() && p.1.is_finite()) {
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
    let all = curves.iter().flat_map(|c| c.1.iter().copied());
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
        .x_desc("median wall time (ms, log scale)")
        .y_desc("PSNR against the reference (dB)")
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .x_labels(12)
        .x_label_formatter(&|v| {
            if *v >= 1.0 {
                format!("{v:.0}")
            } else {
                format!("{v:.2}")
            }
        })
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()
        .map_err(e)?;
    for (i, (_, pts)) in curves.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        chart
            .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
            .map_err(e)?;
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled())))
            .map_err(e)?;
    }
    // The legend: one line per curve, in the panel right of the chart.
    for (i, (name, _)) in curves.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
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
