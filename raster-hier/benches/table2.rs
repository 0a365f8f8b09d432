//! Munkberg 2011, Table 2 on synthetic scenes: sample tests, tile tests and the arithmetic
//! estimate of each traversal at motion 0.25x, 1x, 2x, 4x the triangle size (printed once,
//! with each traversal's coverage difference against BBOX — always 0), then timed; plus
//! triangles per second at 16 spp for a 1000-triangle scene on 1 and 2 threads.
//!
//! `cargo bench -p raster-hier --bench table2 -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use raster_hier::{
    Counters, EdgeTest, RasterConfig, SampleBuffer, Traversal, benchmark_scene, rasterise,
};

const W: u32 = 256;
const H: u32 = 256;
const SPP: u32 = 16;
const TRIANGLES: usize = 400;
const SIZE: f64 = 16.0;

const TRAVERSALS: [(&str, Traversal); 7] = [
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

fn table2(c: &mut Criterion) {
    for motion in [0.25, 1.0, 2.0, 4.0] {
        let tris = benchmark_scene::<f32>(TRIANGLES, SIZE, motion, W, H, 2011);
        let (reference, _) = run(&tris, Traversal::Bbox);
        eprintln!("\nmotion {motion}x ({TRIANGLES} triangles of {SIZE} px, {W}x{H}, {SPP} spp)");
        eprintln!(
            "{:<22} {:>12} {:>10} {:>12} {:>10} {:>14} {:>10}",
            "traversal",
            "sample tests",
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
                "{name:<22} {:>12} {:>10} {:>12} {:>10} {:>14} {:>10}",
                k.sample_tests, k.tile_tests, k.depth_tests, k.zmax_culls, k.arithmetic, diff
            );
        }
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

fn throughput(c: &mut Criterion) {
    let tris = benchmark_scene::<f32>(1000, SIZE, 1.0, 512, 512, 7);
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
