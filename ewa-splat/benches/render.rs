//! Splats per second for the A-buffer and the approximate GPU-style passes, with the image
//! error of each against temporal supersampling of static EWA splatting (2048 samples).

#[path = "../tests/common/mod.rs"]
mod common;

use common::{max_diff, mean_diff, supersample_culled};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use ewa_splat::{Camera, ErfMethod, RenderSettings, Splat, SplatKey, Visibility, render};
use glam::DVec3;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;
use std::hint::black_box;

const BG: [f32; 4] = [0.05, 0.05, 0.1, 1.0];

/// A static back sheet of splats and a moving front sheet sliding diagonally over it (the
/// inter-object case of Fig. 8): 2 x 10 x 10 splats, each sheet one colour per splat row.
fn scene() -> Vec<Splat> {
    let mut rng = Pcg64::seed_from_u64(9);
    let mut out = Vec::new();
    for i in 0..10 {
        for j in 0..10 {
            let (u, v) = (i as f64 * 0.2 - 0.9, j as f64 * 0.2 - 0.9);
            let g = 0.3 + 0.5 * rng.random::<f32>();
            out.push(Splat::fixed(
                SplatKey::disc(DVec3::new(u, v, 0.0), DVec3::Z, 0.16),
                [g, g, g, 1.0],
            ));
            let open = DVec3::new(0.5 * u - 0.8, 0.5 * v - 0.3, 1.0);
            out.push(Splat::moving_disc(
                open,
                DVec3::new(1.2, 0.5, 0.2),
                DVec3::new(0.1, 0.0, 1.0),
                0.08,
                [0.9, 0.5, 0.1, 1.0],
            ));
        }
    }
    out
}

fn bench(c: &mut Criterion) {
    let cam = Camera::look_at_perspective(
        DVec3::new(0.0, 0.0, 4.0),
        DVec3::ZERO,
        DVec3::Y,
        0.8,
        0.1,
        100.0,
        64,
        64,
    );
    let splats = scene();
    let reference = supersample_culled(&cam, &splats, BG, 2.0, 1.0, 2048);
    let configs = [
        ("abuffer_full", RenderSettings::default()),
        (
            "abuffer_table",
            RenderSettings {
                erf: ErfMethod::Table,
                ..RenderSettings::default()
            },
        ),
        (
            "approx_1sub",
            RenderSettings {
                visibility: Visibility::Approximate,
                ..RenderSettings::default()
            },
        ),
        (
            "approx_4sub",
            RenderSettings {
                visibility: Visibility::Approximate,
                subframes: 4,
                ..RenderSettings::default()
            },
        ),
        (
            "approx_16sub",
            RenderSettings {
                visibility: Visibility::Approximate,
                subframes: 16,
                ..RenderSettings::default()
            },
        ),
    ];
    eprintln!(
        "\n{:<14} {:>12} {:>12} {:>10}",
        "setting", "mean |err|", "max |err|", "fragments"
    );
    for (name, s) in &configs {
        let f = render(&cam, &splats, BG, s).unwrap();
        eprintln!(
            "{:<14} {:>12.5} {:>12.4} {:>10}",
            name,
            mean_diff(&f.pixels, &reference),
            max_diff(&f.pixels, &reference),
            f.stats.fragments
        );
    }
    eprintln!();
    let mut g = c.benchmark_group("render_200_splats_64x64");
    g.throughput(Throughput::Elements(splats.len() as u64));
    for (name, s) in &configs {
        g.bench_function(*name, |b| {
            b.iter(|| render(&cam, black_box(&splats), BG, s).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
