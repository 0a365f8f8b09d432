//! Hostile input through the command, each case by name: values beyond what the renderer's
//! arithmetic holds, files that would take unbounded time or memory, accepted-but-wrong
//! input. Every case exits 1 with a message naming the file and the field or line, and
//! leaves no output file.

mod common;

use common::{files, mblur};

const CAMERA: &str = r#""camera": { "width": 16, "height": 8, "projection": { "perspective": { "fov_y_deg": 40 } },
    "eye": [0, 0, 5], "target": [0, 0, 0], "near": 0.1, "far": 100 }"#;

/// A quad scene with `material` and an optional `"shutter"` entry, background `background`.
fn quad_scene(material: &str, background: &str, shutter: &str) -> String {
    format!(
        r#"{{ {CAMERA}, "background": {background}, {shutter}
  "objects": [ {{ "name": "q", "mesh": {{ "quad": {{ "size": [1, 1] }} }}, "material": {material},
    "motion": {{ "open": {{ "translate": [-0.2, 0, 0] }}, "close": {{ "translate": [0.2, 0, 0] }} }} }} ] }}"#
    )
}

/// Runs `mblur render scene.json -o out.pfm` in a folder holding `scene` (and `extra`
/// files), with `args`; expects exit 1, every needle in stderr, and no out.pfm.
fn refused(scene: &str, extra: &[(&str, &[u8])], args: &[&str], needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.json"), scene).unwrap();
    for (name, bytes) in extra {
        std::fs::write(dir.path().join(name), bytes).unwrap();
    }
    let out = mblur()
        .current_dir(dir.path())
        .args(["render", "scene.json", "-o", "out.pfm", "--quiet"])
        .args(args)
        .assert()
        .failure()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    for n in needles {
        assert!(stderr.contains(n), "`{n}` not in: {stderr}");
    }
    assert!(!files(dir.path()).contains(&"out.pfm".to_string()));
    assert!(
        files(dir.path()).iter().all(|f| !f.starts_with(".mblur-")),
        "a temporary file was left behind"
    );
}

/// Renders in a folder holding `scene` and returns the PFM.
fn rendered(scene: &str, method: &str) -> mblur::Image {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.json"), scene).unwrap();
    mblur()
        .current_dir(dir.path())
        .args([
            "render",
            "scene.json",
            "-o",
            "out.pfm",
            "--quiet",
            "-m",
            method,
        ])
        .assert()
        .success();
    mblur_scene::image_io::read_pfm(&dir.path().join("out.pfm")).unwrap()
}

#[test]
fn colours_beyond_the_f32_range_are_refused_at_parse_time_naming_the_field() {
    for method in ["accum", "stochastic", "analytic", "prism"] {
        refused(
            &quad_scene(r#"{ "color": [1e308, 0, 0, 1] }"#, "[0, 0, 0]", ""),
            &[],
            &["-m", method],
            &[
                "scene.json: objects[0] \"q\".material.color[0]",
                "must be at most 1e6",
            ],
        );
        refused(
            &quad_scene(r#"{ "color": [1, 0, 0, 1] }"#, "[0, 1e308, 0]", ""),
            &[],
            &["-m", method],
            &["scene.json: background[1]", "must be at most 1e6"],
        );
    }
}

#[test]
fn a_small_png_declaring_a_huge_image_is_refused_before_decoding() {
    // 16384 x 16384 grey texels of zero: a few hundred kilobytes of PNG, 8 GiB as f64 texels.
    let side = 16384u32;
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, side, side);
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().unwrap();
        let mut stream = writer.stream_writer().unwrap();
        let row = vec![0u8; side as usize];
        for _ in 0..side {
            std::io::Write::write_all(&mut stream, &row).unwrap();
        }
        stream.finish().unwrap();
    }
    assert!(bytes.len() < 2 << 20, "{} bytes", bytes.len());
    refused(
        &quad_scene(
            r#"{ "color": [1, 1, 1, 1], "texture": { "file": "big.png" } }"#,
            "[0, 0, 0]",
            "",
        ),
        &[("big.png", &bytes)],
        &[],
        &["big.png", "16384 x 16384", "268435456 texels", "limit"],
    );
}

#[test]
fn a_mesh_path_to_a_device_is_refused_instead_of_read_forever() {
    if !std::path::Path::new("/dev/zero").exists() {
        return;
    }
    let scene = format!(
        r#"{{ {CAMERA}, "background": [0, 0, 0],
  "objects": [ {{ "name": "m", "mesh": {{ "file": "/dev/zero.obj" }} }} ] }}"#
    );
    // The extension picks the loader; a device has none, so link one in.
    let dir = tempfile::tempdir().unwrap();
    let link = dir.path().join("zero.obj");
    std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
    let scene = scene.replace("/dev/zero.obj", link.to_str().unwrap());
    refused(&scene, &[], &[], &["zero.obj", "is not a regular file"]);
}

#[test]
fn shutter_curves_are_bounded_and_checked_once_at_parse_time() {
    // Too many points: refused at once, naming the field.
    let pts: Vec<String> = (0..=100_000)
        .map(|i| format!("[{}, 1]", f64::from(i) / 100_000.0))
        .collect();
    let many = format!(
        r#""shutter": {{ "open": 0, "close": 1, "response": {{ "piecewise_linear": [{}] }} }},"#,
        pts.join(", ")
    );
    refused(
        &quad_scene(r#"{ "color": [1, 0, 0, 1] }"#, "[0, 0, 0]", &many),
        &[],
        &["-m", "prism"],
        &["shutter.response.piecewise_linear", "needs 2 to 4096"],
    );
    // A one-ulp spike: open for 2e-16 of the shutter.
    let t = 0.5f64;
    let spike = format!(
        r#""shutter": {{ "open": 0, "close": 1, "response": {{ "piecewise_linear": [[0, 0], [{t:?}, 0], [{:?}, 1], [{:?}, 0], [1, 0]] }} }},"#,
        f64::from_bits(t.to_bits() + 1),
        f64::from_bits(t.to_bits() + 2)
    );
    for method in ["accum", "analytic"] {
        refused(
            &quad_scene(r#"{ "color": [1, 0, 0, 1] }"#, "[0, 0, 0]", &spike),
            &[],
            &["-m", method],
            &["shutter.response.piecewise_linear", "is open for"],
        );
    }
    // Constant weights of any finite scale are the box shutter, in every method.
    let plain = quad_scene(r#"{ "color": [1, 0, 0, 1] }"#, "[0, 0, 0]", "");
    for w in ["1e308", "5e-324"] {
        let scaled = quad_scene(
            r#"{ "color": [1, 0, 0, 1] }"#,
            "[0, 0, 0]",
            &format!(
                r#""shutter": {{ "open": 0, "close": 1, "response": {{ "piecewise_linear": [[0, {w}], [1, {w}]] }} }},"#
            ),
        );
        for method in ["accum", "analytic", "prism"] {
            assert_eq!(
                rendered(&scaled, method),
                rendered(&plain, method),
                "{w} {method}"
            );
        }
    }
}

#[test]
fn obj_faces_with_fewer_than_three_vertices_name_the_file_and_line() {
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n";
    let scene = format!(
        r#"{{ {CAMERA}, "background": [0, 0, 0],
  "objects": [ {{ "name": "m", "mesh": {{ "file": "m.obj" }} }} ] }}"#
    );
    refused(
        &scene,
        &[("m.obj", obj)],
        &[],
        &["m.obj: line 5: a face needs at least 3 vertices, this one has 2"],
    );
}

#[test]
fn a_missing_output_folder_is_named_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    let out = mblur()
        .current_dir(dir.path())
        .args(["render", "crossing-quads", "-o", "no/such/out.png"])
        .assert()
        .failure()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        stderr.contains("no/such/out.png") && stderr.contains("does not exist"),
        "{stderr}"
    );
    assert!(
        !stderr.contains(".mblur-"),
        "names the temporary file: {stderr}"
    );
    // Checked before the render: nothing about the scene or method was printed.
    assert!(
        !stderr.contains("motion:") && !stderr.contains("wrote"),
        "{stderr}"
    );
    assert!(files(dir.path()).is_empty());
}

/// A quiet 16 x 12 render of crossing-quads to x.pfm, before the flags under test.
const SMALL_RENDER: [&str; 9] = [
    "render",
    "crossing-quads",
    "--width",
    "16",
    "--height",
    "12",
    "-o",
    "x.pfm",
    "-q",
];

#[test]
fn a_flag_of_another_method_is_an_error_naming_flag_and_method() {
    let cases: [(&[&str], &str); 4] = [
        (
            &["-m", "analytic", "--spp", "64"],
            "--spp: is a setting of stochastic and -m analytic was asked for",
        ),
        (
            &["-m", "accum", "--intervals", "4"],
            "--intervals: is a setting of analytic and -m accum was asked for",
        ),
        (
            &["--times", "16"],
            "--times: is a setting of accum and auto picked analytic for this scene",
        ),
        (
            &["-m", "prism", "--subframes", "4"],
            "--subframes: is a setting of ewa and -m prism was asked for",
        ),
    ];
    for (args, needle) in cases {
        let dir = tempfile::tempdir().unwrap();
        let out = mblur()
            .current_dir(dir.path())
            .args(SMALL_RENDER)
            .args(args)
            .assert()
            .failure()
            .code(1);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
        assert!(files(dir.path()).is_empty(), "{args:?}");
    }
    // The same flags are accepted by the methods that use them.
    let dir = tempfile::tempdir().unwrap();
    mblur()
        .current_dir(dir.path())
        .args(SMALL_RENDER)
        .args(["--intervals", "4", "--precision", "f64"])
        .assert()
        .success();
}

/// A transparent grid of `divisions`² cells sweeping across a `side`² frame: every pixel
/// of a row meets hundreds of moving triangles (the exact lists' worst case).
fn sweeping_grid(side: u32, divisions: u32) -> String {
    format!(
        r#"{{ "camera": {{ "width": {side}, "height": {side}, "projection": {{ "perspective": {{ "fov_y_deg": 40 }} }},
    "eye": [0, 0, 5], "target": [0, 0, 0], "near": 0.1, "far": 100 }},
  "objects": [ {{ "name": "grid", "mesh": {{ "grid": {{ "size": [3, 3], "divisions": [{divisions}, {divisions}] }} }},
    "material": {{ "color": [0.2, 0.5, 0.9, 0.5] }},
    "motion": {{ "open": {{ "translate": [-2, 0, 0] }}, "close": {{ "translate": [2, 0, 0] }} }} }} ] }}"#
    )
}

#[test]
fn exact_lists_past_the_memory_budget_fail_early_naming_the_row() {
    // 1024² with 80 000 transparent triangles sweeping across: the exact lists of one row
    // hold ~10^6 intervals; a 1 MiB budget allows ~10^4. The render stops at the first
    // row past its share, long before it would finish (the timeout bounds the time).
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.json"), sweeping_grid(1024, 200)).unwrap();
    let out = mblur()
        .current_dir(dir.path())
        .args([
            "render",
            "scene.json",
            "-o",
            "out.pfm",
            "-q",
            "--threads",
            "1",
        ])
        .args(["--max-memory", "1M"])
        .timeout(std::time::Duration::from_secs(120))
        .assert()
        .failure()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    for needle in [
        "invalid option --max-memory: analytic: row ",
        " alone needs more than ",
        " intervals (1024.0 KiB per thread at ",
        "--intervals K",
    ] {
        assert!(stderr.contains(needle), "`{needle}` not in: {stderr}");
    }
    assert!(files(dir.path()).contains(&"scene.json".to_string()));
    assert!(!files(dir.path()).contains(&"out.pfm".to_string()));
}

#[test]
fn bounded_lists_render_under_a_budget_the_exact_lists_exceed() {
    // The same sweep, smaller: exact lists need more than a 64 KiB budget, K = 4 per pixel
    // holds 4 x width intervals a row whatever is emitted, and renders.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.json"), sweeping_grid(64, 40)).unwrap();
    let run = |extra: &[&str]| {
        mblur()
            .current_dir(dir.path())
            .args([
                "render",
                "scene.json",
                "-o",
                "out.pfm",
                "-q",
                "--threads",
                "1",
            ])
            .args(["--max-memory", "64K"])
            .args(extra)
            .assert()
    };
    run(&[]).failure().code(1);
    run(&["--intervals", "4"]).success();
    let image = mblur_scene::image_io::read_pfm(&dir.path().join("out.pfm")).unwrap();
    assert!(image.pixels.iter().flatten().all(|v| v.is_finite()));
    assert!(
        image.pixels.iter().any(|p| p[2] > 0.1),
        "the grid is not in the image"
    );
}

#[test]
fn splats_larger_than_their_point_set_are_refused_at_load() {
    // A sampled ball whose splat radius (1e6, and 2^32 as a mutated file had it) dwarfs the
    // ball: every splat would cover every pixel the ball does, and the exact A-buffer would
    // resolve that in time quadratic in the splats.
    for radius in ["1e6", "4294967296"] {
        let scene = format!(
            r#"{{ {CAMERA},
  "splats": [ {{ "name": "ball", "radius": {radius},
    "source": {{ "sample": {{ "mesh": {{ "sphere": {{ "radius": 1 }} }}, "count": 5000 }} }},
    "motion": {{ "open": {{ "translate": [-0.5, 0, 0] }}, "close": {{ "translate": [0.5, 0, 0] }} }} }} ] }}"#
        );
        refused(
            &scene,
            &[],
            &[],
            &[
                "scene.json: splats[0] \"ball\".radius: ",
                "is larger than the whole point set",
            ],
        );
    }
}

#[test]
fn thread_counts_beyond_four_per_core_are_refused() {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    for threads in [0, 4 * cores + 1, 100_000] {
        let dir = tempfile::tempdir().unwrap();
        let out = mblur()
            .current_dir(dir.path())
            .args(["render", "static", "-o", "x.pfm", "-q", "--threads"])
            .arg(threads.to_string())
            .assert()
            .failure()
            .code(1);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        assert!(
            stderr.contains("invalid option --threads: must be between 1 and"),
            "{stderr}"
        );
        assert!(files(dir.path()).is_empty());
    }
}
