//! The time-dependent back-face culling of opaque closed meshes (`mblur::cull`) never
//! changes the image beyond rounding: a textured closed sphere (front and back faces show
//! different texels, so culling the wrong half would show) moving and spinning, rendered by
//! the analytic method with and without culling, both against accum at a high time count;
//! and every built-in scene with a closed mesh, with and without culling.

use integration_tests::{accum, from_json, max_abs, rmse};
use mblur::{AnalyticOptions, Effects, NoProgress};

const SPHERE: &str = r#"{
  "camera": { "width": 48, "height": 36,
    "projection": { "perspective": { "fov_y_deg": 35 } },
    "eye": [0, 0.5, 6], "target": [0, 0, 0], "near": 0.5, "far": 50 },
  "background": [0.05, 0.05, 0.08],
  "objects": [
    { "name": "ball",
      "mesh": { "sphere": { "radius": 1.5, "subdivisions": 24, "wrinkle": 0.08, "wrinkle_frequency": 5 } },
      "material": { "color": [1, 1, 1, 1],
                    "texture": { "checker": { "squares": 6, "texels_per_square": 1, "a": [1, 1, 1, 1], "b": [0.6, 0.15, 0.2, 1] } } },
      "motion": { "open": { "translate": [-0.4, 0, 0], "rotate": { "axis": [0.2, 1, 0], "degrees": 0 } },
                  "close": { "translate": [0.4, 0, 0], "rotate": { "axis": [0.2, 1, 0], "degrees": 35 } } } }
  ]
}"#;

#[test]
fn culling_a_closed_opaque_sphere_keeps_the_image() {
    let p = from_json(SPHERE);
    let pipeline = Effects::analyse(&p).pipeline();
    let render = |keep_backfaces| {
        let o = AnalyticOptions {
            keep_backfaces,
            ..Default::default()
        };
        mblur::analytic::render_stats(&p, &pipeline, &o, &NoProgress).unwrap()
    };
    let (culled, s_culled) = render(false);
    let (kept, s_kept) = render(true);
    let (s_culled, s_kept) = (s_culled.unwrap(), s_kept.unwrap());
    let n = p.triangles.len() as u64;
    assert!(
        s_culled.culled > n * 2 / 5 && s_culled.culled < n * 3 / 5,
        "{} of {n}",
        s_culled.culled
    );
    assert_eq!((s_kept.culled, s_kept.clipped), (0, 0));
    // The spin turns triangles near the silhouette during the shutter: they are clipped.
    assert!(s_culled.clipped > 0);
    assert!(s_culled.total < s_kept.total);
    let reference = accum(&p, 512);
    let (e_c, e_k, d) = (
        rmse(&culled, &reference),
        rmse(&kept, &reference),
        rmse(&culled, &kept),
    );
    let max = max_abs(&culled, &kept);
    eprintln!(
        "sphere: culled {} and clipped {} of {n} triangles, intervals {} -> {}; rmse vs accum culled {e_c:.5}, kept {e_k:.5}; culled vs kept rmse {d:.2e}, max {max:.2e}",
        s_culled.culled, s_culled.clipped, s_kept.total, s_culled.total
    );
    assert!(e_c < 1.5e-2 && e_k < 1.5e-2, "{e_c} {e_k}");
    assert!(d < 1e-3 && max < 2e-2, "{d} {max}");
}

const CAM: &str = r#""camera": {"width": 64, "height": 48, "projection": {"perspective": {"fov_y_deg": 40}}, "eye": [0, 0, 6], "target": [0, 0, 0], "near": 0.5, "far": 50}, "background": [0, 0, 0]"#;

#[test]
fn closed_opaque_sphere_loses_about_half() {
    let s = from_json(&format!(
        r#"{{ {CAM}, "objects": [{{"name": "s", "mesh": {{"sphere": {{"radius": 1, "subdivisions": 16}}}}, "material": {{"color": [1, 0, 0, 1]}}, "motion": {{"open": {{"translate": [-0.5, 0, 0]}}, "close": {{"translate": [0.5, 0, 0]}}}}}}] }}"#
    ));
    let n = s.triangles.len();
    let c = mblur::cull::backface_count(&s);
    assert!(c > n / 3 && c < n * 2 / 3, "{c} of {n}");
    // Every culled triangle faces away at open: its normal points away from the eye.
    let eye = glam::DVec3::new(0.0, 0.0, 6.0);
    for (t, &m) in s.triangles.iter().zip(&mblur::cull::backface_mask(&s)) {
        if m {
            let [a, b, c] = t.world_open;
            let nrm = (b - a).cross(c - a);
            assert!(nrm.dot(a - eye) > 0.0);
        }
    }
}

#[test]
fn transparent_or_open_meshes_are_not_culled() {
    let transparent = from_json(&format!(
        r#"{{ {CAM}, "objects": [{{"name": "s", "mesh": {{"sphere": {{"radius": 1, "subdivisions": 8}}}}, "material": {{"color": [1, 0, 0, 0.5]}}}}] }}"#
    ));
    assert_eq!(mblur::cull::backface_count(&transparent), 0);
    let quad = from_json(&format!(
        r#"{{ {CAM}, "objects": [{{"name": "q", "mesh": {{"quad": {{"size": [1, 1]}}}}, "material": {{"color": [1, 0, 0, 1]}}}}] }}"#
    ));
    assert_eq!(mblur::cull::backface_count(&quad), 0);
}

/// Every built-in triangle scene with an opaque closed mesh (billiards, clothball-ronnow,
/// pills, ...), small, in f32 and f64: the analytic method with the time-dependent culling
/// removes intervals and renders the image it renders with every back face kept — up to
/// rounding for flat unlit surfaces, up to the per-partition shading and texture filtering
/// otherwise — and is as close to accum.
#[test]
fn time_dependent_culling_keeps_every_builtin_closed_mesh_scene() {
    use mblur::cull::{Culling, Motion};
    let mut checked = 0;
    for name in integration_tests::triangle_scenes() {
        let p = integration_tests::builtin(name, 80, 45);
        let counts = Culling::of(&p).counts(&p, Motion::Homogeneous);
        if counts.culled + counts.clipped == 0 {
            continue;
        }
        checked += 1;
        let pipeline = Effects::analyse(&p).pipeline();
        let reference = accum(&p, 256);
        for precision in mblur::Precision::ALL {
            let render = |keep_backfaces| {
                let o = AnalyticOptions {
                    keep_backfaces,
                    precision,
                    ..Default::default()
                };
                mblur::analytic::render_stats(&p, &pipeline, &o, &NoProgress).unwrap()
            };
            let ((culled, s_culled), (kept, s_kept)) = (render(false), render(true));
            let (Some(s_culled), Some(s_kept)) = (s_culled, s_kept) else {
                continue; // a static scene: the static path, no intervals
            };
            let (d, max) = (rmse(&culled, &kept), max_abs(&culled, &kept));
            let (e_culled, e_kept) = (rmse(&culled, &reference), rmse(&kept, &reference));
            eprintln!(
                "{name} {precision}: {} culled, {} clipped; intervals {} -> {}; culled vs kept rmse {d:.2e}, max {max:.2e}; vs accum culled {e_culled:.4e}, kept {e_kept:.4e}",
                s_culled.culled, s_culled.clipped, s_kept.total, s_culled.total
            );
            assert_eq!(
                (s_culled.culled, s_culled.clipped),
                (counts.culled, counts.clipped)
            );
            assert!(s_culled.total < s_kept.total, "{name} {precision}");
            // Not bit for bit: without the hidden intervals the resolve has fewer partitions,
            // so a lit or textured surface is shaded and filtered at other instants, and a
            // kept back face's linear depth chord can cross its front face's near a
            // silhouette. Either render is as close to accum.
            assert!(
                d < 3e-4 && max < 1e-2,
                "{name} {precision}: rmse {d}, max {max}"
            );
            if !pipeline.textures && !pipeline.lighting {
                assert!(max < 1e-4, "{name} {precision}: max {max}");
            }
            assert!(
                e_culled <= 1.01 * e_kept,
                "{name} {precision}: {e_culled} vs {e_kept}"
            );
        }
    }
    assert!(checked >= 3, "{checked} scenes with closed meshes");
}
