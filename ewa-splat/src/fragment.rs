//! One kernel's footprint on one pixel ray: the integration line, its visible parameter-time
//! span inside the bounding cylinder and the depth along the ray (Heinzle 2010, §4.2-§4.4).

use crate::erf::ErfMethod;
use crate::integral::line_integral_with;
use crate::kernel::{Kernel, RayLine};

/// A kernel crossing a pixel ray (an A-buffer entry of §4.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Fragment {
    /// Pixel index (row-major).
    pub pixel: u32,
    /// Index of the splat (for its colour).
    pub splat: u32,
    /// Subframe index (§5.5).
    pub subframe: u32,
    /// Integration line in parameter space.
    pub line: RayLine,
    /// Parameter-time span inside the cylinder (and the exposure), za < zb.
    pub za: f64,
    /// End of the parameter-time span.
    pub zb: f64,
    /// Exposure time of z = 0 and per unit z (time_half > 0).
    pub time_mid: f64,
    /// Exposure time per unit z.
    pub time_half: f64,
    /// Depth tolerance of the ternary depth test (world units along the ray).
    pub eps: f64,
}

impl Fragment {
    /// The fragment of `kernel` on a pixel ray (`line`, its parameter-time `span` inside the
    /// cylinder), clipped to the splat's part `exists` of the exposure (\[0, 1\] for a whole
    /// splat). `None` when nothing is left.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        pixel: u32,
        splat: u32,
        subframe: u32,
        kernel: &Kernel,
        line: RayLine,
        span: (f64, f64),
        eps: f64,
        exists: [f64; 2],
    ) -> Option<Self> {
        // Clip to the exposure t in [0, 1] and the splat's span.
        let za = span.0.max(kernel.z_of_time(exists[0].max(0.0)));
        let zb = span.1.min(kernel.z_of_time(exists[1].min(1.0)));
        (za < zb).then_some(Self {
            pixel,
            splat,
            subframe,
            line,
            za,
            zb,
            time_mid: kernel.time_mid,
            time_half: kernel.time_half,
            eps,
        })
    }

    /// Exposure time at which the fragment starts.
    pub fn t_start(&self) -> f64 {
        self.time_mid + self.za * self.time_half
    }

    /// Exposure time at which the fragment ends.
    pub fn t_end(&self) -> f64 {
        self.time_mid + self.zb * self.time_half
    }

    /// Parameter time of an exposure time.
    pub fn z_of(&self, t: f64) -> f64 {
        (t - self.time_mid) / self.time_half
    }

    /// Depth at exposure time t.
    pub fn depth_at(&self, t: f64) -> f64 {
        self.line.depth(self.z_of(t))
    }

    /// Kernel weight over the exposure times [t0, t1] (clipped to the fragment's span): the
    /// line integral of Eq. 19 in parameter time, times dt/dz so that kernels of different
    /// subframes weigh in the same measure. The Gaussian is unnormalised (1 at its centre),
    /// as in static EWA splatting with per-pixel normalisation (§5.4).
    pub fn weight(&self, method: ErfMethod, delta: f64, t0: f64, t1: f64) -> f64 {
        let z0 = self.z_of(t0).max(self.za);
        let z1 = self.z_of(t1).min(self.zb);
        if z0 >= z1 {
            return 0.0;
        }
        self.time_half
            * line_integral_with(
                method,
                self.line.b.to_array(),
                self.line.f.to_array(),
                delta,
                z0,
                z1,
            )
    }
}
