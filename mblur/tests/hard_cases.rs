//! Hard cases by name: accum against hand-computed references.

use integration_tests::ortho_camera as ortho;
use mblur::NoProgress;
use mblur::accum::{self, AccumOptions};
use mblur_scene::Scene;

fn scene(json: &str) -> Scene {
    Scene::from_json(json, "test.json", ".").unwrap_or_else(|e| panic!("{e}"))
}

fn accum(s: &Scene, times: u32) -> mblur::Image {
    accum::render(
        &s.prepare().unwrap(),
        &AccumOptions {
            times: Some(times),
            jitter: None,
            ..Default::default()
        },
        &NoProgress,
    )
    .unwrap()
}

/// A quad from x0 to x1 (world), full height, at depth z, as two inline triangles.
fn slab(x0: f64, x1: f64, z: f64) -> String {
    format!(
        "[[[{x0}, -100, {z}], [{x1}, -100, {z}], [{x1}, 100, {z}]], [[{x0}, -100, {z}], [{x1}, 100, {z}], [{x0}, 100, {z}]]]"
    )
}

#[test]
fn static_half_cover_hits_exactly_the_covered_centres() {
    // Image 8 x 2; the slab covers world x in [-4, -0.3]: pixel centres -3.5 .. -0.5 -> i = 0..3.
    let s = scene(&format!(
        r#"{{ {}, "background": [0, 0, 1],
            "objects": [{{ "name": "half", "mesh": {{ "triangles": {} }}, "material": {{ "color": [1, 0, 0, 1] }} }}] }}"#,
        ortho(8, 2, ""),
        slab(-4.0, -0.3, 0.0)
    ));
    let img = accum(&s, 1);
    for j in 0..2 {
        for i in 0..8 {
            let expect = if i < 4 {
                [1.0, 0.0, 0.0]
            } else {
                [0.0, 0.0, 1.0]
            };
            assert_eq!(img.get(i, j).unwrap(), expect, "pixel ({i}, {j})");
        }
    }
}

#[test]
fn moving_edge_box_shutter_matches_analytic_coverage_fraction() {
    // Right edge of a white slab moves from pixel x = 2 to x = 10 (world -6 .. 2 in a 16-wide
    // image). A centre c is covered for t >= (c - 2) / 8, so its value is 1 - (c - 2) / 8
    // clamped to [0, 1]. With 16 sub-frames at stratum midpoints this is exact.
    let s = scene(&format!(
        r#"{{ {}, "objects": [{{ "name": "slab", "mesh": {{ "triangles": {} }},
              "motion": {{ "open": {{ "translate": [-6, 0, 0] }}, "close": {{ "translate": [2, 0, 0] }} }} }}] }}"#,
        ortho(16, 1, ""),
        slab(-50.0, 0.0, 0.0)
    ));
    let img = accum(&s, 16);
    for i in 0..16 {
        let c = f64::from(i) + 0.5;
        let expect = (1.0 - (c - 2.0) / 8.0).clamp(0.0, 1.0);
        let got = f64::from(img.get(i, 0).unwrap()[0]);
        assert!((got - expect).abs() < 1e-6, "pixel {i}: {got} vs {expect}");
    }
}

#[test]
fn moving_edge_tent_shutter_converges_to_exact_integral() {
    // Same edge motion with the tent response w(t) = 1 - |2t - 1|: value = integral of w over
    // [t_c, 1] / integral over [0, 1], t_c = (c - 2) / 8.
    let s = scene(&format!(
        r#"{{ {}, "shutter": {{ "response": "tent" }},
            "objects": [{{ "name": "slab", "mesh": {{ "triangles": {} }},
              "motion": {{ "open": {{ "translate": [-6, 0, 0] }}, "close": {{ "translate": [2, 0, 0] }} }} }}] }}"#,
        ortho(16, 1, ""),
        slab(-50.0, 0.0, 0.0)
    ));
    let n = 1024;
    let img = accum(&s, n);
    let tent_tail = |a: f64| -> f64 {
        // integral of the tent over [a, 1], total 0.5
        let a = a.clamp(0.0, 1.0);
        let f = |t: f64| {
            if t <= 0.5 {
                t * t
            } else {
                0.5 - (1.0 - t) * (1.0 - t)
            }
        };
        (0.5 - f(a)) / 0.5
    };
    for i in 0..16 {
        let c = f64::from(i) + 0.5;
        let expect = tent_tail((c - 2.0) / 8.0);
        let got = f64::from(img.get(i, 0).unwrap()[0]);
        // Coverage switches once inside one stratum: error at most that stratum's weight.
        assert!(
            (got - expect).abs() <= 2.0 / f64::from(n),
            "pixel {i}: {got} vs {expect}"
        );
    }
}

/// accum keeps static triangles in a base layer and, per sub-frame, draws the moving ones
/// over it and returns what they changed to the base: the base's transparent fragments
/// must survive every sub-frame and the moving ones must leave with theirs.
#[test]
fn moving_transparent_edge_over_a_static_transparent_layer_blends_per_sub_frame() {
    // Static red (alpha 0.5) at z = 1 over the blue background everywhere; a green slab
    // (alpha 0.5) at z = 2 in front, its right edge moving from pixel x = 2 to x = 10 as in
    // `moving_edge_box_shutter_matches_analytic_coverage_fraction`, so centre c is covered
    // a fraction f = 1 - (c - 2) / 8 (clamped) of the shutter. Covered: green over red over
    // blue = (0.25, 0.5, 0.25); uncovered: red over blue = (0.5, 0, 0.5). Exact with 16
    // sub-frames at stratum midpoints.
    let s = scene(&format!(
        r#"{{ {}, "background": [0, 0, 1], "objects": [
            {{ "name": "red", "mesh": {{ "triangles": {} }}, "material": {{ "color": [1, 0, 0, 0.5] }} }},
            {{ "name": "green", "mesh": {{ "triangles": {} }}, "material": {{ "color": [0, 1, 0, 0.5] }},
              "motion": {{ "open": {{ "translate": [-6, 0, 0] }}, "close": {{ "translate": [2, 0, 0] }} }} }}] }}"#,
        ortho(16, 2, ""),
        slab(-50.0, 50.0, 1.0),
        slab(-50.0, 0.0, 2.0)
    ));
    let img = accum(&s, 16);
    for j in 0..2 {
        for i in 0..16 {
            let c = f64::from(i) + 0.5;
            let f = (1.0 - (c - 2.0) / 8.0).clamp(0.0, 1.0);
            let expect = [0.5 - 0.25 * f, 0.5 * f, 0.5 - 0.25 * f];
            let got = img.get(i, j).unwrap();
            for k in 0..3 {
                assert!(
                    (f64::from(got[k]) - expect[k]).abs() < 1e-6,
                    "pixel ({i}, {j}): {got:?} vs {expect:?}"
                );
            }
        }
    }
}

#[test]
fn transparent_layers_blend_front_to_back_in_any_scene_order() {
    // Red (alpha 0.5) at z = 1 in front of green (alpha 0.5) at z = 0, blue background:
    // 0.5 red + 0.25 green + 0.25 blue, whichever object is listed first.
    let red = format!(
        r#"{{ "name": "red", "mesh": {{ "triangles": {} }}, "material": {{ "color": [1, 0, 0, 0.5] }} }}"#,
        slab(-50.0, 50.0, 1.0)
    );
    let green = format!(
        r#"{{ "name": "green", "mesh": {{ "triangles": {} }}, "material": {{ "color": [0, 1, 0, 0.5] }} }}"#,
        slab(-50.0, 50.0, 0.0)
    );
    for objs in [format!("{red}, {green}"), format!("{green}, {red}")] {
        let s = scene(&format!(
            r#"{{ {}, "background": [0, 0, 1], "objects": [{objs}] }}"#,
            ortho(4, 2, "")
        ));
        let img = accum(&s, 1);
        for p in &img.pixels {
            assert!(
                (p[0] - 0.5).abs() < 1e-7
                    && (p[1] - 0.25).abs() < 1e-7
                    && (p[2] - 0.25).abs() < 1e-7,
                "{p:?}"
            );
        }
    }
}

#[test]
fn opaque_in_front_hides_transparent_behind() {
    let s = scene(&format!(
        r#"{{ {}, "objects": [
            {{ "name": "glass", "mesh": {{ "triangles": {} }}, "material": {{ "color": [1, 0, 0, 0.5] }} }},
            {{ "name": "wall", "mesh": {{ "triangles": {} }}, "material": {{ "color": [0, 1, 0, 1] }} }}] }}"#,
        ortho(4, 2, ""),
        slab(-50.0, 50.0, -1.0),
        slab(-50.0, 50.0, 0.0)
    ));
    for p in &accum(&s, 1).pixels {
        assert_eq!(*p, [0.0, 1.0, 0.0]);
    }
}

#[test]
fn exact_depth_tie_goes_to_the_later_object() {
    let s = scene(&format!(
        r#"{{ {}, "objects": [
            {{ "name": "first", "mesh": {{ "triangles": {} }}, "material": {{ "color": [1, 0, 0, 1] }} }},
            {{ "name": "second", "mesh": {{ "triangles": {} }}, "material": {{ "color": [0, 1, 0, 1] }} }}] }}"#,
        ortho(4, 2, ""),
        slab(-50.0, 50.0, 0.0),
        slab(-50.0, 50.0, 0.0)
    ));
    for p in &accum(&s, 1).pixels {
        assert_eq!(*p, [0.0, 1.0, 0.0]);
    }
}

#[test]
fn shared_diagonal_through_pixel_centres_is_watertight() {
    // A quad split along a diagonal through every pixel centre of an 8 x 8 image; additive
    // check through transparency: each half has alpha 0.5 over black, so a centre covered
    // twice would read 0.75 and a centre missed 0.
    let s = scene(&format!(
        r#"{{ {}, "objects": [
            {{ "name": "lower", "mesh": {{ "triangles": [[[-4, -4, 0], [4, -4, 0], [4, 4, 0]]] }}, "material": {{ "color": [1, 1, 1, 0.5] }} }},
            {{ "name": "upper", "mesh": {{ "triangles": [[[-4, -4, 0], [4, 4, 0], [-4, 4, 0]]] }}, "material": {{ "color": [1, 1, 1, 0.5] }} }}] }}"#,
        ortho(8, 8, "")
    ));
    for p in &accum(&s, 1).pixels {
        assert!((p[0] - 0.5).abs() < 1e-7, "{p:?}");
    }
}

#[test]
fn camera_motion_equals_opposite_object_motion() {
    let obj = |motion: &str| {
        format!(
            r#"[{{ "name": "box", "mesh": {{ "box": {{ "size": [3, 2, 1] }} }}, "material": {{ "color": [1, 0.5, 0.2, 1] }} {motion} }}]"#
        )
    };
    let cam_moving = scene(&format!(
        r#"{{ {}, "objects": {} }}"#,
        ortho(
            24,
            12,
            r#", "motion": { "eye": [5, 0, 10], "target": [5, 0, 0] }"#
        ),
        obj("")
    ));
    let obj_moving = scene(&format!(
        r#"{{ {}, "objects": {} }}"#,
        ortho(24, 12, ""),
        obj(r#", "motion": { "close": { "translate": [-5, 0, 0] } }"#)
    ));
    let (a, b) = (accum(&cam_moving, 32), accum(&obj_moving, 32));
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        for k in 0..3 {
            assert!((p[k] - q[k]).abs() < 1e-5, "{p:?} vs {q:?}");
        }
    }
    assert!(
        a.pixels.iter().any(|p| p[0] > 0.2 && p[0] < 0.8),
        "motion blur expected"
    );
}

#[test]
fn texel_centres_on_pixel_centres_reproduce_the_texture_exactly() {
    // A 4 x 4 checker (1 texel per square) on a 4 x 4 quad filling a 4 x 4 image.
    let s = scene(&format!(
        r#"{{ {}, "objects": [{{ "name": "tex", "mesh": {{ "quad": {{ "size": [4, 4] }} }},
            "material": {{ "texture": {{ "checker": {{ "squares": 4, "texels_per_square": 1, "a": [1, 1, 1, 1], "b": [0, 0, 0, 1] }} }} }} }}] }}"#,
        ortho(4, 4, "")
    ));
    let img = accum(&s, 1);
    for j in 0..4 {
        for i in 0..4 {
            let expect = if (i + j) % 2 == 0 { 1.0 } else { 0.0 };
            let got = img.get(i, j).unwrap()[0];
            assert!((got - expect).abs() < 1e-6, "({i}, {j}): {got}");
        }
    }
}

#[test]
fn near_plane_crossing_floor_renders_finite_and_clipped() {
    // A floor extending behind the eye: must be clipped, not wrap around.
    let s = scene(
        r#"{ "camera": { "width": 32, "height": 16, "projection": { "perspective": { "fov_y_deg": 60 } },
              "eye": [0, 1, 0], "target": [0, 1, -1], "near": 0.1, "far": 100 },
            "background": [0, 0, 1],
            "objects": [{ "name": "floor", "mesh": { "quad": { "size": [200, 200] } },
              "material": { "color": [1, 0, 0, 1] },
              "transform": { "rotate": { "axis": [1, 0, 0], "degrees": -90 } } }] }"#,
    );
    let img = accum(&s, 1);
    assert!(img.pixels.iter().all(|p| p.iter().all(|c| c.is_finite())));
    for i in 0..32 {
        assert_eq!(img.get(i, 0).unwrap(), [0.0, 0.0, 1.0], "sky at top");
        assert_eq!(img.get(i, 15).unwrap(), [1.0, 0.0, 0.0], "floor at bottom");
    }
}

#[test]
fn degenerate_zero_area_triangles_render_without_nan() {
    let s = scene(&format!(
        r#"{{ {}, "background": [0.25, 0.5, 0.75], "objects": [{{ "name": "flat",
            "mesh": {{ "triangles": [[[0, 0, 0], [1, 1, 0], [2, 2, 0]], [[1, 1, 0], [1, 1, 0], [1, 1, 0]]] }},
            "motion": {{ "close": {{ "translate": [3, 0, 0] }} }} }}] }}"#,
        ortho(8, 8, "")
    ));
    for p in &accum(&s, 8).pixels {
        assert_eq!(*p, [0.25, 0.5, 0.75]);
    }
}

#[test]
fn static_scene_renders_one_subframe_and_needs_no_intervals() {
    let s = Scene::builtin("static").unwrap();
    let p = s.prepare().unwrap();
    assert_eq!(accum::auto_times(&p), 1);
    let e = mblur::Effects::analyse(&p);
    assert!(!e.pipeline().interval_storage && !e.pipeline().motion);
    assert!(e.to_string().contains("interval storage: none"));
}

#[test]
fn effects_report_counts_motion_transparency_and_crossings() {
    let e = mblur::Effects::analyse(
        &Scene::builtin("transparent-cubes")
            .unwrap()
            .prepare()
            .unwrap(),
    );
    assert_eq!(e.moving(), 3);
    assert_eq!(e.transparent(), 3);
    assert_eq!(e.textured(), 1);
    assert!(e.pipeline().intersection);
    let e = mblur::Effects::analyse(&Scene::builtin("fence").unwrap().prepare().unwrap());
    assert_eq!(e.moving(), 1);
    assert!(!e.pipeline().intersection);
    assert!(
        e.to_string()
            .contains("intersection handling: off (no overlapping swept bounds)")
    );
}

#[test]
fn piecewise_linear_response_weights_match_their_integrals() {
    let s = scene(&format!(
        r#"{{ {}, "shutter": {{ "response": {{ "piecewise_linear": [[0, 0], [0.25, 1], [1, 1]] }} }} }}"#,
        ortho(2, 2, "")
    ));
    let p = s.prepare().unwrap();
    let w = accum::sample_times(&p, 4, None);
    // Integrals per quarter: 0.125, 0.25, 0.25, 0.25 of a total 0.875.
    let expect = [0.125, 0.25, 0.25, 0.25].map(|x| x / 0.875);
    for ((t, wt), e) in w.iter().zip(expect) {
        assert!((wt - e).abs() < 1e-15, "t {t}: {wt} vs {e}");
    }
}

// ---- bad input through the library ----

/// A camera orbiting a single splat keeps its projected centre in place but turns the disc
/// from face-on to oblique: that is motion. Before, only the splat's own centre, normal and
/// radius counted, so the scene was analysed as static: accum took one sub-frame and the
/// static path drew one instant. Now the effects analysis, accum's automatic sub-frame
/// count and ewa's keys all count camera motion, and a pixel-centre stochastic render
/// converges to the many-sub-frame reference instead of the single frame.
#[test]
fn camera_orbiting_a_still_splat_is_motion() {
    // One splat exactly at the orbit's centre, facing +z.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("one.ply"),
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n\
         property float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
         end_header\n0 0 0 0 0 1\n",
    )
    .unwrap();
    let s = Scene::from_json(
        r#"{
  "camera": { "width": 64, "height": 64, "projection": { "perspective": { "fov_y_deg": 40 } },
    "eye": [0, 0, 5], "target": [0, 0, 0], "near": 0.5, "far": 50,
    "motion": { "eye": [4, 0, 3] } },
  "background": [0, 0, 0],
  "splats": [ { "name": "disc", "source": { "ply": "one.ply" }, "radius": 1.5, "color": [1, 1, 1, 1] } ]
}"#,
        "orbit.json",
        dir.path(),
    )
    .unwrap();
    let p = s.prepare().unwrap();
    // The projected centre does not move at all.
    assert_eq!(p.splats[0].open, p.splats[0].close);
    let pipeline = mblur::Effects::analyse(&p).pipeline();
    assert!(pipeline.motion && pipeline.interval_storage);
    assert!(accum::auto_times(&p) > 1);
    let reference = accum(&s, 256);
    let still = accum::render_static(&p, 0.5);
    let stochastic = mblur::StochasticOptions {
        spp: Some(64),
        footprint: mblur::Footprint::Centre,
        ..Default::default()
    };
    let (img, _) = stochastic.run(&p, &pipeline, &NoProgress).unwrap();
    let (e_still, e_stoch) = (
        still.rmse(&reference).unwrap(),
        img.rmse(&reference).unwrap(),
    );
    assert!(e_still > 0.05, "the orbit changes the image: {e_still}");
    assert!(
        e_stoch < 0.3 * e_still,
        "stochastic {e_stoch} vs one frame {e_still}"
    );
}

/// Time covered by the union of `spans` (each `[t0, t1]`), by sorting and merging.
fn union_length(mut spans: Vec<(f64, f64)>) -> f64 {
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut total, mut end) = (0.0, f64::NEG_INFINITY);
    for (a, b) in spans {
        if b > end {
            total += b - a.max(end);
            end = b;
        }
    }
    total
}

/// A silhouette edge of the rotating tessellated ball of `clothball-ronnow` grazes the
/// centre of pixel (232, 404), far from the image origin: the edge passes the centre and
/// comes back, two close roots of Gribel 2010, Eq. 7, whose times are ill-conditioned. The
/// analytic method's f32 chain (what `inspect` and the default render use) must cover the
/// same time as a dense f64 reference built from the 2DH corners directly. With edge
/// coefficients in absolute pixel coordinates it covered 0.585 of the shutter against 0.550
/// (0.02 of error in the pixel); in local coordinates (origin at the corner of the
/// primitive's 16-pixel block) it matches.
#[test]
fn grazing_silhouette_far_from_the_image_origin_in_f32() {
    let p = Scene::builtin("clothball-ronnow")
        .unwrap()
        .prepare()
        .unwrap();
    let (x, y) = (232u32, 404u32);
    let (sx, sy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
    let ball = p.objects.iter().position(|o| o.name == "ball").unwrap() as u32;
    // Reference: the centre is inside some ball triangle at time t (f64, both windings; for
    // a closed mesh the union over all faces is the union over the front faces).
    let near: Vec<_> = p
        .triangles
        .iter()
        .filter(|t| t.object == ball)
        .filter(|t| {
            (0..=16).any(|k| {
                t.at(f64::from(k) / 16.0).iter().any(|v| {
                    let (vx, vy) = (v.x / v.w, v.y / v.w);
                    (vx - sx).abs() < 8.0 && (vy - sy).abs() < 8.0
                })
            })
        })
        .collect();
    assert!(!near.is_empty());
    let n = 20_000;
    let mut covered = 0;
    let mut changes = 0;
    let mut prev = None;
    for k in 0..n {
        let t = (f64::from(k) + 0.5) / f64::from(n);
        let inside = near.iter().any(|tri| {
            let q = tri.at(t).map(|v| (v.x / v.w, v.y / v.w));
            let e =
                |a: (f64, f64), b: (f64, f64)| (b.0 - a.0) * (sy - a.1) - (b.1 - a.1) * (sx - a.0);
            let es = [e(q[0], q[1]), e(q[1], q[2]), e(q[2], q[0])];
            es.iter().all(|&v| v >= 0.0) || es.iter().all(|&v| v <= 0.0)
        });
        covered += usize::from(inside);
        if prev.is_some_and(|p| p != inside) {
            changes += 1;
        }
        prev = Some(inside);
    }
    let reference = covered as f64 / f64::from(n);
    // The case is what its name says: the ball leaves the centre and comes back.
    assert!(
        changes == 2 && (0.3..0.8).contains(&reference),
        "{changes} {reference}"
    );
    let got = mblur::inspect::pixel_intervals(&p, x, y, 4).unwrap();
    let spans: Vec<(f64, f64)> = got
        .exact
        .intervals
        .iter()
        .filter(|iv| iv.object == "ball")
        .map(|iv| (f64::from(iv.t0), f64::from(iv.t1)))
        .collect();
    let analytic = union_length(spans);
    assert!(
        (analytic - reference).abs() < 2e-3,
        "analytic (f32) covers {analytic}, the f64 reference {reference}"
    );
}

/// The image of `s` by analytic and by accum at `times` instants; every pixel finite.
fn lit_pair(s: &Scene, times: u32) -> (mblur::Image, mblur::Image) {
    let p = s.prepare().unwrap();
    let options = mblur::MethodOptions::defaults(mblur::Method::Analytic);
    let a = mblur::render(&p, &options, &NoProgress).unwrap().image;
    let b = accum(s, times);
    for (what, im) in [("analytic", &a), ("accum", &b)] {
        assert!(
            im.pixels.iter().flatten().all(|c| c.is_finite()),
            "{what}: non-finite pixel"
        );
    }
    (a, b)
}

/// A white Lambert quad in the XY plane (facing the orthographic camera) with `lights`
/// and `motion`, on a black background, 16 x 8.
fn lit_quad(lights: &str, motion: &str) -> Scene {
    scene(&format!(
        r#"{{ {}, "background": [0, 0, 0], "lights": [{lights}],
            "objects": [{{ "name": "q", "mesh": {{ "quad": {{ "size": [40, 40] }} }},
              "material": {{ "color": [1, 1, 1, 1], "shading": "lambert" }} {motion} }}] }}"#,
        ortho(16, 8, "")
    ))
}

#[test]
fn light_exactly_in_the_plane_of_a_triangle_adds_nothing() {
    // n.l = 0: the directional light grazes the quad; only the ambient 0.25 is left.
    let s = lit_quad(
        r#"{ "type": "ambient", "color": [0.25, 0.25, 0.25] },
           { "type": "directional", "direction": [1, 0, 0], "intensity": 5 }"#,
        r#", "motion": { "close": { "translate": [3, 0, 0] } }"#,
    );
    let (a, b) = lit_pair(&s, 16);
    for im in [a, b] {
        for p in im.pixels.iter().flatten() {
            assert!((p - 0.25).abs() < 1e-6, "{p}");
        }
    }
}

#[test]
fn a_normal_flipping_sign_during_the_shutter_stays_finite_and_matches_accum() {
    // The quad turns 180 degrees about Y: its normal passes edge-on at mid-shutter, and
    // the interpolated normals of a segment may pass through zero.
    let s = lit_quad(
        r#"{ "type": "ambient", "color": [0.1, 0.1, 0.1] },
           { "type": "directional", "direction": [0, 0, -1], "intensity": 1 }"#,
        r#", "motion": { "close": { "rotate": { "axis": [0, 1, 0], "degrees": 180 } } }"#,
    );
    let (a, b) = lit_pair(&s, 1024);
    let rmse = integration_tests::rmse(&a, &b);
    assert!(rmse < 5e-3, "analytic vs accum rmse {rmse}");
}

#[test]
fn a_point_light_inside_the_object_or_on_a_vertex_stays_finite() {
    // Inside a ball the light reaches only the inner sides: where the camera sees the
    // outside for the whole shutter, the ball shows the ambient term exactly (at the moving
    // rim the inner side of a back triangle may show for an instant). A light exactly on a quad corner has
    // distance zero there and is skipped at that point.
    let s = scene(&format!(
        r#"{{ {}, "background": [0, 0, 0],
            "lights": [{{ "type": "ambient", "color": [0.2, 0.2, 0.2] }},
                       {{ "type": "point", "position": [0, 0, 0], "intensity": 100 }}],
            "objects": [{{ "name": "ball", "mesh": {{ "sphere": {{ "radius": 3, "subdivisions": 8 }} }},
              "material": {{ "color": [1, 1, 1, 1], "shading": "blinn_phong" }},
              "motion": {{ "close": {{ "translate": [2, 0, 0] }} }} }}] }}"#,
        ortho(16, 8, "")
    ));
    let (a, b) = lit_pair(&s, 64);
    for im in [a, b] {
        // The pixels the ball covers throughout (columns 7 and 8 of the middle rows).
        for y in 2..6 {
            for x in 7..9 {
                let p = im.get(x, y).unwrap();
                assert!(
                    p.iter().all(|c| (*c - 0.2).abs() < 1e-6),
                    "({x}, {y}): {p:?}"
                );
            }
        }
        assert!(im.pixels.iter().flatten().all(|c| *c <= 1.0));
    }
    let corner = lit_quad(
        r#"{ "type": "point", "position": [-20, -20, 0], "intensity": 3 }"#,
        r#", "motion": { "close": { "translate": [1, 0, 0] } }"#,
    );
    lit_pair(&corner, 16);
}

#[test]
fn huge_intensities_saturate_instead_of_overflowing() {
    // 1e12 at 1e-6 from the surface: 1e24 before the clamp to MAX_RADIANCE.
    let s = lit_quad(
        r#"{ "type": "point", "position": [0, 0, 0.000001], "intensity": 1e12 },
           { "type": "directional", "direction": [0, 0, -1], "intensity": 1e12 }"#,
        r#", "motion": { "close": { "translate": [2, 0, 0] } }"#,
    );
    let (a, b) = lit_pair(&s, 16);
    let max = mblur::lighting::MAX_RADIANCE as f32;
    for im in [a, b] {
        assert!(im.pixels.iter().flatten().all(|c| *c <= 2.0 * max));
    }
}

/// A closed box spinning 150° about a tilted axis (a curved path, cut into segments) while
/// the camera stands still: most faces turn towards or away from the eye during the
/// shutter. For every triangle (segment) and both sweeps' motions, the culling windows
/// (`mblur::cull::Culling::windows`, times local to the segment's span) hold every instant
/// at which an independent reference says the triangle faces the eye: the world-space
/// triple product (a − eye) · ((b − a) × (c − a)) of the corners interpolated linearly in
/// the span (edge-eqn's motion with a still camera), and the 2D orientation of the screen
/// positions interpolated linearly (the prism's motion), each with a rounding bound; and
/// they remove most of the time at which it is clearly turned away.
#[test]
fn spinning_box_culling_windows_match_dense_sampling() {
    use glam::{DVec2, DVec3};
    use mblur::cull::{Culling, Motion};
    let s = scene(
        r#"{
      "camera": { "width": 64, "height": 48, "projection": { "perspective": { "fov_y_deg": 40 } },
                  "eye": [0, 0, 6], "target": [0, 0, 0], "near": 0.5, "far": 50 },
      "background": [0, 0, 0],
      "objects": [ { "name": "box", "mesh": { "box": { "size": [1.6, 1.2, 1] } },
        "material": { "color": [1, 0.5, 0.2, 1] },
        "motion": { "open": { "rotate": { "axis": [0.3, 1, 0.2], "degrees": 0 } },
                    "close": { "translate": [0.3, 0, 0], "rotate": { "axis": [0.3, 1, 0.2], "degrees": 150 } } } } ]
    }"#,
    );
    let p = s.prepare().unwrap();
    let eye = DVec3::new(0.0, 0.0, 6.0);
    let culling = Culling::of(&p);
    let n = 2048;
    let (mut clipped, mut removed, mut clearly_away) = (0, 0.0, 0.0);
    for (i, t) in p.triangles.iter().enumerate() {
        let lerp3 = |u: f64| [0, 1, 2].map(|k| t.world_open[k].lerp(t.world_close[k], u));
        let screen = |u: f64| {
            [0, 1, 2].map(|k| {
                let (a, b) = (t.open[k].screen(), t.close[k].screen());
                DVec2::new(a.0, a.1).lerp(DVec2::new(b.0, b.1), u)
            })
        };
        // World: value and the size of its terms (rounding within 1e-12 of it).
        let world = |u: f64| {
            let [a, b, c] = lerp3(u).map(|v| v - eye);
            (a.dot(b.cross(c)), a.length() * b.length() * c.length())
        };
        let flat = |u: f64| {
            let [a, b, c] = screen(u);
            let (e, f) = (b - a, c - a);
            (e.perp_dot(f), e.length() * f.length())
        };
        // The sign relating the screen orientation to the world triple product (the
        // projection's handedness), from the span's start.
        let ((w0, wm), (f0, fm)) = (world(0.0), flat(0.0));
        if w0.abs() < 1e-6 * wm || f0.abs() < 1e-6 * fm {
            continue;
        }
        let rel = (w0 * f0).signum();
        for motion in [Motion::Homogeneous, Motion::Screen] {
            let win = culling.windows(&p, i, motion);
            if !win.is_all() && !win.is_empty() {
                clipped += 1;
            }
            removed += 1.0 - win.len();
            for j in 0..=n {
                let u = f64::from(j) / f64::from(n);
                // Facing the eye: (a − eye) · ((b − a) × (c − a)) < 0.
                let (v, mag) = match motion {
                    Motion::Homogeneous => world(u),
                    Motion::Screen => {
                        let (v, m) = flat(u);
                        (rel * v, m)
                    }
                };
                if v < -1e-12 * mag {
                    assert!(
                        win.contains(u),
                        "triangle {i} {motion:?} at u = {u}: {win:?}"
                    );
                } else if v > 1e-3 * mag {
                    clearly_away += 1.0 / f64::from(n + 1);
                }
            }
        }
    }
    assert!(clipped > 0, "no triangle turns during the shutter");
    // Nearly all clearly turned-away time is removed (the rest lies next to a root).
    assert!(
        removed > 0.9 * clearly_away,
        "removed {removed}, clearly away {clearly_away}"
    );
}
