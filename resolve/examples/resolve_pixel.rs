//! Resolves one pixel three ways and prints its partitions: Rønnow 2021, Fig. 11 (two quads
//! moving through each other along z) with and without intersection handling, and a
//! semi-transparent trio in the style of Gribel 2010, Fig. 8 under a tent shutter.
//!
//! Run: `cargo run -p resolve --example resolve_pixel`

use interval_buffer::{Interval, Rgba};
use resolve::{Flat, Resolver, Settings, Shutter};

fn show(title: &str, settings: Settings<f64>, intervals: &[Interval<f64, Rgba<f64>>]) {
    println!("{title}");
    let mut resolver = Resolver::new(settings);
    let colour = resolver
        .resolve_partitions(intervals, &Flat, |p| {
            println!(
                "  [{:.3}, {:.3}) weight {:.4} front {:?} layers {} colour (premultiplied) [{:.3}, {:.3}, {:.3}, {:.3}]",
                p.t0, p.t1, p.weight, p.front, p.layers, p.colour[0], p.colour[1], p.colour[2], p.colour[3]
            )
        })
        .expect("finite, sorted input");
    println!(
        "  pixel = ({:.4}, {:.4}, {:.4}, alpha {:.4})\n",
        colour.r, colour.g, colour.b, colour.a
    );
}

fn main() {
    // Red moves from back (depth 2) to front (1), green from front (1) to back (2).
    let fig11 = [
        Interval::new(0.0, 1.0, 2.0, -1.0, Rgba::opaque(1.0, 0.0, 0.0)),
        Interval::new(0.0, 1.0, 1.0, 1.0, Rgba::opaque(0.0, 1.0, 0.0)),
    ];
    show(
        "Fig. 11 with intersection handling (yellow):",
        Settings::opaque(),
        &fig11,
    );
    show(
        "Fig. 11 without intersection handling (green keeps its start order):",
        Settings::opaque().with_intersections(false),
        &fig11,
    );

    let trio = [
        Interval::new(0.1, 0.6, 1.0, 0.0, Rgba::new(1.0, 0.0, 0.0, 0.6)),
        Interval::new(0.3, 0.8, 2.0, -1.0, Rgba::new(0.0, 1.0, 0.0, 0.6)),
        Interval::new(0.4, 0.9, 0.5, 1.0, Rgba::new(0.0, 0.0, 1.0, 0.6)),
    ];
    show(
        "Semi-transparent trio over white, tent shutter:",
        Settings::transparent()
            .with_background(Rgba::opaque(1.0, 1.0, 1.0))
            .with_shutter(Shutter::tent()),
        &trio,
    );
}
