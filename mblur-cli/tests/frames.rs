//! Frame sequences of `mblur render` on a glTF animation: numbered outputs, a middle frame
//! equal to a one-frame render of its window, resuming a killed job, and clear messages for
//! bad ranges, a missing camera, JSON scenes and an animation shorter than the range.

mod common;

use std::path::Path;

use common::mblur;

/// Writes the animated cubes fixture (1 s of animation) to DIR/cubes.glb.
fn fixture(dir: &Path) {
    integration_tests::gltf_fixtures::animated_cubes().write_glb(&dir.join("cubes.glb"));
}

/// Runs `mblur render cubes.glb ARGS` (32 x 24) in `dir`; returns (success, stderr).
fn run(dir: &Path, args: &[&str]) -> (bool, String) {
    let out = mblur()
        .current_dir(dir)
        .args(["render", "cubes.glb", "--width", "32", "--height", "24"])
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn pixels(path: &Path) -> Vec<f32> {
    let img = mblur_scene::image_io::read(path).unwrap_or_else(|e| panic!("{e}"));
    img.pixels.iter().flatten().copied().collect()
}

#[test]
fn a_range_writes_numbered_frames_and_the_middle_one_equals_a_single_render() {
    let dir = tempfile::tempdir().unwrap();
    fixture(dir.path());
    let (ok, err) = run(
        dir.path(),
        &["--frames", "1-3", "--fps", "4", "-o", "out_####.exr"],
    );
    assert!(ok, "{err}");
    for f in ["out_0001.exr", "out_0002.exr", "out_0003.exr"] {
        assert!(dir.path().join(f).is_file(), "{f} missing: {err}");
    }
    let (ok, err) = run(
        dir.path(),
        &["--frame", "2", "--fps", "4", "-o", "single_#.exr"],
    );
    assert!(ok, "{err}");
    let (a, b) = (
        pixels(&dir.path().join("out_0002.exr")),
        pixels(&dir.path().join("single_2.exr")),
    );
    assert_eq!(a, b, "frame 2 of the range differs from frame 2 alone");
    // Frames differ from each other: the animation moves.
    assert_ne!(a, pixels(&dir.path().join("out_0001.exr")));
}

#[test]
fn a_killed_job_resumes_and_skips_finished_frames() {
    let dir = tempfile::tempdir().unwrap();
    fixture(dir.path());
    let args = ["--frames", "1-3", "--fps", "4", "-o", "f_##.png"];
    assert!(run(dir.path(), &args).0);
    // The job was killed after frame 1: frames 2 and 3 are missing.
    std::fs::remove_file(dir.path().join("f_02.png")).unwrap();
    std::fs::remove_file(dir.path().join("f_03.png")).unwrap();
    let before = std::fs::metadata(dir.path().join("f_01.png"))
        .unwrap()
        .modified()
        .unwrap();
    let (ok, err) = run(dir.path(), &args);
    assert!(ok, "{err}");
    assert!(err.contains("frame 1: f_01.png exists, skipped"), "{err}");
    assert!(err.contains("frame 2: wrote f_02.png"), "{err}");
    assert!(dir.path().join("f_03.png").is_file());
    let after = std::fs::metadata(dir.path().join("f_01.png"))
        .unwrap()
        .modified()
        .unwrap();
    assert_eq!(before, after, "a finished frame was rendered again");
    let (ok, err) = run(
        dir.path(),
        &[
            "--frames",
            "1",
            "--fps",
            "4",
            "-o",
            "f_##.png",
            "--overwrite",
        ],
    );
    assert!(ok && err.contains("frame 1: wrote"), "{err}");
}

#[test]
fn bad_ranges_cameras_and_short_animations_are_explained() {
    let dir = tempfile::tempdir().unwrap();
    fixture(dir.path());
    for (args, says) in [
        (
            vec!["--frames", "5-2", "-o", "o_#.png"],
            "--frames: `5-2`: the range runs backwards",
        ),
        (
            vec!["--frames", "1-3x0", "-o", "o_#.png"],
            "the step must be 1",
        ),
        (
            vec!["--frames", "1-3", "-o", "plain.png"],
            "need a run of `#`",
        ),
        (
            vec!["--frames", "1-3", "--frame", "9", "-o", "o_#.png"],
            "frame 9 is not in --frames",
        ),
        (
            vec!["--camera", "nope"],
            "has no camera `nope` (cameras: cam)",
        ),
        (
            vec!["--animation", "walk"],
            "has no animation `walk` (animations: take)",
        ),
        (vec!["--fps", "0"], "--fps"),
        (vec!["--shutter-angle", "400"], "--shutter-angle"),
    ] {
        let (ok, err) = run(dir.path(), &args);
        assert!(!ok, "{args:?} succeeded");
        assert!(
            err.starts_with("error: ") && err.contains(says),
            "{args:?}: {err}"
        );
    }
    // The animation ends at 1 s; frames 24-26 at 24 fps reach past it: a note, then the
    // frames render holding the last key.
    let (ok, err) = run(dir.path(), &["--frames", "24-26", "-o", "late_####.png"]);
    assert!(ok, "{err}");
    assert!(err.contains("the animation ends at 1 s"), "{err}");
    assert!(dir.path().join("late_0026.png").is_file());
    // JSON scenes have no timeline.
    std::fs::write(
        dir.path().join("s.json"),
        r#"{ "camera": { "width": 8, "height": 8, "projection": { "perspective": { "fov_y_deg": 40 } },
             "eye": [0, 0, 5], "target": [0, 0, 0], "near": 0.1, "far": 10 } }"#,
    )
    .unwrap();
    let out = mblur()
        .current_dir(dir.path())
        .args(["render", "s.json", "--frames", "1-2", "-o", "j_#.png"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("--frames: applies to glTF files"),
        "{err}"
    );
}
