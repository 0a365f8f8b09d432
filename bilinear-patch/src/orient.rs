//! Exact sign of a 2D edge function with a symbolic tie-break.
//!
//! Every inside/outside decision that two neighbouring faces must agree on (ray vs a shared
//! edge) goes through [`edge_sign`]. It returns the exact sign of `cross(a, b)`, the edge
//! function of the segment a → b evaluated at the origin of ray space, computed from the
//! transformed vertices alone, so two faces that share the edge reach the same decision
//! bit for bit (Woop, Benthin and Wald 2013). An exact zero is broken by Simulation of
//! Simplicity: the ray is treated as moved by (ε, ε²) in ray space, which gives the sign of
//! `a.y - b.y`, then of `b.x - a.x` (the top-left rule of rasterisers). The only remaining
//! zero is a degenerate edge, a == b.

use num_traits::Float;

/// 2D cross product a.x * b.y - a.y * b.x, plain floating point.
#[inline]
pub(crate) fn cross2<F: Float>(a: [F; 2], b: [F; 2]) -> F {
    a[0] * b[1] - a[1] * b[0]
}

/// `a * d - b * c` with Kahan's FMA algorithm: relative error at most 2 ulps (Jeannerod,
/// Louvet and Muller 2013), so its sign is the sign of the exact value, and it is zero only
/// when the exact value is zero (barring underflow).
#[inline]
pub(crate) fn diff_of_products<F: Float>(a: F, d: F, b: F, c: F) -> F {
    let w = b * c;
    let err = (-b).mul_add(c, w);
    let f = a.mul_add(d, -w);
    f + err
}

/// Sign of a float as -1, 0 or 1.
#[inline]
pub(crate) fn sign<F: Float>(x: F) -> i8 {
    if x > F::zero() {
        1
    } else if x < F::zero() {
        -1
    } else {
        0
    }
}

/// Edge function of the segment a → b at the ray-space origin: the plainly computed value
/// and its exact, symbolically perturbed sign (0 only when a == b).
#[inline]
pub(crate) fn edge_sign<F: Float>(a: [F; 2], b: [F; 2]) -> (F, i8) {
    let p = a[0] * b[1];
    let q = a[1] * b[0];
    let e = p - q;
    // |fl(p - q) - (a0 b1 - a1 b0)| <= eps * (|p| + |q|) (two products, one difference,
    // unit roundoff eps / 2 each); outside that band the plain sign is already exact.
    let bound = F::epsilon() * (p.abs() + q.abs());
    if e.abs() > bound {
        return (e, sign(e));
    }
    (e, exact_sign(a, b))
}

/// The slow path of [`edge_sign`]: exact sign via the FMA difference of products, then the
/// symbolic tie-break.
#[cold]
#[inline(never)]
fn exact_sign<F: Float>(a: [F; 2], b: [F; 2]) -> i8 {
    let exact = diff_of_products(a[0], b[1], a[1], b[0]);
    let s = sign(exact);
    if s != 0 {
        return s;
    }
    // Simulation of Simplicity: origin moved by (eps, eps^2).
    let s = sign(a[1] - b[1]);
    if s != 0 {
        return s;
    }
    sign(b[0] - a[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_sign_where_plain_product_cancels() {
        // a0*b1 and a1*b0 differ only below f32 precision.
        let a = [1.0f32 + f32::EPSILON, 1.0];
        let b = [1.0f32, 1.0 - f32::EPSILON / 2.0];
        // exact: (1 + e)(1 - e/2) - 1 = e/2 - e^2/2 > 0
        let exact = (1.0f64 + f32::EPSILON as f64) * (1.0 - f32::EPSILON as f64 / 2.0) - 1.0;
        assert!(exact > 0.0);
        assert_eq!(edge_sign(a, b).1, 1);
        assert_eq!(edge_sign(b, a).1, -1);
    }

    #[test]
    fn zero_broken_by_perturbation_antisymmetrically() {
        let pts = [
            [0.0f64, 1.0],
            [0.0, -2.0],
            [3.0, 0.0],
            [-1.0, 0.0],
            [2.0, 2.0],
            [-3.0, -3.0],
        ];
        for a in pts {
            for b in pts {
                if a == b {
                    assert_eq!(edge_sign(a, b).1, 0);
                    continue;
                }
                let (_, s) = edge_sign(a, b);
                let (_, r) = edge_sign(b, a);
                assert_ne!(s, 0);
                assert_eq!(s, -r, "antisymmetry for {a:?} {b:?}");
            }
        }
    }

    #[test]
    fn kahan_difference_of_products_is_exact_in_sign() {
        // 3 * 3 - 9 = 0 exactly; (1 + 2^-30)^2 - 1 * (1 + 2^-29) = 2^-60 > 0.
        assert_eq!(diff_of_products(3.0f64, 3.0, 1.0, 9.0), 0.0);
        let x = 1.0f64 + 2f64.powi(-30);
        let y = 1.0f64 + 2f64.powi(-29);
        assert_eq!(diff_of_products(x, x, 1.0, y), 2f64.powi(-60));
    }
}
