//! AOVs against hand-computed references: motion vectors of a translating quad are its
//! projected displacement, the depth of a tilted static plane is the ray-plane distance, the
//! coverage of a moving quad is the fraction of the shutter its screen span holds the pixel
//! centre, the sharp layer is the render of the scene frozen at that instant, and ids name
//! the object in front.

use integration_tests::{from_json, render, rmse};
use mblur::{AovOptions, AovSet, Method, MethodOptions, NoProgress, render_aovs};

const W: u32 = 48;
const H: u32 = 32;

/// Focal length in pixels of the cameras below (vertical field of view 40°).
fn focal() -> f64 {
    (f64::from(H) / 2.0) / 20f64.to_radians().tan()
}

fn scene(objects: &str) -> String {
    format!(
        r#"{{ "camera": {{ "width": {W}, "height": {H}, "projection": {{ "perspective": {{ "fov_y_deg": 40 }} }},
      "eye": [0, 0, 5], "target": [0, 0, 0], "near": 0.1, "far": 100 }},
      "background": [0.1, 0.1, 0.1], "objects": [ {objects} ] }}"#
    )
}

/// A unit quad at depth 5 moving from `from` to `to` (world x, y).
fn moving_quad(from: [f64; 2], to: [f64; 2]) -> String {
    scene(&format!(
        r#"{{ "name": "q", "mesh": {{ "quad": {{ "size": [1, 1] }} }},
        "material": {{ "color": [0.9, 0.5, 0.2, 1] }},
        "motion": {{ "open": {{ "translate": [{}, {}, 0] }}, "close": {{ "translate": [{}, {}, 0] }} }} }}"#,
        from[0], from[1], to[0], to[1]
    ))
}

#[test]
fn motion_vectors_of_a_translating_quad_are_its_projected_displacement() {
    let p = from_json(&moving_quad([-0.4, -0.2], [0.4, 0.2]));
    let which = AovSet {
        motion: true,
        id: true,
        ..AovSet::default()
    };
    let a = render_aovs(&p, which, &AovOptions::default(), &NoProgress).unwrap();
    let (motion, id) = (a.motion.unwrap(), a.id.unwrap());
    // Depth 5 throughout: x moves by f * 0.8 / 5 pixels, y by -f * 0.4 / 5 (rows go down).
    let want = [focal() * 0.8 / 5.0, -focal() * 0.4 / 5.0];
    let mut covered = 0;
    for (m, i) in motion.iter().zip(&id) {
        if *i == 1 {
            covered += 1;
            assert!(
                (f64::from(m[0]) - want[0]).abs() < 1e-4,
                "{m:?} vs {want:?}"
            );
            assert!(
                (f64::from(m[1]) - want[1]).abs() < 1e-4,
                "{m:?} vs {want:?}"
            );
        } else {
            assert_eq!(*m, [0.0, 0.0]);
            assert_eq!(*i, 0);
        }
    }
    // The quad at mid-shutter spans f / 5 pixels a side.
    let side = focal() / 5.0;
    assert!(
        (f64::from(covered) - side * side).abs() < 2.0 * side + 2.0,
        "{covered}"
    );
}

#[test]
fn depth_of_a_tilted_static_plane_is_the_ray_plane_distance() {
    let p = from_json(&scene(
        r#"{ "name": "plane", "mesh": { "quad": { "size": [3, 3] } },
        "material": { "color": [0.5, 0.5, 0.5, 1] },
        "transform": { "rotate": { "axis": [0, 1, 0], "degrees": 30 } } }"#,
    ));
    let which = AovSet {
        depth: true,
        coverage: true,
        ..AovSet::default()
    };
    let a = render_aovs(&p, which, &AovOptions::default(), &NoProgress).unwrap();
    let (depth, coverage) = (a.depth.unwrap(), a.coverage.unwrap());
    let n = [30f64.to_radians().sin(), 0.0, 30f64.to_radians().cos()];
    let f = focal();
    let mut inside = 0;
    for j in 0..H {
        for i in 0..W {
            let k = (j * W + i) as usize;
            // The pixel centre's ray from the eye (0, 0, 5), view depth 1 per unit of s.
            let d = [
                (f64::from(i) + 0.5 - f64::from(W) / 2.0) / f,
                -(f64::from(j) + 0.5 - f64::from(H) / 2.0) / f,
                -1.0,
            ];
            let s = -(n[2] * 5.0) / (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
            let hit = [s * d[0], s * d[1], 5.0 + s * d[2]];
            // In the plane's own coordinates: within the 3 x 3 square?
            let u = hit[0] * n[2] - hit[2] * n[0];
            if u.abs() < 1.45 && hit[1].abs() < 1.45 {
                inside += 1;
                assert_eq!(coverage[k], 1.0, "pixel ({i}, {j})");
                let rel = (f64::from(depth[k]) - s).abs() / s;
                assert!(rel < 1e-6, "pixel ({i}, {j}): {} vs {s}", depth[k]);
            } else if u.abs() > 1.55 || hit[1].abs() > 1.55 {
                assert_eq!(coverage[k], 0.0, "pixel ({i}, {j})");
                assert_eq!(depth[k], 100.0, "the far plane where never covered");
            }
        }
    }
    assert!(inside > 300, "{inside}");
}

#[test]
fn coverage_of_a_moving_quad_is_the_fraction_of_the_shutter_it_holds_the_centre() {
    let p = from_json(&moving_quad([-0.4, 0.0], [0.4, 0.0]));
    let which = AovSet {
        coverage: true,
        depth: true,
        ..AovSet::default()
    };
    let options = AovOptions {
        times: Some(4096),
        ..AovOptions::default()
    };
    let a = render_aovs(&p, which, &options, &NoProgress).unwrap();
    let (coverage, depth) = (a.coverage.unwrap(), a.depth.unwrap());
    let f = focal();
    let half = f * 0.5 / 5.0;
    let (c0, c1) = (
        f64::from(W) / 2.0 - f * 0.4 / 5.0,
        f64::from(W) / 2.0 + f * 0.4 / 5.0,
    );
    let row = H / 2; // centre y = 16.5, within the quad's rows
    for i in 0..W {
        let x = f64::from(i) + 0.5;
        // The centre c(t) = c0 + (c1 - c0) t holds x while |x - c(t)| < half.
        let lo = ((x - half - c0) / (c1 - c0)).clamp(0.0, 1.0);
        let hi = ((x + half - c0) / (c1 - c0)).clamp(0.0, 1.0);
        let want = hi - lo;
        let k = (row * W + i) as usize;
        assert!(
            (f64::from(coverage[k]) - want).abs() <= 2.0 / 4096.0,
            "pixel {i}: {} vs {want}",
            coverage[k]
        );
        if want > 0.01 {
            assert!((depth[k] - 5.0).abs() < 1e-5, "pixel {i}: {}", depth[k]);
        }
    }
}

#[test]
fn the_sharp_layer_is_the_scene_frozen_at_that_instant() {
    let moving = from_json(&moving_quad([-0.4, 0.0], [0.4, 0.0]));
    let frozen = from_json(&scene(
        r#"{ "name": "q", "mesh": { "quad": { "size": [1, 1] } },
        "material": { "color": [0.9, 0.5, 0.2, 1] }, "transform": { "translate": [-0.2, 0, 0] } }"#,
    ));
    let which = AovSet {
        sharp: true,
        ..AovSet::default()
    };
    let options = AovOptions {
        sharp_at: 0.25,
        ..AovOptions::default()
    };
    let sharp = render_aovs(&moving, which, &options, &NoProgress)
        .unwrap()
        .sharp
        .unwrap();
    let still = render(&frozen, &MethodOptions::defaults(Method::Analytic)).image;
    assert!(rmse(&sharp, &still) < 1e-6, "{}", rmse(&sharp, &still));
    let moved = render(&moving, &MethodOptions::defaults(Method::Analytic)).image;
    assert!(
        rmse(&sharp, &moved) > 1e-2,
        "the sharp layer is not the blurred image"
    );
}

#[test]
fn ids_name_the_object_in_front_at_the_sharp_instant() {
    // A wall (object 0) behind a card (object 1) that moves from the left half to the right
    // half: at 0.1 the card covers the left centre, at 0.9 the right.
    let p = from_json(&scene(
        r#"{ "name": "wall", "mesh": { "quad": { "size": [20, 20] } },
          "material": { "color": [0.2, 0.2, 0.6, 1] }, "transform": { "translate": [0, 0, -1] } },
        { "name": "card", "mesh": { "quad": { "size": [0.6, 0.6] } },
          "material": { "color": [0.9, 0.9, 0.2, 0.5] },
          "motion": { "open": { "translate": [-1, 0, 0] }, "close": { "translate": [1, 0, 0] } } }"#,
    ));
    let id_at = |t: f64| {
        let which = AovSet {
            id: true,
            ..AovSet::default()
        };
        let options = AovOptions {
            sharp_at: t,
            ..AovOptions::default()
        };
        render_aovs(&p, which, &options, &NoProgress)
            .unwrap()
            .id
            .unwrap()
    };
    let f = focal();
    let px = |x: f64| ((f64::from(W) / 2.0 + f * x / 5.0) as u32 + H / 2 * W) as usize;
    let (early, late) = (id_at(0.1), id_at(0.9));
    // At t = 0.1 the card is at x = -0.8; at 0.9 at x = +0.8 (a transparent card is still the
    // nearest surface).
    assert_eq!((early[px(-0.8)], early[px(0.8)]), (2, 1));
    assert_eq!((late[px(-0.8)], late[px(0.8)]), (1, 2));
    assert!(
        early.iter().all(|&i| i == 1 || i == 2),
        "the wall covers the view"
    );
}

#[test]
fn options_out_of_range_name_the_setting() {
    let p = from_json(&moving_quad([0.0, 0.0], [0.1, 0.0]));
    for options in [
        AovOptions {
            sharp_at: 1.5,
            ..AovOptions::default()
        },
        AovOptions {
            times: Some(0),
            ..AovOptions::default()
        },
    ] {
        let e = render_aovs(&p, AovSet::ALL, &options, &NoProgress).unwrap_err();
        assert!(
            matches!(e, mblur::Error::Setting { method: "aov", .. }),
            "{e}"
        );
    }
}
