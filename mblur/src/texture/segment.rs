//! The exact average of a texture along a straight UV segment (Rønnow 2021, §4.3: "the
//! continuous range of texels between the start and end UVs"): one Simpson step per
//! bilinear cell the segment crosses.

use glam::DVec2;

use super::Texture;
use super::grid::{bilinear, floor, split, wrap};

impl Texture {
    /// How many texel-cell borders the straight segment `uv0` → `uv1` crosses (its exact
    /// integral, [`Texture::segment_average`], takes one more piece than this); infinite for
    /// non-finite coordinates.
    pub fn borders_crossed(&self, uv0: DVec2, uv1: DVec2) -> f64 {
        borders(self.texel_space(uv0), self.texel_space(uv1))
    }

    /// The premultiplied colour averaged along the straight segment `uv0` → `uv1` with a
    /// weight linear from `w0` at `uv0` to `w1` at `uv1` (both 0: unweighted):
    /// ∫₀¹ w(s) c(uv(s)) ds / ∫₀¹ w(s) ds, with c the bilinear [`Texture::sample`].
    ///
    /// Exact up to rounding (Rønnow 2021, §4.3: "the continuous range of texels between the
    /// start and end UVs"): inside one bilinear cell c is a product of two linear functions
    /// of s, so w c is a cubic, which Simpson's rule integrates exactly; the segment is cut
    /// at every cell border it crosses and each piece takes one Simpson step with its
    /// cell's four texels fetched once. The cost grows with [`Texture::borders_crossed`].
    /// Non-finite input gives transparent black.
    pub fn segment_average(&self, uv0: DVec2, uv1: DVec2, w0: f64, w1: f64) -> [f64; 4] {
        self.segment_average_within(uv0, uv1, [w0, w1], f64::INFINITY)
            .unwrap_or([0.0; 4])
    }

    /// [`Texture::segment_average`] when the segment crosses at most `max_borders` cell
    /// borders, else `None` (also for non-finite input): for a caller that takes the exact
    /// integral only where it is cheaper than point taps.
    pub fn segment_average_within(
        &self,
        uv0: DVec2,
        uv1: DVec2,
        [w0, w1]: [f64; 2],
        max_borders: f64,
    ) -> Option<[f64; 4]> {
        let (p0, p1) = (self.texel_space(uv0), self.texel_space(uv1));
        let n = borders(p0, p1);
        if !n.is_finite() || n > max_borders {
            return None;
        }
        let (w0, w1) = if w0 + w1 > 0.0 { (w0, w1) } else { (1.0, 1.0) };
        let norm = 1.0 / (0.5 * (w0 + w1));
        if n == 0.0 {
            // One cell (the common case): one Simpson step, no border search.
            let ((i, fx0), (j, fy0)) = (split(p0.0), split(p0.1));
            let (dx, dy) = (p1.0 - p0.0, p1.1 - p0.1);
            // The inside of a flat region: the texture is constant over the cell, and so
            // is its average.
            if let Some((c, _)) = self.flat_cell(i, j) {
                return Some(c);
            }
            let texels = self.cell(i, j);
            let wm = 0.5 * (w0 + w1);
            // -0.0 is the exact additive identity (0.0 + -0.0 would be +0.0).
            let mut sum = [-0.0; 4];
            simpson_step(
                &mut sum,
                texels,
                [
                    (fx0, fy0, w0),
                    (fx0 + 0.5 * dx, fy0 + 0.5 * dy, 4.0 * wm),
                    (fx0 + dx, fy0 + dy, w1),
                ],
            );
            let k = norm / 6.0;
            return Some(sum.map(|c| c * k));
        }
        Some(
            self.average_across_cells(p0, p1, [w0, w1], n)
                .map(|c| c * norm),
        )
    }

    /// The weighted integral ∫₀¹ w(s) c(s) ds along the texel-space segment `p0` → `p1`
    /// crossing `n` cell borders, one Simpson step per cell ([`Texture::segment_average`]).
    fn average_across_cells(
        &self,
        p0: (f64, f64),
        p1: (f64, f64),
        [w0, w1]: [f64; 2],
        n: f64,
    ) -> [f64; 4] {
        // Whole periods off the start, so that coordinates stay small (exact integer shifts).
        let (sw, sh) = (f64::from(self.width), f64::from(self.height));
        let (ox, oy) = (sw * floor(p0.0 / sw), sh * floor(p0.1 / sh));
        let (x0, y0) = (p0.0 - ox, p0.1 - oy);
        let (dx, dy) = (p1.0 - ox - x0, p1.1 - oy - y0);
        let at = |s: f64| (x0 + dx * s, y0 + dy * s);
        let w = |s: f64| w0 + (w1 - w0) * s;
        let mut sum = [0.0; 4];
        // One Simpson step over [sa, sb] inside cell (i, j).
        let piece = |sum: &mut [f64; 4], sa: f64, sb: f64, (i, j): (i64, i64)| {
            let sm = 0.5 * (sa + sb);
            let h = (sb - sa) / 6.0;
            let texels = self.cell(i, j);
            let (fi, fj) = (i as f64, j as f64);
            // The cell's polynomial, also slightly outside it at rounded borders.
            let taps = [(sa, h), (sm, 4.0 * h), (sb, h)].map(|(s, factor)| {
                let (x, y) = at(s);
                (x - fi, y - fj, w(s) * factor)
            });
            simpson_step(sum, texels, taps);
        };
        let cell_of = |sa: f64, sb: f64| {
            let (xm, ym) = at(0.5 * (sa + sb));
            (split(xm).0, split(ym).0)
        };
        let (mut xs, mut ys) = (Borders::new(x0, dx), Borders::new(y0, dy));
        let mut sa = 0.0;
        // Each step passes at least one border or restarts the border search after a flat
        // box (which passes at least one more); the guard bounds the loop for any rounding.
        for _ in 0..3 * (n.min(1e12) as u64) + 4 {
            if sa >= 1.0 {
                break;
            }
            let mut sb = xs.next_s().min(ys.next_s()).min(1.0);
            if sb > sa {
                let (i, j) = cell_of(sa, sb);
                if let Some((c, r)) = self.flat_cell(i, j) {
                    // A flat box of radius r around the cell: one constant piece to where
                    // the segment leaves it, where the border search starts again.
                    if r > 1 {
                        let r = i64::from(r);
                        sb = xs.box_exit(i, r).min(ys.box_exit(j, r)).min(1.0);
                        xs.restart(sb);
                        ys.restart(sb);
                    }
                    let wsum = (sb - sa) * w(0.5 * (sa + sb));
                    for (acc, c) in sum.iter_mut().zip(c) {
                        *acc += wsum * c;
                    }
                } else {
                    piece(&mut sum, sa, sb, (i, j));
                }
                sa = sb;
            }
            xs.pass(sb);
            ys.pass(sb);
        }
        if sa < 1.0 {
            let cell = cell_of(sa, 1.0);
            piece(&mut sum, sa, 1.0, cell);
        }
        sum
    }

    /// The colour of cell (i, j) (top-left texel, wrapped) and its flat radius (see
    /// `super::flat`) when the cell is flat; `None` when it is not. Textures without a map
    /// compare the cell's texels (radius 1).
    #[inline(always)]
    fn flat_cell(&self, i: i64, j: i64) -> Option<([f64; 4], u8)> {
        let ((xi, _), (yi, _)) = (wrap(i, self.width), wrap(j, self.height));
        match self.flat.radius(xi, yi) {
            Some(0) => None,
            Some(r) => Some((self.texel(xi, yi), r)),
            None => {
                let texels = self.cell(i, j);
                flat(&texels).then_some((texels[0], 1))
            }
        }
    }
}

/// Whether a cell's four texels are equal (the inside of a flat region of the texture),
/// so that the bilinear blend is the same colour everywhere in it.
#[inline(always)]
fn flat(texels: &[[f64; 4]; 4]) -> bool {
    texels[1] == texels[0] && texels[2] == texels[0] && texels[3] == texels[0]
}

/// Cell borders crossed between texel-space points `p0` and `p1` (infinite when not finite).
#[inline]
fn borders(p0: (f64, f64), p1: (f64, f64)) -> f64 {
    let n = (floor(p1.0) - floor(p0.0)).abs() + (floor(p1.1) - floor(p0.1)).abs();
    if n.is_finite() { n } else { f64::INFINITY }
}

/// The parameters s in (0, 1] at which x0 + d s crosses an integer (a cell border of the
/// texel grid), in increasing order.
struct Borders {
    x0: f64,
    d: f64,
    next: f64,
}

impl Borders {
    fn new(x0: f64, d: f64) -> Self {
        Borders {
            x0,
            d,
            next: first_beyond(x0, d),
        }
    }

    /// Restarts the search at parameter `s`: the next border is the first one beyond the
    /// coordinate there.
    fn restart(&mut self, s: f64) {
        self.next = first_beyond(self.x0 + self.d * s, self.d);
    }

    /// The parameter at which the coordinate leaves the box of cells `i - r + 1 ..= i + r - 1`
    /// (texel-space coordinates `i - r + 1` to `i + r`); infinite when it does not move.
    fn box_exit(&self, i: i64, r: i64) -> f64 {
        if self.d == 0.0 {
            return f64::INFINITY;
        }
        let wall = if self.d > 0.0 { i + r } else { i - r + 1 };
        (wall as f64 - self.x0) / self.d
    }

    /// The parameter of the next border (infinite when the coordinate does not move).
    fn next_s(&self) -> f64 {
        if self.d == 0.0 {
            f64::INFINITY
        } else {
            (self.next - self.x0) / self.d
        }
    }

    /// Steps past the border at parameter `s` if that is the next one.
    fn pass(&mut self, s: f64) {
        if self.d != 0.0 && self.next_s() <= s {
            self.next += self.d.signum();
        }
    }
}

/// The first integer (cell border) beyond `x` in the direction of `d`.
#[inline]
fn first_beyond(x: f64, d: f64) -> f64 {
    if d > 0.0 {
        floor(x) + 1.0
    } else {
        -floor(-x) - 1.0
    }
}

/// One Simpson step over a bilinear cell: adds `w c(fx, fy)` to `sum` for the step's start,
/// middle and end taps `(fx, fy, w)` in that order, with c the [`bilinear`] blend of
/// `texels` and w the shutter weight times the Simpson weight (1, 4, 1 over 6, or a
/// multiple of them the caller divides out).
#[inline(always)]
fn simpson_step(sum: &mut [f64; 4], texels: [[f64; 4]; 4], taps: [(f64, f64, f64); 3]) {
    for (fx, fy, w) in taps {
        let c = bilinear(fx, fy, texels);
        for (acc, c) in sum.iter_mut().zip(c) {
            *acc += w * c;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::Texels;

    /// The weighted mean of `sample` along the segment by the composite midpoint rule with
    /// `n` taps: an independent quadrature of the same integral.
    fn dense_average(t: &Texture, uv0: DVec2, uv1: DVec2, w0: f64, w1: f64, n: u32) -> [f64; 4] {
        let (mut sum, mut weights) = ([0.0; 4], 0.0);
        for k in 0..n {
            let s = (f64::from(k) + 0.5) / f64::from(n);
            let w = w0 + (w1 - w0) * s;
            let c = t.sample(uv0 + (uv1 - uv0) * s);
            for (a, c) in sum.iter_mut().zip(c) {
                *a += w * c;
            }
            weights += w;
        }
        sum.map(|c| c / weights)
    }

    /// Seeded uniform numbers in [0, 1) (a 64-bit LCG's top 53 bits).
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    #[test]
    fn segment_average_is_the_dense_quadrature() {
        // Distinct texels with alpha, power-of-two and other sizes; segments inside one
        // cell, along a row, diagonal, across the wrap, far outside [0, 1], backwards, and
        // of zero length. The midpoint rule with 2^16 taps errs by O(1/n^2) inside cells and
        // O(1/n) at the kinks of the borders: below 1e-5 for these lengths.
        let mut next = uniform(5);
        for (w, h) in [(4u32, 4u32), (5, 3), (1, 8), (16, 2)] {
            let texels = (0..w * h)
                .map(|_| [next(), next(), next(), 0.25 + 0.75 * next()])
                .collect();
            let t = Texture::from_straight(w, h, texels);
            let mut cases = vec![
                (DVec2::new(0.1, 0.2), DVec2::new(0.12, 0.21)),
                (DVec2::new(0.0, 0.5), DVec2::new(1.0, 0.5)),
                (DVec2::new(-0.3, 0.9), DVec2::new(1.7, -1.2)),
                (DVec2::new(5.3, -7.1), DVec2::new(5.1, -6.6)),
                (DVec2::new(0.7, 0.3), DVec2::new(0.7, 0.3)),
                (DVec2::new(0.95, 0.05), DVec2::new(1.05, -0.05)),
            ];
            for _ in 0..40 {
                let a = DVec2::new(4.0 * next() - 2.0, 4.0 * next() - 2.0);
                cases.push((a, a + DVec2::new(next() - 0.5, next() - 0.5)));
            }
            for (uv0, uv1) in cases {
                for (w0, w1) in [(1.0, 1.0), (0.2, 1.7), (2.0, 0.0), (0.0, 0.0)] {
                    let got = t.segment_average(uv0, uv1, w0, w1);
                    let want = if uv0 == uv1 {
                        t.sample(uv0)
                    } else {
                        let (v0, v1) = if w0 + w1 > 0.0 { (w0, w1) } else { (1.0, 1.0) };
                        dense_average(&t, uv0, uv1, v0, v1, 1 << 16)
                    };
                    for k in 0..4 {
                        assert!(
                            (got[k] - want[k]).abs() < 1e-5,
                            "{w}x{h} {uv0} -> {uv1} ({w0}, {w1}): {got:?} vs {want:?}"
                        );
                    }
                }
            }
        }
        // A checkerboard: most cells hold four equal texels (constant there).
        let t = Texture::checker(4, 4, [0.9, 0.2, 0.1, 0.5], [0.05, 0.6, 0.7, 1.0]);
        for _ in 0..200 {
            let a = DVec2::new(2.0 * next() - 1.0, 2.0 * next() - 1.0);
            let b = a + DVec2::new(0.1 * next() - 0.05, 0.1 * next() - 0.05);
            let (got, want) = (
                t.segment_average(a, b, 1.0, 0.5),
                dense_average(&t, a, b, 1.0, 0.5, 1 << 16),
            );
            for k in 0..4 {
                assert!(
                    (got[k] - want[k]).abs() < 1e-5,
                    "{a} -> {b}: {got:?} vs {want:?}"
                );
            }
        }
        // Non-finite coordinates: transparent black, no hang.
        let t = Texture::checker(2, 2, [1.0; 4], [0.0, 0.0, 0.0, 1.0]);
        let bad = DVec2::new(f64::NAN, 0.0);
        assert_eq!(t.segment_average(bad, DVec2::ZERO, 1.0, 1.0), [0.0; 4]);
        assert_eq!(t.borders_crossed(bad, DVec2::ZERO), f64::INFINITY);
        // A segment across 2e6 cells still ends (one piece per cell).
        let long = t.segment_average(DVec2::ZERO, DVec2::new(5e5, 0.0), 1.0, 1.0);
        assert!(long.iter().all(|c| c.is_finite()));
    }

    #[test]
    fn flat_regions_are_crossed_exactly() {
        // Checkerboards of 16 texels a square (flat boxes up to radius 8) and a board of
        // squares of one texel (no flat cell), decoded (with the flat-region map) and
        // computed on fetch (no map: one piece per cell). Colours exact in f32, so both
        // forms hold the same texels. Segments along texel rows and columns exactly on
        // cell borders, with one coordinate fixed, backwards, across the wrap, and long
        // (crossing up to ~200 cells): the map changes only rounding, and both agree with
        // the dense quadrature.
        let (a, b) = ([0.5, 0.25, 0.75, 1.0], [0.125, 0.625, 0.375, 0.5]);
        let mut next = uniform(11);
        for (squares, tps) in [(4u32, 16u32), (3, 5), (8, 1)] {
            let mapped = Texture::checker(squares, tps, a, b);
            let plain = Texture::checker_decoding(squares, tps, a, b, 0);
            assert!(matches!(mapped.texels, Texels::Linear(_)));
            assert!(matches!(plain.texels, Texels::Checker { .. }));
            let n = f64::from(squares * tps);
            // Texel-space integer k is u = (k + 0.5) / n: a cell border.
            let border = |k: f64| (k + 0.5) / n;
            let mut cases = vec![
                (DVec2::new(border(3.0), 0.3), DVec2::new(border(3.0), 1.9)),
                (
                    DVec2::new(0.1, 1.0 - border(7.0)),
                    DVec2::new(-1.3, 1.0 - border(7.0)),
                ),
                (
                    DVec2::new(border(0.0), border(0.0)),
                    DVec2::new(border(40.0), border(40.0)),
                ),
                (DVec2::new(0.97, 0.5), DVec2::new(1.8, 0.52)),
                (DVec2::new(-2.2, 3.1), DVec2::new(0.4, 2.0)),
            ];
            for _ in 0..30 {
                let a = DVec2::new(4.0 * next() - 2.0, 4.0 * next() - 2.0);
                let len = 3.0 * next();
                let dir = DVec2::from_angle(std::f64::consts::TAU * next());
                cases.push((a, a + len * dir));
            }
            for (uv0, uv1) in cases {
                let got = mapped.segment_average(uv0, uv1, 0.3, 1.2);
                let per_cell = plain.segment_average(uv0, uv1, 0.3, 1.2);
                let dense = dense_average(&mapped, uv0, uv1, 0.3, 1.2, 1 << 17);
                for k in 0..4 {
                    assert!(
                        (got[k] - per_cell[k]).abs() < 1e-12,
                        "{squares}x{tps} {uv0} -> {uv1}: {got:?} vs per cell {per_cell:?}"
                    );
                    assert!(
                        (got[k] - dense[k]).abs() < 1e-4,
                        "{squares}x{tps} {uv0} -> {uv1}: {got:?} vs dense {dense:?}"
                    );
                }
            }
        }
    }
}
