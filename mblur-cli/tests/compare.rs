//! The `mblur compare` command: its files, its options and its errors.

mod common;

use common::{files, mblur};
use integration_tests::csv_rows;
use mblur::TraversalChoice;
use mblur_lab::compare::{self, CompareOptions, LadderSize};

#[test]
fn tiny_compare_run_writes_every_file_with_one_row_per_entry() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cmp");
    mblur()
        .args([
            "compare",
            "billiards",
            "--width",
            "48",
            "--height",
            "27",
            "--quick",
        ])
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let options = CompareOptions {
        ladder: LadderSize::Small,
        traversals: vec![TraversalChoice::Fallback],
        ..Default::default()
    };
    // billiards' balls spin and are lit: the segments ladder, then the shading ladder,
    // follow the analytic settings.
    let mut ladder = compare::ladder(&options);
    let prepared = integration_tests::builtin("billiards", 48, 27);
    let segments = compare::segments_ladder(&prepared, &options);
    assert_eq!(segments.len(), compare::SEGMENTS_LADDER.len() + 1);
    let at = ladder
        .iter()
        .position(|e| e.options.method() != mblur::Method::Analytic)
        .unwrap_or(ladder.len());
    let shading = compare::shading_ladder(&prepared, &options);
    assert_eq!(shading.len(), 4);
    ladder.splice(at..at, segments.into_iter().chain(shading));
    let rows = csv_rows(&out);
    // A method that refuses the scene is run and listed once.
    let refused: Vec<&str> = rows
        .iter()
        .filter(|r| r[4] == "skipped")
        .map(|r| r[3].as_str())
        .collect();
    let mut seen = Vec::new();
    let expected: Vec<_> = ladder
        .iter()
        .filter(|e| {
            let m = e.options.method().name();
            let first = !seen.contains(&m);
            seen.push(m);
            first || !refused.contains(&m)
        })
        .collect();
    assert_eq!(rows.len(), expected.len());
    let mut rmse = std::collections::HashMap::new();
    for (row, entry) in rows.iter().zip(expected) {
        assert_eq!(row.len(), 14, "{row:?}");
        assert_eq!((&row[1], &row[2]), (&entry.series, &entry.setting));
        match row[4].as_str() {
            "ok" => {
                for k in [5, 8, 9, 10, 11] {
                    let v: f64 = row[k].parse().unwrap();
                    assert!(v.is_finite() && v >= 0.0, "{row:?}");
                }
                // The binary meters the heap: a measured byte count.
                let heap: u64 = row[7].parse().unwrap();
                assert!(heap >= 48 * 27 * 12, "{row:?}");
                let ssim: f64 = row[11].parse().unwrap();
                assert!(ssim <= 1.0 + 1e-12);
                let img = image::open(out.join(&row[12])).unwrap();
                assert_eq!((img.width(), img.height()), (96, 27));
                rmse.insert(
                    format!("{} {}", row[1], row[2]),
                    row[9].parse::<f64>().unwrap(),
                );
            }
            "skipped" => {
                assert!(row[13].contains("cannot render this scene"), "{row:?}");
                assert!(row[5].is_empty() && row[12].is_empty());
            }
            other => panic!("unexpected status {other}: {row:?}"),
        }
    }
    // ewa refuses a triangle scene: skipped with its reason, not a failure.
    assert!(
        rows.iter()
            .any(|r| r[1] == "ewa" && r[4] == "skipped" && r[13].contains("splat-only"))
    );
    let exact = rmse["analytic unbounded"];
    let accum4 = rmse["accum 4 times"];
    assert!(
        exact < accum4,
        "analytic unbounded {exact} vs accum 4 {accum4}"
    );
    let md = std::fs::read_to_string(out.join("results.md")).unwrap();
    let (table, pareto) = md
        .split_once("\n## Pareto check\n")
        .expect("a Pareto section");
    assert_eq!(
        table.lines().filter(|l| l.starts_with("| ")).count(),
        rows.len() + 1
    );
    pareto_section_agrees_with_the_csv(&rows, pareto);
    assert!(md.contains(&format!("{} of {} runs done", rows.len(), rows.len())));
    let svg = std::fs::read_to_string(out.join("plot.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("analytic") && svg.contains("accum"));
    let plot = image::open(out.join("plot.png")).unwrap();
    assert_eq!((plot.width(), plot.height()), mblur_lab::plot::PLOT_SIZE);
    let reference = image::open(out.join("reference.png")).unwrap();
    assert_eq!((reference.width(), reference.height()), (48, 27));
}

/// Checks the Pareto section of results.md against the definition applied to the CSV rows
/// (full precision): an accum or stochastic run at >= 40 dB is dominated when some analytic
/// run has at least its PSNR and at most its time.
fn pareto_section_agrees_with_the_csv(rows: &[Vec<String>], section: &str) {
    let ok = |method: &str| -> Vec<(String, f64, f64)> {
        rows.iter()
            .filter(|r| r[3] == method && r[4] == "ok")
            .map(|r| {
                let label = format!("{} {}", r[1], r[2]);
                (label, r[5].parse().unwrap(), r[8].parse().unwrap())
            })
            .collect()
    };
    let analytic = ok("analytic");
    let checked: Vec<_> = ok("accum")
        .into_iter()
        .chain(ok("stochastic"))
        .filter(|(_, _, psnr)| *psnr >= 40.0)
        .collect();
    let mut yes = 0;
    for (label, ms, psnr) in &checked {
        let dominated = analytic
            .iter()
            .any(|(_, a_ms, a_psnr)| a_psnr >= psnr && a_ms <= ms);
        yes += usize::from(dominated);
        let row = section
            .lines()
            .find(|l| l.starts_with(&format!("| {label} |")))
            .unwrap_or_else(|| panic!("{label} missing from the Pareto section:\n{section}"));
        let verdict = if dominated { "| yes |" } else { "| no |" };
        assert!(row.contains(verdict), "{row}");
    }
    assert!(
        section.contains(&format!("{yes} of {} yes", checked.len())),
        "{section}"
    );
}

#[test]
fn unknown_scene_fails_clearly() {
    let dir = tempfile::tempdir().unwrap();
    let out = mblur()
        .current_dir(dir.path())
        .args(["compare", "no-such-scene", "--quick"])
        .assert()
        .failure()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        stderr.contains("unknown built-in scene `no-such-scene`"),
        "{stderr}"
    );
    assert!(files(dir.path()).is_empty());
}

#[test]
fn unwritable_out_fails_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("a-file");
    std::fs::write(&file, "x").unwrap();
    let out = mblur()
        .args(["compare", "billiards", "--quick", "--out"])
        .arg(file.join("sub"))
        .assert()
        .failure()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        stderr.starts_with("error: cannot write") && stderr.contains("a-file/sub"),
        "{stderr}"
    );
}

#[test]
fn bad_options_fail_clearly() {
    for (args, needle) in [
        (
            vec!["--traversals", "diagonal"],
            "unknown traversal `diagonal`",
        ),
        (vec!["--reference-times", "0"], "--reference-times"),
        (vec!["--diff-scale", "0"], "--diff-scale"),
        (vec!["--threads", "0"], "--threads"),
        (vec!["--spp", "3"], "--spp: must be a power of two"),
        (vec!["--spp", "4,2048"], "got 2048"),
        (vec!["--pareto-floor", "nan"], "--pareto-floor"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let out = mblur()
            .args([
                "compare", "static", "--quick", "--width", "16", "--height", "9", "--out",
            ])
            .arg(dir.path().join("o"))
            .args(&args)
            .assert()
            .failure();
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
    }
}

#[test]
fn an_external_reference_replaces_the_rendered_one() {
    // The reference is a file: the analytic render itself, written as PFM. Measured against
    // it, the unbounded analytic run has RMSE 0 (a rendered accum reference would not), and
    // a file of another size is refused before any run.
    let dir = tempfile::tempdir().unwrap();
    let size = ["--width", "48", "--height", "27"];
    mblur()
        .current_dir(dir.path())
        .args([
            "render",
            "billiards",
            "-m",
            "analytic",
            "-q",
            "-o",
            "ref.pfm",
        ])
        .args(size)
        .assert()
        .success();
    mblur()
        .current_dir(dir.path())
        .args([
            "compare",
            "billiards",
            "--quick",
            "--methods",
            "analytic",
            "-q",
        ])
        .args(["--reference", "ref.pfm", "--out", "cmp"])
        .args(size)
        .assert()
        .success();
    let rows = csv_rows(&dir.path().join("cmp"));
    let exact = rows
        .iter()
        .find(|r| r[1] == "analytic" && r[2] == "unbounded")
        .unwrap();
    assert_eq!(exact[9].parse::<f64>().unwrap(), 0.0, "{exact:?}");
    let out = mblur()
        .current_dir(dir.path())
        .args([
            "compare",
            "billiards",
            "--quick",
            "--methods",
            "analytic",
            "-q",
        ])
        .args(["--reference", "ref.pfm", "--out", "cmp2"])
        .args(["--width", "40", "--height", "27"])
        .assert()
        .failure()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        stderr.contains(
            "invalid option --reference: ref.pfm is 48 x 27, the scene renders at 40 x 27"
        ),
        "{stderr}"
    );
}

#[test]
fn compare_aa_measures_every_run_at_the_same_positions() {
    // With --aa 4 the reference and the runs sample the same four positions: unbounded
    // analytic stays as close to accum as at the pixel centre (what remains is the
    // segments' chord error on the rolling balls). A reference with 64 positions adds the
    // runs' spatial error.
    let dir = tempfile::tempdir().unwrap();
    let run = |extra: &[&str], out: &str| {
        mblur()
            .current_dir(dir.path())
            .args([
                "compare",
                "billiards",
                "--quick",
                "--methods",
                "analytic",
                "-q",
            ])
            .args([
                "--width",
                "32",
                "--height",
                "18",
                "--reference-times",
                "128",
            ])
            .args(["--out", out])
            .args(extra)
            .assert()
    };
    let exact_rmse = |out: &str| -> f64 {
        let rows = csv_rows(&dir.path().join(out));
        let row = rows
            .iter()
            .find(|r| r[1] == "analytic" && r[2] == "unbounded")
            .unwrap();
        row[9].parse().unwrap()
    };
    run(&[], "centre").success();
    run(&["--aa", "4"], "same").success();
    run(&["--aa", "4", "--reference-aa", "64"], "finer").success();
    let (centre, same, finer) = (
        exact_rmse("centre"),
        exact_rmse("same"),
        exact_rmse("finer"),
    );
    eprintln!(
        "analytic unbounded RMSE: centre {centre:.3e}, --aa 4 {same:.3e}, against 64 positions {finer:.3e}"
    );
    assert!(same < 1.5 * centre, "{same} vs {centre}");
    assert!(finer > 3.0 * same, "{finer} vs {same}");
    let out = run(&["--aa", "3"], "bad").failure().code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        stderr.contains("invalid option --aa: must be a power of two from 1 to 1024, got 3"),
        "{stderr}"
    );
}
