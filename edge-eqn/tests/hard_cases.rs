//! Hard cases by name. Each compares against an independent reference: exact rational
//! roots (pinned from 90-digit arithmetic on the exact binary coefficients), exactly
//! constructed roots, correctly rounded integer ratios, analytic crossing times, or the
//! dense-time f64 static inside test of `common`.

mod common;

use common::*;
use edge_eqn::quadratic::real_roots;
use edge_eqn::{EdgeQuadratic, MovingTriangle, Span};
use rand::{RngExt, SeedableRng};

fn assert_dense(q: &Tri, r: &Tri, x: f64, y: f64) {
    let cov = MovingTriangle::new(*q, *r).setup().coverage(x, y);
    if let Err(e) = check_dense(&cov, q, r, (x, y), 20_000, (1e-9, 1e-9)) {
        panic!("{e}");
    }
}

fn near(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

// ---------------------------------------------------------------------------------------
// Quadratic solver
// ---------------------------------------------------------------------------------------

/// Goualard 2023, Table 2: the degenerate coefficient patterns, f32 and f64.
#[test]
fn quadratic_goualard_table2_degenerate_cases() {
    fn check<F: num_traits::Float + std::fmt::Debug>() {
        let v = |x: f64| F::from(x).unwrap();
        let r = |a, b, c| real_roots(v(a), v(b), v(c)).to_vec();
        assert_eq!(r(0.0, 0.0, 0.0), vec![]); // every x: documented as empty
        assert_eq!(r(0.0, 0.0, 1.0), vec![]); // no x
        assert_eq!(r(0.0, 1.0, 0.0), vec![v(0.0)]);
        assert_eq!(r(0.0, 1.0, 1.0), vec![v(-1.0)]);
        assert_eq!(r(1.0, 0.0, 0.0), vec![v(0.0)]); // double root, once
        assert_eq!(r(1.0, 0.0, 1.0), vec![]);
        assert_eq!(r(1.0, 0.0, -1.0), vec![v(-1.0), v(1.0)]);
        assert_eq!(r(1.0, 4.0, 0.0), vec![v(-4.0), v(0.0)]);
        assert_eq!(r(-1.0, 4.0, 0.0), vec![v(0.0), v(4.0)]);
    }
    check::<f32>();
    check::<f64>();
}

/// Forsythe 1970 ("How do you solve a quadratic equation?", cited by Goualard 2023), Kahan
/// 2004's two cancellation examples, and extreme-exponent cases. References: exact roots
/// of the binary coefficients (Python `fractions` + 90-digit `decimal` sqrt), correctly
/// rounded to f64.
const TABLE_F64: &[(&str, f64, f64, f64, &[f64])] = &[
    ("forsythe_1", 6.0, 5.0, -4.0, &[-1.3333333333333333, 0.5]),
    (
        "forsythe_2_scaled_1e30",
        6e+30,
        5e+30,
        -4e+30,
        &[-1.3333333333333335, 0.5],
    ),
    ("forsythe_3_linear", 0.0, 1.0, 1.0, &[-1.0]),
    (
        "forsythe_4_b_dominant",
        1.0,
        -100000.0,
        1.0,
        &[1.0000000001e-05, 99999.99999],
    ),
    (
        "forsythe_5_near_double",
        1.0,
        -4.0,
        3.9999999,
        &[1.999683772234242, 2.000316227765758],
    ),
    (
        "forsythe_6_wide_exponents",
        1e-30,
        -1e+30,
        1e+30,
        &[1.0, 1e+60],
    ),
    (
        "kahan_1",
        94906265.625,
        -189812534.0,
        94906268.375,
        &[1.0, 1.0000000289759583],
    ),
    (
        "kahan_2",
        94906266.375,
        -189812534.75,
        94906268.375,
        &[1.0, 1.0000000210734241],
    ),
    (
        "cancel_b_squared",
        1.0,
        -100000000.0,
        1.0,
        &[1e-08, 99999999.99999999],
    ),
    (
        "tiny_all",
        1e-300,
        -3e-300,
        2e-300,
        &[0.9999999999999999, 2.0000000000000004],
    ),
    ("huge_all", 1e+300, -3e+300, 2e+300, &[1.0, 2.0]),
    (
        "a_huge_c_tiny",
        4.149515568880993e+180,
        -1.0,
        2.409919865102884e-181,
        &[],
    ),
    (
        "a_tiny_c_huge",
        2.409919865102884e-181,
        -3.0,
        8.299031137761986e+180,
        &[4.149515568880993e+180, 8.299031137761986e+180],
    ),
    (
        "b_zero_extreme",
        1.90109156629516e-211,
        0.0,
        -3.273390607896142e+150,
        &[-4.149515568880993e+180, 4.149515568880993e+180],
    ),
];

/// The same families with f32 coefficients (f32-sized exponents); references exact as above.
const TABLE_F32: &[(&str, f64, f64, f64, &[f64])] = &[
    ("forsythe_1", 6.0, 5.0, -4.0, &[-1.3333333333333333, 0.5]),
    (
        "forsythe_2_scaled_1e30",
        5.999999788053342e+30,
        4.9999999241216036e+30,
        -4.000000060189865e+30,
        &[-1.333333363861764, 0.5000000137377937],
    ),
    ("forsythe_3_linear", 0.0, 1.0, 1.0, &[-1.0]),
    (
        "forsythe_4_b_dominant",
        1.0,
        -100000.0,
        1.0,
        &[1.0000000001e-05, 99999.99999],
    ),
    (
        "forsythe_5_near_double",
        1.0,
        -4.0,
        3.9999001026153564,
        &[1.990005132084737, 2.009994867915263],
    ),
    (
        "forsythe_6_wide_exponents",
        1.000000045813705e-18,
        -9.999999843067494e+17,
        9.999999843067494e+17,
        &[1.0, 9.999999384930473e+35],
    ),
    (
        "kahan_style_f32",
        12582913.0,
        -25165828.0,
        12582915.0,
        &[1.0, 1.0000001589457068],
    ),
    (
        "cancel_b_squared",
        1.0,
        -10000.0,
        1.0,
        &[0.00010000000100000001, 9999.999899999999],
    ),
    (
        "tiny_all",
        1.0000000031710769e-30,
        -3.0000000095132306e-30,
        2.0000000063421537e-30,
        &[1.0, 2.0],
    ),
    (
        "huge_all",
        1.0000000150474662e+30,
        -2.999999894026671e+30,
        2.0000000300949324e+30,
        &[1.0000001511157708, 1.999999697768504],
    ),
    (
        "a_huge_c_tiny",
        1.152921504606847e+18,
        -3.0,
        1.734723475976807e-18,
        &[8.673617379884035e-19, 1.734723475976807e-18],
    ),
    (
        "a_tiny_c_huge",
        8.673617379884035e-19,
        -3.0,
        2.305843009213694e+18,
        &[1.152921504606847e+18, 2.305843009213694e+18],
    ),
    (
        "b_zero_extreme",
        7.888609052210118e-31,
        0.0,
        -1.2089258196146292e+24,
        &[-1.2379400392853803e+27, 1.2379400392853803e+27],
    ),
];

#[test]
fn quadratic_forsythe_kahan_extreme_table() {
    let mut worst64: f64 = 0.0;
    for &(name, a, b, c, want) in TABLE_F64 {
        let got = real_roots(a, b, c);
        assert_eq!(got.len(), want.len(), "{name}: {got:?} vs {want:?}");
        for (g, w) in got.iter().zip(want) {
            let u = ulps64(*g, *w);
            worst64 = worst64.max(u);
            assert!(u <= 2.0, "{name}: {g} vs {w} ({u} ulps)");
        }
    }
    let mut worst32: f64 = 0.0;
    for &(name, a, b, c, want) in TABLE_F32 {
        let got = real_roots(a as f32, b as f32, c as f32);
        assert_eq!(got.len(), want.len(), "{name}: {got:?} vs {want:?}");
        for (g, w) in got.iter().zip(want) {
            let u = ulps32(*g, *w);
            worst32 = worst32.max(u);
            assert!(u <= 2.0, "{name} f32: {g} vs {w} ({u} ulps)");
        }
    }
    eprintln!("published table: worst root error f64 {worst64:.2} ulps, f32 {worst32:.2} ulps");
}

fn fib(n: u32) -> u64 {
    let (mut a, mut b) = (0u64, 1u64);
    for _ in 0..n {
        (a, b) = (b, a + b);
    }
    a
}

/// Kahan's Fibonacci family (used by Goualard 2023): M F_n x² - 2 M F_{n-1} x + M F_{n-2},
/// n even, roots (F_{n-1} ± 1) / F_n, which are 2/F_n apart while b² ≈ 4ac to ~2 log2 F_n
/// bits. References are correctly rounded integer ratios.
#[test]
fn quadratic_kahan_fibonacci_near_double_roots() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(2023);
    let mut worst64: f64 = 0.0;
    for n in (4..=74).step_by(2) {
        let (f0, f1, f2) = (fib(n), fib(n - 1), fib(n - 2));
        if f0 >= 1 << 52 {
            break;
        }
        for _ in 0..200 {
            let r: u64 = rng.random_range((1u64 << 52)..(1u64 << 53));
            let m = (r / f0).max(1);
            let (a, b, c) = ((m * f0) as f64, -2.0 * (m * f1) as f64, (m * f2) as f64);
            let lo = (f1 - 1) as f64 / f0 as f64;
            let hi = (f1 + 1) as f64 / f0 as f64;
            let got = real_roots(a, b, c);
            assert_eq!(got.len(), 2, "n {n} m {m}: {got:?}");
            for (g, w) in got.iter().zip([lo, hi]) {
                let u = ulps64(*g, w);
                worst64 = worst64.max(u);
                assert!(u <= 2.0, "n {n}: {g} vs {w} ({u} ulps)");
            }
        }
    }
    let mut worst32: f64 = 0.0;
    for n in (4..=34).step_by(2) {
        let (f0, f1, f2) = (fib(n), fib(n - 1), fib(n - 2));
        if f0 >= 1 << 23 {
            break;
        }
        for _ in 0..200 {
            let r: u64 = rng.random_range((1u64 << 23)..(1u64 << 24));
            let m = (r / f0).max(1);
            let (a, b, c) = ((m * f0) as f32, -2.0 * (m * f1) as f32, (m * f2) as f32);
            let lo = (f1 - 1) as f64 / f0 as f64;
            let hi = (f1 + 1) as f64 / f0 as f64;
            let got = real_roots(a, b, c);
            assert_eq!(got.len(), 2, "f32 n {n} m {m}: {got:?}");
            for (g, w) in got.iter().zip([lo, hi]) {
                let u = ulps32(*g, w);
                worst32 = worst32.max(u);
                assert!(u <= 2.0, "f32 n {n}: {g} vs {w} ({u} ulps)");
            }
        }
    }
    eprintln!("Kahan-Fibonacci: worst root error f64 {worst64:.2} ulps, f32 {worst32:.2} ulps");
}

/// Roots 1 and 1 + 2^-k (k up to 26): b² and 4ac agree to 2k bits; a naive discriminant
/// returns a double root or none from k = 27 on in f64. Coefficients are exact.
#[test]
fn quadratic_close_roots_exact_coefficients() {
    for k in 1..=26 {
        let r2 = 1.0 + 2f64.powi(-k);
        let got = real_roots(1.0, -(1.0 + r2), r2);
        assert_eq!(got.as_slice(), &[1.0, r2], "k = {k}");
    }
    for k in 1..=11 {
        let r2 = 1.0 + 2f32.powi(-k);
        let got = real_roots(1.0_f32, -(1.0 + r2), r2);
        assert_eq!(got.as_slice(), &[1.0, r2], "f32 k = {k}");
    }
}

/// Coefficients near 2^±600 in f64 (and 2^±60 in f32) with exactly known roots.
#[test]
fn quadratic_extreme_exponents_exact_roots() {
    let p = |e: i32| 2f64.powi(e);
    for (ea, r1, r2) in [
        (600, p(-300), p(-299)),
        (-600, p(300), 3.0 * p(300)),
        (600, -p(-500), p(-490)),
        (-600, -p(500), p(500)),
        (0, p(-500), p(500)),
        (300, p(-400), p(-400) * 1.5),
    ] {
        let a = p(ea);
        let (b, c) = (-(r1 + r2) * a, r1 * r2 * a);
        assert!(b.is_finite() && c.is_finite() && c != 0.0);
        let got = real_roots(a, b, c);
        assert_eq!(got.as_slice(), &[r1.min(r2), r1.max(r2)], "a = 2^{ea}");
    }
    let p = |e: i32| 2f32.powi(e);
    for (ea, r1, r2) in [
        (60, p(-30), p(-29)),
        (-60, p(30), 3.0 * p(30)),
        (0, p(-50), p(50)),
    ] {
        let a = p(ea);
        let (b, c) = (-(r1 + r2) * a, r1 * r2 * a);
        let got = real_roots(a, b, c);
        assert_eq!(got.as_slice(), &[r1.min(r2), r1.max(r2)], "f32 a = 2^{ea}");
    }
}

/// Seeded sweep over exactly constructed roots at every scale; prints the worst error that
/// `BENCHMARKS.md` quotes. f64: roots with 26-bit mantissas (coefficients exact);
/// f32: arbitrary coefficients against an f64 reference with an exact discriminant.
#[test]
fn quadratic_worst_ulps_sweep() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(42);
    let deep = std::env::var("MBLUR_DEEP").is_ok_and(|v| v == "1");
    let n = if deep { 2_000_000 } else { 200_000 };
    let mut worst64: f64 = 0.0;
    for _ in 0..n {
        let m1 = rng.random_range(1u64..(1 << 26)) as f64;
        let m2 = rng.random_range(1u64..(1 << 26)) as f64;
        let e1 = rng.random_range(-30..30);
        let de = rng.random_range(0..27);
        let sx = rng.random_range(-100..100);
        let se = rng.random_range(-600..600);
        let s1 = if rng.random_bool(0.5) { -1.0 } else { 1.0 };
        let s2 = if rng.random_bool(0.5) { -1.0 } else { 1.0 };
        let r1 = s1 * m1 * 2f64.powi(e1 - 26 + sx);
        let r2 = s2 * m2 * 2f64.powi(e1 - de - 26 + sx);
        let a = 2f64.powi(se);
        let (b, c) = (-(r1 + r2) * a, r1 * r2 * a);
        if (r1 + r2) - r1 != r2 || r1 == r2 {
            continue;
        }
        let got = real_roots(a, b, c);
        assert_eq!(got.len(), 2);
        worst64 = worst64
            .max(ulps64(got[0], r1.min(r2)))
            .max(ulps64(got[1], r1.max(r2)));
    }
    // f64: arbitrary coefficients (exponents within ±200) against the double-double
    // reference; skip the ill-conditioned near-double roots (|D| < 2^-40 b²) whose
    // reference is itself only accurate to about an ulp.
    let mut worst64_dd: f64 = 0.0;
    for _ in 0..n {
        let g = |rng: &mut rand_pcg::Pcg64| {
            let m: f64 = rng.random_range(-1.0..1.0);
            m * 2f64.powi(rng.random_range(-200..200))
        };
        let (a, b, c) = (g(&mut rng), g(&mut rng), g(&mut rng));
        if a == 0.0 || c == 0.0 {
            continue;
        }
        let got = real_roots(a, b, c);
        match dd_roots(a, b, c) {
            None => assert!(got.len() <= 1, "{a} {b} {c}: {got:?}"),
            Some((x1, x2)) => {
                let d = Dd::prod(b, b).add(Dd::prod(4.0 * a, c).neg());
                if d.0 < (b * b).abs() * 2f64.powi(-40) {
                    continue;
                }
                assert_eq!(got.len(), 2, "{a} {b} {c}");
                worst64_dd = worst64_dd.max(x1.ulps_of(got[0])).max(x2.ulps_of(got[1]));
            }
        }
    }
    let mut worst32: f64 = 0.0;
    for _ in 0..n {
        let g = |rng: &mut rand_pcg::Pcg64| {
            let m: f32 = rng.random_range(-1.0..1.0);
            m * 2f32.powi(rng.random_range(-40..40))
        };
        let (a, b, c) = (g(&mut rng), g(&mut rng), g(&mut rng));
        if a == 0.0 {
            continue; // the linear case has its own exact tests
        }
        let (a6, b6, c6) = (f64::from(a), f64::from(b), f64::from(c));
        let d = b6 * b6 - 4.0 * a6 * c6;
        let got = real_roots(a, b, c);
        if d <= 0.0 {
            assert!(got.len() <= 1 || d == 0.0);
            continue;
        }
        let q = -0.5 * (b6 + d.sqrt().copysign(b6));
        let (x1, x2) = (q / a6, c6 / q);
        assert_eq!(got.len(), 2, "{a} {b} {c}");
        worst32 = worst32
            .max(ulps32(got[0], x1.min(x2)))
            .max(ulps32(got[1], x1.max(x2)));
    }
    eprintln!(
        "random sweep ({n} each): worst root error: f64 exact-root construction {worst64:.2} ulps; \
         f64 arbitrary coefficients vs double-double {worst64_dd:.2} ulps; \
         f32 vs exact-discriminant f64 {worst32:.2} ulps"
    );
    assert!(worst64 <= 2.0 && worst64_dd <= 3.0 && worst32 <= 4.0);
}

// ---------------------------------------------------------------------------------------
// Edge and triangle coverage
// ---------------------------------------------------------------------------------------

/// α tiny relative to β and γ (α = β 2^-k) at magnitudes 1e-6, 1 and 1e6: the crossing is
/// the near root 0.375, within a few ulps, and no spurious far root appears.
#[test]
fn near_linear_motion_tiny_alpha_several_magnitudes() {
    for mag in [1e-6, 1.0, 1e6] {
        for k in [8, 20, 27, 40, 52, 53, 60, 100, 200] {
            for sgn in [-1.0, 1.0] {
                let beta = 3.0 * mag;
                let alpha = sgn * beta * 2f64.powi(-k);
                let gamma = -(alpha * 0.140625 + beta * 0.375);
                let e = EdgeQuadratic { alpha, beta, gamma };
                let spans = e.inside_spans();
                assert_eq!(spans.len(), 1, "mag {mag} k {k}");
                assert_eq!(spans[0].t0, 0.0);
                assert!(ulps64(spans[0].t1, 0.375) <= 4.0, "{} (k {k})", spans[0].t1);
                let e32 = EdgeQuadratic {
                    alpha: alpha as f32,
                    beta: beta as f32,
                    gamma: gamma as f32,
                };
                let s32 = e32.inside_spans();
                assert_eq!(s32.len(), 1);
                assert!(
                    ulps32(s32[0].t1, 0.375) <= 4.0,
                    "f32 {} (mag {mag} k {k})",
                    s32[0].t1
                );
            }
        }
    }
    // Triangle-level: a translation whose w grows by 1e-9 (α ≈ 1e-9 β) vs the dense reference.
    let q: Tri = [[10.0, 10.0, 1.0], [40.0, 12.0, 1.0], [15.0, 35.0, 1.0]];
    let r: Tri = q.map(|[x, y, w]| {
        let w1 = w * (1.0 + 1e-9);
        [(x / w + 25.0) * w1, (y / w + 3.0) * w1, w1]
    });
    let setup = MovingTriangle::new(q, r).setup();
    let a = setup
        .sample(38.5, 20.5)
        .edges()
        .map(|e| e.alpha.abs() / e.beta.abs().max(e.gamma.abs()));
    assert!(a.iter().all(|&v| v < 1e-6), "{a:?}");
    for (x, y) in [(38.5, 20.5), (45.5, 14.5), (30.5, 30.5)] {
        assert_dense(&q, &r, x, y);
    }
}

/// A pure translation with constant w has α exactly 0 for every edge and sample; the
/// crossing times are the analytic ones.
#[test]
fn pure_translation_alpha_exactly_zero() {
    // Screen triangle (0,0), (8,0), (0,8) at w = 2, moving 8 px right.
    let q: Tri = [[0.0, 0.0, 2.0], [16.0, 0.0, 2.0], [0.0, 16.0, 2.0]];
    let r: Tri = q.map(|[x, y, w]| [x + 8.0 * w, y, w]);
    let setup = MovingTriangle::new(q, r).setup();
    for e in setup.edges() {
        assert_eq!(e.f, [0.0; 3]);
    }
    for (x, y) in [(6.5, 1.5), (10.5, 1.5), (3.25, 3.0)] {
        assert!(setup.sample(x, y).edges().iter().all(|e| e.alpha == 0.0));
    }
    // (6.5, 1.5): inside while the left edge x = 8t is left of it: t <= 6.5/8.
    assert_eq!(&setup.coverage(6.5, 1.5)[..], &[Span::new(0.0, 0.8125)]);
    // (10.5, 1.5): enters when the hypotenuse x + y = 8 + 8t passes it: t >= 0.5.
    assert_eq!(&setup.coverage(10.5, 1.5)[..], &[Span::new(0.5, 1.0)]);
    for (x, y) in [(6.5, 1.5), (10.5, 1.5), (3.25, 3.0)] {
        assert_dense(&q, &r, x, y);
    }
}

/// The edge AB rotates about the sample: relative to it A(t) = (-1, t - 1/2) and
/// B(t) = (3/2 - t, 1/2 - t), so its edge function is exactly ±(t - 1/2)² (a double root,
/// the sample touches the middle of the edge at t = 1/2 and stays on the same side). With C
/// on the sample's side the sample is covered for the whole shutter; with C on the other
/// side it is never covered (the touching instant has zero length).
#[test]
fn double_root_tangent_sample() {
    let (sx, sy) = (10.5, 10.5);
    let a0 = [sx - 1.0, sy - 0.5, 1.0];
    let a1 = [sx - 1.0, sy + 0.5, 1.0];
    let b0 = [sx + 1.5, sy + 0.5, 1.0];
    let b1 = [sx + 0.5, sy - 0.5, 1.0];
    for (c, expect_full) in [([sx, sy + 30.0, 1.0], true), ([sx, sy - 30.0, 1.0], false)] {
        let q = [a0, b0, c];
        let r = [a1, b1, c];
        let s = MovingTriangle::new(q, r).setup().sample(sx, sy);
        let tangent = s.edges().iter().find(|e| {
            let d = e.beta * e.beta - 4.0 * e.alpha * e.gamma;
            e.alpha != 0.0 && d == 0.0
        });
        let e = tangent.expect("one edge has an exact double root");
        assert_eq!(-e.beta / (2.0 * e.alpha), 0.5);
        let cov = s.coverage();
        if expect_full {
            assert_eq!(&cov[..], &[Span::new(0.0, 1.0)]);
        } else {
            assert!(cov.is_empty(), "{:?}", &cov[..]);
        }
        assert_dense(&q, &r, sx, sy);
        // f32 agrees (all coordinates are exact in f32).
        let c32 = MovingTriangle::new(narrow(q), narrow(r))
            .setup()
            .coverage(sx as f32, sy as f32);
        assert_eq!(c32.len(), cov.len());
    }
}

/// The sample lies exactly on an edge at t = 0 (entering) and exactly on an edge at t = 1
/// (leaving): the spans start at exactly 0 and end at exactly 1, and their other ends are
/// the analytic crossing times.
#[test]
fn sample_exactly_on_edge_at_t0_and_t1() {
    // Right triangle (2,0), (10,0), (2,8) sliding right by 4 px: left edge x = 2 + 4t,
    // hypotenuse x + y = 10 + 4t.
    let q: Tri = [[2.0, 0.0, 1.0], [10.0, 0.0, 1.0], [2.0, 8.0, 1.0]];
    let r: Tri = q.map(|[x, y, w]| [x + 4.0, y, w]);
    let setup = MovingTriangle::new(q, r).setup();
    // On the left edge at t = 0 and outside after: zero length, empty.
    assert!(setup.coverage(2.0, 3.0).is_empty());
    // On the hypotenuse at t = 0 and inside after, until the left edge passes at t = 0.75.
    assert_eq!(&setup.coverage(5.0, 5.0)[..], &[Span::new(0.0, 0.75)]);
    // On the hypotenuse at t = 1, outside before: zero length, empty.
    assert!(setup.coverage(11.0, 3.0).is_empty());
    // Enters at t = 0.25 through the hypotenuse and is on the left edge exactly at t = 1.
    assert_eq!(&setup.coverage(6.0, 5.0)[..], &[Span::new(0.25, 1.0)]);
    // On the left edge at t = 1, inside from t = 0.
    assert_eq!(&setup.coverage(6.0, 3.0)[..], &[Span::new(0.0, 1.0)]);
    for (x, y) in [(2.0, 3.0), (5.0, 5.0), (11.0, 3.0), (6.0, 5.0), (6.0, 3.0)] {
        assert_dense(&q, &r, x, y);
    }
}

/// Vertex C lands exactly on the line AB at t = 1 (zero area at one instant, no flip):
/// the sample inside is covered until the shrinking triangle leaves it; depth and
/// barycentrics stay finite at the degenerate instant.
#[test]
fn triangle_degenerate_zero_area_at_one_instant() {
    let q: Tri = [[0.0, 0.0, 1.0], [10.0, 0.0, 1.0], [5.0, 10.0, 1.0]];
    let r: Tri = [[0.0, 0.0, 1.0], [10.0, 0.0, 1.0], [5.0, 0.0, 1.0]];
    let setup = MovingTriangle::new(q, r).setup();
    assert_eq!(setup.orientation_at(1.0), 0.0);
    assert!(setup.orientation_at(0.0) > 0.0 && setup.orientation_at(0.999) > 0.0);
    let cov = setup.coverage(5.0, 2.0);
    // Apex height 10 - 10t >= 2 ↔ t <= 0.8.
    assert_eq!(cov.len(), 1);
    assert!(
        near(cov[0].t0, 0.0, 0.0) && near(cov[0].t1, 0.8, 1e-12),
        "{:?}",
        &cov[..]
    );
    let s = setup.sample(5.0, 0.0);
    let cov = s.coverage();
    assert_eq!(&cov[..], &[Span::new(0.0, 1.0)]); // on the base line all the time
    assert!(s.depth_at(1.0).is_finite() && s.barycentrics(1.0).iter().all(|v| v.is_finite()));
    // The combined inside-and-depth call at the collapsed instant: covered (all e = 0 on the
    // base line) with the documented fallback depth (mean of the vertex depths, here 1).
    assert_eq!(setup.inside_depth_at(5.0, 0.0, 1.0), Some(1.0));
    assert_eq!(
        setup.inside_depth_at(5.0, 0.0, 1.0).is_some(),
        setup.inside_at(5.0, 0.0, 1.0)
    );
    for (x, y) in [(5.0, 2.0), (5.0, 0.5), (2.0, 1.0)] {
        assert_dense(&q, &r, x, y);
    }
}

/// Vertex C crosses AB at t = 1/2, so the signed area (the 2DH determinant, a cubic in t)
/// changes sign inside the shutter. A sample above AB is covered before the flip
/// ([0, 0.4]), one below after it ([0.65, 1]); Gribel's front-facing-only e <= 0 rule would
/// miss one of the two.
#[test]
fn orientation_flip_inside_shutter() {
    let q: Tri = [[0.0, 0.0, 1.0], [10.0, 0.0, 1.0], [5.0, 10.0, 1.0]];
    let r: Tri = [[0.0, 0.0, 1.0], [10.0, 0.0, 1.0], [5.0, -10.0, 1.0]];
    let setup = MovingTriangle::new(q, r).setup();
    assert!(setup.orientation_at(0.25) > 0.0 && setup.orientation_at(0.75) < 0.0);
    assert_eq!(setup.orientation_at(0.5), 0.0);
    let above = setup.coverage(5.0, 2.0);
    assert_eq!(above.len(), 1);
    assert!(
        above[0].t0 == 0.0 && near(above[0].t1, 0.4, 1e-12),
        "{:?}",
        &above[..]
    );
    let below = setup.coverage(5.0, -3.0);
    assert_eq!(below.len(), 1);
    assert!(
        near(below[0].t0, 0.65, 1e-12) && below[0].t1 == 1.0,
        "{:?}",
        &below[..]
    );
    // Before the flip the triangle is front-facing (det > 0) and Gribel's e <= 0 holds.
    let s = setup.sample(5.0, 2.0);
    assert!(s.edges().iter().all(|e| e.eval(0.25) <= 0.0));
    // After it, the front-facing-only rule (all e <= 0) rejects a covered sample.
    let s = setup.sample(5.0, -3.0);
    assert!(!s.edges().iter().all(|e| e.eval(0.9) <= 0.0));
    assert!(s.inside_at(0.9));
    for (x, y) in [(5.0, 2.0), (5.0, -3.0), (3.0, 0.5), (7.0, -0.5)] {
        assert_dense(&q, &r, x, y);
    }
    // With perspective (w varying) too.
    let qw = q.map(|[x, y, _]| [x * 2.0, y * 2.0, 2.0]);
    let rw = r.map(|[x, y, _]| [x * 0.5, y * 0.5, 0.5]);
    for (x, y) in [(5.0, 2.0), (5.0, -3.0), (3.0, 0.5)] {
        assert_dense(&qw, &rw, x, y);
    }
}

/// Three disjoint spans for a triangle that is front-facing during the whole shutter
/// (Gribel 2010, Fig. 5 right). Found by a seeded search; checked against the dense
/// reference, which sees the same three spans.
#[test]
fn three_disjoint_spans_front_facing() {
    let q: Tri = [[4.0, 4.0, 1.0], [-7.0, 8.0, 1.0], [7.0, -8.0, 1.0]];
    let r: Tri = [[6.0, -8.0, 1.0], [4.0, 6.0, 1.0], [-7.0, 4.0, 1.0]];
    let (x, y) = (4.5, -0.5);
    let setup = MovingTriangle::new(q, r).setup();
    assert!((0..=1000).all(|i| setup.orientation_at(f64::from(i) / 1000.0) > 0.0));
    let cov = setup.coverage(x, y);
    assert_eq!(cov.len(), 3, "{:?}", &cov[..]);
    assert_eq!(count_reference_spans(&q, &r, x, y), 3);
    assert_dense(&q, &r, x, y);
}

/// Four disjoint spans (the theoretical maximum of §4.3), still front-facing throughout.
#[test]
fn four_disjoint_spans_maximum() {
    let q: Tri = [[-4.0, 2.0, 1.0], [3.0, -6.0, 1.0], [1.0, 2.0, 1.0]];
    let r: Tri = [[0.0, 1.0, 1.0], [-8.0, 7.0, 1.0], [-3.0, -3.0, 1.0]];
    let (x, y) = (-1.5, -0.5);
    let cov = MovingTriangle::new(q, r).setup().coverage(x, y);
    assert_eq!(cov.len(), 4, "{:?}", &cov[..]);
    assert_eq!(count_reference_spans(&q, &r, x, y), 4);
    assert_dense(&q, &r, x, y);
    // Same in f32.
    let c32 = MovingTriangle::new(narrow(q), narrow(r))
        .setup()
        .coverage(x as f32, y as f32);
    assert_eq!(c32.len(), 4);
    for (a, b) in c32.iter().zip(cov.iter()) {
        assert!(near(f64::from(a.t0), b.t0, 1e-5) && near(f64::from(a.t1), b.t1, 1e-5));
    }
}

fn count_reference_spans(q: &Tri, r: &Tri, x: f64, y: f64) -> usize {
    let mut n = 0;
    let mut prev = false;
    for i in 0..=100_000 {
        let (inside, _) = static_inside(&lerp_tri(q, r, f64::from(i) / 100_000.0), x, y);
        if inside && !prev {
            n += 1;
        }
        prev = inside;
    }
    n
}

/// w near zero and negative (vertices behind the eye): no NaN or infinity anywhere, and the
/// documented result — the times at which the line through the eye and the sample crosses
/// the triangle (both windings, crossings behind the eye included) — which is what the 2DH
/// static test accepting both windings gives.
#[test]
fn w_near_zero_and_negative_behind_eye() {
    let cases: [(Tri, Tri); 4] = [
        (
            [[1e-12, 0.0, 1e-12], [10.0, 0.0, 1.0], [0.0, 10.0, 1.0]],
            [[5.0, 0.0, 1e-300], [15.0, 0.0, 1.0], [5.0, 10.0, 1.0]],
        ),
        (
            [[-4.0, -4.0, -1.0], [10.0, 0.0, 1.0], [0.0, 10.0, 1.0]],
            [[4.0, 4.0, 1.0], [10.0, 0.0, 1.0], [0.0, 10.0, 1.0]],
        ),
        (
            [[1.0, 1.0, -0.5], [10.0, 2.0, -1.0], [2.0, 10.0, -2.0]],
            [[3.0, 1.0, -0.5], [12.0, 2.0, -1.0], [4.0, 10.0, -2.0]],
        ),
        (
            [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 10.0, 0.0]],
            [[0.0, 0.0, 1.0], [10.0, 0.0, 1.0], [0.0, 10.0, 1.0]],
        ),
    ];
    for (q, r) in cases {
        let setup = MovingTriangle::new(q, r).setup();
        assert!(setup.is_valid());
        for (x, y) in [
            (2.5, 2.5),
            (-3.5, -1.5),
            (8.5, 1.5),
            (0.5, 0.5),
            (20.5, 20.5),
        ] {
            let s = setup.sample(x, y);
            let cov = s.coverage();
            for sp in cov.iter() {
                assert!(sp.t0.is_finite() && sp.t1.is_finite() && sp.t0 < sp.t1);
                let fit = s.linear_depth(*sp);
                assert!(fit.z.is_finite() && fit.k.is_finite() && fit.max_error.is_finite());
            }
            for i in 0..=20 {
                let t = f64::from(i) / 20.0;
                assert!(s.depth_at(t).is_finite());
                let d = setup.inside_depth_at(x, y, t);
                assert_eq!(d.is_some(), setup.inside_at(x, y, t));
                assert!(d.is_none_or(f64::is_finite));
                assert!(s.barycentrics(t).iter().all(|v| v.is_finite()));
            }
            let res = check_dense(&cov, &q, &r, (x, y), 20_000, (1e-9, 1e-9));
            assert!(res.is_ok(), "{:?}", res);
        }
    }
}

/// The same screen-space motion with coordinates scaled by 1e-6 and 1e6 (x, y and sample),
/// and with w scaled by 1e-6 and 1e6 (x, y, w together: same screen positions): coverage
/// times agree with the unscaled triangle, in f64 and f32.
#[test]
fn huge_and_tiny_coordinate_magnitudes() {
    let q: Tri = [[10.0, 10.0, 1.0], [40.0, 12.0, 1.5], [15.0, 35.0, 2.0]];
    let r: Tri = [[30.0, 20.0, 1.2], [55.0, 20.0, 1.0], [20.0, 50.0, 2.5]];
    let samples = [(20.5, 15.5), (25.5, 12.5), (12.5, 14.5)];
    for s in [1e-6, 1e6] {
        for (mode, scale_w) in [("xy", false), ("xyw", true)] {
            let f = |t: Tri| {
                t.map(|[x, y, w]| {
                    if scale_w {
                        [x * s, y * s, w * s]
                    } else {
                        [x * s, y * s, w]
                    }
                })
            };
            let (qs, rs) = (f(q), f(r));
            for (x, y) in samples {
                let (xs, ys) = if scale_w { (x, y) } else { (x * s, y * s) };
                let base = MovingTriangle::new(q, r).setup().coverage(x, y);
                assert!(!base.is_empty());
                let got = MovingTriangle::new(qs, rs).setup().coverage(xs, ys);
                assert_eq!(got.len(), base.len(), "{mode} {s}");
                for (a, b) in got.iter().zip(base.iter()) {
                    assert!(
                        near(a.t0, b.t0, 1e-9) && near(a.t1, b.t1, 1e-9),
                        "{mode} {s}: {a:?} {b:?}"
                    );
                }
                let g32 = MovingTriangle::new(narrow(qs), narrow(rs))
                    .setup()
                    .coverage(xs as f32, ys as f32);
                assert_eq!(g32.len(), base.len(), "f32 {mode} {s}");
                for (a, b) in g32.iter().zip(base.iter()) {
                    assert!(
                        near(f64::from(a.t0), b.t0, 1e-4) && near(f64::from(a.t1), b.t1, 1e-4),
                        "f32 {mode} {s}: {a:?} {b:?}"
                    );
                }
                let d0 = MovingTriangle::new(q, r)
                    .setup()
                    .depth_at(x, y, base[0].mid());
                let d1 = MovingTriangle::new(qs, rs)
                    .setup()
                    .depth_at(xs, ys, base[0].mid());
                let want = if scale_w { d0 * s } else { d0 };
                assert!(
                    ((d1 - want) / want).abs() < 1e-9,
                    "{mode} {s}: {d1} vs {want}"
                );
            }
        }
    }
}

/// q == r: the static fast path (α = β = 0, no quadratic), coverage [0, 1] or empty,
/// agreeing with the static inside test.
#[test]
fn static_triangle_fast_path() {
    let p: Tri = [[2.0, 2.0, 1.0], [20.0, 4.0, 2.0], [4.0, 18.0, 1.5]];
    let tri = MovingTriangle::fixed(p);
    let setup = tri.setup();
    assert!(setup.is_static());
    for (x, y) in [(4.5, 4.5), (9.5, 2.5), (3.5, 9.5), (30.5, 30.5), (2.5, 2.5)] {
        let s = setup.sample(x, y);
        assert!(s.edges().iter().all(|e| e.alpha == 0.0 && e.beta == 0.0));
        let cov = s.coverage();
        let (inside, _) = static_inside(&p, x, y);
        if inside {
            assert_eq!(&cov[..], &[Span::new(0.0, 1.0)]);
        } else {
            assert!(cov.is_empty());
        }
        // Depth is constant in time: the linear fit is exact.
        if inside {
            let fit = s.linear_depth(cov[0]);
            assert!(fit.k.abs() < 1e-12 && fit.max_error < 1e-12);
        }
    }
}

/// Depth: the exact rational depth matches dense f64 screen-space evaluation along every
/// covered span, and the linear fit's reported max error matches a dense scan.
#[test]
fn depth_exact_vs_dense_and_linear_fit_error() {
    let q: Tri = [[10.0, 10.0, 1.0], [40.0, 12.0, 3.0], [15.0, 35.0, 6.0]]
        .map(|[x, y, w]| [x * w, y * w, w]);
    let r: Tri = [[30.0, 20.0, 6.0], [55.0, 20.0, 1.0], [20.0, 50.0, 2.0]]
        .map(|[x, y, w]| [x * w, y * w, w]);
    let setup = MovingTriangle::new(q, r).setup();
    let mut worst_fit: f64 = 0.0;
    for (x, y) in [(20.5, 15.5), (25.5, 20.5), (30.5, 25.5), (22.5, 30.5)] {
        let s = setup.sample(x, y);
        let cov = s.coverage();
        assert!(!cov.is_empty());
        for sp in cov.iter() {
            let fit = s.linear_depth(*sp);
            let mut dense: f64 = 0.0;
            for i in 0..=2000 {
                let t = sp.t0 + sp.len() * f64::from(i) / 2000.0;
                let (want, _) = ref_depth(&q, &r, q.map(|v| v[2]), r.map(|v| v[2]), x, y, t);
                let got = s.depth_at(t);
                assert!(
                    ((got - want) / want).abs() < 1e-12,
                    "t {t}: {got} vs {want}"
                );
                dense = dense.max((got - fit.eval(t)).abs());
            }
            assert!(fit.max_error >= dense * (1.0 - 1e-9));
            assert!(fit.max_error <= dense * (1.0 + 1e-4) + 1e-15);
            worst_fit = worst_fit.max(fit.max_error);
        }
    }
    // Strong perspective change (w from 1 to 6) makes the fit visibly inexact.
    assert!(worst_fit > 1e-3);
    eprintln!("linear depth fit: worst max error {worst_fit:.4} (depth units, w in [1, 6])");
}

/// Non-finite input gives an invalid setup with empty coverage, never NaN.
#[test]
fn non_finite_input_is_empty() {
    let mut q: Tri = [[0.0, 0.0, 1.0], [10.0, 0.0, 1.0], [0.0, 10.0, 1.0]];
    let r = q;
    q[1][0] = f64::NAN;
    let setup = MovingTriangle::new(q, r).setup();
    assert!(!setup.is_valid());
    assert!(setup.coverage(1.0, 1.0).is_empty());
    assert!(!setup.inside_at(1.0, 1.0, 0.5));
    assert_eq!(setup.depth_at(1.0, 1.0, 0.5), 0.0);
    let ok = MovingTriangle::new(r, r).setup();
    assert!(ok.coverage(f64::INFINITY, 1.0).is_empty());
    // Overflowing products in f32: invalid, empty.
    let big = [[3e38_f32, 3e38, 1.0], [-3e38, 3e38, 1.0], [0.0, -3e38, 1.0]];
    let s = MovingTriangle::new(big, big).setup();
    assert!(!s.is_valid() && s.coverage(0.0, 0.0).is_empty());
}

/// Value stability: exact spans and depth of a fixed moving triangle (bit patterns pinned).
#[test]
fn value_stability_pinned_outputs() {
    let q: Tri = [[4.0, 4.0, 1.0], [-7.0, 8.0, 1.0], [7.0, -8.0, 1.0]];
    let r: Tri = [[6.0, -8.0, 1.0], [4.0, 6.0, 1.0], [-7.0, 4.0, 1.0]];
    let s = MovingTriangle::new(q, r).setup().sample(4.5, -0.5);
    let cov = s.coverage();
    let bits: Vec<(u64, u64)> = cov
        .iter()
        .map(|sp| (sp.t0.to_bits(), sp.t1.to_bits()))
        .collect();
    assert_eq!(
        bits,
        PINNED_SPANS.to_vec(),
        "spans changed: {:?}",
        cov.iter().map(|s| (s.t0, s.t1)).collect::<Vec<_>>()
    );
    let c32 = MovingTriangle::new(narrow(q), narrow(r))
        .setup()
        .coverage(4.5_f32, -0.5);
    let bits32: Vec<(u32, u32)> = c32
        .iter()
        .map(|sp| (sp.t0.to_bits(), sp.t1.to_bits()))
        .collect();
    assert_eq!(bits32, PINNED_SPANS_F32.to_vec(), "{:?}", &c32[..]);
}

const PINNED_SPANS: [(u64, u64); 3] = [
    (0, 4594498045847661025),
    (4600013806394084112, 4600925953940808041),
    (4606475554671939404, 4607182418800017408),
];
const PINNED_SPANS_F32: [(u32, u32); 3] = [
    (0, 1041726730),
    (1052000635, 1053699642),
    (1064036579, 1065353216),
];
