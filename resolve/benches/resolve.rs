//! Resolve cost per pixel vs the number of intervals, and texture filtering cost vs error.
//!
//! Before criterion runs, a table is printed (stderr) with, side by side in one run: time per
//! pixel for n = 1 … 1024 in every configuration, sparse and dense, for the active-list
//! sweep (before), the default sweep (after) and the kinetic sweep alone, with the fitted
//! growth exponents; the no-early-termination case separately; the error of
//! early termination per threshold and of switching intersection handling off, and the
//! error vs time of tap filtering against the exact bilinear segment integral.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use interval_buffer::{Interval, Rgba, Textured};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;
use resolve::reference::brute_force;
use resolve::{BilinearTexture, ExactFilter, Flat, Resolver, Settings, Shader, Sweep, TapFilter};

type Flat64 = Interval<f64, Rgba<f64>>;
type TexturedResolve<'a> =
    dyn Fn(&[Interval<f64, Textured<f64>>], &mut Resolver<f64>) -> Rgba<f64> + 'a;

/// `n` intervals in one pixel. Sparse: starts uniform over the shutter, lengths uniform in
/// [0, 16 / n] (on average 8 active at a time, many small triangles passing: Rønnow's
/// 530-interval pixels). Dense: every interval spans the middle of the shutter (~n active).
fn scene(n: usize, dense: bool, seed: u64) -> Vec<Flat64> {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut v: Vec<Flat64> = (0..n)
        .map(|_| {
            let (ts, len) = if dense {
                (rng.random_range(0.0..0.5), rng.random_range(0.5..1.0))
            } else {
                (
                    rng.random_range(0.0..1.0),
                    rng.random_range(0.0..16.0 / n as f64),
                )
            };
            let c = Rgba::new(
                rng.random_range(0.0..1.0),
                rng.random_range(0.0..1.0),
                rng.random_range(0.0..1.0),
                rng.random_range(0.3..0.9),
            );
            Interval::new(
                ts,
                (ts + len).min(1.0),
                rng.random_range(0.0..1.0),
                rng.random_range(-1.0..1.0),
                c,
            )
        })
        .collect();
    v.sort_by(|a, b| a.ts.total_cmp(&b.ts));
    v
}

fn configs() -> [(&'static str, Settings<f64>); 4] {
    [
        ("opaque", Settings::opaque().with_intersections(false)),
        ("opaque+x", Settings::opaque()),
        (
            "transparent",
            Settings::transparent().with_intersections(false),
        ),
        ("transparent+x", Settings::transparent()),
    ]
}

/// Seconds per call of `f`: the fastest of 10 batches of `budget / 10` each (the minimum
/// is robust against other processes on a shared machine).
fn time_per_call(budget: Duration, mut f: impl FnMut()) -> f64 {
    f();
    let mut best = f64::INFINITY;
    for _ in 0..10 {
        let start = Instant::now();
        let mut calls = 0u64;
        while start.elapsed() < budget / 10 {
            f();
            calls += 1;
        }
        best = best.min(start.elapsed().as_secs_f64() / calls as f64);
    }
    best
}

/// Least-squares slope of log y against log x.
fn exponent(points: &[(f64, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x.ln(), y.ln())).collect();
    let m = pts.len() as f64;
    let (sx, sy) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
    let (mx, my) = (sx / m, sy / m);
    let num: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let den: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    num / den
}

fn max_diff(a: Rgba<f64>, b: Rgba<f64>) -> f64 {
    (a.r - b.r)
        .abs()
        .max((a.g - b.g).abs())
        .max((a.b - b.b).abs())
}

const NS: [usize; 11] = [1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024];

/// Before (Algorithm 1's active list, the only sweep until issue 7's follow-up), after (the
/// default: active list while few are active, kinetic beyond), and the kinetic sweep alone.
const SWEEPS: [(&str, Sweep); 3] = [
    ("before", Sweep::ActiveList),
    ("after", Sweep::Auto),
    ("kinetic", Sweep::Kinetic),
];

/// Time per pixel vs n for both sweeps side by side (one run), and the fitted exponents.
fn growth_table() {
    let budget = Duration::from_millis(150);
    let fit = |s: &[(f64, f64)]| exponent(&s[s.len() - 5..]);
    let nlogn: Vec<(f64, f64)> = NS
        .iter()
        .map(|&n| (n as f64, n as f64 * (n as f64).log2().max(1.0)))
        .collect();
    for dense in [false, true] {
        eprintln!(
            "\n## resolve time per pixel (µs), {} scenes; before = active list (Sweep::ActiveList), after = default (Sweep::Auto), kinetic = Sweep::Kinetic",
            if dense {
                "dense (~n active)"
            } else {
                "sparse (~8 active)"
            }
        );
        let mut head = "| n |".to_string();
        for (name, _) in configs() {
            for (sweep, _) in SWEEPS {
                head += &format!(" {name} {sweep} |");
            }
        }
        eprintln!("{head}");
        eprintln!("|---{}", "|---".repeat(4 * SWEEPS.len()) + "|");
        let mut series: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 4 * SWEEPS.len()];
        for &n in &NS {
            let ivs = scene(n, dense, n as u64);
            let mut row = format!("| {n} |");
            for (k, (_, s)) in configs().into_iter().enumerate() {
                let mut colours = Vec::new();
                for (j, (_, sweep)) in SWEEPS.into_iter().enumerate() {
                    let mut r = Resolver::new(s.clone()).with_sweep(sweep);
                    colours.push(r.resolve(&ivs, &Flat).unwrap());
                    let t = time_per_call(budget, || {
                        black_box(r.resolve(black_box(&ivs), &Flat).unwrap());
                    });
                    series[SWEEPS.len() * k + j].push((n as f64, t));
                    row += &format!(" {:.3} |", t * 1e6);
                }
                // The implementations agree (up to rounding) with intersection handling;
                // without it they may rank an interval differently where the stale order
                // it is inserted into has crossings (each does its own binary search).
                if s.intersections {
                    for c in &colours[1..] {
                        assert!(max_diff(colours[0], *c) < 1e-9, "{colours:?}");
                    }
                }
            }
            eprintln!("{row}");
        }
        let mut row = "| exponent n=64..1024 |".to_string();
        for s in &series {
            row += &format!(" {:.2} |", fit(s));
        }
        eprintln!("{row}  (n log n over the same range: {:.2})", fit(&nlogn));
    }
    // No early termination: threshold 0, dense. Every active interval is visible and every
    // crossing between any two of them is an event, so the output itself needs O(n) per
    // partition and O(n²) partitions.
    eprintln!(
        "\n## transparent, threshold 0 (no early termination), dense (~n active): µs per pixel"
    );
    eprintln!(
        "| n | +x before | +x after | +x kinetic | partitions | no x before | no x after | no x kinetic |"
    );
    eprintln!("|---|---|---|---|---|---|---|---|");
    let mut series: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 2 * SWEEPS.len()];
    let ns0 = [16, 32, 64, 128, 256];
    for n in ns0 {
        let ivs = scene(n, true, n as u64);
        let mut row = format!("| {n} |");
        for (k, x) in [true, false].into_iter().enumerate() {
            let s = Settings::transparent()
                .with_threshold(0.0)
                .with_intersections(x);
            for (j, (_, sweep)) in SWEEPS.into_iter().enumerate() {
                let mut r = Resolver::new(s.clone()).with_sweep(sweep);
                let t = time_per_call(budget, || {
                    black_box(r.resolve(black_box(&ivs), &Flat).unwrap());
                });
                series[SWEEPS.len() * k + j].push((n as f64, t));
                row += &format!(" {:.1} |", t * 1e6);
                if x && j + 1 == SWEEPS.len() {
                    let mut parts = 0;
                    r.resolve_partitions(&ivs, &Flat, |_| parts += 1).unwrap();
                    row += &format!(" {parts} |");
                }
            }
        }
        eprintln!("{row}");
    }
    let e: Vec<String> = series
        .iter()
        .map(|s| format!("{:.2}", exponent(s)))
        .collect();
    eprintln!(
        "| exponent n=16..256 | {} | {} | {} | | {} | {} | {} |",
        e[0], e[1], e[2], e[3], e[4], e[5]
    );
}

fn threshold_table() {
    eprintln!(
        "\n## early termination: threshold vs error (max channel over 64 pixels, vs threshold 0) and time"
    );
    eprintln!(
        "| threshold | sparse n=256 error | sparse µs/pixel | dense n=256 error | dense µs/pixel |"
    );
    eprintln!("|---|---|---|---|---|");
    let pixels: Vec<Vec<Vec<Flat64>>> = [false, true]
        .iter()
        .map(|&d| (0..64).map(|i| scene(256, d, 1000 + i)).collect())
        .collect();
    let exact: Vec<Vec<Rgba<f64>>> = pixels
        .iter()
        .map(|ps| {
            let mut r = Resolver::new(Settings::transparent().with_threshold(0.0));
            ps.iter().map(|p| r.resolve(p, &Flat).unwrap()).collect()
        })
        .collect();
    for th in [0.0, 1e-6, 1e-4, 1e-2, 1e-1] {
        let mut row = format!("| {th:e} |");
        for (ps, ex) in pixels.iter().zip(&exact) {
            let mut r = Resolver::new(Settings::transparent().with_threshold(th));
            let err = ps
                .iter()
                .zip(ex)
                .map(|(p, e)| max_diff(r.resolve(p, &Flat).unwrap(), *e))
                .fold(0.0, f64::max);
            let t = time_per_call(Duration::from_millis(100), || {
                for p in ps {
                    black_box(r.resolve(black_box(p), &Flat).unwrap());
                }
            }) / ps.len() as f64;
            row += &format!(" {err:.2e} | {:.2} |", t * 1e6);
        }
        eprintln!("{row}");
    }
    eprintln!(
        "\n## intersection handling off: error vs handling on (exact), 64 sparse pixels, n=64"
    );
    let ps: Vec<_> = (0..64).map(|i| scene(64, false, 2000 + i)).collect();
    for (name, on) in [
        ("opaque", Settings::opaque()),
        ("transparent", Settings::transparent()),
    ] {
        let off = on.clone().with_intersections(false);
        let (mut a, mut b) = (Resolver::new(on.clone()), Resolver::new(off));
        let err = ps
            .iter()
            .map(|p| max_diff(a.resolve(p, &Flat).unwrap(), b.resolve(p, &Flat).unwrap()))
            .fold(0.0, f64::max);
        let ref_err = ps
            .iter()
            .map(|p| {
                max_diff(
                    a.resolve(p, &Flat).unwrap(),
                    brute_force(p, &Flat, &on, 1 << 14),
                )
            })
            .fold(0.0, f64::max);
        eprintln!(
            "| {name} | max error off vs on {err:.3} | on vs brute force (16384 samples) {ref_err:.1e} |"
        );
    }
}

/// `n` textured intervals whose UV moves ~`texels` texels of a 64 × 64 texture.
fn textured_scene(n: usize, texels: f64, seed: u64) -> Vec<Interval<f64, Textured<f64>>> {
    scene(n, false, seed)
        .into_iter()
        .enumerate()
        .map(|(i, iv)| {
            let mut rng = Pcg64Mcg::seed_from_u64(seed * 31 + i as u64);
            let u: f64 = rng.random_range(0.0..1.0);
            let v: f64 = rng.random_range(0.0..1.0);
            let ang: f64 = rng.random_range(0.0..std::f64::consts::TAU);
            let d = texels / 64.0;
            iv.with_payload(Textured {
                uv_start: [u, v],
                uv_end: [u + d * ang.cos(), v + d * ang.sin()],
                material: 0,
                alpha: iv.payload.a,
            })
        })
        .collect()
}

fn texture() -> BilinearTexture<f64> {
    let mut rng = Pcg64Mcg::seed_from_u64(64);
    let texels: Vec<_> = (0..64 * 64)
        .map(|_| {
            Rgba::opaque(
                rng.random_range(0.0..1.0),
                rng.random_range(0.0..1.0),
                rng.random_range(0.0..1.0),
            )
        })
        .collect();
    BilinearTexture::new(64, 64, &texels).unwrap()
}

fn texture_table() {
    let tex = [texture()];
    eprintln!(
        "\n## texture filtering: taps vs exact bilinear segment integral (n=16 intervals, 64 pixels)"
    );
    eprintln!(
        "| filter | UV motion 4 texels: max error | µs/pixel | UV motion 32 texels: max error | µs/pixel |"
    );
    eprintln!("|---|---|---|---|---|");
    let scenes: Vec<Vec<_>> = [4.0, 32.0]
        .iter()
        .map(|&m| (0..64).map(|i| textured_scene(16, m, 3000 + i)).collect())
        .collect();
    let s = Settings::transparent();
    let exact = ExactFilter::new(&tex[..]);
    let truth: Vec<Vec<Rgba<f64>>> = scenes
        .iter()
        .map(|ps| {
            let mut r = Resolver::new(s.clone());
            ps.iter().map(|p| r.resolve(p, &exact).unwrap()).collect()
        })
        .collect();
    let row = |name: String, shader: &TexturedResolve<'_>| {
        let mut line = format!("| {name} |");
        for (ps, tr) in scenes.iter().zip(&truth) {
            let mut r = Resolver::new(s.clone());
            let err = ps
                .iter()
                .zip(tr)
                .map(|(p, t)| max_diff(shader(p, &mut r), *t))
                .fold(0.0, f64::max);
            let t = time_per_call(Duration::from_millis(100), || {
                for p in ps {
                    black_box(shader(black_box(p), &mut r));
                }
            }) / ps.len() as f64;
            line += &format!(" {err:.2e} | {:.2} |", t * 1e6);
        }
        eprintln!("{line}");
    };
    for taps in [1, 2, 4, 8, 16, 32, 64] {
        let f = TapFilter::new(&tex[..], taps);
        row(format!("{taps} taps"), &|p, r| r.resolve(p, &f).unwrap());
    }
    row("exact".into(), &|p, r| r.resolve(p, &exact).unwrap());
    // The exact filter itself against dense time sampling of the texture.
    let p = &scenes[1][0];
    let e = max_diff(
        Resolver::new(s.clone()).resolve(p, &exact).unwrap(),
        brute_force(p, &exact, &s, 1 << 16),
    );
    eprintln!("| exact vs brute force (65536 time samples, 32 texels) | {e:.1e} | | | |");
}

/// All tables; `RESOLVE_TABLES=growth` prints only the n-scaling tables.
fn tables() {
    growth_table();
    if std::env::var("RESOLVE_TABLES").is_ok_and(|v| v == "growth") {
        return;
    }
    threshold_table();
    texture_table();
    eprintln!();
}

fn bench_growth(c: &mut Criterion) {
    tables();
    let mut g = c.benchmark_group("resolve_pixel_sparse");
    for n in [1, 16, 256, 1024] {
        let ivs = scene(n, false, n as u64);
        for (name, s) in configs() {
            let mut r = Resolver::new(s);
            g.bench_with_input(BenchmarkId::new(name, n), &ivs, |b, ivs| {
                b.iter(|| r.resolve(black_box(ivs), &Flat).unwrap())
            });
        }
    }
    g.finish();
    let mut g = c.benchmark_group("resolve_pixel_dense");
    for n in [16, 256, 1024] {
        let ivs = scene(n, true, n as u64);
        for (name, s) in configs() {
            let mut r = Resolver::new(s);
            g.bench_with_input(BenchmarkId::new(name, n), &ivs, |b, ivs| {
                b.iter(|| r.resolve(black_box(ivs), &Flat).unwrap())
            });
        }
    }
    g.finish();
}

fn shade_textured<S: Shader<f64, Textured<f64>>>(
    r: &mut Resolver<f64>,
    ps: &[Vec<Interval<f64, Textured<f64>>>],
    s: &S,
) {
    for p in ps {
        black_box(r.resolve(black_box(p), s).unwrap());
    }
}

fn bench_texture(c: &mut Criterion) {
    let tex = [texture()];
    let ps: Vec<_> = (0..16)
        .map(|i| textured_scene(16, 32.0, 3000 + i))
        .collect();
    let mut g = c.benchmark_group("texture_16_pixels_32_texels");
    let mut r = Resolver::new(Settings::transparent());
    for taps in [1, 8, 64] {
        let f = TapFilter::new(&tex[..], taps);
        g.bench_function(BenchmarkId::new("taps", taps), |b| {
            b.iter(|| shade_textured(&mut r, &ps, &f))
        });
    }
    let e = ExactFilter::new(&tex[..]);
    g.bench_function("exact", |b| b.iter(|| shade_textured(&mut r, &ps, &e)));
    g.finish();
}

criterion_group!(benches, bench_growth, bench_texture);
criterion_main!(benches);
