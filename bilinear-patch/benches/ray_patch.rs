//! Ray vs one bilinear patch against ray vs the two triangles that split it (Möller-Trumbore
//! and the watertight test), side by side, f32 and f64. Before timing it prints the accuracy
//! of each against the f64 patch test: the f32 patch's parameter error, and how far the
//! two-triangle split is from the curved patch.

use bilinear_patch::{Patch, Triangle, moller_trumbore};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use std::hint::black_box;

const N: usize = 1024;

struct Case {
    corners: [[f64; 3]; 4],
    origin: [f64; 3],
    dir: [f64; 3],
}

fn cases() -> Vec<Case> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(4);
    let mut r = |lo: f64, hi: f64| rng.random_range(lo..hi);
    (0..N)
        .map(|_| {
            // A non-planar patch roughly in the unit square, a ray from above aimed at a
            // point of the square grown by 20% (so some rays miss).
            let mut corners = [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ];
            for c in &mut corners {
                c[0] += r(-0.2, 0.2);
                c[1] += r(-0.2, 0.2);
                c[2] += r(-0.5, 0.5);
            }
            let target = [r(-0.2, 1.2), r(-0.2, 1.2), r(-0.3, 0.3)];
            let origin = [r(-1.0, 2.0), r(-1.0, 2.0), r(2.0, 4.0)];
            let dir = [
                target[0] - origin[0],
                target[1] - origin[1],
                target[2] - origin[2],
            ];
            Case {
                corners,
                origin,
                dir,
            }
        })
        .collect()
}

fn split(c: &[[f64; 3]; 4]) -> [[[f64; 3]; 3]; 2] {
    [[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
}

fn f32s<const K: usize>(p: [[f64; 3]; K]) -> [[f32; 3]; K] {
    p.map(|q| q.map(|x| x as f32))
}

fn report(cases: &[Case]) {
    let (mut uv32, mut t32, mut count32) = (0.0f64, 0.0f64, 0usize);
    let (mut split_miss, mut split_dt, mut split_n, mut patch_hits) =
        (0usize, 0.0f64, 0usize, 0usize);
    for c in cases {
        let exact = Patch::new(c.corners).intersect(c.origin, c.dir, 0.0, f64::INFINITY);
        patch_hits += usize::from(!exact.is_empty());
        let h32 = Patch::new(f32s(c.corners)).intersect(
            c.origin.map(|x| x as f32),
            c.dir.map(|x| x as f32),
            0.0,
            f32::INFINITY,
        );
        if h32.len() != exact.len() {
            count32 += 1;
        } else {
            for (a, b) in h32.iter().zip(exact.iter()) {
                uv32 = uv32
                    .max((a.u as f64 - b.u).abs())
                    .max((a.v as f64 - b.v).abs());
                t32 = t32.max((a.t as f64 - b.t).abs() / b.t.abs().max(1e-300));
            }
        }
        // Nearest hit of the two-triangle split vs the nearest patch hit.
        let tri = split(&c.corners)
            .iter()
            .filter_map(|t| moller_trumbore(t, c.origin, c.dir, 0.0, f64::INFINITY))
            .map(|h| h.t)
            .fold(f64::INFINITY, f64::min);
        match (exact.first(), tri.is_finite()) {
            (Some(h), true) => {
                split_dt = split_dt.max((tri - h.t).abs() / h.t);
                split_n += 1;
            }
            (None, false) => {}
            _ => split_miss += 1,
        }
    }
    eprintln!(
        "ray vs patch accuracy on {N} rays ({patch_hits} hit the patch), reference: f64 patch test"
    );
    eprintln!(
        "  f32 patch: max |du|,|dv| = {uv32:.2e}, max rel dt = {t32:.2e}, hit-count mismatches = {count32}"
    );
    eprintln!(
        "  two-triangle split (f64): hit/miss disagrees on {split_miss} rays ({:.1}%), max rel dt of nearest hit = {split_dt:.2e} over {split_n} rays",
        100.0 * split_miss as f64 / N as f64
    );
}

fn bench(c: &mut Criterion) {
    let cases = cases();
    report(&cases);
    let mut g = c.benchmark_group("ray_vs_patch");
    g.throughput(Throughput::Elements(N as u64));

    let p64: Vec<Patch<f64>> = cases.iter().map(|c| Patch::new(c.corners)).collect();
    let t64: Vec<[[[f64; 3]; 3]; 2]> = cases.iter().map(|c| split(&c.corners)).collect();
    let w64: Vec<[Triangle<f64>; 2]> = t64.iter().map(|t| t.map(Triangle::new)).collect();
    let rays64: Vec<([f64; 3], [f64; 3])> = cases.iter().map(|c| (c.origin, c.dir)).collect();
    let p32: Vec<Patch<f32>> = cases.iter().map(|c| Patch::new(f32s(c.corners))).collect();
    let t32: Vec<[[[f32; 3]; 3]; 2]> = t64.iter().map(|t| t.map(f32s)).collect();
    let w32: Vec<[Triangle<f32>; 2]> = t32.iter().map(|t| t.map(Triangle::new)).collect();
    let rays32: Vec<([f32; 3], [f32; 3])> = rays64
        .iter()
        .map(|(o, d)| (o.map(|x| x as f32), d.map(|x| x as f32)))
        .collect();

    g.bench_function("f32/patch", |b| {
        b.iter(|| {
            let mut n = 0;
            for (p, (o, d)) in p32.iter().zip(&rays32) {
                n += black_box(p.intersect(*o, *d, 0.0, f32::INFINITY)).len();
            }
            n
        })
    });
    g.bench_function("f32/two_moller_trumbore", |b| {
        b.iter(|| {
            let mut n = 0;
            for (t, (o, d)) in t32.iter().zip(&rays32) {
                for tri in t {
                    n += usize::from(
                        black_box(moller_trumbore(tri, *o, *d, 0.0, f32::INFINITY)).is_some(),
                    );
                }
            }
            n
        })
    });
    g.bench_function("f32/two_watertight", |b| {
        b.iter(|| {
            let mut n = 0;
            for (t, (o, d)) in w32.iter().zip(&rays32) {
                for tri in t {
                    n +=
                        usize::from(black_box(tri.intersect(*o, *d, 0.0, f32::INFINITY)).is_some());
                }
            }
            n
        })
    });
    g.bench_function("f64/patch", |b| {
        b.iter(|| {
            let mut n = 0;
            for (p, (o, d)) in p64.iter().zip(&rays64) {
                n += black_box(p.intersect(*o, *d, 0.0, f64::INFINITY)).len();
            }
            n
        })
    });
    g.bench_function("f64/two_moller_trumbore", |b| {
        b.iter(|| {
            let mut n = 0;
            for (t, (o, d)) in t64.iter().zip(&rays64) {
                for tri in t {
                    n += usize::from(
                        black_box(moller_trumbore(tri, *o, *d, 0.0, f64::INFINITY)).is_some(),
                    );
                }
            }
            n
        })
    });
    g.bench_function("f64/two_watertight", |b| {
        b.iter(|| {
            let mut n = 0;
            for (t, (o, d)) in w64.iter().zip(&rays64) {
                for tri in t {
                    n +=
                        usize::from(black_box(tri.intersect(*o, *d, 0.0, f64::INFINITY)).is_some());
                }
            }
            n
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
