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
//!     &mblur::RenderOptions { method: mblur::Method::Analytic, ..Default::default() },
//! );
//! assert!(integration_tests::rmse(&analytic.image, &reference) < 0.05);
//! ```

use mblur::{
    AccumOptions, Image, Method, NoProgress, PreparedScene, RenderOptions, Rendered, Scene,
};

/// The built-in scenes made of triangles only (every built-in scene except those with
/// splats, `splat-ball` and `splat-mix`), i.e. the scenes the interval methods
/// (`analytic`, `prism`) apply to.
pub fn triangle_scenes() -> Vec<&'static str> {
    mblur::builtin::SCENES
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

/// Renders with `options` through [`mblur::render`] (the library entry point the CLI uses)
/// and checks that every pixel is finite and non-negative.
///
/// # Panics
/// If the render fails or produces a NaN, infinite or negative value.
pub fn render(scene: &PreparedScene, options: &RenderOptions) -> Rendered {
    let out = mblur::render(scene, options, &NoProgress)
        .unwrap_or_else(|e| panic!("{} render failed: {e}", options.method));
    assert_finite(&out.image, options.method.name());
    out
}

/// Renders with `method` and default options otherwise (see [`render`]).
pub fn render_with(scene: &PreparedScene, method: Method) -> Image {
    render(
        scene,
        &RenderOptions {
            method,
            ..Default::default()
        },
    )
    .image
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
        },
        &NoProgress,
    )
    .unwrap_or_else(|e| panic!("accum reference failed: {e}"));
    assert_finite(&image, "accum");
    image
}

/// The ground truth of a pixel-area (box filter) estimator such as the stochastic method:
/// the built-in scene `name` rendered by `accum` with `times` sub-frames at `k` x `k` times
/// the size, then averaged over each `k` x `k` block (a `k`² point midpoint rule over the
/// pixel area).
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
