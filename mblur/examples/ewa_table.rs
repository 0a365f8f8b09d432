//! Error next to time for the `ewa` method on splat-ball: subframes 1, 4, 16 and A-buffer vs
//! approximate visibility, against `accum` (1024 sub-frames, hard-edged discs) and against an
//! accumulation of ewa-splat's static renders at 256 times (the temporal reference).
//!
//! `cargo run --release -p mblur --example ewa_table -- [WIDTH HEIGHT]` (default 160 120).

use std::time::Instant;

use ewa_splat::{RenderSettings, Splat};
use mblur::ewa::{self, EwaOptions, Visibility};
use mblur::{AccumOptions, Image, Method, MethodOptions, NoProgress};
use mblur_scene::Scene;

fn rmse(a: &Image, b: &Image) -> f64 {
    a.rmse(b).expect("images of the same size")
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<u32> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let (w, h) = (
        args.first().copied().unwrap_or(160),
        args.get(1).copied().unwrap_or(120),
    );
    let mut scene = Scene::builtin("splat-ball")?;
    scene.set_size(Some(w), Some(h))?;
    let p = scene.prepare()?;
    let opts = |method, ewa| match method {
        Method::Accum => MethodOptions::Accum(AccumOptions {
            times: Some(1024),
            jitter: None,
            ..Default::default()
        }),
        _ => MethodOptions::Ewa(ewa),
    };
    let t = Instant::now();
    let accum = mblur::render(&p, &opts(Method::Accum, EwaOptions::default()), &NoProgress)?.image;
    eprintln!("accum 1024: {:.2} s", t.elapsed().as_secs_f64());
    // Integrated static ewa-splat renders.
    let cam = ewa::camera(&p);
    let splats = ewa::ewa_splats(&p);
    let bg = p.background.map(|c| c as f32);
    let n = 256;
    let mut acc = vec![[0.0f64; 3]; (w * h) as usize];
    for k in 0..n {
        let t = (f64::from(k) + 0.5) / f64::from(n);
        let at: Vec<Splat> = splats
            .iter()
            .filter_map(|s| Some(Splat::fixed(s.key_at(t)?, s.colour)))
            .collect();
        let f = ewa_splat::render(
            &cam,
            &at,
            [bg[0], bg[1], bg[2], 1.0],
            &RenderSettings::default(),
        )?;
        for (a, q) in acc.iter_mut().zip(&f.pixels) {
            for c in 0..3 {
                a[c] += f64::from(q[c]) / f64::from(n);
            }
        }
    }
    let reference = Image {
        width: w,
        height: h,
        pixels: acc.iter().map(|q| q.map(|c| c as f32)).collect(),
    };
    println!("splat-ball {w}x{h}");
    println!(
        "| visibility | subframes | time (s) | RMSE vs accum 1024 | RMSE vs static ewa x {n} |"
    );
    println!("|---|---|---|---|---|");
    for visibility in [Visibility::ABuffer, Visibility::Approximate] {
        for subframes in [1, 4, 16] {
            let e = EwaOptions {
                subframes,
                visibility,
                ..Default::default()
            };
            let t = Instant::now();
            let img = mblur::render(&p, &opts(Method::Ewa, e), &NoProgress)?.image;
            let secs = t.elapsed().as_secs_f64();
            println!(
                "| {visibility:?} | {subframes} | {secs:.3} | {:.4} | {:.4} |",
                rmse(&img, &accum),
                rmse(&img, &reference)
            );
        }
    }
    Ok(())
}
