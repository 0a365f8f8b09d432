//! glTF import against the ground truth: fixtures written by the test (animated cubes with
//! LINEAR, STEP and CUBICSPLINE channels, a morph-target quad, a two-bone skinned strip,
//! an animated camera) are prepared over a 1 s shutter window and rendered by `analytic`
//! against `accum` at [`TIMES`] instants (accum places each instant on the keys' true
//! path, independently of the segment chords analytic renders). A glTF file and the
//! equivalent JSON scene render alike. Hostile files give errors naming the file and the
//! problem.

use integration_tests::gltf_fixtures::{self, Doc, QUAD, cube_triangles};
use integration_tests::{accum, render, rmse};
use mblur::{Method, MethodOptions, PreparedScene};
use mblur_scene::gltf::{GltfOptions, GltfScene};
use mblur_scene::segments::MotionOptions;

/// Sub-frames of the reference.
const TIMES: u32 = 1024;

fn options(window: [f64; 2]) -> GltfOptions {
    GltfOptions {
        width: Some(64),
        height: Some(48),
        window,
        ..GltfOptions::default()
    }
}

fn prepare_file(path: &std::path::Path, window: [f64; 2]) -> PreparedScene {
    let g = GltfScene::load(path).unwrap_or_else(|e| panic!("{e}"));
    g.prepare(&options(window), &MotionOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
}

/// Writes `doc` as .glb (and .gltf when `also_text`), prepares it over [0, 1] s; the two
/// encodings prepare to the same scene.
fn prepare(doc: &Doc, name: &str) -> PreparedScene {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join(format!("{name}.glb"));
    let text = dir.path().join(format!("{name}.gltf"));
    doc.write_glb(&glb);
    doc.write_gltf(&text);
    let a = prepare_file(&glb, [0.0, 1.0]);
    let b = prepare_file(&text, [0.0, 1.0]);
    assert_eq!(a.triangles, b.triangles, "{name}: .glb and .gltf differ");
    a
}

/// analytic's RMSE against accum at TIMES instants; asserts it is below `bound` and that
/// the scene moves (the reference differs from the still frame at shutter open by more
/// than 10 times the bound, so the bound is not met by a still image).
fn check(name: &str, p: &PreparedScene, bound: f64) -> f64 {
    let truth = accum(p, TIMES);
    let analytic = render(p, &MethodOptions::defaults(Method::Analytic)).image;
    let e = rmse(&analytic, &truth);
    let still = accum(p, 1);
    let motion = rmse(&still, &truth);
    eprintln!(
        "{name}: analytic vs accum RMSE {e:.3e}, still vs accum {motion:.3e}, {} triangles",
        p.triangles.len()
    );
    assert!(e < bound, "{name}: RMSE {e} >= {bound}");
    assert!(
        motion > 10.0 * bound,
        "{name}: the fixture barely moves ({motion})"
    );
    e
}

#[test]
fn animated_cubes_linear_step_cubic_match_accum() {
    let p = prepare(&gltf_fixtures::animated_cubes(), "cubes");
    let names: Vec<&str> = p.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["linear", "step", "cubic"]);
    // The LINEAR cube turns on its arc (a path); the STEP cube jumps at 0.5 s: its
    // triangles have no span crossing 0.5.
    assert!(p.objects[0].path.is_some());
    let step = &p.objects[1];
    assert!(
        p.triangles[step.range.clone()]
            .iter()
            .all(|t| !(t.span[0] < 0.5 && t.span[1] > 0.5))
    );
    check("cubes", &p, 4e-3);
}

#[test]
fn morph_target_quad_matches_accum() {
    let p = prepare(&gltf_fixtures::morph_quad(), "morph");
    check("morph", &p, 1e-4);
}

#[test]
fn skinned_strip_matches_accum() {
    let p = prepare(&gltf_fixtures::skinned_strip(), "skin");
    check("skin", &p, 1.5e-4);
}

#[test]
fn animated_camera_matches_accum() {
    let p = prepare(&gltf_fixtures::animated_camera(), "camera");
    assert!(p.camera_keys.len() >= 2);
    check("camera", &p, 1e-4);
}

/// The morph quad as JSON: the same triangles with their positions at the same keys.
fn morph_json() -> String {
    let corner = |k: usize, w: f64| {
        let (x, y) = (f64::from(QUAD[3 * k]), f64::from(QUAD[3 * k + 1]));
        let dx = if [2, 4, 5].contains(&k) { 1.2 * w } else { 0.0 };
        format!("[{}, {y}, 0]", x + dx)
    };
    let key = |t: f64, w: f64| {
        let ps: Vec<String> = (0..6).map(|k| corner(k, w)).collect();
        format!(r#"{{ "t": {t}, "positions": [{}] }}"#, ps.join(", "))
    };
    let tris: Vec<String> = (0..2)
        .map(|t| {
            format!(
                "[{}, {}, {}]",
                corner(3 * t, 0.0),
                corner(3 * t + 1, 0.0),
                corner(3 * t + 2, 0.0)
            )
        })
        .collect();
    let fov = 0.7f32.to_degrees();
    format!(
        r#"{{ "camera": {{ "width": 64, "height": 48, "projection": {{ "perspective": {{ "fov_y_deg": {fov} }} }},
              "eye": [0, 0, 5], "target": [0, 0, 4], "near": 0.5, "far": 50 }},
            "objects": [{{ "name": "quad", "mesh": {{ "triangles": [{}] }},
              "material": {{ "color": [{}, {}, {}, 1] }},
              "motion": {{ "keys": [{}, {}, {}] }} }}] }}"#,
        tris.join(", "),
        f64::from(0.2f32),
        f64::from(0.7f32),
        f64::from(0.9f32),
        key(0.0, 0.0),
        key(0.5, 1.0),
        key(1.0, 0.5)
    )
}

/// The LINEAR cube alone as glTF and as JSON (inline triangles, translate and rotate keys).
fn cube_pair() -> (Doc, String) {
    let mut d = Doc::new();
    d.camera("cam", [0.0, 0.0, 8.0]);
    let tris = cube_triangles(0.6);
    let mesh = d.mesh(&tris, [0.5, 0.5, 0.5, 1.0]);
    let n = d.push("nodes", serde_json::json!({ "name": "cube", "mesh": mesh }));
    d.root(n);
    d.channel(
        n,
        "translation",
        "LINEAR",
        &[0.0, 1.0],
        &[-1.0, 0.0, 0.0, 1.0, 0.5, 0.0],
    );
    let q: Vec<f32> = [0.0, 90.0]
        .iter()
        .flat_map(|&a| gltf_fixtures::quat([0.0, 1.0, 0.0], a))
        .collect();
    d.channel(n, "rotation", "LINEAR", &[0.0, 1.0], &q);
    let corners: Vec<String> = tris
        .chunks(3)
        .map(|c| format!("[{}, {}, {}]", c[0], c[1], c[2]))
        .collect();
    let triangles: Vec<String> = corners
        .chunks(3)
        .map(|t| format!("[{}]", t.join(", ")))
        .collect();
    let fov = 0.7f32.to_degrees();
    let json = format!(
        r#"{{ "camera": {{ "width": 64, "height": 48, "projection": {{ "perspective": {{ "fov_y_deg": {fov} }} }},
              "eye": [0, 0, 8], "target": [0, 0, 7], "near": 0.5, "far": 50 }},
            "objects": [{{ "name": "cube", "mesh": {{ "triangles": [{}] }}, "material": {{ "color": [0.5, 0.5, 0.5, 1] }},
              "motion": {{ "keys": [ {{ "t": 0, "translate": [-1, 0, 0] }},
                                    {{ "t": 1, "translate": [1, 0.5, 0], "rotate": {{ "axis": [0, 1, 0], "degrees": 90 }} }} ] }} }}] }}"#,
        triangles.join(", ")
    );
    (d, json)
}

/// A glTF file and the equivalent JSON scene render alike: the morph quad (vertex keys)
/// bit for bit apart from f32 rounding of the fixture's colour, and the turning cube
/// (transform keys: a quaternion from f32 against an axis and angle) within 1e-5 RMSE.
#[test]
fn gltf_and_equivalent_json_render_alike() {
    let json_scene = |json: &str| {
        mblur_scene::Scene::from_json(json, "<json>", "")
            .and_then(|s| s.prepare())
            .unwrap_or_else(|e| panic!("{e}"))
    };
    for (name, doc, json, bound) in [
        ("morph", gltf_fixtures::morph_quad(), morph_json(), 1e-6),
        ("cube", cube_pair().0, cube_pair().1, 1e-5),
    ] {
        let g = prepare(&doc, name);
        let j = json_scene(&json);
        assert_eq!(g.triangles.len(), j.triangles.len(), "{name}");
        for method in [Method::Analytic, Method::Accum] {
            let a = render(&g, &MethodOptions::defaults(method)).image;
            let b = render(&j, &MethodOptions::defaults(method)).image;
            let e = rmse(&a, &b);
            eprintln!("{name} {method:?}: glTF vs JSON RMSE {e:.3e}");
            assert!(e <= bound, "{name} {method:?}: {e}");
        }
    }
}

/// Loads `bytes` as `name` and returns the error message (it must not load).
fn refused(name: &str, bytes: &[u8]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).unwrap();
    let result = GltfScene::load(&path)
        .and_then(|g| g.prepare(&options([0.0, 1.0]), &MotionOptions::default()));
    let e = result
        .err()
        .unwrap_or_else(|| panic!("{name} loaded"))
        .to_string();
    assert!(
        e.contains(name),
        "{name}: the error does not name the file: {e}"
    );
    e
}

#[test]
fn hostile_files_are_refused_by_name() {
    let good = gltf_fixtures::animated_cubes().glb_bytes();
    // Truncated at every few bytes: an error, never a panic.
    for cut in (0..good.len()).step_by(37) {
        let e = refused("cut.glb", good.get(..cut).unwrap_or_default());
        assert!(!e.is_empty());
    }
    // An accessor reaching past its buffer view, an absurd count, an index out of range,
    // a missing camera, a non-triangle primitive, an unsupported required extension.
    let mut d = gltf_fixtures::morph_quad();
    d.json["accessors"][0]["count"] = serde_json::json!(1_000_000);
    let e = refused("long.glb", &d.glb_bytes());
    assert!(e.contains("run past the end"), "{e}");
    let mut d = gltf_fixtures::morph_quad();
    d.json["accessors"][0]["count"] = serde_json::json!(4_000_000_000u64);
    let e = refused("absurd.glb", &d.glb_bytes());
    assert!(e.contains("exceeds the limit"), "{e}");
    let mut d = gltf_fixtures::skinned_strip();
    let idx = d.json["meshes"][0]["primitives"][0]["indices"]
        .as_u64()
        .unwrap() as usize;
    let view = d.json["accessors"][idx]["bufferView"].as_u64().unwrap() as usize;
    let at = d.json["bufferViews"][view]["byteOffset"].as_u64().unwrap() as usize;
    d.bin[at] = 200;
    let e = refused("index.glb", &d.glb_bytes());
    assert!(e.contains("out of range"), "{e}");
    let mut d = gltf_fixtures::morph_quad();
    d.json["nodes"][0]["camera"] = serde_json::Value::Null;
    let e = refused("nocam.glb", &d.glb_bytes());
    assert!(e.contains("has no camera"), "{e}");
    let mut d = gltf_fixtures::morph_quad();
    d.json["meshes"][0]["primitives"][0]["mode"] = serde_json::json!(1);
    let e = refused("lines.glb", &d.glb_bytes());
    assert!(e.contains("not supported"), "{e}");
    let mut d = gltf_fixtures::morph_quad();
    d.json["extensionsUsed"] = serde_json::json!(["KHR_draco_mesh_compression"]);
    d.json["extensionsRequired"] = serde_json::json!(["KHR_draco_mesh_compression"]);
    let e = refused("draco.glb", &d.glb_bytes());
    assert!(e.contains("KHR_draco_mesh_compression"), "{e}");
}

/// A still cube facing the camera under a `KHR_lights_punctual` directional light shining
/// along its node's -Z (intensity 0.5) and a point light behind the camera: the front face
/// shows its base colour 0.5 times 0.5 + 0.5 times the point light's irradiance at the face
/// (hand-computed); a material with `KHR_materials_unlit` keeps its base colour.
#[test]
fn punctual_lights_light_every_material_but_unlit_ones() {
    let render_centre = |unlit: bool| {
        let mut d = Doc::new();
        d.camera("cam", [0.0, 0.0, 8.0]);
        let mesh = d.mesh(&cube_triangles(1.0), [0.5, 0.5, 0.5, 1.0]);
        if unlit {
            d.json["materials"][0]["extensions"] = serde_json::json!({ "KHR_materials_unlit": {} });
            d.json["extensionsUsed"] =
                serde_json::json!(["KHR_lights_punctual", "KHR_materials_unlit"]);
        } else {
            d.json["extensionsUsed"] = serde_json::json!(["KHR_lights_punctual"]);
        }
        d.json["extensions"] = serde_json::json!({ "KHR_lights_punctual": { "lights": [
            { "type": "directional", "intensity": 0.5 },
            { "type": "point", "intensity": 900.0 } ] } });
        let cube = d.push("nodes", serde_json::json!({ "name": "cube", "mesh": mesh }));
        d.root(cube);
        for (light, at) in [(0, [0.0, 0.0, 0.0]), (1, [0.0, 0.0, 31.0])] {
            let n = d.push(
                "nodes",
                serde_json::json!({ "translation": at,
                    "extensions": { "KHR_lights_punctual": { "light": light } } }),
            );
            d.root(n);
        }
        let p = prepare(&d, if unlit { "unlit" } else { "lit" });
        assert_eq!(p.lights.len(), 2);
        let image = render(&p, &MethodOptions::defaults(Method::Accum)).image;
        image.get(32, 24).unwrap()
    };
    // Front face at z = 1: the point light 30 away straight in front, 900 / 30^2 = 1 (the
    // pixel centre is 0.05 off the axis: 3e-6 relative).
    let lit = render_centre(false);
    let want = 0.5 * (0.5 + 1.0);
    assert!(
        lit.iter().all(|c| (f64::from(*c) - want).abs() < 1e-5),
        "{lit:?}"
    );
    let unlit = render_centre(true);
    assert!(
        unlit.iter().all(|c| (f64::from(*c) - 0.5).abs() < 1e-5),
        "{unlit:?}"
    );
}

/// A JSON object may take a glTF file as its mesh (`"mesh": {"file": "cube.glb"}`: the
/// file's geometry at rest, the object's own material and motion): the turning cube of
/// [`cube_pair`] renders as with the same triangles inline, up to the f32 rounding of the
/// file's positions.
#[test]
fn a_json_object_takes_a_gltf_file_as_its_mesh() {
    let (doc, json) = cube_pair();
    let dir = tempfile::tempdir().unwrap();
    doc.write_glb(&dir.path().join("cube.glb"));
    let start = json.find(r#"{ "triangles""#).unwrap();
    let end = json.find(r#", "material""#).unwrap();
    let by_file = format!(
        "{}{{ \"file\": \"cube.glb\" }}{}",
        &json[..start],
        &json[end..]
    );
    let prepare = |text: &str| {
        mblur_scene::Scene::from_json(text, "cube.json", dir.path())
            .and_then(|s| s.prepare())
            .unwrap_or_else(|e| panic!("{e}"))
    };
    let (a, b) = (prepare(&by_file), prepare(&json));
    assert_eq!(a.triangles.len(), b.triangles.len());
    let options = MethodOptions::defaults(Method::Accum);
    let e = rmse(&render(&a, &options).image, &render(&b, &options).image);
    eprintln!("cube from a .glb mesh file vs inline triangles: RMSE {e:.2e}");
    assert!(e < 1e-5, "RMSE {e}");
}
