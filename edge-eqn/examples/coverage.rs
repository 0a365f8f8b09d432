//! Prints the covered spans, exact depth, linear depth (with its error) and barycentrics of
//! a moving, perspective triangle at one pixel, and checks them against 64 stochastic
//! inside tests.
//!
//! Run: `cargo run -p edge-eqn --example coverage [-- PX,PY]` (default pixel 25,30).

use edge_eqn::MovingTriangle;

fn main() {
    // Screen-space vertices (pixels) and view depth w at shutter open and close; in 2DH the
    // stored x, y are the screen position times w. The triangle slides right by 24 px,
    // rotates a little and recedes from w = 1..3 to w = 4..5.
    let open = [[8.0, 8.0, 1.0], [40.0, 10.0, 2.0], [14.0, 40.0, 3.0]];
    let close = [[30.0, 14.0, 4.0], [62.0, 20.0, 4.5], [30.0, 44.0, 5.0]];
    let to_2dh = |v: [[f64; 3]; 3]| v.map(|[x, y, w]| [x * w, y * w, w]);
    let tri = MovingTriangle::new(to_2dh(open), to_2dh(close));
    let setup = tri.setup();

    let (px, py) = std::env::args()
        .nth(1)
        .and_then(|a| {
            let (x, y) = a.split_once(",")?;
            Some((x.parse::<i32>().ok()?, y.parse::<i32>().ok()?))
        })
        .unwrap_or((25, 30));
    let (x, y) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
    let sample = setup.sample(x, y);
    let cov = sample.coverage();

    println!("pixel ({px}, {py}), sample ({x}, {y})");
    for (k, e) in sample.edges().iter().enumerate() {
        println!(
            "  edge {k}: e(t) = {:+.4} t^2 {:+.4} t {:+.4}",
            e.alpha, e.beta, e.gamma
        );
    }
    println!("covered spans: {}", cov.len());
    for span in cov.iter() {
        let fit = sample.linear_depth(*span);
        println!(
            "  t in [{:.6}, {:.6}]  depth {:.4} -> {:.4}  linear: z = {:.4}, k = {:+.4}, max error {:.2e}",
            span.t0,
            span.t1,
            sample.depth_at(span.t0),
            sample.depth_at(span.t1),
            fit.z,
            fit.k,
            fit.max_error
        );
        let t = span.mid();
        let [l0, l1, l2] = sample.barycentrics(t);
        println!(
            "    at t = {t:.4}: barycentrics ({l0:.4}, {l1:.4}, {l2:.4}), exact depth {:.5}, linear {:.5}",
            sample.depth_at(t),
            fit.eval(t)
        );
    }
    let total = cov.total();
    let n = 64;
    let hits = (0..n)
        .filter(|&i| setup.inside_at(x, y, (f64::from(i) + 0.5) / f64::from(n)))
        .count();
    println!(
        "covered time {total:.6}; {n} stratified inside tests: {hits}/{n} = {:.6}",
        hits as f64 / f64::from(n)
    );
}
