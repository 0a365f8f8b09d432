//! Resolving a whole frame: pixels are independent, so they run in parallel with rayon.

use interval_buffer::{Interval, Rgba};
use num_traits::Float;
use rayon::prelude::*;

use crate::sweep::{Scratch, Settings, resolve_with};
use crate::{ResolveError, Shader};

/// Resolves every pixel of a `width × height` frame into `out` (row-major, `y * width + x`)
/// in parallel (Gribel 2010, §5.1: "the resolve pass processes a pixel independently").
///
/// `pixel(i)` gives the sorted interval list of pixel `i`, so either interval-buffer
/// strategy (bounded per-pixel arrays, or exact lists behind an exclusive scan) plugs in
/// through a closure. Each rayon worker reuses one [`Scratch`].
///
/// Errors: [`ResolveError::OutputSize`] if `out.len() != width * height`,
/// [`ResolveError::InvalidSettings`], or [`ResolveError::Pixel`] for a failing pixel (when
/// several fail, which one is reported is unspecified); `out` is partly written then.
///
/// ```
/// use interval_buffer::{Interval, Rgba};
/// use resolve::{Flat, Settings, resolve_frame};
/// let lists = vec![
///     vec![Interval::new(0.0_f32, 1.0, 1.0, 0.0, Rgba::opaque(1.0, 0.0, 0.0))],
///     vec![],
/// ];
/// let mut out = vec![Rgba::new(0.0, 0.0, 0.0, 0.0); 2];
/// resolve_frame(2, 1, |i| lists[i].as_slice(), &Flat, &Settings::opaque(), &mut out).unwrap();
/// assert_eq!(out[0], Rgba::opaque(1.0, 0.0, 0.0));
/// assert_eq!(out[1], Rgba::opaque(0.0, 0.0, 0.0));
/// ```
pub fn resolve_frame<'a, F, P, S, A>(
    width: usize,
    height: usize,
    pixel: A,
    shader: &S,
    settings: &Settings<F>,
    out: &mut [Rgba<F>],
) -> Result<(), ResolveError>
where
    F: Float + Send + Sync + 'a,
    P: Sync + 'a,
    S: Shader<F, P> + Sync,
    A: Fn(usize) -> &'a [Interval<F, P>] + Sync,
{
    let expected = width.saturating_mul(height);
    if out.len() != expected {
        return Err(ResolveError::OutputSize {
            expected,
            got: out.len(),
        });
    }
    out.par_iter_mut()
        .enumerate()
        .with_min_len(64)
        .try_for_each_init(Scratch::new, |scratch, (i, o)| {
            *o = resolve_with(scratch, pixel(i), shader, settings, |_| {})
                .map_err(|e| e.at_pixel(i))?;
            Ok(())
        })
}
