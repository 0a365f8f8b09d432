//! Prism coverage per pixel (Rønnow 2021, this crate) against edge-eqn coverage per pixel
//! (Gribel 2010), side by side on the same random moving triangles with constant w = 1,
//! f32 and f64. Before timing it prints their disagreement in time (measure of the symmetric
//! difference of the covered sets) and each one's error against dense time sampling.

use bilinear_patch::Prism;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use edge_eqn::{MovingTriangle, TriangleSetup};
use rand::{RngExt, SeedableRng};
use std::hint::black_box;

#[path = "../tests/common/mod.rs"]
mod common;
use common::{disagreement, sampled_spans};

const TRIANGLES: usize = 256;
const PIXELS_PER_TRIANGLE: usize = 8;

struct Case {
    q: [[f64; 3]; 3],
    r: [[f64; 3]; 3],
    pixels: Vec<(f64, f64)>,
}

fn cases() -> Vec<Case> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(41);
    (0..TRIANGLES)
        .map(|_| {
            let mut q = [[0.0, 0.0, 1.0]; 3];
            let mut r = [[0.0, 0.0, 1.0]; 3];
            let shift = [rng.random_range(-12.0..12.0), rng.random_range(-12.0..12.0)];
            for k in 0..3 {
                q[k][0] = rng.random_range(8.0..24.0);
                q[k][1] = rng.random_range(8.0..24.0);
                r[k][0] = q[k][0] + shift[0] + rng.random_range(-3.0..3.0);
                r[k][1] = q[k][1] + shift[1] + rng.random_range(-3.0..3.0);
            }
            let lo = |i: usize| {
                q.iter()
                    .chain(&r)
                    .map(|p| p[i])
                    .fold(f64::INFINITY, f64::min)
            };
            let hi = |i: usize| {
                q.iter()
                    .chain(&r)
                    .map(|p| p[i])
                    .fold(f64::NEG_INFINITY, f64::max)
            };
            let pixels = (0..PIXELS_PER_TRIANGLE)
                .map(|_| {
                    let x = rng.random_range(lo(0)..hi(0)).floor() + 0.5;
                    let y = rng.random_range(lo(1)..hi(1)).floor() + 0.5;
                    (x, y)
                })
                .collect();
            Case { q, r, pixels }
        })
        .collect()
}

fn report(cases: &[Case]) {
    let mut stats: Vec<(&str, f64, f64)> = Vec::new();
    let mut add = |name, vals: Vec<f64>| {
        let mean = vals.iter().sum::<f64>() / vals.len() as f64;
        let max = vals.iter().copied().fold(0.0, f64::max);
        stats.push((name, mean, max));
    };
    let (mut p64e64, mut p32e64, mut e32e64, mut p64s, mut e64s) =
        (vec![], vec![], vec![], vec![], vec![]);
    let n = 4096;
    for c in cases {
        let prism64 = Prism::from_homogeneous(c.q, c.r).expect("w = 1");
        let prism32 = Prism::from_homogeneous(f32s(c.q), f32s(c.r)).expect("w = 1");
        let edge64 = MovingTriangle::new(c.q, c.r).setup();
        let edge32 = MovingTriangle::new(f32s(c.q), f32s(c.r)).setup();
        for &(px, py) in &c.pixels {
            let a: Vec<[f64; 2]> = prism64
                .coverage(px, py)
                .iter()
                .map(|s| [s.t0, s.t1])
                .collect();
            let b: Vec<[f64; 2]> = edge64
                .sample(px, py)
                .coverage()
                .iter()
                .map(|s| [s.t0, s.t1])
                .collect();
            let a32: Vec<[f64; 2]> = prism32
                .coverage(px as f32, py as f32)
                .iter()
                .map(|s| [s.t0 as f64, s.t1 as f64])
                .collect();
            let b32: Vec<[f64; 2]> = edge32
                .sample(px as f32, py as f32)
                .coverage()
                .iter()
                .map(|s| [s.t0 as f64, s.t1 as f64])
                .collect();
            let xy = |p: [[f64; 3]; 3]| p.map(|v| [v[0], v[1]]);
            let s = sampled_spans(xy(c.q), xy(c.r), px, py, n);
            p64e64.push(disagreement(&a, &b));
            p32e64.push(disagreement(&a32, &b));
            e32e64.push(disagreement(&b32, &b));
            p64s.push(disagreement(&a, &s));
            e64s.push(disagreement(&b, &s));
        }
    }
    add("prism f64 vs edge-eqn f64", p64e64);
    add("prism f32 vs edge-eqn f64", p32e64);
    add("edge-eqn f32 vs edge-eqn f64", e32e64);
    add("prism f64 vs dense sampling (4096)", p64s);
    add("edge-eqn f64 vs dense sampling (4096)", e64s);
    eprintln!(
        "coverage disagreement in time over {} pixel queries (w = 1), measure of symmetric difference:",
        TRIANGLES * PIXELS_PER_TRIANGLE
    );
    for (name, mean, max) in stats {
        eprintln!("  {name:<40} mean {mean:.2e}  max {max:.2e}");
    }
}

fn f32s(p: [[f64; 3]; 3]) -> [[f32; 3]; 3] {
    p.map(|q| q.map(|x| x as f32))
}

fn bench(c: &mut Criterion) {
    let cases = cases();
    report(&cases);
    let mut g = c.benchmark_group("coverage_per_pixel");
    g.throughput(Throughput::Elements(
        (TRIANGLES * PIXELS_PER_TRIANGLE) as u64,
    ));

    let prisms64: Vec<Prism<f64>> = cases
        .iter()
        .map(|c| Prism::from_homogeneous(c.q, c.r).expect("w = 1"))
        .collect();
    let edges64: Vec<TriangleSetup<f64>> = cases
        .iter()
        .map(|c| MovingTriangle::new(c.q, c.r).setup())
        .collect();
    let prisms32: Vec<Prism<f32>> = cases
        .iter()
        .map(|c| Prism::from_homogeneous(f32s(c.q), f32s(c.r)).expect("w = 1"))
        .collect();
    let edges32: Vec<TriangleSetup<f32>> = cases
        .iter()
        .map(|c| MovingTriangle::new(f32s(c.q), f32s(c.r)).setup())
        .collect();
    let px64: Vec<&[(f64, f64)]> = cases.iter().map(|c| c.pixels.as_slice()).collect();
    let px32: Vec<Vec<(f32, f32)>> = cases
        .iter()
        .map(|c| {
            c.pixels
                .iter()
                .map(|&(x, y)| (x as f32, y as f32))
                .collect()
        })
        .collect();

    g.bench_function("f32/prism", |b| {
        b.iter(|| {
            let mut n = 0;
            for (p, pix) in prisms32.iter().zip(&px32) {
                for &(x, y) in pix {
                    n += black_box(p.coverage(x, y)).len();
                }
            }
            n
        })
    });
    g.bench_function("f32/edge_eqn", |b| {
        b.iter(|| {
            let mut n = 0;
            for (e, pix) in edges32.iter().zip(&px32) {
                for &(x, y) in pix {
                    n += black_box(e.sample(x, y).coverage()).len();
                }
            }
            n
        })
    });
    g.bench_function("f64/prism", |b| {
        b.iter(|| {
            let mut n = 0;
            for (p, pix) in prisms64.iter().zip(&px64) {
                for &(x, y) in pix.iter() {
                    n += black_box(p.coverage(x, y)).len();
                }
            }
            n
        })
    });
    g.bench_function("f64/edge_eqn", |b| {
        b.iter(|| {
            let mut n = 0;
            for (e, pix) in edges64.iter().zip(&px64) {
                for &(x, y) in pix.iter() {
                    n += black_box(e.sample(x, y).coverage()).len();
                }
            }
            n
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
