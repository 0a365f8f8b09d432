//! Cost per ray of one bilinear patch against the two triangles that split it, measured as
//! the minimum over many repetitions (robust on a loaded machine, where the criterion
//! medians of `benches/ray_patch.rs` swing with the load). Same 1024 rays and patches as
//! the benchmark; all methods are timed in an interleaved loop, so they see the same load.
//!
//! Run with `cargo run --release -p bilinear-patch --example ray_patch_costs [repetitions]`.

use bilinear_patch::{MollerTrumbore, Patch, PreparedPatch, Ray, Triangle, moller_trumbore};
use num_traits::Float;
use rand::{RngExt, SeedableRng};
use std::hint::black_box;
use std::time::Instant;

const N: usize = 1024;

/// Patches and rays as in `benches/ray_patch.rs` (same seed, same distribution).
/// Corners, ray origin, ray direction.
type Case = ([[f64; 3]; 4], [f64; 3], [f64; 3]);

fn cases() -> Vec<Case> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(4);
    let mut r = |lo: f64, hi: f64| rng.random_range(lo..hi);
    (0..N)
        .map(|_| {
            let mut c = [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ];
            for q in &mut c {
                q[0] += r(-0.2, 0.2);
                q[1] += r(-0.2, 0.2);
                q[2] += r(-0.5, 0.5);
            }
            let target = [r(-0.2, 1.2), r(-0.2, 1.2), r(-0.3, 0.3)];
            let o = [r(-1.0, 2.0), r(-1.0, 2.0), r(2.0, 4.0)];
            let d = [target[0] - o[0], target[1] - o[1], target[2] - o[2]];
            (c, o, d)
        })
        .collect()
}

fn run<F: Float>(name: &str, cast: fn(f64) -> F, reps: usize) {
    let v = |p: [f64; 3]| p.map(cast);
    let cs = cases();
    let patches: Vec<Patch<F>> = cs.iter().map(|c| Patch::new(c.0.map(v))).collect();
    let prepared: Vec<PreparedPatch<F>> = patches.iter().map(|&p| p.into()).collect();
    let rays: Vec<([F; 3], [F; 3])> = cs.iter().map(|c| (v(c.1), v(c.2))).collect();
    let shared: Vec<Ray<F>> = rays
        .iter()
        .map(|&(o, d)| Ray::new(o, d).expect("finite ray"))
        .collect();
    let tris: Vec<[[[F; 3]; 3]; 2]> = cs
        .iter()
        .map(|c| [[c.0[0], c.0[1], c.0[2]], [c.0[0], c.0[2], c.0[3]]].map(|t| t.map(v)))
        .collect();
    let wt: Vec<[Triangle<F>; 2]> = tris.iter().map(|t| t.map(Triangle::new)).collect();
    let mt: Vec<[MollerTrumbore<F>; 2]> = tris.iter().map(|t| t.map(MollerTrumbore::new)).collect();
    let (lo, hi) = (F::zero(), F::infinity());

    type Method<'a> = (&'a str, Box<dyn Fn() -> usize + 'a>);
    // Plain loops, as in the benchmark.
    let methods: Vec<Method<'_>> = vec![
        (
            "raw: patch (Patch::intersect)",
            Box::new(|| {
                let mut n = 0;
                for (p, (o, d)) in patches.iter().zip(&rays) {
                    n += black_box(p.intersect(*o, *d, lo, hi)).len();
                }
                n
            }),
        ),
        (
            "raw: two watertight triangles",
            Box::new(|| {
                let mut n = 0;
                for (t, (o, d)) in wt.iter().zip(&rays) {
                    for tri in t {
                        n += usize::from(black_box(tri.intersect(*o, *d, lo, hi)).is_some());
                    }
                }
                n
            }),
        ),
        (
            "raw: two Möller-Trumbore",
            Box::new(|| {
                let mut n = 0;
                for (t, (o, d)) in tris.iter().zip(&rays) {
                    for tri in t {
                        n += usize::from(black_box(moller_trumbore(tri, *o, *d, lo, hi)).is_some());
                    }
                }
                n
            }),
        ),
        (
            "prepared: PreparedPatch, shared Ray",
            Box::new(|| {
                let mut n = 0;
                for (p, r) in prepared.iter().zip(&shared) {
                    n += black_box(p.intersect_ray(r, lo, hi)).len();
                }
                n
            }),
        ),
        (
            "prepared: two watertight, shared Ray",
            Box::new(|| {
                let mut n = 0;
                for (t, r) in wt.iter().zip(&shared) {
                    for tri in t {
                        n += usize::from(black_box(tri.intersect_ray(r, lo, hi)).is_some());
                    }
                }
                n
            }),
        ),
        (
            "prepared: two Möller-Trumbore, stored edges",
            Box::new(|| {
                let mut n = 0;
                for (t, (o, d)) in mt.iter().zip(&rays) {
                    for tri in t {
                        n += usize::from(black_box(tri.intersect(*o, *d, lo, hi)).is_some());
                    }
                }
                n
            }),
        ),
        (
            "Ray::new alone",
            Box::new(|| {
                let mut n = 0;
                for (o, d) in &rays {
                    n += usize::from(black_box(Ray::new(*o, *d)).is_some());
                }
                n
            }),
        ),
    ];
    let mut best = vec![f64::INFINITY; methods.len()];
    for _ in 0..reps {
        for (b, (_, f)) in best.iter_mut().zip(&methods) {
            let t0 = Instant::now();
            black_box(f());
            *b = b.min(t0.elapsed().as_secs_f64());
        }
    }
    println!("{name}, {N} rays, minimum over {reps} repetitions:");
    for (b, (label, _)) in best.iter().zip(&methods) {
        println!("  {label:44} {:6.1} ns/ray", b * 1e9 / N as f64);
    }
}

fn main() {
    let reps = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(2000);
    run::<f32>("f32", |x| x as f32, reps);
    run::<f64>("f64", |x| x, reps);
}
