//! One analytic coverage solve per sample vs N time-dependent inside tests (the stochastic
//! alternative, N = 1, 4, 16, 64), f32 and f64; exact rational depth vs linear depth; the
//! quadratic solver. Each setting's error against the f64 analytic reference is printed
//! before its timings.
//!
//! Run: `cargo bench -p edge-eqn --bench coverage -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use edge_eqn::quadratic::real_roots;
use edge_eqn::{MovingTriangle, TriangleSetup};
use num_traits::Float;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

type Tri = [[f64; 3]; 3];

/// Pairs of (moving triangle, pixel centre near it): perspective (w in [1, 4]), vertices in
/// a 64 px box, motion up to ±24 px, the pixel near the triangle at a random time.
fn scenes(n: usize, seed: u64) -> Vec<(Tri, Tri, f64, f64)> {
    let mut rng = Pcg64::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let mut q = [[0.0; 3]; 3];
            let mut r = [[0.0; 3]; 3];
            let mut s = [[0.0; 2]; 3];
            for k in 0..3 {
                let (x, y) = (rng.random_range(0.0..64.0), rng.random_range(0.0..64.0));
                let (w0, w1) = (rng.random_range(1.0..4.0), rng.random_range(1.0..4.0));
                let (dx, dy) = (rng.random_range(-24.0..24.0), rng.random_range(-24.0..24.0));
                q[k] = [x * w0, y * w0, w0];
                r[k] = [(x + dx) * w1, (y + dy) * w1, w1];
                let t: f64 = 0.5;
                s[k] = [x + t * dx, y + t * dy];
            }
            let b: [f64; 3] = [rng.random(), rng.random(), rng.random()];
            let sum = b[0] + b[1] + b[2] + 1e-9;
            let px = (0..3).map(|k| b[k] / sum * s[k][0]).sum::<f64>().floor() + 0.5;
            let py = (0..3).map(|k| b[k] / sum * s[k][1]).sum::<f64>().floor() + 0.5;
            (q, r, px, py)
        })
        .collect()
}

/// Jittered stratified times: sample i of N in [i/N, (i+1)/N).
fn times(n: usize, rng: &mut Pcg64) -> Vec<f64> {
    (0..n)
        .map(|i| (i as f64 + rng.random_range(0.0..1.0)) / n as f64)
        .collect()
}

fn cast<F: Float>(t: &Tri) -> [[F; 3]; 3] {
    t.map(|v| v.map(|c| F::from(c).unwrap()))
}

struct Case<F> {
    setup: TriangleSetup<F>,
    x: F,
    y: F,
}

fn cases<F: Float>(sc: &[(Tri, Tri, f64, f64)]) -> Vec<Case<F>> {
    sc.iter()
        .map(|(q, r, x, y)| Case {
            setup: MovingTriangle::new(cast::<F>(q), cast::<F>(r)).setup(),
            x: F::from(*x).unwrap(),
            y: F::from(*y).unwrap(),
        })
        .collect()
}

const PAIRS: usize = 512;
const NS: [usize; 4] = [1, 4, 16, 64];

fn report_errors(sc: &[(Tri, Tri, f64, f64)]) {
    let reference: Vec<f64> = cases::<f64>(sc)
        .iter()
        .map(|c| c.setup.coverage(c.x, c.y).total())
        .collect();
    let covered = reference.iter().filter(|&&v| v > 0.0).count();
    let f32_err = cases::<f32>(sc)
        .iter()
        .zip(&reference)
        .map(|(c, r)| (f64::from(c.setup.coverage(c.x, c.y).total()) - r).abs())
        .fold(0.0, f64::max);
    eprintln!("\n== covered time per sample: error against the f64 analytic solve ==");
    eprintln!("{PAIRS} pixel/triangle pairs ({covered} with non-empty coverage)");
    eprintln!("analytic f64: 0 (reference)");
    eprintln!("analytic f32: max |error| {f32_err:.2e}");
    let mut rng = Pcg64::seed_from_u64(99);
    let c64 = cases::<f64>(sc);
    for n in NS {
        let mut sq = 0.0;
        let mut worst: f64 = 0.0;
        // Average over 16 independent jitter draws per pair.
        let draws = 16;
        for _ in 0..draws {
            for (c, r) in c64.iter().zip(&reference) {
                let ts = times(n, &mut rng);
                let hits = ts
                    .iter()
                    .filter(|&&t| c.setup.inside_at(c.x, c.y, t))
                    .count();
                let e = hits as f64 / n as f64 - r;
                sq += e * e;
                worst = worst.max(e.abs());
            }
        }
        let rms = (sq / (draws * PAIRS) as f64).sqrt();
        eprintln!("stochastic N = {n:2}: RMS error {rms:.4}, max |error| {worst:.4}");
    }
}

/// Sample times for the N-test variant: `PAIRS * n` jittered stratified times, flat
/// (pair i uses `ts[i * n..(i + 1) * n]`), so both variants walk one contiguous array.
fn flat_times<F: Float>(n: usize, rng: &mut Pcg64) -> Vec<F> {
    (0..PAIRS)
        .flat_map(|_| times(n, rng))
        .map(|t| F::from(t).unwrap())
        .collect()
}

/// One analytic solve per pair (same pairs, same setups as the inside tests).
#[inline(never)]
fn run_analytic<F: Float>(cs: &[Case<F>]) -> usize {
    let mut n = 0usize;
    for c in cs {
        n += black_box(c.setup.coverage(black_box(c.x), black_box(c.y))).len();
    }
    n
}

/// N time-dependent inside tests (`inside_at`) per pair at the pair's N sample times.
#[inline(never)]
fn run_inside<F: Float>(cs: &[Case<F>], ts: &[F], n: usize) -> usize {
    let mut hits = 0usize;
    for (c, tt) in cs.iter().zip(ts.chunks_exact(n)) {
        let (x, y) = (black_box(c.x), black_box(c.y));
        for &t in tt {
            hits += usize::from(c.setup.inside_at(x, y, black_box(t)));
        }
    }
    hits
}

/// Side-by-side ratio, robust to a shared machine: rounds alternate one timed batch of
/// analytic solves with one timed batch of N-test runs; each round gives a ratio of two
/// measurements taken milliseconds apart. Prints the median ratio over rounds and the ratio
/// of the per-variant minimum times.
fn report_ratio<F: Float>(name: &str, cs: &[Case<F>], tss: &[(usize, Vec<F>)]) {
    use std::time::Instant;
    const ROUNDS: usize = 41;
    let reps = |f: &dyn Fn() -> usize, k: usize| {
        let t0 = Instant::now();
        for _ in 0..k {
            black_box(f());
        }
        t0.elapsed().as_secs_f64() / k as f64
    };
    eprintln!(
        "\n== {name}: cost of one analytic solve in inside tests (interleaved, {ROUNDS} rounds) =="
    );
    eprintln!(
        "{:>4} {:>14} {:>16} {:>14} {:>12}",
        "N", "analytic ns/px", "N tests ns/px", "median ratio", "min ratio"
    );
    for (n, ts) in tss {
        let (mut ra, mut rt, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
        // Batches of about the same duration for both variants.
        let k_a = 40;
        let k_t = (40 * 8 / n).max(2);
        for _ in 0..ROUNDS {
            let a = reps(&|| run_analytic(cs), k_a);
            let t = reps(&|| run_inside(cs, ts, *n), k_t);
            ra.push(a);
            rt.push(t);
            ratios.push(a / (t / *n as f64));
        }
        ratios.sort_by(f64::total_cmp);
        let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let (ma, mt) = (min(&ra), min(&rt));
        eprintln!(
            "{n:>4} {:>14.1} {:>16.1} {:>14.2} {:>12.2}",
            ma * 1e9 / PAIRS as f64,
            mt * 1e9 / PAIRS as f64,
            ratios[ROUNDS / 2],
            ma / (mt / *n as f64)
        );
    }
}

/// Per-sample work of a stochastic rasteriser: `inside_at` then `depth_at` for covered
/// samples, against one `inside_depth_at`, at the same 16 times per pair (interleaved rounds,
/// minimum per variant), with the largest depth difference between the two.
fn report_inside_depth<F: Float>(name: &str, cs: &[Case<F>], ts: &[F]) {
    use std::time::Instant;
    let n = 16;
    let separate = || {
        let mut acc = F::zero();
        for (c, tt) in cs.iter().zip(ts.chunks_exact(n)) {
            let (x, y) = (black_box(c.x), black_box(c.y));
            for &t in tt {
                if c.setup.inside_at(x, y, t) {
                    acc = acc + c.setup.depth_at(x, y, t);
                }
            }
        }
        acc
    };
    let combined = || {
        let mut acc = F::zero();
        for (c, tt) in cs.iter().zip(ts.chunks_exact(n)) {
            let (x, y) = (black_box(c.x), black_box(c.y));
            for &t in tt {
                if let Some(d) = c.setup.inside_depth_at(x, y, t) {
                    acc = acc + d;
                }
            }
        }
        acc
    };
    let mut worst = 0.0f64;
    let mut covered = 0usize;
    for (c, tt) in cs.iter().zip(ts.chunks_exact(n)) {
        for &t in tt {
            if let Some(d) = c.setup.inside_depth_at(c.x, c.y, t) {
                let e = c.setup.depth_at(c.x, c.y, t);
                let rel = ((d - e) / e).abs().to_f64().unwrap_or(f64::NAN);
                worst = worst.max(rel);
                covered += 1;
            }
        }
    }
    let time = |f: &dyn Fn() -> F| {
        let t0 = Instant::now();
        for _ in 0..10 {
            black_box(f());
        }
        t0.elapsed().as_secs_f64() / 10.0 / (PAIRS * n) as f64 * 1e9
    };
    let (mut a, mut b) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..31 {
        a = a.min(time(&separate));
        b = b.min(time(&combined));
    }
    eprintln!(
        "{name}: per sample (16 times x {PAIRS} pairs, {covered} covered): inside_at + depth_at {a:.2} ns, inside_depth_at {b:.2} ns ({:.2}x); max relative depth difference {worst:.2e}",
        a / b
    );
}

fn bench_coverage_for<F: Float>(c: &mut Criterion, name: &str, sc: &[(Tri, Tri, f64, f64)]) {
    let cs = cases::<F>(sc);
    let mut rng = Pcg64::seed_from_u64(5);
    let tss: Vec<(usize, Vec<F>)> = NS.iter().map(|&n| (n, flat_times(n, &mut rng))).collect();
    report_ratio(name, &cs, &tss);
    if let Some((_, ts)) = tss.iter().find(|(n, _)| *n == 16) {
        report_inside_depth(name, &cs, ts);
    }
    let mut group = c.benchmark_group(format!("coverage_{name}"));
    group.throughput(Throughput::Elements(PAIRS as u64));
    group.bench_function("analytic", |b| b.iter(|| run_analytic(&cs)));
    for (n, ts) in &tss {
        group.bench_with_input(BenchmarkId::new("inside_at_x", n), ts, |b, ts| {
            b.iter(|| run_inside(&cs, ts, *n))
        });
    }
    group.finish();
}

fn bench_coverage(c: &mut Criterion) {
    let sc = scenes(PAIRS, 1);
    report_errors(&sc);
    bench_coverage_for::<f32>(c, "f32", &sc);
    bench_coverage_for::<f64>(c, "f64", &sc);
}

/// Exact rational depth vs linear depth per evaluation, with the linear fit's error.
fn bench_depth(c: &mut Criterion) {
    let sc = scenes(PAIRS, 2);
    let mut spans64 = Vec::new();
    let c64 = cases::<f64>(&sc);
    for cs in &c64 {
        let s = cs.setup.sample(cs.x, cs.y);
        for sp in s.coverage().iter() {
            spans64.push((s.depth(), s.linear_depth(*sp), *sp));
        }
    }
    let max_err = spans64.iter().map(|s| s.1.max_error).fold(0.0, f64::max);
    let mean_err = spans64.iter().map(|s| s.1.max_error).sum::<f64>() / spans64.len() as f64;
    let max_rel = spans64
        .iter()
        .map(|(d, f, sp)| f.max_error / d.eval(sp.mid()).abs())
        .fold(0.0, f64::max);
    // f32 exact depth against f64 exact depth at span midpoints.
    let c32 = cases::<f32>(&sc);
    let mut f32_rel: f64 = 0.0;
    for (a, b) in c32.iter().zip(&c64) {
        let s64 = b.setup.sample(b.x, b.y);
        let s32 = a.setup.sample(a.x, a.y);
        for sp in s64.coverage().iter() {
            let d64 = s64.depth_at(sp.mid());
            let d32 = f64::from(s32.depth_at(sp.mid() as f32));
            f32_rel = f32_rel.max(((d32 - d64) / d64).abs());
        }
    }
    eprintln!(
        "\n== depth along covered spans ({} spans, depth = w in [1, 4]) ==",
        spans64.len()
    );
    eprintln!(
        "exact rational f64: 0 (reference); exact rational f32: max rel. error {f32_rel:.2e}"
    );
    eprintln!(
        "linear (Eq. 16 chord): max error {max_err:.4}, mean of per-span max {mean_err:.5}, max relative {max_rel:.4}"
    );

    let ts: Vec<f64> = spans64.iter().map(|s| s.2.t0 + 0.37 * s.2.len()).collect();
    let mut group = c.benchmark_group("depth_f64");
    group.throughput(Throughput::Elements(spans64.len() as u64));
    group.bench_function("exact_rational_eval", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for (s, t) in spans64.iter().zip(&ts) {
                acc += s.0.eval(black_box(*t));
            }
            acc
        })
    });
    group.bench_function("linear_eval", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for (s, t) in spans64.iter().zip(&ts) {
                acc += s.1.eval(black_box(*t));
            }
            acc
        })
    });
    group.bench_function("linear_fit_with_max_error", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for s in &spans64 {
                acc += s.0.linear_fit(black_box(s.2)).max_error;
            }
            acc
        })
    });
    group.finish();

    let spans32: Vec<_> = c32
        .iter()
        .flat_map(|cs| {
            let s = cs.setup.sample(cs.x, cs.y);
            let d = s.depth();
            s.coverage()
                .iter()
                .map(|sp| (d, d.linear_fit(*sp), *sp))
                .collect::<Vec<_>>()
        })
        .collect();
    let ts32: Vec<f32> = spans32.iter().map(|s| s.2.t0 + 0.37 * s.2.len()).collect();
    let mut group = c.benchmark_group("depth_f32");
    group.throughput(Throughput::Elements(spans32.len() as u64));
    group.bench_function("exact_rational_eval", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for (s, t) in spans32.iter().zip(&ts32) {
                acc += s.0.eval(black_box(*t));
            }
            acc
        })
    });
    group.bench_function("linear_eval", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for (s, t) in spans32.iter().zip(&ts32) {
                acc += s.1.eval(black_box(*t));
            }
            acc
        })
    });
    group.finish();
}

/// The public solver on the per-edge quadratics of the coverage scenes.
fn bench_quadratic(c: &mut Criterion) {
    let sc = scenes(PAIRS, 3);
    let coefs: Vec<[f64; 3]> = cases::<f64>(&sc)
        .iter()
        .flat_map(|cs| {
            cs.setup
                .sample(cs.x, cs.y)
                .edges()
                .map(|e| [e.alpha, e.beta, e.gamma])
        })
        .collect();
    let coefs32: Vec<[f32; 3]> = coefs.iter().map(|c| c.map(|v| v as f32)).collect();
    let mut group = c.benchmark_group("real_roots");
    group.throughput(Throughput::Elements(coefs.len() as u64));
    group.bench_function("f64", |b| {
        b.iter(|| {
            let mut n = 0usize;
            for c in &coefs {
                n += real_roots(black_box(c[0]), c[1], c[2]).len();
            }
            n
        })
    });
    group.bench_function("f32", |b| {
        b.iter(|| {
            let mut n = 0usize;
            for c in &coefs32 {
                n += real_roots(black_box(c[0]), c[1], c[2]).len();
            }
            n
        })
    });
    group.finish();
}

criterion_group!(benches, bench_coverage, bench_depth, bench_quadratic);
criterion_main!(benches);
