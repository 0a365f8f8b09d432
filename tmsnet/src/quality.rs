//! Quality measures: the (0,m,s)-net property by exhaustive counting, the exact 2D star
//! discrepancy and the minimum distance of a point set (Munkberg 2011, §5, Eq. 10).

use crate::error::{Error, low_mask};

/// The first elementary interval found holding more than one point (so another is empty).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NetViolation {
    /// The split `(l_1, ..., l_s)` with `sum l_i = m` (Eq. 10).
    pub split: Vec<u32>,
    /// The cell `(a_1, ..., a_s)` with `0 <= a_i < 2^{l_i}`.
    pub cell: Vec<u32>,
}

/// Exhaustive (0,m,s)-net check (Munkberg 2011, Eq. 10 with t = 0, b = 2): for every split
/// `l_1 + ... + l_s = m`, every elementary interval of volume 2^-m holds exactly one point.
/// Coordinates are m-bit integers (component i is `points[j][i] / 2^m`).
///
/// Returns `Ok(None)` for a net, `Ok(Some(violation))` otherwise, and
/// `Err(Error::BadPointSet)` unless there are exactly 2^m points with all coordinates below
/// 2^m, or `Err(Error::InvalidM)` unless `1 <= m <= 31`. Cost: `C(m+s-1, s-1) · 2^m`.
pub fn net_violation<const S: usize>(
    points: &[[u32; S]],
    m: u32,
) -> Result<Option<NetViolation>, Error> {
    crate::error::check_m(m)?;
    if S == 0
        || points.len() != 1usize << m
        || points.iter().flatten().any(|&c| c & !low_mask(m) != 0)
    {
        return Err(Error::BadPointSet);
    }
    let mut seen = vec![0u64; points.len().div_ceil(64)];
    let mut split = [0u32; S];
    let mut found = None;
    for_each_split(&mut split, 0, m, &mut |l| {
        if found.is_some() {
            return;
        }
        seen.iter_mut().for_each(|w| *w = 0);
        for p in points {
            // Concatenate the top l_i bits of each coordinate: a cell index in [0, 2^m).
            let cell = p.iter().zip(l).fold(0u64, |acc, (&c, &li)| {
                (acc << li) | u64::from(c >> (m - li))
            });
            let (word, bit) = ((cell / 64) as usize, cell % 64);
            if let Some(w) = seen.get_mut(word) {
                if *w >> bit & 1 == 1 {
                    found = Some(NetViolation {
                        split: l.to_vec(),
                        cell: p.iter().zip(l).map(|(&c, &li)| c >> (m - li)).collect(),
                    });
                    return;
                }
                *w |= 1 << bit;
            }
        }
    });
    Ok(found)
}

/// Calls `f` with every composition of `remaining` into the slots `split[i..]`.
fn for_each_split<const S: usize>(
    split: &mut [u32; S],
    i: usize,
    remaining: u32,
    f: &mut impl FnMut(&[u32; S]),
) {
    if i + 1 >= S {
        if let Some(last) = split.get_mut(i) {
            *last = remaining;
        }
        f(split);
        return;
    }
    for li in 0..=remaining {
        if let Some(slot) = split.get_mut(i) {
            *slot = li;
        }
        for_each_split(split, i + 1, remaining - li, f);
    }
}

/// Exact star discrepancy of a 2D point set in [0, 1)^2:
/// `D* = sup_{a,b} |#{p in [0,a) x [0,b)} / n - a b|`.
///
/// The supremum of `a b - count/n` is approached by open boxes with `a, b` in the point
/// coordinates or 1; that of `count/n - a b` by closed boxes with corners at point
/// coordinates. Both are swept in O(n · k) for k distinct y values (ties are handled), so
/// O(n^2) worst case. Errors with [`Error::BadPointSet`] for an empty set or a coordinate
/// outside [0, 1) (including NaN).
pub fn star_discrepancy(points: &[[f64; 2]]) -> Result<f64, Error> {
    if points.is_empty() || points.iter().flatten().any(|c| !(0.0..1.0).contains(c)) {
        return Err(Error::BadPointSet);
    }
    let n = points.len() as f64;
    let mut by_x: Vec<[f64; 2]> = points.to_vec();
    by_x.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let mut ys: Vec<f64> = points.iter().map(|p| p[1]).collect();
    ys.sort_by(f64::total_cmp);
    ys.dedup();
    let rank = |y: f64| ys.partition_point(|&v| v < y);
    // counts[r] = points so far whose y equals ys[r].
    let mut counts = vec![0u32; ys.len()];
    let mut worst = 0.0f64;
    let mut i = 0;
    while i <= by_x.len() {
        // a = next distinct x (or 1 after the last point).
        let a = by_x.get(i).map_or(1.0, |p| p[0]);
        // Open boxes [0, a) x [0, b): the points added so far all have x < a.
        let mut below = 0u32;
        for (&b, &c) in ys.iter().zip(&counts) {
            worst = worst.max(a * b - f64::from(below) / n);
            below += c;
        }
        worst = worst.max(a - f64::from(below) / n); // b = 1
        if i == by_x.len() {
            break;
        }
        // Add every point with x == a, then closed boxes [0, a] x [0, b].
        while let Some(p) = by_x.get(i).filter(|p| p[0] == a) {
            if let Some(c) = counts.get_mut(rank(p[1])) {
                *c += 1;
            }
            i += 1;
        }
        let mut upto = 0u32;
        for (&b, &c) in ys.iter().zip(&counts) {
            upto += c;
            worst = worst.max(f64::from(upto) / n - a * b);
        }
    }
    Ok(worst)
}

/// Minimum Euclidean distance between two points of the set, on the unit torus when
/// `toroidal` (distances wrap around 1) — a common sample-quality figure (Munkberg 2011, §5
/// mentions larger minimum distance as the goal of a search). O(n^2). Errors with
/// [`Error::BadPointSet`] for fewer than two points or non-finite coordinates.
pub fn min_distance(points: &[[f64; 2]], toroidal: bool) -> Result<f64, Error> {
    if points.len() < 2 || points.iter().flatten().any(|c| !c.is_finite()) {
        return Err(Error::BadPointSet);
    }
    let wrap = |d: f64| {
        let d = d.abs();
        if toroidal { d.min((1.0 - d).abs()) } else { d }
    };
    let mut best = f64::INFINITY;
    for (i, p) in points.iter().enumerate() {
        for q in points.iter().skip(i + 1) {
            best = best.min(wrap(p[0] - q[0]).hypot(wrap(p[1] - q[1])));
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_point_discrepancy() {
        // One point at (a, b): sup is max(1 - a b (closed box at the point), and the open
        // box [0,1) x [0,1) misses nothing); for (0.5, 0.5): max(1 - 0.25, a*1 - 0 with a =
        // 0.5 (box [0,0.5) x [0,1) is empty)) = 0.75.
        assert_eq!(star_discrepancy(&[[0.5, 0.5]]).unwrap(), 0.75);
        assert_eq!(star_discrepancy(&[[0.0, 0.0]]).unwrap(), 1.0);
    }

    #[test]
    fn rejects_bad_input() {
        assert!(star_discrepancy(&[]).is_err());
        assert!(star_discrepancy(&[[1.0, 0.0]]).is_err());
        assert!(star_discrepancy(&[[f64::NAN, 0.0]]).is_err());
        assert!(min_distance(&[[0.0, 0.0]], false).is_err());
        assert!(net_violation(&[[0u32, 0]], 1).is_err());
        assert!(net_violation(&[[0u32, 0], [2, 1]], 1).is_err());
    }

    #[test]
    fn finds_violation_in_a_diagonal() {
        // The diagonal (j, j) for m = 2: split (1, 1) puts j = 0, 1 both in cell (0, 0).
        let pts: Vec<[u32; 2]> = (0..4).map(|j| [j, j]).collect();
        let v = net_violation(&pts, 2).unwrap().unwrap();
        assert_eq!(v.split, vec![1, 1]);
    }

    #[test]
    fn toroidal_distance_wraps() {
        let p = [[0.05, 0.5], [0.95, 0.5]];
        assert!((min_distance(&p, true).unwrap() - 0.1).abs() < 1e-12);
        assert!((min_distance(&p, false).unwrap() - 0.9).abs() < 1e-12);
    }
}
