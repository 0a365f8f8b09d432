//! The `mblur render` command per method: each method's options reach it, refusals are clear
//! errors that leave no output file. The note `auto` prints is checked here for splat-mix
//! (ewa) and in `cli.rs` for billiards (analytic); which method `auto` picks for every
//! built-in scene is `mblur/tests/auto.rs`.

mod common;

use common::mblur;

#[test]
fn cli_renders_with_the_ewa_knobs_and_refuses_triangle_scenes() {
    use predicates::prelude::*;
    let dir = tempfile::tempdir().unwrap();
    let mut cmd = mblur();
    cmd.current_dir(dir.path())
        .args([
            "render",
            "splat-ball",
            "--method",
            "ewa",
            "--subframes",
            "2",
            "--visibility",
            "approx",
            "--erf",
            "table",
            "--width",
            "32",
            "--height",
            "24",
            "-o",
            "out.pfm",
        ])
        .assert()
        .success()
        .stderr(predicate::str::contains(
            "2 subframes, visibility approx, erf table",
        ));
    let img = mblur_scene::image_io::read_pfm(&dir.path().join("out.pfm")).unwrap();
    integration_tests::assert_finite(&img, "out.pfm");
    let mut cmd = mblur();
    cmd.current_dir(dir.path())
        .args(["render", "static", "--method", "ewa", "-o", "static.png"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("ewa renders splat-only scenes"));
    assert!(!dir.path().join("static.png").exists());
    let mut cmd = mblur();
    cmd.args(["render", "splat-ball", "--visibility", "exact"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("expected one of: abuffer, approx"));
}

#[test]
fn cli_renders_splat_mix_and_refuses_approx_visibility_without_output() {
    use predicates::prelude::*;
    let dir = tempfile::tempdir().unwrap();
    let mut cmd = mblur();
    cmd.current_dir(dir.path())
        .args([
            "render",
            "splat-mix",
            "--width",
            "32",
            "--height",
            "24",
            "-o",
            "mix.pfm",
        ])
        .assert()
        .success()
        .stderr(predicate::str::contains("method auto: using ewa"));
    let img = mblur_scene::image_io::read_pfm(&dir.path().join("mix.pfm")).unwrap();
    integration_tests::assert_finite(&img, "mix.pfm");
    let mut cmd = mblur();
    cmd.current_dir(dir.path())
        .args([
            "render",
            "splat-mix",
            "--method",
            "ewa",
            "--visibility",
            "approx",
            "--width",
            "32",
            "--height",
            "24",
            "-o",
            "approx.png",
        ])
        .assert()
        .failure()
        .stderr(predicate::str::contains("triangle intervals"));
    assert!(!dir.path().join("approx.png").exists());
}

/// The command line: `--spp`, `--traversal`, `--seed`, `--footprint` and
/// `--max-pass-samples` reach the method, the counters are printed; a transparent scene
/// fails with exit code 1, names the objects and writes nothing; a bad `--spp`,
/// `--traversal`, `--footprint` or `--max-pass-samples` is rejected and writes nothing,
/// on the sampled and on the static path.
#[test]
fn command_line_options_and_errors() {
    let dir = tempfile::tempdir().unwrap();
    let mblur = common::mblur;
    let out = mblur()
        .current_dir(dir.path())
        .args([
            "render",
            "crossing-quads",
            "-m",
            "stochastic",
            "--spp",
            "4",
            "--traversal",
            "our-exact",
            "--seed",
            "5",
            "--footprint",
            "centre",
            "--width",
            "32",
            "--height",
            "18",
            "-o",
            "cq.pfm",
        ])
        .assert()
        .success();
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        stderr.contains("4 samples per pixel")
            && stderr.contains("at the pixel centre")
            && stderr.contains("our-exact"),
        "{stderr}"
    );
    assert!(stderr.contains("moving pass: 4 triangles"), "{stderr}");
    let img = mblur_scene::image_io::read_pfm(&dir.path().join("cq.pfm")).unwrap();
    assert_eq!((img.width, img.height), (32, 18));
    // --max-pass-samples: room for 2 of the 4 samples per pixel (of the 32 x 32 pixels the
    // buffer's whole 16-pixel bins hold), so two passes of 2.
    let out = mblur()
        .current_dir(dir.path())
        .args(["render", "crossing-quads", "-m", "stochastic", "--spp", "4"])
        .args(["--max-pass-samples", &(32 * 32 * 2).to_string()])
        .args(["--width", "32", "--height", "18", "-o", "cq2.pfm"])
        .assert()
        .success();
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        stderr.contains("2 passes of 2 samples per pixel"),
        "{stderr}"
    );
    let out = mblur()
        .current_dir(dir.path())
        .args([
            "render",
            "pills",
            "-m",
            "stochastic",
            "-o",
            "pills.png",
            "--quiet",
        ])
        .assert()
        .failure()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        stderr.contains("pill-glass") && stderr.contains("pill-amber"),
        "{stderr}"
    );
    assert!(!dir.path().join("pills.png").exists());
    for bad in [
        ["--spp", "3"],
        ["--traversal", "zigzag"],
        ["--footprint", "middle"],
        ["--max-pass-samples", "many"],
        // Not even one sample per pixel of the 640 x 360 default fits.
        ["--max-pass-samples", "1000"],
    ] {
        mblur()
            .current_dir(dir.path())
            .args([
                "render",
                "static",
                "-m",
                "stochastic",
                "-o",
                "s.png",
                "--quiet",
            ])
            .args(bad)
            .assert()
            .failure();
        assert!(!dir.path().join("s.png").exists());
    }
    // Checked on the static path too (nothing moves, samples at the centre).
    let out = mblur()
        .current_dir(dir.path())
        .args([
            "render",
            "static",
            "-m",
            "stochastic",
            "--footprint",
            "centre",
        ])
        .args(["--max-pass-samples", "1000", "-o", "s.png", "--quiet"])
        .assert()
        .failure()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(stderr.contains("--max-pass-samples"), "{stderr}");
    assert!(!dir.path().join("s.png").exists());
}

#[test]
fn aa_reaches_accum_analytic_and_prism_and_one_position_changes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str], out: &str| {
        mblur()
            .current_dir(dir.path())
            .args([
                "render",
                "billiards",
                "--width",
                "48",
                "--height",
                "27",
                "-o",
                out,
            ])
            .args(args)
            .assert()
    };
    let read = |f: &str| mblur_scene::image_io::read_pfm(&dir.path().join(f)).unwrap();
    // A method asked for by name samples the pixel centre; `--aa 1` is that image.
    run(&["-q", "-m", "analytic"], "plain.pfm").success();
    run(&["-q", "--aa", "1"], "one.pfm").success();
    assert_eq!(read("plain.pfm"), read("one.pfm"));
    // The default render (auto) takes AUTO_SAMPLES positions and says so.
    let n = mblur::aa::AUTO_SAMPLES.to_string();
    let out = run(&[], "default.pfm").success();
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        stderr.contains(&format!("{n} sample positions per pixel, box filter")),
        "{stderr}"
    );
    run(&["-q", "-m", "analytic", "--aa", &n], "n.pfm").success();
    // `render --help` names the same default.
    let help = mblur().args(["render", "--help"]).assert().success();
    let help = String::from_utf8_lossy(&help.get_output().stdout).into_owned();
    assert!(
        help.contains(&format!("Default: {n} under -m auto (the default render)")),
        "{help}"
    );
    assert_eq!(read("default.pfm"), read("n.pfm"));
    assert_ne!(read("default.pfm"), read("plain.pfm"));
    for method in ["accum", "analytic", "prism"] {
        let out = run(&["-m", method, "--aa", "4", "--filter", "tent"], "aa.pfm").success();
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        assert!(
            stderr.contains("4 sample positions per pixel, tent filter of radius 1 px"),
            "{method}: {stderr}"
        );
        assert_ne!(read("aa.pfm"), read("plain.pfm"), "{method}");
    }
    // stochastic weights its area samples by the same filter.
    let out = run(
        &["-m", "stochastic", "--spp", "4", "--filter", "tent"],
        "st.pfm",
    )
    .success();
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        stderr.contains("tent filter of radius 1 px over the samples of neighbouring pixels"),
        "{stderr}"
    );
    for (args, needle) in [
        (
            &["--aa", "3"][..],
            "invalid option --aa: must be a power of two from 1 to 1024, got 3",
        ),
        (
            &["--aa", "4", "--filter-radius", "0.1"][..],
            "invalid option --filter-radius: must be between 0.5 and 8 pixels, got 0.1",
        ),
        (
            &["-m", "stochastic", "--aa", "4"][..],
            "invalid option --aa: is a setting of accum and analytic and prism",
        ),
        (
            &[
                "-m",
                "stochastic",
                "--footprint",
                "centre",
                "--filter",
                "tent",
            ][..],
            "invalid option --filter: tent of radius 1 needs the area footprint",
        ),
    ] {
        let out = run(args, "bad.pfm").failure().code(1);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        assert!(stderr.contains(needle), "`{needle}` not in: {stderr}");
    }
}
