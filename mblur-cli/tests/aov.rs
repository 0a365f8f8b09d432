//! `mblur render --aov`: the layers land in one multi-channel EXR with the usual layer names,
//! and the flags are checked before rendering.

mod common;

use common::{files, mblur};

#[test]
fn every_layer_is_written_with_its_conventional_channel_names() {
    let dir = tempfile::tempdir().unwrap();
    mblur()
        .current_dir(dir.path())
        .args([
            "render",
            "billiards",
            "--width",
            "64",
            "--height",
            "48",
            "-q",
        ])
        .args(["-o", "out.exr", "--aov", "depth,motion,sharp,id,coverage"])
        .args(["--sharp-at", "0.25"])
        .assert()
        .success();
    let ((w, h), channels) = mblur_scene::layered_exr::read(&dir.path().join("out.exr")).unwrap();
    assert_eq!((w, h), (64, 48));
    let names: Vec<&str> = channels.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "B",
            "G",
            "R",
            "coverage.X",
            "depth.Z",
            "id.X",
            "motion.X",
            "motion.Y",
            "sharp.B",
            "sharp.G",
            "sharp.R"
        ]
    );
    for (name, samples) in &channels {
        assert_eq!(samples.len(), 64 * 48, "{name}");
        assert!(samples.iter().all(|v| v.is_finite()), "{name}");
    }
    let channel = |n: &str| &channels.iter().find(|(c, _)| c == n).unwrap().1;
    assert!(
        channel("coverage.X")
            .iter()
            .all(|c| (0.0..=1.0).contains(c))
    );
    // Billiards: ids are whole numbers, the table and several balls are in view, and the
    // balls move.
    let ids = channel("id.X");
    assert!(ids.iter().all(|&i| i.fract() == 0.0 && i >= 0.0));
    assert!(ids.iter().filter(|&&i| i >= 2.0).count() > 20);
    assert!(channel("motion.X").iter().any(|&m| m.abs() > 1.0));
    // The image channels are the render's own.
    mblur()
        .current_dir(dir.path())
        .args([
            "render",
            "billiards",
            "--width",
            "64",
            "--height",
            "48",
            "-q",
        ])
        .args(["-o", "plain.exr"])
        .assert()
        .success();
    let (_, plain) = mblur_scene::layered_exr::read(&dir.path().join("plain.exr")).unwrap();
    for c in ["R", "G", "B"] {
        let p = &plain.iter().find(|(n, _)| n == c).unwrap().1;
        assert_eq!(p, channel(c), "channel {c}");
    }
}

#[test]
fn aov_flags_are_checked_before_rendering() {
    for (args, needle) in [
        (
            &["-o", "out.png", "--aov", "depth"][..],
            "invalid option --aov: layers are written into a multi-channel EXR",
        ),
        (
            &["-o", "out.exr", "--sharp-at", "0.3"][..],
            "invalid option --sharp-at: sets the instant of the AOV layers and needs --aov",
        ),
        (
            &["-o", "out.exr", "--aov", "id", "--sharp-at", "1.5"][..],
            "invalid option --sharp-at: must be in [0, 1], got 1.5",
        ),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let out = mblur()
            .current_dir(dir.path())
            .args(["render", "billiards", "-q"])
            .args(args)
            .assert()
            .failure()
            .code(1);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        assert!(stderr.contains(needle), "`{needle}` not in: {stderr}");
        assert!(files(dir.path()).is_empty());
    }
}
