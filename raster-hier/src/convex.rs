//! The convex hull of a moving triangle's six projected vertices (three at each end of a
//! time interval), the screen-space bound of the region it sweeps while w > 0.
//!
//! With every vertex in front of the eye (w > 0), each projected vertex moves along the
//! screen segment between its two projections (the projection of a 2DH segment with w > 0),
//! and the projected triangle at time t is the triangle of its projected vertices. Every
//! covered point is therefore a convex combination of the six projected vertices: the swept
//! region lies in their convex hull ([`SweptHull`]). Two queries on it:
//! - per row, the exact slice of the hull ([`SweptHull::row`], [`SweptHull::pixels`]): the
//!   pixel columns the analytic renderer evaluates a moving triangle at;
//! - per tile, the CONVEX baseline's tile test (Munkberg 2011, §7, after McGuire et al.
//!   2010): tiles against the hull's edge lines ([`ConvexHull`], [`SweptHull::edges`]).

use arrayvec::ArrayVec;
use num_traits::Float;

/// Slack added on both sides of each row span of [`SweptHull::pixels`], in pixels: covers
/// the rounding of a sweep's own arithmetic (f32 vertices near the span ends), so a pixel
/// centre the sweep would find covered is never skipped.
pub const ROW_SLACK: f64 = 1.0 / 64.0;

/// The six projected vertices `(x / w, y / w)` of a moving triangle: its three corners at
/// the start of a time interval, then at its end. Their convex hull bounds the screen region
/// the triangle covers in between, as long as every w stays positive (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweptHull {
    /// The projected vertices (start, then end), in pixels, in f64.
    pub points: [[f64; 2]; 6],
}

impl SweptHull {
    /// The hull of the 2DH corners `(x, y, w)` `a` (start) and `b` (end): each divided by
    /// its w in `F`, then widened to f64. Not finite where a w is zero.
    pub fn project<F: Float>(a: &[[F; 3]; 3], b: &[[F; 3]; 3]) -> Self {
        let f = |v: F| v.to_f64().unwrap_or(0.0);
        SweptHull {
            points: core::array::from_fn(|i| {
                let p = if i < 3 { a[i] } else { b[i - 3] };
                [f(p[0] / p[2]), f(p[1] / p[2])]
            }),
        }
    }

    /// The x extent `[x_lo, x_hi]` of the hull on the line at height `y`, or `None` when
    /// the line misses it.
    ///
    /// A horizontal line meets the hull in one segment whose ends lie on hull edges, which
    /// are segments between two of the six points, and every such segment lies inside the
    /// hull; so the exact slice is the min / max over the 15 point pairs straddling the line.
    pub fn row(&self, y: f64) -> Option<(f64, f64)> {
        let p = &self.points;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..6 {
            let a = p[i];
            if a[1] == y {
                lo = lo.min(a[0]);
                hi = hi.max(a[0]);
            }
            for b in &p[i + 1..] {
                if (a[1] < y) != (b[1] < y) && a[1] != b[1] {
                    let x = a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
                    lo = lo.min(x);
                    hi = hi.max(x);
                }
            }
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// Pixel columns `x0..=x1` of row `y` (centre `y + 0.5`) whose centres lie within
    /// [`ROW_SLACK`] of the hull, intersected with `lo..=hi`; `None` when empty. A
    /// conservative bound per row, tighter than the bounding box when the motion is diagonal
    /// or curved in screen space.
    pub fn pixels(&self, y: u32, lo: u32, hi: u32) -> Option<(u32, u32)> {
        let cy = f64::from(y) + 0.5;
        row_pixels(
            band_of_rows(|y| self.row(y), (cy - ROW_SLACK, cy + ROW_SLACK)),
            lo,
            hi,
        )
    }

    /// The hull's edge lines, each pushed outwards by `pad` pixels ([`ConvexHull::new`]).
    pub fn edges(&self, pad: f64) -> ConvexHull {
        ConvexHull::new(&self.points, pad)
    }

    /// The hull set up for many row queries ([`HullRows`]): its outline computed once, so
    /// a row tests at most six edges instead of the fifteen point pairs of
    /// [`SweptHull::row`].
    pub fn rows(&self) -> HullRows {
        let p = &self.points;
        if p.iter().flatten().all(|v| v.is_finite()) {
            HullRows {
                corners: outline(p),
                all_pairs: false,
            }
        } else {
            // Non-finite points: every pair, as `row` takes them (comparisons with NaN
            // are false, so such points drop out the same way).
            HullRows {
                corners: p.iter().copied().collect(),
                all_pairs: true,
            }
        }
    }
}

/// A [`SweptHull`] prepared for row queries: the corners and sides of its outline (the
/// convex polygon of the six points; for a degenerate hull a segment or a point). A
/// horizontal line meets a convex polygon in the segment between its crossings with the
/// sides, so the slice is the min / max over the sides straddling the line, the same
/// value [`SweptHull::row`] finds among all fifteen point pairs.
#[derive(Clone, Debug, PartialEq)]
pub struct HullRows {
    /// Outline corners in order (or all six points when one is not finite).
    corners: ArrayVec<[f64; 2], 6>,
    /// True when `corners` are the six points, whose fifteen pairs are all tested.
    all_pairs: bool,
}

impl HullRows {
    /// The x extent `[x_lo, x_hi]` of the hull on the line at height `y`, or `None` when
    /// the line misses it ([`SweptHull::row`]).
    pub fn row(&self, y: f64) -> Option<(f64, f64)> {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for a in &self.corners {
            if a[1] == y {
                lo = lo.min(a[0]);
                hi = hi.max(a[0]);
            }
        }
        let mut side = |a: &[f64; 2], b: &[f64; 2]| {
            if (a[1] < y) != (b[1] < y) && a[1] != b[1] {
                let x = a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
                lo = lo.min(x);
                hi = hi.max(x);
            }
        };
        let c = &self.corners;
        if self.all_pairs {
            for (i, a) in c.iter().enumerate() {
                for b in &c[i + 1..] {
                    side(a, b);
                }
            }
        } else if c.len() == 2 {
            side(&c[0], &c[1]);
        } else if c.len() > 2 {
            for (i, a) in c.iter().enumerate() {
                side(a, &c[(i + 1) % c.len()]);
            }
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// The x extent of the hull over the band `y0 <= y <= y1` (`y0 <= y1`), or `None` when
    /// the band misses it: over a convex polygon it is reached at a corner inside the band
    /// or where a side crosses one of the band's two edges, so one pass over the outline
    /// finds it (a superset of the slices at `y0`, `y1` and every height between).
    pub fn band(&self, y0: f64, y1: f64) -> Option<(f64, f64)> {
        let c = &self.corners;
        if self.all_pairs {
            return band_of_rows(|y| self.row(y), (y0, y1));
        }
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for a in c {
            if y0 <= a[1] && a[1] <= y1 {
                lo = lo.min(a[0]);
                hi = hi.max(a[0]);
            }
        }
        let mut side = |a: &[f64; 2], b: &[f64; 2]| {
            if a[1] == b[1] {
                return;
            }
            let slope = (b[0] - a[0]) / (b[1] - a[1]);
            for y in [y0, y1] {
                if (a[1] < y) != (b[1] < y) {
                    let x = a[0] + (y - a[1]) * slope;
                    lo = lo.min(x);
                    hi = hi.max(x);
                }
            }
        };
        if c.len() == 2 {
            side(&c[0], &c[1]);
        } else if c.len() > 2 {
            let mut prev = &c[c.len() - 1];
            for a in c {
                side(prev, a);
                prev = a;
            }
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// Pixel columns `x0..=x1` of row `y` whose centres lie within [`ROW_SLACK`] of the
    /// hull, intersected with `lo..=hi`: the hull's extent over the band within
    /// [`ROW_SLACK`] of the row's centre line ([`HullRows::band`]), widened by it.
    pub fn pixels(&self, y: u32, lo: u32, hi: u32) -> Option<(u32, u32)> {
        let cy = f64::from(y) + 0.5;
        row_pixels(self.band(cy - ROW_SLACK, cy + ROW_SLACK), lo, hi)
    }
}

/// The x extent over the band `(y0, y1)` of a convex region whose slice at height `y` is
/// `row(y)`, from three slices: at both edges and the middle. Convexity makes the band's
/// extent the slices at its edges, except near a corner inside the band, which the middle
/// slice and [`ROW_SLACK`]'s widening cover.
fn band_of_rows(
    row: impl Fn(f64) -> Option<(f64, f64)>,
    (y0, y1): (f64, f64),
) -> Option<(f64, f64)> {
    let none = (f64::INFINITY, f64::NEG_INFINITY);
    let (a0, a1) = row(y0).unwrap_or(none);
    let (b0, b1) = row(y1).unwrap_or(none);
    let (c0, c1) = row(0.5 * (y0 + y1)).unwrap_or(none);
    let (l, h) = (a0.min(b0).min(c0), a1.max(b1).max(c1));
    (l <= h).then_some((l, h))
}

/// The columns whose centres lie within [`ROW_SLACK`] of the x extent `extent` of a row
/// band, intersected with `lo..=hi`.
fn row_pixels(extent: Option<(f64, f64)>, lo: u32, hi: u32) -> Option<(u32, u32)> {
    let (l, h) = extent?;
    let (l, h) = (l - ROW_SLACK, h + ROW_SLACK);
    if l.partial_cmp(&h).is_none_or(|o| o.is_gt()) {
        return None;
    }
    let first = (l - 0.5).ceil().max(f64::from(lo));
    let last = (h - 0.5).floor().min(f64::from(hi));
    (first <= last).then_some((first as u32, last as u32))
}

/// The convex outline of `points` counter-clockwise (Andrew's monotone chain; collinear
/// points dropped): at most six corners, two for collinear points, one when all coincide.
fn outline(points: &[[f64; 2]; 6]) -> ArrayVec<[f64; 2], 6> {
    let mut p: ArrayVec<[f64; 2], 6> = points.iter().copied().collect();
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    let mut hull: ArrayVec<[f64; 2], 12> = ArrayVec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: ArrayVec<[f64; 2], 6> = if pass == 0 {
            p.clone()
        } else {
            p.iter().rev().copied().collect()
        };
        for q in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    // All points equal: both chains popped back to nothing.
    if hull.is_empty() {
        hull.push(p[0]);
    }
    hull.iter().take(6).copied().collect()
}

/// The convex hull of a moving triangle's six projected vertices as at most six edge lines
/// `a x + b y + c ≤ 0` (unit normals, pushed out by a rounding margin), computed in f64.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexHull {
    edges: ArrayVec<[f64; 3], 6>,
}

fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

impl ConvexHull {
    /// The hull of `points` (Andrew's monotone chain), each edge pushed outwards by `pad`
    /// pixels. Fewer than three distinct hull points (a degenerate hull) give no edges, so
    /// the test accepts every tile of the bound — conservative.
    pub fn new(points: &[[f64; 2]; 6], pad: f64) -> Self {
        let hull = outline(points);
        let mut edges = ArrayVec::new();
        if hull.len() >= 3 {
            for i in 0..hull.len() {
                let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
                let (nx, ny) = (b[1] - a[1], -(b[0] - a[0]));
                let len = (nx * nx + ny * ny).sqrt();
                if len > 0.0 && edges.len() < 6 {
                    let (nx, ny) = (nx / len, ny / len);
                    edges.push([nx, ny, -(nx * a[0] + ny * a[1]) - pad]);
                }
            }
        }
        ConvexHull { edges }
    }

    /// Number of hull edges (0 for a degenerate hull).
    pub fn len(&self) -> usize {
        self.edges.len()
    }

    /// True for a degenerate hull (no edges).
    pub fn is_empty(&self) -> bool {
        self.edges.is_empty()
    }

    /// Tile `[x0, x1] x [y0, y1]` against the hull edges: rejected when some edge has all
    /// four corners outside (the corner minimising the edge function is chosen by signs).
    pub fn overlaps(&self, x0: f64, y0: f64, x1: f64, y1: f64) -> bool {
        self.edges.iter().all(|e| {
            let x = if e[0] >= 0.0 { x0 } else { x1 };
            let y = if e[1] >= 0.0 { y0 } else { y1 };
            e[0] * x + e[1] * y + e[2] <= 0.0
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_translated_triangle() {
        let pts = [
            [0.0, 0.0],
            [4.0, 0.0],
            [0.0, 4.0],
            [10.0, 0.0],
            [14.0, 0.0],
            [10.0, 4.0],
        ];
        let h = ConvexHull::new(&pts, 0.0);
        assert_eq!(h.len(), 4);
        assert!(h.overlaps(11.0, 1.0, 12.0, 2.0));
        assert!(!h.overlaps(12.0, 3.5, 14.0, 5.0));
        assert!(!h.overlaps(-3.0, 0.0, -1.0, 1.0));
    }

    /// Dense check: every pixel centre inside the hull (by a point-in-convex-polygon test
    /// built from all point triples) is inside the returned row span.
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
                points: [0; 6].map(|_| [rnd(), rnd()]),
            };
            // In the hull iff inside some triangle of three of the points.
            let inside = |q: [f64; 2]| {
                let p = &h.points;
                (0..6).any(|i| {
                    (i + 1..6).any(|j| {
                        (j + 1..6).any(|k| {
                            let (d0, d1, d2) = (
                                cross(p[i], p[j], q),
                                cross(p[j], p[k], q),
                                cross(p[k], p[i], q),
                            );
                            (d0 >= 0.0 && d1 >= 0.0 && d2 >= 0.0)
                                || (d0 <= 0.0 && d1 <= 0.0 && d2 <= 0.0)
                        })
                    })
                })
            };
            let rows = h.rows();
            for y in 0..40u32 {
                for span in [h.pixels(y, 0, 39), rows.pixels(y, 0, 39)] {
                    for x in 0..40u32 {
                        if inside([f64::from(x) + 0.5, f64::from(y) + 0.5]) {
                            let (a, b) = span.expect("a covered centre in an empty row");
                            assert!(a <= x && x <= b, "{x} not in {a}..={b} at row {y}");
                        }
                    }
                }
            }
        }
    }

    /// The outline's slices against all fifteen point pairs, on random hulls, hulls with
    /// repeated and collinear points, and hulls with a non-finite point.
    #[test]
    fn outline_rows_equal_all_pair_rows() {
        let mut seed = 777u64;
        let mut rnd = |n: f64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (((seed >> 33) as f64) / f64::from(1u32 << 31) * n).floor()
        };
        for case in 0..3000 {
            // Coarse integer coordinates make repeated, collinear and horizontal cases common.
            let mut points = [0; 6].map(|_| [rnd(8.0), rnd(8.0)]);
            if case % 7 == 0 {
                points[case % 6] = [f64::NAN, 1.0];
            }
            if case % 11 == 0 {
                points = [points[0]; 6];
            }
            let h = SweptHull { points };
            let rows = h.rows();
            for k in 0..=64 {
                let y = -0.5 + 9.0 * f64::from(k) / 64.0;
                let (a, b) = (h.row(y), rows.row(y));
                match (a, b) {
                    (Some(a), Some(b)) => assert!(
                        (a.0 - b.0).abs() <= 1e-12 && (a.1 - b.1).abs() <= 1e-12,
                        "{points:?} at {y}: {a:?} vs {b:?}"
                    ),
                    _ => assert_eq!(a, b, "{points:?} at {y}"),
                }
            }
        }
    }

    /// The band extent against the slices of all fifteen point pairs at the band's edges,
    /// at every point's height inside the band (where a convex region's extent over a band
    /// is reached) and at 33 heights between: it contains all of them and equals the
    /// largest.
    #[test]
    fn band_extent_is_the_union_of_its_slices() {
        let mut seed = 4242u64;
        let mut rnd = |n: f64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 33) as f64) / f64::from(1u32 << 31) * n
        };
        for case in 0..3000 {
            let mut points = [0; 6].map(|_| [rnd(8.0), rnd(8.0)]);
            if case % 5 == 0 {
                points = points.map(|p| p.map(f64::floor));
            }
            let h = SweptHull { points };
            let rows = h.rows();
            let y0 = rnd(10.0) - 1.0;
            let y1 = y0 + if case % 3 == 0 { 1.0 / 32.0 } else { rnd(2.0) };
            let mut heights = vec![y0, y1];
            heights.extend((1..33).map(|k| y0 + (y1 - y0) * f64::from(k) / 33.0));
            heights.extend(
                points
                    .iter()
                    .map(|p| p[1])
                    .filter(|y| (y0..=y1).contains(y)),
            );
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for y in heights {
                if let Some((a, b)) = h.row(y) {
                    lo = lo.min(a);
                    hi = hi.max(b);
                }
            }
            match rows.band(y0, y1) {
                Some((a, b)) => assert!(
                    (a - lo).abs() <= 1e-9 && (b - hi).abs() <= 1e-9,
                    "{points:?} over {y0}..{y1}: {a}..{b} vs {lo}..{hi}"
                ),
                None => assert!(lo > hi, "{points:?} over {y0}..{y1}: missed {lo}..{hi}"),
            }
        }
    }

    #[test]
    fn horizontal_motion_gives_tight_rows() {
        let t = [[10.0, 10.0], [12.0, 10.0], [10.0, 12.0]];
        let moved = t.map(|[x, y]| [x + 20.0, y]);
        let h = SweptHull {
            points: [t[0], t[1], t[2], moved[0], moved[1], moved[2]],
        };
        assert_eq!(h.pixels(10, 0, 100), Some((10, 31)));
        assert_eq!(h.pixels(20, 0, 100), None);
    }

    #[test]
    fn projection_divides_by_w() {
        let a = [[2.0f32, 4.0, 2.0], [6.0, 3.0, 3.0], [1.0, 1.0, 1.0]];
        let b = a.map(|[x, y, w]| [x + w, y, w]);
        let h = SweptHull::project(&a, &b);
        assert_eq!(h.points[0], [1.0, 2.0]);
        assert_eq!(h.points[4], [3.0, 1.0]);
        assert_eq!(h.edges(0.0).len(), ConvexHull::new(&h.points, 0.0).len());
    }
}
