//! Ray vs one bilinear patch against ray vs the two triangles that split it (Möller-Trumbore
//! and the watertight test), side by side, f32 and f64, in two settings: `raw` (each call
//! pays its own set-up) and `prepared` (rays and primitives set up outside the timed loop,
//! as in a BVH traversal). The patch is tested watertight (`Patch`, `PreparedPatch`) and
//! non-watertight (`FastPatch`: `intersect`, Reshetov's world-space algorithm, and
//! `intersect_ray`, the same quadratic in the space of a prepared `Ray`; the like-for-like
//! counterparts of Möller-Trumbore). Before timing it prints the accuracy of each against
//! the f64 patch test: the f32 patch's and the fast patches' parameter error, whether the
//! prepared patch reproduces the patch bit for bit, and how far the two-triangle split is
//! from the curved patch.
//!
//! Every result is passed to `black_box` by reference, so it is kept in memory where it was
//! built (as a caller reading the hits in place would); passing it by value made the
//! compiler copy it through the stack with loads wider than the stores that built it, a
//! store-forwarding stall of the harness, not of the test.

use bilinear_patch::{
    FastPatch, Hit, MollerTrumbore, Patch, PreparedPatch, Ray, Triangle, moller_trumbore,
};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use num_traits::Float;
use std::hint::black_box;

#[path = "../tests/common/mod.rs"]
mod common;

use common::RayCase as Case;
use common::split;

const N: usize = 1024;

fn f32s<const K: usize>(p: [[f64; 3]; K]) -> [[f32; 3]; K] {
    p.map(|q| q.map(|x| x as f32))
}

/// Error of a hit list (f32 or f64) against the f64 reference: (max |du|, |dv|; max
/// relative dt; hit-count mismatch).
fn f32_error<F: Into<f64> + Copy>(h32: &[Hit<F>], exact: &[Hit<f64>]) -> (f64, f64, bool) {
    if h32.len() != exact.len() {
        return (0.0, 0.0, true);
    }
    let (mut uv, mut t) = (0.0f64, 0.0f64);
    for (a, b) in h32.iter().zip(exact.iter()) {
        let (at, au, av): (f64, f64, f64) = (a.t.into(), a.u.into(), a.v.into());
        uv = uv.max((au - b.u).abs()).max((av - b.v).abs());
        t = t.max((at - b.t).abs() / b.t.abs().max(1e-300));
    }
    (uv, t, false)
}

/// Relative t error of the nearest hit of the two-triangle split against the nearest hit
/// of the f64 patch, and whether hit/miss disagrees.
fn split_error(exact: &[Hit<f64>], tri_t: f64) -> (Option<f64>, bool) {
    match (exact.first(), tri_t.is_finite()) {
        (Some(h), true) => (Some((tri_t - h.t).abs() / h.t), false),
        (None, false) => (None, false),
        _ => (None, true),
    }
}

fn report(cases: &[Case]) {
    let (mut uv32, mut t32, mut count32) = (0.0f64, 0.0f64, 0usize);
    let (mut puv32, mut pt32, mut pcount32) = (0.0f64, 0.0f64, 0usize);
    let (mut same32, mut same64) = (0usize, 0usize);
    // FastPatch f64 and f32, world space (`intersect`) and ray space (`intersect_ray`),
    // against the f64 watertight patch: (max |du|,|dv|, max rel dt, hit-count mismatches).
    let mut fast_err = [(0.0f64, 0.0f64, 0usize); 4];
    let mut patch_hits = 0usize;
    // [f64 MT, f32 MT, f64 watertight, f32 watertight]: (max rel dt, hit/miss mismatches).
    let mut split_err = [(0.0f64, 0usize); 4];
    for c in cases {
        let exact = Patch::new(c.corners).intersect(c.origin, c.dir, 0.0, f64::INFINITY);
        patch_hits += usize::from(!exact.is_empty());
        let prepared64 =
            PreparedPatch::new(c.corners).intersect(c.origin, c.dir, 0.0, f64::INFINITY);
        same64 += usize::from(prepared64 == exact);
        let (o32, d32) = (c.origin.map(|x| x as f32), c.dir.map(|x| x as f32));
        let h32 = Patch::new(f32s(c.corners)).intersect(o32, d32, 0.0, f32::INFINITY);
        let p32 = PreparedPatch::new(f32s(c.corners)).intersect(o32, d32, 0.0, f32::INFINITY);
        same32 += usize::from(p32 == h32);
        let (uv, t, bad) = f32_error(&h32, &exact);
        (uv32, t32, count32) = (uv32.max(uv), t32.max(t), count32 + usize::from(bad));
        let (uv, t, bad) = f32_error(&p32, &exact);
        (puv32, pt32, pcount32) = (puv32.max(uv), pt32.max(t), pcount32 + usize::from(bad));
        let fast64 = FastPatch::new(c.corners).intersect_world(c.origin, c.dir, 0.0, f64::INFINITY);
        let fast32 = FastPatch::new(f32s(c.corners)).intersect_world(o32, d32, 0.0, f32::INFINITY);
        let ray64 = Ray::new(c.origin, c.dir).expect("finite ray");
        let ray32 = Ray::new(o32, d32).expect("finite ray");
        let fast_ray64 = FastPatch::new(c.corners).intersect_ray(&ray64, 0.0, f64::INFINITY);
        let fast_ray32 = FastPatch::new(f32s(c.corners)).intersect_ray(&ray32, 0.0, f32::INFINITY);
        for (e, (uv, t, bad)) in fast_err.iter_mut().zip([
            f32_error(&fast64, &exact),
            f32_error(&fast32, &exact),
            f32_error(&fast_ray64, &exact),
            f32_error(&fast_ray32, &exact),
        ]) {
            *e = (e.0.max(uv), e.1.max(t), e.2 + usize::from(bad));
        }
        // Nearest hit of the two-triangle split vs the nearest patch hit.
        let tris = split(&c.corners);
        let nearest = |hits: &mut dyn Iterator<Item = f64>| hits.fold(f64::INFINITY, f64::min);
        let ts = [
            nearest(&mut tris.iter().filter_map(|t| {
                moller_trumbore(t, c.origin, c.dir, 0.0, f64::INFINITY).map(|h| h.t)
            })),
            nearest(&mut tris.iter().filter_map(|t| {
                moller_trumbore(&f32s(*t), o32, d32, 0.0, f32::INFINITY).map(|h| h.t as f64)
            })),
            nearest(&mut tris.iter().filter_map(|t| {
                Triangle::new(*t)
                    .intersect(c.origin, c.dir, 0.0, f64::INFINITY)
                    .map(|h| h.t)
            })),
            nearest(&mut tris.iter().filter_map(|t| {
                Triangle::new(f32s(*t))
                    .intersect(o32, d32, 0.0, f32::INFINITY)
                    .map(|h| h.t as f64)
            })),
        ];
        for (s, t) in split_err.iter_mut().zip(ts) {
            let (dt, miss) = split_error(&exact, t);
            s.0 = s.0.max(dt.unwrap_or(0.0));
            s.1 += usize::from(miss);
        }
    }
    eprintln!(
        "ray vs patch accuracy on {N} rays ({patch_hits} hit the patch), reference: f64 patch test"
    );
    eprintln!(
        "  f32 patch:          max |du|,|dv| = {uv32:.2e}, max rel dt = {t32:.2e}, hit-count mismatches = {count32}"
    );
    eprintln!(
        "  f32 prepared patch: max |du|,|dv| = {puv32:.2e}, max rel dt = {pt32:.2e}, hit-count mismatches = {pcount32}"
    );
    eprintln!(
        "  prepared patch == patch (bit for bit, hits and order): f64 {same64}/{N}, f32 {same32}/{N}"
    );
    for (name, (uv, t, bad)) in [
        "f64 fast patch, world space",
        "f32 fast patch, world space",
        "f64 fast patch, ray space",
        "f32 fast patch, ray space",
    ]
    .iter()
    .zip(fast_err)
    {
        eprintln!(
            "  {name} (not watertight): max |du|,|dv| = {uv:.2e}, max rel dt = {t:.2e}, hit-count mismatches = {bad}"
        );
    }
    for (name, (dt, miss)) in [
        "two Möller-Trumbore f64",
        "two Möller-Trumbore f32",
        "two watertight f64",
        "two watertight f32",
    ]
    .iter()
    .zip(split_err)
    {
        eprintln!(
            "  split, {name}: hit/miss disagrees on {miss} rays, max rel dt of nearest hit = {dt:.2e}"
        );
    }
}

/// Times the tests of one precision, `raw` (everything per call, as a one-off query would
/// pay it) and `prepared` (per-ray and per-primitive set-up outside the timed loop, as in a
/// BVH traversal: one `Ray` per ray, `PreparedPatch`, precomputed Möller-Trumbore edges).
fn bench_precision<F>(c: &mut Criterion, name: &str, cases: &[Case], cast: fn(f64) -> F)
where
    F: Float + std::fmt::Debug,
{
    let v = |p: [f64; 3]| p.map(cast);
    let patches: Vec<Patch<F>> = cases.iter().map(|c| Patch::new(c.corners.map(v))).collect();
    let prepared: Vec<PreparedPatch<F>> = patches.iter().map(|&p| p.into()).collect();
    let fast: Vec<FastPatch<F>> = patches.iter().map(|&p| p.into()).collect();
    let tris: Vec<[[[F; 3]; 3]; 2]> = cases
        .iter()
        .map(|c| split(&c.corners).map(|t| t.map(v)))
        .collect();
    let watertight: Vec<[Triangle<F>; 2]> = tris.iter().map(|t| t.map(Triangle::new)).collect();
    let mt: Vec<[MollerTrumbore<F>; 2]> = tris.iter().map(|t| t.map(MollerTrumbore::new)).collect();
    let rays: Vec<([F; 3], [F; 3])> = cases.iter().map(|c| (v(c.origin), v(c.dir))).collect();
    let prepared_rays: Vec<Ray<F>> = rays
        .iter()
        .map(|&(o, d)| Ray::new(o, d).expect("finite ray"))
        .collect();
    let (lo, hi) = (F::zero(), F::infinity());

    let mut g = c.benchmark_group("ray_vs_patch_raw");
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function(format!("{name}/patch"), |b| {
        b.iter(|| {
            let mut n = 0;
            for (p, (o, d)) in patches.iter().zip(&rays) {
                n += black_box(&p.intersect(*o, *d, lo, hi)).len();
            }
            n
        })
    });
    g.bench_function(format!("{name}/fast_patch"), |b| {
        b.iter(|| {
            let mut n = 0;
            for (p, (o, d)) in patches.iter().zip(&rays) {
                n += black_box(&FastPatch::from(*p).intersect_world(*o, *d, lo, hi)).len();
            }
            n
        })
    });
    g.bench_function(format!("{name}/fast_patch_ray_space"), |b| {
        b.iter(|| {
            let mut n = 0;
            for (p, (o, d)) in patches.iter().zip(&rays) {
                // `intersect`: `Ray::new` + `intersect_ray`.
                n += black_box(&FastPatch::from(*p).intersect(*o, *d, lo, hi)).len();
            }
            n
        })
    });
    g.bench_function(format!("{name}/two_moller_trumbore"), |b| {
        b.iter(|| {
            let mut n = 0;
            for (t, (o, d)) in tris.iter().zip(&rays) {
                for tri in t {
                    n += usize::from(black_box(&moller_trumbore(tri, *o, *d, lo, hi)).is_some());
                }
            }
            n
        })
    });
    g.bench_function(format!("{name}/two_watertight"), |b| {
        b.iter(|| {
            let mut n = 0;
            for (t, (o, d)) in watertight.iter().zip(&rays) {
                for tri in t {
                    n += usize::from(black_box(&tri.intersect(*o, *d, lo, hi)).is_some());
                }
            }
            n
        })
    });
    g.finish();

    let mut g = c.benchmark_group("ray_vs_patch_prepared");
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function(format!("{name}/prepared_patch"), |b| {
        b.iter(|| {
            let mut n = 0;
            for (p, r) in prepared.iter().zip(&prepared_rays) {
                n += black_box(&p.intersect_ray(r, lo, hi)).len();
            }
            n
        })
    });
    g.bench_function(format!("{name}/fast_patch_prepared"), |b| {
        b.iter(|| {
            let mut n = 0;
            for (p, (o, d)) in fast.iter().zip(&rays) {
                n += black_box(&p.intersect_world(*o, *d, lo, hi)).len();
            }
            n
        })
    });
    g.bench_function(format!("{name}/fast_patch_ray_space_shared_ray"), |b| {
        b.iter(|| {
            let mut n = 0;
            for (p, r) in fast.iter().zip(&prepared_rays) {
                n += black_box(&p.intersect_ray(r, lo, hi)).len();
            }
            n
        })
    });
    g.bench_function(format!("{name}/patch_shared_ray"), |b| {
        b.iter(|| {
            let mut n = 0;
            for (p, r) in patches.iter().zip(&prepared_rays) {
                n += black_box(&p.intersect_ray(r, lo, hi)).len();
            }
            n
        })
    });
    g.bench_function(format!("{name}/two_moller_trumbore_prepared"), |b| {
        b.iter(|| {
            let mut n = 0;
            for (t, (o, d)) in mt.iter().zip(&rays) {
                for tri in t {
                    n += usize::from(black_box(&tri.intersect(*o, *d, lo, hi)).is_some());
                }
            }
            n
        })
    });
    g.bench_function(format!("{name}/two_watertight_shared_ray"), |b| {
        b.iter(|| {
            let mut n = 0;
            for (t, r) in watertight.iter().zip(&prepared_rays) {
                for tri in t {
                    n += usize::from(black_box(&tri.intersect_ray(r, lo, hi)).is_some());
                }
            }
            n
        })
    });
    g.finish();
}

fn bench(c: &mut Criterion) {
    let cases = common::ray_cases(N);
    report(&cases);
    bench_precision::<f32>(c, "f32", &cases, |x| x as f32);
    bench_precision::<f64>(c, "f64", &cases, |x| x);
}

criterion_group!(benches, bench);
criterion_main!(benches);
