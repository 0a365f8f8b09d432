//! Helpers shared by mblur's integration tests: scenes at a test size, renders by method
//! (every pixel checked finite and non-negative), image comparisons and the command under
//! test. Each test file uses a subset.
#![allow(dead_code)]

use assert_cmd::Command;
use mblur::{Image, Method, NoProgress, PreparedScene, RenderOptions, Rendered, Scene};

/// The built-in scene `name` at `w` x `h` pixels, prepared.
pub fn builtin(name: &str, w: u32, h: u32) -> PreparedScene {
    let mut s = Scene::builtin(name).unwrap();
    s.set_size(Some(w), Some(h)).unwrap();
    s.prepare().unwrap()
}

/// A scene from JSON text (file paths relative to the current folder), prepared.
pub fn from_json(json: &str) -> PreparedScene {
    Scene::from_json(json, "<test>", "")
        .unwrap()
        .prepare()
        .unwrap()
}

/// As [`from_json`], resized to `w` x `h`.
pub fn from_json_at(json: &str, w: u32, h: u32) -> PreparedScene {
    let mut s = Scene::from_json(json, "<test>", "").unwrap();
    s.set_size(Some(w), Some(h)).unwrap();
    s.prepare().unwrap()
}

/// Renders `scene` with `options`; every pixel must be finite and non-negative.
pub fn render(scene: &PreparedScene, options: RenderOptions) -> Rendered {
    let r = mblur::render(scene, &options, &NoProgress).unwrap();
    assert_finite(&r.image, r.method);
    r
}

/// Renders `scene` with `method` and otherwise default options.
pub fn render_with(scene: &PreparedScene, method: Method) -> Image {
    render(
        scene,
        RenderOptions {
            method,
            ..Default::default()
        },
    )
    .image
}

/// The accum ground truth with `times` sub-frames.
pub fn accum(scene: &PreparedScene, times: u32) -> Image {
    render(
        scene,
        RenderOptions {
            method: Method::Accum,
            times: Some(times),
            ..Default::default()
        },
    )
    .image
}

/// Every channel finite and non-negative; `what` names the render in the failure message.
pub fn assert_finite(img: &Image, what: &str) {
    assert!(
        img.pixels
            .iter()
            .flatten()
            .all(|c| c.is_finite() && *c >= 0.0),
        "{what}: NaN, inf or negative pixel"
    );
}

/// RMSE over the RGB channels of two images of one size.
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

/// The `mblur` command built from this crate.
pub fn mblur() -> Command {
    Command::cargo_bin("mblur").unwrap()
}
