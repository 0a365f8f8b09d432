//! Rasterises a synthetic scene of moving triangles with the hierarchical traversal, prints
//! the cost counters of every traversal, and writes the resolved image as a binary PPM.
//!
//! `cargo run --release -p raster-hier --example rasterise -- [out.ppm] [motion]`

use std::io::Write;

use raster_hier::{EdgeTest, RasterConfig, SampleBuffer, Traversal, benchmark_scene, rasterise};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args.next().unwrap_or_else(|| "raster-hier.ppm".to_string());
    let motion: f64 = args.next().map(|s| s.parse()).transpose()?.unwrap_or(1.0);
    let (w, h, spp) = (256u32, 160u32, 16u32);
    let tris = benchmark_scene::<f32>(200, 24.0, motion, w, h, 2011);
    let palette = |id: u32| {
        let f =
            |k: u32| ((id.wrapping_mul(2_654_435_761).rotate_left(k * 8) & 0xff) as f32) / 255.0;
        [0.2 + 0.8 * f(0), 0.2 + 0.8 * f(1), 0.2 + 0.8 * f(2), 1.0]
    };
    let mut image = Vec::new();
    for tr in [
        Traversal::Bbox,
        Traversal::Convex,
        Traversal::Interleave,
        Traversal::Our(EdgeTest::LinearisedSetup),
        Traversal::Our(EdgeTest::Exact),
        Traversal::OurFallback(EdgeTest::LinearisedSetup),
    ] {
        let mut buf = SampleBuffer::<f32>::new(w, h, spp, 4, 16, 4, 1)?;
        let start = std::time::Instant::now();
        let c = rasterise(&mut buf, &tris, &RasterConfig::new(tr))?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        println!(
            "{:<32} {:>8.2} ms  tile tests {:>8}  sample tests {:>9}  depth tests {:>7}  z-max culls {:>6}  arithmetic {:>11}",
            format!("{tr:?}"),
            ms,
            c.tile_tests,
            c.sample_tests,
            c.depth_tests,
            c.zmax_culls,
            c.arithmetic
        );
        image = buf.resolve(palette, [0.05, 0.05, 0.08, 1.0]);
    }
    let mut out = std::io::BufWriter::new(std::fs::File::create(&path)?);
    write!(out, "P6\n{w} {h}\n255\n")?;
    for p in &image {
        for c in &p[..3] {
            out.write_all(&[(c.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8])?;
        }
    }
    println!("wrote {path} ({w}x{h}, {spp} spp, motion {motion}x triangle size)");
    Ok(())
}
