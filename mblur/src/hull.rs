//! Per-row pixel spans of the screen region a moving triangle can cover during the shutter.
//!
//! With all vertices in front of the eye for the whole shutter (w > 0), each projected
//! vertex moves along the screen segment between its projections at open and close (the
//! projection of a 2DH segment with w > 0), and the projected triangle at time t is the
//! triangle of its projected vertices. Every covered point is therefore a convex
//! combination of the six projected vertices: the swept region lies in their convex hull.
//! A horizontal line meets that hull in one segment whose ends lie on hull edges, which are
//! segments between two of the six points, and every such segment lies inside the hull; so
//! the exact slice is the min / max over the 15 point pairs straddling the line. This is a
//! conservative bound per row, tighter than the bounding box when the motion is diagonal or
//! curved in screen space.

use glam::DVec2;

/// Screen-space convex hull of a moving triangle's six projected vertices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweptHull {
    /// The six projected vertices (open, then close).
    pub points: [DVec2; 6],
}

/// Slack added on both sides of each row span, in pixels: covers the rounding of the
/// sweep's own arithmetic (f32 vertices near the span ends), so a pixel centre the sweep
/// would find covered is never skipped.
pub const SLACK: f64 = 1.0 / 64.0;

impl SweptHull {
    /// The x extent `[x_lo, x_hi]` of the hull on the line at height `y`, or `None` when
    /// the line misses it.
    pub fn row(&self, y: f64) -> Option<(f64, f64)> {
        let p = &self.points;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..6 {
            let a = p[i];
            if a.y == y {
                lo = lo.min(a.x);
                hi = hi.max(a.x);
            }
            for b in &p[i + 1..] {
                if (a.y < y) != (b.y < y) && a.y != b.y {
                    let x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
                    lo = lo.min(x);
                    hi = hi.max(x);
                }
            }
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// Pixel columns `x0..=x1` of row `y` (centre `y + 0.5`) whose centres lie within
    /// [`SLACK`] of the hull, intersected with `lo..=hi`; `None` when empty.
    pub fn pixels(&self, y: u32, lo: u32, hi: u32) -> Option<(u32, u32)> {
        let cy = f64::from(y) + 0.5;
        // The slice over the band [cy - SLACK, cy + SLACK] contains the slices at both ends
        // (convexity), and taking both covers a vertex lying just off the centre line.
        let (a0, a1) = self
            .row(cy - SLACK)
            .unwrap_or((f64::INFINITY, f64::NEG_INFINITY));
        let (b0, b1) = self
            .row(cy + SLACK)
            .unwrap_or((f64::INFINITY, f64::NEG_INFINITY));
        let (c0, c1) = self.row(cy).unwrap_or((f64::INFINITY, f64::NEG_INFINITY));
        let (l, h) = (a0.min(b0).min(c0) - SLACK, a1.max(b1).max(c1) + SLACK);
        if l.partial_cmp(&h).is_none_or(|o| o.is_gt()) {
            return None;
        }
        let first = (l - 0.5).ceil().max(f64::from(lo));
        let last = (h - 0.5).floor().min(f64::from(hi));
        (first <= last).then_some((first as u32, last as u32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dense check: every pixel centre inside the hull (by a point-in-convex-polygon test
    /// built from all point triples) is inside the returned span.
    #[test]
    fn row_spans_contain_every_covered_centre() {
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 33) as f64) / f64::from(1u32 << 31) * 40.0
        };
        for _ in 0..200 {
            let h = SweptHull {
                points: [0; 6].map(|_| DVec2::new(rnd(), rnd())),
            };
            // In the hull iff inside some triangle of three of the points.
            let inside = |q: DVec2| {
                let p = &h.points;
                (0..6).any(|i| {
                    (i + 1..6).any(|j| {
                        (j + 1..6).any(|k| {
                            let s = |a: DVec2, b: DVec2| (b - a).perp_dot(q - a);
                            let (d0, d1, d2) = (s(p[i], p[j]), s(p[j], p[k]), s(p[k], p[i]));
                            (d0 >= 0.0 && d1 >= 0.0 && d2 >= 0.0)
                                || (d0 <= 0.0 && d1 <= 0.0 && d2 <= 0.0)
                        })
                    })
                })
            };
            for y in 0..40u32 {
                let span = h.pixels(y, 0, 39);
                for x in 0..40u32 {
                    let q = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
                    if inside(q) {
                        let (a, b) = span.expect("a covered centre in an empty row");
                        assert!(a <= x && x <= b, "{x} not in {a}..={b} at row {y}");
                    }
                }
            }
        }
    }

    #[test]
    fn horizontal_motion_gives_tight_rows() {
        let t = [
            DVec2::new(10.0, 10.0),
            DVec2::new(12.0, 10.0),
            DVec2::new(10.0, 12.0),
        ];
        let h = SweptHull {
            points: [
                t[0],
                t[1],
                t[2],
                t[0] + DVec2::X * 20.0,
                t[1] + DVec2::X * 20.0,
                t[2] + DVec2::X * 20.0,
            ],
        };
        assert_eq!(h.pixels(10, 0, 100), Some((10, 31)));
        assert_eq!(h.pixels(20, 0, 100), None);
    }
}
