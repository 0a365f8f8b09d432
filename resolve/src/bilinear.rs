//! A bilinearly filtered, wrapping texel grid with an exact segment integral.

use interval_buffer::Rgba;
use num_traits::Float;

use crate::ResolveError;
use crate::texture::{SegmentTexture, Texture};

/// Segments crossing more texel-cell boundaries than this are integrated by a composite
/// Simpson rule with this many pieces instead of exactly (keeps the cost bounded for
/// texture coordinates that sweep across the texture many times).
pub const MAX_EXACT_PIECES: usize = 1 << 16;

/// A `width × height` texel grid sampled with bilinear filtering and wrap (repeat)
/// addressing. Texel (i, j) sits at uv ((i + ½) / width, (j + ½) / height); filtering
/// interpolates premultiplied texels.
///
/// Along a straight UV segment the filtered colour is, inside each texel cell, the product
/// of two linear functions of the segment parameter, i.e. a quadratic; times a linear
/// shutter weight it is a cubic, which Simpson's rule integrates exactly. The
/// [`SegmentTexture`] implementation therefore splits the segment at every cell boundary it
/// crosses and sums one Simpson step per piece: the exact box-filtered (in time) line
/// integral of the bilinear texture (Rønnow 2021, §4.3, Fig. 8), up to rounding.
///
/// `material` is ignored; a slice `[BilinearTexture]` is a material table indexed by it.
#[derive(Clone, Debug, PartialEq)]
pub struct BilinearTexture<F> {
    width: usize,
    height: usize,
    texels: Vec<[F; 4]>,
}

impl<F: Float> BilinearTexture<F> {
    /// A texture from row-major straight-alpha texels (`texels[j * width + i]`).
    ///
    /// Errors with [`ResolveError::InvalidTexture`] for an empty grid, a length other than
    /// `width * height`, or a non-finite texel.
    pub fn new(width: usize, height: usize, texels: &[Rgba<F>]) -> Result<Self, ResolveError> {
        let finite = texels
            .iter()
            .all(|t| t.r.is_finite() && t.g.is_finite() && t.b.is_finite() && t.a.is_finite());
        if width == 0 || height == 0 || width.checked_mul(height) != Some(texels.len()) || !finite {
            return Err(ResolveError::InvalidTexture);
        }
        Ok(Self {
            width,
            height,
            texels: texels.iter().map(Rgba::premultiplied).collect(),
        })
    }

    /// Width in texels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The premultiplied bilinear value at texel-space position (x, y) (texel centres at
    /// integers).
    pub fn premultiplied_at(&self, x: F, y: F) -> [F; 4] {
        let (i, j) = (x.floor(), y.floor());
        self.cell_value(i, j, x - i, y - j)
    }

    /// Bilinear value inside cell (i, j) (corner texels i, i+1 × j, j+1, wrapped) at local
    /// coordinates (fx, fy); the polynomial is evaluated as is, also slightly outside [0, 1].
    fn cell_value(&self, i: F, j: F, fx: F, fy: F) -> [F; 4] {
        let i0 = wrap(i, self.width);
        let j0 = wrap(j, self.height);
        let i1 = if i0 + 1 == self.width { 0 } else { i0 + 1 };
        let j1 = if j0 + 1 == self.height { 0 } else { j0 + 1 };
        let t = |i: usize, j: usize| {
            self.texels
                .get(j * self.width + i)
                .copied()
                .unwrap_or([F::zero(); 4])
        };
        let (a, b, c, d) = (t(i0, j0), t(i1, j0), t(i0, j1), t(i1, j1));
        let one = F::one();
        let mut out = [F::zero(); 4];
        for (k, o) in out.iter_mut().enumerate() {
            let top = a[k] * (one - fx) + b[k] * fx;
            let bottom = c[k] * (one - fx) + d[k] * fx;
            *o = top * (one - fy) + bottom * fy;
        }
        out
    }

    /// Texel-space position of `uv` (texel centres at integers).
    fn texel_space(&self, uv: [F; 2]) -> (F, F) {
        let half = F::one() / (F::one() + F::one());
        let w = F::from(self.width).unwrap_or_else(F::one);
        let h = F::from(self.height).unwrap_or_else(F::one);
        (uv[0] * w - half, uv[1] * h - half)
    }

    fn size(&self) -> (F, F) {
        (
            F::from(self.width).unwrap_or_else(F::one),
            F::from(self.height).unwrap_or_else(F::one),
        )
    }

    /// Exact weighted mean along the texel-space segment p0 → p1 (see the type's docs).
    fn exact_average(&self, p0: (F, F), p1: (F, F), w0: F, w1: F) -> [F; 4] {
        let (w0, w1) = if w0 + w1 > F::zero() {
            (w0, w1)
        } else {
            (F::one(), F::one())
        };
        // Shift by whole periods so that the coordinates are small (exact integer steps).
        let (sw, sh) = self.size();
        let ox = sw * (p0.0 / sw).floor();
        let oy = sh * (p0.1 / sh).floor();
        let (x0, y0) = (p0.0 - ox, p0.1 - oy);
        let (dx, dy) = (p1.0 - ox - x0, p1.1 - oy - y0);
        let at = |s: F| (x0 + dx * s, y0 + dy * s);
        let weight = |s: F| w0 + (w1 - w0) * s;
        let two = F::one() + F::one();
        let four = two + two;
        let six = four + two;
        let mut sum = [F::zero(); 4];
        let mut piece = |sa: F, sb: F| {
            let sm = (sa + sb) / two;
            let (xm, ym) = at(sm);
            let (i, j) = (xm.floor(), ym.floor());
            let mut add = |s: F, factor: F| {
                let (x, y) = at(s);
                let c = self.cell_value(i, j, x - i, y - j);
                let w = weight(s) * factor * (sb - sa) / six;
                for (acc, c) in sum.iter_mut().zip(c) {
                    *acc = *acc + w * c;
                }
            };
            add(sa, F::one());
            add(sm, four);
            add(sb, F::one());
        };
        let crossings = (x0 + dx).floor() - x0.floor();
        let crossings = crossings.abs() + ((y0 + dy).floor() - y0.floor()).abs();
        let cap = F::from(MAX_EXACT_PIECES).unwrap_or_else(F::one);
        if crossings.is_nan() || crossings >= cap {
            // Too long for the exact split: composite Simpson with a fixed piece count.
            let mut sa = F::zero();
            for k in 1..=MAX_EXACT_PIECES {
                let sb = F::from(k).unwrap_or_else(F::one) / cap;
                piece(sa, sb);
                sa = sb;
            }
        } else {
            let mut xs = Crossings::new(x0, dx);
            let mut ys = Crossings::new(y0, dy);
            let mut sa = F::zero();
            let mut guard = 0;
            while sa < F::one() && guard <= MAX_EXACT_PIECES + 2 {
                let sb = xs.next_s().min(ys.next_s()).min(F::one());
                if sb > sa {
                    piece(sa, sb);
                    sa = sb;
                }
                xs.pass(sb);
                ys.pass(sb);
                guard += 1;
            }
        }
        let norm = (w0 + w1) / two;
        [sum[0] / norm, sum[1] / norm, sum[2] / norm, sum[3] / norm]
    }
}

/// Index `i` (an integer-valued float) wrapped into `0..n`.
fn wrap<F: Float>(i: F, n: usize) -> usize {
    let nf = F::from(n).unwrap_or_else(F::one);
    let r = i - nf * (i / nf).floor();
    r.to_usize().map_or(0, |r| if r >= n { 0 } else { r })
}

/// The parameters s in (0, 1] at which x0 + d s crosses an integer, in increasing order.
struct Crossings<F> {
    x0: F,
    d: F,
    next: F,
}

impl<F: Float> Crossings<F> {
    fn new(x0: F, d: F) -> Self {
        let next = if d > F::zero() {
            x0.floor() + F::one()
        } else {
            x0.ceil() - F::one()
        };
        Self { x0, d, next }
    }

    fn next_s(&self) -> F {
        if self.d == F::zero() {
            F::infinity()
        } else {
            (self.next - self.x0) / self.d
        }
    }

    /// Steps past the crossing at parameter `s` if that is the current one.
    fn pass(&mut self, s: F) {
        if self.d != F::zero() && self.next_s() <= s {
            self.next = if self.d > F::zero() {
                self.next + F::one()
            } else {
                self.next - F::one()
            };
        }
    }
}

impl<F: Float> Texture<F> for BilinearTexture<F> {
    fn sample(&self, _material: u32, uv: [F; 2]) -> Rgba<F> {
        unpremultiply(self.sample_premultiplied(0, uv))
    }

    fn sample_premultiplied(&self, _material: u32, uv: [F; 2]) -> [F; 4] {
        let (x, y) = self.texel_space(uv);
        let (sw, sh) = self.size();
        self.premultiplied_at(x - sw * (x / sw).floor(), y - sh * (y / sh).floor())
    }
}

impl<F: Float> SegmentTexture<F> for BilinearTexture<F> {
    fn segment_average(&self, _: u32, uv0: [F; 2], uv1: [F; 2], w0: F, w1: F) -> [F; 4] {
        self.exact_average(self.texel_space(uv0), self.texel_space(uv1), w0, w1)
    }
}

impl<F: Float> Texture<F> for [BilinearTexture<F>] {
    /// Looks up texture number `material`; an unknown material is transparent black.
    fn sample(&self, material: u32, uv: [F; 2]) -> Rgba<F> {
        match self.get(material as usize) {
            Some(t) => t.sample(material, uv),
            None => Rgba::new(F::zero(), F::zero(), F::zero(), F::zero()),
        }
    }

    fn sample_premultiplied(&self, material: u32, uv: [F; 2]) -> [F; 4] {
        self.get(material as usize)
            .map_or([F::zero(); 4], |t| t.sample_premultiplied(material, uv))
    }
}

impl<F: Float> SegmentTexture<F> for [BilinearTexture<F>] {
    fn segment_average(&self, material: u32, uv0: [F; 2], uv1: [F; 2], w0: F, w1: F) -> [F; 4] {
        match self.get(material as usize) {
            Some(t) => t.segment_average(material, uv0, uv1, w0, w1),
            None => [F::zero(); 4],
        }
    }
}

/// Straight alpha from premultiplied (transparent black where alpha is 0).
pub(crate) fn unpremultiply<F: Float>(p: [F; 4]) -> Rgba<F> {
    if p[3] > F::zero() {
        Rgba::new(p[0] / p[3], p[1] / p[3], p[2] / p[3], p[3])
    } else {
        Rgba::new(F::zero(), F::zero(), F::zero(), F::zero())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checker() -> BilinearTexture<f64> {
        let texels: Vec<_> = (0..12)
            .map(|k| {
                let v = ((k * 7) % 5) as f64 / 4.0;
                Rgba::new(v, 1.0 - v, 0.5, 0.25 + 0.5 * ((k % 3) as f64) / 2.0)
            })
            .collect();
        BilinearTexture::new(4, 3, &texels).unwrap()
    }

    #[test]
    fn texel_centres_return_texels() {
        let t = checker();
        let c = t.sample(0, [(1.0 + 0.5) / 4.0, (2.0 + 0.5) / 3.0]);
        let k = 2 * 4 + 1;
        let v = ((k * 7) % 5) as f64 / 4.0;
        assert!((c.r - v).abs() < 1e-12 && (c.g - (1.0 - v)).abs() < 1e-12);
        // Wrapping: one period away is the same texel.
        let d = t.sample(0, [(1.0 + 0.5) / 4.0 + 3.0, (2.0 + 0.5) / 3.0 - 2.0]);
        assert!((c.r - d.r).abs() < 1e-12 && (c.a - d.a).abs() < 1e-12);
    }

    #[test]
    fn constant_texture_integrates_to_itself() {
        let t = BilinearTexture::new(2, 2, &[Rgba::new(0.2, 0.4, 0.6, 0.5); 4]).unwrap();
        let c = t.segment_average(0, [-3.3, 0.7], [5.1, -2.0], 0.0, 2.0);
        assert!((c[0] - 0.1).abs() < 1e-12 && (c[3] - 0.5).abs() < 1e-12);
    }

    #[test]
    fn invalid_textures_are_rejected() {
        assert!(BilinearTexture::<f64>::new(0, 1, &[]).is_err());
        assert!(BilinearTexture::new(2, 2, &[Rgba::opaque(0.0, 0.0, 0.0); 3]).is_err());
        assert!(BilinearTexture::new(1, 1, &[Rgba::opaque(f64::NAN, 0.0, 0.0)]).is_err());
    }

    #[test]
    fn unknown_material_is_transparent_black() {
        let table = [checker()];
        assert_eq!(table[..].sample(3, [0.1, 0.1]).a, 0.0);
        assert_eq!(
            table[..].segment_average(3, [0.1, 0.1], [0.2, 0.2], 1.0, 1.0),
            [0.0; 4]
        );
    }
}
