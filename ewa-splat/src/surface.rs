//! External surfaces in the A-buffer: time intervals of other primitives (triangles of a
//! renderer that draws meshes and splats together) that cover a pixel centre, with a depth
//! linear in time along the same pixel ray as the splat fragments and a premultiplied colour.
//!
//! Heinzle 2010 §4.4 resolves a pixel from fragments that carry a time interval and a depth
//! linear in time; a triangle covering the pixel during `[t0, t1]` (Gribel 2010, Eq. 16) is
//! the same kind of entry, so the A-buffer takes both ([`crate::render_with_surfaces`]).
//!
//! **Depth** is the ray parameter of ewa-splat's pixel ray ([`crate::Camera::pixel_ray`]):
//! world-space distance from the ray's origin on the near plane. For a renderer whose depth
//! is the view-space distance `z_v` along the viewing direction, the exact conversion at a
//! pixel is `s = (z_v - z_v(o)) / c` with `z_v(o)` the view depth of the ray origin (the
//! near distance) and `c` the view-depth gained per unit of ray length (the cosine between
//! the ray and the viewing direction, 1 for an orthographic camera). It is affine, so a depth
//! linear in time stays linear in time.

use crate::render::RenderError;

/// One external surface covering a pixel centre during `[t0, t1]` (exposure time in [0, 1])
/// at depth `depth + depth_slope (t - t0)` along the pixel ray, with a premultiplied linear
/// RGBA colour (alpha 1: opaque; below 1: composited front to back with what is behind).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceInterval {
    /// Start of the interval (exposure time).
    pub t0: f64,
    /// End of the interval (>= `t0`).
    pub t1: f64,
    /// Depth along the pixel ray at `t0` (ray parameter, world units; smaller is nearer).
    pub depth: f64,
    /// Depth per unit exposure time.
    pub depth_slope: f64,
    /// Premultiplied linear RGBA over the interval (alpha in [0, 1]).
    pub colour: [f64; 4],
}

impl SurfaceInterval {
    /// Depth at exposure time `t`.
    pub fn depth_at(&self, t: f64) -> f64 {
        self.depth + self.depth_slope * (t - self.t0)
    }

    /// Finite, ordered ends, alpha in [0, 1].
    fn is_valid(&self) -> bool {
        self.t0.is_finite()
            && self.t1.is_finite()
            && self.t0 <= self.t1
            && self.depth.is_finite()
            && self.depth_slope.is_finite()
            && self.colour.iter().all(|c| c.is_finite())
            && (0.0..=1.0).contains(&self.colour[3])
    }

    /// Alpha clamped to [0, 1].
    pub(crate) fn alpha(&self) -> f64 {
        self.colour[3].clamp(0.0, 1.0)
    }
}

/// Per-pixel lists of [`SurfaceInterval`]s for a `width` x `height` viewport (row-major,
/// row 0 at the top; the same pixel indexing as [`crate::Frame::pixels`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceLists {
    width: u32,
    height: u32,
    /// `offsets[p]..offsets[p + 1]` indexes `intervals` for pixel p.
    offsets: Vec<usize>,
    intervals: Vec<SurfaceInterval>,
}

impl SurfaceLists {
    /// No surfaces at all for a `width` x `height` viewport.
    pub fn empty(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            offsets: Vec::new(),
            intervals: Vec::new(),
        }
    }

    /// Lists from `(x, y, interval)` entries in any order (a counting sort by pixel; the
    /// order within a pixel is kept). Empty intervals (`t0 == t1`) are dropped.
    ///
    /// # Errors
    /// [`RenderError::Surface`] with the entry's index when a pixel is outside the viewport
    /// or an interval is not finite, has `t0 > t1` or alpha outside [0, 1].
    pub fn new(
        width: u32,
        height: u32,
        entries: &[(u32, u32, SurfaceInterval)],
    ) -> Result<Self, RenderError> {
        let n = width as usize * height as usize;
        let mut counts = vec![0usize; n + 1];
        for (i, (x, y, iv)) in entries.iter().enumerate() {
            if *x >= width || *y >= height || !iv.is_valid() {
                return Err(RenderError::Surface(i));
            }
            if iv.t1 > iv.t0 {
                let p = *y as usize * width as usize + *x as usize;
                if let Some(c) = counts.get_mut(p + 1) {
                    *c += 1;
                }
            }
        }
        for p in 0..n {
            let prev = counts.get(p).copied().unwrap_or(0);
            if let Some(c) = counts.get_mut(p + 1) {
                *c += prev;
            }
        }
        let total = counts.get(n).copied().unwrap_or(0);
        let mut next = counts.clone();
        let filler = SurfaceInterval {
            t0: 0.0,
            t1: 0.0,
            depth: 0.0,
            depth_slope: 0.0,
            colour: [0.0; 4],
        };
        let mut intervals = vec![filler; total];
        for (x, y, iv) in entries {
            if iv.t1 > iv.t0 {
                let p = *y as usize * width as usize + *x as usize;
                if let Some(slot) = next.get_mut(p) {
                    if let Some(dst) = intervals.get_mut(*slot) {
                        *dst = *iv;
                    }
                    *slot += 1;
                }
            }
        }
        Ok(Self {
            width,
            height,
            offsets: counts,
            intervals,
        })
    }

    /// Viewport width.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Viewport height.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Number of intervals over all pixels.
    pub fn len(&self) -> usize {
        self.intervals.len()
    }

    /// True when no pixel has an interval.
    pub fn is_empty(&self) -> bool {
        self.intervals.is_empty()
    }

    /// The intervals of pixel `p` (row-major index); empty outside the viewport.
    pub fn pixel(&self, p: usize) -> &[SurfaceInterval] {
        let (Some(&a), Some(&b)) = (self.offsets.get(p), self.offsets.get(p + 1)) else {
            return &[];
        };
        self.intervals.get(a..b).unwrap_or(&[])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(t0: f64, t1: f64, depth: f64) -> SurfaceInterval {
        SurfaceInterval {
            t0,
            t1,
            depth,
            depth_slope: 0.0,
            colour: [0.5, 0.5, 0.5, 1.0],
        }
    }

    #[test]
    fn lists_group_by_pixel_and_keep_order() {
        let e = [
            (1, 1, iv(0.0, 1.0, 3.0)),
            (0, 0, iv(0.0, 0.5, 1.0)),
            (1, 1, iv(0.2, 0.4, 2.0)),
            (1, 0, iv(0.3, 0.3, 2.0)), // empty: dropped
        ];
        let l = SurfaceLists::new(2, 2, &e).unwrap();
        assert_eq!(l.len(), 3);
        assert_eq!(l.pixel(0), &[iv(0.0, 0.5, 1.0)]);
        assert!(l.pixel(1).is_empty());
        assert!(l.pixel(2).is_empty());
        assert_eq!(l.pixel(3), &[iv(0.0, 1.0, 3.0), iv(0.2, 0.4, 2.0)]);
        assert!(l.pixel(4).is_empty());
        assert!(SurfaceLists::empty(2, 2).pixel(3).is_empty());
    }

    #[test]
    fn bad_entries_are_errors_naming_the_entry() {
        let ok = iv(0.0, 1.0, 1.0);
        let mut nan = ok;
        nan.depth = f64::NAN;
        let mut rev = ok;
        rev.t0 = 0.8;
        rev.t1 = 0.2;
        let mut alpha = ok;
        alpha.colour[3] = 1.5;
        for (e, i) in [
            (vec![(0, 0, ok), (2, 0, ok)], 1),
            (vec![(0, 0, nan)], 0),
            (vec![(0, 0, ok), (0, 1, ok), (1, 1, rev)], 2),
            (vec![(0, 0, alpha)], 0),
        ] {
            assert_eq!(SurfaceLists::new(2, 2, &e), Err(RenderError::Surface(i)));
        }
    }

    #[test]
    fn depth_is_linear_from_t0() {
        let s = SurfaceInterval {
            t0: 0.25,
            t1: 0.75,
            depth: 2.0,
            depth_slope: -4.0,
            colour: [0.0; 4],
        };
        assert_eq!(s.depth_at(0.25), 2.0);
        assert_eq!(s.depth_at(0.75), 0.0);
    }
}
