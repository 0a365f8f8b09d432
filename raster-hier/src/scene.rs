//! Deterministic synthetic scenes for benchmarks and examples: many moving triangles of one
//! size with motion given as a multiple of that size (the paper's "motion 1x ≈ triangle
//! size", Munkberg 2011, §8 Table 2 uses scaled motion of real game scenes).

use edge_eqn::MovingTriangle;
use num_traits::Float;

use crate::interval::lit;
use crate::raster::RasterTriangle;

/// SplitMix64 step: a tiny portable generator so that scenes are the same everywhere.
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

fn unit(state: &mut u64) -> f64 {
    (splitmix(state) >> 11) as f64 / (1u64 << 53) as f64
}

/// `count` triangles of about `size` pixels (vertices on a circle of diameter `size`) with
/// centres uniform in a `width` x `height` image, each translating by `motion · size`
/// pixels in a random direction during the shutter and changing its w (depth) by up to
/// ±10 % per vertex, so edges move non-linearly. Depth w in [1, 4]; ids are 0..count.
pub fn benchmark_scene<F: Float>(
    count: usize,
    size: f64,
    motion: f64,
    width: u32,
    height: u32,
    seed: u64,
) -> Vec<RasterTriangle<F>> {
    let mut s = seed;
    let (w, h) = (f64::from(width), f64::from(height));
    (0..count)
        .map(|i| {
            let (cx, cy) = (unit(&mut s) * w, unit(&mut s) * h);
            let depth = 1.0 + 3.0 * unit(&mut s);
            let dir = unit(&mut s) * core::f64::consts::TAU;
            let (dx, dy) = (dir.cos() * motion * size, dir.sin() * motion * size);
            let a0 = unit(&mut s) * core::f64::consts::TAU;
            let mut q = [[F::zero(); 3]; 3];
            let mut r = [[F::zero(); 3]; 3];
            for k in 0..3 {
                let a = a0 + core::f64::consts::TAU * (k as f64) / 3.0 + 0.4 * (unit(&mut s) - 0.5);
                let (x, y) = (cx + 0.5 * size * a.cos(), cy + 0.5 * size * a.sin());
                let w1 = depth * (1.0 + 0.2 * (unit(&mut s) - 0.5));
                q[k] = [lit(x * depth), lit(y * depth), lit(depth)];
                r[k] = [lit((x + dx) * w1), lit((y + dy) * w1), lit(w1)];
            }
            RasterTriangle::whole(MovingTriangle::new(q, r), i as u32)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_is_deterministic_and_sized() {
        let a = benchmark_scene::<f32>(10, 20.0, 1.0, 128, 64, 3);
        let b = benchmark_scene::<f32>(10, 20.0, 1.0, 128, 64, 3);
        assert_eq!(a, b);
        for t in &a {
            let q = t.triangle.q;
            let (x, y) = (q[0][0] / q[0][2], q[0][1] / q[0][2]);
            assert!((-20.0..148.0).contains(&x) && (-20.0..84.0).contains(&y));
        }
    }
}
