//! Cost per ray of one bilinear patch against the two triangles that split it, measured as
//! the minimum over many repetitions (robust on a loaded machine, where the criterion
//! medians of `benches/ray_patch.rs` swing with the load). Same 1024 rays and patches as
//! the benchmark; all methods are timed in an interleaved loop, so they see the same load.
//!
//! Next to each time it prints the error against the f64 watertight patch test (outside the
//! timed loop): for the patch tests the parameter and relative t error of the hits and the
//! number of rays with a different hit count; for the triangle pairs the relative t error of
//! the nearest hit (the geometric error of the split) and the hit/miss disagreements.
//!
//! Every result is passed to `black_box` by reference, so it is kept in memory where it was
//! built (as a caller reading the hits in place would); passing it by value made the
//! compiler copy it through the stack with loads wider than the stores that built it, a
//! store-forwarding stall of the harness, not of the test.
//!
//! Without a filter it then times the prepared ray-space patch test against the prepared
//! Möller-Trumbore pair on rays that all hit, on the benchmark's mix and on rays that all
//! miss, to show where the difference comes from.
//!
//! Run with `cargo run --release -p bilinear-patch --example ray_patch_costs [repetitions]
//! [filter]`; with a filter only the methods whose label contains it are timed (e.g. to
//! count one method's instructions under `valgrind --tool=cachegrind`).

use bilinear_patch::{
    FastPatch, MollerTrumbore, Patch, PreparedPatch, Ray, Triangle, moller_trumbore,
};
use num_traits::Float;
use std::hint::black_box;
use std::time::Instant;

// The patches and rays of `benches/ray_patch.rs` (same generator, same seed).
#[path = "../tests/common/mod.rs"]
mod common;

const N: usize = 1024;

/// The benchmark's patches, triangle pairs and rays in one precision, set up for each test.
struct Set<F> {
    patches: Vec<Patch<F>>,
    prepared: Vec<PreparedPatch<F>>,
    fast: Vec<FastPatch<F>>,
    /// (origin, direction) per ray.
    rays: Vec<([F; 3], [F; 3])>,
    /// The same rays prepared once, shared by the faces they meet.
    shared: Vec<Ray<F>>,
    tris: Vec<[[[F; 3]; 3]; 2]>,
    wt: Vec<[Triangle<F>; 2]>,
    mt: Vec<[MollerTrumbore<F>; 2]>,
}

impl<F: Float> Set<F> {
    fn new(cs: &[common::RayCase], cast: fn(f64) -> F) -> Self {
        let v = |p: [f64; 3]| p.map(cast);
        let patches: Vec<Patch<F>> = cs.iter().map(|c| Patch::new(c.corners.map(v))).collect();
        let rays: Vec<([F; 3], [F; 3])> = cs.iter().map(|c| (v(c.origin), v(c.dir))).collect();
        let tris: Vec<[[[F; 3]; 3]; 2]> = cs
            .iter()
            .map(|c| common::split(&c.corners).map(|t| t.map(v)))
            .collect();
        Set {
            prepared: patches.iter().map(|&p| p.into()).collect(),
            fast: patches.iter().map(|&p| p.into()).collect(),
            shared: rays
                .iter()
                .map(|&(o, d)| Ray::new(o, d).expect("finite ray"))
                .collect(),
            wt: tris.iter().map(|t| t.map(Triangle::new)).collect(),
            mt: tris.iter().map(|t| t.map(MollerTrumbore::new)).collect(),
            patches,
            rays,
            tris,
        }
    }

    /// Prepared `FastPatch::intersect_ray` with the shared rays, t in [0, inf): hits.
    fn fast_ray(&self) -> usize {
        let (lo, hi) = (F::zero(), F::infinity());
        let mut n = 0;
        for (p, r) in self.fast.iter().zip(&self.shared) {
            n += black_box(&p.intersect_ray(r, lo, hi)).len();
        }
        n
    }

    /// Prepared Möller-Trumbore (stored edges) on both triangles, t in [0, inf): hits.
    fn mt_pair(&self) -> usize {
        let (lo, hi) = (F::zero(), F::infinity());
        let mut n = 0;
        for (t, (o, d)) in self.mt.iter().zip(&self.rays) {
            for tri in t {
                n += usize::from(black_box(&tri.intersect(*o, *d, lo, hi)).is_some());
            }
        }
        n
    }
}

fn run<F: Float>(name: &str, cast: fn(f64) -> F, reps: usize, filter: &str) {
    let cs = common::ray_cases(N);
    let set = Set::new(&cs, cast);
    let Set {
        patches,
        prepared,
        fast,
        rays,
        shared,
        tris,
        wt,
        mt,
    } = &set;
    let (lo, hi) = (F::zero(), F::infinity());

    type Method<'a> = (&'a str, Box<dyn Fn() -> usize + 'a>);
    // Plain loops, as in the benchmark.
    let methods: Vec<Method<'_>> = vec![
        (
            "raw: patch (Patch::intersect)",
            Box::new(|| {
                let mut n = 0;
                for (p, (o, d)) in patches.iter().zip(rays) {
                    n += black_box(&p.intersect(*o, *d, lo, hi)).len();
                }
                n
            }),
        ),
        (
            "raw: fast patch, world (FastPatch::new + intersect_world)",
            Box::new(|| {
                let mut n = 0;
                for (p, (o, d)) in patches.iter().zip(rays) {
                    n += black_box(&FastPatch::from(*p).intersect_world(*o, *d, lo, hi)).len();
                }
                n
            }),
        ),
        (
            "raw: fast patch, ray space (FastPatch::new + intersect)",
            Box::new(|| {
                let mut n = 0;
                for (p, (o, d)) in patches.iter().zip(rays) {
                    n += black_box(&FastPatch::from(*p).intersect(*o, *d, lo, hi)).len();
                }
                n
            }),
        ),
        (
            "raw: two watertight triangles",
            Box::new(|| {
                let mut n = 0;
                for (t, (o, d)) in wt.iter().zip(rays) {
                    for tri in t {
                        n += usize::from(black_box(&tri.intersect(*o, *d, lo, hi)).is_some());
                    }
                }
                n
            }),
        ),
        (
            "raw: two Möller-Trumbore",
            Box::new(|| {
                let mut n = 0;
                for (t, (o, d)) in tris.iter().zip(rays) {
                    for tri in t {
                        n +=
                            usize::from(black_box(&moller_trumbore(tri, *o, *d, lo, hi)).is_some());
                    }
                }
                n
            }),
        ),
        (
            "prepared: PreparedPatch, shared Ray",
            Box::new(|| {
                let mut n = 0;
                for (p, r) in prepared.iter().zip(shared) {
                    n += black_box(&p.intersect_ray(r, lo, hi)).len();
                }
                n
            }),
        ),
        (
            "prepared: FastPatch::intersect_world (edges, q_n)",
            Box::new(|| {
                let mut n = 0;
                for (p, (o, d)) in fast.iter().zip(rays) {
                    n += black_box(&p.intersect_world(*o, *d, lo, hi)).len();
                }
                n
            }),
        ),
        (
            "prepared: FastPatch::intersect_ray, shared Ray",
            Box::new(|| set.fast_ray()),
        ),
        (
            "prepared: two watertight, shared Ray",
            Box::new(|| {
                let mut n = 0;
                for (t, r) in wt.iter().zip(shared) {
                    for tri in t {
                        n += usize::from(black_box(&tri.intersect_ray(r, lo, hi)).is_some());
                    }
                }
                n
            }),
        ),
        (
            "prepared: two Möller-Trumbore, stored edges",
            Box::new(|| set.mt_pair()),
        ),
        (
            "Ray::new alone",
            Box::new(|| {
                let mut n = 0;
                for (o, d) in rays {
                    n += usize::from(black_box(&Ray::new(*o, *d)).is_some());
                }
                n
            }),
        ),
    ];
    // Errors against the f64 watertight patch, in the order of `methods`.
    let exact: Vec<Vec<[f64; 3]>> = cs
        .iter()
        .map(|c| {
            let h = Patch::new(c.corners).intersect(c.origin, c.dir, 0.0, f64::INFINITY);
            h.iter().map(|h| [h.t, h.u, h.v]).collect()
        })
        .collect();
    let f = |x: F| x.to_f64().unwrap_or(f64::NAN);
    let patch_err = |hits: &dyn Fn(usize) -> Vec<[f64; 3]>| {
        let (mut uv, mut t, mut bad) = (0.0f64, 0.0f64, 0usize);
        for (i, e) in exact.iter().enumerate() {
            let h = hits(i);
            if h.len() != e.len() {
                bad += 1;
                continue;
            }
            for (a, b) in h.iter().zip(e) {
                uv = uv.max((a[1] - b[1]).abs()).max((a[2] - b[2]).abs());
                t = t.max((a[0] - b[0]).abs() / b[0].abs());
            }
        }
        format!("max |du|,|dv| {uv:.1e}, rel dt {t:.1e}, {bad} count mismatches")
    };
    let tri_err = |nearest: &dyn Fn(usize) -> Option<f64>| {
        let (mut t, mut bad) = (0.0f64, 0usize);
        for (i, e) in exact.iter().enumerate() {
            match (nearest(i), e.first()) {
                (Some(a), Some(b)) => t = t.max((a - b[0]).abs() / b[0].abs()),
                (None, None) => {}
                _ => bad += 1,
            }
        }
        format!("split: nearest-hit rel dt {t:.1e}, {bad} hit/miss mismatches")
    };
    let to3 = |h: &[bilinear_patch::Hit<F>]| h.iter().map(|h| [f(h.t), f(h.u), f(h.v)]).collect();
    let min_t = |a: Option<F>, b: Option<F>| match (a, b) {
        (Some(a), Some(b)) => Some(f(a.min(b))),
        (Some(a), None) | (None, Some(a)) => Some(f(a)),
        (None, None) => None,
    };
    let raw_patch = patch_err(&|i| to3(&patches[i].intersect(rays[i].0, rays[i].1, lo, hi)));
    let fast_patch = patch_err(&|i| to3(&fast[i].intersect_world(rays[i].0, rays[i].1, lo, hi)));
    let fast_ray = patch_err(&|i| to3(&fast[i].intersect_ray(&shared[i], lo, hi)));
    let prepared_patch = patch_err(&|i| to3(&prepared[i].intersect_ray(&shared[i], lo, hi)));
    let wt_err = tri_err(&|i| {
        let [a, b] = wt[i].map(|t| t.intersect_ray(&shared[i], lo, hi).map(|h| h.t));
        min_t(a, b)
    });
    let mt_err = tri_err(&|i| {
        let [a, b] = mt[i].map(|t| t.intersect(rays[i].0, rays[i].1, lo, hi).map(|h| h.t));
        min_t(a, b)
    });
    let errors = [
        raw_patch,
        fast_patch.clone(),
        fast_ray.clone(),
        wt_err.clone(),
        mt_err.clone(),
        prepared_patch,
        fast_patch,
        fast_ray,
        wt_err,
        mt_err,
        String::new(),
    ];
    assert_eq!(errors.len(), methods.len());

    let mut best = vec![f64::INFINITY; methods.len()];
    for _ in 0..reps {
        for (b, (label, f)) in best.iter_mut().zip(&methods) {
            if !label.contains(filter) {
                continue;
            }
            let t0 = Instant::now();
            black_box(f());
            *b = b.min(t0.elapsed().as_secs_f64());
        }
    }
    println!(
        "{name}, {N} rays, minimum over {reps} repetitions; error vs the f64 watertight patch:"
    );
    for ((b, (label, _)), err) in best.iter().zip(&methods).zip(&errors) {
        if !label.contains(filter) {
            continue;
        }
        println!("  {label:52} {:6.1} ns/ray  {err}", b * 1e9 / N as f64);
    }
}

/// The prepared ray-space patch test against the prepared Möller-Trumbore pair on rays that
/// all hit, on the benchmark's mix, and on rays that all miss (same patches, same seed;
/// only the aim changes): where the difference in time comes from.
fn by_outcome<F: Float>(name: &str, cast: fn(f64) -> F, reps: usize) {
    println!("{name}, {N} rays by outcome, minimum over {reps} repetitions, prepared:");
    for (label, aim) in [
        ("all hit (aimed at [0.35, 0.65]²)", 0.35..0.65),
        ("benchmark mix (aimed at [-0.2, 1.2]²)", -0.2..1.2),
        ("all miss (aimed at [1.6, 2.0]²)", 1.6..2.0),
    ] {
        let set = Set::new(&common::ray_cases_aimed(N, aim), cast);
        let (mut patch, mut pair, mut hits) = (f64::INFINITY, f64::INFINITY, 0);
        for _ in 0..reps {
            let t0 = Instant::now();
            hits = set.fast_ray();
            patch = patch.min(t0.elapsed().as_secs_f64());
            let t0 = Instant::now();
            black_box(set.mt_pair());
            pair = pair.min(t0.elapsed().as_secs_f64());
        }
        let ns = |s: f64| s * 1e9 / N as f64;
        println!(
            "  {label:38} {hits:4} patch hits: FastPatch::intersect_ray {:5.1} ns/ray, two Möller-Trumbore {:5.1} ns/ray, ratio {:.2}",
            ns(patch),
            ns(pair),
            patch / pair
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let reps = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(2000);
    let filter = args.get(2).map_or("", String::as_str);
    run::<f32>("f32", |x| x as f32, reps, filter);
    run::<f64>("f64", |x| x, reps, filter);
    // Not with a filter (which selects methods to count under cachegrind).
    if filter.is_empty() {
        by_outcome::<f32>("f32", |x| x as f32, reps);
        by_outcome::<f64>("f64", |x| x, reps);
    }
}
