//! Insert + compress throughput per interval for K = 4, 8, 16, 64 next to the exact
//! strategy's count / scan / fill / sort, on a 64 x 64 image of moving-mesh pixels.

use std::hint::black_box;

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use interval_buffer::{
    AtomicIntervalCounts, BoundedBuffer, Insertion, Interval, IntervalCounts, Rgba,
};
use rayon::prelude::*;

#[path = "../tests/common/mod.rs"]
mod common;

type Iv32 = Interval<f32, Rgba<f32>>;
const W: usize = 64;
const H: usize = 64;

fn to32(i: &common::Iv) -> Iv32 {
    let p = i.payload;
    Interval::new(
        i.ts as f32,
        i.te as f32,
        i.z as f32,
        i.k as f32,
        Rgba::opaque(p.r as f32, p.g as f32, p.b as f32),
    )
}

/// Per-pixel lists, and the same intervals as a renderer would emit them: round-robin over
/// pixels (one triangle touches many pixels), as (pixel, interval).
fn workload() -> (Vec<Vec<Iv32>>, Vec<(usize, Iv32)>) {
    let mut r = common::rng(66);
    let lists: Vec<Vec<Iv32>> = (0..W * H)
        .map(|_| common::moving_meshes(&mut r).iter().map(to32).collect())
        .collect();
    let longest = lists.iter().map(Vec::len).max().unwrap_or(0);
    let mut stream = Vec::new();
    for s in 0..longest {
        for (p, l) in lists.iter().enumerate() {
            if let Some(iv) = l.get(s) {
                stream.push((p, *iv));
            }
        }
    }
    (lists, stream)
}

fn bench(c: &mut Criterion) {
    let (lists, stream) = workload();
    let n = stream.len() as u64;
    eprintln!(
        "workload: {W}x{H} pixels, {n} intervals, mean {:.1} / max {} per pixel, {} bytes per full interval",
        n as f64 / (W * H) as f64,
        lists.iter().map(Vec::len).max().unwrap_or(0),
        size_of::<Iv32>()
    );

    let mut g = c.benchmark_group("insert");
    g.throughput(Throughput::Elements(n));
    for k in [4, 8, 16, 64] {
        g.bench_function(format!("bounded_k{k}"), |b| {
            b.iter(|| {
                let mut buf = BoundedBuffer::new(W, H, k, Insertion::paper(true)).expect("buffer");
                for (p, iv) in &stream {
                    buf.insert(p % W, p / W, *iv).expect("insert");
                }
                black_box(buf.pixel(0, 0).len())
            })
        });
    }
    g.bench_function("bounded_k8_pixel_order", |b| {
        b.iter(|| {
            let mut buf = BoundedBuffer::new(W, H, 8, Insertion::paper(true)).expect("buffer");
            for (p, l) in lists.iter().enumerate() {
                for iv in l {
                    buf.insert(p % W, p / W, *iv).expect("insert");
                }
            }
            black_box(buf.pixel(0, 0).len())
        })
    });
    g.bench_function("bounded_k8_par_rows", |b| {
        b.iter(|| {
            let mut buf = BoundedBuffer::new(W, H, 8, Insertion::paper(true)).expect("buffer");
            buf.par_rows_mut().for_each(|mut row| {
                for x in 0..W {
                    for iv in &lists[row.y() * W + x] {
                        row.insert(x, *iv).expect("insert");
                    }
                }
            });
            black_box(buf.pixel(0, 0).len())
        })
    });
    g.bench_function("exact_all_passes", |b| {
        b.iter(|| {
            let mut counts = IntervalCounts::new(W, H).expect("counts");
            for (p, _) in &stream {
                counts.count(*p).expect("count");
            }
            let mut fill = counts.finish::<f32, Rgba<f32>>().expect("scan");
            for (p, iv) in &stream {
                fill.push(*p, *iv).expect("push");
            }
            black_box(fill.finish().expect("finish").intervals().len())
        })
    });
    g.finish();

    let mut g = c.benchmark_group("exact_passes");
    g.throughput(Throughput::Elements(n));
    let counted = {
        let mut counts = IntervalCounts::new(W, H).expect("counts");
        for (p, _) in &stream {
            counts.count(*p).expect("count");
        }
        counts
    };
    g.bench_function("count", |b| {
        b.iter(|| {
            let mut counts = IntervalCounts::new(W, H).expect("counts");
            for (p, _) in &stream {
                counts.count(*p).expect("count");
            }
            black_box(counts.total())
        })
    });
    g.bench_function("count_atomic_par", |b| {
        b.iter(|| {
            let counts = AtomicIntervalCounts::new(W, H).expect("counts");
            stream
                .par_iter()
                .for_each(|(p, _)| counts.count(*p).expect("count"));
            black_box(counts.into_counts().expect("counts").total())
        })
    });
    g.bench_function("count_per_thread_merge_par", |b| {
        b.iter(|| {
            let counts = stream
                .par_chunks(4096)
                .fold(
                    || IntervalCounts::new(W, H).expect("counts"),
                    |mut c, chunk| {
                        for (p, _) in chunk {
                            c.count(*p).expect("count");
                        }
                        c
                    },
                )
                .reduce(
                    || IntervalCounts::new(W, H).expect("counts"),
                    |mut a, b| {
                        a.add(&b).expect("add");
                        a
                    },
                );
            black_box(counts.total())
        })
    });
    g.bench_function("scan", |b| {
        b.iter_batched(
            || counted.clone(),
            |c| black_box(c.finish::<f32, Rgba<f32>>().expect("scan")),
            BatchSize::LargeInput,
        )
    });
    g.bench_function("fill", |b| {
        b.iter_batched(
            || counted.clone().finish::<f32, Rgba<f32>>().expect("scan"),
            |mut f| {
                for (p, iv) in &stream {
                    f.push(*p, *iv).expect("push");
                }
                black_box(f)
            },
            BatchSize::LargeInput,
        )
    });
    let filled = {
        let mut f = counted.clone().finish::<f32, Rgba<f32>>().expect("scan");
        for (p, iv) in &stream {
            f.push(*p, *iv).expect("push");
        }
        f
    };
    g.bench_function("fill_par_rows", |b| {
        b.iter_batched(
            || counted.clone().finish::<f32, Rgba<f32>>().expect("scan"),
            |mut f| {
                f.par_rows_mut().for_each(|mut row| {
                    for x in 0..W {
                        for iv in &lists[row.y() * W + x] {
                            row.push(x, *iv).expect("push");
                        }
                    }
                });
                black_box(f)
            },
            BatchSize::LargeInput,
        )
    });
    g.bench_function("segmented_sort", |b| {
        b.iter_batched(
            || filled.clone(),
            |f| black_box(f.finish().expect("finish")),
            BatchSize::LargeInput,
        )
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
