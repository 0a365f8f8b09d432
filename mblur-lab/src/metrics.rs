//! Error metrics of an image against a reference, as `mblur compare` reports them: mean
//! squared error, RMSE, PSNR and the largest absolute difference on the linear RGB values,
//! and the structural similarity index SSIM (Wang, Bovik, Sheikh and Simoncelli 2004, "Image
//! quality assessment: from error visibility to structural similarity", Eq. 13 with the
//! 11 x 11 circular-symmetric Gaussian window of σ = 1.5, K1 = 0.01, K2 = 0.03, and the mean
//! over the image, Eq. 17) on the display-encoded luma.
//!
//! All metrics are computed in f64 and return `None` when the sizes differ or the image is
//! empty (SSIM also when the image is smaller than the window). A non-finite pixel value
//! makes the result non-finite rather than silently ignored (the renderers never produce one).

use mblur::image::Image;
use mblur::texture::linear_to_srgb;

/// SSIM constant K1 (Wang et al. 2004, Eq. 7).
pub const SSIM_K1: f64 = 0.01;
/// SSIM constant K2 (Wang et al. 2004, Eq. 9).
pub const SSIM_K2: f64 = 0.03;
/// Side of the SSIM window in pixels (Wang et al. 2004, §III-C).
pub const SSIM_WINDOW: usize = 11;
/// Standard deviation of the SSIM Gaussian window in pixels (Wang et al. 2004, §III-C).
pub const SSIM_SIGMA: f64 = 1.5;

/// The errors of one image against a reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Metrics {
    /// Mean squared difference over all RGB channels (linear units).
    pub mse: f64,
    /// Root of [`Metrics::mse`].
    pub rmse: f64,
    /// Peak signal-to-noise ratio in dB for a peak of 1.0: `10 log10(1 / mse)`; `+inf`
    /// for identical images.
    pub psnr: f64,
    /// The largest absolute difference of any channel of any pixel (linear units).
    pub max_abs: f64,
    /// Mean SSIM of the luma (Wang et al. 2004, Eq. 17); `None` for images smaller than the
    /// 11 x 11 window.
    pub ssim: Option<f64>,
}

impl Metrics {
    /// All metrics of `image` against `reference` (`None` when the sizes differ or the
    /// images are empty).
    pub fn of(image: &Image, reference: &Image) -> Option<Metrics> {
        let mse = mse(image, reference)?;
        Some(Metrics {
            mse,
            rmse: mse.sqrt(),
            psnr: psnr_from_mse(mse),
            max_abs: max_abs(image, reference)?,
            ssim: ssim(image, reference),
        })
    }
}

fn same_size(a: &Image, b: &Image) -> bool {
    (a.width, a.height) == (b.width, b.height)
        && !a.pixels.is_empty()
        && a.pixels.len() == b.pixels.len()
}

/// Mean squared difference over all RGB channels.
pub fn mse(a: &Image, b: &Image) -> Option<f64> {
    if !same_size(a, b) {
        return None;
    }
    let sum: f64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| {
            (0..3)
                .map(|k| (f64::from(p[k]) - f64::from(q[k])).powi(2))
                .sum::<f64>()
        })
        .sum();
    Some(sum / (3 * a.pixels.len()) as f64)
}

/// PSNR in dB for a peak value of 1.0 (linear white): `10 log10(1 / mse)`, `+inf` when
/// `mse` is 0.
pub fn psnr_from_mse(mse: f64) -> f64 {
    if mse == 0.0 {
        f64::INFINITY
    } else {
        -10.0 * mse.log10()
    }
}

/// The largest absolute channel difference.
pub fn max_abs(a: &Image, b: &Image) -> Option<f64> {
    if !same_size(a, b) {
        return None;
    }
    Some(
        a.pixels
            .iter()
            .zip(&b.pixels)
            .flat_map(|(p, q)| (0..3).map(move |k| (f64::from(p[k]) - f64::from(q[k])).abs()))
            .fold(0.0, f64::max),
    )
}

/// The display luma SSIM works on: Rec. 601 weights (as MATLAB's `rgb2gray` in Wang et
/// al.'s reference code) of the sRGB-encoded channels clamped to [0, 1].
pub fn luma(image: &Image) -> Vec<f64> {
    image
        .pixels
        .iter()
        .map(|p| {
            let [r, g, b] = p.map(|c| linear_to_srgb(f64::from(c).clamp(0.0, 1.0)));
            0.299 * r + 0.587 * g + 0.114 * b
        })
        .collect()
}

/// The normalised 1-D Gaussian whose outer product is the SSIM window.
pub fn gaussian_window() -> [f64; SSIM_WINDOW] {
    let mut w = [0.0; SSIM_WINDOW];
    let c = (SSIM_WINDOW / 2) as f64;
    for (i, v) in w.iter_mut().enumerate() {
        let d = i as f64 - c;
        *v = (-d * d / (2.0 * SSIM_SIGMA * SSIM_SIGMA)).exp();
    }
    let s: f64 = w.iter().sum();
    w.map(|v| v / s)
}

/// Mean SSIM of two single-channel images of `width` x `height` with values in [0, 1]
/// (dynamic range L = 1), over every position where the 11 x 11 window fits inside the
/// image (Wang et al. 2004, Eq. 13 and 17). `None` when the sizes differ or the image is
/// smaller than the window.
pub fn ssim_gray(a: &[f64], b: &[f64], width: usize, height: usize) -> Option<f64> {
    let n = width.checked_mul(height)?;
    if a.len() != n || b.len() != n || width < SSIM_WINDOW || height < SSIM_WINDOW {
        return None;
    }
    let g = gaussian_window();
    let (c1, c2) = (SSIM_K1 * SSIM_K1, SSIM_K2 * SSIM_K2);
    let (ow, oh) = (width - SSIM_WINDOW + 1, height - SSIM_WINDOW + 1);
    // Separable filtering of the five moments: horizontal pass to ow columns, vertical to oh rows.
    let moments = |f: &dyn Fn(usize) -> f64| -> Vec<f64> {
        let mut horiz = vec![0.0; ow * height];
        for y in 0..height {
            for x in 0..ow {
                horiz[y * ow + x] = (0..SSIM_WINDOW).map(|k| g[k] * f(y * width + x + k)).sum();
            }
        }
        let mut out = vec![0.0; ow * oh];
        for y in 0..oh {
            for x in 0..ow {
                out[y * ow + x] = (0..SSIM_WINDOW)
                    .map(|k| g[k] * horiz[(y + k) * ow + x])
                    .sum();
            }
        }
        out
    };
    let mx = moments(&|i| a[i]);
    let my = moments(&|i| b[i]);
    let mxx = moments(&|i| a[i] * a[i]);
    let myy = moments(&|i| b[i] * b[i]);
    let mxy = moments(&|i| a[i] * b[i]);
    let sum: f64 = (0..ow * oh)
        .map(|i| {
            let (ux, uy) = (mx[i], my[i]);
            let sxx = mxx[i] - ux * ux;
            let syy = myy[i] - uy * uy;
            let sxy = mxy[i] - ux * uy;
            ((2.0 * ux * uy + c1) * (2.0 * sxy + c2))
                / ((ux * ux + uy * uy + c1) * (sxx + syy + c2))
        })
        .sum();
    Some(sum / (ow * oh) as f64)
}

/// Mean SSIM of the display luma of two images ([`luma`], [`ssim_gray`]).
pub fn ssim(a: &Image, b: &Image) -> Option<f64> {
    if !same_size(a, b) {
        return None;
    }
    ssim_gray(&luma(a), &luma(b), a.width as usize, a.height as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaussian_window_is_normalised_and_symmetric() {
        let g = gaussian_window();
        assert!((g.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        for k in 0..SSIM_WINDOW {
            assert_eq!(g[k], g[SSIM_WINDOW - 1 - k]);
        }
        // Centre over neighbour: exp(1 / (2 * 1.5^2)).
        assert!((g[5] / g[4] - (1.0f64 / 4.5).exp()).abs() < 1e-12);
    }

    #[test]
    fn psnr_of_mse() {
        assert_eq!(psnr_from_mse(0.01), 20.0);
        assert_eq!(psnr_from_mse(0.0), f64::INFINITY);
    }
}
