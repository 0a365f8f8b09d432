//! Whether a triangle soup is a closed mesh: every directed edge of a non-degenerate
//! triangle has exactly one reversed partner, vertices matched on their position snapped to
//! a grid of 1e-9 of the soup's size (so seams that duplicate a vertex for its UV or normal
//! still close).
//!
//! A snapped position is three integers in 0..=10⁹, so it packs into the low 90 bits of a
//! `u128`, and an edge use into two: its lower end, then its upper end shifted left by one
//! with the direction in the last bit. Sorting those 32-byte keys puts the two uses of an
//! undirected edge side by side, exactly (no hashing), with a third of the memory of
//! unpacked keys. Each step runs on the caller's rayon pool.

use glam::DVec3;
use rayon::prelude::*;

/// An edge use: the packed lower end of the undirected edge, then the packed upper end
/// shifted left by one with 1 in the last bit when the triangle runs from the upper end
/// to the lower. [`NONE`] for the edges of a degenerate triangle.
type EdgeUse = [u128; 2];

/// The edges of a degenerate triangle (it has none): sorted after every real edge use.
const NONE: EdgeUse = [u128::MAX; 2];

/// Snapped coordinates are at most 10⁹ + 1 < 2³⁰.
const AXIS_BITS: u32 = 30;

/// True when `tris` (each triangle's three corners) is a closed mesh (see the module
/// documentation); false for an empty soup, a soup of zero or non-finite size, or one
/// whose triangles are all degenerate.
pub(crate) fn is_closed<T: Sync>(tris: &[T], corners: impl Fn(&T) -> [DVec3; 3] + Sync) -> bool {
    let (lo, hi) = tris.iter().flat_map(&corners).fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    );
    let size = (hi - lo).max_element();
    if !(size.is_finite() && size > 0.0) {
        return false;
    }
    let cell = size * 1e-9;
    // (p - lo) / cell is in [0, 1e9] on every axis, up to rounding.
    let key = |p: DVec3| -> u128 {
        let q = ((p - lo) / cell).round();
        [q.x, q.y, q.z]
            .into_iter()
            .fold(0, |k, v| (k << AXIS_BITS) | v as u128)
    };
    let mut edges: Vec<EdgeUse> = tris
        .par_iter()
        .map(|t| {
            let k = corners(t).map(key);
            if k[0] == k[1] || k[1] == k[2] || k[0] == k[2] {
                // Zero area for the whole shutter (rigid per-vertex transforms).
                return [NONE; 3];
            }
            [(k[0], k[1]), (k[1], k[2]), (k[2], k[0])].map(|(a, b)| {
                if a < b {
                    [a, b << 1]
                } else {
                    [b, (a << 1) | 1]
                }
            })
        })
        .collect::<Vec<[EdgeUse; 3]>>()
        .into_flattened();
    edges.par_sort_unstable();
    let real = edges.partition_point(|e| *e != NONE);
    // Each undirected edge must be used exactly twice, once per direction.
    real > 0
        && edges[..real]
            .par_chunk_by(|x, y| x[0] == y[0] && x[1] >> 1 == y[1] >> 1)
            .all(|uses| matches!(uses, [a, b] if a[1] & 1 != b[1] & 1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The 12 triangles of the unit cube, outward winding, each face's two triangles with
    /// their own copies of the corners (as a mesh split at every face for its normals).
    fn cube() -> Vec<[DVec3; 3]> {
        let v = |i: u32| DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2));
        let quads = [
            [0, 2, 3, 1], // z = 0, facing -z
            [4, 5, 7, 6], // z = 1
            [0, 1, 5, 4], // y = 0
            [2, 6, 7, 3], // y = 1
            [0, 4, 6, 2], // x = 0
            [1, 3, 7, 5], // x = 1
        ];
        quads
            .iter()
            .flat_map(|q| [[v(q[0]), v(q[1]), v(q[2])], [v(q[0]), v(q[2]), v(q[3])]])
            .collect()
    }

    /// The reference: for every directed edge of every non-degenerate triangle, count the
    /// edges of all triangles equal to it and to its reverse, pair by pair (positions
    /// compared after the same snapping, so the two agree on what "the same vertex" means).
    fn brute_force(tris: &[[DVec3; 3]]) -> bool {
        let pts = tris.iter().flatten();
        let lo = pts.clone().fold(DVec3::INFINITY, |a, &p| a.min(p));
        let hi = pts.fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
        let size = (hi - lo).max_element();
        if !(size.is_finite() && size > 0.0) {
            return false;
        }
        let key = |p: DVec3| ((p - lo) / (size * 1e-9)).round();
        let solid: Vec<[DVec3; 3]> = tris
            .iter()
            .map(|t| t.map(key))
            .filter(|k| k[0] != k[1] && k[1] != k[2] && k[0] != k[2])
            .collect();
        let directed = |t: &[DVec3; 3]| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])];
        !solid.is_empty()
            && solid.iter().flat_map(directed).all(|(a, b)| {
                let all = solid.iter().flat_map(directed);
                let same = all.clone().filter(|&e| e == (a, b)).count();
                let reversed = all.filter(|&e| e == (b, a)).count();
                same == 1 && reversed == 1
            })
    }

    fn closed(tris: &[[DVec3; 3]]) -> bool {
        is_closed(tris, |t| *t)
    }

    #[test]
    fn a_cube_split_at_its_faces_is_closed() {
        let c = cube();
        assert!(brute_force(&c));
        assert!(closed(&c));
    }

    #[test]
    fn a_cube_with_a_hole_a_flipped_face_or_a_doubled_face_is_not_closed() {
        let mut hole = cube();
        hole.truncate(10);
        let mut flipped = cube();
        flipped[0].swap(1, 2);
        flipped[1].swap(1, 2);
        let mut doubled = cube();
        doubled.extend_from_slice(&cube()[..2]);
        for (name, t) in [("hole", hole), ("flipped", flipped), ("doubled", doubled)] {
            assert!(!brute_force(&t), "{name}");
            assert!(!closed(&t), "{name}");
        }
    }

    #[test]
    fn degenerate_empty_and_non_finite_soups_are_not_closed() {
        let p = DVec3::ONE;
        assert!(!closed(&[]));
        assert!(!closed(&[[p, p, p]]));
        assert!(!closed(&[[DVec3::ZERO, p, DVec3::new(f64::NAN, 0.0, 0.0)]]));
        // Degenerate triangles are left out: the cube with a sliver stays closed.
        let mut c = cube();
        c.push([DVec3::ZERO, DVec3::ZERO, DVec3::X]);
        assert!(closed(&c) && brute_force(&c));
    }

    #[test]
    fn corners_within_the_snapping_grid_are_one_vertex() {
        // Seams within 1e-12 of the mesh's size weld; 1e-6 does not.
        for (shift, expect) in [(1e-12, true), (1e-6, false)] {
            let mut c = cube();
            c[0][0] += DVec3::splat(shift);
            assert_eq!(closed(&c), expect, "{shift}");
            assert_eq!(brute_force(&c), expect, "{shift}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]

        /// Cubes on a small lattice, touching (shared faces and edges are used four times)
        /// or apart (closed), with faces dropped and flipped at random, against the pairwise
        /// count.
        #[test]
        fn lattices_of_cubes_agree_with_the_pairwise_count(
            cells in prop::collection::vec((0..3i32, 0..2i32, 0..2i32), 1..4),
            spacing in 1..3i32,
            drop in prop::collection::vec(0..40usize, 0..3),
            flip in prop::collection::vec(0..40usize, 0..3),
        ) {
            let mut tris: Vec<[DVec3; 3]> = cells
                .iter()
                .flat_map(|&(x, y, z)| {
                    let o = DVec3::new(f64::from(x), f64::from(y), f64::from(z))
                        * f64::from(spacing);
                    cube().into_iter().map(move |t| t.map(|p| p + o))
                })
                .collect();
            for &f in &flip {
                let n = tris.len();
                tris[f % n].swap(1, 2);
            }
            for &d in &drop {
                let n = tris.len();
                if n > 1 {
                    tris.remove(d % n);
                }
            }
            let expect = brute_force(&tris);
            prop_assert_eq!(closed(&tris), expect);
        }
    }
}
