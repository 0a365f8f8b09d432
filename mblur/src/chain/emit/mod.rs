//! Emission: the intervals one primitive leaves in the pixels of one row, per primitive
//! kind — static rasteriser fragments (`Prim::Fixed`, one interval of constant depth over
//! the primitive's time range), edge-eqn coverage spans (`edge_eqn`, Gribel 2010 Eq. 3-9
//! and 16) and ray-prism coverage spans (`prism`, Rønnow 2021 §4.1, Fig. 6). A swept
//! triangle that back-face culling clips ([`crate::cull`]) has each coverage span clipped
//! to its facing windows before the span gets depth and payload. Far clipping
//! is approximate for moving intervals: a span is dropped when its depth is beyond the far
//! plane at both ends.

mod edge_eqn;
mod prism;

use arrayvec::ArrayVec;
use interval_buffer::Interval;
use raster_hier::windows::MAX_WINDOWS;

use super::payload::MakePayload;
use super::prim::{Prim, Swept, local_centre};
use super::{Real, cf};
use crate::error::{Error, Result};
use crate::prepared::{PreparedScene, PreparedTriangle};
use crate::static_path::ScreenTriangle;

/// The pixels of one row that emission evaluates: row `y`, columns `x_start..x_end`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct RowSpan {
    /// The row.
    pub y: u32,
    /// First column.
    pub x_start: u32,
    /// One past the last column.
    pub x_end: u32,
}

impl RowSpan {
    /// The whole row `y` of a `width`-pixel image.
    pub(crate) fn row(y: u32, width: u32) -> Self {
        RowSpan {
            y,
            x_start: 0,
            x_end: width,
        }
    }

    /// The single pixel (x, y).
    pub(crate) fn pixel(x: u32, y: u32) -> Self {
        RowSpan {
            y,
            x_start: x,
            x_end: x.saturating_add(1),
        }
    }
}

/// Calls `f(x, iv)` for every interval primitive `prim` leaves in the pixels of `span`.
pub(crate) fn emit<F: Real, M: MakePayload<F>>(
    scene: &PreparedScene,
    prim: &Prim<F>,
    span: RowSpan,
    mk: &M,
    mut f: impl FnMut(usize, Interval<F, M::P>) -> Result<()>,
) -> Result<()> {
    match prim {
        Prim::Fixed { st, t0, t1 } => emit_fixed(scene, st, [*t0, *t1], span, mk, &mut f),
        Prim::Moving { setup, swept } => match SweptRow::new(scene, swept, span)? {
            Some(row) => edge_eqn::emit(setup, &row, mk, &mut in_span(swept, f)),
            None => Ok(()),
        },
        Prim::Prism { prism, swept } => match SweptRow::new(scene, swept, span)? {
            Some(row) => prism::emit(prism, &row, mk, &mut in_span(swept, f)),
            None => Ok(()),
        },
    }
}

/// `f` with the intervals' local times u ∈ \[0, 1\] of a swept primitive mapped into its
/// span `[t0, t1]` of the shutter: times `(1 - u) t0 + u t1` (exact at both ends, so
/// consecutive segments meet without gap or overlap) and depth slopes divided by the
/// span's length.
fn in_span<F: Real, P>(
    swept: &Swept,
    mut f: impl FnMut(usize, Interval<F, P>) -> Result<()>,
) -> impl FnMut(usize, Interval<F, P>) -> Result<()> {
    let [a, b] = swept.span;
    let whole = swept.span == [0.0, 1.0];
    let (t0, t1): (F, F) = (cf(a), cf(b));
    let len: F = cf(b - a);
    move |x, mut iv| {
        if !whole {
            let map = |u: F| (F::one() - u) * t0 + u * t1;
            iv.ts = map(iv.ts);
            iv.te = map(iv.te).max(iv.ts);
            iv.k = if len > F::zero() {
                iv.k / len
            } else {
                F::zero()
            };
        }
        f(x, iv)
    }
}

/// A static rasteriser primitive: one interval `[t0, t1]` of constant depth per covered
/// pixel centre of the span in front of the far plane.
fn emit_fixed<F: Real, M: MakePayload<F>>(
    scene: &PreparedScene,
    st: &ScreenTriangle,
    [t0, t1]: [F; 2],
    span: RowSpan,
    mk: &M,
    f: &mut impl FnMut(usize, Interval<F, M::P>) -> Result<()>,
) -> Result<()> {
    let mut res = Ok(());
    st.rasterise(span.y, span.y + 1, |x, _, frag| {
        if res.is_err() || frag.depth > scene.far || x < span.x_start || x >= span.x_end {
            return;
        }
        let p = mk.make_at(st.order, st.material, [frag.uv; 2], [frag.bary; 2]);
        res = f(
            x as usize,
            Interval::new(t0, t1, cf(frag.depth), F::zero(), p),
        );
    });
    res
}

/// A swept primitive's work in one row: its triangle, the columns to evaluate and the
/// local coordinates of the row's pixel centres.
pub(super) struct SweptRow<'a, F> {
    /// The triangle.
    tri: &'a PreparedTriangle,
    /// Its index in [`PreparedScene::triangles`].
    index: u32,
    /// Columns `first..=last` to evaluate: inside the bounds, the hull's row span and the
    /// row span asked for.
    columns: (u32, u32),
    /// The local y of the row's pixel centres.
    sy: F,
    /// The origin's column.
    ox: u32,
    /// The far plane.
    far: F,
    /// The times (local u) the triangle may face the eye ([`Swept::facing`]); `None`: all.
    facing: Option<&'a [[f64; 2]]>,
}

impl<'a, F: Real> SweptRow<'a, F> {
    /// The row of `swept` in `span`, or `None` when it has no columns there.
    fn new(scene: &'a PreparedScene, swept: &'a Swept, span: RowSpan) -> Result<Option<Self>> {
        let (b, y) = (&swept.bounds, span.y);
        if y < b.y0 || y > b.y1 || span.x_end == 0 {
            return Ok(None);
        }
        let Some(columns) = swept
            .hull
            .pixels(y, b.x0.max(span.x_start), b.x1.min(span.x_end - 1))
        else {
            return Ok(None);
        };
        let tri = scene.triangles.get(swept.tri as usize).ok_or_else(|| {
            Error::internal(
                "interval emission",
                format!("primitive of triangle {} out of range", swept.tri),
            )
        })?;
        let [ox, oy] = swept.origin;
        Ok(Some(SweptRow {
            tri,
            index: swept.tri,
            columns,
            sy: local_centre(y - oy),
            ox,
            far: cf(scene.far),
            facing: swept.facing.as_deref(),
        }))
    }

    /// The parts of the coverage interval `[t0, t1]` (local u) inside the triangle's facing
    /// windows, in time order: `[t0, t1]` itself when back-face culling does not clip the
    /// triangle. A part shrunk to an instant is dropped (unless the interval was one).
    fn facing_pieces(&self, t0: F, t1: F) -> ArrayVec<(F, F), MAX_WINDOWS> {
        let mut out = ArrayVec::new();
        let Some(windows) = self.facing else {
            out.push((t0, t1));
            return out;
        };
        for &[a, b] in windows {
            let (lo, hi) = (t0.max(cf(a)), t1.min(cf(b)));
            if lo < hi || (lo == hi && t0 == t1) {
                out.push((lo, hi));
            }
        }
        out
    }

    /// The local x of the centre of column `x`.
    fn sx(&self, x: u32) -> F {
        local_centre(x - self.ox)
    }
}
