//! Independent references shared by the integration tests: a dense-time static inside test
//! on vertices interpolated in f64, perspective-correct depth from screen-space
//! barycentrics, and ulp distances.
#![allow(dead_code)]

use edge_eqn::Span;

pub type Tri = [[f64; 3]; 3];

/// Vertices at time t, p(t) = (1 - t) q + t r (Gribel Eq. 2), in f64.
pub fn lerp_tri(q: &Tri, r: &Tri, t: f64) -> Tri {
    let mut p = [[0.0; 3]; 3];
    for k in 0..3 {
        for i in 0..3 {
            p[k][i] = (1.0 - t) * q[k][i] + t * r[k][i];
        }
    }
    p
}

/// Static inside test of a 2DH triangle at the screen point (x, y), accepting both windings.
/// Returns (inside, smallest distance in pixels from the sample to an edge line) when all
/// w > 0 (screen-space orient tests), or (inside, smallest |e| normalised by the edge
/// coefficient length) from 2DH determinants otherwise.
pub fn static_inside(p: &Tri, x: f64, y: f64) -> (bool, f64) {
    if p.iter().all(|v| v[2] > 0.0) {
        let s = p.map(|v| [v[0] / v[2], v[1] / v[2]]);
        let mut o = [0.0; 3];
        let mut dmin = f64::INFINITY;
        for k in 0..3 {
            let a = s[(k + 1) % 3];
            let b = s[(k + 2) % 3];
            let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
            o[k] = ex * (y - a[1]) - ey * (x - a[0]);
            let len = (ex * ex + ey * ey).sqrt();
            let d = if len > 0.0 {
                o[k].abs() / len
            } else {
                ((x - a[0]).powi(2) + (y - a[1]).powi(2)).sqrt()
            };
            dmin = dmin.min(d);
        }
        let inside = o.iter().all(|&v| v <= 0.0) || o.iter().all(|&v| v >= 0.0);
        (inside, dmin)
    } else {
        let s = [x, y, 1.0];
        let mut e = [0.0; 3];
        let mut dmin = f64::INFINITY;
        for k in 0..3 {
            let a = p[(k + 1) % 3];
            let b = p[(k + 2) % 3];
            let n = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            e[k] = n[0] * s[0] + n[1] * s[1] + n[2];
            let len = (n[0] * n[0] + n[1] * n[1]).sqrt();
            dmin = dmin.min(if len > 0.0 {
                e[k].abs() / len
            } else {
                e[k].abs()
            });
        }
        let inside = e.iter().all(|&v| v <= 0.0) || e.iter().all(|&v| v >= 0.0);
        (inside, dmin)
    }
}

/// Compares coverage spans with the dense reference at `n + 1` times. A disagreement is
/// allowed only within `tau_t` of a computed span boundary or where the sample lies within
/// `tau_px` of an edge line at that time. Also checks shape: sorted, disjoint, in [0, 1],
/// positive length, and each span's midpoint inside (or within `tau_px` of an edge).
/// Returns the number of excused disagreements.
pub fn check_dense(
    spans: &[Span<f64>],
    q: &Tri,
    r: &Tri,
    (x, y): (f64, f64),
    n: usize,
    (tau_t, tau_px): (f64, f64),
) -> Result<usize, String> {
    let mut prev = 0.0;
    for (i, s) in spans.iter().enumerate() {
        if !(s.t0 >= 0.0 && s.t1 <= 1.0 && s.t0 < s.t1) {
            return Err(format!("bad span {s:?}"));
        }
        if i > 0 && s.t0 <= prev {
            return Err(format!("spans overlap or unsorted: {spans:?}"));
        }
        prev = s.t1;
        let tm = 0.5 * (s.t0 + s.t1);
        let (inside, d) = static_inside(&lerp_tri(q, r, tm), x, y);
        if !inside && d > tau_px {
            return Err(format!("span {s:?} midpoint not inside (distance {d})"));
        }
    }
    let mut excused = 0;
    for i in 0..=n {
        let t = i as f64 / n as f64;
        let got = spans.iter().any(|s| s.t0 <= t && t <= s.t1);
        let (want, d) = static_inside(&lerp_tri(q, r, t), x, y);
        if got != want {
            let near_boundary = spans
                .iter()
                .any(|s| (s.t0 - t).abs() <= tau_t || (s.t1 - t).abs() <= tau_t);
            if near_boundary || d <= tau_px {
                excused += 1;
            } else {
                return Err(format!(
                    "t = {t}: coverage says {got}, reference {want} (distance {d} px), spans {spans:?}"
                ));
            }
        }
    }
    Ok(excused)
}

/// Perspective-correct depth reference at time t: screen-space barycentrics β_k, then
/// λ_k ∝ β_k / w_k (normalised), d = Σ λ_k z_k(t). Requires all w > 0. Also returns a
/// condition estimate (perimeter² / |2 area|) of the screen triangle.
pub fn ref_depth(
    q: &Tri,
    r: &Tri,
    zq: [f64; 3],
    zr: [f64; 3],
    x: f64,
    y: f64,
    t: f64,
) -> (f64, f64) {
    let p = lerp_tri(q, r, t);
    let s = p.map(|v| [v[0] / v[2], v[1] / v[2]]);
    let area2 =
        (s[1][0] - s[0][0]) * (s[2][1] - s[0][1]) - (s[1][1] - s[0][1]) * (s[2][0] - s[0][0]);
    let mut beta = [0.0; 3];
    let mut per = 0.0;
    for k in 0..3 {
        let a = s[(k + 1) % 3];
        let b = s[(k + 2) % 3];
        beta[k] = ((a[0] - x) * (b[1] - y) - (a[1] - y) * (b[0] - x)) / area2;
        per += ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
    }
    let wts = [0, 1, 2].map(|k| beta[k] / p[k][2]);
    let sum: f64 = wts.iter().sum();
    let z = [0, 1, 2].map(|k| (1.0 - t) * zq[k] + t * zr[k]);
    let d = (0..3).map(|k| wts[k] / sum * z[k]).sum();
    (d, per * per / area2.abs())
}

/// Distance between two f64 values in units in the last place of `want`.
pub fn ulps64(got: f64, want: f64) -> f64 {
    if got == want {
        return 0.0;
    }
    let ulp = if want == 0.0 {
        f64::from_bits(1)
    } else {
        let b = want.abs().to_bits();
        f64::from_bits(b + 1) - want.abs()
    };
    (got - want).abs() / ulp
}

/// Distance of an f32 result from an f64 reference in f32 ulps of the reference.
pub fn ulps32(got: f32, want: f64) -> f64 {
    let w32 = want as f32;
    let ulp = if w32 == 0.0 {
        f64::from(f32::from_bits(1))
    } else {
        let b = w32.abs().to_bits();
        f64::from(f32::from_bits(b + 1)) - f64::from(w32.abs())
    };
    (f64::from(got) - want).abs() / ulp
}

/// Converts an f32 triangle to f64 (exact).
pub fn widen(t: [[f32; 3]; 3]) -> Tri {
    t.map(|v| v.map(f64::from))
}

/// Rounds an f64 triangle to f32.
pub fn narrow(t: Tri) -> [[f32; 3]; 3] {
    t.map(|v| v.map(|c| c as f32))
}

/// f32 spans widened to f64.
pub fn widen_spans(s: &[Span<f32>]) -> Vec<Span<f64>> {
    s.iter()
        .map(|s| Span::new(f64::from(s.t0), f64::from(s.t1)))
        .collect()
}

/// Double-double arithmetic (≈106-bit significand), used as an independent high-precision
/// reference for f64 roots.
#[derive(Clone, Copy, Debug)]
pub struct Dd(pub f64, pub f64);

fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    Dd(s, (a - (s - bb)) + (b - bb))
}

fn quick_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd(s, b - (s - a))
}

impl Dd {
    pub fn from(v: f64) -> Dd {
        Dd(v, 0.0)
    }
    pub fn prod(a: f64, b: f64) -> Dd {
        let p = a * b;
        Dd(p, a.mul_add(b, -p))
    }
    pub fn add(self, o: Dd) -> Dd {
        let s = two_sum(self.0, o.0);
        let t = two_sum(self.1, o.1);
        let v = quick_two_sum(s.0, s.1 + t.0);
        quick_two_sum(v.0, v.1 + t.1)
    }
    pub fn neg(self) -> Dd {
        Dd(-self.0, -self.1)
    }
    pub fn mul(self, o: Dd) -> Dd {
        let p = Dd::prod(self.0, o.0);
        quick_two_sum(p.0, p.1 + (self.0 * o.1 + self.1 * o.0))
    }
    pub fn scale(self, s: f64) -> Dd {
        Dd(self.0 * s, self.1 * s)
    }
    pub fn div(self, o: Dd) -> Dd {
        let q1 = self.0 / o.0;
        let r = self.add(o.mul(Dd::from(q1)).neg());
        let q2 = r.0 / o.0;
        let r = r.add(o.mul(Dd::from(q2)).neg());
        let q3 = r.0 / o.0;
        quick_two_sum(q1, q2).add(Dd::from(q3))
    }
    pub fn sqrt(self) -> Dd {
        if self.0 <= 0.0 {
            return Dd(0.0, 0.0);
        }
        let s = self.0.sqrt();
        let r = self.add(Dd::prod(s, s).neg());
        quick_two_sum(s, r.0 / (2.0 * s))
    }
    /// Error of `got` against this value in ulps of the rounded value.
    pub fn ulps_of(self, got: f64) -> f64 {
        let hi = self.0;
        let ulp = f64::from_bits(hi.abs().to_bits() + 1) - hi.abs();
        ((got - hi) - self.1).abs() / ulp
    }
}

/// Roots of a x² + b x + c (a ≠ 0) in double-double: exact products, ≈106-bit
/// discriminant, stable form. None when the discriminant is negative.
pub fn dd_roots(a: f64, b: f64, c: f64) -> Option<(Dd, Dd)> {
    let d = Dd::prod(b, b).add(Dd::prod(4.0 * a, c).neg());
    if d.0 < 0.0 {
        return None;
    }
    let s = d.sqrt();
    let s = if b < 0.0 { s.neg() } else { s };
    let q = Dd::from(b).add(s).scale(-0.5);
    let x1 = q.div(Dd::from(a));
    let x2 = Dd::from(c).div(q);
    Some(if x1.0 <= x2.0 { (x1, x2) } else { (x2, x1) })
}
