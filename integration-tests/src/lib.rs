//! # integration-tests
//!
//! End-to-end tests of the `mblur` renderer at small resolutions, each against a reference
//! that does not share the code under test: the `accum` method (many static renders at
//! evenly spaced times, averaged with the shutter weights; supersampled and box-filtered when
//! the method under test integrates over the pixel area), the static rasteriser, or the
//! analytic answer of a scene built so the answer is known (Rønnow 2021, Fig. 11).
//!
//! The tests live in `tests/` (see the crate README for what each one checks and the bounds
//! it asserts). This library holds the helpers they share: loading a built-in scene at a
//! small size ([`builtin`]), rendering with a checked, NaN-free result ([`render`]), the
//! references ([`accum`], [`supersampled_accum`]), the error metric ([`rmse`]) and the
//! log-log slope fit of error against sample count ([`loglog_slope`]).
//!
//! ```
//! let p = integration_tests::builtin("crossing-quads", 32, 24);
//! let reference = integration_tests::accum(&p, 64);
//! let analytic = integration_tests::render(
//!     &p,
//!     &mblur::MethodOptions::defaults(mblur::Method::Analytic),
//! );
//! assert!(integration_tests::rmse(&analytic.image, &reference) < 0.05);
//! ```

pub mod gltf_fixtures;

use mblur::{AccumOptions, Image, Method, MethodOptions, NoProgress, PreparedScene, Rendered};
use mblur_scene::Scene;

/// The built-in scenes made of triangles only (every built-in scene except those with
/// splats, `splat-ball` and `splat-mix`), i.e. the scenes the interval methods
/// (`analytic`, `prism`) apply to.
pub fn triangle_scenes() -> Vec<&'static str> {
    mblur_scene::builtin::SCENES
        .iter()
        .map(|&(name, _, _)| name)
        .filter(|&name| {
            let p = builtin(name, 8, 8);
            p.splats.is_empty()
        })
        .collect()
}

/// A built-in scene at `width` x `height`, prepared.
///
/// # Panics
/// If the name is unknown or the size is invalid (a test setup error).
pub fn builtin(name: &str, width: u32, height: u32) -> PreparedScene {
    let mut scene = Scene::builtin(name).unwrap_or_else(|e| panic!("{name}: {e}"));
    scene
        .set_size(Some(width), Some(height))
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    scene.prepare().unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A scene from JSON text (file paths relative to the current folder), prepared.
///
/// # Panics
/// If the scene is invalid (a test setup error).
pub fn from_json(json: &str) -> PreparedScene {
    Scene::from_json(json, "<test>", "")
        .and_then(|s| s.prepare())
        .unwrap_or_else(|e| panic!("{e}"))
}

/// As [`from_json`], with curved paths cut into `segments`.
///
/// # Panics
/// If the scene is invalid (a test setup error).
pub fn from_json_segments(json: &str, segments: mblur_scene::segments::Segments) -> PreparedScene {
    let opts = mblur_scene::segments::MotionOptions {
        segments,
        ..Default::default()
    };
    Scene::from_json(json, "<test>", "")
        .and_then(|s| s.prepare_with(&opts))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// As [`from_json`], resized to `width` x `height`.
///
/// # Panics
/// If the scene or the size is invalid (a test setup error).
pub fn from_json_at(json: &str, width: u32, height: u32) -> PreparedScene {
    let mut s = Scene::from_json(json, "<test>", "").unwrap_or_else(|e| panic!("{e}"));
    s.set_size(Some(width), Some(height))
        .unwrap_or_else(|e| panic!("{e}"));
    s.prepare().unwrap_or_else(|e| panic!("{e}"))
}

/// Orthographic camera looking down -Z at the XY plane; 1 world unit = 1 pixel, image
/// `w` x `h`, pixel (i, j) centred at world (i + 0.5 - w/2, h/2 - j - 0.5).
pub fn ortho_camera(w: u32, h: u32, extra: &str) -> String {
    format!(
        r#""camera": {{ "width": {w}, "height": {h}, "projection": {{ "orthographic": {{ "height": {h} }} }},
            "eye": [0, 0, 10], "target": [0, 0, 0], "near": 1, "far": 100 {extra} }}"#
    )
}

/// Renders with `options` through [`mblur::render`] (the library entry point the CLI uses)
/// and checks that every pixel is finite and non-negative.
///
/// # Panics
/// If the render fails or produces a NaN, infinite or negative value.
pub fn render(scene: &PreparedScene, options: &MethodOptions) -> Rendered {
    let out = mblur::render(scene, options, &NoProgress)
        .unwrap_or_else(|e| panic!("{} render failed: {e}", options.method()));
    assert_finite(&out.image, options.method().name());
    out
}

/// Renders with `method` and default options otherwise (see [`render`]).
pub fn render_with(scene: &PreparedScene, method: Method) -> Image {
    render(scene, &MethodOptions::defaults(method)).image
}

/// Asserts that every channel of every pixel is finite and non-negative.
///
/// # Panics
/// Naming `what` and the first bad pixel.
pub fn assert_finite(image: &Image, what: &str) {
    if let Some((i, px)) = image
        .pixels
        .iter()
        .enumerate()
        .find(|(_, px)| px.iter().any(|c| !c.is_finite() || *c < 0.0))
    {
        panic!(
            "{what}: pixel ({}, {}) is {px:?}",
            i as u32 % image.width,
            i as u32 / image.width
        );
    }
}

/// The ground truth at pixel centres: `accum` with `times` evenly spaced sub-frames (the
/// shutter integral by the midpoint rule over `times` strata, each weighted by the exact
/// integral of the shutter response over it).
pub fn accum(scene: &PreparedScene, times: u32) -> Image {
    let image = mblur::accum::render(
        scene,
        &AccumOptions {
            times: Some(times),
            jitter: None,
            ..Default::default()
        },
        &NoProgress,
    )
    .unwrap_or_else(|e| panic!("accum reference failed: {e}"));
    assert_finite(&image, "accum");
    image
}

/// `scene` with the true paths of its curved objects dropped: `accum` then places every
/// sub-frame on the segments' chords, the motion the interval methods render exactly (the
/// chords' own distance to the true arc is measured by `tests/curved_motion.rs`).
pub fn chords(scene: &PreparedScene) -> PreparedScene {
    let mut out = scene.clone();
    for o in &mut out.objects {
        o.path = None;
    }
    out
}

/// `accum` of the segments' chords ([`chords`]): the reference of a method's exactness on
/// the motion it is given.
pub fn chord_accum(scene: &PreparedScene, times: u32) -> Image {
    accum(&chords(scene), times)
}

/// The ground truth of a pixel-area (box filter) estimator such as the stochastic method:
/// the built-in scene `name` rendered by `accum` (on the true motion, curved paths
/// included) with `times` sub-frames at `k` x `k` times the size, then averaged over each
/// `k` x `k` block (a `k`² point midpoint rule over the pixel area).
pub fn supersampled_accum(name: &str, width: u32, height: u32, k: u32, times: u32) -> Image {
    let big = accum(&builtin(name, width * k, height * k), times);
    downsample(&big, k)
}

/// Box-filters `image` by `k` in both directions (its size must be a multiple of `k`).
///
/// # Panics
/// If the size is not a multiple of `k` or `k` is 0.
pub fn downsample(image: &Image, k: u32) -> Image {
    assert!(k > 0 && image.width.is_multiple_of(k) && image.height.is_multiple_of(k));
    let (w, h) = (image.width / k, image.height / k);
    let inv = 1.0 / f64::from(k * k);
    let pixels = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let mut acc = [0.0f64; 3];
            for sy in 0..k {
                for sx in 0..k {
                    let px = image.pixels[((y * k + sy) * image.width + x * k + sx) as usize];
                    for (a, v) in acc.iter_mut().zip(px) {
                        *a += f64::from(v);
                    }
                }
            }
            acc.map(|v| (v * inv) as f32)
        })
        .collect();
    Image {
        width: w,
        height: h,
        pixels,
    }
}

/// Root-mean-square difference over all pixels and the three channels.
///
/// # Panics
/// If the sizes differ.
pub fn rmse(a: &Image, b: &Image) -> f64 {
    a.rmse(b).expect("images of the same size")
}

/// Largest absolute channel difference of two images of one size.
pub fn max_abs(a: &Image, b: &Image) -> f64 {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(p, q)| (0..3).map(move |k| (f64::from(p[k]) - f64::from(q[k])).abs()))
        .fold(0.0, f64::max)
}

/// The number of interval lines in each panel of an SVG drawn by the temporal pixel
/// visualiser (`mblur_lab::inspect::to_svg`), read with an XML parser.
///
/// # Panics
/// If the SVG is not well-formed XML with an `svg` root.
pub fn svg_panel_intervals(svg: &str) -> Vec<usize> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    doc.descendants()
        .filter(|n| n.has_tag_name("g") && n.attribute("class") == Some("panel"))
        .map(|g| {
            g.descendants()
                .filter(|n| n.has_tag_name("line") && n.attribute("class") == Some("interval"))
                .count()
        })
        .collect()
}

/// The names of the files and folders in `dir`, sorted (to check what a command or a failed
/// write left behind).
///
/// # Panics
/// If the folder cannot be read.
pub fn files(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The data rows of `results.csv` in `dir` (as `mblur compare` writes it), each split into
/// its fields (commas inside double quotes do not split).
///
/// # Panics
/// If the file cannot be read.
pub fn csv_rows(dir: &std::path::Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    let mut rows = Vec::new();
    for line in text.lines().skip(1) {
        // Split on commas outside quotes.
        let mut fields = vec![String::new()];
        let mut quoted = false;
        for c in line.chars() {
            match c {
                '"' => quoted = !quoted,
                ',' if !quoted => fields.push(String::new()),
                _ => fields.last_mut().unwrap().push(c),
            }
        }
        rows.push(fields);
    }
    rows
}

/// Least-squares slope of `ln(error)` against `ln(samples)`: -0.5 for an error falling like
/// 1 / sqrt(samples) (plain Monte Carlo), steeper (more negative) for stratified samples.
///
/// # Panics
/// If fewer than two points are given or any value is not positive.
pub fn loglog_slope(points: &[(f64, f64)]) -> f64 {
    assert!(points.len() >= 2);
    assert!(points.iter().all(|&(x, y)| x > 0.0 && y > 0.0));
    let n = points.len() as f64;
    let (xs, ys): (Vec<f64>, Vec<f64>) = points.iter().map(|&(x, y)| (x.ln(), y.ln())).unzip();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_of_a_power_law_is_its_exponent() {
        let pts: Vec<(f64, f64)> = [1.0, 4.0, 16.0, 64.0]
            .iter()
            .map(|&s: &f64| (s, 0.3 * s.powf(-0.5)))
            .collect();
        assert!((loglog_slope(&pts) + 0.5).abs() < 1e-12);
    }

    #[test]
    fn downsample_averages_blocks() {
        let img = Image {
            width: 2,
            height: 2,
            pixels: vec![[0.0; 3], [1.0; 3], [2.0; 3], [3.0; 3]],
        };
        assert_eq!(downsample(&img, 2).pixels, vec![[1.5; 3]]);
    }

    #[test]
    fn splat_ball_is_not_a_triangle_scene() {
        let s = triangle_scenes();
        assert!(!s.contains(&"splat-ball") && s.contains(&"fence"));
    }
}
