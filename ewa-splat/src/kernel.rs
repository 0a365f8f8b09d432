//! The 3D spatio-temporal reconstruction kernel (Heinzle 2010, §4.1, Eq. 12-14), the ray to
//! parameter space mapping and integration line (Eq. 15-17) and the cylinder cut-off (Eq. 21).

use glam::{DMat3, DVec3};

/// Parameters of kernel construction (Heinzle 2010, §4 and §5.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KernelParams {
    /// Variance scale δ of Eq. 12: the Gaussian is `exp(-δ |x|²)` in parameter space and is
    /// cut off at parameter radius 1 (value `exp(-δ)`).
    pub delta: f64,
    /// α of `a3 = (α/2) m`: 1 makes the cut-off planes z = ±1 coincide with the subframe's
    /// start and end; larger values overlap neighbouring subframes.
    pub alpha: f64,
    /// Minimum length of a3 relative to the longer tangent axis (static splats, §5.2).
    pub min_a3_rel: f64,
    /// Minimum angle (radians) between a3 and the a1-a2 plane (tangential motion, §5.2).
    /// The added normal component tilts the swept volume, so oblique rays see the splat
    /// displaced by up to `tan(min_angle) |a3| tan(ray angle)`; the default 0.1° keeps that
    /// below 1e-3 of the motion while T stays well-conditioned in f64.
    pub min_angle: f64,
    /// Screen-space low-pass: each tangent axis is enlarged so that its projection is at
    /// least this many pixels (§4.1, §5.2), but to no more than the world length of this
    /// many pixels (an axis seen end-on is not stretched along the view ray, see
    /// [`low_pass`]).
    pub low_pass_radius: f64,
}

impl Default for KernelParams {
    fn default() -> Self {
        Self {
            delta: 2.0,
            alpha: 1.0,
            min_a3_rel: 1e-3,
            min_angle: 0.1f64.to_radians(),
            low_pass_radius: 1.0,
        }
    }
}

/// One ellipsoidal kernel: `T = [a1 a2 a3 c]` (Eq. 13) with the time mapping of its z axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kernel {
    /// Centre c (object/world space) at the kernel's mid time.
    pub centre: DVec3,
    /// The axes a1, a2 (tangent, after the low-pass) and a3 (temporal, after the safeguards).
    pub axes: [DVec3; 3],
    /// `T⁻¹` restricted to the linear part: world offsets to parameter space.
    pub inv: DMat3,
    /// Exposure time of parameter z = 0.
    pub time_mid: f64,
    /// Exposure time per unit z: time(z) = time_mid + z · time_half.
    pub time_half: f64,
}

/// A pixel ray in parameter space as the integration line `l(z) = b + z f` (Eq. 16-17),
/// z being the kernel's temporal coordinate, and its depth `s(z) = s0 + z ds_dz` along the
/// world ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayLine {
    /// Support point at z = 0 (its z component is 0).
    pub b: DVec3,
    /// Direction per unit z (its z component is 1).
    pub f: DVec3,
    /// Ray parameter (depth) at z = 0.
    pub s0: f64,
    /// Ray parameter per unit z.
    pub ds_dz: f64,
}

impl RayLine {
    /// Depth along the world ray at parameter time z.
    pub fn depth(&self, z: f64) -> f64 {
        self.s0 + z * self.ds_dz
    }
}

impl Kernel {
    /// Builds the kernel of a splat with tangent axes `a1`, `a2` and raw temporal axis
    /// `a3 = (α/2) m` (Heinzle 2010, §4 and Eq. 13), enforcing a minimum length of a3 and a
    /// minimum angle between a3 and the a1-a2 plane (§5.2). `None` when a1 and a2 are
    /// (nearly) parallel or anything is non-finite.
    pub fn new(
        centre: DVec3,
        a1: DVec3,
        a2: DVec3,
        a3: DVec3,
        time_mid: f64,
        time_half: f64,
        params: &KernelParams,
    ) -> Option<Self> {
        if !(centre.is_finite() && a1.is_finite() && a2.is_finite() && a3.is_finite()) {
            return None;
        }
        let a3 = safeguard_a3(a1, a2, a3, params)?;
        let t = DMat3::from_cols(a1, a2, a3);
        let det = t.determinant();
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let inv = t.inverse();
        if !inv.is_finite() {
            return None;
        }
        Some(Self {
            centre,
            axes: [a1, a2, a3],
            inv,
            time_mid,
            time_half,
        })
    }

    /// Transforms the ray `o + s d` into parameter space and re-parametrises it by the
    /// kernel's time z (Eq. 15-17). `None` when the ray keeps a constant z (it lies parallel
    /// to the a1-a2 plane at a fixed time: a set of measure zero in time, weight 0), or when
    /// the line's parameters overflow (a direction so short, subnormal say, that ray depth
    /// per unit of z is infinite).
    pub fn ray_line(&self, o: DVec3, d: DVec3) -> Option<RayLine> {
        let p = self.inv * (o - self.centre);
        let dd = self.inv * d;
        if dd.z == 0.0 || !dd.z.is_finite() {
            return None;
        }
        let f = dd / dd.z;
        let b = p - dd * (p.z / dd.z);
        let line = RayLine {
            b: DVec3::new(b.x, b.y, 0.0),
            f: DVec3::new(f.x, f.y, 1.0),
            s0: -p.z / dd.z,
            ds_dz: 1.0 / dd.z,
        };
        let ok = line.b.is_finite()
            && line.f.is_finite()
            && line.s0.is_finite()
            && line.ds_dz.is_finite();
        ok.then_some(line)
    }

    /// The z interval in which the line lies inside the bounding cylinder (Eq. 21 and the
    /// cut-off planes z = ±1), restricted to depths `s >= 0` (in front of the ray origin).
    pub fn cylinder_span(line: &RayLine) -> Option<(f64, f64)> {
        let (b, f) = (line.b, line.f);
        let a = f.x * f.x + f.y * f.y;
        let bq = b.x * f.x + b.y * f.y;
        let c = b.x * b.x + b.y * b.y - 1.0;
        let (mut lo, mut hi) = (-1.0f64, 1.0f64);
        if a == 0.0 {
            if c > 0.0 {
                return None;
            }
        } else {
            let disc = bq * bq - a * c;
            if disc.is_nan() || disc < 0.0 {
                return None;
            }
            let q = -(bq + bq.signum() * disc.sqrt());
            let (r0, r1) = if q == 0.0 {
                (-bq / a, -bq / a)
            } else {
                (q / a, c / q)
            };
            lo = lo.max(r0.min(r1));
            hi = hi.min(r0.max(r1));
        }
        // s(z) = s0 + z ds_dz >= 0
        let z0 = -line.s0 / line.ds_dz;
        if line.ds_dz > 0.0 {
            lo = lo.max(z0);
        } else {
            hi = hi.min(z0);
        }
        (lo < hi).then_some((lo, hi))
    }

    /// Exposure time of parameter time z.
    pub fn time(&self, z: f64) -> f64 {
        self.time_mid + z * self.time_half
    }

    /// Parameter time z of exposure time t.
    pub fn z_of_time(&self, t: f64) -> f64 {
        (t - self.time_mid) / self.time_half
    }
}

/// Minimum length and minimum angle to the a1-a2 plane for the temporal axis (§5.2).
fn safeguard_a3(a1: DVec3, a2: DVec3, a3: DVec3, p: &KernelParams) -> Option<DVec3> {
    let n = a1.cross(a2);
    let rmax = a1.length().max(a2.length());
    let nl = n.length();
    if nl.is_nan() || nl <= 1e-12 * rmax * rmax {
        return None;
    }
    let nh = n / nl;
    let an = a3.dot(nh);
    let ap = a3 - nh * an;
    let need = an
        .abs()
        .max(ap.length() * p.min_angle.clamp(0.0, 1.5).tan());
    let sign = if an < 0.0 { -1.0 } else { 1.0 };
    let mut out = ap + nh * (sign * need);
    let min_len = p.min_a3_rel.max(1e-9) * rmax;
    let len = out.length();
    if len < min_len {
        out = if len > 0.0 {
            out * (min_len / len)
        } else {
            nh * min_len
        };
    }
    out.is_finite().then_some(out)
}

/// Screen-space low-pass (§4.1, §5.2): enlarges a tangent axis so that its projection with
/// the screen Jacobian `jac` is at least `radius` pixels.
///
/// The enlargement is capped at the world length of `radius` pixels at that point
/// (`radius / σ_min`, σ_min the smaller singular value of `jac`), or the axis's own length if
/// that is longer. Without the cap an axis seen nearly end-on (along the view ray, a splat
/// seen edge-on) has a projection near 0 and would be stretched by `radius / projection`
/// along the ray — by orders of magnitude; seen from any other point (the ends of the
/// motion, or an off-centre pixel under perspective) that needle projects to a long radial
/// streak. With the cap such an axis stays at most `radius` pixels long in world terms, so
/// its projection is at most about `radius` pixels from every viewpoint; the edge-on splat
/// keeps a footprint thinner than the filter across that axis (its other axis is still
/// low-passed).
pub fn low_pass(axis: DVec3, jac: [DVec3; 2], radius: f64) -> DVec3 {
    let l = (jac[0].dot(axis).powi(2) + jac[1].dot(axis).powi(2)).sqrt();
    if !(l < radius && l.is_finite() && radius.is_finite()) {
        return axis;
    }
    // σ_min² = the smaller eigenvalue of the 2x2 Gram matrix J Jᵀ.
    let (g11, g12, g22) = (
        jac[0].length_squared(),
        jac[0].dot(jac[1]),
        jac[1].length_squared(),
    );
    let half_tr = 0.5 * (g11 + g22);
    let det = g11 * g22 - g12 * g12;
    let sig2 = det / (half_tr + (half_tr * half_tr - det).max(0.0).sqrt());
    let len = axis.length();
    if !(sig2 > 0.0 && sig2.is_finite() && len > 0.0 && len.is_finite()) {
        return axis;
    }
    let cap = (radius / sig2.sqrt()).max(len);
    let scale = if l > 0.0 { radius / l } else { f64::INFINITY };
    let scale = scale.min(cap / len);
    let out = axis * scale;
    if out.is_finite() { out } else { axis }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn static_splat_gets_normal_a3() {
        let p = KernelParams::default();
        let a3 = safeguard_a3(DVec3::X, DVec3::Y, DVec3::ZERO, &p).unwrap();
        assert!((a3 - DVec3::Z * 1e-3).length() < 1e-15);
    }

    #[test]
    fn tangential_motion_gets_min_angle() {
        let p = KernelParams::default();
        let a3 = safeguard_a3(DVec3::X, DVec3::Y, DVec3::X * 2.0, &p).unwrap();
        let angle = (a3.z / a3.length()).asin();
        assert!((angle - p.min_angle).abs() < 1e-12);
        assert_eq!(a3.x, 2.0);
    }

    #[test]
    fn low_pass_enlarges_a_short_axis_to_the_radius() {
        // 10 px per world unit in x and y: an axis of 0.05 projects to 0.5 px.
        let jac = [DVec3::X * 10.0, DVec3::Y * 10.0];
        let a = low_pass(DVec3::X * 0.05, jac, 1.0);
        assert!((a - DVec3::X * 0.1).length() < 1e-15);
        assert_eq!(low_pass(DVec3::X * 0.5, jac, 1.0), DVec3::X * 0.5);
    }

    #[test]
    fn low_pass_does_not_stretch_an_axis_along_the_view_ray() {
        // An axis almost along the view direction (z) projects to ~1e-9 px: it is enlarged
        // to at most the world length of one pixel (0.1), not by 1e9.
        let jac = [DVec3::X * 10.0, DVec3::Y * 10.0];
        let a = low_pass(DVec3::new(1e-10, 0.0, 0.05), jac, 1.0);
        assert!((a.length() - 0.1).abs() < 1e-12, "{a}");
        // Exactly along it: the same cap instead of an infinite factor.
        let a = low_pass(DVec3::Z * 0.05, jac, 1.0);
        assert!((a - DVec3::Z * 0.1).length() < 1e-15, "{a}");
        // Already longer than the cap: unchanged.
        assert_eq!(low_pass(DVec3::Z * 0.5, jac, 1.0), DVec3::Z * 0.5);
    }
}
