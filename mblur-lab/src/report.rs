//! The files `mblur compare` writes: the results as a printed table, `results.csv` and
//! `results.md` (rewritten atomically after every run, so an interruption leaves a complete
//! file with the runs gathered so far), `reference.png`, and per run one PNG with the run's
//! image on the left and its difference from the reference on the right (the largest
//! channel difference, divided by the diff scale, through a black-red-yellow-white heat map).

use std::fmt;
use std::path::Path;

use crate::record::{Outcome, Reference, RunRecord, SceneInfo};
use mblur::image::Image;
use mblur_scene::{Error, Result};

/// Creates `dir` (and its parents) and checks files can be written in it.
pub fn prepare_dir(dir: &Path) -> Result<()> {
    let werr = |m: String| Error::Write {
        path: dir.to_path_buf(),
        message: m,
    };
    std::fs::create_dir_all(dir).map_err(|e| werr(format!("cannot create the folder: {e}")))?;
    tempfile::Builder::new()
        .prefix(".mblur-")
        .tempfile_in(dir)
        .map_err(|e| werr(format!("the folder is not writable: {e}")))?;
    Ok(())
}

/// PNG bytes of 8-bit RGB data.
pub fn png_bytes(width: u32, height: u32, rgb: Vec<u8>, path: &Path) -> Result<Vec<u8>> {
    let werr = |m: String| Error::Write {
        path: path.to_path_buf(),
        message: m,
    };
    let img = image::RgbImage::from_raw(width, height, rgb)
        .ok_or_else(|| werr("image size mismatch".into()))?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    img.write_to(&mut bytes, image::ImageFormat::Png)
        .map_err(|e| werr(e.to_string()))?;
    Ok(bytes.into_inner())
}

/// Saves an image as an sRGB PNG.
pub fn save_png(image: &Image, path: &Path) -> Result<()> {
    mblur_scene::image_io::save(image, path)
}

/// The heat-map colour (8-bit sRGB) of `v` in [0, 1]: black, red, yellow, white.
pub fn heat(v: f64) -> [u8; 3] {
    let v = if v.is_nan() { 1.0 } else { v.clamp(0.0, 1.0) };
    let ramp = |a: f64| ((a.clamp(0.0, 1.0)) * 255.0).round() as u8;
    [ramp(3.0 * v), ramp(3.0 * v - 1.0), ramp(3.0 * v - 2.0)]
}

/// The difference heat map of `image` against `reference`: per pixel the largest absolute
/// channel difference divided by `scale`, through [`heat`]. RGB bytes, row-major.
pub fn difference_rgb(image: &Image, reference: &Image, scale: f64) -> Vec<u8> {
    image
        .pixels
        .iter()
        .zip(&reference.pixels)
        .flat_map(|(p, q)| {
            let d = (0..3)
                .map(|k| (f64::from(p[k]) - f64::from(q[k])).abs())
                .fold(0.0, f64::max);
            heat(d / scale)
        })
        .collect()
}

/// Writes the run's image (left) and its heat-mapped difference from the reference (right)
/// into one PNG of twice the width.
pub fn save_side_by_side(image: &Image, reference: &Image, scale: f64, path: &Path) -> Result<()> {
    let (w, h) = (image.width as usize, image.height as usize);
    let left = image.to_srgb8();
    let right = difference_rgb(image, reference, scale);
    let mut rgb = Vec::with_capacity(left.len() * 2);
    for y in 0..h {
        let row = y * w * 3..(y + 1) * w * 3;
        rgb.extend_from_slice(left.get(row.clone()).unwrap_or_default());
        rgb.extend_from_slice(right.get(row).unwrap_or_default());
    }
    if rgb.len() != w * h * 6 {
        return Err(Error::Write {
            path: path.to_path_buf(),
            message: "the run and the reference differ in size".into(),
        });
    }
    mblur_scene::atomic::write_atomic(path, &png_bytes(image.width * 2, image.height, rgb, path)?)
}

/// A PSNR in dB with two decimals, `inf` for an exact match.
pub(crate) fn fmt_psnr(v: f64) -> String {
    if v.is_infinite() {
        "inf".into()
    } else {
        format!("{v:.2}")
    }
}

fn fmt_heap(b: Option<usize>) -> String {
    b.map_or("n/a".into(), |b| {
        format!("{:.2}", b as f64 / (1024.0 * 1024.0))
    })
}

/// Seconds as milliseconds with three significant digits or more.
pub(crate) fn fmt_ms(s: f64) -> String {
    let ms = s * 1e3;
    if ms >= 100.0 {
        format!("{ms:.0}")
    } else if ms >= 10.0 {
        format!("{ms:.1}")
    } else {
        format!("{ms:.2}")
    }
}

/// The column titles of the printed table.
pub fn table_header() -> String {
    format!(
        "{:>3}  {:<32} {:>10} {:>4} {:>9} {:>8} {:>9} {:>8} {:>7}",
        "#", "setting", "time ms", "reps", "heap MiB", "PSNR dB", "RMSE", "max abs", "SSIM"
    )
}

/// One printed table row (skipped and failed runs carry their reason).
pub fn table_row(r: &RunRecord) -> String {
    let label = r.entry.label();
    match &r.outcome {
        Outcome::Done(s) => format!(
            "{:>3}  {:<32} {:>10} {:>4} {:>9} {:>8} {:>9.6} {:>8.5} {:>7}",
            r.index,
            label,
            fmt_ms(s.seconds),
            s.repeats,
            fmt_heap(s.heap_bytes),
            fmt_psnr(s.metrics.psnr),
            s.metrics.rmse,
            s.metrics.max_abs,
            s.metrics.ssim.map_or("n/a".into(), |v| format!("{v:.4}")),
        ),
        Outcome::Skipped(why) => format!("{:>3}  {label:<32} skipped: {why}", r.index),
        Outcome::Failed(why) => format!("{:>3}  {label:<32} FAILED: {why}", r.index),
    }
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// `results.csv`: one row per run; numbers in full precision, empty where not measured
/// (`peak_heap_bytes` is `n/a` without a heap meter), `detail` is the method's describe
/// line or the skip/failure reason.
pub fn csv(records: &[RunRecord]) -> String {
    let mut out = String::from(
        "index,series,setting,method,status,time_ms,repeats,peak_heap_bytes,psnr_db,rmse,max_abs,ssim,image,detail\n",
    );
    for r in records {
        let e = &r.entry;
        let (nums, detail) = match &r.outcome {
            Outcome::Done(s) => (
                format!(
                    "{},{},{},{},{},{},{}",
                    s.seconds * 1e3,
                    s.repeats,
                    s.heap_bytes.map_or("n/a".into(), |b| b.to_string()),
                    s.metrics.psnr,
                    s.metrics.rmse,
                    s.metrics.max_abs,
                    s.metrics.ssim.map_or("n/a".into(), |v| v.to_string()),
                ),
                s.description.clone(),
            ),
            Outcome::Skipped(why) | Outcome::Failed(why) => (",,,,,,".to_string(), why.clone()),
        };
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{}\n",
            r.index,
            csv_field(&e.series),
            csv_field(&e.setting),
            e.options.method(),
            r.outcome.status(),
            nums,
            r.image_file.as_deref().unwrap_or(""),
            csv_field(&detail),
        ));
    }
    out
}

fn md_cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// `results.md`: a header with the scene, the reference and the machine, the table, then
/// the [Pareto check](crate::pareto) at PSNR `pareto_floor` (dB).
pub fn markdown(
    info: &SceneInfo,
    reference: &Reference,
    records: &[RunRecord],
    total: usize,
    diff_scale: f64,
    pareto_floor: f64,
) -> String {
    let mut out = format!(
        "# mblur compare: {} ({} x {})\n\n\
         - reference: {} ({:.2} s){}\n\
         - machine: {} logical cores, {} worker threads\n\
         - time: median wall time of the repeats (a run repeats while the repeats took < 1 s \
         in total, at most 5 times)\n\
         - heap: peak heap growth during the render (buffers, primitive lists, output image), \
         measured with a counting allocator; n/a when not measured\n\
         - PSNR for peak 1.0, RMSE and max abs on linear RGB; SSIM (Wang et al. 2004, \
         11x11 Gaussian σ=1.5) on the sRGB luma\n\
         - stochastic: samples at the pixel centre (`--footprint centre`), where the \
         reference samples (spread over the pixel they would converge to the box-filtered \
         image instead)\n\
         - images: `run-NN-*.png` = the run | |run - reference| (max channel) / {diff_scale} \
         heat-mapped black-red-yellow-white; `plot.svg` / `plot.png` = PSNR vs wall time\n\
         - {} of {} runs done\n\n",
        info.name,
        info.width,
        info.height,
        md_cell(&reference.description),
        reference.seconds,
        reference
            .note
            .as_ref()
            .map_or(String::new(), |n| format!(" — {}", md_cell(n))),
        std::thread::available_parallelism().map_or(0, |n| n.get()),
        info.threads,
        records.len(),
        total,
    );
    out.push_str(
        "| # | method | setting | time (ms) | reps | peak heap (MiB) | PSNR (dB) | RMSE | max abs | SSIM | image / reason |\n\
         |---:|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n",
    );
    for r in records {
        let e = &r.entry;
        match &r.outcome {
            Outcome::Done(s) => out.push_str(&format!(
                "| {} | {} | {} | {} | {} | {} | {} | {:.6} | {:.5} | {} | [{}]({}) |\n",
                r.index,
                e.series,
                e.setting,
                fmt_ms(s.seconds),
                s.repeats,
                fmt_heap(s.heap_bytes),
                fmt_psnr(s.metrics.psnr),
                s.metrics.rmse,
                s.metrics.max_abs,
                s.metrics.ssim.map_or("n/a".into(), |v| format!("{v:.4}")),
                r.image_file.as_deref().unwrap_or(""),
                r.image_file.as_deref().unwrap_or(""),
            )),
            Outcome::Skipped(why) | Outcome::Failed(why) => out.push_str(&format!(
                "| {} | {} | {} | {} | | | | | | | {} |\n",
                r.index,
                e.series,
                e.setting,
                r.outcome.status(),
                md_cell(why),
            )),
        }
    }
    out.push('\n');
    out.push_str(&crate::pareto::markdown_section(&crate::pareto::check(
        records,
        pareto_floor,
    )));
    out
}

/// Rewrites `results.csv` and `results.md` in `dir` (the Pareto check at `pareto_floor` dB).
pub fn write_all(
    dir: &Path,
    info: &SceneInfo,
    reference: &Reference,
    records: &[RunRecord],
    total: usize,
    diff_scale: f64,
    pareto_floor: f64,
) -> Result<()> {
    mblur_scene::atomic::write_atomic(&dir.join("results.csv"), csv(records).as_bytes())?;
    mblur_scene::atomic::write_atomic(
        &dir.join("results.md"),
        markdown(info, reference, records, total, diff_scale, pareto_floor).as_bytes(),
    )?;
    Ok(())
}

impl fmt::Display for RunRecord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", table_row(self))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heat_map_end_points_and_thirds() {
        assert_eq!(heat(0.0), [0, 0, 0]);
        assert_eq!(heat(1.0 / 3.0), [255, 0, 0]);
        assert_eq!(heat(2.0 / 3.0), [255, 255, 0]);
        assert_eq!(heat(1.0), [255, 255, 255]);
        assert_eq!(heat(7.0), [255, 255, 255]);
        assert_eq!(heat(f64::NAN), [255, 255, 255]);
    }

    #[test]
    fn csv_fields_with_commas_are_quoted() {
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"x\", y"), "\"say \"\"x\"\", y\"");
        assert_eq!(csv_field("plain"), "plain");
    }
}
