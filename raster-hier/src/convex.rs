//! The CONVEX baseline's tile test (Munkberg 2011, §7, after McGuire et al. 2010): tiles
//! against the screen-space convex hull of the six projected vertices, all times.

use arrayvec::ArrayVec;

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
}
