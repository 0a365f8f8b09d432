//! Curved motion against the ground truth: `accum` evaluates the true keyed transform
//! (rotation turning at a constant rate) at each of [`TIMES`] instants, independently of the
//! segment chords the interval methods render. A checker-textured wheel turning 90°, 180°
//! and 350° while translating, and a spinning textured box: `analytic` and `prism` with
//! automatic segments stay within a stated RMSE, one segment is measurably wrong, a tighter
//! path tolerance is more accurate. Segment boundaries: a pixel covered across them gets one
//! continuous coverage. Hard cases: a spin past 360° as keys, a zero scale at one key, a
//! camera orbit given by keys.

use integration_tests::{accum, ortho_camera, render, rmse};
use mblur::{Method, MethodOptions, PreparedScene};
use mblur_scene::Scene;
use mblur_scene::segments::{MotionOptions, Segments};

/// Sub-frames of the reference on the true arc.
const TIMES: u32 = 2048;

fn prepare(json: &str, segments: Segments) -> PreparedScene {
    integration_tests::from_json_segments(json, segments)
}

/// A checker-textured wheel (a flat-capped cylinder facing the camera) of radius 20 px
/// turning `degrees` about its axis while moving 12 px right, orthographic, 64 x 48.
fn wheel(degrees: f64) -> String {
    format!(
        r#"{{ {}, "background": [0.1, 0.1, 0.1],
        "objects": [{{ "name": "wheel",
          "mesh": {{ "cylinder": {{ "radius": 20, "height": 2, "segments": 32 }} }},
          "material": {{ "texture": {{ "checker": {{ "squares": 8, "texels_per_square": 4,
              "a": [0.95, 0.95, 0.9, 1], "b": [0.8, 0.2, 0.1, 1] }} }} }},
          "transform": {{ "rotate": {{ "axis": [1, 0, 0], "degrees": 90 }} }},
          "motion": {{ "open": {{ "translate": [-6, 0, 0] }},
                       "close": {{ "translate": [6, 0, 0], "rotate": {{ "axis": [0, 0, 1], "degrees": {degrees} }} }} }} }}] }}"#,
        ortho_camera(64, 48, "")
    )
}

/// A checker-textured box spinning 120° about a tilted axis, perspective, 64 x 48.
fn spinning_box() -> String {
    r#"{ "camera": { "width": 64, "height": 48, "projection": { "perspective": { "fov_y_deg": 40 } },
          "eye": [0, 0, 5], "target": [0, 0, 0], "near": 0.5, "far": 50 },
        "background": [0.1, 0.1, 0.1],
        "objects": [{ "name": "box", "mesh": { "box": { "size": [1.6, 1.6, 1.6] } },
          "material": { "texture": { "checker": { "squares": 4, "texels_per_square": 4 } } },
          "motion": { "keys": [
            { "t": 0, "translate": [-0.3, 0, 0] },
            { "t": 0.5, "rotate": { "axis": [0.3, 1, 0.2], "degrees": 60 } },
            { "t": 1, "translate": [0.3, 0, 0], "rotate": { "axis": [0.3, 1, 0.2], "degrees": 120 } } ] } }] }"#
        .to_string()
}

/// RMSE of `method` against accum on the true path, with `segments`.
fn error(json: &str, method: Method, segments: Segments) -> f64 {
    let truth = accum(&prepare(json, Segments::Auto), TIMES);
    let p = prepare(json, segments);
    let image = render(&p, &MethodOptions::defaults(method)).image;
    rmse(&image, &truth)
}

fn segments_of(json: &str) -> u32 {
    prepare(json, Segments::Auto).objects[0].segments
}

/// Automatic segments within `analytic_bound` (`prism_bound`) of the true arc; one segment
/// at least 3 times worse than automatic ones. The bounds are the RMSE measured when the
/// test was written times about 1.7: what is left is the chords' own error (0.25 px at most
/// per vertex; on the wheel's rim, where the motion is tangential, a pixel centre within
/// that distance of the edge sees the background for part of a segment), and for prism
/// under perspective its screen-linear model.
fn check(name: &str, json: &str, analytic_bound: f64, prism_bound: f64) {
    let auto = error(json, Method::Analytic, Segments::Auto);
    let prism = error(json, Method::Prism, Segments::Auto);
    let one = error(json, Method::Analytic, Segments::Fixed(1));
    let s = segments_of(json);
    eprintln!("{name}: {s} segments; analytic {auto:.2e}, prism {prism:.2e}, 1 segment {one:.2e}");
    assert!(
        auto < analytic_bound,
        "{name}: analytic auto rmse {auto} >= {analytic_bound}"
    );
    assert!(
        prism < prism_bound,
        "{name}: prism auto rmse {prism} >= {prism_bound}"
    );
    assert!(one > 3.0 * auto, "{name}: 1 segment {one} not > 3 x {auto}");
}

#[test]
fn wheel_90_degrees_matches_the_true_arc() {
    check("wheel 90", &wheel(90.0), 2.4e-2, 2.4e-2);
}

#[test]
fn wheel_180_degrees_matches_the_true_arc() {
    check("wheel 180", &wheel(180.0), 2.5e-2, 2.5e-2);
}

#[test]
fn wheel_350_degrees_matches_the_true_arc() {
    check("wheel 350", &wheel(350.0), 1.7e-2, 1.7e-2);
}

#[test]
fn spinning_box_matches_the_true_arc() {
    check("spinning box", &spinning_box(), 6.5e-3, 5.3e-2);
}

/// A tighter path tolerance buys accuracy: 0.05 px instead of 0.25 px at least halves the
/// wheel's error.
#[test]
fn path_tolerance_is_the_accuracy_knob() {
    let json = wheel(350.0);
    let truth = accum(&prepare(&json, Segments::Auto), TIMES);
    let at = |tol: f64| {
        let p = Scene::from_json(&json, "<test>", "")
            .and_then(|s| {
                s.prepare_with(&MotionOptions {
                    segments: Segments::Auto,
                    path_tolerance: tol,
                })
            })
            .unwrap();
        let image = render(&p, &MethodOptions::defaults(Method::Analytic)).image;
        (p.objects[0].segments, rmse(&image, &truth))
    };
    let (coarse, fine) = (at(0.25), at(0.05));
    eprintln!("wheel 350: 0.25 px {coarse:?}, 0.05 px {fine:?}");
    assert!(
        fine.0 > coarse.0 && fine.1 < 0.5 * coarse.1,
        "{coarse:?} {fine:?}"
    );
}

/// More segments converge to the true arc: the error with 8 is below that with 2.
#[test]
fn error_falls_with_segments() {
    let json = wheel(350.0);
    let e: Vec<f64> = [2, 8]
        .map(|n| error(&json, Method::Analytic, Segments::Fixed(n)))
        .to_vec();
    eprintln!(
        "wheel 350: 2 segments {:.2e}, 8 segments {:.2e}",
        e[0], e[1]
    );
    assert!(e[1] < 0.5 * e[0], "{e:?}");
}

/// A half-transparent quad turning 90° about its centre, cut into 4 segments: the pixel at
/// the centre is covered over the whole shutter across the three segment boundaries and
/// shows exactly one layer of the quad over the background (a gap would show more
/// background, a double count more quad).
#[test]
fn segment_boundaries_keep_one_layer() {
    let json = format!(
        r#"{{ {}, "background": [0, 0, 1],
        "objects": [{{ "name": "q", "mesh": {{ "quad": {{ "size": [20, 20] }} }},
          "material": {{ "color": [1, 0, 0, 0.5] }},
          "motion": {{ "close": {{ "rotate": {{ "axis": [0, 0, 1], "degrees": 90 }} }} }} }}] }}"#,
        ortho_camera(32, 32, "")
    );
    let p = prepare(&json, Segments::Fixed(4));
    assert_eq!(p.objects[0].segments, 4);
    let spans: Vec<[f64; 2]> = p.triangles.iter().map(|t| t.span).collect();
    assert!(spans.contains(&[0.25, 0.5]) && spans.contains(&[0.75, 1.0]));
    for method in [Method::Analytic, Method::Prism] {
        let image = render(&p, &MethodOptions::defaults(method)).image;
        // Pixel (16, 16) is centred at world (0.5, -0.5): inside the quad at every angle.
        let c = image.pixels[16 * 32 + 16];
        let want = [0.5, 0.0, 0.5];
        for k in 0..3 {
            assert!((f64::from(c[k]) - want[k]).abs() < 1e-5, "{method}: {c:?}");
        }
    }
}

/// Segments whose chords are the motion itself (a translating half-transparent quad seen by
/// a camera with keys at 0.3 and 0.7: linear 2DH motion between keys by definition): every
/// pixel, including those an edge crosses at a segment boundary, matches dense time
/// sampling (accum at 8192 instants).
#[test]
fn segment_boundaries_match_dense_sampling() {
    let cam = r#", "motion": { "keys": [ { "t": 0 },
        { "t": 0.3, "eye": [3, 1, 10], "target": [3, 1, 0] },
        { "t": 0.7, "eye": [-2, 2, 10], "target": [-2, 2, 0] },
        { "t": 1, "eye": [1, -1, 10], "target": [1, -1, 0] } ] }"#;
    let json = format!(
        r#"{{ {}, "background": [0, 0, 1],
        "objects": [{{ "name": "q", "mesh": {{ "quad": {{ "size": [12, 9] }} }},
          "material": {{ "color": [1, 0.5, 0, 0.5] }},
          "motion": {{ "open": {{ "translate": [-5, 0, 0] }}, "close": {{ "translate": [5, 2, 0] }} }} }}] }}"#,
        ortho_camera(32, 32, cam)
    );
    let p = prepare(&json, Segments::Auto);
    assert_eq!(p.objects[0].segments, 3);
    let dense = accum(&p, 8192);
    for method in [Method::Analytic, Method::Prism] {
        let image = render(&p, &MethodOptions::defaults(method)).image;
        let e = rmse(&image, &dense);
        eprintln!("camera-key segments, {method}: rmse vs dense sampling {e:.2e}");
        assert!(e < 5e-4, "{method}: rmse vs dense sampling {e}");
    }
}

/// A spin past 360° given as three keys renders like accum on the true path, and differs
/// from a still wheel (a 360° chord would be no motion at all).
#[test]
fn spin_past_360_degrees_as_keys() {
    let json = wheel(0.0).replace(
        r#""motion": { "open": { "translate": [-6, 0, 0] },
                       "close": { "translate": [6, 0, 0], "rotate": { "axis": [0, 0, 1], "degrees": 0 } } }"#,
        r#""motion": { "keys": [ { "t": 0 },
            { "t": 0.5, "rotate": { "axis": [0, 0, 1], "degrees": 200 } },
            { "t": 1, "rotate": { "axis": [0, 0, 1], "degrees": 400 } } ] }"#,
    );
    assert!(json.contains("400"), "replacement failed");
    let e = error(&json, Method::Analytic, Segments::Auto);
    let still = prepare(
        &wheel(0.0)
            .replace("[-6, 0, 0]", "[0, 0, 0]")
            .replace("[6, 0, 0]", "[0, 0, 0]"),
        Segments::Auto,
    );
    let moving = accum(&prepare(&json, Segments::Auto), 256);
    let d = rmse(&moving, &accum(&still, 1));
    eprintln!("spin 400 as keys: rmse vs accum {e:.2e}; vs a still wheel {d:.2e}");
    assert!(e < 6.5e-2, "{e}");
    assert!(d > 0.1, "{d}");
}

/// A key with zero scale (the box shrinks to a point mid-shutter and grows back, turning):
/// finite, and analytic matches accum on the true path.
#[test]
fn zero_scale_at_one_key() {
    let json = spinning_box().replace(
        r#"{ "t": 0.5, "rotate": { "axis": [0.3, 1, 0.2], "degrees": 60 } }"#,
        r#"{ "t": 0.5, "rotate": { "axis": [0.3, 1, 0.2], "degrees": 60 }, "scale": 0 }"#,
    );
    assert!(json.contains(r#""scale": 0"#));
    let e = error(&json, Method::Analytic, Segments::Auto);
    eprintln!("zero scale key: rmse {e:.2e}");
    assert!(e < 4e-3, "{e}");
}

/// A camera orbiting a static box through five keys: the static box is cut at the camera's
/// key times and analytic matches accum.
#[test]
fn camera_orbit_with_keys() {
    let key = |t: f64| {
        let a = (t * 60.0_f64 - 30.0).to_radians();
        format!(
            r#"{{ "t": {t}, "eye": [{}, 1, {}] }}"#,
            5.0 * a.sin(),
            5.0 * a.cos()
        )
    };
    let keys: Vec<String> = [0.0, 0.25, 0.5, 0.75, 1.0].map(key).to_vec();
    let json = format!(
        r#"{{ "camera": {{ "width": 64, "height": 48, "projection": {{ "perspective": {{ "fov_y_deg": 40 }} }},
            "eye": [0, 1, 5], "target": [0, 0, 0], "near": 0.5, "far": 50,
            "motion": {{ "keys": [{}] }} }},
          "objects": [{{ "name": "box", "mesh": {{ "box": {{ "size": [1.6, 1.6, 1.6] }} }},
            "material": {{ "texture": {{ "checker": {{ "squares": 4, "texels_per_square": 4 }} }} }} }}] }}"#,
        keys.join(",")
    );
    let p = prepare(&json, Segments::Auto);
    assert_eq!(p.objects[0].segments, 4);
    let e = error(&json, Method::Analytic, Segments::Auto);
    eprintln!("camera orbit: rmse {e:.2e}");
    assert!(e < 2e-3, "{e}");
}

/// Stochastic with its samples at the pixel centre (the quantity accum estimates).
fn stochastic(spp: u32) -> MethodOptions {
    MethodOptions::Stochastic(mblur::StochasticOptions {
        spp: Some(spp),
        footprint: mblur::Footprint::Centre,
        ..Default::default()
    })
}

/// Stochastic follows the segments, so it converges to accum's true-arc image on the wheel
/// turning 350°: its RMSE against accum at [`TIMES`] instants falls with the samples per
/// pixel, to within 2.5x of analytic's (the automatic chords' own error) at 1024 spp, while
/// the one-chord version (1 segment) stays at least 3x above it.
#[test]
fn stochastic_converges_to_the_true_arc() {
    let json = wheel(350.0);
    let truth = accum(&prepare(&json, Segments::Auto), TIMES);
    let auto = prepare(&json, Segments::Auto);
    let err = |p: &PreparedScene, spp: u32| rmse(&render(p, &stochastic(spp)).image, &truth);
    let ladder: Vec<(u32, f64)> = [16, 64, 256, 1024].map(|s| (s, err(&auto, s))).to_vec();
    let analytic = rmse(
        &render(&auto, &MethodOptions::defaults(Method::Analytic)).image,
        &truth,
    );
    let chord = err(&prepare(&json, Segments::Fixed(1)), 1024);
    eprintln!(
        "wheel 350, stochastic (centre) vs accum {TIMES}: {ladder:?}; analytic {analytic:.2e}; \
         one chord at 1024 spp {chord:.2e}"
    );
    for w in ladder.windows(2) {
        assert!(w[1].1 < w[0].1, "{ladder:?}");
    }
    let best = ladder[3].1;
    assert!(best < 2.5 * analytic, "{best} vs analytic {analytic}");
    assert!(chord > 3.0 * best, "chord {chord} vs segments {best}");
}

/// Segment boundaries in stochastic: an opaque quad turning 90° in 4 segments (boundaries
/// at 0.25, 0.5, 0.75, which some samples hit exactly) covers every pixel near its centre
/// at every instant, so those pixels show the quad's colour exactly (a sample that fell
/// between two segments would show the background); over the whole image stochastic at
/// 1024 spp matches dense time sampling of the same 4 segments (accum at 8192 instants on
/// their chords) to its sampling noise.
#[test]
fn stochastic_segment_boundaries_leave_no_gap() {
    let json = format!(
        r#"{{ {}, "background": [0, 0, 1],
        "objects": [{{ "name": "q", "mesh": {{ "quad": {{ "size": [20, 20] }} }},
          "material": {{ "color": [1, 0, 0, 1] }},
          "motion": {{ "close": {{ "rotate": {{ "axis": [0, 0, 1], "degrees": 90 }} }} }} }}] }}"#,
        ortho_camera(32, 32, "")
    );
    let p = prepare(&json, Segments::Fixed(4));
    let image = render(&p, &stochastic(1024)).image;
    let mut inside = 0;
    for j in 0..32u32 {
        for i in 0..32u32 {
            // World position of the pixel centre; the quad always covers the disc of radius 10.
            let (x, y) = (f64::from(i) + 0.5 - 16.0, 16.0 - f64::from(j) - 0.5);
            if x.hypot(y) < 9.0 {
                inside += 1;
                let px = image.pixels[(j * 32 + i) as usize];
                assert_eq!(px, [1.0, 0.0, 0.0], "pixel ({i}, {j})");
            }
        }
    }
    assert!(inside > 200, "{inside}");
    let dense = integration_tests::chord_accum(&p, 8192);
    let e = rmse(&image, &dense);
    eprintln!("4 segments, stochastic 1024 spp vs dense accum of the chords: {e:.2e}");
    assert!(e < 1e-3, "{e}");
}
