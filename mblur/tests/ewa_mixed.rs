//! The `ewa` method on scenes that mix triangle meshes and splats: the splats are EWA
//! splats (Heinzle 2010), the triangles come from the analytic chain (Gribel 2010) as
//! surface intervals in ewa-splat's A-buffer. References, none of them the mixed path
//! itself:
//!
//! * the same scene split in two: where no splat fragment reaches a pixel the mixed render
//!   equals `analytic` (f64) of the triangles alone; where no triangle ever covers a pixel
//!   it equals `ewa` of the splats alone;
//! * exact compositing identities: a static transparent pane in front of everything gives
//!   `α pane + (1 - α) (render without the pane)` per pixel; an opaque flat backdrop behind
//!   everything is the background of the splat-only render;
//! * `accum` at 256 times, which draws splats as hard-edged discs (nearest wins) instead of
//!   normalised Gaussians: a per-pixel RMSE floor at splat silhouettes, as for splat-ball
//!   in `tests/ewa.rs`; the bound below is measured with headroom; pixels no splat reaches
//!   are held to the accum-vs-analytic tolerance instead.
//!
//! The dense time-sampling reference of the piecewise visibility itself is in ewa-splat's
//! `tests/surfaces.rs` (surface intervals given directly, 4096 times per pixel).

use integration_tests::{accum, from_json_at, max_abs, render, render_with};
use mblur::ewa::{EwaOptions, Visibility};
use mblur::{
    AnalyticOptions, Error, Image, Method, MethodOptions, NoProgress, Precision, PreparedScene,
};
use mblur_scene::builtin;

fn splat_mix_json() -> &'static str {
    builtin::json("splat-mix").unwrap()
}

/// splat-mix without its backdrop quad (so some pixels see only splats).
fn without_backdrop() -> String {
    let j = splat_mix_json();
    let a = j.find(r#"{ "name": "backdrop""#).unwrap();
    let b = j.find(r#"{ "name": "front-post""#).unwrap();
    format!("{}{}", &j[..a], &j[b..])
}

fn ewa(scene: &PreparedScene) -> Image {
    render_with(scene, Method::Ewa)
}

fn analytic_f64(scene: &PreparedScene) -> Image {
    render(
        scene,
        &MethodOptions::Analytic(AnalyticOptions {
            precision: Precision::F64,
            ..Default::default()
        }),
    )
    .image
}

fn triangles_only(scene: &PreparedScene) -> PreparedScene {
    let mut s = scene.clone();
    s.splats.clear();
    s.splat_objects.clear();
    s
}

fn splats_only(scene: &PreparedScene) -> PreparedScene {
    let mut s = scene.clone();
    s.triangles.clear();
    s.objects.clear();
    s
}

/// Pixels an image leaves at exactly `bg` (nothing drawn there) when rendered over a
/// background colour that appears nowhere in the scene.
fn untouched(img: &Image, bg: [f64; 3]) -> Vec<bool> {
    img.pixels
        .iter()
        .map(|p| (0..3).all(|k| p[k] == bg[k] as f32))
        .collect()
}

fn diff(a: &[f32; 3], b: &[f32; 3]) -> f64 {
    (0..3)
        .map(|k| (f64::from(a[k]) - f64::from(b[k])).abs())
        .fold(0.0, f64::max)
}

const MAGENTA: [f64; 3] = [1.0, 0.0, 1.0];

/// Where only triangles or only splats contribute, the mixed render is the render of that
/// half of the scene by its own method.
#[test]
fn triangle_only_and_splat_only_regions_match_the_split_renders() {
    for (name, json) in [
        ("splat-mix", splat_mix_json().to_string()),
        ("splat-mix without backdrop", without_backdrop()),
    ] {
        let scene = from_json_at(&json, 96, 72);
        let mixed = ewa(&scene);
        let tris = triangles_only(&scene);
        let splats = splats_only(&scene);
        let tri_img = analytic_f64(&tris);
        let splat_img = ewa(&splats);
        // Footprints, from renders over a magenta background.
        let mut m = splats.clone();
        m.background = MAGENTA;
        let no_splat = untouched(&ewa(&m), MAGENTA);
        let mut m = tris.clone();
        m.background = MAGENTA;
        let no_tri = untouched(&analytic_f64(&m), MAGENTA);
        let (mut n_tri, mut n_splat, mut worst_tri, mut worst_splat) = (0, 0, 0.0f64, 0.0f64);
        for i in 0..mixed.pixels.len() {
            if no_splat[i] {
                n_tri += 1;
                worst_tri = worst_tri.max(diff(&mixed.pixels[i], &tri_img.pixels[i]));
            }
            if no_tri[i] {
                n_splat += 1;
                worst_splat = worst_splat.max(diff(&mixed.pixels[i], &splat_img.pixels[i]));
            }
        }
        eprintln!(
            "{name}: {n_tri} triangle-only pixels (max diff {worst_tri:.2e}), {n_splat} \
             splat-only pixels (max diff {worst_splat:.2e})"
        );
        assert!(n_tri > 1000, "{name}: {n_tri}");
        // Both are exact given the same intervals; f32 output rounding and the resolve's
        // different summation order.
        assert!(worst_tri < 1e-5, "{name}: triangle-only region {worst_tri}");
        // The same fragments through the same arithmetic.
        assert!(
            worst_splat == 0.0,
            "{name}: splat-only region {worst_splat}"
        );
        if name.contains("without") {
            assert!(n_splat > 1000, "{name}: {n_splat}");
        }
    }
}

/// The scene with an added static half-transparent pane in front of everything: per pixel
/// the pane covers, the render is `α pane + (1 - α) (render without the pane)` exactly.
#[test]
fn transparent_pane_in_front_composites_over_splats_and_triangles() {
    let base = without_backdrop();
    let pane = r#"{ "name": "pane", "mesh": { "quad": { "size": [1.6, 1.2] } },
        "material": { "color": [0.2, 0.3, 0.9, 0.4] },
        "transform": { "translate": [0.2, 0.1, 2.5] } },
      { "name": "front-post""#;
    let with_pane = base.replace(r#"{ "name": "front-post""#, pane);
    let a = from_json_at(&base, 80, 60);
    let b = from_json_at(&with_pane, 80, 60);
    let under = ewa(&a);
    let over = ewa(&b);
    // Which pixels the pane covers (its centre, for the whole shutter: it is static):
    // where the triangles-only analytic renders with and without it differ.
    let (ta, tb) = (
        analytic_f64(&triangles_only(&a)),
        analytic_f64(&triangles_only(&b)),
    );
    let bare: Vec<bool> = ta
        .pixels
        .iter()
        .zip(&tb.pixels)
        .map(|(p, q)| p == q)
        .collect();
    let (c, alpha) = ([0.2f64, 0.3, 0.9], 0.4f64);
    let (mut n, mut worst) = (0, 0.0f64);
    for ((o, u), &bare) in over.pixels.iter().zip(&under.pixels).zip(&bare) {
        if bare {
            worst = worst.max(diff(o, u));
            continue;
        }
        n += 1;
        let want: [f32; 3] =
            std::array::from_fn(|k| (alpha * c[k] + (1.0 - alpha) * f64::from(u[k])) as f32);
        worst = worst.max(diff(o, &want));
    }
    eprintln!("pane over {n} pixels: max diff {worst:.2e}");
    assert!(n > 500, "{n}");
    assert!(worst < 2e-6, "{worst}");
    // The pane is transparent: the describe line says so.
    let r = render(&b, &MethodOptions::defaults(Method::Ewa));
    assert!(
        r.description
            .contains("transparent surfaces composited front to back"),
        "{}",
        r.description
    );
}

/// An opaque flat backdrop behind every splat and post-free: the splat-only render with
/// the backdrop's colour as background.
#[test]
fn opaque_backdrop_behind_the_splats_is_their_background() {
    let json = r#"{
      "camera": { "width": 64, "height": 48, "projection": { "perspective": { "fov_y_deg": 40 } },
                  "eye": [0, 0, 6], "target": [0, 0, 0], "near": 0.5, "far": 50 },
      "background": [0.1, 0.1, 0.1],
      "objects": [ { "name": "wall", "mesh": { "quad": { "size": [20, 20] } },
                     "material": { "color": [0.3, 0.6, 0.2, 1] },
                     "transform": { "translate": [0, 0, -3] } } ],
      "splats": [ { "name": "ball",
        "source": { "sample": { "mesh": { "sphere": { "radius": 0.8, "subdivisions": 12 } }, "count": 600, "seed": 3 } },
        "radius": 0.12, "color": [1, 0.5, 0.1, 1],
        "motion": { "open": { "translate": [-1, 0.2, 0.5] }, "close": { "translate": [1, -0.2, -0.5] } } } ]
    }"#;
    let scene = from_json_at(json, 64, 48);
    let mixed = ewa(&scene);
    let mut s = splats_only(&scene);
    s.background = [0.3, 0.6, 0.2];
    let reference = ewa(&s);
    let worst = max_abs(&mixed, &reference);
    let inked = reference
        .pixels
        .iter()
        .filter(|p| (f64::from(p[0]) - 0.3).abs() > 0.05)
        .count();
    assert!(inked > 200, "{inked}");
    assert!(worst < 2e-6, "{worst}");
}

/// Bound on the RMSE of the mixed `ewa` render of splat-mix against accum at 256 times
/// (measured 0.0002 at 96x72, 0.0003 with camera motion, when written), with headroom:
/// splat silhouettes differ (Gaussian normalisation and the 1-px low-pass against hard
/// 16-gon discs), and accum samples 256 instants where ewa and the triangle intervals
/// integrate exactly.
const RMSE_SPLAT_MIX_ACCUM: f64 = 0.002;
/// Where no splat reaches, the difference is accum's time sampling of moving triangles
/// (at most 1/256 per edge crossing a pixel centre, over colour jumps below 1) against the
/// analytic coverage (measured 0.0011, and 0.0016 with camera motion).
const MAX_NO_SPLAT_ACCUM: f64 = 0.005;
/// Mean colour difference over the splat footprint: no silhouette floor, both integrate the
/// same coverage (measured 0.0001, and 0.0003 with camera motion).
const MEAN_SPLAT_ACCUM: f64 = 0.002;

#[test]
fn splat_mix_agrees_with_accum_with_and_without_camera_motion() {
    let moving_camera = splat_mix_json().replace(
        r#""near": 0.5, "far": 50"#,
        r#""near": 0.5, "far": 50, "motion": { "eye": [0.5, 0.9, 5.8] }"#,
    );
    assert_ne!(moving_camera, splat_mix_json());
    for (name, json) in [
        ("splat-mix", splat_mix_json().to_string()),
        ("splat-mix, camera moving", moving_camera),
    ] {
        let scene = from_json_at(&json, 96, 72);
        let mixed = ewa(&scene);
        let acc = accum(&scene, 256);
        let r = mixed.rmse(&acc).unwrap();
        let mut m = splats_only(&scene);
        m.background = MAGENTA;
        let no_splat = untouched(&ewa(&m), MAGENTA);
        let worst = (0..mixed.pixels.len())
            .filter(|&i| no_splat[i])
            .map(|i| diff(&mixed.pixels[i], &acc.pixels[i]))
            .fold(0.0, f64::max);
        let (mut sa, mut sb, mut n) = ([0.0f64; 3], [0.0f64; 3], 0.0);
        for i in (0..mixed.pixels.len()).filter(|&i| !no_splat[i]) {
            for k in 0..3 {
                sa[k] += f64::from(mixed.pixels[i][k]);
                sb[k] += f64::from(acc.pixels[i][k]);
            }
            n += 1.0;
        }
        let mean = (0..3)
            .map(|k| ((sa[k] - sb[k]) / n).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "{name} 96x72 vs accum 256: rmse {r:.4}, max {worst:.4} where no splat reaches, \
             mean colour difference {mean:.4} over the {n} splat pixels"
        );
        assert!(n > 500.0, "{name}: splat footprint {n}");
        assert!(r < RMSE_SPLAT_MIX_ACCUM, "{name}: rmse {r}");
        assert!(
            worst < MAX_NO_SPLAT_ACCUM,
            "{name}: no-splat pixels {worst}"
        );
        assert!(
            mean < MEAN_SPLAT_ACCUM,
            "{name}: mean over splat pixels {mean}"
        );
    }
}

/// The `ewa` description of splat-mix (32x24) says the triangles are composited in the
/// A-buffer, each splat taking one [0, 1] interval. (That `auto` picks ewa for it, with the
/// same image, is in `tests/auto.rs`.)
#[test]
fn mixed_render_describes_the_triangles_in_the_a_buffer() {
    let scene = from_json_at(splat_mix_json(), 32, 24);
    let r = render(&scene, &MethodOptions::defaults(Method::Ewa));
    assert!(
        r.description
            .contains("triangles composited in the A-buffer")
            && r.description.contains("one [0, 1] interval"),
        "{}",
        r.description
    );
}

fn refusal(scene: &PreparedScene, opts: MethodOptions) -> String {
    match mblur::render(scene, &opts, &NoProgress) {
        Err(e @ Error::MethodNotApplicable { .. }) => e.to_string(),
        Err(e) => panic!("wrong error: {e}"),
        Ok(_) => panic!("rendered an unsupported combination"),
    }
}

/// What ewa refuses in a mixed scene, each a `MethodNotApplicable` error naming it:
/// transparent splats (naming the object), and the approximate visibility, which cannot
/// take triangle intervals. (A triangle-only scene is refused in `tests/ewa.rs`; `auto`'s
/// fall-back to accum for transparent splats is in `tests/auto.rs`.)
#[test]
fn unsupported_combinations_are_clear_errors() {
    let json = splat_mix_json().replace("[1.0, 0.55, 0.15, 1]", "[1.0, 0.55, 0.15, 0.5]");
    let scene = from_json_at(&json, 24, 18);
    let msg = refusal(&scene, MethodOptions::defaults(Method::Ewa));
    assert!(
        msg.contains("transparent splats") && msg.contains("ball"),
        "{msg}"
    );
    let scene = from_json_at(splat_mix_json(), 24, 18);
    let msg = refusal(
        &scene,
        MethodOptions::Ewa(EwaOptions {
            visibility: Visibility::Approximate,
            ..Default::default()
        }),
    );
    assert!(msg.contains("triangle") && msg.contains("abuffer"), "{msg}");
}
