//! RMSE and time of the stochastic method per samples-per-pixel, traversal and footprint,
//! against `accum` rendered 4x4 supersampled with 512 sub-frames and box-filtered (the pixel
//! integral the stochastic estimator with samples spread over the pixel converges to) and
//! against `accum` at pixel centres (what it converges to with samples at the centre).
//!
//! `cargo run --release -p mblur --example stochastic_table -- [SCENE] [W] [H]`
//! (default: billiards 160 90).

use std::time::Instant;

use mblur::stochastic::{self, StochasticOptions, TraversalChoice};
use mblur::{AccumOptions, Footprint, NoProgress};
use mblur_scene::Scene;

fn main() -> Result<(), mblur_scene::Error> {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "billiards".into());
    let w: u32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(160);
    let h: u32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(90);
    let k = 4;
    let mut big = Scene::builtin(&name)?;
    big.set_size(Some(w * k), Some(h * k))?;
    let t0 = Instant::now();
    let opts = AccumOptions {
        times: Some(512),
        jitter: None,
        ..Default::default()
    };
    let ref_img = mblur::accum::render(&big.prepare()?, &opts, &NoProgress)?;
    eprintln!(
        "reference: accum {}x{} x 512 times in {:.2} s",
        w * k,
        h * k,
        t0.elapsed().as_secs_f64()
    );
    let mut scene = Scene::builtin(&name)?;
    scene.set_size(Some(w), Some(h))?;
    let p = scene.prepare()?;
    let t0 = Instant::now();
    let plain = mblur::accum::render(&p, &opts, &NoProgress)?;
    let accum_time = t0.elapsed().as_secs_f64();
    let down = |x: u32, y: u32, c: usize| {
        let mut s = 0.0f64;
        for sy in 0..k {
            for sx in 0..k {
                s += f64::from(ref_img.pixels[((y * k + sy) * w * k + x * k + sx) as usize][c]);
            }
        }
        s / f64::from(k * k)
    };
    let rmse = |img: &mblur::Image| {
        let mut s = 0.0;
        for y in 0..h {
            for x in 0..w {
                let px = img.pixels[(y * w + x) as usize];
                for (c, v) in px.iter().enumerate() {
                    s += (f64::from(*v) - down(x, y, c)).powi(2);
                }
            }
        }
        (s / f64::from(w * h * 3)).sqrt()
    };
    println!("{name} {w}x{h}; reference accum 4x4 supersampled, 512 times");
    println!(
        "accum 512 times at pixel centres: RMSE {:.5}, {:.1} ms",
        rmse(&plain),
        accum_time * 1e3
    );
    let centre_rmse = |img: &mblur::Image| {
        let s: f64 = img
            .pixels
            .iter()
            .zip(&plain.pixels)
            .flat_map(|(a, b)| (0..3).map(move |c| (f64::from(a[c]) - f64::from(b[c])).powi(2)))
            .sum();
        (s / f64::from(w * h * 3)).sqrt()
    };
    println!(
        "| traversal | footprint | spp | RMSE vs 4x4 accum | RMSE vs centre accum | time (ms) | sample tests | tile tests | ~ops |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for t in TraversalChoice::ALL {
        for (footprint, spp) in Footprint::ALL
            .into_iter()
            .flat_map(|f| [1, 4, 16, 64].map(|spp| (f, spp)))
        {
            let o = StochasticOptions {
                spp: Some(spp),
                traversal: t,
                seed: 1,
                footprint,
                ..Default::default()
            };
            // Best of three runs.
            let mut best = f64::INFINITY;
            let mut last = None;
            for _ in 0..3 {
                let t0 = Instant::now();
                let r = stochastic::render(&p, &o, &NoProgress)?;
                best = best.min(t0.elapsed().as_secs_f64());
                last = Some(r);
            }
            let Some(r) = last else { continue };
            let (s, m) = (r.static_counters, r.moving_counters);
            println!(
                "| {t} | {footprint} | {spp} | {:.5} | {:.5} | {:.1} | {} | {} | {} |",
                rmse(&r.image),
                centre_rmse(&r.image),
                best * 1e3,
                s.sample_tests + m.sample_tests,
                s.tile_tests + m.tile_tests,
                s.arithmetic + m.arithmetic
            );
        }
    }
    Ok(())
}
