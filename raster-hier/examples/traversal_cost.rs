//! One traversal of the synthetic Table 2 scene (200 triangles, 256x160, 16 spp, 4x4 pattern
//! tiles, 16 px bins) on one thread, printing the cost counters and a hash of the sample ids:
//! a small deterministic workload for instruction counts.
//!
//! `cargo run --release -p raster-hier --example traversal_cost -- [setup|perlevel|exact|convex|fine] [motion]`
//!
//! `setup`, `perlevel`, `exact`: OUR with that edge test and the default levels 16 → 8 → 4;
//! `fine`: [`RasterConfig::fine`] (16 → 8 → 4 → 2 → 1); anything else: CONVEX.

use raster_hier::{EdgeTest, RasterConfig, SampleBuffer, Traversal, benchmark_scene, rasterise};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let which = args.next().unwrap_or_else(|| "setup".into());
    let motion: f64 = args.next().map(|s| s.parse()).transpose()?.unwrap_or(1.0);
    let cfg = match which.as_str() {
        "setup" => RasterConfig::new(Traversal::Our(EdgeTest::LinearisedSetup)),
        "perlevel" => RasterConfig::new(Traversal::Our(EdgeTest::LinearisedPerLevel)),
        "exact" => RasterConfig::new(Traversal::Our(EdgeTest::Exact)),
        "fine" => RasterConfig::fine(),
        _ => RasterConfig::new(Traversal::Convex),
    };
    let (w, h, spp) = (256u32, 160u32, 16u32);
    let tris = benchmark_scene::<f32>(200, 24.0, motion, w, h, 2011);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let mut buf = SampleBuffer::<f32>::new(w, h, spp, 4, 16, 4, 1)?;
    let c = pool.install(|| rasterise(&mut buf, &tris, &cfg))?;
    let hash = buf.ids().iter().fold(0u64, |a, &i| {
        a.wrapping_mul(1_000_003).wrapping_add(u64::from(i))
    });
    println!(
        "{which}: tile tests {} sample tests {} depth tests {} written {} z-max culls {} ids hash {hash:016x}",
        c.tile_tests, c.sample_tests, c.depth_tests, c.samples_written, c.zmax_culls
    );
    Ok(())
}
