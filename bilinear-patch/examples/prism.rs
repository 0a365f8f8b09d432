//! The prism of a moving triangle: hits and coverage spans for one pixel centre, then the
//! fraction of the shutter each pixel of a small window is covered, as ASCII shades.
//!
//! Run with `cargo run -p bilinear-patch --example prism`.

use bilinear_patch::{Prism, ScreenVertex};

fn main() {
    // A triangle that moves 14 px right and 4 px down while it turns a little; depth grows
    // from 1 to 2 over the shutter. (x, y) in pixels, already divided by w.
    let v = |x, y, depth| ScreenVertex { x, y, depth };
    let open = [v(2.0, 2.0, 1.0), v(10.0, 3.0, 1.0), v(4.0, 11.0, 1.0)];
    let close = [v(16.0, 6.0, 2.0), v(23.0, 9.0, 2.0), v(17.0, 15.0, 2.0)];
    let prism = Prism::new(open, close);

    let (px, py) = (12.5, 6.5);
    println!("pixel centre ({px}, {py}):");
    for h in prism.hits(px, py).iter() {
        println!(
            "  hit   t = {:.4}  depth = {:.4}  uv = ({:.3}, {:.3})  on {:?}",
            h.time, h.depth, h.uv[0], h.uv[1], h.face
        );
    }
    for s in prism.coverage(px, py).iter() {
        println!(
            "  span  [{:.4}, {:.4}]  depth {:.4} -> {:.4}  uv ({:.3}, {:.3}) -> ({:.3}, {:.3})",
            s.t0, s.t1, s.depth0, s.depth1, s.uv0[0], s.uv0[1], s.uv1[0], s.uv1[1]
        );
    }

    println!("\nfraction of the shutter each pixel is covered:");
    let shades = [' ', '.', ':', '-', '=', '+', '*', '#', '%', '@'];
    for j in 0..18 {
        let row: String = (0..26)
            .map(|i| {
                let cov = prism.coverage(i as f64 + 0.5, j as f64 + 0.5);
                let f: f64 = cov.iter().map(|s| s.t1 - s.t0).sum();
                shades[((f * 9.0).round() as usize).min(9)]
            })
            .collect();
        println!("  |{row}|");
    }
}
