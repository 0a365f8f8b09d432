//! Tile vs moving triangle tests with temporal bounds (Munkberg 2011, §4): the moving
//! 2DH AABB against the four tile frustum planes (Eq. 1-2) and the moving edges, either
//! linearised (Eq. 4-9) or solved exactly per tile corner. Each returns trivial reject
//! (an empty interval) or a conservative interval t̂ that contains every time at which a
//! sample of the tile is covered (in front of the eye).

use edge_eqn::MovingEdge;
use num_traits::Float;

use crate::bound::Rect;
use crate::cull::{Facing, plane_margin};
use crate::interval::{TimeInterval, linear_nonpositive, lit};

/// How the moving-edge part of the tile test is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EdgeTest {
    /// Linearised edges (Eq. 4-9) with γ from the triangle's screen bound at setup (Eq. 7
    /// with S = the bound).
    LinearisedSetup,
    /// Linearised edges with γ recomputed per coarsest-level tile (Eq. 7 with S = the tile).
    LinearisedPerTile,
    /// The exact alternative: the quadratic edge function solved at each tile corner; for a
    /// fixed t the edge is linear in (x, y), so its minimum over the tile is at a corner and
    /// the per-edge time set is the union of the corners' sub-level sets.
    Exact,
    /// Linearised edges re-derived per tile at every level over the parent tile's time
    /// interval [t₀, t₁] (Eq. 4-9 with S = the tile and the expansion point t₀ instead of 0;
    /// see [`TileTester::edge_interval_window`]): γ and the time bounds tighten as tiles
    /// shrink and as the parent's interval narrows. At levels below the sample-pattern
    /// tile (quads, pixels) the traversal evaluates the pattern tile's linearisation around
    /// its own interval on each sub-tile ([`TileTester::sub_tile_interval`]; no box test).
    LinearisedPerLevel,
    /// [`EdgeTest::LinearisedPerLevel`] at the coarser levels and [`EdgeTest::Exact`] at the
    /// finest level only (the level whose interval decides which samples are tested). With
    /// levels below the pattern tile every level runs the full [`TileTester::test_window`]
    /// (box test included) and the finest (quads or pixels) the exact quadratic.
    ExactFinest,
}

/// Linearised edge parameters over a region S (Eq. 4-7): for winding σ and edge k,
/// σ e_k(s, t) ≥ σ h_k · s + γ t − M_k for all s ∈ S, t ∈ [0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Linearised<F> {
    /// The region S the parameters are valid for.
    pub region: Rect<F>,
    /// γ per winding (σ = +1, −1) and edge (Eq. 7).
    pub gamma: [[F; 3]; 2],
    /// Rounding margin M_k per edge (covers the evaluation error of e, o · s and γ).
    pub margin: [F; 3],
}

/// A tile's linearised moving edges over a time window (Eq. 4-9 around the window start
/// t₀, see [`TileTester::edge_window`]): per edge o(t₀), the slope vectors at τ = t₀ and
/// τ = t₁, and the rounding margin, valid for every point of the tile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeWindow<F> {
    tile: Rect<F>,
    window: TimeInterval<F>,
    /// Per winding σ = +1, −1 (`None` when the facing rules it out) and edge:
    /// σ o(t₀), σ (g + 2 t₀ f), σ (g + (t₀ + t₁) f) and the margin.
    sides: [Option<[WindowEdge<F>; 3]>; 2],
}

/// One edge of an [`EdgeWindow`] for one winding: σ o(t₀), the two σ slope vectors, margin.
type WindowEdge<F> = ([F; 3], [F; 3], [F; 3], F);

impl<F: Float> EdgeWindow<F> {
    /// The window the linearisation holds on.
    pub fn window(&self) -> TimeInterval<F> {
        self.window
    }

    /// The times in the window at which some point of `rect` (inside the linearised
    /// tile) can be covered: per winding and edge the n-corner of `rect` bounds
    /// σ o(t₀) · s and the slope, the edge's half-interval follows (Eq. 8-9), the edges
    /// are intersected and the windings joined. Empty if `rect` is not inside the tile.
    #[inline]
    pub fn interval(&self, rect: &Rect<F>) -> TimeInterval<F> {
        let z = F::zero();
        let (t0, t1) = (self.window.lo, self.window.hi);
        if self.window.is_empty()
            || !(rect.x0 >= self.tile.x0
                && rect.x1 <= self.tile.x1
                && rect.y0 >= self.tile.y0
                && rect.y1 <= self.tile.y1)
        {
            return TimeInterval::empty();
        }
        // min over the rectangle of v · (x, y, 1): the n-corner.
        let nmin = |v: [F; 3]| {
            let x = if v[0] >= z { rect.x0 } else { rect.x1 };
            let y = if v[1] >= z { rect.y0 } else { rect.y1 };
            dot(v, x, y)
        };
        let mut out = TimeInterval::empty();
        for side in self.sides.iter().flatten() {
            let mut iv = self.window;
            for &(o, s0, s1, margin) in side {
                let c = nmin(o) - margin;
                let g = nmin(s0).min(nmin(s1));
                // Without a division where the answer is the whole window or nothing: the
                // same results as the general branches below (there −c/g ≤ 0 resp. < 0).
                if c <= z && g <= z {
                    continue;
                }
                if c > z && g >= z {
                    iv = TimeInterval::empty();
                    break;
                }
                let ek = if g > z {
                    let u = -c / g;
                    if u < z {
                        TimeInterval::empty()
                    } else {
                        TimeInterval::new(t0, t0 + u)
                    }
                } else if g < z {
                    TimeInterval::new(t0 + -c / g, t1)
                } else if c <= z {
                    self.window
                } else {
                    TimeInterval::empty()
                };
                iv = iv.intersect(ek);
                if iv.is_empty() {
                    break;
                }
            }
            out = out.hull(iv);
        }
        out
    }
}

/// Per-triangle data for the tile tests, built once at triangle setup.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TileTester<F> {
    /// 2DH AABB of the vertices at t = 0: `[min, max]` of (x, y, w).
    pub box0: [[F; 3]; 2],
    /// 2DH AABB of the vertices at t = 1.
    pub box1: [[F; 3]; 2],
    /// The three moving edges (from edge-eqn's setup).
    pub edges: [MovingEdge<F>; 3],
    /// Which windings σ = +1 / −1 a covered sample can have.
    pub windings: [bool; 2],
    /// The triangle-level time interval (frustum culling), intersected into every result.
    pub frustum: TimeInterval<F>,
    /// Linearised parameters over the triangle's screen bound (γ at setup).
    pub setup: Linearised<F>,
}

fn aabb<F: Float>(p: &[[F; 3]; 3]) -> [[F; 3]; 2] {
    let mut lo = p[0];
    let mut hi = p[0];
    for v in &p[1..] {
        for c in 0..3 {
            lo[c] = lo[c].min(v[c]);
            hi[c] = hi[c].max(v[c]);
        }
    }
    [lo, hi]
}

#[inline]
fn dot<F: Float>(a: [F; 3], x: F, y: F) -> F {
    a[0] * x + a[1] * y + a[2]
}

#[inline]
fn abs_dot<F: Float>(a: [F; 3], x: F, y: F) -> F {
    a[0].abs() * x + a[1].abs() * y + a[2].abs()
}

impl<F: Float> TileTester<F> {
    /// The tester for a moving triangle with vertices `q` (open) and `r` (close), edges
    /// from edge-eqn's setup, its facing, frustum interval and screen bound.
    pub fn new(
        q: &[[F; 3]; 3],
        r: &[[F; 3]; 3],
        edges: [MovingEdge<F>; 3],
        facing: Facing,
        frustum: TimeInterval<F>,
        bound: Rect<F>,
    ) -> Self {
        let mut t = TileTester {
            box0: aabb(q),
            box1: aabb(r),
            edges,
            windings: facing.windings(),
            frustum,
            setup: Linearised {
                region: bound,
                gamma: [[F::zero(); 3]; 2],
                margin: [F::zero(); 3],
            },
        };
        t.setup = t.linearise(bound);
        t
    }

    /// Linearised parameters over region `s` (Eq. 7): γ = min over the corners of S of
    /// min(g · s, (f + g) · s) (both linear in s, so the minimum is at a corner), per winding.
    pub fn linearise(&self, s: Rect<F>) -> Linearised<F> {
        let corners = [(s.x0, s.y0), (s.x1, s.y0), (s.x0, s.y1), (s.x1, s.y1)];
        let mx = s.x0.abs().max(s.x1.abs());
        let my = s.y0.abs().max(s.y1.abs());
        let mut gamma = [[F::zero(); 3]; 2];
        let mut margin = [F::zero(); 3];
        for (k, e) in self.edges.iter().enumerate() {
            let fg = [e.f[0] + e.g[0], e.f[1] + e.g[1], e.f[2] + e.g[2]];
            let (mut lo, mut hi) = (F::infinity(), F::neg_infinity());
            for &(x, y) in &corners {
                let (a, b) = (dot(e.g, x, y), dot(fg, x, y));
                lo = lo.min(a).min(b);
                hi = hi.max(a).max(b);
            }
            gamma[0][k] = lo;
            gamma[1][k] = -hi;
            let mag = abs_dot(e.f, mx, my) + abs_dot(e.g, mx, my) + abs_dot(e.h, mx, my);
            margin[k] = mag * F::epsilon() * lit(64.0);
        }
        Linearised {
            region: s,
            gamma,
            margin,
        }
    }

    /// Moving AABB vs the four tile frustum planes with the n-vertex (Eq. 1-2). `tile` is
    /// in pixels; the planes are x ≥ x0 w, x ≤ x1 w, y ≥ y0 w, y ≤ y1 w. A plane test returns
    /// early with an empty interval (fine-grained trivial reject).
    pub fn box_interval(&self, tile: &Rect<F>) -> TimeInterval<F> {
        let z = F::zero();
        let o = F::one();
        let planes = [
            [-o, z, tile.x0],
            [o, z, -tile.x1],
            [z, -o, tile.y0],
            [z, o, -tile.y1],
        ];
        let mut iv = TimeInterval::full();
        for n in planes {
            // n-vertex: the corner minimising n · p, chosen by the signs of n.
            let pick = |b: &[[F; 3]; 2]| {
                core::array::from_fn(|c| if n[c] >= z { b[0][c] } else { b[1][c] })
            };
            let (qn, rn): ([F; 3], [F; 3]) = (pick(&self.box0), pick(&self.box1));
            let d = |p: [F; 3]| n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - plane_margin(n, p);
            iv = iv.intersect(linear_nonpositive(d(qn), d(rn)));
            if iv.is_empty() {
                return iv;
            }
        }
        iv
    }

    /// Linearised moving-edge test (Eq. 8-9) of `tile` with parameters `lin`: per edge the
    /// tile corner that minimises σ o · s gives t = −(σ o · s − M)/γ; the interval is
    /// [max(0, t), 1] for γ < 0 and [0, min(1, t)] otherwise. Both windings that the facing
    /// allows are tested and their intervals joined.
    pub fn edge_interval_linearised(&self, tile: &Rect<F>, lin: &Linearised<F>) -> TimeInterval<F> {
        let r = tile.intersect(&lin.region);
        if r.is_empty() {
            return TimeInterval::empty();
        }
        let z = F::zero();
        let mut out = TimeInterval::empty();
        for (w, sigma) in [(0usize, F::one()), (1, -F::one())] {
            if !self.windings[w] {
                continue;
            }
            let mut iv = TimeInterval::full();
            for (k, e) in self.edges.iter().enumerate() {
                let o = [sigma * e.h[0], sigma * e.h[1], sigma * e.h[2]];
                let x = if o[0] >= z { r.x0 } else { r.x1 };
                let y = if o[1] >= z { r.y0 } else { r.y1 };
                let c = dot(o, x, y) - lin.margin[k];
                let g = lin.gamma[w][k];
                let ek = if g > z {
                    let t = -c / g;
                    if t < z {
                        TimeInterval::empty()
                    } else {
                        TimeInterval::new(z, t.min(F::one()))
                    }
                } else if g < z {
                    let t = -c / g;
                    if t > F::one() {
                        TimeInterval::empty()
                    } else {
                        TimeInterval::new(t.max(z), F::one())
                    }
                } else if c <= z {
                    TimeInterval::full()
                } else {
                    TimeInterval::empty()
                };
                iv = iv.intersect(ek);
                if iv.is_empty() {
                    break;
                }
            }
            out = out.hull(iv);
        }
        out
    }

    /// Exact moving-edge test: for each edge and winding, the hull over the four tile
    /// corners of {t ∈ [0, 1] : σ e_k(corner, t) − M_k ≤ 0}, solved in f64 with edge-eqn's
    /// robust quadratic solver; the edges' hulls are intersected, the windings joined.
    pub fn edge_interval_exact(&self, tile: &Rect<F>, region: &Linearised<F>) -> TimeInterval<F> {
        let r = tile.intersect(&region.region);
        if r.is_empty() {
            return TimeInterval::empty();
        }
        let f64_of = |v: F| v.to_f64().unwrap_or(f64::NAN);
        let corners = [(r.x0, r.y0), (r.x1, r.y0), (r.x0, r.y1), (r.x1, r.y1)]
            .map(|(x, y)| (f64_of(x), f64_of(y)));
        let mut out: Option<(f64, f64)> = None;
        for (w, sigma) in [(0usize, 1.0f64), (1, -1.0)] {
            if !self.windings[w] {
                continue;
            }
            let mut iv = (0.0f64, 1.0f64);
            for (k, e) in self.edges.iter().enumerate() {
                let c3 = |v: [F; 3]| v.map(|c| sigma * f64_of(c));
                let (f, g, h) = (c3(e.f), c3(e.g), c3(e.h));
                let m = f64_of(region.margin[k]);
                let mut hull: Option<(f64, f64)> = None;
                for &(x, y) in &corners {
                    let a = f[0] * x + f[1] * y + f[2];
                    let b = g[0] * x + g[1] * y + g[2];
                    let c = h[0] * x + h[1] * y + h[2] - m;
                    if let Some(s) = sublevel_hull(a, b, c) {
                        hull = Some(match hull {
                            None => s,
                            Some(p) => (p.0.min(s.0), p.1.max(s.1)),
                        });
                    }
                }
                match hull {
                    Some(s) => iv = (iv.0.max(s.0), iv.1.min(s.1)),
                    None => iv = (1.0, 0.0),
                }
                if iv.0 > iv.1 {
                    break;
                }
            }
            if iv.0 <= iv.1 {
                out = Some(match out {
                    None => iv,
                    Some(p) => (p.0.min(iv.0), p.1.max(iv.1)),
                });
            }
        }
        match out {
            Some((lo, hi)) => {
                let pad = 1e-7;
                TimeInterval::new(lit((lo - pad).max(0.0)), lit((hi + pad).min(1.0)))
            }
            None => TimeInterval::empty(),
        }
    }

    /// Linearised moving-edge test of `tile` over the time window `window` = [t₀, t₁]
    /// (Munkberg 2011, Eq. 4-9, re-derived per tile around t₀): for t in the window,
    /// e(s, t) = o(t₀) · s + (t − t₀)(g + (t + t₀) f) · s with o(t₀) = (a, b, c)(t₀)
    /// (Gribel 2010, Eq. 3), and the slope factor is linear in t, so for winding σ
    /// σ e(s, t) ≥ min_s σ o(t₀) · s + (t − t₀) γ with
    /// γ = min over the tile's n-corner and τ ∈ {t₀, t₁} of σ (g + (t₀ + τ) f) · s.
    /// Solving the right side ≤ M for t gives the interval (intersected with the window).
    /// Both windings that the facing allows are tested and their intervals joined.
    /// Equal to `self.edge_window(tile, window).interval(tile)`.
    pub fn edge_interval_window(&self, tile: &Rect<F>, window: TimeInterval<F>) -> TimeInterval<F> {
        if window.is_empty() {
            return window;
        }
        self.edge_window(tile, window).interval(tile)
    }

    /// The per-edge part of [`TileTester::edge_interval_window`] that depends only on the
    /// window and on the tile's extent: o(t₀), the two slope vectors and the rounding
    /// margin. The bound it encodes holds at every point of `tile` and every time of
    /// `window`, so [`EdgeWindow::interval`] can evaluate it on any sub-rectangle of the
    /// tile (levels below the sample-pattern tile: quads and pixels) for the price of the
    /// n-corner dots and one division per edge.
    pub fn edge_window(&self, tile: &Rect<F>, window: TimeInterval<F>) -> EdgeWindow<F> {
        let (t0, t1) = (window.lo, window.hi);
        let mx = tile.x0.abs().max(tile.x1.abs());
        let my = tile.y0.abs().max(tile.y1.abs());
        let edges = self.edges.map(|e| {
            let o = e.coefficients_at(t0);
            let s0 = [0, 1, 2].map(|i| e.g[i] + (t0 + t0) * e.f[i]);
            let s1 = [0, 1, 2].map(|i| e.g[i] + (t0 + t1) * e.f[i]);
            let mag = abs_dot(e.f, mx, my) * lit(2.0) + abs_dot(e.g, mx, my) + abs_dot(e.h, mx, my);
            (o, s0, s1, mag * F::epsilon() * lit(64.0))
        });
        let side = |w: usize, sigma: F| {
            self.windings[w].then(|| {
                edges.map(|(o, s0, s1, m)| {
                    let sg = |v: [F; 3]| v.map(|c| sigma * c);
                    (sg(o), sg(s0), sg(s1), m)
                })
            })
        };
        EdgeWindow {
            tile: *tile,
            window,
            sides: [side(0, F::one()), side(1, -F::one())],
        }
    }

    /// The tile test of a sub-tile (a quad or pixel of a sample-pattern tile) from the
    /// pattern tile's window linearisation `ew` (Eq. 4-9 around the start of the pattern
    /// tile's interval): `parent` ∩ the window edge test of `rect`, widened by a few ulps
    /// for the division. No moving-AABB test: at this size the edge bounds are the tight
    /// part, and the parent's box test already bounds the interval. `rect` must lie in
    /// `ew`'s tile (outside it the bound is not valid and the result is empty).
    #[inline]
    pub fn sub_tile_interval(
        &self,
        ew: &EdgeWindow<F>,
        rect: &Rect<F>,
        parent: TimeInterval<F>,
    ) -> TimeInterval<F> {
        let eps = F::epsilon() * lit(8.0);
        parent
            .intersect(ew.interval(rect).widened(eps))
            .widened(eps)
    }
    /// The full tile test (Munkberg 2011, §4.2): t̂_tot = frustum ∩ t̂_box ∩ t̂_edges, widened
    /// by a few ulps for the rounding of the divisions. `lin` gives γ (the setup's or a coarse
    /// tile's); for [`EdgeTest::Exact`] only its region and margins are used.
    ///
    /// For [`EdgeTest::LinearisedPerLevel`] and [`EdgeTest::ExactFinest`] this is the
    /// window test over the whole shutter; the traversal calls [`TileTester::test_window`]
    /// with the parent tile's interval instead.
    pub fn test(&self, tile: &Rect<F>, method: EdgeTest, lin: &Linearised<F>) -> TimeInterval<F> {
        self.test_window(tile, method, lin, TimeInterval::full(), false)
    }

    /// The tile test inside the parent tile's interval `parent`: t̂ = parent ∩ frustum ∩
    /// t̂_box ∩ t̂_edges. `finest` selects the exact edge test for
    /// [`EdgeTest::ExactFinest`]; the window methods linearise around `parent.lo`.
    pub fn test_window(
        &self,
        tile: &Rect<F>,
        method: EdgeTest,
        lin: &Linearised<F>,
        parent: TimeInterval<F>,
        finest: bool,
    ) -> TimeInterval<F> {
        let mut iv = self
            .frustum
            .intersect(parent)
            .intersect(self.box_interval(tile));
        if iv.is_empty() {
            return iv;
        }
        let e = match method {
            EdgeTest::Exact => self.edge_interval_exact(tile, lin),
            EdgeTest::ExactFinest if finest => self.edge_interval_exact(tile, lin),
            EdgeTest::LinearisedPerLevel | EdgeTest::ExactFinest => {
                // The window starts where the box and frustum already allow, so the
                // expansion point is as late as possible.
                self.edge_interval_window(tile, iv)
            }
            _ => self.edge_interval_linearised(tile, lin),
        };
        iv = iv.intersect(e.widened(F::epsilon() * lit(8.0)));
        iv.widened(F::epsilon() * lit(8.0))
    }
}

/// Static tile test at one time t (HIERARCHICAL INTERLEAVE, Munkberg 2011, Table 1): the
/// triangle's 2DH AABB at t against the tile planes, and the three edges with coefficients
/// `coeffs` = (a, b, c)(t) against the tile corners, for each allowed winding, with the same
/// rounding margins as the moving tests.
pub fn static_tile_overlap<F: Float>(
    tile: &Rect<F>,
    aabb_t: &[[F; 3]; 2],
    coeffs: &[[F; 3]; 3],
    windings: [bool; 2],
) -> bool {
    let z = F::zero();
    let o = F::one();
    let planes = [
        [-o, z, tile.x0],
        [o, z, -tile.x1],
        [z, -o, tile.y0],
        [z, o, -tile.y1],
    ];
    for n in planes {
        let p: [F; 3] = core::array::from_fn(|c| {
            if n[c] >= z {
                aabb_t[0][c]
            } else {
                aabb_t[1][c]
            }
        });
        if n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - plane_margin(n, p) > z {
            return false;
        }
    }
    let mx = tile.x0.abs().max(tile.x1.abs());
    let my = tile.y0.abs().max(tile.y1.abs());
    [(0usize, o), (1, -o)].iter().any(|&(w, sigma)| {
        windings[w]
            && coeffs.iter().all(|c| {
                let e = [sigma * c[0], sigma * c[1], sigma * c[2]];
                let x = if e[0] >= z { tile.x0 } else { tile.x1 };
                let y = if e[1] >= z { tile.y0 } else { tile.y1 };
                dot(e, x, y) - abs_dot(e, mx, my) * F::epsilon() * lit(64.0) <= z
            })
    })
}

/// The 2DH AABB `[min, max]` of three points.
pub fn aabb3<F: Float>(p: &[[F; 3]; 3]) -> [[F; 3]; 2] {
    aabb(p)
}

/// The hull of {t ∈ [0, 1] : a t² + b t + c ≤ 0}: its boundary points are roots or the ends
/// 0 and 1, so the hull spans the roots in [0, 1] and the ends where the value is ≤ 0.
fn sublevel_hull(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    let mut add = |t: f64| {
        lo = lo.min(t);
        hi = hi.max(t);
    };
    if c <= 0.0 {
        add(0.0);
    }
    if a + b + c <= 0.0 {
        add(1.0);
    }
    for t in edge_eqn::quadratic::real_roots(a, b, c) {
        if (0.0..=1.0).contains(&t) {
            add(t);
        }
    }
    (lo <= hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The window test contains every covered (point, time) of the tile inside the window
    /// (dense sampling with edge-eqn's inside test), and is no wider than the linearised
    /// test with γ over the whole screen bound.
    #[test]
    fn window_test_against_dense_sampling() {
        use crate::cull::facing;
        use edge_eqn::MovingTriangle;
        let q = [[2.0, 2.0, 1.0], [14.0, 3.0, 1.0], [5.0, 15.0, 1.0]];
        let r = [[36.0, 8.0, 1.5], [48.0, 9.0, 1.5], [39.0, 21.0, 1.5]]
            .map(|[x, y, w]: [f64; 3]| [x * w, y * w, w]);
        let setup = MovingTriangle::new(q, r).setup();
        let bound = Rect::new(0.0, 0.0, 64.0, 64.0);
        let tester = TileTester::new(
            &q,
            &r,
            *setup.edges(),
            facing(&q, &r),
            TimeInterval::full(),
            bound,
        );
        let mut hits = 0;
        for (tx, ty) in [(16.0, 4.0), (20.0, 8.0), (28.0, 12.0), (40.0, 12.0)] {
            let tile = Rect::new(tx, ty, tx + 4.0, ty + 4.0);
            for window in [TimeInterval::full(), TimeInterval::new(0.3, 0.8)] {
                let iv = tester.edge_interval_window(&tile, window);
                let lin = tester.edge_interval_linearised(&tile, &tester.setup);
                assert!(iv.is_empty() || (window.lo <= iv.lo && iv.hi <= window.hi));
                if window == TimeInterval::full() {
                    assert!(iv.len() <= lin.len() + 1e-12, "{iv:?} vs {lin:?}");
                }
                for i in 0..=400 {
                    let t = f64::from(i) / 400.0;
                    if !window.contains(t) {
                        continue;
                    }
                    for j in 0..=8 {
                        for k in 0..=8 {
                            let (x, y) = (tx + 0.5 * f64::from(j), ty + 0.5 * f64::from(k));
                            if setup.inside_at(x, y, t) {
                                hits += 1;
                                assert!(iv.contains(t), "tile ({tx}, {ty}) t {t} iv {iv:?}");
                            }
                        }
                    }
                }
            }
        }
        assert!(hits > 1000, "{hits}");
    }

    #[test]
    fn sublevel_hull_against_dense_sampling() {
        let cases = [
            (1.0, -1.0, 0.2),
            (-1.0, 1.0, -0.2),
            (0.0, 1.0, -0.5),
            (2.0, 0.1, 0.3),
            (-4.0, 4.0, -0.99),
        ];
        for (a, b, c) in cases {
            let h = sublevel_hull(a, b, c);
            for i in 0..=10000 {
                let t = f64::from(i) / 10000.0;
                if a * t * t + b * t + c <= 0.0 {
                    let (lo, hi) = h.expect("non-empty");
                    assert!(lo - 1e-12 <= t && t <= hi + 1e-12, "{a} {b} {c} {t}");
                }
            }
        }
        assert!(sublevel_hull(1.0, 0.0, 0.5).is_none());
    }
}
