//! A resumable walk over the items filed in a range of grid cells: the queries of a tip update
//! (its sector's tips and segments, the segments along its move) look at one cell or one entry
//! per unit of work, and stop between any two when [`Glass::step`]'s budget is spent, to go on
//! from there at the next call.

use super::Glass;
use super::grid::NONE;

/// Which of the plate's grids a scan reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Filed {
    /// The growing tips of the time step, by crack.
    Tips,
    /// The crack segments, by edge; each is visited once per scan, however many cells it is in.
    Segments,
    /// The crack segments as F2 reads them: as [`Filed::Segments`], but a cell's entries for
    /// segments grown in the time step under way, which F2 passes over by their time, are
    /// skipped unseen where they lead its list (`SpatialIndex::earlier`).
    Earlier,
}

/// Where a scan of the cells `cells` (inclusive, as [`super::grid::Grid::span`] gives them)
/// stands: the cell at (`cx`, `cy`), and the next entry of its list to visit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Scan {
    cells: (usize, usize, usize, usize),
    cx: usize,
    cy: usize,
    /// The cell has been looked at (and `entry` is the next of its entries, NONE past the last).
    entered: bool,
    entry: u32,
}

impl Scan {
    /// A scan over `cells`, not yet started.
    pub(super) const fn new(cells: (usize, usize, usize, usize)) -> Scan {
        Scan { cells, cx: cells.0, cy: cells.1, entered: false, entry: NONE }
    }

    /// The cells it scans.
    pub(super) const fn cells(&self) -> (usize, usize, usize, usize) {
        self.cells
    }
}

impl Glass<'_> {
    /// Starts a scan of `filed` over `cells`: a segment scan takes a fresh stamp, so that it
    /// visits each segment once.
    pub(super) fn start_scan(&mut self, filed: Filed, cells: (usize, usize, usize, usize)) -> Scan {
        if filed != Filed::Tips {
            self.index.stamp = self.index.stamp.wrapping_add(1);
            if self.index.stamp == 0 {
                // The stamps start over (every 2³² − 1 scans): those of the edges so far are
                // reset; an edge added later gets its own when it is added.
                self.index.stamps[..self.edge_count].fill(0);
                self.index.stamp = 1;
            }
        }
        Scan::new(cells)
    }

    /// Goes on with `scan` of the tips ([`Filed::Tips`]: `SEGMENTS` and `EARLIER` false), of the
    /// segments ([`Filed::Segments`]: `SEGMENTS`) or of the segments as F2 reads them
    /// ([`Filed::Earlier`]: both), as [`Self::start_scan`] started it, until it has
    /// visited every entry of its cells (true) or the work reaches `deadline` (false; the next
    /// call goes on from there). One unit per cell looked at and per entry passed: a cell for
    /// which `skip(cx, cy)` holds (one wholly outside a tip's sector) or that is empty is
    /// passed over after its unit; `visit` gets every item of the others (a segment once per
    /// scan). An item for which `near` does not hold is passed over before that (`near` is a
    /// pure test of the item, such as its box against the query's: a segment it fails in one
    /// cell fails it in every other, so it need not be marked as seen).
    ///
    /// The scans and their visitors are inlined into the update on 64-bit targets (out of
    /// line, generation took 1.30 times the instructions of the inlined build); on 32-bit ones
    /// the compiler decides, as the 256 KiB of flash of `targets/run`'s Cortex-M3 has no room
    /// for three inlined copies.
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    pub(super) fn go_on<const SEGMENTS: bool, const EARLIER: bool>(
        &mut self,
        scan: &mut Scan,
        deadline: u64,
        skip: impl FnMut(usize, usize) -> bool,
        near: impl Fn(&Self, u32) -> bool,
        visit: impl FnMut(&Self, u32),
    ) -> bool {
        // A scan that cannot reach the deadline, whatever its cells hold: it looks at each of
        // its cells left once and passes each filed entry at most once (an entry is in one
        // cell's list), so it runs without a check per unit, by plain loops over the rows and
        // cells ([`Self::go_on_whole`]). Same units, same visits. On 64-bit targets only: the
        // Cortex-M3's flash has no room for the second copy.
        let (cx0, _, cx1, cy1) = scan.cells;
        let cells = (cy1 + 1).saturating_sub(scan.cy).saturating_mul((cx1 + 1).saturating_sub(cx0));
        let filed = if SEGMENTS { self.index.segments.used } else { self.index.tips.used };
        let far = cfg!(target_pointer_width = "64")
            && deadline.saturating_sub(self.clock.work) > (cells as u64).saturating_add(filed as u64);
        if far {
            self.go_on_in::<SEGMENTS, EARLIER, false>(scan, deadline, skip, near, visit)
        } else {
            self.go_on_in::<SEGMENTS, EARLIER, true>(scan, deadline, skip, near, visit)
        }
    }

    /// The first entry of segment cell `cell` that F2 looks at, for a cell with entries filed
    /// in the time step under way (`SpatialIndex::earlier`). Out of line, so that the entry
    /// loops it leads to keep their registers.
    #[inline(never)]
    pub(super) fn earlier(&self, cell: usize) -> u32 {
        self.index.earlier[cell]
    }

    /// [`Self::go_on`] over the segments (`SEGMENTS`; from the entries F2 reads, `EARLIER`) or
    /// the tips, checking the deadline before every unit (`BUDGETED`) or not (a scan
    /// [`Self::go_on`] found cannot reach it: [`Self::go_on_whole`]). The budgeted loop walks a
    /// cell's entries itself rather than through a budgeted [`Self::entries`]: with that,
    /// generation took about 1 % more instructions, the scans that never reach their deadline
    /// included.
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    fn go_on_in<const SEGMENTS: bool, const EARLIER: bool, const BUDGETED: bool>(
        &mut self,
        scan: &mut Scan,
        deadline: u64,
        mut skip: impl FnMut(usize, usize) -> bool,
        near: impl Fn(&Self, u32) -> bool,
        mut visit: impl FnMut(&Self, u32),
    ) -> bool {
        let (cx0, _, cx1, cy1) = scan.cells;
        if cx0 > cx1 {
            return true; // no cells (a range the grid's span never gives)
        }
        if !BUDGETED {
            self.go_on_whole::<SEGMENTS, EARLIER>(scan, skip, near, visit);
            return true;
        }
        let columns = self.index.grid.columns;
        let mut work = self.clock.work;
        let (mut cx, mut cy, mut entered, mut entry) = (scan.cx, scan.cy, scan.entered, scan.entry);
        let over = 'scan: loop {
            if entered {
                // The entries of the cell looked at, a unit each.
                while entry != NONE {
                    if BUDGETED && work >= deadline {
                        break 'scan false;
                    }
                    work += 1;
                    let buckets = if SEGMENTS { &self.index.segments } else { &self.index.tips };
                    let [item, next] = buckets.entries[entry as usize];
                    entry = next;
                    self.pass::<SEGMENTS>(item, &near, &mut visit);
                }
                entered = false;
                if cx < cx1 {
                    cx += 1;
                } else {
                    cx = cx0;
                    cy += 1;
                }
            }
            if cy > cy1 {
                break true;
            }
            // The next cell, a unit.
            if BUDGETED && work >= deadline {
                break false;
            }
            work += 1;
            let heads = if SEGMENTS { &self.index.segments.heads } else { &self.index.tips.heads };
            let cell = cy * columns + cx;
            let head = heads[cell];
            entered = true;
            entry = if head == NONE || skip(cx, cy) {
                NONE
            } else if EARLIER && head >= self.index.fresh {
                self.earlier(cell)
            } else {
                head
            };
        };
        (scan.cx, scan.cy, scan.entered, scan.entry) = (cx, cy, entered, entry);
        self.clock.work = work;
        over
    }

    /// [`Self::go_on`] to the end, for a scan that cannot reach its deadline: the same units
    /// and visits as [`Self::go_on_in`], by plain loops over the rows and cells left.
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    fn go_on_whole<const SEGMENTS: bool, const EARLIER: bool>(
        &mut self,
        scan: &mut Scan,
        mut skip: impl FnMut(usize, usize) -> bool,
        near: impl Fn(&Self, u32) -> bool,
        mut visit: impl FnMut(&Self, u32),
    ) {
        let (cx0, _, cx1, cy1) = scan.cells;
        let columns = self.index.grid.columns;
        let (mut cx, mut cy) = (scan.cx, scan.cy);
        let mut work = self.clock.work;
        if scan.entered {
            // The rest of the cell looked at.
            self.entries::<SEGMENTS>(scan.entry, &mut work, &near, &mut visit);
            if cx < cx1 {
                cx += 1;
            } else {
                cx = cx0;
                cy += 1;
            }
        }
        while cy <= cy1 {
            let row = cy * columns;
            while cx <= cx1 {
                work += 1;
                let heads = if SEGMENTS { &self.index.segments.heads } else { &self.index.tips.heads };
                let head = heads[row + cx];
                if head != NONE && !skip(cx, cy) {
                    let entry = if EARLIER && head >= self.index.fresh { self.earlier(row + cx) } else { head };
                    self.entries::<SEGMENTS>(entry, &mut work, &near, &mut visit);
                }
                cx += 1;
            }
            cx = cx0;
            cy += 1;
        }
        (scan.cx, scan.cy, scan.entered, scan.entry) = (cx0, cy1 + 1, false, NONE);
        self.clock.work = work;
    }

    /// Visits the entries of a cell's list from `entry` on, a unit of `work` each, as
    /// [`Self::go_on_in`] does with no deadline.
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    fn entries<const SEGMENTS: bool>(
        &mut self,
        mut entry: u32,
        work: &mut u64,
        near: &impl Fn(&Self, u32) -> bool,
        visit: &mut impl FnMut(&Self, u32),
    ) {
        while entry != NONE {
            *work += 1;
            let buckets = if SEGMENTS { &self.index.segments } else { &self.index.tips };
            let [item, next] = buckets.entries[entry as usize];
            entry = next;
            self.pass::<SEGMENTS>(item, near, visit);
        }
    }

    /// Passes an entry's item to `visit`, unless `near` does not hold for it or (a segment) the
    /// scan has visited it already.
    #[inline(always)]
    fn pass<const SEGMENTS: bool>(
        &mut self,
        item: u32,
        near: &impl Fn(&Self, u32) -> bool,
        visit: &mut impl FnMut(&Self, u32),
    ) {
        if !near(self, item) {
            return;
        }
        if SEGMENTS {
            if self.index.stamps[item as usize] == self.index.stamp {
                return;
            }
            self.index.stamps[item as usize] = self.index.stamp;
        }
        visit(self, item);
    }
}
