//! `--method auto` (the default): which method it picks for each built-in scene (read back
//! from `Rendered::method`), the static path for a fully static scene, `ewa` with a stated
//! reason for a scene mixing splats and triangles (`accum` when ewa refuses it), and
//! through the CLI.

use mblur::{Effects, Method, NoProgress, RenderOptions, accum};
use mblur_scene::{Scene, builtin};

fn auto(p: &mblur::PreparedScene) -> mblur::Rendered {
    mblur::render(p, &RenderOptions::default(), &NoProgress).unwrap()
}

#[test]
fn auto_is_the_default_method() {
    assert_eq!(RenderOptions::default().method, Method::Auto);
}

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
        assert_eq!(r.method, method, "{name}");
        let note = r.note.unwrap_or_default();
        assert!(
            note.starts_with(&format!("method auto: using {method} (")),
            "{name}: {note}"
        );
        if name.starts_with("clothball") {
            continue; // 64k triangles: one render is enough in a debug build
        }
        // The same image as asking for that method.
        let m: Method = method.parse().unwrap();
        let direct = mblur::render(
            &p,
            &RenderOptions {
                method: m,
                ..Default::default()
            },
            &NoProgress,
        )
        .unwrap();
        assert_eq!(r.image.pixels, direct.image.pixels, "{name}");
    }
}

#[test]
fn auto_takes_the_static_path_for_a_static_scene() {
    let p = integration_tests::builtin("static", 48, 27);
    let pipeline = Effects::analyse(&p).pipeline();
    assert!(!pipeline.interval_storage && !pipeline.motion);
    let r = auto(&p);
    assert!(
        r.description.contains("no interval storage"),
        "{}",
        r.description
    );
    assert!(r.note.as_deref().unwrap_or("").contains("static path"));
    // Exactly the static rasteriser at one instant.
    assert_eq!(r.image.pixels, accum::render_static(&p, 0.5).pixels);
}

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
    let p = Scene::from_json(json, "mixed", ".")
        .unwrap()
        .prepare()
        .unwrap();
    let r = auto(&p);
    assert_eq!(r.method, "ewa");
    let note = r.note.unwrap_or_default();
    assert!(
        note.contains("mixes") && note.contains("triangles") && note.contains("splats"),
        "{note}"
    );
    let choice = mblur::auto::choose(&p, &Effects::analyse(&p).pipeline());
    assert_eq!(choice.method, Method::Ewa);
    // Transparent splats: ewa refuses, so accum, with ewa's reason.
    let p = Scene::from_json(
        &json.replace("[1, 0.5, 0.1, 1]", "[1, 0.5, 0.1, 0.5]"),
        "mixed",
        ".",
    )
    .unwrap()
    .prepare()
    .unwrap();
    let choice = mblur::auto::choose(&p, &Effects::analyse(&p).pipeline());
    assert_eq!(choice.method, Method::Accum);
    assert!(
        choice.note.contains("transparent splats"),
        "{}",
        choice.note
    );
}
