//! `--method auto` (the default): which method it picks for each built-in scene (read back
//! from `Rendered::method` and the note), and the same image as asking for that method;
//! `ewa` with a stated reason for a scene mixing splats and triangles, `accum` with ewa's
//! reason when ewa refuses it. The static scene's static path (auto included) is checked in
//! `integration-tests/tests/effects.rs`; that `mblur render` prints the choice, in
//! `mblur-cli/tests/cli.rs` and `mblur-cli/tests/methods.rs`.

use integration_tests::{from_json, render};
use mblur::{Effects, Method, MethodOptions};
use mblur_scene::builtin;

/// `auto` through the library entry point, every pixel checked finite.
fn auto(p: &mblur::PreparedScene) -> mblur::Rendered {
    render(p, &MethodOptions::default())
}

#[test]
fn auto_is_the_default_method() {
    assert_eq!(MethodOptions::default().method(), Method::Auto);
}

/// Every built-in scene at 24x16: the method auto picks, its note, and (except the 64k
/// triangle clothballs) the same image as asking for that method with auto's
/// [`mblur::aa::AUTO_SAMPLES`] sample positions.
#[test]
fn auto_picks_per_built_in_scene() {
    let expected = [
        ("billiards", "analytic"),
        ("fence", "analytic"),
        ("transparent-cubes", "analytic"),
        ("crossing-quads", "analytic"),
        ("pills", "analytic"),
        ("clothball", "analytic"),
        ("clothball-ronnow", "analytic"),
        ("textured-quad", "analytic"),
        ("spinning-wheel", "analytic"),
        ("spinning-lit-ball", "analytic"),
        ("splat-ball", "ewa"),
        ("splat-mix", "ewa"),
        ("static", "analytic"),
    ];
    // Every built-in scene is listed.
    let mut names: Vec<&str> = builtin::SCENES.iter().map(|s| s.0).collect();
    let mut listed: Vec<&str> = expected.iter().map(|e| e.0).collect();
    names.sort_unstable();
    listed.sort_unstable();
    assert_eq!(names, listed);
    for (name, method) in expected {
        let p = integration_tests::builtin(name, 24, 16);
        let r = auto(&p);
        assert_eq!(r.method.name(), method, "{name}");
        let note = r.note.unwrap_or_default();
        assert!(
            note.starts_with(&format!("method auto: using {method} (")),
            "{name}: {note}"
        );
        if name.starts_with("clothball") {
            continue; // 64k triangles: one render is enough in a debug build
        }
        // The same image as asking for that method with auto's sample positions.
        let asked = MethodOptions::defaults(method.parse().unwrap())
            .with_antialiasing(mblur::aa::Antialiasing::auto());
        let direct = render(&p, &asked);
        assert_eq!(r.image.pixels, direct.image.pixels, "{name}");
    }
}

/// A floor quad under a moving ball of splats, 24x16: `auto` picks ewa, and its note says
/// the scene mixes triangles and splats, drawn as EWA splats with the triangles from the
/// analytic chain; `auto::choose` agrees. With the splats half transparent ewa refuses the
/// scene, so `auto` renders it with accum and its note gives ewa's reason.
#[test]
fn auto_renders_splats_with_triangles_by_ewa_and_says_why() {
    let json = r#"{
      "camera": { "width": 24, "height": 16, "projection": { "perspective": { "fov_y_deg": 40 } },
                  "eye": [0, 0, 6], "target": [0, 0, 0], "near": 0.5, "far": 50 },
      "background": [0.1, 0.1, 0.1],
      "objects": [ { "name": "floor", "mesh": { "quad": { "size": [4, 4] } },
                     "material": { "color": [0.2, 0.6, 0.2, 1] } } ],
      "splats": [ { "name": "ball",
        "source": { "sample": { "mesh": { "sphere": { "radius": 1, "subdivisions": 8 } }, "count": 200, "seed": 1 } },
        "radius": 0.1, "color": [1, 0.5, 0.1, 1],
        "motion": { "open": { "translate": [-1, 0, 1] }, "close": { "translate": [1, 0, 1] } } } ]
    }"#;
    let p = from_json(json);
    let r = auto(&p);
    assert_eq!(r.method, Method::Ewa);
    let note = r.note.unwrap_or_default();
    assert!(
        note.contains("mixes")
            && note.contains("triangles")
            && note.contains("EWA splats")
            && note.contains("analytic"),
        "{note}"
    );
    let choice = mblur::auto::choose(&p, &Effects::analyse(&p).pipeline());
    assert_eq!(choice.method, Method::Ewa);
    // Transparent splats: ewa refuses, so accum, with ewa's reason.
    let p = from_json(&json.replace("[1, 0.5, 0.1, 1]", "[1, 0.5, 0.1, 0.5]"));
    let r = auto(&p);
    assert_eq!(r.method, Method::Accum);
    let note = r.note.unwrap_or_default();
    assert!(note.contains("transparent splats"), "{note}");
    let choice = mblur::auto::choose(&p, &Effects::analyse(&p).pipeline());
    assert_eq!(choice.method, Method::Accum);
    assert_eq!(choice.note, note);
}
