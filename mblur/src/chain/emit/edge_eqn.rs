//! Emission of a moving triangle swept by edge-eqn (Gribel 2010): per pixel centre the
//! exact time spans during which it covers the centre (Eq. 3-9), each with the depth chord
//! through the exact depth at its ends (Eq. 15-16), cut into pieces where a textured span's
//! UV path bends ([`crate::chain::pieces`]), with UV from perspective-correct barycentrics
//! (Eq. 11-12).

use edge_eqn::TriangleSetup;
use glam::DVec2;
use interval_buffer::Interval;

use super::SweptRow;
use crate::chain::Real;
use crate::chain::payload::MakePayload;
use crate::chain::pieces::{chord_slope, piece_cap, piece_end, pieces_within, probe_times};
use crate::error::Result;

/// Calls `f(x, iv)` for every interval `setup` leaves in the columns of `row`.
pub(super) fn emit<F: Real, M: MakePayload<F>>(
    setup: &TriangleSetup<F>,
    row: &SweptRow<'_, F>,
    mk: &M,
    f: &mut impl FnMut(usize, Interval<F, M::P>) -> Result<()>,
) -> Result<()> {
    let t = row.tri;
    let texels = mk.texels(t.material);
    let cells = mk.bary_cells(t.material);
    for x in row.columns.0..=row.columns.1 {
        let s = setup.sample(row.sx(x), row.sy);
        let cov = s.coverage();
        if cov.iter().next().is_none() {
            continue;
        }
        // Eq. 16 as edge-eqn's `linear_depth` defines it: the chord through the exact depth
        // (Eq. 15) at the span ends (its error estimate is not needed).
        let depth = s.depth();
        let mut emit_span = |t0: F, t1: F| -> Result<()> {
            let bary = |tt: F| s.barycentrics(tt).map(|v| v.to_f64().unwrap_or(0.0));
            let uv_of = |bc: [f64; 3]| t.uv[0] * bc[0] + t.uv[1] * bc[1] + t.uv[2] * bc[2];
            // The barycentrics at the span's ends, computed once for the piece count and
            // the payloads of the first and last piece.
            let ends = [bary(t0), bary(t1)];
            let n = match piece_cap(t0, t1) {
                Some(cap) if texels.is_some() || cells.is_some() => {
                    // The barycentrics at the probes, once for both paths.
                    let probes = probe_times(t0, t1).map(bary);
                    let n = texels.map_or(1, |tx| {
                        let uv_ends = [uv_of(ends[0]), uv_of(ends[1])];
                        pieces_within(cap, tx, uv_ends, probes.map(uv_of))
                    });
                    cells.map_or(n, |c| {
                        let b = |bc: [f64; 3]| DVec2::new(bc[1], bc[2]);
                        let b_ends = [b(ends[0]), b(ends[1])];
                        n.max(pieces_within(cap, DVec2::splat(c), b_ends, probes.map(b)))
                    })
                }
                _ => 1,
            };
            let mut ba = ends[0];
            for j in 0..n {
                let a = piece_end(t0, t1, j, n);
                let b = piece_end(t0, t1, j + 1, n).max(a);
                let bb = if b == t1 { ends[1] } else { bary(b) };
                let (za, zb) = (depth.eval(a), depth.eval(b));
                let k = chord_slope(a, b, za, zb);
                if !za.is_finite() || (za > row.far && zb > row.far) {
                    ba = bb;
                    continue;
                }
                let p = mk.make_at(row.index, t.material, [uv_of(ba), uv_of(bb)], [ba, bb]);
                f(x as usize, Interval::new(a, b, za, k, p))?;
                ba = bb;
            }
            Ok(())
        };
        // Each span clipped to the times the triangle may face the eye (`crate::cull`);
        // without culling windows the span itself, with no clipping machinery.
        for w in cov.iter() {
            if !w.t1.partial_cmp(&w.t0).is_some_and(|o| o.is_ge()) {
                continue;
            }
            if row.facing.is_none() {
                emit_span(w.t0, w.t1)?;
            } else {
                for (t0, t1) in row.facing_pieces(w.t0, w.t1) {
                    emit_span(t0, t1)?;
                }
            }
        }
    }
    Ok(())
}
