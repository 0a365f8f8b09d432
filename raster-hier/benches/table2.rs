//! Munkberg 2011, Table 2 on synthetic scenes: sample tests, tile tests and the arithmetic
//! estimate of each traversal at motion 0.25x, 1x, 2x, 4x the triangle size (printed once,
//! with each traversal's coverage difference against BBOX — always 0), then timed; plus
//! triangles per second at 16 spp for a 1000-triangle scene on 1 and 2 threads.
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

fn buffer() -> SampleBuffer<f32> {
    SampleBuffer::new(W, H, SPP, 4, 16, 4, 1).expect("valid buffer")
}

fn run(tris: &[raster_hier::RasterTriangle<f32>], tr: Traversal) -> (SampleBuffer<f32>, Counters) {
    let mut buf = buffer();
    let c = rasterise(&mut buf, tris, &RasterConfig::new(tr)).expect("valid config");
    (buf, c)
}

/// The floor for any traversal that gives each 4x4 tile one time interval: per triangle and
/// finest tile in its screen bound, the samples whose time index lies between the first and
/// the last covered sample of that tile (an oracle that knows the coverage; no z-max culling).
fn single_interval_floor(tris: &[raster_hier::RasterTriangle<f32>]) -> u64 {
    let buf = buffer();
    let tiles_x = W / 4;
    let tiles = (tiles_x * (H / 4)) as usize;
    let mut per_tile: Vec<Vec<(f32, f32, f32)>> = vec![Vec::new(); tiles];
    buf.for_each_sample(|px, py, x, y, t, _, _| {
        per_tile[((py / 4) * tiles_x + px / 4) as usize].push((x, y, t));
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
        let cell = |v: f32, n: u32| ((v.max(0.0) / 4.0) as u32).min(n - 1);
        for ty in cell(rect.y0, H / 4)..=cell(rect.y1, H / 4) {
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
/// median over the rounds and its median per-round time relative to CONVEX.
fn report_times(tris: &[raster_hier::RasterTriangle<f32>]) {
    use std::time::Instant;
    const ROUNDS: usize = 9;
    let mut buf = buffer();
    let mut t = vec![Vec::new(); TRAVERSALS.len()];
    let mut rel = vec![Vec::new(); TRAVERSALS.len()];
    let convex = TRAVERSALS
        .iter()
        .position(|(_, tr)| *tr == Traversal::Convex)
        .unwrap_or(0);
    for _ in 0..ROUNDS {
        let mut round = Vec::new();
        for (_, tr) in TRAVERSALS {
            let cfg = RasterConfig::new(tr);
            buf.clear();
            let t0 = Instant::now();
            black_box(rasterise(&mut buf, black_box(tris), &cfg).expect("valid"));
            round.push(t0.elapsed().as_secs_f64());
        }
        for (i, v) in round.iter().enumerate() {
            t[i].push(*v);
            rel[i].push(v / round[convex]);
        }
    }
    eprintln!(
        "{:<22} {:>9} {:>12} {:>16}",
        "traversal", "min ms", "median ms", "median / CONVEX"
    );
    for (i, (name, _)) in TRAVERSALS.iter().enumerate() {
        t[i].sort_by(f64::total_cmp);
        rel[i].sort_by(f64::total_cmp);
        eprintln!(
            "{name:<22} {:>9.2} {:>12.2} {:>16.3}",
            t[i][0] * 1e3,
            t[i][ROUNDS / 2] * 1e3,
            rel[i][ROUNDS / 2]
        );
    }
}

fn table2(c: &mut Criterion) {
    for motion in [0.25, 1.0, 2.0, 4.0] {
        let tris = benchmark_scene::<f32>(TRIANGLES, SIZE, motion, W, H, 2011);
        let (reference, _) = run(&tris, Traversal::Bbox);
        let (_, convex) = run(&tris, Traversal::Convex);
        let floor = single_interval_floor(&tris);
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
        for (name, tr) in TRAVERSALS {
            let (buf, k) = run(&tris, tr);
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
        eprintln!(
            "{:<22} {floor:>12} {:>9.3}   (one exact interval per 4x4 tile, no z-max culling)",
            "single-interval floor",
            floor as f64 / convex.sample_tests as f64
        );
        report_times(&tris);
        let mut g = c.benchmark_group(format!("table2/motion_{motion}x"));
        g.sample_size(10);
        for (name, tr) in TRAVERSALS {
            let cfg = RasterConfig::new(tr);
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
