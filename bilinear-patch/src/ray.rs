//! A ray prepared for watertight intersection: translation, axis permutation and shear that
//! map it onto the +z axis (Woop, Benthin and Wald 2013).

use num_traits::Float;

/// A ray `origin + t * dir` transformed so that it runs along +z from the origin.
///
/// Every face tested against the same `Ray` sees the same transformed vertices, so decisions
/// about a shared edge are made from identical numbers (Woop et al. 2013). The permutation
/// puts the largest component of `dir` on z; the shear `(sx, sy, sz)` then maps
/// `origin + t * dir` to `(0, 0, t)`, so the third ray-space coordinate of a point on the ray
/// is its ray parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray<F> {
    pub(crate) origin: [F; 3],
    /// Permutation (kx, ky, kz) of the axes.
    pub(crate) k: [usize; 3],
    /// Shear (sx, sy, sz).
    pub(crate) s: [F; 3],
    /// The origin with its axes permuted, (o\[kx\], o\[ky\], o\[kz\]): read by every face test,
    /// so permuted once here.
    pub(crate) origin_k: [F; 3],
}

impl<F: Float> Ray<F> {
    /// Prepares the ray `origin + t * dir`. Returns `None` when a component is not finite or
    /// `dir` is zero (Woop et al. 2013: kz is the dimension of largest |dir|).
    pub fn new(origin: [F; 3], dir: [F; 3]) -> Option<Self> {
        // Independent tests (no serial chain through the six components).
        let finite = |p: [F; 3]| p[0].is_finite() & p[1].is_finite() & p[2].is_finite();
        if !(finite(origin) & finite(dir)) {
            return None;
        }
        let (ax, ay, az) = (dir[0].abs(), dir[1].abs(), dir[2].abs());
        let (kx, ky, kz, dx, dy, dz) = if ax >= ay && ax >= az {
            (1usize, 2usize, 0usize, dir[1], dir[2], dir[0])
        } else if ay >= az {
            (2, 0, 1, dir[2], dir[0], dir[1])
        } else {
            (0, 1, 2, dir[0], dir[1], dir[2])
        };
        if dz == F::zero() {
            return None;
        }
        // Keep the winding of projected faces (Woop et al. 2013: swap kx and ky).
        let (kx, ky, dx, dy) = if dz < F::zero() {
            (ky, kx, dy, dx)
        } else {
            (kx, ky, dx, dy)
        };
        let sz = dz.recip();
        let (sx, sy) = (dx * sz, dy * sz);
        if !(sx.is_finite() & sy.is_finite() & sz.is_finite()) {
            return None;
        }
        Some(Ray {
            origin,
            k: [kx, ky, kz],
            s: [sx, sy, sz],
            origin_k: [origin[kx], origin[ky], origin[kz]],
        })
    }

    /// The ray origin.
    pub fn origin(&self) -> [F; 3] {
        self.origin
    }

    /// Maps a world point into ray space: `(x', y')` is its offset from the ray, `z'` its ray
    /// parameter when it lies on the ray.
    #[inline]
    pub(crate) fn transform(&self, p: [F; 3]) -> [F; 3] {
        // k < 3 always; `& 3` into four entries lets the compiler drop the bounds checks.
        let [kx, ky, kz] = self.k;
        let [ox, oy, oz] = self.origin_k;
        let p = [p[0], p[1], p[2], F::zero()];
        let az = p[kz & 3] - oz;
        [
            (p[kx & 3] - ox) - self.s[0] * az,
            (p[ky & 3] - oy) - self.s[1] * az,
            self.s[2] * az,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_on_the_ray_map_to_the_z_axis() {
        let o = [1.0f64, -2.0, 0.5];
        for d in [
            [0.3, -0.2, 1.0],
            [-1.0, 0.1, 0.2],
            [0.0, -3.0, 1.0],
            [0.5, 0.5, -0.5],
        ] {
            let ray = Ray::new(o, d).expect("valid ray");
            for t in [-1.0, 0.0, 0.25, 2.0] {
                let p = [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]];
                let q = ray.transform(p);
                assert!(q[0].abs() < 1e-12 && q[1].abs() < 1e-12, "{q:?}");
                assert!((q[2] - t).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn rejects_zero_and_non_finite_directions() {
        assert!(Ray::new([0.0f32; 3], [0.0; 3]).is_none());
        assert!(Ray::new([0.0f32; 3], [f32::NAN, 0.0, 1.0]).is_none());
        assert!(Ray::new([f32::INFINITY, 0.0, 0.0], [0.0, 0.0, 1.0]).is_none());
    }
}
