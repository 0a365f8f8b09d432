//! Independent f64 references shared by the integration tests.
#![allow(dead_code)]

pub type V3 = [f64; 3];

pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}
pub fn lerp(a: V3, b: V3, s: f64) -> V3 {
    add(a, scale(sub(b, a), s))
}

/// Q(u, v) from the patch definition, corners [q00, q10, q11, q01].
pub fn patch_point(c: &[V3; 4], u: f64, v: f64) -> V3 {
    let w = [(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v];
    let mut p = [0.0; 3];
    for (q, wi) in c.iter().zip(w) {
        p = add(p, scale(*q, wi));
    }
    p
}

/// A reference root of ray vs patch.
#[derive(Clone, Copy, Debug)]
pub struct RefHit {
    pub t: f64,
    pub u: f64,
    pub v: f64,
    /// |det J| / (|Qu| |Qv|) of the projected 2x2 system at the root (0: tangent).
    pub conditioning: f64,
    /// How much more u and v move under rounding of the input than a patch as large as
    /// its coordinates would let them: max(1, M / |Qu|) and max(1, M / |Qv|), with M the
    /// largest coordinate magnitude (corners and origin) and Qu, Qv projected along the
    /// ray. Rounding the input moves the root's projected residual by about ε M, hence u
    /// by about ε M / (|Qu| conditioning) (Cramer's rule), and v likewise with |Qv|: a
    /// patch thin along v next to coordinates far larger (seen edge-on, or far from the
    /// origin) has a v that no arithmetic of the input's precision determines better.
    pub sensitivity: [f64; 2],
}

/// Solves Q(u, v) = o + t d by 2D Newton iteration in an orthonormal frame perpendicular to
/// d, started from a 7 x 7 grid over [-0.2, 1.2]^2; keeps converged roots in [0, 1]^2
/// (within 1e-9) and merges duplicates. Independent of the crate's quadratic formulation.
pub fn reference_hits(c: &[V3; 4], o: V3, d: V3) -> Vec<RefHit> {
    let n = scale(d, 1.0 / norm(d));
    let helper = if n[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = {
        let x = cross(n, helper);
        scale(x, 1.0 / norm(x))
    };
    let e2 = cross(n, e1);
    let size = c
        .iter()
        .map(|q| norm(sub(*q, o)))
        .fold(0.0, f64::max)
        .max(1e-300);
    // The largest coordinate magnitude of the input, the scale of its rounding.
    let m = c.iter().chain([&o]).map(|p| norm(*p)).fold(0.0, f64::max);
    let h = |u: f64, v: f64| {
        let p = sub(patch_point(c, u, v), o);
        [dot(p, e1), dot(p, e2)]
    };
    let jac = |u: f64, v: f64| {
        let qu = sub(lerp(c[1], c[2], v), lerp(c[0], c[3], v));
        let qv = sub(lerp(c[3], c[2], u), lerp(c[0], c[1], u));
        (
            [dot(qu, e1), dot(qu, e2)],
            [dot(qv, e1), dot(qv, e2)],
            norm(qu) * norm(qv),
        )
    };
    let mut out: Vec<RefHit> = Vec::new();
    for i in 0..7 {
        for j in 0..7 {
            let (mut u, mut v) = (-0.2 + 1.4 * i as f64 / 6.0, -0.2 + 1.4 * j as f64 / 6.0);
            let mut ok = false;
            for _ in 0..60 {
                let r = h(u, v);
                let (a, b, _) = jac(u, v);
                let det = a[0] * b[1] - a[1] * b[0];
                if det == 0.0 || !det.is_finite() {
                    break;
                }
                let du = (r[0] * b[1] - r[1] * b[0]) / det;
                let dv = (a[0] * r[1] - a[1] * r[0]) / det;
                u -= du;
                v -= dv;
                if !(u.abs() < 10.0 && v.abs() < 10.0) {
                    break;
                }
                if du.abs() < 1e-15 && dv.abs() < 1e-15 {
                    ok = true;
                    break;
                }
            }
            let r = h(u, v);
            if !ok && (r[0].hypot(r[1]) > 1e-13 * size || !u.is_finite()) {
                continue;
            }
            if r[0].hypot(r[1]) > 1e-11 * size {
                continue;
            }
            if !(-1e-9..=1.0 + 1e-9).contains(&u) || !(-1e-9..=1.0 + 1e-9).contains(&v) {
                continue;
            }
            if out
                .iter()
                .any(|x| (x.u - u).abs() < 1e-7 && (x.v - v).abs() < 1e-7)
            {
                continue;
            }
            let (a, b, s) = jac(u, v);
            let conditioning = (a[0] * b[1] - a[1] * b[0]).abs() / s.max(1e-300);
            let t = dot(sub(patch_point(c, u, v), o), d) / dot(d, d);
            let factor = |q: [f64; 2]| (m / q[0].hypot(q[1]).max(1e-300)).max(1.0);
            out.push(RefHit {
                t,
                u,
                v,
                conditioning,
                sensitivity: [factor(a), factor(b)],
            });
        }
    }
    out.sort_by(|a, b| a.t.total_cmp(&b.t));
    out
}

/// Static inside test of a 2D triangle at a point, either orientation, boundary included; a
/// triangle of zero area covers nothing.
pub fn inside_tri(p: [[f64; 2]; 3], x: f64, y: f64) -> bool {
    let e = |a: [f64; 2], b: [f64; 2]| (a[0] - x) * (b[1] - y) - (a[1] - y) * (b[0] - x);
    let (e0, e1, e2) = (e(p[0], p[1]), e(p[1], p[2]), e(p[2], p[0]));
    let area2 = e0 + e1 + e2;
    area2 != 0.0 && ((e0 >= 0.0 && e1 >= 0.0 && e2 >= 0.0) || (e0 <= 0.0 && e1 <= 0.0 && e2 <= 0.0))
}

/// Brute-force coverage of (x, y) by a triangle moving linearly in screen space from
/// `open` to `close` (each vertex (x, y)): the inside test at the n times (k + 1/2) / n,
/// returned as the list of sample states.
pub fn sampled_coverage(
    open: [[f64; 2]; 3],
    close: [[f64; 2]; 3],
    x: f64,
    y: f64,
    n: usize,
) -> Vec<bool> {
    (0..n)
        .map(|k| {
            let t = sample_time(k, n);
            let p = [0, 1, 2].map(|i| {
                [
                    open[i][0] + t * (close[i][0] - open[i][0]),
                    open[i][1] + t * (close[i][1] - open[i][1]),
                ]
            });
            inside_tri(p, x, y)
        })
        .collect()
}

/// Time of sample k of n.
pub fn sample_time(k: usize, n: usize) -> f64 {
    (k as f64 + 0.5) / n as f64
}

/// Measure of the covered time from the samples (midpoint rule).
pub fn sampled_measure(states: &[bool]) -> f64 {
    states.iter().filter(|&&s| s).count() as f64 / states.len() as f64
}

/// Runs of covered samples of [`sampled_coverage`] merged into time spans [t0, t1] (each
/// sample stands for its stratum [k / n, (k + 1) / n]).
pub fn sampled_spans(
    open: [[f64; 2]; 3],
    close: [[f64; 2]; 3],
    x: f64,
    y: f64,
    n: usize,
) -> Vec<[f64; 2]> {
    let mut out: Vec<[f64; 2]> = Vec::new();
    for (k, covered) in sampled_coverage(open, close, x, y, n)
        .into_iter()
        .enumerate()
    {
        let (t0, t1) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
        if covered {
            match out.last_mut() {
                Some(s) if s[1] == t0 => s[1] = t1,
                _ => out.push([t0, t1]),
            }
        }
    }
    out
}

/// Measure of the symmetric difference of two unions of disjoint sorted spans in [0, 1].
pub fn disagreement(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    let mut cuts: Vec<f64> = a.iter().chain(b).flatten().copied().collect();
    cuts.extend([0.0, 1.0]);
    cuts.sort_by(f64::total_cmp);
    let inside = |s: &[[f64; 2]], t: f64| s.iter().any(|x| x[0] <= t && t <= x[1]);
    cuts.windows(2)
        .map(|w| {
            let m = 0.5 * (w[0] + w[1]);
            if inside(a, m) != inside(b, m) {
                w[1] - w[0]
            } else {
                0.0
            }
        })
        .sum()
}

/// One random ray/patch pair of the ray-vs-patch benchmark (`benches/ray_patch.rs`) and its
/// example (`examples/ray_patch_costs.rs`).
pub struct RayCase {
    pub corners: [V3; 4],
    pub origin: V3,
    pub dir: V3,
}

/// The two triangles `(q00, q10, q11)` and `(q00, q11, q01)` that split a patch along its
/// q00-q11 diagonal (the benchmark's triangle pair).
pub fn split(c: &[V3; 4]) -> [[V3; 3]; 2] {
    [[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
}

/// `n` pairs, seeded: a non-planar patch roughly in the unit square (corners jittered by
/// ±0.2 in x, y and ±0.5 in z), a ray from above aimed at a point of the square grown by
/// 20 % (so some rays miss).
pub fn ray_cases(n: usize) -> Vec<RayCase> {
    ray_cases_aimed(n, -0.2..1.2)
}

/// As [`ray_cases`], the ray aimed at a point with x and y in `aim` (`0.35..0.65`: every
/// ray hits; `1.6..2.0`: every ray misses).
pub fn ray_cases_aimed(n: usize, aim: std::ops::Range<f64>) -> Vec<RayCase> {
    use rand::{RngExt, SeedableRng};
    let mut rng = rand_pcg::Pcg64::seed_from_u64(4);
    let mut r = |lo: f64, hi: f64| rng.random_range(lo..hi);
    (0..n)
        .map(|_| {
            let mut corners = [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ];
            for c in &mut corners {
                c[0] += r(-0.2, 0.2);
                c[1] += r(-0.2, 0.2);
                c[2] += r(-0.5, 0.5);
            }
            let target = [r(aim.start, aim.end), r(aim.start, aim.end), r(-0.3, 0.3)];
            let origin = [r(-1.0, 2.0), r(-1.0, 2.0), r(2.0, 4.0)];
            let dir = sub(target, origin);
            RayCase {
                corners,
                origin,
                dir,
            }
        })
        .collect()
}
