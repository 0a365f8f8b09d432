//! The accumulation method's accuracy knob: sub-frame count N. Prints the RMS error against
//! a 1024-sub-frame reference for each N once, then times each N.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use mblur::accum::{self, AccumOptions};
use mblur::{Image, NoProgress, PreparedScene};
use mblur_scene::Scene;

fn scene(name: &str, w: u32, h: u32) -> PreparedScene {
    let mut s = Scene::builtin(name).expect("built-in scene");
    s.set_size(Some(w), Some(h)).expect("size");
    s.prepare().expect("prepare")
}

fn render(p: &PreparedScene, n: u32, jitter: Option<u64>) -> Image {
    accum::render(
        p,
        &AccumOptions {
            times: Some(n),
            jitter,
            ..Default::default()
        },
        &NoProgress,
    )
    .expect("render")
}

fn rms(a: &Image, b: &Image) -> f64 {
    let sum: f64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(p, q)| (0..3).map(move |k| f64::from(p[k] - q[k]).powi(2)))
        .sum();
    (sum / (3 * a.pixels.len()) as f64).sqrt()
}

fn bench(c: &mut Criterion) {
    for (name, w, h) in [
        ("crossing-quads", 96, 72),
        ("transparent-cubes", 96, 54),
        ("static", 160, 90),
    ] {
        let p = scene(name, w, h);
        let reference = render(&p, 1024, None);
        let mut group = c.benchmark_group(format!("accum/{name}"));
        for n in [1u32, 4, 16, 64] {
            let even = rms(&render(&p, n, None), &reference);
            let jit = rms(&render(&p, n, Some(1)), &reference);
            eprintln!(
                "accum {name} {w}x{h} N={n:>3}: RMS vs N=1024 even {even:.5}, jittered {jit:.5}"
            );
            group.bench_function(format!("N={n}"), |b| {
                b.iter(|| black_box(render(black_box(&p), n, None)))
            });
        }
        group.finish();
    }
}

// No criterion plots: mblur enables plotters' `ab_glyph` text backend (for `mblur compare`),
// under which criterion's plots find no registered font and panic.
criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = bench
}
criterion_main!(benches);
