//! Stochastic's pixel filter: the same reconstruction filter `--filter` gives accum, analytic
//! and prism ([`crate::aa::Filter`]), so every method estimates the same image.
//!
//! With [`raster_hier::Footprint::Area`] the samples are spread uniformly over their pixel
//! squares by tmsnet's nets. Each sample then adds its colour to every pixel whose filter
//! support holds it, weighted by the filter at its offset from that pixel's centre, and a
//! pixel is the weighted sum over the weights' sum (the usual filtered splatting of sample
//! renderers): with uniformly spread samples it converges to `∫ f c / ∫ f` over the support,
//! the quantity accum's filter-weighted positions converge to. The box of radius 1/2 keeps
//! each sample in its own pixel with weight 1 (the plain pixel mean, bit for bit). Wider
//! filters draw samples from neighbouring pixels, also beyond the image's border: the
//! scene is rendered into a buffer larger by the filter's reach on every side
//! ([`SampleFilter::padded`]) and only the image's own pixels are kept.

use crate::aa::{Antialiasing, Filter};
use crate::prepared::PreparedScene;

/// A filter wider than the pixel's own box, placed over an image of `width` x `height`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SampleFilter {
    filter: Filter,
    radius: f64,
    /// Pixels added on each side of the image: the filter's reach beyond the pixel square.
    pad: u32,
    width: u32,
    height: u32,
}

impl SampleFilter {
    /// The filter `filter` of radius `radius` over a `scene`-sized image, or `None` for the
    /// box of radius 1/2 (each sample in its own pixel with weight 1: no splatting).
    pub(super) fn new(filter: Filter, radius: f64, scene: &PreparedScene) -> Option<Self> {
        if filter == Filter::Box && radius == 0.5 {
            return None;
        }
        Some(SampleFilter {
            filter,
            radius,
            pad: (radius - 0.5).max(0.0).ceil() as u32,
            width: scene.width,
            height: scene.height,
        })
    }

    /// Pixels added on each side of the image.
    pub(super) fn pad(&self) -> u32 {
        self.pad
    }

    /// `scene` in a buffer grown by the filter's reach on every side: its pixel (i, j) is
    /// pixel (i - pad, j - pad) of `scene` ([`crate::aa::shifted`] by `-pad`).
    pub(super) fn padded(&self, scene: &PreparedScene) -> PreparedScene {
        let p = f64::from(self.pad);
        let mut out = crate::aa::shifted(scene, [-p, -p]);
        out.width = scene.width + 2 * self.pad;
        out.height = scene.height + 2 * self.pad;
        out
    }

    /// Calls `f(pixel, weight)` for every pixel of the image whose filter support holds a
    /// sample at `(x, y)` of the padded buffer (pixel units), with the filter's weight
    /// there; `pixel` is the row-major index in the unpadded image.
    pub(super) fn splat(&self, x: f64, y: f64, mut f: impl FnMut(usize, f64)) {
        let (r, pad) = (self.radius, f64::from(self.pad));
        // Pixel centres i + 1/2 within r of x: i in [x - 1/2 - r, x - 1/2 + r].
        let range = |v: f64, n: u32| {
            let lo = (v - 0.5 - r - pad).ceil().max(0.0) as u32;
            let hi = (v - 0.5 + r - pad).floor().min(f64::from(n) - 1.0);
            (lo, if hi < 0.0 { None } else { Some(hi as u32) })
        };
        let ((x0, x1), (y0, y1)) = (range(x, self.width), range(y, self.height));
        let (Some(x1), Some(y1)) = (x1, y1) else {
            return;
        };
        for j in y0..=y1 {
            let fy = self.filter.profile(y - pad - (f64::from(j) + 0.5), r);
            if fy == 0.0 {
                continue;
            }
            for i in x0..=x1 {
                let fx = self.filter.profile(x - pad - (f64::from(i) + 0.5), r);
                if fx > 0.0 {
                    f(j as usize * self.width as usize + i as usize, fx * fy);
                }
            }
        }
    }
}

/// The radius check of `--filter-radius` ([`Antialiasing::validate`]'s).
pub(super) fn validate(filter: Filter, radius: Option<f64>) -> crate::error::Result<f64> {
    let aa = Antialiasing {
        samples: 1,
        filter,
        radius,
    };
    aa.validate()?;
    Ok(aa.radius())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn filter(f: Filter, r: f64, w: u32, h: u32) -> SampleFilter {
        SampleFilter {
            filter: f,
            radius: r,
            pad: (r - 0.5).max(0.0).ceil() as u32,
            width: w,
            height: h,
        }
    }

    #[test]
    fn a_sample_reaches_exactly_the_pixels_whose_support_holds_it() {
        // Brute force: every pixel of the image, the distance of its centre from the sample.
        for (f, r) in [
            (Filter::Tent, 1.0),
            (Filter::Gaussian, 1.5),
            (Filter::BlackmanHarris, 2.0),
            (Filter::Box, 1.25),
        ] {
            let sf = filter(f, r, 7, 5);
            let pad = f64::from(sf.pad);
            for k in 0..400 {
                let x = f64::from(k % 20) * 0.61 - 1.3 + pad;
                let y = f64::from(k / 20) * 0.47 - 1.1 + pad;
                let mut got = Vec::new();
                sf.splat(x, y, |p, w| got.push((p, w)));
                let mut want = Vec::new();
                for j in 0..5u32 {
                    for i in 0..7u32 {
                        let dx = x - pad - (f64::from(i) + 0.5);
                        let dy = y - pad - (f64::from(j) + 0.5);
                        let w = f.profile(dx, r) * f.profile(dy, r);
                        if w > 0.0 {
                            want.push(((j * 7 + i) as usize, w));
                        }
                    }
                }
                assert_eq!(got, want, "{f} r {r} at ({x}, {y})");
            }
        }
    }
}
