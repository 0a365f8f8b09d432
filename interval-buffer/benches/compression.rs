//! Compression error vs K (paper's oracle vs our variants) and insert throughput.
//!
//! Before timing, prints the resolved-colour error of each K and oracle against the
//! uncompressed list (brute-force reference resolve, 4096 samples), with bytes per pixel.

use std::hint::black_box;
use std::time::Instant;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};

use interval_buffer::{
    BoundedBuffer, CompactInterval8, CompactInterval16, Insertion, Interval, Oracle, Rgba,
};

#[path = "../tests/common/mod.rs"]
mod common;

type Iv32 = Interval<f32, Rgba<f32>>;

const BG: [f64; 3] = [0.0, 0.0, 0.0];
const SAMPLES: usize = 4096;

fn to32(l: &[common::Iv]) -> Vec<Iv32> {
    l.iter()
        .map(|i| {
            let p = i.payload;
            Interval::new(
                i.ts as f32,
                i.te as f32,
                i.z as f32,
                i.k as f32,
                Rgba::new(p.r as f32, p.g as f32, p.b as f32, p.a as f32),
            )
        })
        .collect()
}

/// Recorded per-pixel workloads: (name, pixel lists).
fn workloads() -> Vec<(&'static str, Vec<Vec<Iv32>>)> {
    let mut r = common::rng(6);
    let meshes = (0..1500)
        .map(|_| to32(&common::moving_meshes(&mut r)))
        .collect();
    let random = (0..1500)
        .map(|_| to32(&common::random_intervals(&mut r, 40)))
        .collect();
    let fence = [8, 12, 16, 20, 24, 32, 40]
        .iter()
        .flat_map(|&p| {
            let bg = Rgba::opaque(0.4, 0.3, 0.2);
            let f = common::fence(p, bg);
            let mut rev = f.clone();
            rev.rotate_left(1); // background inserted last
            [to32(&f), to32(&rev)]
        })
        .collect();
    vec![("meshes", meshes), ("random", random), ("fence", fence)]
}

/// (label, insertion): the paper's oracle with and without the opaque Fig. 7
/// optimisations, and our coverage-preserving merge.
fn configs() -> Vec<(&'static str, Insertion<f32>)> {
    let p = Oracle::<f32>::paper();
    vec![
        (
            "paper",
            Insertion {
                oracle: p,
                opaque: true,
            },
        ),
        (
            "paper, no Fig. 7 opts",
            Insertion {
                oracle: p,
                opaque: false,
            },
        ),
        (
            "coverage (ours)",
            Insertion {
                oracle: p.with_keep_coverage(true),
                opaque: true,
            },
        ),
    ]
}

fn fill(lists: &[Vec<Iv32>], k: usize, how: Insertion<f32>) -> BoundedBuffer<f32, Rgba<f32>> {
    let mut buf = BoundedBuffer::new(lists.len(), 1, k, how).expect("buffer");
    for (x, l) in lists.iter().enumerate() {
        for iv in l {
            buf.insert(x, 0, *iv).expect("insert");
        }
    }
    buf
}

fn error_table() {
    eprintln!(
        "| workload | K | oracle | mean err | max err | bytes/px | ns/interval (best of 3) |"
    );
    eprintln!("|---|---|---|---|---|---|---|");
    for (name, lists) in workloads() {
        let refs: Vec<[f64; 3]> = lists
            .iter()
            .map(|l| common::resolve_blend(l, BG, SAMPLES))
            .collect();
        let n: usize = lists.iter().map(Vec::len).sum();
        for k in [4, 8, 16, 64] {
            for (oname, how) in configs() {
                let mut ns = f64::INFINITY;
                let mut buf = None;
                for _ in 0..3 {
                    let t0 = Instant::now();
                    let b = black_box(fill(&lists, k, how));
                    ns = ns.min(t0.elapsed().as_nanos() as f64 / n as f64);
                    buf = Some(b);
                }
                let Some(buf) = buf else { continue };
                let errs: Vec<f64> = (0..lists.len())
                    .map(|x| {
                        common::colour_error(
                            common::resolve_blend(buf.pixel(x, 0), BG, SAMPLES),
                            refs[x],
                        )
                    })
                    .collect();
                let mean = errs.iter().sum::<f64>() / errs.len() as f64;
                let max = errs.iter().copied().fold(0.0, f64::max);
                eprintln!(
                    "| {name} | {k} | {oname} | {mean:.5} | {max:.4} | {} | {ns:.0} |",
                    buf.bytes_per_pixel()
                );
            }
        }
    }
}

/// Memory vs accuracy of the compact storage form on the uncompressed lists.
fn compact_table() {
    eprintln!("| workload | storage | bytes/interval | mean err | max err |");
    eprintln!("|---|---|---|---|---|");
    for (name, lists) in workloads() {
        let refs: Vec<[f64; 3]> = lists
            .iter()
            .map(|l| common::resolve_blend(l, BG, SAMPLES))
            .collect();
        let row = |label: &str, bytes: usize, conv: &dyn Fn(&Iv32) -> Iv32| {
            let errs: Vec<f64> = lists
                .iter()
                .zip(&refs)
                .map(|(l, r)| {
                    let c: Vec<Iv32> = l.iter().map(conv).collect();
                    common::colour_error(common::resolve_blend(&c, BG, SAMPLES), *r)
                })
                .collect();
            let mean = errs.iter().sum::<f64>() / errs.len() as f64;
            let max = errs.iter().copied().fold(0.0, f64::max);
            eprintln!("| {name} | {label} | {bytes} | {mean:.6} | {max:.5} |");
        };
        row("full f32", size_of::<Iv32>(), &|i| *i);
        row("compact u16 times", CompactInterval16::BYTES, &|i| {
            CompactInterval16::from_interval(i).map_or(*i, |c| c.to_interval())
        });
        row("compact u8 times (Gribel)", CompactInterval8::BYTES, &|i| {
            CompactInterval8::from_interval(i).map_or(*i, |c| c.to_interval())
        });
    }
}

fn bench(c: &mut Criterion) {
    error_table();
    compact_table();
    let loads = workloads();
    let mut g = c.benchmark_group("compress_k8");
    for (name, lists) in &loads {
        let n: usize = lists.iter().map(Vec::len).sum();
        g.throughput(Throughput::Elements(n as u64));
        for (oname, how) in configs() {
            let id = format!("{name}_{}", oname.replace([' ', ',', '.', '(', ')'], ""));
            g.bench_function(id, |b| b.iter(|| black_box(fill(lists, 8, how))));
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
