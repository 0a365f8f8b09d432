//! The fence pattern (Gribel 2010, Fig. 11) in one pixel: 12 white slats passing over a
//! brown background, stored with K = 8 intervals. Prints the temporal-pixel-visualiser
//! trace of the compression steps, then the final lists with the paper's oracle and with
//! the coverage-preserving merge, next to the exact (uncompressed) list.
//!
//! Run with `cargo run -p interval-buffer --example compress`.

use interval_buffer::{
    BoundedBuffer, CompactInterval8, Insertion, Interval, IntervalCounts, Oracle, Rgba,
};

fn show(label: &str, list: &[Interval<f32, Rgba<f32>>]) {
    println!("{label} ({} intervals):", list.len());
    for iv in list {
        let c = iv.payload;
        println!(
            "  [{:.3}, {:.3}] z {:.2} k {:+.2} rgba ({:.2}, {:.2}, {:.2}, {:.2})",
            iv.ts, iv.te, iv.z, iv.k, c.r, c.g, c.b, c.a
        );
    }
}

fn main() -> Result<(), interval_buffer::Error> {
    let bg = Interval::new(0.0_f32, 1.0, 10.0, 0.0, Rgba::opaque(0.4, 0.3, 0.2));
    let slats: Vec<_> = (0..12)
        .map(|i| {
            let ts = i as f32 / 12.0;
            Interval::new(ts, ts + 0.5 / 12.0, 1.0, 0.0, Rgba::opaque(1.0, 1.0, 1.0))
        })
        .collect();

    // Exact strategy: count, scan, fill, sort.
    let mut counts = IntervalCounts::new(1, 1)?;
    counts.count_n(0, 1 + slats.len() as u32)?;
    let mut fill = counts.finish()?;
    fill.push(0, bg)?;
    for s in &slats {
        fill.push(0, *s)?;
    }
    let exact = fill.finish()?;
    show("exact", exact.pixel(0, 0));

    for (name, oracle) in [
        ("paper oracle", Oracle::paper()),
        (
            "coverage-preserving merge",
            Oracle::paper().with_keep_coverage(true),
        ),
    ] {
        let mut buf = BoundedBuffer::new(
            1,
            1,
            8,
            Insertion {
                oracle,
                opaque: true,
            },
        )?;
        buf.trace_pixel_index(0);
        buf.insert(0, 0, bg)?;
        for s in &slats {
            buf.insert(0, 0, *s)?;
        }
        println!("\n== {name}, K = 8 ==");
        if let Some(trace) = buf.take_trace() {
            for (n, step) in trace.compression_steps().enumerate() {
                if let Some(m) = step.outcome.merged {
                    println!(
                        "step {n}: inserted [{:.3}, {:.3}], merged list items {} and {} (oracle {:.1}), {} -> {} intervals",
                        step.inserted.ts,
                        step.inserted.te,
                        m.i,
                        m.j,
                        m.cost,
                        step.before.len() + 1,
                        step.after.len()
                    );
                }
            }
        }
        show("final", buf.pixel(0, 0));
        println!("bytes per pixel: {}", buf.bytes_per_pixel());
    }

    let c = CompactInterval8::from_interval(&slats[1])?;
    let back: Interval<f32, Rgba<f32>> = c.to_interval();
    println!(
        "\ncompact form: {} bytes (full: {}); slat 1 [{}, {}] -> [{:.4}, {:.4}]",
        CompactInterval8::BYTES,
        size_of::<Interval<f32, Rgba<f32>>>(),
        slats[1].ts,
        slats[1].te,
        back.ts,
        back.te
    );
    Ok(())
}
