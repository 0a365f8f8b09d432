//! Independent references shared by the test suites: adaptive Gauss-Kronrod quadrature,
//! static EWA splatting by ray-plane intersection, temporal supersampling.
#![allow(dead_code)]

use ewa_splat::{Camera, Splat};
use glam::{DVec3, DVec4};

/// Kronrod 15-point nodes (positive half, descending) with K15 and G7 weights.
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_728_8,
];
const WG: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

fn gk15(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let fc = f(c);
    let mut k = WGK[7] * fc;
    let mut g = WG[3] * fc;
    for i in 0..7 {
        let x = h * XGK[i];
        let s = f(c - x) + f(c + x);
        k += WGK[i] * s;
        if i % 2 == 1 {
            g += WG[i / 2] * s;
        }
    }
    (k * h, g * h)
}

fn adapt(f: &dyn Fn(f64) -> f64, a: f64, b: f64, rel: f64, depth: u32) -> f64 {
    let (k, g) = gk15(f, a, b);
    if (k - g).abs() <= rel * k.abs() || (k - g).abs() < 1e-320 || depth > 60 {
        return k;
    }
    let m = 0.5 * (a + b);
    adapt(f, a, m, rel, depth + 1) + adapt(f, m, b, rel, depth + 1)
}

/// Adaptive G7-K15 quadrature of `f` over [a, b] to relative tolerance `rel`, first split at
/// the given breakpoints (so narrow peaks are never stepped over).
pub fn quad(f: &dyn Fn(f64) -> f64, a: f64, b: f64, rel: f64, breaks: &[f64]) -> f64 {
    if a == b {
        return 0.0;
    }
    if a > b {
        return -quad(f, b, a, rel, breaks);
    }
    let mut pts = vec![a, b];
    pts.extend(breaks.iter().copied().filter(|p| *p > a && *p < b));
    pts.sort_by(f64::total_cmp);
    pts.windows(2).map(|w| adapt(f, w[0], w[1], rel, 0)).sum()
}

/// Reference for `line_integral`: adaptive quadrature of exp(-δ|b + t f|²), split at the
/// peak and at 1, 3, 10, 30 widths either side of it.
pub fn line_integral_quad(b: DVec3, f: DVec3, delta: f64, ta: f64, tb: f64) -> f64 {
    line_integral_quad_tol(b, f, delta, ta, tb, 1e-12)
}

/// [`line_integral_quad`] with a chosen relative tolerance (for the benchmarks).
pub fn line_integral_quad_tol(b: DVec3, f: DVec3, delta: f64, ta: f64, tb: f64, rel: f64) -> f64 {
    let g = |t: f64| {
        let l = b + t * f;
        (-delta * l.dot(l)).exp()
    };
    quad(&g, ta, tb, rel, &peak_breaks(b, f, delta))
}

/// Adaptive Simpson quadrature of exp(-δ|b + t f|²) over [ta, tb] (Lyness criterion
/// |S2 - S1| <= 15 tol, recursion depth at most 30), first split at the same peak
/// breakpoints as [`line_integral_quad`], each piece to `rel` x its 5-point estimate — the
/// textbook method, given the same help as the Kronrod oracle.
pub fn line_integral_simpson(b: DVec3, f: DVec3, delta: f64, ta: f64, tb: f64, rel: f64) -> f64 {
    let g = |t: f64| {
        let l = b + t * f;
        (-delta * l.dot(l)).exp()
    };
    #[allow(clippy::too_many_arguments)]
    fn rec(
        g: &dyn Fn(f64) -> f64,
        a: f64,
        b: f64,
        fa: f64,
        fm: f64,
        fb: f64,
        whole: f64,
        tol: f64,
        depth: u32,
    ) -> f64 {
        let m = 0.5 * (a + b);
        let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
        let (flm, frm) = (g(lm), g(rm));
        let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
        let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
        let delta = left + right - whole;
        if depth >= 30 || delta.abs() <= 15.0 * tol {
            return left + right + delta / 15.0;
        }
        rec(g, a, m, fa, flm, fm, left, 0.5 * tol, depth + 1)
            + rec(g, m, b, fm, frm, fb, right, 0.5 * tol, depth + 1)
    }
    let piece = |a: f64, c: f64| {
        let (fa, fm, fb) = (g(a), g(0.5 * (a + c)), g(c));
        let whole = (c - a) / 6.0 * (fa + 4.0 * fm + fb);
        let (q1, q3) = (g(0.75 * a + 0.25 * c), g(0.25 * a + 0.75 * c));
        let scale = (c - a) / 12.0 * (fa + 4.0 * q1 + 2.0 * fm + 4.0 * q3 + fb);
        rec(
            &g,
            a,
            c,
            fa,
            fm,
            fb,
            whole,
            rel * scale.abs().max(1e-300),
            0,
        )
    };
    let mut pts = vec![ta, tb];
    pts.extend(
        peak_breaks(b, f, delta)
            .into_iter()
            .filter(|p| *p > ta && *p < tb),
    );
    pts.sort_by(f64::total_cmp);
    pts.windows(2).map(|w| piece(w[0], w[1])).sum()
}

/// The peak of exp(-δ|b + t f|²) in t and 1, 3, 10, 30 widths either side of it.
pub fn peak_breaks(b: DVec3, f: DVec3, delta: f64) -> Vec<f64> {
    let ff = f.dot(f);
    let mut breaks = Vec::new();
    if ff > 0.0 {
        let peak = -b.dot(f) / ff;
        let width = 1.0 / (delta * ff).sqrt();
        breaks.push(peak);
        for k in [1.0, 3.0, 10.0, 30.0] {
            breaks.push(peak - k * width);
            breaks.push(peak + k * width);
        }
    }
    breaks
}

/// Plain adaptive G7-K15 over [ta, tb] without the peak breakpoints.
pub fn line_integral_gk_plain(b: DVec3, f: DVec3, delta: f64, ta: f64, tb: f64, rel: f64) -> f64 {
    let g = |t: f64| {
        let l = b + t * f;
        (-delta * l.dot(l)).exp()
    };
    quad(&g, ta, tb, rel, &[])
}

/// Pixel ray through (px, py), computed independently of the crate from the inverse
/// view-projection: origin on the near plane, unit direction.
pub fn pixel_ray(cam: &Camera, px: f64, py: f64) -> (DVec3, DVec3) {
    let inv = cam.view_proj.inverse();
    let nx = 2.0 * px / cam.width as f64 - 1.0;
    let ny = 1.0 - 2.0 * py / cam.height as f64;
    let n = inv * DVec4::new(nx, ny, -1.0, 1.0);
    let fa = inv * DVec4::new(nx, ny, 1.0, 1.0);
    let o = n.truncate() / n.w;
    (o, (fa.truncate() / fa.w - o).normalize())
}

/// Static EWA splatting of the splats' geometry at time `t` for one pixel, by ray-plane
/// intersection: weight exp(-δ r²) inside the cut-off r <= 1, ternary depth test against
/// the nearest hit with tolerance `eps_rel` x the longer axis, normalised premultiplied
/// colour over the premultiplied background.
pub fn static_ewa_pixel(
    splats: &[Splat],
    t: f64,
    o: DVec3,
    d: DVec3,
    delta: f64,
    eps_rel: f64,
    bg: [f64; 4],
) -> [f64; 4] {
    let mut hits: Vec<(f64, f64, f64, [f64; 4])> = Vec::new(); // depth, eps, weight, colour
    for s in splats {
        // Only the splats whose span holds t (the last piece of a path holds t = 1).
        let [t0, t1] = s.span;
        if !(t0 <= t && (t < t1 || (t1 >= 1.0 && t <= t1))) {
            continue;
        }
        let k = s.key_at(t).unwrap();
        let (a1, a2) = (k.axis_u, k.axis_v);
        let n = a1.cross(a2);
        let dn = d.dot(n);
        if dn == 0.0 {
            continue;
        }
        let depth = (k.centre - o).dot(n) / dn;
        if depth < 0.0 {
            continue;
        }
        let q = o + depth * d - k.centre;
        // Solve q = u a1 + v a2 (Gram system).
        let (g11, g12, g22) = (a1.dot(a1), a1.dot(a2), a2.dot(a2));
        let (r1, r2) = (q.dot(a1), q.dot(a2));
        let det = g11 * g22 - g12 * g12;
        let u = (r1 * g22 - r2 * g12) / det;
        let v = (r2 * g11 - r1 * g12) / det;
        let r2s = u * u + v * v;
        if r2s <= 1.0 {
            let a = s.colour[3] as f64;
            let c = [
                s.colour[0] as f64 * a,
                s.colour[1] as f64 * a,
                s.colour[2] as f64 * a,
                a,
            ];
            let eps = eps_rel * a1.length().max(a2.length());
            hits.push((depth, eps, (-delta * r2s).exp(), c));
        }
    }
    let Some(front) = hits.iter().min_by(|a, b| a.0.total_cmp(&b.0)).copied() else {
        return bg;
    };
    let mut acc = [0.0; 4];
    let mut ws = 0.0;
    for h in &hits {
        if h.0 <= front.0 + front.1.max(h.1) {
            for (a, v) in acc.iter_mut().zip(h.3) {
                *a += h.2 * v;
            }
            ws += h.2;
        }
    }
    let p = acc.map(|v| v / ws);
    std::array::from_fn(|c| p[c] + (1.0 - p[3]) * bg[c])
}

/// [`supersample`] with a per-pixel cull: only splats whose swept bounding sphere meets
/// the pixel ray are tested (same result, much faster for benchmark scenes).
pub fn supersample_culled(
    cam: &Camera,
    splats: &[Splat],
    bg: [f32; 4],
    delta: f64,
    eps_rel: f64,
    n: usize,
) -> Vec<[f64; 4]> {
    let bgp = premul(bg);
    let spheres: Vec<(DVec3, f64)> = splats
        .iter()
        .map(|s| {
            let lo = s.keys.iter().fold(DVec3::INFINITY, |m, k| m.min(k.centre));
            let hi = s
                .keys
                .iter()
                .fold(DVec3::NEG_INFINITY, |m, k| m.max(k.centre));
            let r = s
                .keys
                .iter()
                .map(|k| k.axis_u.length().max(k.axis_v.length()))
                .fold(0.0, f64::max);
            (0.5 * (lo + hi), 0.5 * (hi - lo).length() + r)
        })
        .collect();
    let mut out = Vec::new();
    for j in 0..cam.height {
        for i in 0..cam.width {
            let (o, d) = pixel_ray(cam, i as f64 + 0.5, j as f64 + 0.5);
            let near: Vec<Splat> = splats
                .iter()
                .zip(&spheres)
                .filter(|(_, (c, r))| (*c - o).cross(d).length() <= *r * 1.000001)
                .map(|(s, _)| s.clone())
                .collect();
            let mut acc = [0.0; 4];
            for k in 0..n {
                let t = (k as f64 + 0.5) / n as f64;
                let p = static_ewa_pixel(&near, t, o, d, delta, eps_rel, bgp);
                for (a, v) in acc.iter_mut().zip(p) {
                    *a += v / n as f64;
                }
            }
            out.push(unpremul(acc));
        }
    }
    out
}

/// Temporal supersampling of static EWA (box shutter, `n` midpoint samples): the
/// brute-force motion-blur reference. Returns straight-alpha RGBA per pixel.
pub fn supersample(
    cam: &Camera,
    splats: &[Splat],
    bg: [f32; 4],
    delta: f64,
    eps_rel: f64,
    n: usize,
) -> Vec<[f64; 4]> {
    let bgp = premul(bg);
    let mut out = Vec::new();
    for j in 0..cam.height {
        for i in 0..cam.width {
            let (o, d) = pixel_ray(cam, i as f64 + 0.5, j as f64 + 0.5);
            let mut acc = [0.0; 4];
            for k in 0..n {
                let t = (k as f64 + 0.5) / n as f64;
                let p = static_ewa_pixel(splats, t, o, d, delta, eps_rel, bgp);
                for (a, v) in acc.iter_mut().zip(p) {
                    *a += v / n as f64;
                }
            }
            out.push(unpremul(acc));
        }
    }
    out
}

pub fn premul(c: [f32; 4]) -> [f64; 4] {
    let a = c[3] as f64;
    [c[0] as f64 * a, c[1] as f64 * a, c[2] as f64 * a, a]
}

pub fn unpremul(p: [f64; 4]) -> [f64; 4] {
    if p[3] > 0.0 {
        [p[0] / p[3], p[1] / p[3], p[2] / p[3], p[3]]
    } else {
        [0.0; 4]
    }
}

/// Largest absolute channel difference between two images.
pub fn max_diff(a: &[[f32; 4]], b: &[[f64; 4]]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| (0..4).map(move |c| (p[c] as f64 - q[c]).abs()))
        .fold(0.0, f64::max)
}

/// Mean absolute channel difference between two images.
pub fn mean_diff(a: &[[f32; 4]], b: &[[f64; 4]]) -> f64 {
    let s: f64 = a
        .iter()
        .zip(b)
        .flat_map(|(p, q)| (0..4).map(move |c| (p[c] as f64 - q[c]).abs()))
        .sum();
    s / (4 * a.len()) as f64
}

pub fn deep() -> bool {
    std::env::var("MBLUR_DEEP").is_ok_and(|v| v == "1")
}
