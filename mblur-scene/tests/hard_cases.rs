//! Hard cases by name for scene and image files: malformed JSON, bad values, missing or
//! broken mesh, point-cloud and texture files, and image files that round-trip exactly.
//! Every error names the file and the place; nothing partial is written.

use integration_tests::ortho_camera as ortho;
use mblur_scene::{Error, Scene};

fn accum(s: &Scene, times: u32) -> mblur::Image {
    integration_tests::accum(&s.prepare().unwrap(), times)
}

fn err(json: &str) -> Error {
    Scene::from_json(json, "bad.json", ".").expect_err("must fail")
}

#[test]
fn malformed_json_names_file_line_and_column() {
    let e = err("{\n  \"camera\": {\n    \"width\": 10,,\n  }\n}");
    match &e {
        Error::Json {
            file, line, column, ..
        } => {
            assert_eq!(file, "bad.json");
            assert_eq!(*line, 3);
            assert!(*column > 0);
        }
        other => panic!("{other:?}"),
    }
    assert!(e.to_string().starts_with("bad.json: line 3, column"), "{e}");
}

#[test]
fn unknown_field_is_named() {
    let json = format!(
        r#"{{ {}, "objects": [{{ "name": "a", "mesh": {{ "box": {{}} }}, "material": {{ "colour": [1, 0, 0, 1] }} }}] }}"#,
        ortho(4, 4, "")
    );
    let msg = err(&json).to_string();
    assert!(
        msg.contains("unknown field `colour`") && msg.contains("objects[0].material"),
        "{msg}"
    );
}

#[test]
fn overflowing_number_is_rejected_with_position() {
    let json = format!(r#"{{ {}, "background": [1e999, 0, 0] }}"#, ortho(4, 4, ""));
    let msg = err(&json).to_string();
    assert!(
        msg.starts_with("bad.json: line 2, column")
            && msg.contains("background[0]: number out of range"),
        "{msg}"
    );
}

#[test]
fn negative_size_names_object_and_field() {
    let json = format!(
        r#"{{ {}, "objects": [{{ "name": "crate", "mesh": {{ "box": {{ "size": [1, -2, 1] }} }} }}] }}"#,
        ortho(4, 4, "")
    );
    let msg = err(&json).to_string();
    assert!(
        msg.contains(r#"objects[0] "crate".mesh.box.size[1]"#) && msg.contains("> 0"),
        "{msg}"
    );
}

#[test]
fn near_not_below_far_is_rejected() {
    let json = r#"{ "camera": { "width": 4, "height": 4, "projection": { "perspective": { "fov_y_deg": 40 } },
        "eye": [0, 0, 5], "target": [0, 0, 0], "near": 10, "far": 10 } }"#;
    let msg = err(json).to_string();
    assert!(
        msg.contains("camera.near") && msg.contains("camera.far"),
        "{msg}"
    );
}

#[test]
fn oversized_image_is_rejected() {
    let json = r#"{ "camera": { "width": 30000, "height": 30000, "projection": { "perspective": { "fov_y_deg": 40 } },
        "eye": [0, 0, 5], "target": [0, 0, 0], "near": 0.1, "far": 10 } }"#;
    let msg = err(json).to_string();
    assert!(
        msg.contains("camera.width x camera.height") && msg.contains("exceeds"),
        "{msg}"
    );
}

#[test]
fn non_finite_values_from_code_are_rejected() {
    let mut s = Scene::builtin("static").unwrap().desc;
    s.background[1] = f64::NAN;
    let msg = Scene::from_desc(s).unwrap_err().to_string();
    assert!(
        msg.contains("background[1]") && msg.contains("finite"),
        "{msg}"
    );
}

#[test]
fn missing_mesh_file_gives_path_and_os_reason() {
    let json = format!(
        r#"{{ {}, "objects": [{{ "name": "m", "mesh": {{ "file": "nope/missing.obj" }} }}] }}"#,
        ortho(4, 4, "")
    );
    let e = Scene::from_json(&json, "bad.json", "/tmp")
        .unwrap()
        .prepare()
        .unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("/tmp/nope/missing.obj") && msg.contains("No such file"),
        "{msg}"
    );
}

#[test]
fn missing_texture_gives_path_and_os_reason() {
    let json = format!(
        r#"{{ {}, "objects": [{{ "name": "m", "mesh": {{ "quad": {{}} }}, "material": {{ "texture": {{ "file": "gone.png" }} }} }}] }}"#,
        ortho(4, 4, "")
    );
    let msg = Scene::from_json(&json, "bad.json", "/tmp")
        .unwrap()
        .prepare()
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("/tmp/gone.png") && msg.contains("No such file"),
        "{msg}"
    );
}

#[test]
fn positions_close_count_mismatch_names_the_field() {
    let json = format!(
        r#"{{ {}, "objects": [{{ "name": "t", "mesh": {{ "triangles": [[[0,0,0],[1,0,0],[0,1,0]]] }},
            "motion": {{ "positions_close": [[0,0,0]] }} }}] }}"#,
        ortho(4, 4, "")
    );
    let msg = Scene::from_json(&json, "bad.json", ".")
        .unwrap()
        .prepare()
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("motion.positions_close") && msg.contains("3 vertices"),
        "{msg}"
    );
}

/// Vertex positions at keys: a wrong count, a key without positions and a key mixing
/// positions with a transform are errors naming the key; good keys cut the shutter at
/// every key and the vertices reach each key's positions.
#[test]
fn key_positions_are_checked_per_key_and_cut_the_shutter() {
    let scene = |keys: &str| {
        format!(
            r#"{{ {}, "objects": [{{ "name": "t", "mesh": {{ "triangles": [[[0,0,0],[1,0,0],[0,1,0]]] }},
                "transform": {{ "translate": [0.5, 0, 0] }},
                "motion": {{ "keys": [{keys}] }} }}] }}"#,
            ortho(4, 4, "")
        )
    };
    let p3 = r#""positions": [[0,0,0],[1,0,0],[0,1,0]]"#;
    let fails = |keys: String, needle: &str| {
        let msg = Scene::from_json(&scene(&keys), "bad.json", ".")
            .and_then(|s| s.prepare())
            .unwrap_err()
            .to_string();
        assert!(msg.contains(needle), "`{needle}` not in {msg}");
    };
    fails(
        format!(r#"{{ "t": 0, {p3} }}, {{ "t": 1, "positions": [[0,0,0]] }}"#),
        "objects[0] \"t\".motion.keys[1].positions: has 1 positions but the mesh has 3 vertices",
    );
    fails(
        format!(r#"{{ "t": 0, {p3} }}, {{ "t": 1 }}"#),
        "motion.keys[1].positions: is missing",
    );
    fails(
        format!(r#"{{ "t": 0, {p3} }}, {{ "t": 1, "translate": [1, 0, 0], {p3} }}"#),
        "motion.keys[1]: a key with `positions` takes no",
    );
    let good = format!(
        r#"{{ "t": 0, {p3} }}, {{ "t": 0.25, "positions": [[1,0,0],[2,0,0],[1,1,0]] }}, {{ "t": 1, {p3} }}"#
    );
    let p = Scene::from_json(&scene(&good), "good.json", ".")
        .and_then(|s| s.prepare())
        .unwrap();
    let spans: Vec<[f64; 2]> = p.triangles.iter().map(|t| t.span).collect();
    assert_eq!(spans, [[0.0, 0.25], [0.25, 1.0]]);
    // Placed by the transform (+0.5 in x); the second span starts where the first ends.
    assert_eq!(p.triangles[0].world_close[0].x, 1.5);
    assert_eq!(p.triangles[1].world_open, p.triangles[0].world_close);
    assert!(p.objects[0].path.is_none());
}

// ---- files ----

#[test]
fn obj_and_ply_ascii_and_binary_load_the_same_triangle() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("t.obj"),
        "v -2 -2 0\nv 2 -2 0\nv 0 2 0\nvt 0 0\nvt 1 0\nvt 0.5 1\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("a.ply"),
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n-2 -2 0\n2 -2 0\n0 2 0\n3 0 1 2\n",
    )
    .unwrap();
    let mut bin = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    for v in [[-2.0f32, -2.0, 0.0], [2.0, -2.0, 0.0], [0.0, 2.0, 0.0]] {
        for c in v {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    bin.push(3);
    for i in [0i32, 1, 2] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    std::fs::write(dir.path().join("b.ply"), bin).unwrap();
    let mut images = Vec::new();
    for f in ["t.obj", "a.ply", "b.ply"] {
        let json = format!(
            r#"{{ {}, "objects": [{{ "name": "m", "mesh": {{ "file": "{f}" }} }}] }}"#,
            ortho(8, 8, "")
        );
        std::fs::write(dir.path().join("s.json"), json).unwrap();
        let s = Scene::load(dir.path().join("s.json")).unwrap();
        let p = s.prepare().unwrap();
        assert_eq!(p.triangles.len(), 1, "{f}");
        images.push(accum(&s, 1));
    }
    assert_eq!(images[0], images[1]);
    assert_eq!(images[1], images[2]);
    assert!(images[0].pixels.iter().any(|p| p[0] == 1.0));
}

#[test]
fn ply_face_with_bad_index_is_a_format_error() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("a.ply"),
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
    )
    .unwrap();
    let json = format!(
        r#"{{ {}, "objects": [{{ "name": "m", "mesh": {{ "file": "a.ply" }} }}] }}"#,
        ortho(8, 8, "")
    );
    let msg = Scene::from_json(&json, "s.json", dir.path())
        .unwrap()
        .prepare()
        .unwrap_err()
        .to_string();
    assert!(msg.contains("a.ply") && msg.contains("vertex 7"), "{msg}");
}

#[test]
fn pfm_round_trip_is_bit_exact_and_failed_write_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let img = mblur::Image {
        width: 3,
        height: 2,
        pixels: (0..6).map(|k| [k as f32 * 0.1, 1.0 / 3.0, -2.5]).collect(),
    };
    let path = dir.path().join("x.pfm");
    mblur_scene::image_io::save(&img, &path).unwrap();
    assert_eq!(mblur_scene::image_io::read_pfm(&path).unwrap(), img);
    // Unsupported extension and missing folder: error, no file.
    assert!(mblur_scene::image_io::save(&img, &dir.path().join("x.bmp")).is_err());
    assert!(mblur_scene::image_io::save(&img, &dir.path().join("no/such/dir/x.png")).is_err());
    assert_eq!(integration_tests::files(dir.path()), ["x.pfm"]);
}

#[test]
fn png_and_exr_outputs_decode_to_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let img = mblur::Image {
        width: 2,
        height: 1,
        pixels: vec![[0.0, 0.5, 1.0], [0.25, 0.75, 0.125]],
    };
    mblur_scene::image_io::save(&img, &dir.path().join("x.png")).unwrap();
    mblur_scene::image_io::save(&img, &dir.path().join("x.exr")).unwrap();
    let png = image::open(dir.path().join("x.png")).unwrap().into_rgb8();
    assert_eq!(png.as_raw(), &img.to_srgb8());
    let exr = image::open(dir.path().join("x.exr")).unwrap().into_rgb32f();
    let flat: Vec<f32> = img.pixels.iter().flatten().copied().collect();
    assert_eq!(exr.as_raw(), &flat);
}

#[test]
fn scene_format_example_parses_and_validates() {
    // The full example of SCENE_FORMAT.md (here, or in docs/ once moved by the integrator).
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = [
        root.join("SCENE_FORMAT.md"),
        root.join("../docs/SCENE_FORMAT.md"),
    ]
    .iter()
    .find_map(|p| std::fs::read_to_string(p).ok())
    .expect("SCENE_FORMAT.md");
    let start = doc.find("## Full example").unwrap();
    let block = &doc[start..];
    let json = &block[block.find("```json").unwrap() + 7..];
    let json = &json[..json.find("```").unwrap()];
    let s =
        Scene::from_json(json, "example.json", "/nonexistent").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.desc.objects.len(), 4);
    // Its bunny mesh is not shipped: preparing names the missing file.
    let msg = s.prepare().unwrap_err().to_string();
    assert!(msg.contains("/nonexistent/meshes/bunny.obj"), "{msg}");
}

#[test]
fn splat_ply_with_normals_colours_and_radii_renders_discs() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("pts.ply"),
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n\
         property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
         property float radius\nend_header\n-4 0 0 0 0 1 255 0 0 2.5\n4 0 0 0 0 1 0 255 0 2.5\n",
    )
    .unwrap();
    let json = format!(
        r#"{{ {}, "splats": [{{ "name": "p", "source": {{ "ply": "pts.ply" }} }}] }}"#,
        ortho(16, 8, "")
    );
    let s = Scene::from_json(&json, "s.json", dir.path()).unwrap();
    let p = s.prepare().unwrap();
    assert_eq!(p.splats.len(), 2);
    assert_eq!(p.splats[1].radius_open, 2.5);
    let img = accum(&s, 1);
    // Disc centres at pixels (4, 4) and (12, 4): red and green; between them black.
    assert_eq!(img.get(3, 3).unwrap(), [1.0, 0.0, 0.0]);
    assert_eq!(img.get(12, 4).unwrap(), [0.0, 1.0, 0.0]);
    assert_eq!(img.get(8, 4).unwrap(), [0.0, 0.0, 0.0]);
    // A 16-gon of radius 2.5 covers about pi r^2 = 19.6 pixel centres (16-gon: 19.1).
    let red = img.pixels.iter().filter(|q| q[0] == 1.0).count();
    assert!((16..=24).contains(&red), "{red}");
}

#[test]
fn splat_ply_without_normals_is_rejected() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("pts.ply"),
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
    )
    .unwrap();
    let json = format!(
        r#"{{ {}, "splats": [{{ "name": "p", "source": {{ "ply": "pts.ply" }}, "radius": 1 }}] }}"#,
        ortho(16, 8, "")
    );
    let msg = Scene::from_json(&json, "s.json", dir.path())
        .unwrap()
        .prepare()
        .unwrap_err()
        .to_string();
    assert!(msg.contains("pts.ply") && msg.contains("normals"), "{msg}");
}

#[cfg(unix)]
#[test]
fn saved_images_are_ordinary_readable_files() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("x.png");
    mblur_scene::image_io::save(&mblur::Image::filled(2, 2, [0.5; 3]), &path).unwrap();
    let mode = std::fs::metadata(&path).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o644);
}

/// `motion.positions_close` of an OBJ mesh follows the file's `v` lines: two files with
/// the same `v` lines and the faces `f 3 1 2` and `f 1 2 3` render the same motion, and a
/// file with an unused `v` line accepts a list with one position per `v` line.
#[test]
fn obj_positions_close_follow_the_v_lines() {
    let dir = tempfile::tempdir().unwrap();
    let v = "v -2 -2 0\nv 2 -2 0\nv 0 2 0\n";
    std::fs::write(dir.path().join("a.obj"), format!("{v}f 1 2 3\n")).unwrap();
    std::fs::write(dir.path().join("b.obj"), format!("{v}f 3 1 2\n")).unwrap();
    std::fs::write(dir.path().join("c.obj"), format!("{v}v 9 9 9\nf 1 2 3\n")).unwrap();
    let close = "[-1,-2,0],[3,-2,0],[1,2,0]";
    let scene = |f: &str, extra: &str| {
        let json = format!(
            r#"{{ {}, "objects": [{{ "name": "m", "mesh": {{ "file": "{f}" }},
                "motion": {{ "positions_close": [{close}{extra}] }} }}] }}"#,
            ortho(8, 8, "")
        );
        std::fs::write(dir.path().join("s.json"), json).unwrap();
        Scene::load(dir.path().join("s.json")).unwrap()
    };
    let (a, b) = (scene("a.obj", ""), scene("b.obj", ""));
    let c = scene("c.obj", ",[9,9,9]");
    let (pa, pb, pc) = (
        a.prepare().unwrap(),
        b.prepare().unwrap(),
        c.prepare().unwrap(),
    );
    // Every corner moves by +1 in x whichever order the face lists it in.
    for p in [&pa, &pb, &pc] {
        for t in &p.triangles {
            for k in 0..3 {
                let d = t.world_close[k] - t.world_open[k];
                assert_eq!(d, glam::DVec3::X, "{:?}", t.world_open);
            }
        }
    }
    assert_eq!(accum(&a, 16), accum(&b, 16));
    assert_eq!(accum(&a, 16), accum(&c, 16));
    // One position per `v` line: the three of the used lines alone do not match c.obj.
    let json = format!(
        r#"{{ {}, "objects": [{{ "name": "m", "mesh": {{ "file": "c.obj" }},
            "motion": {{ "positions_close": [{close}] }} }}] }}"#,
        ortho(8, 8, "")
    );
    std::fs::write(dir.path().join("s.json"), json).unwrap();
    let msg = Scene::load(dir.path().join("s.json"))
        .and_then(|s| s.prepare())
        .expect_err("3 positions for 4 `v` lines")
        .to_string();
    assert!(
        msg.contains("positions_close") && msg.contains("4 vertices"),
        "{msg}"
    );
}

/// Every triangle corner's 2DH position is the projection of its world position at its
/// span's ends, bit for bit, whether the motion is keyed vertex positions (the frames cut at
/// every key), a curved path cut into segments or a straight path: the preparation projects
/// each vertex once per frame and the triangles share it.
#[test]
fn corners_are_the_projection_of_their_world_positions() {
    let p3 = r#""positions": [[0,0,0],[1,0,0],[0,1,0]]"#;
    let keyed = format!(
        r#"{{ {}, "objects": [{{ "name": "t", "mesh": {{ "triangles": [[[0,0,0],[1,0,0],[0,1,0]]] }},
            "motion": {{ "keys": [{{ "t": 0, {p3} }}, {{ "t": 0.25, "positions": [[1,0,0],[2,0,0],[1,1,0]] }}, {{ "t": 1, {p3} }}] }} }}] }}"#,
        ortho(4, 4, "")
    );
    // Keyed and turning scenes are cut into several frames; fence moves in one segment.
    let scenes = [
        ("keyed.json", keyed, true),
        (
            "spinning-wheel.json",
            include_str!("../scenes/spinning-wheel.json").to_string(),
            true,
        ),
        (
            "fence.json",
            include_str!("../scenes/fence.json").to_string(),
            false,
        ),
    ];
    for (name, text, cut) in scenes {
        let p = Scene::from_json(&text, name, ".")
            .and_then(|s| s.prepare())
            .unwrap();
        assert_eq!(
            p.triangles.iter().any(|t| t.span != [0.0, 1.0]),
            cut,
            "{name}"
        );
        for t in &p.triangles {
            for k in 0..3 {
                assert_eq!(
                    t.open[k],
                    p.project_at(t.span[0], t.world_open[k]),
                    "{name}"
                );
                assert_eq!(
                    t.close[k],
                    p.project_at(t.span[1], t.world_close[k]),
                    "{name}"
                );
            }
        }
    }
}

fn keyed(keys: &str) -> String {
    format!(
        r#"{{ {}, "objects": [{{ "name": "w", "mesh": {{ "box": {{}} }},
            "motion": {{ "keys": [{keys}] }} }}] }}"#,
        ortho(8, 8, "")
    )
}

/// Key times that do not strictly increase are an error naming the key.
#[test]
fn key_times_not_increasing_name_the_key() {
    let msg = err(&keyed(
        r#"{ "t": 0 }, { "t": 0.6 }, { "t": 0.4 }, { "t": 1 }"#,
    ))
    .to_string();
    assert!(
        msg.contains(r#"objects[0] "w".motion.keys[2].t"#) && msg.contains("strictly increase"),
        "{msg}"
    );
    let msg = err(&keyed(r#"{ "t": 0.1 }, { "t": 1 }"#)).to_string();
    assert!(msg.contains("keys[0].t") && msg.contains("t = 0"), "{msg}");
    let msg = err(&keyed(r#"{ "t": 0 }, { "t": 0.9 }"#)).to_string();
    assert!(msg.contains("keys[1].t") && msg.contains("t = 1"), "{msg}");
    let msg = err(&keyed(r#"{ "t": 0 }"#)).to_string();
    assert!(
        msg.contains("motion.keys") && msg.contains("at least two"),
        "{msg}"
    );
    let json = format!(
        r#"{{ {}, "objects": [{{ "name": "w", "mesh": {{ "box": {{}} }},
            "motion": {{ "close": {{}}, "keys": [{{ "t": 0 }}, {{ "t": 1 }}] }} }}] }}"#,
        ortho(8, 8, "")
    );
    assert!(err(&json).to_string().contains("one of them"));
}

/// Camera key times are checked the same way, and so are a splat set's keys (transforms
/// only: per-point positions at keys are refused).
#[test]
fn camera_keys_and_splat_keys_are_checked() {
    let cam = r#", "motion": { "keys": [ { "t": 0 }, { "t": 0 }, { "t": 1 } ] }"#;
    let json = format!(r#"{{ {} }}"#, ortho(8, 8, cam));
    let msg = err(&json).to_string();
    assert!(msg.contains("camera.motion.keys[1].t"), "{msg}");
    let splats = |keys: &str| {
        format!(
            r#"{{ {}, "splats": [{{ "name": "s", "radius": 0.1,
            "source": {{ "sample": {{ "mesh": {{ "box": {{}} }}, "count": 4 }} }},
            "motion": {{ "keys": [{keys}] }} }}] }}"#,
            ortho(8, 8, "")
        )
    };
    let msg = err(&splats(
        r#"{ "t": 0 }, { "t": 0.5 }, { "t": 0.25, "translate": [1, 0, 0] }, { "t": 1 }"#,
    ))
    .to_string();
    assert!(
        msg.contains(r#"splats[0] "s".motion.keys[2].t"#) && msg.contains("strictly increase"),
        "{msg}"
    );
    let msg = err(&splats(
        r#"{ "t": 0, "positions": [[0, 0, 0]] }, { "t": 1, "positions": [[1, 0, 0]] }"#,
    ))
    .to_string();
    assert!(
        msg.contains(r#"splats[0] "s".motion.keys"#) && msg.contains("positions"),
        "{msg}"
    );
    let ok = splats(r#"{ "t": 0 }, { "t": 1, "rotate": { "axis": [0, 1, 0], "degrees": 270 } }"#);
    let p = Scene::from_json(&ok, "s.json", ".")
        .unwrap()
        .prepare()
        .unwrap();
    assert!(p.splat_objects[0].path.is_some() && p.splat_objects[0].segments > 1);
}

/// A turn of exactly 180° between rotations about different axes goes the positive way
/// about the relative rotation's axis (the documented choice); about one axis, the angle
/// given is the turn, so 350° turns 350° and keys at 0°, 200°, 400° spin past 360°.
#[test]
fn rotation_interpolation_choices() {
    let prepare = |keys: &str| {
        Scene::from_json(&keyed(keys), "k.json", ".")
            .unwrap()
            .prepare()
            .unwrap()
    };
    let at = |p: &mblur::PreparedScene, t: f64| {
        let path = p.objects[0].path.as_ref().expect("curved");
        path.affine(t).transform_point3(glam::DVec3::X)
    };
    let near = |a: glam::DVec3, b: [f64; 3]| (a - glam::DVec3::from_array(b)).length() < 1e-9;
    let half = prepare(
        r#"{ "t": 0, "rotate": { "axis": [1, 0, 0], "degrees": 0 } },
           { "t": 1, "rotate": { "axis": [0, 0, 1], "degrees": 180 } }"#,
    );
    assert!(near(at(&half, 0.5), [0.0, 1.0, 0.0]), "{}", at(&half, 0.5));
    let spin =
        prepare(r#"{ "t": 0 }, { "t": 1, "rotate": { "axis": [0, 0, 1], "degrees": 350 } }"#);
    let a = 175f64.to_radians();
    assert!(
        near(at(&spin, 0.5), [a.cos(), a.sin(), 0.0]),
        "{}",
        at(&spin, 0.5)
    );
    let past = prepare(
        r#"{ "t": 0 }, { "t": 0.5, "rotate": { "axis": [0, 0, 1], "degrees": 200 } },
           { "t": 1, "rotate": { "axis": [0, 0, 1], "degrees": 400 } }"#,
    );
    let a = 300f64.to_radians();
    assert!(
        near(at(&past, 0.75), [a.cos(), a.sin(), 0.0]),
        "{}",
        at(&past, 0.75)
    );
    // Every key pair turns, so each is cut into segments that meet at the keys.
    let times: Vec<f64> = past.triangles[..past.objects[0].segments as usize]
        .iter()
        .map(|t| t.span[0])
        .collect();
    assert!(times.contains(&0.5), "{times:?}");
}

/// Straight motion (translation only) stays one segment per triangle spanning the shutter;
/// `--segments 3` cuts a turning object into 3 per key pair; more than 64 is refused.
#[test]
fn segment_counts() {
    use mblur_scene::segments::{MotionOptions, Segments};
    let straight = keyed(r#"{ "t": 0 }, { "t": 1, "translate": [1, 0, 0] }"#);
    let s = Scene::from_json(&straight, "s.json", ".")
        .unwrap()
        .prepare()
        .unwrap();
    assert!(
        s.triangles
            .iter()
            .all(|t| t.span == [0.0, 1.0] && t.local.is_none())
    );
    assert_eq!(s.objects[0].segments, 1);
    let turning =
        keyed(r#"{ "t": 0 }, { "t": 1, "rotate": { "axis": [0, 0, 1], "degrees": 90 } }"#);
    let scene = Scene::from_json(&turning, "s.json", ".").unwrap();
    let opts = |segments| MotionOptions {
        segments,
        ..MotionOptions::default()
    };
    let p = scene.prepare_with(&opts(Segments::Fixed(3))).unwrap();
    assert_eq!(p.objects[0].segments, 3);
    assert_eq!(p.triangles.len(), 3 * 12);
    let msg = scene
        .prepare_with(&opts(Segments::Fixed(65)))
        .expect_err("65 segments")
        .to_string();
    assert!(msg.contains("segments") && msg.contains("64"), "{msg}");
}

#[test]
fn zero_length_normals_in_a_mesh_file_fall_back_to_smooth_normals() {
    // `vn 0 0 0` carries no direction: the corner takes the smooth (here: face) normal,
    // the documented fallback, instead of a NaN from normalising it.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("z.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n",
    )
    .unwrap();
    let json = format!(
        r#"{{ {}, "objects": [{{ "name": "m", "mesh": {{ "file": "z.obj" }},
            "material": {{ "shading": "lambert" }} }}] }}"#,
        ortho(8, 8, "")
    );
    let s = Scene::from_json(&json, "z.json", dir.path()).unwrap();
    let p = s.prepare().unwrap();
    for t in &p.triangles {
        for n in t.normal_open.iter().chain(&t.normal_close) {
            assert!((*n - glam::DVec3::Z).length() < 1e-12, "{n}");
        }
    }
}

#[test]
fn built_in_shapes_carry_their_analytic_normals() {
    // A sphere's normal at a corner is the direction from its centre; a box's corners take
    // their face's normal (the box's positions are not shared between faces).
    let json = format!(
        r#"{{ {}, "objects": [
            {{ "name": "s", "mesh": {{ "sphere": {{ "radius": 2, "subdivisions": 6 }} }},
              "transform": {{ "translate": [1, 2, 3] }}, "material": {{ "shading": "lambert" }} }},
            {{ "name": "b", "mesh": {{ "box": {{ "size": [1, 2, 3] }} }}, "normals": "auto" }}] }}"#,
        ortho(8, 8, "")
    );
    let p = Scene::from_json(&json, "n.json", ".")
        .unwrap()
        .prepare()
        .unwrap();
    let centre = glam::DVec3::new(1.0, 2.0, 3.0);
    let (sphere, boxed) = (&p.objects[0], &p.objects[1]);
    for t in &p.triangles[sphere.range.clone()] {
        for (w, n) in t.world_open.iter().zip(&t.normal_open) {
            assert!(((*w - centre).normalize() - *n).length() < 1e-9, "{w} {n}");
        }
    }
    for t in &p.triangles[boxed.range.clone()] {
        let [a, b, c] = t.world_open;
        let face = (b - a).cross(c - a).normalize();
        for n in t.normal_open {
            assert!((n - face).length() < 1e-12, "{n} vs face {face}");
        }
    }
}

#[test]
fn smooth_and_flat_normals_of_a_shared_vertex_mesh() {
    // Two triangles folded along a shared edge: smooth normals at the shared corners are
    // the normalised sum of both faces' area vectors; flat ones each face's own.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("fold.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 -1\nf 1 2 3\nf 1 3 4\n",
    )
    .unwrap();
    let normals = |mode: &str| {
        let json = format!(
            r#"{{ {}, "objects": [{{ "name": "m", "mesh": {{ "file": "fold.obj" }}, "normals": "{mode}" }}] }}"#,
            ortho(8, 8, "")
        );
        let p = Scene::from_json(&json, "f.json", dir.path())
            .unwrap()
            .prepare()
            .unwrap();
        p.triangles
            .iter()
            .map(|t| t.normal_open)
            .collect::<Vec<_>>()
    };
    let z = glam::DVec3::Z;
    let x = -glam::DVec3::X;
    let both = (z + x).normalize();
    let smooth = normals("smooth");
    // Corners 0 and 2 of the first face are the shared positions 1 and 3.
    assert!((smooth[0][0] - both).length() < 1e-12 && (smooth[0][2] - both).length() < 1e-12);
    assert!((smooth[0][1] - z).length() < 1e-12);
    let flat = normals("flat");
    assert!(flat[0].iter().all(|n| (*n - z).length() < 1e-12));
    assert!(flat[1].iter().all(|n| (*n - x).length() < 1e-12));
    assert_eq!(normals("auto"), smooth);
}

/// Light keys follow the rules of motion keys: times strictly increasing from 0 to 1 (the
/// error names the key), directions non-zero, and `keys` excludes the open/close values.
#[test]
fn light_key_times_and_values_are_checked() {
    let scene = |light: &str| format!(r#"{{ {}, "lights": [{light}] }}"#, ortho(8, 8, ""));
    let cases = [
        (
            r#"{ "type": "directional", "keys": [{ "t": 0, "direction": [0, 0, -1] },
                { "t": 0.7, "direction": [1, 0, -1] }, { "t": 0.7, "direction": [1, 0, 0] },
                { "t": 1, "direction": [0, 1, 0] }] }"#,
            "lights[0].keys[2].t",
            "strictly increase",
        ),
        (
            r#"{ "type": "point", "keys": [{ "t": 0.2, "position": [0, 0, 1] },
                { "t": 1, "position": [1, 0, 1] }] }"#,
            "lights[0].keys[0].t",
            "t = 0",
        ),
        (
            r#"{ "type": "point", "keys": [{ "t": 0, "position": [0, 0, 1] },
                { "t": 0.5, "position": [1, 0, 1] }] }"#,
            "lights[0].keys[1].t",
            "t = 1",
        ),
        (
            r#"{ "type": "point", "keys": [{ "t": 0, "position": [0, 0, 1] }] }"#,
            "lights[0].keys",
            "at least two",
        ),
        (
            r#"{ "type": "directional", "keys": [{ "t": 0, "direction": [0, 0, -1] },
                { "t": 1, "direction": [0, 0, 0] }] }"#,
            "lights[0].keys[1].direction",
            "non-zero",
        ),
        (
            r#"{ "type": "directional", "direction": [0, 0, -1],
                 "keys": [{ "t": 0, "direction": [0, 0, -1] }, { "t": 1, "direction": [1, 0, 0] }] }"#,
            "lights[0]",
            "not both",
        ),
        (
            r#"{ "type": "point", "intensity": 2 }"#,
            "lights[0].position",
            "required",
        ),
    ];
    for (light, place, what) in cases {
        let msg = err(&scene(light)).to_string();
        assert!(msg.contains(place) && msg.contains(what), "{msg}");
    }
}

/// A directional light keyed between exactly opposite directions turns through the side
/// of world up (the documented choice for the 180° ambiguity): from +X to -X it travels
/// along +Y half way.
#[test]
fn opposite_light_keys_turn_through_the_side_of_world_up() {
    let json = format!(
        r#"{{ {}, "lights": [{{ "type": "directional", "keys": [
            {{ "t": 0, "direction": [1, 0, 0] }}, {{ "t": 1, "direction": [-1, 0, 0] }}] }}] }}"#,
        ortho(8, 8, "")
    );
    let s = Scene::from_json(&json, "l.json", ".")
        .unwrap()
        .prepare()
        .unwrap();
    let d = s.lights[0].direction_at(0.5).expect("directional");
    assert!((d - glam::DVec3::Y).length() < 1e-12, "{d}");
}
