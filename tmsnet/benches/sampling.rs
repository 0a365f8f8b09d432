//! Benchmarks for tmsnet (Munkberg 2011, §5).
//!
//! 1. Cost per sample: GetXY (checked and unchecked), the incremental range iterator, the
//!    full tile iterator (pixel, offset, time in f32), two u32 from rand's SmallRng, and a
//!    precomputed table lookup — side by side at m = 8 (4x4 pixels x 16 spp) and m = 12.
//! 2. Quality vs cost: star discrepancy of the spatial projection (whole 4x4 tile and mean
//!    per pixel) for the permuted net, the original Grünschloß-Keller ordering and
//!    stratified random sampling at 16, 64 and 256 spp, printed once, next to the timed
//!    generation of the tile's samples.
//!
//! Run: `cargo bench -p tmsnet -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg32;
use tmsnet::quality::{min_distance, star_discrepancy};
use tmsnet::{
    Scramble, TileLayout, TileSampler, TimeOrderedNet, get_xy, get_xy_paper_loop, get_xy_unchecked,
};

fn per_sample(c: &mut Criterion) {
    let mut g = c.benchmark_group("per_sample");
    for m in [8u32, 12] {
        let n = 1u32 << m;
        g.throughput(Throughput::Elements(u64::from(n)));
        g.bench_with_input(BenchmarkId::new("get_xy", m), &m, |b, &m| {
            b.iter(|| {
                let mut acc = 0u32;
                for j in 0..n {
                    let (x, y) = get_xy(black_box(j), m).unwrap_or((0, 0));
                    acc = acc.wrapping_add(x ^ y.rotate_left(7));
                }
                acc
            })
        });
        g.bench_with_input(BenchmarkId::new("get_xy_paper_loop", m), &m, |b, &m| {
            b.iter(|| {
                let mut acc = 0u32;
                for j in 0..n {
                    let (x, y) = get_xy_paper_loop(black_box(j), m);
                    acc = acc.wrapping_add(x ^ y.rotate_left(7));
                }
                acc
            })
        });
        g.bench_with_input(BenchmarkId::new("get_xy_unchecked", m), &m, |b, &m| {
            b.iter(|| {
                let mut acc = 0u32;
                for j in 0..n {
                    let (x, y) = get_xy_unchecked(black_box(j), m);
                    acc = acc.wrapping_add(x ^ y.rotate_left(7));
                }
                acc
            })
        });
        let net = TimeOrderedNet::permuted(m).expect("valid m");
        g.bench_with_input(BenchmarkId::new("incremental_iter", m), &m, |b, _| {
            b.iter(|| {
                let mut acc = 0u32;
                for (_, x, y) in black_box(&net).iter_range(0..n) {
                    acc = acc.wrapping_add(x ^ y.rotate_left(7));
                }
                acc
            })
        });
        let layout = if m == 8 {
            TileLayout::new(4, 4, 16)
        } else {
            TileLayout::new(4, 4, 256)
        }
        .expect("valid layout");
        let tile = TileSampler::new(layout, 3, 5, 7).expect("valid tile");
        g.bench_with_input(BenchmarkId::new("tile_iter_f32", m), &m, |b, _| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for s in black_box(&tile)
                    .samples_in(0.0f32, 1.0)
                    .into_iter()
                    .flatten()
                {
                    acc += s.offset[0] + s.offset[1] + s.t + s.pixel[0] as f32;
                }
                acc
            })
        });
        let mut rng = SmallRng::seed_from_u64(1);
        g.bench_with_input(BenchmarkId::new("small_rng_2xu32", m), &m, |b, _| {
            b.iter(|| {
                let mut acc = 0u32;
                for _ in 0..n {
                    let (x, y) = (rng.next_u32(), rng.next_u32());
                    acc = acc.wrapping_add(x ^ y.rotate_left(7));
                }
                acc
            })
        });
        let table: Vec<(u32, u32)> = (0..n).map(|j| get_xy_unchecked(j, m)).collect();
        g.bench_with_input(BenchmarkId::new("table_lookup", m), &m, |b, _| {
            b.iter(|| {
                let t = black_box(&table);
                let mut acc = 0u32;
                for j in 0..n {
                    let (x, y) = t.get(black_box(j) as usize).copied().unwrap_or((0, 0));
                    acc = acc.wrapping_add(x ^ y.rotate_left(7));
                }
                acc
            })
        });
    }
    g.finish();
}

/// Which sample pattern to generate for a tile.
#[derive(Clone, Copy)]
enum Method {
    Permuted,
    Original,
    Stratified,
}

impl Method {
    fn name(self) -> &'static str {
        match self {
            Method::Permuted => "permuted",
            Method::Original => "original",
            Method::Stratified => "stratified",
        }
    }
}

/// The tile's samples as (x, y, t) with x, y in tile pixel units, written into `out`.
fn generate(method: Method, layout: TileLayout, tile: (u32, u32), out: &mut Vec<[f32; 3]>) {
    out.clear();
    match method {
        Method::Permuted | Method::Original => {
            let net = match method {
                Method::Permuted => TimeOrderedNet::permuted(layout.m()),
                _ => TimeOrderedNet::original(layout.m()),
            };
            let Ok(net) = net else { return };
            let Ok(sampler) =
                TileSampler::with_net(layout, net, Scramble::for_tile(tile.0, tile.1, 7))
            else {
                return;
            };
            if let Ok(it) = sampler.samples_in(0.0f32, 1.0) {
                out.extend(it.map(|s| {
                    let p = s.position();
                    [p[0], p[1], s.t]
                }));
            }
        }
        Method::Stratified => {
            // Per pixel: xy jittered on a 2^a x 2^b grid (a + b = log2 S), t stratified into
            // S strata in random order (Munkberg 2011, Fig. 8 left).
            let s = layout.spp();
            let bits = s.trailing_zeros();
            let (gx, gy) = (1u32 << bits.div_ceil(2), 1u32 << (bits / 2));
            let mut rng = Pcg32::new(u64::from(tile.0) << 32 | u64::from(tile.1), 7);
            let mut strata: Vec<u32> = (0..s).collect();
            let unit = |r: u32| (r >> 8) as f32 * (1.0 / (1u32 << 24) as f32);
            for py in 0..layout.height() {
                for px in 0..layout.width() {
                    for i in (1..s as usize).rev() {
                        let k = (rng.next_u32() % (i as u32 + 1)) as usize;
                        strata.swap(i, k);
                    }
                    for (cell, &st) in strata.iter().enumerate() {
                        let (cx, cy) = (cell as u32 % gx, cell as u32 / gx);
                        let x = px as f32 + (cx as f32 + unit(rng.next_u32())) / gx as f32;
                        let y = py as f32 + (cy as f32 + unit(rng.next_u32())) / gy as f32;
                        let t = (st as f32 + unit(rng.next_u32())) / s as f32;
                        out.push([x, y, t]);
                    }
                }
            }
        }
    }
}

/// Mean star discrepancy over `tiles` tiles: whole tile (scaled to the unit square) and
/// the mean over pixels of each pixel's pattern; mean toroidal min distance per pixel.
fn quality(method: Method, layout: TileLayout, tiles: u32) -> (f64, f64, f64) {
    let (w, h) = (f64::from(layout.width()), f64::from(layout.height()));
    let mut buf = Vec::new();
    let (mut d_tile, mut d_pix, mut md) = (0.0, 0.0, 0.0);
    for k in 0..tiles {
        generate(method, layout, (k * 7 + 1, k * 3 + 2), &mut buf);
        let pts: Vec<[f64; 2]> = buf
            .iter()
            .map(|p| [f64::from(p[0]) / w, f64::from(p[1]) / h])
            .collect();
        d_tile += star_discrepancy(&pts).unwrap_or(f64::NAN);
        let npix = layout.width() * layout.height();
        for pix in 0..npix {
            let (px, py) = (
                f64::from(pix % layout.width()),
                f64::from(pix / layout.width()),
            );
            let local: Vec<[f64; 2]> = buf
                .iter()
                .filter(|p| f64::from(p[0]).floor() == px && f64::from(p[1]).floor() == py)
                .map(|p| [f64::from(p[0]) - px, f64::from(p[1]) - py])
                .collect();
            d_pix += star_discrepancy(&local).unwrap_or(f64::NAN) / f64::from(npix);
            md += min_distance(&local, true).unwrap_or(f64::NAN) / f64::from(npix);
        }
    }
    let t = f64::from(tiles);
    (d_tile / t, d_pix / t, md / t)
}

fn quality_vs_cost(c: &mut Criterion) {
    let methods = [Method::Permuted, Method::Original, Method::Stratified];
    eprintln!("\n4x4-pixel tile, mean over 8 tiles (scrambled per tile / reseeded per tile)");
    eprintln!(
        "{:>11} {:>4} {:>6} {:>12} {:>14} {:>16}",
        "method", "spp", "n", "D*(tile)", "mean D*(pixel)", "mean mindist(px)"
    );
    for spp in [16u32, 64, 256] {
        let layout = TileLayout::new(4, 4, spp).expect("valid layout");
        for method in methods {
            let (dt, dp, md) = quality(method, layout, 8);
            eprintln!(
                "{:>11} {:>4} {:>6} {:>12.5} {:>14.5} {:>16.5}",
                method.name(),
                spp,
                layout.samples(),
                dt,
                dp,
                md
            );
        }
    }
    let mut g = c.benchmark_group("generate_tile");
    for spp in [16u32, 64, 256] {
        let layout = TileLayout::new(4, 4, spp).expect("valid layout");
        g.throughput(Throughput::Elements(u64::from(layout.samples())));
        for method in methods {
            let mut buf = Vec::with_capacity(layout.samples() as usize);
            g.bench_with_input(BenchmarkId::new(method.name(), spp), &spp, |b, _| {
                b.iter(|| {
                    generate(method, black_box(layout), (3, 5), &mut buf);
                    buf.len()
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, per_sample, quality_vs_cost);
criterion_main!(benches);
