//! The analytic method (edge-eqn -> interval-buffer -> resolve) on what only it does:
//! triangles that cross the near plane during the shutter (time-sliced and clipped), against
//! accum at a high time count; and its option and scene errors.
//!
//! Its accuracy against accum on every built-in triangle scene is in
//! `integration-tests/tests/versus_accum.rs`, the static scene's identity with the static
//! path in `integration-tests/tests/effects.rs`, Rønnow's crossing quads with and without
//! intersection handling in `integration-tests/tests/intersections.rs`, the error against
//! the interval count K in `integration-tests/tests/convergence.rs`, and its refusal of splat
//! scenes in `integration-tests/tests/finite.rs`.

use integration_tests::{accum, builtin, from_json, render, rmse};
use mblur::{AnalyticOptions, Method, MethodOptions, NoProgress};

/// A quad starting at depth 6 and ending behind the near plane (depth 0.2 < 0.5): its
/// triangles cannot go to edge-eqn and are rendered in time slices with clipping. The
/// description counts the two crossing triangles, and the image matches accum at 1024
/// sub-frames within RMSE 2e-2.
#[test]
fn quad_moving_through_the_near_plane_matches_accum() {
    let p = from_json(
        r#"{
      "camera": { "width": 48, "height": 32,
        "projection": { "perspective": { "fov_y_deg": 60 } },
        "eye": [0, 0, 6], "target": [0, 0, 0], "near": 0.5, "far": 50 },
      "background": [0.2, 0.2, 0.2],
      "objects": [
        { "name": "wall", "mesh": { "quad": { "size": [20, 20] } },
          "material": { "color": [0.1, 0.6, 0.2, 1] },
          "transform": { "translate": [0, 0, -3] } },
        { "name": "flyer", "mesh": { "quad": { "size": [1.0, 1.0] } },
          "material": { "color": [0.9, 0.8, 0.1, 1] },
          "motion": { "open": { "translate": [0.3, 0, 0] }, "close": { "translate": [0, 0, 5.8] } } }
      ]
    }"#,
    );
    let out = render(&p, &MethodOptions::defaults(Method::Analytic));
    assert!(
        out.description.contains("2 near-plane crossings"),
        "{}",
        out.description
    );
    let e = rmse(&out.image, &accum(&p, 1024));
    eprintln!("near-plane flyer: rmse {e:.5}");
    assert!(e < 2e-2, "{e}");
}

/// More intervals per pixel than the buffer allows: an option error naming `--intervals`.
#[test]
fn too_many_intervals_is_a_setting_error() {
    let p = builtin("billiards", 16, 9);
    let e = mblur::render(
        &p,
        &MethodOptions::Analytic(AnalyticOptions {
            intervals: mblur::analytic::MAX_INTERVALS + 1,
            ..Default::default()
        }),
        &NoProgress,
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("analytic: invalid setting `intervals`: must be at most 1024"),
        "{e}"
    );
}

/// Shading reuses colours a thread computed before (`chain::end_samples`), across pixels
/// and rows too: lit adaptive shading the colour at the end of a partition for the
/// partition starting there, textured shading the tap of a static surface. The image must
/// not depend on what the thread shaded before. Each pixel of three rows, resolved alone on
/// a fresh thread (the pixel visualiser's exact list, nothing recalled), is the rendered
/// pixel, bit for bit; and so is a render on 3 threads, and one on a thread that rendered
/// the other scene of its pair first. Lit: a turning Blinn-Phong ball (large triangles on
/// a curved path) and the lit clothball (a transparent cloth over a ball). Textured: the
/// fence over its static checkerboard and the textured quad.
#[test]
fn shading_does_not_depend_on_what_a_thread_shaded_before() {
    let ball = builtin("spinning-lit-ball", 64, 36);
    let cloth = builtin("clothball-ronnow", 40, 40);
    let fence = builtin("fence", 64, 36);
    let quad = builtin("textured-quad", 48, 36);
    let options = MethodOptions::defaults(Method::Analytic);
    let on = |threads: usize, scenes: &[&mblur::PreparedScene]| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut last = None;
            for s in scenes {
                last = Some(render(s, &options).image);
            }
            last.unwrap()
        })
    };
    for (p, other) in [
        (&ball, &cloth),
        (&cloth, &ball),
        (&fence, &quad),
        (&quad, &fence),
    ] {
        let image = on(1, &[p]);
        let mut seen = 0;
        for y in [p.height / 2 - 4, p.height / 2, p.height / 2 + 4] {
            for x in 0..p.width {
                let alone = std::thread::scope(|s| {
                    s.spawn(|| mblur::inspect::pixel_intervals(p, x, y, 1).unwrap())
                        .join()
                        .unwrap()
                });
                let i = (y * p.width + x) as usize;
                assert_eq!(image.pixels[i], alone.exact.colour, "pixel ({x}, {y})");
                seen += usize::from(!alone.exact.intervals.is_empty());
            }
        }
        assert!(seen > 30, "{seen} pixels see the scene's objects");
        assert_eq!(image, on(3, &[p]), "1 vs 3 threads");
        assert_eq!(image, on(1, &[other, p]), "after another scene");
    }
}
