//! Issue 11's renderer-level goal that is a ratio measured side by side: a static scene through
//! `auto` (analysis, pipeline choice, then the static path) against the static path alone
//! (`accum::render_static`, one watertight raster pass). Prints the ratio of medians and the
//! largest pixel difference between the two images once, before timing.

use std::hint::black_box;
use std::time::Instant;

use criterion::{Criterion, criterion_group, criterion_main};
use mblur::{Method, MethodOptions, NoProgress, PreparedScene, accum};
use mblur_scene::Scene;

fn scene(name: &str) -> PreparedScene {
    Scene::builtin(name)
        .expect("built-in scene")
        .prepare()
        .expect("prepare")
}

fn auto(p: &PreparedScene) -> mblur::Rendered {
    // At the pixel centre: the goal is the static path's cost for one sample position.
    let options =
        MethodOptions::defaults(Method::Auto).with_antialiasing(mblur::aa::Antialiasing::default());
    mblur::render(p, &options, &NoProgress).expect("render")
}

fn median_seconds(mut f: impl FnMut(), n: usize) -> f64 {
    let mut times: Vec<f64> = (0..n)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[n / 2]
}

fn bench(c: &mut Criterion) {
    let p = scene("static");
    let a = auto(&p);
    let s = accum::render_static(&p, 0.0);
    let max_diff = a
        .image
        .pixels
        .iter()
        .zip(&s.pixels)
        .flat_map(|(x, y)| (0..3).map(move |k| (x[k] - y[k]).abs()))
        .fold(0.0f32, f32::max);
    // Interleaved medians so both see the same machine load.
    let (mut ta, mut ts) = (Vec::new(), Vec::new());
    for _ in 0..15 {
        ta.push(median_seconds(|| drop(black_box(auto(black_box(&p)))), 1));
        ts.push(median_seconds(
            || drop(black_box(accum::render_static(black_box(&p), 0.0))),
            1,
        ));
    }
    ta.sort_by(f64::total_cmp);
    ts.sort_by(f64::total_cmp);
    eprintln!(
        "goal static: {}x{} auto ({}) {:.2} ms, static path {:.2} ms, ratio {:.3} (goal <= 1.1); max |auto - static| = {max_diff:e}",
        p.width,
        p.height,
        a.method,
        ta[7] * 1e3,
        ts[7] * 1e3,
        ta[7] / ts[7]
    );
    let mut group = c.benchmark_group("goal/static");
    group.bench_function("auto", |b| b.iter(|| black_box(auto(black_box(&p)))));
    group.bench_function("static_path", |b| {
        b.iter(|| black_box(accum::render_static(black_box(&p), 0.0)))
    });
    group.finish();
}

// No criterion plots: mblur enables plotters' `ab_glyph` text backend (for `mblur compare`),
// under which criterion's plots find no registered font and panic.
criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = bench
}
criterion_main!(benches);
