//! Munkberg 2011, Table 2 on synthetic scenes: sample tests, tile tests and the arithmetic
//! estimate of each traversal at motion 0.25x, 1x, 2x, 4x the triangle size (printed once,
//! with each traversal's coverage difference against BBOX — always 0), also with traversal
//! levels below the 4x4 pattern tile (→ 2x2 quads, → pixels) and the single-interval oracle
//! floors per 4x4, 2x2 and 1x1 cell; then timed (interleaved wall-time rounds, 1-thread CPU
//! time ratios, criterion); plus triangles per second at 16 spp for a 1000-triangle scene
//! on 1 and 2 threads.
//!
//! `cargo bench -p raster-hier --bench table2 -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use raster_hier::{
    Counters, EdgeTest, RasterConfig, SampleBuffer, Traversal, benchmark_scene, covered,
    frustum_interval, rasterise, screen_bound,
};

const W: u32 = 256;
const H: u32 = 256;
const SPP: u32 = 16;
const TRIANGLES: usize = 400;
const SIZE: f64 = 16.0;

/// The traversals at the paper's levels 16 → 8 → 4 (4x4 = the sample-pattern tile).
const TRAVERSALS: [(&str, Traversal); 9] = [
    ("BBOX", Traversal::Bbox),
    ("CONVEX", Traversal::Convex),
    (
        "OUR lin (γ setup)",
        Traversal::Our(EdgeTest::LinearisedSetup),
    ),
    (
        "OUR lin (γ per tile)",
        Traversal::Our(EdgeTest::LinearisedPerTile),
    ),
    ("OUR exact", Traversal::Our(EdgeTest::Exact)),
    (
        "OUR lin per level",
        Traversal::Our(EdgeTest::LinearisedPerLevel),
    ),
    ("OUR exact at 4x4", Traversal::Our(EdgeTest::ExactFinest)),
    ("INTERLEAVE", Traversal::Interleave),
    (
        "OUR lin + fallback",
        Traversal::OurFallback(EdgeTest::LinearisedSetup),
    ),
];

/// The best edge tests with levels below the 4x4 pattern tile: each 2x2 quad, or each
/// pixel, gets its own tile test and interval (same pattern, same image); the last number
/// is `RasterConfig::sub_tile_min_samples` (0: always split the pattern tile).
const FINE: [(&str, Traversal, &[u32], u32); 5] = [
    (
        "OUR lin per level ↓2",
        Traversal::Our(EdgeTest::LinearisedPerLevel),
        &[16, 8, 4, 2],
        0,
    ),
    (
        "OUR exact at 2x2",
        Traversal::Our(EdgeTest::ExactFinest),
        &[16, 8, 4, 2],
        0,
    ),
    (
        "OUR lin per level ↓1",
        Traversal::Our(EdgeTest::LinearisedPerLevel),
        &[16, 8, 4, 2, 1],
        0,
    ),
    (
        "OUR lin ↓1 split ≥ 2",
        Traversal::Our(EdgeTest::LinearisedPerLevel),
        &[16, 8, 4, 2, 1],
        2,
    ),
    (
        "OUR exact at 1x1",
        Traversal::Our(EdgeTest::ExactFinest),
        &[16, 8, 4, 2, 1],
        0,
    ),
];

/// Every configuration of the table: name and frame settings.
fn configs() -> Vec<(&'static str, RasterConfig)> {
    let mut v: Vec<_> = TRAVERSALS
        .iter()
        .map(|&(name, tr)| (name, RasterConfig::new(tr)))
        .collect();
    for (name, tr, levels, min) in FINE {
        let mut cfg = RasterConfig::new(tr);
        cfg.levels = levels.to_vec();
        cfg.sub_tile_min_samples = min;
        v.push((name, cfg));
    }
    v
}

fn buffer() -> SampleBuffer<f32> {
    SampleBuffer::new(W, H, SPP, 4, 16, 4, 1).expect("valid buffer")
}

fn run(
    tris: &[raster_hier::RasterTriangle<f32>],
    cfg: &RasterConfig,
) -> (SampleBuffer<f32>, Counters) {
    let mut buf = buffer();
    let c = rasterise(&mut buf, tris, cfg).expect("valid config");
    (buf, c)
}

/// The floor for any traversal that gives each `cell` x `cell` pixel tile (4: the pattern
/// tile; 2: a quad; 1: a pixel) one time interval: per triangle and cell in its screen
/// bound, the cell's samples whose time index lies between the first and the last covered
/// sample of that cell (an oracle that knows the coverage; no z-max culling).
fn single_interval_floor(tris: &[raster_hier::RasterTriangle<f32>], cell_px: u32) -> u64 {
    let buf = buffer();
    let tiles_x = W / cell_px;
    let tiles = (tiles_x * (H / cell_px)) as usize;
    let mut per_tile: Vec<Vec<(f32, f32, f32)>> = vec![Vec::new(); tiles];
    // Samples arrive per 4x4 pattern tile in time order, so each cell's list is time-sorted.
    buf.for_each_sample(|px, py, x, y, t, _, _| {
        per_tile[((py / cell_px) * tiles_x + px / cell_px) as usize].push((x, y, t));
    });
    let (wf, hf) = (W as f32, H as f32);
    let mut total = 0u64;
    for tri in tris {
        let (q, r) = (tri.triangle.q, tri.triangle.r);
        let setup = tri.triangle.setup();
        let frustum = frustum_interval(&q, &r, wf, hf);
        let rect = screen_bound(&q, &r, frustum, wf, hf).rect;
        if !setup.is_valid() || frustum.is_empty() || rect.is_empty() {
            continue;
        }
        let all_w = q.iter().chain(r.iter()).all(|v| v[2] > 0.0);
        let cell = |v: f32, n: u32| ((v.max(0.0) / cell_px as f32) as u32).min(n - 1);
        for ty in cell(rect.y0, H / cell_px)..=cell(rect.y1, H / cell_px) {
            for tx in cell(rect.x0, tiles_x)..=cell(rect.x1, tiles_x) {
                let samples = &per_tile[(ty * tiles_x + tx) as usize];
                let hit = |&(x, y, t): &(f32, f32, f32)| covered(&setup, all_w, x, y, t);
                if let (Some(a), Some(b)) =
                    (samples.iter().position(hit), samples.iter().rposition(hit))
                {
                    total += (b - a + 1) as u64;
                }
            }
        }
    }
    total
}

/// Side-by-side frame times on a shared machine: rounds run every traversal once in turn
/// (buffer clear excluded), so all see the same load; prints each traversal's minimum and
/// median over the rounds, its median per-round time relative to CONVEX and its minimum relative
/// to CONVEX's minimum (the least disturbed runs).
fn report_times(tris: &[raster_hier::RasterTriangle<f32>]) {
    use std::time::Instant;
    const ROUNDS: usize = 15;
    let mut buf = buffer();
    let configs = configs();
    let mut t = vec![Vec::new(); configs.len()];
    let mut rel = vec![Vec::new(); configs.len()];
    let convex = configs
        .iter()
        .position(|(_, cfg)| cfg.traversal == Traversal::Convex)
        .unwrap_or(0);
    for _ in 0..ROUNDS {
        let mut round = Vec::new();
        for (_, cfg) in &configs {
            buf.clear();
            let t0 = Instant::now();
            black_box(rasterise(&mut buf, black_box(tris), cfg).expect("valid"));
            round.push(t0.elapsed().as_secs_f64());
        }
        for (i, v) in round.iter().enumerate() {
            t[i].push(*v);
            rel[i].push(v / round[convex]);
        }
    }
    eprintln!(
        "{:<22} {:>9} {:>12} {:>16} {:>13}",
        "traversal", "min ms", "median ms", "median / CONVEX", "min / CONVEX"
    );
    for i in 0..configs.len() {
        t[i].sort_by(f64::total_cmp);
        rel[i].sort_by(f64::total_cmp);
    }
    for (i, (name, _)) in configs.iter().enumerate() {
        eprintln!(
            "{name:<22} {:>9.2} {:>12.2} {:>16.3} {:>13.3}",
            t[i][0] * 1e3,
            t[i][ROUNDS / 2] * 1e3,
            rel[i][ROUNDS / 2],
            t[i][0] / t[convex][0]
        );
    }
}

/// Process CPU time per frame on a 1-thread pool, interleaved in rounds (each round renders
/// `FRAMES` frames with every configuration in turn): on a loaded machine CPU time is much
/// less disturbed by other processes than wall time. `/proc/self/stat` ticks are 10 ms, so
/// each configuration accumulates ≥ 1.5 s of frames. Prints CPU ms per frame and the ratio
/// to CONVEX; skipped where `/proc/self/stat` is missing.
fn report_cpu(tris: &[raster_hier::RasterTriangle<f32>]) {
    const ROUNDS: usize = 4;
    const FRAMES: usize = 12;
    if process_cpu_seconds().is_none() {
        return;
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    let configs: Vec<_> = configs()
        .into_iter()
        .filter(|(name, _)| {
            matches!(
                *name,
                "CONVEX"
                    | "OUR lin per level"
                    | "OUR lin per level ↓2"
                    | "OUR lin per level ↓1"
                    | "OUR lin ↓1 split ≥ 2"
            )
        })
        .collect();
    let mut cpu = vec![0.0f64; configs.len()];
    let mut buf = buffer();
    pool.install(|| {
        for _ in 0..ROUNDS {
            for (i, (_, cfg)) in configs.iter().enumerate() {
                let c0 = process_cpu_seconds().unwrap_or(0.0);
                for _ in 0..FRAMES {
                    buf.clear();
                    black_box(rasterise(&mut buf, black_box(tris), cfg).expect("valid"));
                }
                cpu[i] += process_cpu_seconds().unwrap_or(0.0) - c0;
            }
        }
    });
    let frames = (ROUNDS * FRAMES) as f64;
    eprintln!(
        "{:<22} {:>16} {:>14}",
        "1 thread", "CPU ms / frame", "CPU / CONVEX"
    );
    for (i, (name, _)) in configs.iter().enumerate() {
        eprintln!(
            "{name:<22} {:>16.2} {:>14.3}",
            cpu[i] / frames * 1e3,
            cpu[i] / cpu[0]
        );
    }
}

fn table2(c: &mut Criterion) {
    for motion in [0.25, 1.0, 2.0, 4.0] {
        let tris = benchmark_scene::<f32>(TRIANGLES, SIZE, motion, W, H, 2011);
        let (reference, _) = run(&tris, &RasterConfig::new(Traversal::Bbox));
        let (_, convex) = run(&tris, &RasterConfig::new(Traversal::Convex));
        eprintln!("\nmotion {motion}x ({TRIANGLES} triangles of {SIZE} px, {W}x{H}, {SPP} spp)");
        eprintln!(
            "{:<22} {:>12} {:>9} {:>10} {:>12} {:>10} {:>14} {:>10}",
            "traversal",
            "sample tests",
            "/CONVEX",
            "tile tests",
            "depth tests",
            "z-max culls",
            "arithmetic",
            "diff vs BBOX"
        );
        for (name, cfg) in configs() {
            let (buf, k) = run(&tris, &cfg);
            let diff = buf
                .ids()
                .iter()
                .zip(reference.ids())
                .zip(buf.depths().iter().zip(reference.depths()))
                .filter(|((a, b), (da, db))| a != b || da.to_bits() != db.to_bits())
                .count();
            eprintln!(
                "{name:<22} {:>12} {:>9.3} {:>10} {:>12} {:>10} {:>14} {:>10}",
                k.sample_tests,
                k.sample_tests as f64 / convex.sample_tests as f64,
                k.tile_tests,
                k.depth_tests,
                k.zmax_culls,
                k.arithmetic,
                diff
            );
        }
        for cell in [4, 2, 1] {
            let floor = single_interval_floor(&tris, cell);
            eprintln!(
                "{:<22} {floor:>12} {:>9.3}   (one exact interval per {cell}x{cell} tile, no z-max culling)",
                format!("floor {cell}x{cell}"),
                floor as f64 / convex.sample_tests as f64
            );
        }
        report_times(&tris);
        report_cpu(&tris);
        let mut g = c.benchmark_group(format!("table2/motion_{motion}x"));
        g.sample_size(10);
        for (name, cfg) in configs() {
            let mut buf = buffer();
            g.bench_function(name, |b| {
                b.iter(|| {
                    buf.clear();
                    black_box(rasterise(&mut buf, black_box(&tris), &cfg).expect("valid"))
                })
            });
        }
        g.finish();
    }
}

/// utime + stime of this process in seconds (Linux `/proc/self/stat`, clock ticks of 10 ms);
/// `None` elsewhere.
fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the parenthesised command name; utime and stime are fields 14 and 15.
    let rest = stat.rsplit_once(')')?.1;
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// Wall time and process CPU time per frame on 1 and 2 threads, interleaved in rounds so
/// both see the same machine load, with the frame split into the buffer clear (serial) and
/// `rasterise` (parallel). CPU/wall shows how much of a second core the run actually got;
/// CPU per frame on 2 vs 1 threads shows the extra work of the parallel path.
fn report_parallel(tris: &[raster_hier::RasterTriangle<f32>]) {
    use std::time::Instant;
    let cfg = RasterConfig::new(Traversal::Our(EdgeTest::LinearisedSetup));
    let pools: Vec<_> = [1usize, 2]
        .iter()
        .map(|&n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .expect("pool")
        })
        .collect();
    let mut buf = SampleBuffer::<f32>::new(512, 512, 16, 4, 16, 4, 1).expect("valid");
    const ROUNDS: usize = 6;
    const FRAMES: usize = 4;
    let mut wall = [Vec::new(), Vec::new()];
    let mut cpu = [0.0f64; 2];
    let mut clear = Vec::new();
    for _ in 0..ROUNDS {
        for (i, pool) in pools.iter().enumerate() {
            let c0 = process_cpu_seconds().unwrap_or(0.0);
            let t0 = Instant::now();
            for _ in 0..FRAMES {
                let tc = Instant::now();
                buf.clear();
                clear.push(tc.elapsed().as_secs_f64());
                pool.install(|| {
                    black_box(rasterise(&mut buf, black_box(tris), &cfg).expect("valid"))
                });
            }
            wall[i].push(t0.elapsed().as_secs_f64() / FRAMES as f64);
            cpu[i] += process_cpu_seconds().unwrap_or(0.0) - c0;
        }
    }
    let med = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (w1, w2) = (med(&mut wall[0]), med(&mut wall[1]));
    let frames = (ROUNDS * FRAMES) as f64;
    let clear_ms = med(&mut clear) * 1e3;
    eprintln!(
        "\n== 1000 triangles, 512x512, 16 spp, OUR lin: 1 vs 2 threads ({ROUNDS} interleaved rounds of {FRAMES} frames) =="
    );
    eprintln!("threads  wall ms/frame (median)  CPU ms/frame  CPU/wall");
    for (i, w) in [w1, w2].iter().enumerate() {
        let c = cpu[i] / frames;
        eprintln!(
            "{:>7} {:>23.1} {:>13.1} {:>9.2}",
            i + 1,
            w * 1e3,
            c * 1e3,
            c / w
        );
    }
    eprintln!(
        "speed-up (wall) {:.2}; CPU work 2 threads / 1 thread {:.2}; serial buffer clear {clear_ms:.1} ms/frame",
        w1 / w2,
        cpu[1] / cpu[0]
    );
}

fn throughput(c: &mut Criterion) {
    let tris = benchmark_scene::<f32>(1000, SIZE, 1.0, 512, 512, 7);
    report_parallel(&tris);
    let mut g = c.benchmark_group("throughput_1000_tris_16spp");
    g.sample_size(10);
    g.throughput(Throughput::Elements(tris.len() as u64));
    for threads in [1usize, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        let cfg = RasterConfig::new(Traversal::Our(EdgeTest::LinearisedSetup));
        let mut buf = SampleBuffer::<f32>::new(512, 512, 16, 4, 16, 4, 1).expect("valid");
        g.bench_function(format!("OUR lin, {threads} thread(s)"), |b| {
            b.iter(|| {
                pool.install(|| {
                    buf.clear();
                    black_box(rasterise(&mut buf, black_box(&tris), &cfg).expect("valid"))
                })
            })
        });
    }
    g.finish();
}

criterion_group!(benches, table2, throughput);
criterion_main!(benches);
