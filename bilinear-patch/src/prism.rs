//! The space-time prism of a moving triangle and its coverage of a pixel centre
//! (Rønnow et al. 2021, §3 Fig. 3, §4.1 Fig. 5-6).
//!
//! The prism lives in (x, y, t) space: x, y in pixel units (already divided by w) and t the
//! shutter time in [0, 1]. Its caps are the triangle at shutter open (t = 0) and close
//! (t = 1); its sides are the bilinear patches swept by the edges, corners
//! `[a(0), b(0), b(1), a(1)]` for edge a → b, so the patch parameter v across the side is the
//! time and u runs along the edge. The ray of pixel centre (px, py) is the line
//! `(px, py, 0) + t (0, 0, 1)`: its parameter is the time itself, and the horizontal slice
//! of the prism at height t is exactly the triangle at time t.

use arrayvec::ArrayVec;
use core::ops::Deref;
use num_traits::Float;

use crate::patch::Patch;
use crate::ray::Ray;
use crate::triangle::Triangle;

/// A vertex of the moving triangle at one instant, in screen space: `x`, `y` in pixel units
/// (already divided by w) and a depth value that is interpolated linearly (Rønnow 2021, §3).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScreenVertex<F> {
    /// Horizontal position in pixels.
    pub x: F,
    /// Vertical position in pixels.
    pub y: F,
    /// Depth (smaller is nearer).
    pub depth: F,
}

/// Which face of the prism a hit lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Face {
    /// The triangle at shutter open (t = 0).
    Open,
    /// The bilinear patch swept by edge `i → (i + 1) % 3`.
    Side(u8),
    /// The triangle at shutter close (t = 1).
    Close,
}

/// One hit of a pixel's time line with the prism (Rønnow 2021, §4.1 "intersection sample").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrismHit<F> {
    /// Shutter time of the hit, in [0, 1].
    pub time: F,
    /// Depth at the hit, interpolated from the vertex depths at open and close.
    pub depth: F,
    /// Barycentrics `(u, v)` of the moving triangle at the hit: the point is
    /// `(1 - u - v) v0(t) + u v1(t) + v v2(t)`.
    pub uv: [F; 2],
    /// The face that was hit.
    pub face: Face,
}

/// Up to eight prism hits sorted by time (two caps, two per side patch). Dereferences to
/// `&[PrismHit<F>]`.
#[derive(Clone, Debug, PartialEq)]
pub struct PrismHits<F>(ArrayVec<PrismHit<F>, 8>);

impl<F> Default for PrismHits<F> {
    fn default() -> Self {
        PrismHits(ArrayVec::new())
    }
}

impl<F> Deref for PrismHits<F> {
    type Target = [PrismHit<F>];
    fn deref(&self) -> &[PrismHit<F>] {
        &self.0
    }
}

/// A time span during which the triangle covers the pixel centre, with depth and triangle
/// barycentrics at both ends (Rønnow 2021, Fig. 6: t_s, t_e, z_s, z_e, uv_s, uv_e). The same
/// `t0`, `t1` shape as edge-eqn's coverage spans.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span<F> {
    /// Entry time.
    pub t0: F,
    /// Exit time (`t1 > t0`).
    pub t1: F,
    /// Depth at entry.
    pub depth0: F,
    /// Depth at exit.
    pub depth1: F,
    /// Triangle barycentrics (weights of v1, v2) at entry.
    pub uv0: [F; 2],
    /// Triangle barycentrics (weights of v1, v2) at exit.
    pub uv1: [F; 2],
}

/// The coverage spans of a pixel centre, at most four (Rønnow 2021, §4.1), sorted by time
/// and disjoint. Dereferences to `&[Span<F>]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Coverage<F>(ArrayVec<Span<F>, 4>);

impl<F> Default for Coverage<F> {
    fn default() -> Self {
        Coverage(ArrayVec::new())
    }
}

impl<F> Deref for Coverage<F> {
    type Target = [Span<F>];
    fn deref(&self) -> &[Span<F>] {
        &self.0
    }
}

/// The prism swept by a linearly moving screen-space triangle (Rønnow 2021, Fig. 3): two cap
/// triangles and three bilinear side patches in (x, y, t) space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prism<F> {
    open: [ScreenVertex<F>; 3],
    close: [ScreenVertex<F>; 3],
    sides: [Patch<F>; 3],
    caps: [Triangle<F>; 2],
}

impl<F: Float> Prism<F> {
    /// Prism of the triangle with vertices `open` at t = 0 and `close` at t = 1, each vertex
    /// moving on a straight line in (x, y) and in depth.
    pub fn new(open: [ScreenVertex<F>; 3], close: [ScreenVertex<F>; 3]) -> Self {
        let (z, o) = (F::zero(), F::one());
        let p0 = open.map(|p| [p.x, p.y, z]);
        let p1 = close.map(|p| [p.x, p.y, o]);
        let side = |i: usize| {
            let j = (i + 1) % 3;
            Patch::new([p0[i], p0[j], p1[j], p1[i]])
        };
        Prism {
            open,
            close,
            sides: [side(0), side(1), side(2)],
            caps: [Triangle::new(p0), Triangle::new(p1)],
        }
    }

    /// Prism from `(x, y, depth)` triples at shutter open and close.
    pub fn from_arrays(open: [[F; 3]; 3], close: [[F; 3]; 3]) -> Self {
        let v = |p: [F; 3]| ScreenVertex {
            x: p[0],
            y: p[1],
            depth: p[2],
        };
        Prism::new(open.map(v), close.map(v))
    }

    /// Prism from 2DH vertices `(x, y, w)` at shutter open (`q`) and close (`r`), the input
    /// edge-eqn takes: positions are divided by w at both ends and w is used as the depth.
    /// Between the ends the prism moves the projected vertices linearly, which is exact only
    /// when w does not change (see the crate doc). `None` when some w is not positive or a
    /// value is not finite.
    pub fn from_homogeneous(q: [[F; 3]; 3], r: [[F; 3]; 3]) -> Option<Self> {
        let project = |p: [F; 3]| {
            let ok = p[2] > F::zero() && p.iter().all(|c| c.is_finite());
            let v = ScreenVertex {
                x: p[0] / p[2],
                y: p[1] / p[2],
                depth: p[2],
            };
            (ok && v.x.is_finite() && v.y.is_finite()).then_some(v)
        };
        let [a, b, c] = q.map(project);
        let [d, e, f] = r.map(project);
        Some(Prism::new([a?, b?, c?], [d?, e?, f?]))
    }

    /// The vertices at shutter open and close.
    pub fn vertices(&self) -> ([ScreenVertex<F>; 3], [ScreenVertex<F>; 3]) {
        (self.open, self.close)
    }

    /// The triangle at time t: `(1 - t) open + t close` per vertex.
    pub fn at(&self, t: F) -> [ScreenVertex<F>; 3] {
        let l = |a: F, b: F| a + t * (b - a);
        let mut out = self.open;
        for (o, c) in out.iter_mut().zip(self.close.iter()) {
            *o = ScreenVertex {
                x: l(o.x, c.x),
                y: l(o.y, c.y),
                depth: l(o.depth, c.depth),
            };
        }
        out
    }

    /// Whether the triangle at time t covers (px, py): inside or on all three edges, for
    /// either orientation (the prism has no back face in time). A triangle of zero area
    /// covers nothing.
    pub fn covers(&self, px: F, py: F, t: F) -> bool {
        let v = self.at(t);
        let e = |a: &ScreenVertex<F>, b: &ScreenVertex<F>| {
            (a.x - px) * (b.y - py) - (a.y - py) * (b.x - px)
        };
        let (e0, e1, e2) = (e(&v[0], &v[1]), e(&v[1], &v[2]), e(&v[2], &v[0]));
        let z = F::zero();
        let area2 = e0 + e1 + e2;
        area2 != z && ((e0 >= z && e1 >= z && e2 >= z) || (e0 <= z && e1 <= z && e2 <= z))
    }

    /// Barycentrics and depth of (px, py) in the triangle at time t (a degenerate triangle
    /// gives vertex 0's values).
    fn sample(&self, px: F, py: F, t: F, face: Face) -> PrismHit<F> {
        let v = self.at(t);
        let (ax, ay) = (v[1].x - v[0].x, v[1].y - v[0].y);
        let (bx, by) = (v[2].x - v[0].x, v[2].y - v[0].y);
        let (cx, cy) = (px - v[0].x, py - v[0].y);
        let det = ax * by - ay * bx;
        let (mut u, mut w) = ((cx * by - cy * bx) / det, (ax * cy - ay * cx) / det);
        if !(u.is_finite() && w.is_finite()) {
            (u, w) = (F::zero(), F::zero());
        }
        let depth = v[0].depth + u * (v[1].depth - v[0].depth) + w * (v[2].depth - v[0].depth);
        PrismHit {
            time: t,
            depth,
            uv: [u, w],
            face,
        }
    }

    /// All hits of the time line through pixel centre (px, py) with the prism, sorted by
    /// time (Rønnow 2021, §4.1: two ray/triangle and three ray/patch tests, up to 8 hits).
    /// All five tests share one [`Ray`], so a pixel centre on a shared edge is counted once.
    /// Non-finite input gives no hits.
    pub fn hits(&self, px: F, py: F) -> PrismHits<F> {
        let mut out = PrismHits::default();
        let (z, o) = (F::zero(), F::one());
        let Some(ray) = Ray::new([px, py, z], [z, z, o]) else {
            return out;
        };
        let (t_min, t_max) = (-o, o + o);
        let mut push = |h: PrismHit<F>| {
            if h.depth.is_finite() && !out.0.is_full() {
                out.0.push(h);
            }
        };
        for (cap, (verts, face)) in self
            .caps
            .iter()
            .zip([(&self.open, Face::Open), (&self.close, Face::Close)])
        {
            if let Some(h) = cap.intersect_ray(&ray, t_min, t_max) {
                let w0 = o - h.u - h.v;
                let depth = w0 * verts[0].depth + h.u * verts[1].depth + h.v * verts[2].depth;
                let time = if face == Face::Open { z } else { o };
                push(PrismHit {
                    time,
                    depth,
                    uv: [h.u, h.v],
                    face,
                });
            }
        }
        for (i, side) in self.sides.iter().enumerate() {
            let j = (i + 1) % 3;
            for h in side.intersect_ray(&ray, t_min, t_max).iter() {
                // v is the time (the ray parameter equals it up to rounding).
                let (u, time) = (h.u, h.v);
                let l = |a: F, b: F, s: F| a + s * (b - a);
                let da = l(self.open[i].depth, self.close[i].depth, time);
                let db = l(self.open[j].depth, self.close[j].depth, time);
                let uv = match i {
                    0 => [u, z],
                    1 => [o - u, u],
                    _ => [z, o - u],
                };
                push(PrismHit {
                    time,
                    depth: l(da, db, u),
                    uv,
                    face: Face::Side(i as u8),
                });
            }
        }
        // Insertion sort by (time, face rank): at equal times the open cap comes first and
        // the close cap last.
        let rank = |f: Face| match f {
            Face::Open => 0,
            Face::Side(_) => 1,
            Face::Close => 2,
        };
        let hs = out.0.as_mut_slice();
        for k in 1..hs.len() {
            let mut m = k;
            while m > 0 {
                let (a, b) = (hs[m - 1], hs[m]);
                let later = a.time > b.time || (a.time == b.time && rank(a.face) > rank(b.face));
                if !later {
                    break;
                }
                hs.swap(m - 1, m);
                m -= 1;
            }
        }
        out
    }

    /// Coverage spans of pixel centre (px, py): the hits sorted by time and paired into
    /// entry/exit spans (Rønnow 2021, §4.1, Fig. 5). Spans of zero length (a tangent graze)
    /// are left out.
    ///
    /// The shared-edge decisions are exact, so the hit count is even except in doubly
    /// degenerate configurations that the symbolic tie-break does not resolve (the centre
    /// exactly on a vertex that does not move, an edge touching the centre tangentially in
    /// time exactly at t = 0 or 1). Then the time line is cast again from the centre moved
    /// by 16 ulps of its coordinates in a few directions, and the first even hit list is
    /// used; failing that, each gap between consecutive events (shutter open, the hits,
    /// shutter close) is classified by [`Prism::covers`] at its midpoint.
    pub fn coverage(&self, px: F, py: F) -> Coverage<F> {
        let mut hits = self.hits(px, py);
        if !hits.len().is_multiple_of(2) {
            let one = F::one();
            let half = one / (one + one);
            let delta = F::epsilon() * F::from(16).unwrap_or(one) * px.abs().max(py.abs()).max(one);
            for (dx, dy) in [(one, half), (-half, one), (-one, -half), (half, -one)] {
                let moved = self.hits(px + dx * delta, py + dy * delta);
                if moved.len().is_multiple_of(2) {
                    hits = moved;
                    break;
                }
            }
        }
        let mut out = Coverage::default();
        let mut push = |a: &PrismHit<F>, b: &PrismHit<F>| {
            let finite = [a.depth, b.depth, a.uv[0], a.uv[1], b.uv[0], b.uv[1]]
                .iter()
                .all(|x| x.is_finite());
            if b.time > a.time && finite && !out.0.is_full() {
                out.0.push(Span {
                    t0: a.time,
                    t1: b.time,
                    depth0: a.depth,
                    depth1: b.depth,
                    uv0: a.uv,
                    uv1: b.uv,
                });
            }
        };
        if hits.len().is_multiple_of(2) {
            for pair in hits.chunks_exact(2) {
                push(&pair[0], &pair[1]);
            }
            return out;
        }
        // Fallback: classify every gap between consecutive events (shutter open, the hits,
        // shutter close) by the static inside test at its midpoint and merge covered runs.
        let two = F::one() + F::one();
        let mut events: ArrayVec<PrismHit<F>, 10> = ArrayVec::new();
        events.push(self.sample(px, py, F::zero(), Face::Open));
        events.extend(hits.iter().copied());
        events.push(self.sample(px, py, F::one(), Face::Close));
        let mut start: Option<usize> = None;
        for k in 0..events.len() - 1 {
            let (a, b) = (events[k].time, events[k + 1].time);
            if b.partial_cmp(&a) != Some(core::cmp::Ordering::Greater) {
                continue;
            }
            let inside = self.covers(px, py, (a + b) / two);
            match (inside, start) {
                (true, None) => start = Some(k),
                (false, Some(s)) => {
                    push(&events[s], &events[k]);
                    start = None;
                }
                _ => {}
            }
        }
        if let (Some(s), Some(last)) = (start, events.last()) {
            push(&events[s], last);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangle_sweeping_across_a_pixel() {
        // A triangle moving 10 px to the right covers the pixel centre for part of the
        // shutter: x from 0..2 at t = 0 to 10..12 at t = 1; centre 5.5 → covered while
        // the left edge x = 10t <= 5.5 and the slanted edge is right of it.
        let open = [[0.0f64, 0.0, 1.0], [2.0, 0.0, 1.0], [0.0, 10.0, 1.0]];
        let close = [[10.0f64, 0.0, 3.0], [12.0, 0.0, 3.0], [10.0, 10.0, 3.0]];
        let prism = Prism::from_arrays(open, close);
        let cov = prism.coverage(5.5, 0.5);
        assert_eq!(cov.len(), 1);
        // Slanted edge x + y/5 = 2 + 10 t → enters at t = (5.5 + 0.1 - 2) / 10 = 0.36;
        // left edge x = 10 t exits at 0.55.
        let s = cov[0];
        assert!(
            (s.t0 - 0.36).abs() < 1e-12 && (s.t1 - 0.55).abs() < 1e-12,
            "{s:?}"
        );
        assert!((s.depth0 - 1.72).abs() < 1e-12 && (s.depth1 - 2.1).abs() < 1e-12);
    }
}
