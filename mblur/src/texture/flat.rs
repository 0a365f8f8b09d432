//! Flat regions of a texture: per bilinear cell, how far around it the texture keeps one
//! colour, so that the exact segment average ([`super::Texture::segment_average`]) crosses
//! a flat region in one step instead of one per cell.
//!
//! Cell (x, y) is the square between texel centres (x, y) and (x + 1, y + 1) (wrapped),
//! where the bilinear blend mixes those four texels; it is flat when the four are equal,
//! and then the texture is that colour everywhere in it. Two flat cells that touch share a
//! texel, so a connected group of flat cells has one colour: a box of flat cells is a box
//! of constant colour.

/// Largest radius recorded: a segment inside a flat region steps at most this many cells
/// from the cell it is in (so building the map costs at most this many probes per cell).
pub(super) const MAX_RADIUS: u8 = 16;

/// Per cell of a texture, row-major, its flat radius: 0 when the cell is not flat, else
/// the largest r <= [`MAX_RADIUS`] such that every cell (x', y') with |x' - x| < r and
/// |y' - y| < r is flat and inside the texture (the box does not wrap, so it is a lower
/// bound near the edges).
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct FlatCells {
    /// Cells per row (the texture's width).
    width: usize,
    /// The radii, `width` per row; empty when the texture has no map.
    radius: Vec<u8>,
}

impl FlatCells {
    /// The map of a `width` x `height` texture whose cell (x, y) (x, y in range) is flat
    /// when `flat(x, y)`.
    pub(super) fn new(width: u32, height: u32, flat: impl Fn(usize, usize) -> bool) -> Self {
        let (w, h) = (width as usize, height as usize);
        // Side of the largest square of flat cells whose bottom-right cell is (x, y), the
        // classic dynamic programme, capped (2 MAX_RADIUS - 1 is the most a radius uses).
        let cap = 2 * usize::from(MAX_RADIUS) - 1;
        let mut side = vec![0u8; w * h];
        for y in 0..h {
            for x in 0..w {
                if !flat(x, y) {
                    continue;
                }
                let s = if x == 0 || y == 0 {
                    1
                } else {
                    let up = side[(y - 1) * w + x];
                    let left = side[y * w + x - 1];
                    let diag = side[(y - 1) * w + x - 1];
                    usize::from(up.min(left).min(diag)) + 1
                };
                side[y * w + x] = s.min(cap) as u8;
            }
        }
        // The box of radius r around (x, y) is flat iff the square ending at its
        // bottom-right cell (x + r - 1, y + r - 1) has a side of at least 2 r - 1; that
        // holds for every r up to the radius and for none beyond.
        let mut radius = vec![0u8; w * h];
        for y in 0..h {
            for x in 0..w {
                let mut r = 0;
                while r < usize::from(MAX_RADIUS) {
                    let (cx, cy) = (x + r, y + r);
                    if cx >= w || cy >= h || usize::from(side[cy * w + cx]) < 2 * r + 1 {
                        break;
                    }
                    r += 1;
                }
                radius[y * w + x] = r as u8;
            }
        }
        FlatCells { width: w, radius }
    }

    /// The flat radius of cell (x, y), indices inside the texture; `None` without a map.
    #[inline(always)]
    pub(super) fn radius(&self, x: i64, y: i64) -> Option<u8> {
        self.radius
            .get(y as usize * self.width + x as usize)
            .copied()
    }

    /// Bytes the map occupies.
    pub(super) fn bytes(&self) -> usize {
        self.radius.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The radius by definition: grow the box until a cell in it is not flat or it leaves
    /// the texture.
    fn brute_radius(
        w: usize,
        h: usize,
        flat: &dyn Fn(usize, usize) -> bool,
        x: usize,
        y: usize,
    ) -> u8 {
        let mut r = 0usize;
        'grow: while r < usize::from(MAX_RADIUS) {
            let next = r + 1;
            for cy in y as i64 - next as i64 + 1..y as i64 + next as i64 {
                for cx in x as i64 - next as i64 + 1..x as i64 + next as i64 {
                    let inside = cx >= 0 && cy >= 0 && (cx as usize) < w && (cy as usize) < h;
                    if !inside || !flat(cx as usize, cy as usize) {
                        break 'grow;
                    }
                }
            }
            r = next;
        }
        r as u8
    }

    #[test]
    fn radii_match_growing_boxes_cell_by_cell() {
        // Random flat patterns of several densities and sizes (one all flat, reaching the
        // cap), against growing each box cell by cell.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for (w, h, per_mille) in [
            (1, 1, 1000),
            (7, 5, 900),
            (40, 33, 970),
            (64, 64, 1000),
            (13, 29, 500),
        ] {
            let cells: Vec<bool> = (0..w * h).map(|_| next() % 1000 < per_mille).collect();
            let flat = |x: usize, y: usize| cells[y * w + x];
            let map = FlatCells::new(w as u32, h as u32, flat);
            for y in 0..h {
                for x in 0..w {
                    let want = brute_radius(w, h, &flat, x, y);
                    assert_eq!(
                        map.radius(x as i64, y as i64),
                        Some(want),
                        "{w}x{h} cell ({x}, {y})"
                    );
                }
            }
        }
        assert_eq!(FlatCells::default().radius(0, 0), None);
    }
}
