//! A uniform grid over the plate, so that a tip's neighbourhood (its sector, its next step)
//! is found without scanning every crack: each cell heads a linked list of items (segment or
//! tip indices) in caller words.

/// No item / end of a list.
pub(super) const NONE: u32 = u32::MAX;

/// A grid of `columns × rows` cells of side `cell` over [0, width] × [0, height].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Grid {
    pub(super) columns: usize,
    pub(super) rows: usize,
    pub(super) cell: f32,
}

impl Grid {
    /// The grid for a plate, with cells about `cell` wide (at most 256 × 256 cells).
    pub(super) fn new(width: f32, height: f32, cell: f32) -> Grid {
        let cell = cell.max(width / 256.0).max(height / 256.0).max(1.0);
        let columns = (libm::ceilf(width / cell) as usize).max(1);
        let rows = (libm::ceilf(height / cell) as usize).max(1);
        Grid { columns, rows, cell }
    }

    /// Number of cells.
    pub(super) const fn cells(&self) -> usize {
        self.columns * self.rows
    }

    /// The cell range (inclusive) covering [x0, x1] × [y0, y1], clamped to the grid.
    pub(super) fn span(&self, x0: f32, y0: f32, x1: f32, y1: f32) -> (usize, usize, usize, usize) {
        // `as` truncates towards zero and saturates (negative and NaN give 0): the floor of
        // v / cell clamped at 0, without calling floorf. Through u32, whose saturating
        // conversion is a few instructions shorter than a 64-bit one (the grid has at most 256
        // cells a side, so the clamp gives the same cell).
        let clamp = |v: f32, n: usize| ((v / self.cell) as u32 as usize).min(n - 1);
        (clamp(x0, self.columns), clamp(y0, self.rows), clamp(x1, self.columns), clamp(y1, self.rows))
    }
}

/// Items in cells: `heads[cell]` starts a list of entries, each entry `[item, next]` naming an
/// item and the entry after it (kept side by side, so that a walk reads one place per entry).
pub(super) struct Buckets<'a> {
    pub(super) heads: &'a mut [u32],
    pub(super) entries: &'a mut [[u32; 2]],
    pub(super) used: usize,
}

impl Buckets<'_> {
    /// Empties the cells from `first` up to `first + count` (those that exist; the others
    /// keep what they hold, so that a plate's grids are emptied a bounded chunk at a time);
    /// how many it emptied.
    pub(super) fn empty(&mut self, first: usize, count: usize) -> usize {
        let cells = self.heads.get_mut(first..).unwrap_or_default();
        let n = count.min(cells.len());
        cells[..n].fill(NONE);
        n
    }

    /// Adds `value` to `cell`; false when the entries are full.
    pub(super) fn insert(&mut self, cell: usize, value: u32) -> bool {
        if self.used == self.entries.len() {
            return false;
        }
        let entry = self.used;
        self.entries[entry] = [value, self.heads[cell]];
        self.heads[cell] = entry as u32;
        self.used += 1;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buckets_hold_items_per_cell_until_full() {
        let g = Grid::new(100.0, 50.0, 25.0);
        assert_eq!((g.columns, g.rows, g.cells()), (4, 2, 8));
        assert_eq!(g.span(-5.0, 10.0, 60.0, 80.0), (0, 0, 2, 1));
        let (mut heads, mut entries) = ([0u32; 8], [[0u32; 2]; 3]);
        let mut b = Buckets { heads: &mut heads, entries: &mut entries, used: 0 };
        // Emptied in chunks: up to the grid's last cell, and no further.
        assert_eq!((b.empty(0, 3), b.heads[2], b.heads[3]), (3, NONE, 0));
        assert_eq!((b.empty(3, 3), b.empty(6, 3), b.empty(8, 3), b.empty(9, 3)), (3, 2, 0, 0));
        assert!(b.heads.iter().all(|&h| h == NONE));
        assert!(b.insert(5, 10) && b.insert(5, 11) && b.insert(2, 12));
        assert!(!b.insert(1, 13));
        // Newest first.
        let mut seen = [0u32; 2];
        let (mut n, mut entry) = (0, b.heads[5]);
        while entry != NONE {
            let [item, next] = b.entries[entry as usize];
            seen[n] = item;
            n += 1;
            entry = next;
        }
        assert_eq!(seen, [11, 10]);
    }
}
