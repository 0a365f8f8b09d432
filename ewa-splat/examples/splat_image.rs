//! Renders a motion-blurred ring of splats with the A-buffer and with the approximate GPU
//! passes, prints their difference and frame counters, and writes both as PFM images
//! (linear float RGB, written by hand; no image crates).
//!
//! `cargo run --release -p ewa-splat --example splat_image -- [out_dir]`

use ewa_splat::{Camera, RenderSettings, Splat, SplatKey, Visibility, render};
use glam::DVec3;
use std::io::Write;

/// A spinning ring of overlapping splats (tangential, non-linear motion: 5 keys per splat)
/// in front of a static back wall.
fn scene() -> Vec<Splat> {
    let mut out = Vec::new();
    let n = 90;
    for i in 0..n {
        let a0 = std::f64::consts::TAU * i as f64 / n as f64;
        let keys = (0..5)
            .map(|k| {
                let a = a0 + 0.6 * k as f64 / 4.0; // rotates 0.6 rad over the exposure
                let c = DVec3::new(a.cos(), a.sin(), 0.5);
                SplatKey::disc(c, DVec3::Z, 0.09)
            })
            .collect();
        let hue = i as f32 / n as f32;
        out.push(Splat {
            keys,
            colour: [hue, 0.4, 1.0 - hue, 1.0],
            span: [0.0, 1.0],
        });
    }
    for i in 0..12 {
        for j in 0..12 {
            let c = DVec3::new(-1.65 + 0.3 * i as f64, -1.65 + 0.3 * j as f64, -0.5);
            let checker = if (i + j) % 2 == 0 { 0.8 } else { 0.3 };
            out.push(Splat::fixed(
                SplatKey::disc(c, DVec3::Z, 0.22),
                [checker, checker, checker, 1.0],
            ));
        }
    }
    out
}

fn write_pfm(path: &std::path::Path, w: u32, h: u32, px: &[[f32; 4]]) -> std::io::Result<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    write!(f, "PF\n{w} {h}\n-1.0\n")?;
    // PFM stores rows bottom to top, little-endian (negative scale).
    for j in (0..h as usize).rev() {
        for p in &px[j * w as usize..(j + 1) * w as usize] {
            for c in &p[..3] {
                f.write_all(&c.to_le_bytes())?;
            }
        }
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out_dir = std::env::args().nth(1).unwrap_or_else(|| ".".into());
    let cam = Camera::look_at_perspective(
        DVec3::new(0.0, 0.0, 4.0),
        DVec3::ZERO,
        DVec3::Y,
        0.9,
        0.1,
        100.0,
        160,
        120,
    );
    let splats = scene();
    let bg = [0.02, 0.02, 0.05, 1.0];
    let exact = RenderSettings {
        subframes: 4,
        ..RenderSettings::default()
    };
    let t = std::time::Instant::now();
    let a = render(&cam, &splats, bg, &exact)?;
    let ta = t.elapsed();
    let t = std::time::Instant::now();
    let g = render(
        &cam,
        &splats,
        bg,
        &RenderSettings {
            visibility: Visibility::Approximate,
            ..exact
        },
    )?;
    let tg = t.elapsed();
    let (mut sum, mut max) = (0.0f64, 0.0f64);
    for (p, q) in a.pixels.iter().zip(&g.pixels) {
        for c in 0..3 {
            let d = (p[c] - q[c]).abs() as f64;
            sum += d;
            max = max.max(d);
        }
    }
    println!("A-buffer:    {:?} in {ta:.2?}", a.stats);
    println!("approximate: {:?} in {tg:.2?}", g.stats);
    println!(
        "approximate vs A-buffer: mean |diff| {:.4}, max {:.4}",
        sum / (3 * a.pixels.len()) as f64,
        max
    );
    let dir = std::path::Path::new(&out_dir);
    write_pfm(&dir.join("ewa_abuffer.pfm"), a.width, a.height, &a.pixels)?;
    write_pfm(&dir.join("ewa_approx.pfm"), g.width, g.height, &g.pixels)?;
    println!(
        "wrote {} and {}",
        dir.join("ewa_abuffer.pfm").display(),
        dir.join("ewa_approx.pfm").display()
    );
    Ok(())
}
