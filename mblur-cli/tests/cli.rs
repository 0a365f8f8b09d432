//! The `mblur` command: bad input gives a clear error, a non-zero exit code and no output
//! file; good input writes the file.

mod common;

use common::{files, mblur};
use predicates::prelude::*;

const CAMERA: &str = r#""camera": { "width": 16, "height": 8, "projection": { "perspective": { "fov_y_deg": 40 } },
    "eye": [0, 0, 5], "target": [0, 0, 0], "near": 0.1, "far": 100 }"#;

/// Writes `json` to DIR/scene.json, runs `mblur render scene.json -o out.png`, expects
/// failure with `needles` in stderr and no out.png (nor stray temporary files).
fn fails(json: &str, needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.json"), json).unwrap();
    let out = mblur()
        .current_dir(dir.path())
        .args(["render", "scene.json", "-o", "out.png", "--quiet"])
        .assert()
        .failure()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(stderr.starts_with("error: "), "{stderr}");
    for n in needles {
        assert!(stderr.contains(n), "`{n}` not in: {stderr}");
    }
    assert_eq!(files(dir.path()), ["scene.json"]);
}

#[test]
fn malformed_json_reports_file_line_column() {
    fails(
        &format!("{{ {CAMERA},\n \"objects\": [ }}"),
        &["scene.json: line 3, column 15", "expected value"],
    );
}

#[test]
fn unknown_field_is_named() {
    fails(
        &format!(r#"{{ {CAMERA}, "backgrund": [0, 0, 0] }}"#),
        &["unknown field `backgrund`"],
    );
}

#[test]
fn infinite_number_is_rejected() {
    fails(
        &format!(r#"{{ {CAMERA}, "background": [0, -1e400, 0] }}"#),
        &["line 2", "number out of range"],
    );
}

#[test]
fn negative_radius_names_object_and_field() {
    fails(
        &format!(
            r#"{{ {CAMERA}, "objects": [{{ "name": "ball", "mesh": {{ "sphere": {{ "radius": -1 }} }} }}] }}"#
        ),
        &[r#"objects[0] "ball".mesh.sphere.radius"#, "must be > 0"],
    );
}

#[test]
fn near_at_or_beyond_far_is_rejected() {
    let json = format!("{{ {} }}", CAMERA.replace("\"near\": 0.1", "\"near\": 200"));
    fails(&json, &["camera.near", "less than camera.far"]);
}

#[test]
fn image_over_the_pixel_limit_is_rejected() {
    let json = format!(
        "{{ {} }}",
        CAMERA.replace(
            "\"width\": 16, \"height\": 8",
            "\"width\": 32768, \"height\": 32768"
        )
    );
    fails(&json, &["exceeds the limit"]);
}

#[test]
fn missing_mesh_file_names_path_and_reason() {
    fails(
        &format!(
            r#"{{ {CAMERA}, "objects": [{{ "name": "m", "mesh": {{ "file": "meshes/none.ply" }} }}] }}"#
        ),
        &["meshes/none.ply", "No such file or directory"],
    );
}

#[test]
fn unreadable_texture_names_path_and_reason() {
    // A texture path that is a directory: refused before reading, naming the path.
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("tex.png")).unwrap();
    std::fs::write(
        dir.path().join("scene.json"),
        format!(r#"{{ {CAMERA}, "objects": [{{ "name": "m", "mesh": {{ "quad": {{}} }}, "material": {{ "texture": {{ "file": "tex.png" }} }} }}] }}"#),
    )
    .unwrap();
    mblur()
        .current_dir(dir.path())
        .args(["render", "scene.json", "-o", "out.png", "-q"])
        .assert()
        .failure()
        .stderr(
            predicate::str::contains("tex.png").and(predicate::str::contains("not a regular file")),
        );
    assert!(!dir.path().join("out.png").exists());
}

#[test]
fn missing_scene_file_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    mblur()
        .current_dir(dir.path())
        .args(["render", "nowhere.json", "-o", "out.png"])
        .assert()
        .failure()
        .stderr(
            predicate::str::contains("cannot read nowhere.json")
                .and(predicate::str::contains("No such file")),
        );
    assert!(!dir.path().join("out.png").exists());
}

#[test]
fn unknown_builtin_scene_is_an_error() {
    mblur()
        .args(["render", "marbles"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("unknown built-in scene `marbles`"));
}

#[test]
fn bad_output_extension_is_rejected_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    mblur()
        .current_dir(dir.path())
        .args(["render", "static", "-o", "out.jpg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("unsupported extension"));
    assert!(files(dir.path()).is_empty());
}

#[test]
fn zero_times_and_zero_width_are_rejected() {
    mblur()
        .args(["render", "static", "--times", "0"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("--times"));
    mblur()
        .args(["render", "static", "--width", "0"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("camera.width"));
}

#[test]
fn scenes_lists_every_builtin() {
    let out = mblur().arg("scenes").assert().success();
    let stdout = String::from_utf8_lossy(&out.get_output().stdout).into_owned();
    assert!(
        stdout
            .lines()
            .next()
            .is_some_and(|l| l.starts_with("billiards") && l.ends_with("(default)")),
        "{stdout}"
    );
    for (name, _, _) in mblur_scene::builtin::SCENES {
        assert!(
            stdout
                .lines()
                .any(|l| l.split_whitespace().next() == Some(name)),
            "{name} missing: {stdout}"
        );
    }
}

#[test]
fn render_prints_the_pipeline_and_writes_the_file() {
    let dir = tempfile::tempdir().unwrap();
    mblur()
        .current_dir(dir.path())
        .args([
            "render",
            "billiards",
            "--width",
            "48",
            "--height",
            "27",
            "--threads",
            "1",
        ])
        .assert()
        .success()
        .stderr(
            predicate::str::contains("motion: 4 objects")
                .and(predicate::str::contains("intersection handling: on"))
                .and(predicate::str::contains("method auto: using analytic"))
                .and(predicate::str::contains("wrote billiards.png")),
        );
    let img = image::open(dir.path().join("billiards.png")).unwrap();
    assert_eq!((img.width(), img.height()), (48, 27));
    assert_eq!(files(dir.path()), ["billiards.png"]);
}

#[test]
fn quiet_render_to_pfm_and_exr_is_silent() {
    let dir = tempfile::tempdir().unwrap();
    for out in ["a.pfm", "a.exr"] {
        mblur()
            .current_dir(dir.path())
            .args([
                "render",
                "textured-quad",
                "--width",
                "24",
                "--height",
                "18",
                "-m",
                "accum",
                "--times",
                "4",
                "-q",
                "-o",
                out,
            ])
            .assert()
            .success()
            .stderr(predicate::str::is_empty())
            .stdout(predicate::str::is_empty());
    }
    let pfm = mblur_scene::image_io::read_pfm(&dir.path().join("a.pfm")).unwrap();
    let exr = image::open(dir.path().join("a.exr")).unwrap().into_rgb32f();
    let flat: Vec<f32> = pfm.pixels.iter().flatten().copied().collect();
    assert_eq!(exr.as_raw(), &flat);
}

#[test]
fn scene_file_with_relative_mesh_renders() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("meshes")).unwrap();
    std::fs::write(
        dir.path().join("meshes/tri.obj"),
        "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("scene.json"),
        format!(r#"{{ {CAMERA}, "objects": [{{ "name": "t", "mesh": {{ "file": "meshes/tri.obj" }}, "motion": {{ "close": {{ "translate": [0.5, 0, 0] }} }} }}] }}"#),
    )
    .unwrap();
    // Run from another folder: the mesh path is relative to the scene file.
    mblur()
        .current_dir(std::env::temp_dir())
        .arg("render")
        .arg(dir.path().join("scene.json"))
        .arg("-o")
        .arg(dir.path().join("out.png"))
        .assert()
        .success();
    assert!(dir.path().join("out.png").exists());
}

/// `--segments` and `--path-tolerance`: render reports the segments it chose per object;
/// a count out of range is refused naming the flag, before anything is written.
#[test]
fn segments_flags_are_reported_and_checked() {
    let dir = tempfile::tempdir().unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec![
            "render",
            "spinning-wheel",
            "--width",
            "48",
            "--height",
            "36",
        ];
        args.extend_from_slice(extra);
        mblur().current_dir(dir.path()).args(args).assert()
    };
    run(&[]).success().stderr(predicate::str::contains(
        "motion segments (auto, path tolerance 0.25 px): wheel ",
    ));
    run(&["--segments", "3"])
        .success()
        .stderr(predicate::str::contains(
            "motion segments (3 per turning key pair): wheel 3",
        ));
    run(&["--segments", "1"])
        .success()
        .stderr(predicate::str::contains("motion segments").not());
    std::fs::remove_file(dir.path().join("spinning-wheel.png")).unwrap();
    run(&["--segments", "65"])
        .failure()
        .stderr(predicate::str::contains("--segments"));
    run(&["--path-tolerance", "0"])
        .failure()
        .stderr(predicate::str::contains("path tolerance"));
    assert!(files(dir.path()).is_empty());
}
