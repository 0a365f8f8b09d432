//! The three erf evaluations against mpmath values (tests/data/erf_reference.csv, made by
//! tools/gen_erf_reference.py at 60 digits).

use ewa_splat::ErfMethod;
use ewa_splat::erf::{erf, erfc, erfcx_pos};

fn table() -> Vec<[f64; 4]> {
    include_str!("data/erf_reference.csv")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|s| s.parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3]]
        })
        .collect()
}

fn rel(a: f64, b: f64) -> f64 {
    if a == b { 0.0 } else { ((a - b) / b).abs() }
}

#[test]
fn reference_table_is_complete() {
    let t = table();
    assert!(t.len() > 1200);
    assert!(t.iter().any(|r| r[0] == 30.0) && t.iter().any(|r| r[0] == -26.0));
}

#[test]
fn full_erf_within_a_few_ulp() {
    for [x, e, _, _] in table() {
        let got = erf(ErfMethod::Full, x);
        assert!(
            rel(got, e) <= 4.0 * f64::EPSILON,
            "erf({x}) = {got}, want {e}"
        );
    }
}

#[test]
fn full_erfc_within_a_few_ulp_where_normal() {
    for [x, _, e, _] in table() {
        if e < f64::MIN_POSITIVE {
            continue;
        }
        let got = erfc(ErfMethod::Full, x);
        assert!(
            rel(got, e) <= 8.0 * f64::EPSILON,
            "erfc({x}) = {got}, want {e}"
        );
    }
}

#[test]
fn full_erfcx_relative_1e13_for_every_positive_argument() {
    for [x, _, _, e] in table() {
        if x < 0.0 {
            continue;
        }
        let got = erfcx_pos(ErfMethod::Full, x);
        // exp(x²) amplifies the rounding of x² by x² (about 700 eps at x = 26).
        let tol = 8.0 * f64::EPSILON * (1.0 + x * x);
        assert!(
            rel(got, e) <= tol.max(1e-15),
            "erfcx({x}) = {got}, want {e}"
        );
    }
}

#[test]
fn polynomial_relative_1_2e7_in_erfc_and_absolute_in_erf() {
    for [x, e, ec, ex] in table() {
        let got = erf(ErfMethod::Polynomial, x);
        assert!((got - e).abs() <= 1.3e-7, "erf({x}) = {got}, want {e}");
        if x.abs() < 0.5 {
            assert!(
                rel(got, e) <= 1e-8,
                "small-argument erf({x}) = {got}, want {e}"
            );
        }
        if x >= 0.0 {
            assert!(
                rel(erfcx_pos(ErfMethod::Polynomial, x), ex) <= 1.3e-7,
                "erfcx({x})"
            );
            if ec >= f64::MIN_POSITIVE {
                assert!(
                    rel(erfc(ErfMethod::Polynomial, x), ec) <= 1.3e-7 * (1.0 + 1e-13 * x * x),
                    "erfc({x})"
                );
            }
        }
    }
}

#[test]
fn table_absolute_3e5() {
    let mut worst = 0.0f64;
    for [x, e, _, _] in table() {
        let got = erf(ErfMethod::Table, x);
        worst = worst.max((got - e).abs());
    }
    assert!(worst <= 3.5e-5, "table erf error {worst}");
    // and it is a real interpolation error, not zero
    assert!(worst > 1e-6);
}
