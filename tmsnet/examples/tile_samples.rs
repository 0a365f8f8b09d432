//! Prints the samples of one 4x4-pixel tile at 16 samples per pixel (m = 8) whose time
//! lies in a range, with pixel, sub-pixel offset and time, and draws pixel (0, 0)'s
//! spatial pattern as ASCII art.
//!
//! Run: `cargo run -p tmsnet --example tile_samples -- [t0] [t1]`

use tmsnet::{TileLayout, TileSampler, get_xy};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let t0: f32 = args.next().map_or(Ok(0.25), |s| s.parse())?;
    let t1: f32 = args.next().map_or(Ok(0.3), |s| s.parse())?;

    let layout = TileLayout::new(4, 4, 16)?;
    let tile = TileSampler::new(layout, 12, 5, 2024)?;
    println!(
        "tile (12, 5), {}x{} pixels, {} spp, m = {}, scramble x = {:#x}, y = {:#x}",
        layout.width(),
        layout.height(),
        layout.spp(),
        layout.m(),
        tile.scramble().x,
        tile.scramble().y
    );
    println!("samples with t in [{t0}, {t1}]:");
    println!("    j  pixel   offset            t");
    for s in tile.samples_in(t0, t1)? {
        println!(
            "  {:3}  ({}, {})  ({:.4}, {:.4})  {:.6}",
            s.index, s.pixel[0], s.pixel[1], s.offset[0], s.offset[1], s.t
        );
    }

    // Unscrambled GetXY: the 16 samples of pixel (0, 0) on a 16x16 sub-pixel grid, each
    // marked with its time order within the pixel (hex digit).
    let mut grid = [['.'; 16]; 16];
    let mut k = 0;
    for j in 0..layout.samples() {
        let (x, y) = get_xy(j, layout.m())?;
        let (pixel, sub) = layout.split(x, y);
        if pixel == [0, 0] {
            // 6 fractional bits; keep the top 4 for a 16x16 grid.
            let (gx, gy) = ((sub[0] >> 2) as usize, (sub[1] >> 2) as usize);
            if let Some(c) = grid.get_mut(gy).and_then(|row| row.get_mut(gx)) {
                *c = char::from_digit(k % 16, 16).unwrap_or('?');
            }
            k += 1;
        }
    }
    println!("\npixel (0, 0), unscrambled, samples numbered in time order (y down):");
    for row in &grid {
        println!("  {}", row.iter().collect::<String>());
    }
    Ok(())
}
