//! A-buffer visibility for motion-blurred kernels (Heinzle 2010, §4.4) with normalisation by
//! the kernel weights (§5.4) and the background blend by the covered-time integral.
//!
//! The fragments of one pixel carry time intervals [t_start, t_end] and depths that are
//! linear in time along the ray. The exposure is cut at every interval end; on each piece
//! the ternary depth test runs against the nearest active fragment (at the piece's middle):
//! fragments within the depth tolerance belong to the same surface and are accumulated,
//! weighted by their line integrals over the piece and normalised; farther fragments are
//! occluded for that piece (their occluded time is removed). The pieces are summed with the
//! shutter weight (Eq. 1), and the background fills the time no surface covers.

use crate::erf::ErfMethod;
use crate::fragment::Fragment;
use crate::shutter::Shutter;

/// Reusable per-thread scratch space.
#[derive(Default)]
pub(crate) struct Scratch {
    times: Vec<f64>,
    group: Vec<usize>,
}

/// Resolves one pixel; `colours` are premultiplied RGBA per splat, `bg` premultiplied.
#[allow(clippy::too_many_arguments)]
pub(crate) fn resolve(
    frags: &[Fragment],
    colours: &[[f64; 4]],
    bg: [f64; 4],
    delta: f64,
    method: ErfMethod,
    shutter: Shutter,
    scratch: &mut Scratch,
    integrals: &mut u64,
) -> [f64; 4] {
    let total = shutter.integral(0.0, 1.0);
    let times = &mut scratch.times;
    times.clear();
    times.push(0.0);
    times.push(1.0);
    for f in frags {
        times.push(f.t_start().clamp(0.0, 1.0));
        times.push(f.t_end().clamp(0.0, 1.0));
    }
    times.sort_unstable_by(f64::total_cmp);
    times.dedup();

    let mut out = [0.0f64; 4];
    let mut covered_alpha = 0.0;
    for w in times.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        if t1 <= t0 {
            continue;
        }
        let tm = 0.5 * (t0 + t1);
        // Nearest active fragment at the middle of the piece.
        let mut front: Option<(f64, f64)> = None;
        for f in frags {
            if f.t_start() <= t0 && f.t_end() >= t1 {
                let d = f.depth_at(tm);
                if front.is_none_or(|(fd, _)| d < fd) {
                    front = Some((d, f.eps));
                }
            }
        }
        let Some((fd, feps)) = front else { continue };
        // Ternary depth test: same surface within the tolerance, occluded beyond it.
        scratch.group.clear();
        for (i, f) in frags.iter().enumerate() {
            if f.t_start() <= t0 && f.t_end() >= t1 && f.depth_at(tm) <= fd + feps.max(f.eps) {
                scratch.group.push(i);
            }
        }
        let mut acc = [0.0f64; 4];
        let mut wsum = 0.0;
        for &i in &scratch.group {
            let Some(f) = frags.get(i) else { continue };
            let wgt = f.weight(method, delta, t0, t1);
            *integrals += 1;
            let c = colours.get(f.splat as usize).copied().unwrap_or([0.0; 4]);
            for k in 0..4 {
                acc[k] += wgt * c[k];
            }
            wsum += wgt;
        }
        if wsum.is_nan() || wsum <= 0.0 {
            // All weights underflowed: fall back to the plain average of the surface.
            wsum = 0.0;
            acc = [0.0; 4];
            for &i in &scratch.group {
                let Some(f) = frags.get(i) else { continue };
                let c = colours.get(f.splat as usize).copied().unwrap_or([0.0; 4]);
                for k in 0..4 {
                    acc[k] += c[k];
                }
                wsum += 1.0;
            }
        }
        let s = shutter.integral(t0, t1);
        for k in 0..4 {
            out[k] += s * acc[k] / wsum;
        }
        covered_alpha += s * acc[3] / wsum;
    }
    let rest = (total - covered_alpha).max(0.0);
    for k in 0..4 {
        out[k] = (out[k] + rest * bg[k]) / total;
    }
    out
}
