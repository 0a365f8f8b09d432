//! The approximate visibility of the paper's GPU implementation (Heinzle 2010, §5.1-§5.5),
//! kept so its error can be measured against the A-buffer.
//!
//! Per subframe: passes 1-2 build depth buffers of the splat ellipses at the subframe's start
//! and end; a kernel fragment survives if its nearest depth passes either buffer (within
//! the depth tolerance); passes 3-4 record the earliest and latest time any surviving kernel
//! covers the pixel (t_min, t_max); pass 5 blends every surviving kernel with the weight of
//! its whole integration period; pass 6 normalises by the weight sum and blends with the
//! background by the shutter integral over [t_min, t_max]. Subframes are accumulated with
//! the shutter integral over each subframe (§5.5).

use crate::erf::ErfMethod;
use crate::fragment::Fragment;
use crate::shutter::Shutter;

/// Per-pixel buffers of one subframe (passes 1-4).
pub(crate) struct Passes {
    pub depth_start: Vec<f64>,
    pub depth_end: Vec<f64>,
}

impl Passes {
    pub fn new(pixels: usize) -> Self {
        Self {
            depth_start: vec![f64::INFINITY; pixels],
            depth_end: vec![f64::INFINITY; pixels],
        }
    }

    pub fn reset(&mut self) {
        self.depth_start.fill(f64::INFINITY);
        self.depth_end.fill(f64::INFINITY);
    }

    /// Passes 1 and 2: the splat ellipse at the kernel's cut-off planes z = -1 (start) and
    /// z = +1 (end) writes its depth where the pixel ray hits it.
    pub fn splat_depths(&mut self, frag: &Fragment) {
        let l = &frag.line;
        let p = frag.pixel as usize;
        for (z, buf) in [(-1.0, &mut self.depth_start), (1.0, &mut self.depth_end)] {
            let (x, y) = (l.b.x + z * l.f.x, l.b.y + z * l.f.y);
            let d = l.depth(z);
            if x * x + y * y <= 1.0
                && d >= 0.0
                && let Some(slot) = buf.get_mut(p)
                && d < *slot
            {
                *slot = d;
            }
        }
    }
}

/// Passes 3-6 for the fragments of one pixel and one subframe; returns the premultiplied
/// pixel of this subframe (already blended with the background).
#[allow(clippy::too_many_arguments)]
pub(crate) fn resolve_subframe(
    frags: &[Fragment],
    depth_start: f64,
    depth_end: f64,
    sub_t0: f64,
    sub_t1: f64,
    colours: &[[f64; 4]],
    bg: [f64; 4],
    delta: f64,
    method: ErfMethod,
    shutter: Shutter,
    integrals: &mut u64,
) -> [f64; 4] {
    let mut acc = [0.0f64; 4];
    let mut wsum = 0.0;
    let (mut tmin, mut tmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for f in frags {
        let dmin = f.line.depth(f.za).min(f.line.depth(f.zb));
        let visible = dmin <= depth_start + f.eps || dmin <= depth_end + f.eps;
        if !visible {
            continue;
        }
        tmin = tmin.min(f.t_start());
        tmax = tmax.max(f.t_end());
        let wgt = f.weight(method, delta, f.t_start(), f.t_end());
        *integrals += 1;
        let c = colours.get(f.splat as usize).copied().unwrap_or([0.0; 4]);
        for k in 0..4 {
            acc[k] += wgt * c[k];
        }
        wsum += wgt;
    }
    let sub = shutter.integral(sub_t0, sub_t1);
    if tmax <= tmin || sub.is_nan() || sub <= 0.0 {
        return bg;
    }
    let cov = (shutter.integral(tmin, tmax) / sub).clamp(0.0, 1.0);
    let colour = if wsum > 0.0 {
        acc.map(|v| v / wsum)
    } else {
        [0.0; 4]
    };
    let mut out = [0.0; 4];
    for k in 0..4 {
        out[k] = cov * colour[k] + (1.0 - cov * colour[3]) * bg[k];
    }
    out
}
