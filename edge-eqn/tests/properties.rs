//! Property tests against independent references (dense-time static inside tests in f64,
//! screen-space perspective-correct depth, exact roots). Case counts come from
//! `PROPTEST_CASES`.

mod common;

use common::*;
use edge_eqn::quadratic::real_roots;
use edge_eqn::{MovingTriangle, Span};
use proptest::prelude::*;

/// Dense times per case.
const DENSE: usize = 400;

/// A moving triangle with w in [0.5, 4], screen positions in [-20, 120] px, motion up to
/// ±60 px and a sample near the triangle at a random time.
fn scene() -> impl Strategy<Value = (Tri, Tri, f64, f64)> {
    let vert = (-20.0..120.0_f64, -20.0..120.0_f64, 0.5..4.0_f64);
    let motion = (-60.0..60.0_f64, -60.0..60.0_f64, 0.5..4.0_f64);
    (
        [vert.clone(), vert.clone(), vert],
        [motion.clone(), motion.clone(), motion],
        0.0..1.0_f64,
        (0.0..1.0_f64, 0.0..1.0_f64, 0.0..1.0_f64),
        (-4.0..4.0_f64, -4.0..4.0_f64),
    )
        .prop_map(|(v, m, ts, (b0, b1, b2), (nx, ny))| {
            let q = v.map(|(x, y, w)| [x * w, y * w, w]);
            let r = [0, 1, 2].map(|k| {
                let (x, y, _) = v[k];
                let (dx, dy, w) = m[k];
                [(x + dx) * w, (y + dy) * w, w]
            });
            let p = lerp_tri(&q, &r, ts);
            let bs = b0 + b1 + b2 + 1e-9;
            let b = [b0 / bs, b1 / bs, b2 / bs];
            let sx: f64 = (0..3).map(|k| b[k] * p[k][0] / p[k][2]).sum();
            let sy: f64 = (0..3).map(|k| b[k] * p[k][1] / p[k][2]).sum();
            (q, r, (sx + nx).floor() + 0.5, (sy + ny).floor() + 0.5)
        })
}

/// Any finite f64 whose magnitude class is drawn from tiny to huge.
fn wild() -> impl Strategy<Value = f64> {
    prop_oneof![
        -2.0..2.0_f64,
        -1e6..1e6_f64,
        prop::num::f64::NORMAL | prop::num::f64::NEGATIVE | prop::num::f64::POSITIVE,
        prop::num::f64::SUBNORMAL | prop::num::f64::NEGATIVE | prop::num::f64::POSITIVE,
        Just(0.0),
        (-1.0..1.0_f64).prop_map(|v| v * 1e-300),
    ]
}

proptest! {
    /// f64 coverage agrees with the dense f64 reference except within 1e-10 of a boundary or
    /// where the sample is within 1e-9 px of an edge line.
    #[test]
    fn coverage_f64_matches_dense_reference((q, r, x, y) in scene()) {
        let cov = MovingTriangle::new(q, r).setup().coverage(x, y);
        let res = check_dense(&cov, &q, &r, (x, y), DENSE, (1e-10, 1e-9));
        prop_assert!(res.is_ok(), "{}", res.unwrap_err());
    }

    /// f32 coverage agrees with the dense f64 reference (run on the same f32-rounded
    /// vertices) except within 3e-5 of a boundary or within 5e-4 px of an edge line.
    #[test]
    fn coverage_f32_matches_dense_reference((q, r, x, y) in scene()) {
        let (q32, r32) = (narrow(q), narrow(r));
        let (q, r) = (widen(q32), widen(r32));
        let cov = MovingTriangle::new(q32, r32).setup().coverage(x as f32, y as f32);
        let spans = widen_spans(&cov);
        let res = check_dense(&spans, &q, &r, (x, y), DENSE, (3e-5, 5e-4));
        prop_assert!(res.is_ok(), "{}", res.unwrap_err());
    }

    /// The per-time inside test agrees with the dense reference away from edges.
    #[test]
    fn inside_at_matches_reference((q, r, x, y) in scene(), t in 0.0..1.0_f64) {
        let setup = MovingTriangle::new(q, r).setup();
        let (want, d) = static_inside(&lerp_tri(&q, &r, t), x, y);
        prop_assert!(d <= 1e-7 || setup.inside_at(x, y, t) == want);
        prop_assert!(d <= 1e-7 || setup.sample(x, y).inside_at(t) == want);
    }

    /// Exact depth (default w and an explicit attribute) matches screen-space
    /// perspective-correct interpolation at covered times; barycentrics sum to one and lie
    /// in [0, 1]; the linear fit's max error bounds a dense scan and is attained.
    #[test]
    fn depth_matches_reference(
        (q, r, x, y) in scene(),
        zq in [1.0..10.0_f64, 1.0..10.0, 1.0..10.0],
        zr in [1.0..10.0_f64, 1.0..10.0, 1.0..10.0],
    ) {
        for explicit in [false, true] {
            let tri = MovingTriangle::new(q, r);
            let (tri, zq, zr) = if explicit {
                (tri.with_depth(zq, zr), zq, zr)
            } else {
                (tri, q.map(|v| v[2]), r.map(|v| v[2]))
            };
            let s = tri.setup().sample(x, y);
            for span in s.coverage().iter() {
                for f in [0.25, 0.5, 0.75] {
                    let t = span.t0 + f * span.len();
                    let (want, cond) = ref_depth(&q, &r, zq, zr, x, y, t);
                    let got = s.depth_at(t);
                    let tol = 1e-13 * cond.max(1.0) * want.abs().max(1.0);
                    prop_assert!((got - want).abs() <= tol, "t {t}: {got} vs {want} (cond {cond})");
                    let l = s.barycentrics(t);
                    prop_assert!((l[0] + l[1] + l[2] - 1.0).abs() < 1e-12);
                    prop_assert!(l.iter().all(|&v| (-1e-12..=1.0 + 1e-12).contains(&v)));
                }
                let fit = s.linear_depth(*span);
                prop_assert_eq!(fit.z, s.depth_at(span.t0));
                let mut dense = 0.0_f64;
                for i in 0..=64 {
                    let t = span.t0 + span.len() * f64::from(i) / 64.0;
                    dense = dense.max((s.depth_at(t) - fit.eval(t)).abs());
                }
                let scale = zq.iter().chain(zr.iter()).fold(0.0_f64, |a, &b| a.max(b.abs()));
                prop_assert!(fit.max_error >= dense - 1e-12 * scale, "{} < {}", fit.max_error, dense);
                prop_assert!(fit.max_error <= scale);
            }
        }
    }

    /// The combined call agrees with the separate ones: `inside_depth_at` is `Some` exactly
    /// when `inside_at` is true (same edge values, bit for bit), and its depth matches
    /// `depth_at` to a few ulps and the screen-space perspective-correct f64 reference
    /// (`ref_depth`, independent of the edge equations), in f64 and f32.
    #[test]
    fn inside_depth_at_matches_separate_calls_and_reference(
        (q, r, x, y) in scene(),
        t in 0.0..1.0_f64,
        zq in [1.0..10.0_f64, 1.0..10.0, 1.0..10.0],
        zr in [1.0..10.0_f64, 1.0..10.0, 1.0..10.0],
        explicit in any::<bool>(),
    ) {
        let tri = MovingTriangle::new(q, r);
        let (tri, zq, zr) = if explicit {
            (tri.with_depth(zq, zr), zq, zr)
        } else {
            (tri, q.map(|v| v[2]), r.map(|v| v[2]))
        };
        let setup = tri.setup();
        // Times inside the coverage (so the depth comparison is exercised) and the random t.
        let cov = setup.coverage(x, y);
        let mut ts: Vec<f64> = cov.iter().map(|s| s.t0 + 0.37 * s.len()).collect();
        ts.push(t);
        for t in ts {
            let got = setup.inside_depth_at(x, y, t);
            prop_assert_eq!(got.is_some(), setup.inside_at(x, y, t));
            if let Some(d) = got {
                let sep = setup.depth_at(x, y, t);
                let (want, cond) = ref_depth(&q, &r, zq, zr, x, y, t);
                let scale = want.abs().max(1.0);
                prop_assert!((d - sep).abs() <= 1e-13 * cond.max(1.0) * scale, "{d} vs depth_at {sep}");
                prop_assert!((d - want).abs() <= 1e-13 * cond.max(1.0) * scale, "{d} vs reference {want} (cond {cond})");
            }
        }
        // f32 on the same (rounded) triangle: identical inside decisions, depth within
        // f32 rounding of the f64 reference.
        let (q32, r32) = (narrow(q), narrow(r));
        let tri32 = MovingTriangle::new(q32, r32);
        let tri32 = if explicit { tri32.with_depth(zq.map(|v| v as f32), zr.map(|v| v as f32)) } else { tri32 };
        let s32 = tri32.setup();
        let (x32, y32, t32) = (x as f32, y as f32, t as f32);
        let got = s32.inside_depth_at(x32, y32, t32);
        prop_assert_eq!(got.is_some(), s32.inside_at(x32, y32, t32));
        if let Some(d) = got {
            let sep = s32.depth_at(x32, y32, t32);
            let (want, cond) = ref_depth(&widen(q32), &widen(r32),
                zq.map(|v| f64::from(v as f32)), zr.map(|v| f64::from(v as f32)),
                f64::from(x32), f64::from(y32), f64::from(t32));
            let tol = 1e-4 * cond.max(1.0) * want.abs().max(1.0);
            prop_assert!((f64::from(d) - want).abs() <= tol, "f32 {d} vs reference {want} (cond {cond})");
            prop_assert!((f64::from(d) - f64::from(sep)).abs() <= tol, "f32 {d} vs depth_at {sep}");
        }
    }

    /// No NaN or infinity in any output for any finite input, and spans stay well formed.
    #[test]
    fn outputs_finite_for_finite_input(
        q in [[wild(), wild(), wild()], [wild(), wild(), wild()], [wild(), wild(), wild()]],
        r in [[wild(), wild(), wild()], [wild(), wild(), wild()], [wild(), wild(), wild()]],
        x in wild(), y in wild(), t in 0.0..1.0_f64,
        zq in [wild(), wild(), wild()], zr in [wild(), wild(), wild()],
    ) {
        for tri in [MovingTriangle::new(q, r), MovingTriangle::new(q, r).with_depth(zq, zr)] {
            let setup = tri.setup();
            let s = setup.sample(x, y);
            let cov = s.coverage();
            let mut prev = -1.0;
            for sp in cov.iter() {
                prop_assert!(sp.t0.is_finite() && sp.t1.is_finite());
                prop_assert!(0.0 <= sp.t0 && sp.t0 < sp.t1 && sp.t1 <= 1.0 && sp.t0 > prev);
                prev = sp.t1;
                let fit = s.linear_depth(*sp);
                prop_assert!(fit.z.is_finite() && fit.k.is_finite() && fit.max_error.is_finite());
            }
            let _ = setup.inside_at(x, y, t);
            prop_assert!(setup.inside_depth_at(x, y, t).is_none_or(f64::is_finite));
            prop_assert_eq!(setup.inside_depth_at(x, y, t).is_some(), setup.inside_at(x, y, t));
            prop_assert!(s.depth_at(t).is_finite());
            prop_assert!(s.barycentrics(t).iter().all(|v| v.is_finite()));
            prop_assert!(setup.orientation_at(t).is_finite());
            let fit = s.linear_depth(Span::new(0.0, 1.0));
            prop_assert!(fit.z.is_finite() && fit.k.is_finite() && fit.max_error.is_finite());
            // Same in f32.
            let s32 = MovingTriangle::new(narrow(q), narrow(r)).setup().sample(x as f32, y as f32);
            for sp in s32.coverage().iter() {
                prop_assert!(0.0 <= sp.t0 && sp.t0 < sp.t1 && sp.t1 <= 1.0);
            }
            prop_assert!(s32.depth_at(t as f32).is_finite());
            prop_assert!(s32.barycentrics(t as f32).iter().all(|v| v.is_finite()));
        }
    }

    /// f64 roots built from exactly known roots (26-bit mantissas, coefficients exact, any
    /// power-of-two scale of the equation and the unknown) come back within 2 ulps.
    #[test]
    fn quadratic_f64_exact_roots(
        m1 in 1u64..(1 << 26), m2 in 1u64..(1 << 26),
        e1 in -20i32..20, de in 0i32..20,
        s1 in any::<bool>(), s2 in any::<bool>(),
        scale_eq in -600i32..600, scale_x in -100i32..100,
    ) {
        let r1 = pm(s1) * m1 as f64 * 2f64.powi(e1 - 26) * 2f64.powi(scale_x);
        let r2 = pm(s2) * m2 as f64 * 2f64.powi(e1 - de - 26) * 2f64.powi(scale_x);
        let a = 2f64.powi(scale_eq);
        let b = -(r1 + r2) * a;
        let c = r1 * r2 * a;
        prop_assume!(b.is_finite() && c.is_finite() && c != 0.0 && c.abs() >= f64::MIN_POSITIVE);
        // Exactness of the constructed coefficients.
        prop_assume!((r1 + r2) - r1 == r2 && (r1 * r2) / r1 == r2);
        let got = real_roots(a, b, c);
        let (lo, hi) = if r1 <= r2 { (r1, r2) } else { (r2, r1) };
        if lo == hi {
            prop_assert_eq!(got.as_slice(), &[lo]);
        } else {
            prop_assert_eq!(got.len(), 2, "{:?} for roots {} {}", got, lo, hi);
            prop_assert!(ulps64(got[0], lo) <= 2.0, "{} vs {}", got[0], lo);
            prop_assert!(ulps64(got[1], hi) <= 2.0, "{} vs {}", got[1], hi);
        }
    }

    /// f32 roots of arbitrary f32 coefficients against an f64 reference with an exact
    /// discriminant (products of f32 values are exact in f64): within 4 f32 ulps.
    #[test]
    fn quadratic_f32_vs_exact_discriminant(
        a in f32_coef(), b in f32_coef(), c in f32_coef(),
    ) {
        let got = real_roots(a, b, c);
        let want = ref_roots_f32(a, b, c);
        match want {
            None => prop_assert!(got.is_empty() || a == 0.0),
            Some((lo, hi)) => {
                if a == 0.0 {
                    // The root of a line, dropped only when beyond f32::MAX.
                    prop_assert_eq!(got.len(), usize::from(lo.abs() <= f64::from(f32::MAX)));
                    prop_assert!(got.iter().all(|&g| ulps32(g, lo) <= 2.0));
                } else if lo == hi {
                    prop_assert!(got.len() == 1 && ulps32(got[0], lo) <= 2.0);
                } else {
                    // A root beyond f32::MAX is dropped; one below the subnormal range is 0.
                    let keep: Vec<f64> = [lo, hi].into_iter().filter(|v| v.abs() <= f64::from(f32::MAX)).collect();
                    prop_assert_eq!(got.len(), keep.len(), "{:?} vs {:?}", got, keep);
                    for (g, w) in got.iter().zip(keep.iter()) {
                        let ok = ulps32(*g, *w) <= 4.0 || (w.abs() < 1e-37 && f64::from(*g).abs() < 1e-37);
                        prop_assert!(ok, "{} vs {} ({} ulps)", g, w, ulps32(*g, *w));
                    }
                }
            }
        }
    }
}

fn pm(s: bool) -> f64 {
    if s { -1.0 } else { 1.0 }
}

fn f32_coef() -> impl Strategy<Value = f32> {
    prop_oneof![
        -100.0..100.0_f32,
        prop::num::f32::NORMAL | prop::num::f32::NEGATIVE | prop::num::f32::POSITIVE,
        Just(0.0_f32),
    ]
}

/// Roots of an f32 quadratic computed in f64 with an exact discriminant (f32 products are
/// exact in f64; b² - 4ac rounds once), the stable form, and correctly rounded f64 divisions.
fn ref_roots_f32(a: f32, b: f32, c: f32) -> Option<(f64, f64)> {
    let (a, b, c) = (f64::from(a), f64::from(b), f64::from(c));
    if a == 0.0 {
        return if b == 0.0 {
            None
        } else {
            Some((-c / b, -c / b))
        };
    }
    let d = b * b - 4.0 * a * c;
    if d < 0.0 {
        return None;
    }
    if d == 0.0 {
        return Some((-b / (2.0 * a), -b / (2.0 * a)));
    }
    let q = -0.5 * (b + d.sqrt().copysign(b));
    let (x1, x2) = (q / a, c / q);
    Some((x1.min(x2), x1.max(x2)))
}
