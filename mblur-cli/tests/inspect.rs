//! The `mblur inspect` command: the SVG it writes and its errors.

mod common;

use common::{files, mblur};

#[test]
fn cli_out_of_range_pixel_fails_without_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = mblur()
        .current_dir(dir.path())
        .args([
            "inspect",
            "crossing-quads",
            "--pixel",
            "48,10",
            "--width",
            "48",
        ])
        .args(["--height", "36", "-o", "pixel.svg"])
        .assert()
        .failure()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        stderr.starts_with("error: ") && stderr.contains("--pixel"),
        "{stderr}"
    );
    assert!(files(dir.path()).is_empty());
    // A splat-only scene, and a file name that is not .svg.
    mblur()
        .current_dir(dir.path())
        .args(["inspect", "splat-ball", "--pixel", "1,1", "-o", "pixel.svg"])
        .assert()
        .failure()
        .stderr(predicates::str::contains("splats"));
    mblur()
        .current_dir(dir.path())
        .args([
            "inspect",
            "crossing-quads",
            "--pixel",
            "1,1",
            "-o",
            "pixel.png",
        ])
        .assert()
        .failure()
        .stderr(predicates::str::contains(".svg"));
    assert!(files(dir.path()).is_empty());
}

#[test]
fn cli_writes_the_svg() {
    let dir = tempfile::tempdir().unwrap();
    mblur()
        .current_dir(dir.path())
        .args(["inspect", "fence", "--pixel", "32,18", "--width", "64"])
        .args(["--height", "36", "--intervals", "3", "--quiet"])
        .assert()
        .success();
    assert_eq!(files(dir.path()), vec!["fence-32-18.svg".to_string()]);
    let svg = std::fs::read_to_string(dir.path().join("fence-32-18.svg")).unwrap();
    let lines = integration_tests::svg_panel_intervals(&svg);
    assert_eq!(lines.len(), 2);
    assert!(lines[1] <= 3 && lines[0] > 3, "{lines:?}");
}
