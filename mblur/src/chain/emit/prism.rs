//! Emission of a moving triangle swept as a space-time prism (bilinear-patch, Rønnow 2021
//! §3-4.1): per pixel centre the spans between the sorted, paired prism hits, each with
//! depth and barycentrics at both ends (Fig. 6). A textured span whose UV path bends is cut
//! into pieces ([`crate::chain::pieces`]) with UV and depth at each piece end from the
//! screen-space barycentrics of the triangle at that time (the prism's own model of the
//! motion; the paper keeps one UV segment per span). A span of a triangle that back-face
//! culling clips ([`crate::cull`]) is cut to its facing windows first, with barycentrics
//! and depth at a new end from the same screen-space triangle.

use bilinear_patch::{Prism, Span};
use glam::DVec2;
use interval_buffer::Interval;

use super::SweptRow;
use crate::chain::Real;
use crate::chain::payload::MakePayload;
use crate::chain::pieces::{chord_slope, piece_cap, piece_end, pieces_within, probe_times};
use crate::error::Result;

/// Calls `f(x, iv)` for every interval `prism` leaves in the columns of `row`.
pub(super) fn emit<F: Real, M: MakePayload<F>>(
    prism: &Prism<F>,
    row: &SweptRow<'_, F>,
    mk: &M,
    f: &mut impl FnMut(usize, Interval<F, M::P>) -> Result<()>,
) -> Result<()> {
    let zero = F::zero();
    let far = row.far;
    for x in row.columns.0..=row.columns.1 {
        let centre = (row.sx(x), row.sy);
        let cov = prism.coverage(centre.0, centre.1);
        // Each span clipped to the times the triangle may face the eye (`crate::cull`).
        let spans = cov.iter().flat_map(|whole| {
            let pieces = row.facing_pieces(whole.t0, whole.t1);
            pieces
                .into_iter()
                .map(move |(a, b)| clip(prism, whole, centre, a, b))
        });
        for span in spans {
            let span = &span;
            let len = span.t1 - span.t0;
            let k = if len > zero {
                (span.depth1 - span.depth0) / len
            } else {
                zero
            };
            let ok = len >= zero && span.depth0.is_finite() && k.is_finite();
            if !ok || (span.depth0 > far && span.depth1 > far) {
                continue;
            }
            let at = SpanAt {
                prism,
                span,
                centre,
                len,
            };
            at.emit(row, mk, k, &mut |iv| f(x as usize, iv))?;
        }
    }
    Ok(())
}

/// `span` restricted to `[a, b]` within it, with barycentrics and depth at a new end from
/// the prism's triangle at that time ([`SpanAt::at`]); `span` itself when `[a, b]` is all
/// of it.
fn clip<F: Real>(prism: &Prism<F>, span: &Span<F>, centre: (F, F), a: F, b: F) -> Span<F> {
    if a == span.t0 && b == span.t1 {
        return *span;
    }
    let at = SpanAt {
        prism,
        span,
        centre,
        len: span.t1 - span.t0,
    };
    let (uv0, depth0) = if a == span.t0 {
        (span.uv0, span.depth0)
    } else {
        at.at(a)
    };
    let (uv1, depth1) = if b == span.t1 {
        (span.uv1, span.depth1)
    } else {
        at.at(b)
    };
    Span {
        t0: a,
        t1: b,
        depth0,
        depth1,
        uv0,
        uv1,
    }
}

/// One coverage span of a pixel centre.
struct SpanAt<'a, F> {
    prism: &'a Prism<F>,
    span: &'a Span<F>,
    /// The pixel centre in the prism's local coordinates.
    centre: (F, F),
    /// `t1 - t0`.
    len: F,
}

impl<F: Real> SpanAt<'_, F> {
    /// Barycentrics (weights of v1, v2) and depth at the pixel centre at time `tt`, from
    /// the screen-space triangle of the prism at `tt`; where those are not finite, linear
    /// in t between the span's ends.
    fn at(&self, tt: F) -> ([F; 2], F) {
        let (px, py) = self.centre;
        let span = self.span;
        let v = self.prism.at(tt);
        let (ax, ay) = (v[1].x - v[0].x, v[1].y - v[0].y);
        let (bx, by) = (v[2].x - v[0].x, v[2].y - v[0].y);
        let (cx, cy) = (px - v[0].x, py - v[0].y);
        let d = ax * by - ay * bx;
        let (b1, b2) = ((cx * by - cy * bx) / d, (ax * cy - ay * cx) / d);
        let z = (F::one() - b1 - b2) * v[0].depth + b1 * v[1].depth + b2 * v[2].depth;
        if b1.is_finite() && b2.is_finite() && z.is_finite() {
            ([b1, b2], z)
        } else {
            let s = (tt - span.t0) / self.len;
            let l = |a: F, b: F| a + (b - a) * s;
            (
                [l(span.uv0[0], span.uv1[0]), l(span.uv0[1], span.uv1[1])],
                l(span.depth0, span.depth1),
            )
        }
    }

    /// Emits the span (depth slope `k`) as one interval, or as pieces when its material is
    /// textured and its UV path bends.
    fn emit<M: MakePayload<F>>(
        &self,
        row: &SweptRow<'_, F>,
        mk: &M,
        k: F,
        f: &mut impl FnMut(Interval<F, M::P>) -> Result<()>,
    ) -> Result<()> {
        let (t, span) = (row.tri, self.span);
        let bary = |b: [F; 2]| {
            let (b1, b2) = (b[0].to_f64().unwrap_or(0.0), b[1].to_f64().unwrap_or(0.0));
            [1.0 - b1 - b2, b1, b2]
        };
        let uv = |b: [F; 2]| {
            let (b1, b2) = (b[0].to_f64().unwrap_or(0.0), b[1].to_f64().unwrap_or(0.0));
            t.uv[0] * (1.0 - b1 - b2) + t.uv[1] * b1 + t.uv[2] * b2
        };
        let (texels, cells) = (mk.texels(t.material), mk.bary_cells(t.material));
        let n = match piece_cap(span.t0, span.t1) {
            Some(cap) if texels.is_some() || cells.is_some() => {
                // The patch coordinates at the ends and probes, once for both paths.
                let ends = [span.t0, span.t1].map(|tt| self.at(tt).0);
                let probes = probe_times(span.t0, span.t1).map(|tt| self.at(tt).0);
                let n = texels.map_or(1, |tx: DVec2| {
                    pieces_within(cap, tx, ends.map(uv), probes.map(uv))
                });
                cells.map_or(n, |c| {
                    let b = |w: [F; 2]| {
                        let w = bary(w);
                        DVec2::new(w[1], w[2])
                    };
                    n.max(pieces_within(
                        cap,
                        DVec2::splat(c),
                        ends.map(b),
                        probes.map(b),
                    ))
                })
            }
            _ => 1,
        };
        if n == 1 {
            let p = mk.make_at(
                row.index,
                t.material,
                [uv(span.uv0), uv(span.uv1)],
                [bary(span.uv0), bary(span.uv1)],
            );
            return f(Interval::new(span.t0, span.t1, span.depth0, k, p));
        }
        let mut prev = (span.t0, span.uv0, span.depth0);
        for j in 1..=n {
            let (tb, bb, zb) = if j == n {
                (span.t1, span.uv1, span.depth1)
            } else {
                let tb = piece_end(span.t0, span.t1, j, n);
                let (bb, zb) = self.at(tb);
                (tb, bb, zb)
            };
            let (ta, ba, za) = prev;
            let kk = chord_slope(ta, tb, za, zb);
            let p = mk.make_at(
                row.index,
                t.material,
                [uv(ba), uv(bb)],
                [bary(ba), bary(bb)],
            );
            f(Interval::new(ta, tb.max(ta), za, kk, p))?;
            prev = (tb, bb, zb);
        }
        Ok(())
    }
}
