//! Property tests: the closed-form line integral against adaptive quadrature and the
//! analytic Gaussian mass, f32 against f64, no NaN for any finite input, the screen bounds
//! against dense sampling and a generic convex hull.

mod common;

use common::line_integral_quad;
use ewa_splat::{
    Aabb2, Camera, ErfMethod, RenderSettings, Splat, SplatKey, Visibility, ellipse_aabb,
    line_integral, line_integral_f32, line_integral_with, octagon, polygon_contains, render,
};
use glam::{DMat4, DVec2, DVec3, DVec4, Vec3};
use proptest::prelude::*;

fn vec3(r: f64) -> impl Strategy<Value = DVec3> {
    (-r..r, -r..r, -r..r).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// f with a magnitude spread over 10^-9 .. 10^1 (near-static kernels included).
fn direction() -> impl Strategy<Value = DVec3> {
    (vec3(1.0), -9.0f64..1.0).prop_filter_map("zero", |(v, e)| {
        v.try_normalize().map(|u| u * 10f64.powf(e))
    })
}

/// The line parameter at which the erf argument equals x.
fn t_of_x(b: DVec3, f: DVec3, delta: f64, x: f64) -> f64 {
    let fl = f.length();
    (x / delta.sqrt() - b.dot(f / fl)) / fl
}

fn check_rel(b: DVec3, f: DVec3, delta: f64, ta: f64, tb: f64) -> Result<(), TestCaseError> {
    let got = line_integral(b, f, delta, ta, tb);
    let want = line_integral_quad(b, f, delta, ta, tb);
    if want.abs() > 1e-280 {
        let rel = ((got - want) / want).abs();
        prop_assert!(
            rel <= 1e-6,
            "b={b:?} f={f:?} δ={delta} [{ta}, {tb}]: {got} vs {want} (rel {rel:e})"
        );
    } else {
        prop_assert!(got.abs() <= 1e-270, "{got} vs {want}");
    }
    Ok(())
}

proptest! {
    #[test]
    fn matches_quadrature_on_random_lines(
        b in vec3(2.0), f in direction(), le in -2.0f64..2.0, ta in -3.0f64..3.0, len in 0.0f64..4.0,
    ) {
        let delta = 10f64.powf(le);
        check_rel(DVec3::new(b.x, b.y, 0.0), f, delta, ta, ta + len)?;
    }

    #[test]
    fn matches_quadrature_in_the_erf_tails(
        b in vec3(1.0), f in direction(), le in -2.0f64..2.0, xa in -27.0f64..27.0, dx in -8.0f64..8.0,
    ) {
        let delta = 10f64.powf(le);
        let ta = t_of_x(b, f, delta, xa);
        let tb = t_of_x(b, f, delta, xa + dx);
        // Stay where the integrand is a normal float so the quadrature itself is exact.
        let q = |t: f64| delta * (b + t * f).length_squared();
        prop_assume!(q(ta).min(q(tb)) < 700.0);
        check_rel(b, f, delta, ta, tb)?;
    }

    #[test]
    fn short_intervals_match_quadrature(
        b in vec3(2.0), f in direction(), le in -2.0f64..2.0, t in -2.0f64..2.0, ulps in 1u64..1_000_000,
    ) {
        let delta = 10f64.powf(le);
        let tb = f64::from_bits(t.to_bits() + ulps);
        check_rel(b, f, delta, t, tb)?;
    }

    #[test]
    fn whole_line_equals_gaussian_mass(b in vec3(2.0), f in direction(), le in -2.0f64..2.0) {
        let delta = 10f64.powf(le);
        let b = b - f * (b.dot(f) / f.dot(f)) * 0.5; // any support point on the line
        let ff = f.dot(f);
        let perp2 = b.cross(f).length_squared() / ff;
        let want = (std::f64::consts::PI / (delta * ff)).sqrt() * (-delta * perp2).exp();
        let got = line_integral(b, f, delta, -1e300, 1e300);
        prop_assume!(want > 1e-280);
        prop_assert!(((got - want) / want).abs() <= 1e-12 * (1.0 + delta * perp2), "{got} vs {want}");
    }

    #[test]
    fn f32_path_tracks_f64(b in vec3(1.0), f in vec3(3.0), le in -1.0f64..1.0, ta in -1.0f64..1.0, len in 0.0f64..2.0) {
        let delta = 10f64.powf(le) as f32;
        let (bf, ff) = (b.as_vec3(), f.as_vec3());
        let (ta, tb) = (ta as f32, (ta + len) as f32);
        let got = line_integral_f32(Vec3::new(bf.x, bf.y, 0.0), ff, delta, ta, tb) as f64;
        let want = line_integral(DVec3::new(bf.x as f64, bf.y as f64, 0.0), ff.as_dvec3(), delta as f64, ta as f64, tb as f64);
        if want > 1e-30 {
            prop_assert!(((got - want) / want).abs() <= 2e-4, "{got} vs {want}");
        }
    }

    #[test]
    fn polynomial_erf_is_1e6_accurate(b in vec3(1.0), f in direction(), le in -1.0f64..1.0, ta in -2.0f64..2.0, len in 0.0f64..3.0) {
        let delta = 10f64.powf(le);
        let b = DVec3::new(b.x, b.y, 0.0);
        let got = line_integral_with(ErfMethod::Polynomial, b.to_array(), f.to_array(), delta, ta, ta + len);
        let want = line_integral_quad(b, f, delta, ta, ta + len);
        if want > 1e-280 {
            prop_assert!(((got - want) / want).abs() <= 1e-6, "{got} vs {want}");
        }
    }

    #[test]
    fn no_nan_or_infinity_for_any_finite_input(
        v in proptest::array::uniform9(proptest::num::f64::NORMAL | proptest::num::f64::SUBNORMAL | proptest::num::f64::ZERO),
        m in 0usize..3,
    ) {
        let method = [ErfMethod::Full, ErfMethod::Polynomial, ErfMethod::Table][m];
        let b = [v[0], v[1], v[2]];
        let f = [v[3], v[4], v[5]];
        let r = line_integral_with(method, b, f, v[6].abs(), v[7], v[8]);
        prop_assert!(r.is_finite(), "{v:?} -> {r}");
        let r32 = line_integral_with(method, b.map(|x| x as f32), f.map(|x| x as f32), v[6].abs() as f32, v[7] as f32, v[8] as f32);
        prop_assert!(r32.is_finite(), "{v:?} -> {r32}");
        if v[7] <= v[8] { prop_assert!(r >= 0.0); }
    }

    #[test]
    fn render_never_produces_nan(
        seeds in proptest::collection::vec((vec3(4.0), vec3(6.0), vec3(1.0), -3.0f64..1.0, 0.0f32..1.0), 1..4),
        sub in 1u32..3, approx in any::<bool>(),
    ) {
        let cam = Camera::look_at_perspective(DVec3::new(0.0, 0.0, 3.0), DVec3::ZERO, DVec3::Y, 1.0, 0.1, 50.0, 8, 6);
        let splats: Vec<Splat> = seeds.iter().map(|(c, m, n, lr, a)| {
            Splat::moving_disc(*c, *m, *n, 10f64.powf(*lr), [0.3, 0.6, 0.9, *a])
        }).collect();
        let settings = RenderSettings {
            subframes: sub,
            visibility: if approx { Visibility::Approximate } else { Visibility::ABuffer },
            ..RenderSettings::default()
        };
        let frame = render(&cam, &splats, [0.1, 0.2, 0.3, 1.0], &settings).unwrap();
        for p in &frame.pixels {
            prop_assert!(p.iter().all(|c| c.is_finite() && *c >= 0.0 && *c <= 1.0 + 1e-5), "{p:?}");
        }
    }

    #[test]
    fn ellipse_box_is_tight_and_contains_dense_samples(c in vec3(2.0), a in vec3(1.0), b in vec3(1.0)) {
        let cam = Camera::look_at_perspective(DVec3::new(0.0, 0.0, 6.0), DVec3::ZERO, DVec3::Y, 0.9, 0.1, 50.0, 64, 48);
        let screen = screen_matrix(&cam);
        let Some(bx) = ellipse_aabb(&screen, c, a, b) else { return Ok(()) };
        let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        for k in 0..4096 {
            let th = k as f64 / 4096.0 * std::f64::consts::TAU;
            let p = screen * (c + th.cos() * a + th.sin() * b).extend(1.0);
            let s = DVec2::new(p.x / p.w, p.y / p.w);
            lo = lo.min(s);
            hi = hi.max(s);
        }
        let scale = (bx.max - bx.min).length().max(1.0);
        prop_assert!(lo.x >= bx.min.x - 1e-9 * scale && lo.y >= bx.min.y - 1e-9 * scale);
        prop_assert!(hi.x <= bx.max.x + 1e-9 * scale && hi.y <= bx.max.y + 1e-9 * scale);
        // tight: the sampled extremes come within the sampling resolution of the box
        prop_assert!((lo - bx.min).abs().max_element() <= 1e-3 * scale);
        prop_assert!((hi - bx.max).abs().max_element() <= 1e-3 * scale);
    }

    #[test]
    fn octagon_is_the_convex_hull_of_two_boxes(
        p0 in (-10.0f64..10.0, -10.0f64..10.0), ps in (0.0f64..8.0, 0.0f64..8.0),
        q0 in (-10.0f64..10.0, -10.0f64..10.0), qs in (0.0f64..8.0, 0.0f64..8.0),
    ) {
        let p = Aabb2 { min: DVec2::new(p0.0, p0.1), max: DVec2::new(p0.0 + ps.0, p0.1 + ps.1) };
        let q = Aabb2 { min: DVec2::new(q0.0, q0.1), max: DVec2::new(q0.0 + qs.0, q0.1 + qs.1) };
        let oct = octagon(&p, &q);
        let corners: Vec<DVec2> = [p, q].iter().flat_map(|b| [
            b.min, DVec2::new(b.max.x, b.min.y), b.max, DVec2::new(b.min.x, b.max.y)]).collect();
        for c in &corners {
            prop_assert!(polygon_contains(&oct, *c), "{c:?} outside {oct:?}");
        }
        for v in &oct {
            prop_assert!(corners.contains(v));
        }
        let hull = monotone_chain(&corners);
        prop_assert!((area(&oct) - area(&hull)).abs() <= 1e-9 * (1.0 + area(&hull)), "{oct:?} vs {hull:?}");
    }
}

fn screen_matrix(cam: &Camera) -> DMat4 {
    let (w, h) = (cam.width as f64, cam.height as f64);
    let vp = DMat4::from_cols(
        DVec4::new(w / 2.0, 0.0, 0.0, 0.0),
        DVec4::new(0.0, -h / 2.0, 0.0, 0.0),
        DVec4::new(0.0, 0.0, 1.0, 0.0),
        DVec4::new(w / 2.0, h / 2.0, 0.0, 1.0),
    );
    vp * cam.view_proj
}

fn area(poly: &[DVec2]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| poly[i].perp_dot(poly[(i + 1) % n]))
        .sum::<f64>()
        * 0.5
}

/// Andrew's monotone chain convex hull (counter-clockwise, y up).
fn monotone_chain(pts: &[DVec2]) -> Vec<DVec2> {
    let mut p = pts.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut hull: Vec<DVec2> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &DVec2>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &pt in iter {
            while hull.len() >= start + 2 {
                let a = hull[hull.len() - 2];
                let b = hull[hull.len() - 1];
                if (b - a).perp_dot(pt - a) <= 0.0 {
                    hull.pop();
                } else {
                    break;
                }
            }
            hull.push(pt);
        }
        hull.pop();
    }
    hull
}

#[test]
fn splat_key_interpolates_paths() {
    let k = |x: f64| SplatKey::disc(DVec3::new(x, 0.0, 0.0), DVec3::Z, 1.0);
    let s = Splat {
        keys: vec![k(0.0), k(1.0), k(3.0)],
        colour: [1.0; 4],
        span: [0.0, 1.0],
    };
    assert_eq!(s.key_at(0.75).unwrap().centre.x, 2.0);
    assert_eq!(s.key_at(2.0).unwrap().centre.x, 3.0);
}
