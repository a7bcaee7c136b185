//! Growth by the sector rule (Agui et al. §4.2.2, Eqs. 12–19) and the stop rules (§4.2.3).
//!
//! A time step is done in phases ([`Phase`]), and a tip's update in stages ([`Stage`]): F1's
//! scan of the tips in its sector, F2's scan of the segments there, the move planned (the
//! forces summed, F3 drawn, the turn), the scan of the segments along the move, the move made,
//! and stop condition 2's face walks when it closed a cycle. [`Glass::step`] may stop between
//! any two units of work of these (frame budgets); what an update has summed so far is kept in
//! [`Update`], and nothing it reads changes until it is over, so a budgeted run is the same
//! bit for bit as one call.

use super::faces::{Enclosure, HalfEdge};
use super::grid::NONE;
use super::scan::{Filed, Scan};
use super::{CrackEnd, CrackKind, Edge, Glass, GlassProgress, ceil, wrap};
use crate::geom::{Intersection, Point, Segment};

/// The longest update \[px\]: a time step is cut into equal updates (dt) no longer than
/// this, the length the paper measured its cracks' turning over (Fig. 5), so that a tip turns
/// (Eqs. 12–16) at least every 10 px whatever its speed.
pub(super) const UPDATE_LENGTH: f32 = 10.0;

/// An update is cut to this share of the distance to the nearest crack or edge in S that the
/// tip is closing in on, so that F2 turns it several times before it meets it (rule 8).
const APPROACH_SHARE: f32 = 0.25;

/// The shortest update \[px\] near a crack or edge the tip heads at squarely; shorter, down
/// to MIN_SQUARENESS of it, the more shallowly it heads at it.
const MIN_UPDATE: f32 = 0.5;

/// The least share of MIN_UPDATE an update near a crack covers.
const MIN_SQUARENESS: f32 = 0.25;

/// The cosine (20°) between a radial crack's heading and the normal of the crack or edge it
/// closes in on above which its update is not cut: a tip heading that squarely at it already
/// meets it at nearly a right angle, and the short updates would only slow it (rule 8's figures
/// stay: a median meeting angle of 79.0° over seeds 0–99, against 82.4° with every approach cut,
/// for 17.5 % fewer instructions). A ring crack's updates are always cut near a crack: without
/// it 1 of 990 ring cracks (seeds 0–99) turned 2° less than the arc it spans (rule 5).
const SQUARE: f32 = 0.94;

/// A margin \[px\] on the distance bounds that let a sector query skip a segment: larger than
/// the rounding of a distance on the plate (about 1e-4 px at 640 px, and positions are 1/256 px
/// apart or closer on the largest plate, 65536 px), so that a skipped segment is one whose
/// computed distance could not have passed the bound.
const SLACK: f32 = 1.0 / 64.0;

/// The box (x0, y0, x1, y1) of the segment `a`–`z`, its ends' coordinates sorted by plain
/// comparisons (for the finite coordinates of the plate, what `min` and `max` give, without
/// their NaN handling).
#[inline(always)]
fn span_of(a: [f32; 2], z: [f32; 2]) -> [f32; 4] {
    let (lx, hx) = if a[0] <= z[0] { (a[0], z[0]) } else { (z[0], a[0]) };
    let (ly, hy) = if a[1] <= z[1] { (a[1], z[1]) } else { (z[1], a[1]) };
    [lx, ly, hx, hy]
}

/// Whether the segment `a`–`z` and the box `bounds` (x0, y0, x1, y1) are apart: both ends
/// beyond one side of the box. The very comparisons of the segment's box ([`span_of`]) with
/// it, as its low and high ends are two of the ends' coordinates (for the plate's finite
/// coordinates).
#[inline(always)]
fn apart(a: [f32; 2], z: [f32; 2], bounds: [f32; 4]) -> bool {
    let [x0, y0, x1, y1] = bounds;
    (a[0] < x0 && z[0] < x0) || (a[0] > x1 && z[0] > x1) || (a[1] < y0 && z[1] < y0) || (a[1] > y1 && z[1] > y1)
}

/// The most work one piece of growth does, in [`Glass::step`]'s units: a step of the two face
/// walks of stop condition 2 in lockstep (2); every other piece is one unit. A call does at
/// most max(budget, 1) − 1 + this.
pub const STEP_PIECE: u64 = 2;

/// Grid cells emptied per unit of [`Phase::Clear`].
pub(super) const CLEAR_CHUNK: usize = 64;

const _: () = assert!(CLEAR_CHUNK == 64, "the docs of Glass::step and hibi_glass_step say 64 cells a unit");

/// What a step ran into.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Hit {
    /// Nothing: the tip moves the whole step.
    Nothing,
    /// The plate's edge, at this point.
    Edge([f32; 2]),
    /// Segment `edge`, at this point and parameter along the step.
    Crack { edge: u32, at: [f32; 2], along: f32 },
}

/// What the time step under way is doing ([`Glass::step`] resumes it between any two units of
/// work).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Phase {
    /// A new plate's first units: emptying the cells of the segment grid, then of the tip
    /// grid, [`CLEAR_CHUNK`] cells a unit (`Clock::done` cells so far), so that creation does
    /// no work that grows with the plate. Nothing reads the grids before it is over.
    Clear,
    /// Taking the tips of the last time step out of the tip grid, one a unit.
    Unfile,
    /// Filing the growing tips where they start this time step, one crack a unit.
    File,
    /// Advancing the cracks in order (`Clock::cursor`), each by its updates.
    Advance,
    /// An update of the crack at the cursor is under way: [`Update::stage`].
    Update,
    /// The time step is over: looking for a large or ring crack of the impact still growing,
    /// one crack a unit.
    Settle,
}

/// Where the update of a tip under way stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Stage {
    /// F1: the tips in its sector (and F2 in the same walk of its cells, when the budget cannot
    /// run out in it: [`Glass::sum_forces`]).
    Tips,
    /// F2: the segments in its sector.
    Segments,
    /// The move: the segments along it.
    Path,
    /// Stop condition 2: the walks around the faces its stop split (faces.rs).
    Enclose,
}

/// The F2 entries of an update: past this many cracks in S, the rest each pull on their own.
const NEAR: usize = 16;

/// Where a tip sums F2 from: its crack, where it is, and its sector S (heading, boundary rays,
/// box).
#[derive(Clone, Copy)]
struct Sight {
    crack: u32,
    w: [f32; 2],
    direction: [f32; 2],
    rays: [[f32; 2]; 2],
    bounds: [f32; 4],
}

/// F2 summed so far: per crack in S, its nearest point's distance and normal (`count` of
/// them), and the pulls of the cracks past NEAR.
#[derive(Clone, Copy, Debug)]
struct Sums {
    near: [(u32, f32, [f32; 2]); NEAR],
    count: usize,
    extra: [f32; 2],
}

impl Sums {
    const EMPTY: Sums = Sums { near: [(NONE, 0.0, [0.0; 2]); NEAR], count: 0, extra: [0.0; 2] };
}

/// The state of one tip update (Eqs. 12–17) between the calls of [`Glass::step`] that carry it
/// out: what it set out from, the forces summed so far, and the move.
#[derive(Clone, Copy, Debug)]
pub(super) struct Update {
    pub(super) stage: Stage,
    /// The scan of the grid under way.
    scan: Scan,
    /// What is left of the crack's time step, and what of it is done \[px\].
    left: f32,
    done: f32,
    ring: bool,
    /// The crack's course (Eq. 13) and its direction, the sector's boundary rays and box.
    course: f32,
    direction: [f32; 2],
    rays: [[f32; 2]; 2],
    bounds: [f32; 4],
    /// F1 + F2 so far.
    force: [f32; 2],
    /// F2 so far.
    sums: Sums,
    /// The move: its heading and length, where it ends, and the first crack or edge it meets.
    heading: f32,
    length: f32,
    next: [f32; 2],
    hit: (Hit, f32),
    found: (u32, f32, [f32; 2]),
    /// The move stopped the tip (on a crack or the edge, or by running out of capacity).
    pub(super) stopped: bool,
    /// The face walks of stop condition 2.
    pub(super) enclosure: Enclosure,
}

impl Update {
    /// No update under way.
    pub(super) const IDLE: Update = Update {
        stage: Stage::Tips,
        scan: Scan::new((0, 0, 0, 0)),
        left: 0.0,
        done: 0.0,
        ring: false,
        course: 0.0,
        direction: [0.0; 2],
        rays: [[0.0; 2]; 2],
        bounds: [0.0; 4],
        force: [0.0; 2],
        sums: Sums::EMPTY,
        heading: 0.0,
        length: 0.0,
        next: [0.0; 2],
        hit: (Hit::Nothing, 1.0),
        found: (NONE, 1.0, [0.0; 2]),
        stopped: false,
        enclosure: Enclosure::IDLE,
    };
}

impl Glass<'_> {
    /// Grows every crack of the current impact to its end.
    pub fn run(&mut self) -> GlassProgress {
        self.step(u64::MAX)
    }

    /// Advances growth by `budget` units of work (at least one). A unit is a grid cell or a
    /// grid entry (a segment or a tip) examined by a distance or crossing query, a crack looked
    /// at (by the step loop, the filing of the tips, the check at the end of a time step and
    /// stop condition 2), a step of a face walk of stop condition 2, or 64 grid cells emptied
    /// (a new plate's first units, at most 2 · 65 536 cells in all, which [`Glass::new`] leaves
    /// to this call so that creation does no work that grows with the plate or the
    /// capacities). The budget is checked before every unit, and the rest of an
    /// update (its forces summed, its move made) is a few units, so a call overruns it by less
    /// than [`STEP_PIECE`] units, whatever the parameters (speeds, forces, sector, plate size);
    /// generation resumes exactly where it stopped, so the result does not depend on the
    /// budgets. A time step moves every growing tip once, in crack order, each by |v| in
    /// updates of at most 10 px.
    pub fn step(&mut self, budget: u64) -> GlassProgress {
        let deadline = self.clock.work.saturating_add(budget.max(1));
        while !self.clock.finished && self.clock.work < deadline {
            match self.clock.phase {
                Phase::Clear => self.clear_cells(),
                Phase::Unfile => self.unfile_tip(),
                Phase::File => self.file_tip(),
                Phase::Advance => {
                    if self.clock.cursor < self.crack_count {
                        self.clock.work += 1;
                        let c = self.cracks[self.clock.cursor];
                        if c.growing() && self.clock.time >= c.wake {
                            self.clock.awake = true;
                            let update = self.begin_update(self.clock.cursor);
                            self.go_on_update(update, deadline);
                        } else {
                            if c.growing() {
                                self.clock.next_wake = self.clock.next_wake.min(c.wake);
                            }
                            self.clock.cursor += 1;
                        }
                    } else {
                        self.clock.cursor = 0;
                        self.clock.time += 1;
                        self.clock.phase = Phase::Settle;
                        self.clock.done = 0;
                    }
                }
                Phase::Update => self.go_on_update(self.clock.update, deadline),
                Phase::Settle => self.settle(),
            }
        }
        self.progress()
    }

    /// One unit of emptying a new plate's grids: the next [`CLEAR_CHUNK`] cells of the segment
    /// grid, then of the tip grid. Then the first time step begins.
    fn clear_cells(&mut self) {
        let k = self.clock.done;
        let cells = self.index.grid.cells();
        if k < 2 * cells {
            self.clock.work += 1;
            self.clock.done += if k < cells {
                self.index.segments.empty(k, CLEAR_CHUNK)
            } else {
                self.index.tips.empty(k - cells, CLEAR_CHUNK)
            };
        } else {
            self.clock.phase = Phase::Unfile;
            self.clock.done = 0;
        }
    }

    /// One unit of taking the last time step's tips out of the tip grid: the cell of the next
    /// filed tip is emptied (a tip was filed where its crack's `before` is). Then filing.
    fn unfile_tip(&mut self) {
        let k = self.clock.done;
        if k < self.index.tips.used {
            self.clock.work += 1;
            let crack = self.index.tips.entries[k][0] as usize;
            let at = self.cracks[crack].before;
            let (cx, cy, _, _) = self.index.grid.span(at[0], at[1], at[0], at[1]);
            self.index.tips.heads[cy * self.index.grid.columns + cx] = NONE;
            self.clock.done += 1;
        } else {
            self.index.tips.used = 0;
            self.clock.phase = Phase::File;
            self.clock.done = 0;
        }
    }

    /// One unit of filing the tips: if the next crack grows, its tip and direction at the start
    /// of the time step are kept (what other tips' F1 sees) and its tip is filed. A stopped
    /// crack's are read no more. Then the cracks advance; the plate finishes if the tip grid is
    /// full.
    fn file_tip(&mut self) {
        let i = self.clock.done;
        if i == self.crack_count {
            // The segments filed from here on are this time step's (`SpatialIndex::earlier`).
            self.index.fresh = self.index.segments.used as u32;
            self.clock.phase = Phase::Advance;
            self.clock.done = 0;
            self.clock.awake = false;
            self.clock.next_wake = u32::MAX;
            return;
        }
        self.clock.work += 1;
        let c = &mut self.cracks[i];
        if c.growing() {
            c.before = c.tip;
            c.before_direction = [libm::cosf(c.heading), libm::sinf(c.heading)];
            let c = *c;
            let (cx, cy, _, _) = self.index.grid.span(c.tip[0], c.tip[1], c.tip[0], c.tip[1]);
            if !self.index.tips.insert(cy * self.index.grid.columns + cx, i as u32) {
                self.clock.capacity_reached = true;
                self.finish();
                return;
            }
        }
        self.clock.done += 1;
    }

    /// One unit of the check at the end of a time step: generation ends when every large and
    /// ring crack of this impact has stopped (or at the time limit); else the next time step
    /// begins. When no crack was awake to grow in the step just done, every step until the
    /// next crack wakes would do the same nothing (no crack moves, no random draw is made):
    /// the clock goes straight to that step, or to the time limit if it comes first.
    fn settle(&mut self) {
        let impact = self.impacts - 1;
        let i = self.clock.done;
        if i < self.crack_count {
            self.clock.work += 1;
            let c = &self.cracks[i];
            if c.growing() && c.impact == impact && !c.is(CrackKind::Radial) {
                // A crack still drives growth: the next time step, unless time is up.
                self.clock.done = self.crack_count + 1;
            } else {
                self.clock.done += 1;
            }
            return;
        }
        if i != self.crack_count && !self.clock.awake {
            self.clock.time = self.clock.time.max(self.clock.next_wake.min(self.clock.time_limit));
        }
        if i == self.crack_count || self.clock.time >= self.clock.time_limit {
            self.finish();
        } else {
            self.clock.phase = Phase::Unfile;
            self.clock.done = 0;
        }
    }

    /// Whether `point` lies in the sector S ahead of a tip at `w` heading `direction`
    /// (angle φ, radius B), and its offset from `w` and distance.
    fn in_sector(&self, w: [f32; 2], direction: [f32; 2], point: [f32; 2]) -> Option<([f32; 2], f32)> {
        let e = [point[0] - w[0], point[1] - w[1]];
        let distance = crate::scalar::sqrtf(e[0] * e[0] + e[1] * e[1]);
        if distance == 0.0 || distance > self.params.sector_radius {
            return None;
        }
        let cosine = (e[0] * direction[0] + e[1] * direction[1]) / distance;
        (cosine >= self.sector.cosine).then_some((e, distance))
    }

    /// The bounding box (x0, y0, x1, y1) of the sector S ahead of a tip at `w` heading
    /// `direction`: its apex, the ends of its arc, and the arc's extremes along the axes that
    /// fall inside it.
    fn sector_box(&self, w: [f32; 2], direction: [f32; 2]) -> [f32; 4] {
        let b = self.params.sector_radius;
        let (c, s) = (self.sector.cosine, self.sector.sine);
        let mut bounds = [w[0], w[1], w[0], w[1]];
        let mut include = |d: [f32; 2]| {
            let q = [w[0] + b * d[0], w[1] + b * d[1]];
            bounds = [bounds[0].min(q[0]), bounds[1].min(q[1]), bounds[2].max(q[0]), bounds[3].max(q[1])];
        };
        let [dx, dy] = direction;
        include([dx * c - dy * s, dx * s + dy * c]);
        include([dx * c + dy * s, -dx * s + dy * c]);
        for axis in [[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]] {
            if axis[0] * dx + axis[1] * dy >= c {
                include(axis);
            }
        }
        bounds
    }

    /// The cell tests for the sector S of a tip at `w` whose wedge's boundary rays are `rays`
    /// ([`Self::wedge`]), with `margin` \[px\] of slack.
    fn sector_cells(&self, w: [f32; 2], rays: [[f32; 2]; 2], margin: f32) -> SectorCells {
        let reach = self.params.sector_radius + margin;
        SectorCells {
            w,
            rays,
            cell: self.index.grid.cell,
            reach2: reach * reach,
            wedge: self.sector.cosine >= 0.0,
            margin,
        }
    }

    /// The unit directions of the left and right boundary rays of the sector S of a tip
    /// heading `direction` (its heading turned by ±φ/2).
    fn wedge(&self, direction: [f32; 2]) -> [[f32; 2]; 2] {
        let (c, s) = (self.sector.cosine, self.sector.sine);
        let [dx, dy] = direction;
        [[dx * c - dy * s, dx * s + dy * c], [dx * c + dy * s, -dx * s + dy * c]]
    }

    /// The endpoints of edge `e`.
    fn edge_points(&self, e: u32) -> ([f32; 2], [f32; 2]) {
        let ends = self.edges[e as usize].ends;
        ([ends[0], ends[1]], [ends[2], ends[3]])
    }

    /// The point of segment `a`–`z` inside the sector S ahead of a tip at `w` heading
    /// `direction` that is nearest the tip: its offset from `w` and its distance (the paper's
    /// "shortest distance" from the tip to a crack or edge in S). The segment is clipped to the
    /// sector's wedge first, so a crack that only crosses a corner of S is seen there. `rays`
    /// is [`Self::wedge`] of `direction`.
    #[inline(always)]
    fn nearest_in_sector(
        &self,
        w: [f32; 2],
        direction: [f32; 2],
        rays: [[f32; 2]; 2],
        a: [f32; 2],
        z: [f32; 2],
    ) -> Option<([f32; 2], f32)> {
        let c = self.sector.cosine;
        let (ea, ez) = ([a[0] - w[0], a[1] - w[1]], [z[0] - w[0], z[1] - w[1]]);
        let d = [ez[0] - ea[0], ez[1] - ea[1]];
        let (mut t0, mut t1) = (0.0f32, 1.0f32);
        if c >= 0.0 {
            // A wedge of half-angle ≤ 90°: inside both boundary rays' half-planes.
            let [left, right] = rays;
            let planes = [(right, 1.0f32), (left, -1.0f32)];
            for (ray, sign) in planes {
                let f0 = sign * (ray[0] * ea[1] - ray[1] * ea[0]);
                let f1 = sign * (ray[0] * ez[1] - ray[1] * ez[0]);
                if f0 < 0.0 && f1 < 0.0 {
                    return None;
                }
                if f0 < 0.0 {
                    t0 = t0.max(f0 / (f0 - f1));
                } else if f1 < 0.0 {
                    t1 = t1.min(f0 / (f0 - f1));
                }
            }
            if t0 > t1 {
                return None;
            }
        }
        let length2 = d[0] * d[0] + d[1] * d[1];
        let t = if length2 > 0.0 { (-(ea[0] * d[0] + ea[1] * d[1]) / length2).clamp(t0, t1) } else { t0 };
        let e = [ea[0] + d[0] * t, ea[1] + d[1] * t];
        let distance = crate::scalar::sqrtf(e[0] * e[0] + e[1] * e[1]);
        if !(distance > 0.0 && distance <= self.params.sector_radius) {
            return None;
        }
        // A wider wedge is not convex: keep the nearest point only if it lies in it.
        if c < 0.0 && (e[0] * direction[0] + e[1] * direction[1]) < c * distance {
            return None;
        }
        Some((e, distance))
    }

    /// Starts an update of crack `i` (Eqs. 12–17): its course (Eq. 13, θ_w, the direction of
    /// v(t); a ring crack's v runs along its circle, rule 5), the sector S ahead of it, and the
    /// scan of the tips in S.
    fn begin_update(&mut self, i: usize) -> Update {
        let c = self.cracks[i];
        let left = if c.left > 0.0 { c.left } else { c.speed };
        let ring = c.is_ring();
        let course = if ring { Self::ring_course(&c) } else { c.heading };
        // A radial crack's first update of the time step sets out in the direction the step
        // began with (`file_tip` worked out the very same cosine and sine of its heading).
        let direction =
            if !ring && c.left <= 0.0 { c.before_direction } else { [libm::cosf(course), libm::sinf(course)] };
        let bounds = self.sector_box(c.tip, direction);
        let [x0, y0, x1, y1] = bounds;
        let cells = self.index.grid.span(x0, y0, x1, y1);
        let scan = self.start_scan(Filed::Tips, cells);
        Update {
            stage: Stage::Tips,
            scan,
            left,
            done: c.speed - left,
            ring,
            course,
            direction,
            rays: self.wedge(direction),
            bounds,
            ..Update::IDLE
        }
    }

    /// Goes on with update `u` of the crack at the cursor until it is over or the work reaches
    /// `deadline` (then it is kept in the clock, and the next call goes on from there): its
    /// scans stop between any two cells or entries, its face walks between any two steps.
    fn go_on_update(&mut self, mut u: Update, deadline: u64) {
        let i = self.clock.cursor;
        let over = loop {
            match u.stage {
                Stage::Tips => {
                    if self.sum_forces(i, &mut u, deadline) {
                        self.plan_move(i, &mut u);
                        u.stage = Stage::Path;
                        continue;
                    }
                    if !self.sum_tips(i, &mut u, deadline) {
                        break false;
                    }
                    // The same cells: the sector's box.
                    u.scan = self.start_scan(Filed::Earlier, u.scan.cells());
                    u.stage = Stage::Segments;
                }
                Stage::Segments => {
                    if !self.sum_segments(i, &mut u, deadline) {
                        break false;
                    }
                    self.plan_move(i, &mut u);
                    u.stage = Stage::Path;
                }
                Stage::Path => {
                    if !self.trace_path(i, &mut u, deadline) {
                        break false;
                    }
                    match self.make_move(i, &mut u) {
                        Some(h) => {
                            u.enclosure = Enclosure::new(h);
                            u.stage = Stage::Enclose;
                        }
                        None => break true,
                    }
                }
                Stage::Enclose => break self.go_on_enclosure(&mut u.enclosure, deadline),
            }
        };
        if over {
            self.end_update(i, &u);
        } else {
            self.clock.update = u;
            self.clock.phase = Phase::Update;
        }
    }

    /// F1, from where the scan stopped: away from every other tip in S, |F1| = k1/r². Cells
    /// wholly outside S (by more than SLACK, which covers the rounding of `in_sector`'s cosine)
    /// hold no tip in it. True when every tip in S has pushed.
    fn sum_tips(&mut self, i: usize, u: &mut Update, deadline: u64) -> bool {
        let w = self.cracks[i].tip;
        let sight = Sight { crack: i as u32, w, direction: u.direction, rays: u.rays, bounds: u.bounds };
        let cells = self.sector_cells(w, u.rays, SLACK);
        let force = &mut u.force;
        let outside = cells.test();
        self.go_on::<false, false>(
            &mut u.scan,
            deadline,
            outside,
            |_, _| true,
            #[cfg_attr(target_pointer_width = "64", inline(always))]
            |glass, j| glass.push(&sight, force, j),
        )
    }

    /// Adds the push of crack `j`'s tip to `force`, the F1 of the tip `sight` (see
    /// [`Self::sum_tips`]).
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    fn push(&self, sight: &Sight, force: &mut [f32; 2], j: u32) {
        if j == sight.crack {
            return;
        }
        let p = &self.params;
        let w = sight.w;
        let far = p.sector_radius + SLACK;
        let other = &self.cracks[j as usize];
        let e = [other.before[0] - w[0], other.before[1] - w[1]];
        // Only a tip growing towards this one pushes it (two tips closing in turn apart);
        // one running away from it, as the radial cracks of an impact do, does not. Tested
        // first, with the distance bound, as they are cheaper than `in_sector`'s root (the
        // same offset, so the same outcome).
        if e[0] * other.before_direction[0] + e[1] * other.before_direction[1] >= 0.0
            || e[0] * e[0] + e[1] * e[1] > far * far
        {
            return;
        }
        if let Some((e, r)) = self.in_sector(w, sight.direction, other.before) {
            let k = p.tip_repulsion / (r * r * r);
            force[0] -= k * e[0];
            force[1] -= k * e[1];
        }
    }

    /// F1 and F2 of an update in one walk of its sector's cells (a cell's tips, then its
    /// segments), for an update whose scans have not started and cannot reach the deadline
    /// (on 64-bit targets): the very visits, in the same order, and the same units, as
    /// [`Self::sum_tips`] then [`Self::sum_segments`], with each cell's place found once. False
    /// (nothing done) otherwise.
    fn sum_forces(&mut self, i: usize, u: &mut Update, deadline: u64) -> bool {
        let cells = u.scan.cells();
        let (cx0, cy0, cx1, cy1) = cells;
        if !cfg!(target_pointer_width = "64") || u.scan != Scan::new(cells) || cx0 > cx1 {
            return false;
        }
        let count = (cy1 + 1).saturating_sub(cy0).saturating_mul(cx1 + 1 - cx0);
        let filed = self.index.tips.used.saturating_add(self.index.segments.used);
        if deadline.saturating_sub(self.clock.work) <= (2 * count as u64).saturating_add(filed as u64) {
            return false;
        }
        let w = self.cracks[i].tip;
        let sight = Sight { crack: i as u32, w, direction: u.direction, rays: u.rays, bounds: u.bounds };
        let (near, far) = (self.sector_cells(w, u.rays, 0.0), self.sector_cells(w, u.rays, SLACK));
        self.start_scan(Filed::Earlier, cells);
        let columns = self.index.grid.columns;
        let mut work = self.clock.work;
        for cy in cy0..=cy1 {
            let row = near.row(cy);
            // The row's cells in the scan, their lists of tips and of segments.
            let first = cy * columns + cx0;
            let last = cy * columns + cx1;
            let (tips, segments) = (&self.index.tips.heads[first..=last], &self.index.segments.heads[first..=last]);
            work += 2 * tips.len() as u64;
            for (k, (&tip, &head)) in tips.iter().zip(segments).enumerate() {
                if tip == NONE && head == NONE {
                    continue;
                }
                let (cx, cell) = (cx0 + k, first + k);
                let column = near.column(cx);
                let mut entry = tip;
                if entry != NONE && !far.outside_at(row, column) {
                    while entry != NONE {
                        work += 1;
                        let [item, next] = self.index.tips.entries[entry as usize];
                        entry = next;
                        self.push(&sight, &mut u.force, item);
                    }
                }
                if head == NONE || near.outside_at(row, column) {
                    continue;
                }
                let mut entry = if head >= self.index.fresh { self.earlier(cell) } else { head };
                while entry != NONE {
                    work += 1;
                    let [item, next] = self.index.segments.entries[entry as usize];
                    entry = next;
                    if self.index.stamps[item as usize] == self.index.stamp {
                        continue;
                    }
                    self.index.stamps[item as usize] = self.index.stamp;
                    self.pull(&sight, &mut u.sums, item);
                }
            }
        }
        self.clock.work = work;
        true
    }

    /// F2, from where the scan stopped: for every crack in S, one pull along its normal at its
    /// nearest point in S (to cross it at a right angle), |F2| = k2/d² with d that shortest
    /// distance. A crack's pieces are folded into one entry per crack (the nearest); past NEAR
    /// cracks the rest each pull on their own. True when every segment in S has been seen.
    fn sum_segments(&mut self, i: usize, u: &mut Update, deadline: u64) -> bool {
        let w = self.cracks[i].tip;
        let cells = self.sector_cells(w, u.rays, 0.0);
        let sight = Sight { crack: i as u32, w, direction: u.direction, rays: u.rays, bounds: u.bounds };
        let sums = &mut u.sums;
        let outside = cells.test();
        self.go_on::<true, true>(
            &mut u.scan,
            deadline,
            outside,
            |_, _| true,
            #[cfg_attr(target_pointer_width = "64", inline(always))]
            |glass, e| glass.pull(&sight, sums, e),
        )
    }

    /// Folds segment `e` into `sums`, the F2 of the tip `sight` (see [`Self::sum_segments`]).
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    fn pull(&self, sight: &Sight, sums: &mut Sums, e: u32) {
        let p = &self.params;
        let (w, direction, rays) = (sight.w, sight.direction, sight.rays);
        let now = self.clock.time as f32;
        let radius = p.sector_radius;
        let edge = &self.edges[e as usize];
        let (a, z) = self.edge_points(e);
        // Outside the sector's box: no point of it is in the sector. Tested first, as it
        // passes over most of the segments the scan meets.
        if apart(a, z, sight.bounds) {
            return;
        }
        let owner = edge.crack;
        // Not its own crack, nor pieces other tips grew earlier in this time step (all
        // tips move at once).
        if owner == sight.crack || edge.time[0] >= now {
            return;
        }
        // Beyond a side of the wedge (the test `nearest_in_sector` starts with), or run
        // alongside or away from: it does not pull. The wedge's test first, as it is the
        // cheaper one and passes over most of the pieces beside the tip (its neighbours
        // at the impact). On 64-bit targets only: with soft floats (the Cortex-M3 of
        // `targets/run`) the extra products cost more than they save.
        if (cfg!(target_pointer_width = "64") && self.beyond_a_side(w, rays, a, z))
            || self.moving_away(w, direction, a, z)
        {
            return;
        }
        let [lx, ly, hx, hy] = span_of(a, z);
        // Skipped unseen, as they cannot change the sum: a segment whose box lies farther
        // than B from the tip (it has no point in S), or farther than its crack's nearest
        // point found so far (it would not replace it). The box's distance is a lower
        // bound on the segment's (up to rounding, which SLACK covers many times over).
        let gap = |lo: f32, hi: f32, at: f32| {
            if at < lo {
                lo - at
            } else if at > hi {
                at - hi
            } else {
                0.0
            }
        };
        let (gx, gy) = (gap(lx, hx, w[0]), gap(ly, hy, w[1]));
        let box_distance2 = gx * gx + gy * gy;
        // The bound against B first (no bound below is larger), so that a far segment
        // skips the search for its crack's entry.
        let far = radius + SLACK;
        if box_distance2 > far * far {
            return;
        }
        let (near, count) = (&mut sums.near, &mut sums.count);
        let slot = near[..*count].iter().position(|n| n.0 == owner);
        let bound = slot.map_or(radius, |k| near[k].1.min(radius)) + SLACK;
        if box_distance2 > bound * bound {
            return;
        }
        let Some((v, d)) = self.nearest_in_sector(w, direction, rays, a, z) else { return };
        let normal = self.normal_towards(a, z, v, d);
        // Only a crack the tip is closing in on can be met; one it runs alongside or away
        // from (a neighbour from the same impact, diverging) does not pull.
        if normal[0] * direction[0] + normal[1] * direction[1] <= 0.0 {
            return;
        }
        match slot.map(|k| &mut near[k]) {
            Some(n) if d < n.1 => *n = (owner, d, normal),
            Some(_) => {}
            None if *count < NEAR => {
                near[*count] = (owner, d, normal);
                *count += 1;
            }
            None => {
                let k = p.crack_attraction / (d * d);
                sums.extra[0] += k * normal[0];
                sums.extra[1] += k * normal[1];
            }
        }
    }

    /// The sum F1 + F2 + F3 on the tip and the move it makes (Eqs. 12–16): the cracks' F2
    /// summed, the plate's edges' F2 and a ring crack's pull along its circle added, the
    /// update's length, F3 drawn, the turn; then the plate's edge the move would leave by, and
    /// the scan of the segments along it.
    fn plan_move(&mut self, i: usize, u: &mut Update) {
        let p = self.params;
        let c = self.cracks[i];
        let w = c.tip;
        let (direction, rays) = (u.direction, u.rays);
        let mut f = u.force;
        // The nearest crack or edge closed in on: its distance, and the cosine between the
        // tip's heading and its normal (1 head-on, near 0 alongside).
        let mut nearest = (f32::INFINITY, 1.0f32);
        let mut closer = |d: f32, normal: [f32; 2]| {
            if d < nearest.0 {
                nearest = (d, normal[0] * direction[0] + normal[1] * direction[1]);
            }
        };
        for &(_, d, normal) in &u.sums.near[..u.sums.count] {
            closer(d, normal);
            let k = p.crack_attraction / (d * d);
            f[0] += k * normal[0];
            f[1] += k * normal[1];
        }
        f[0] += u.sums.extra[0];
        f[1] += u.sums.extra[1];
        // F2 for the plate's edges; one farther than B (and SLACK) from the tip has no point
        // in S (its nearest point's offset across it is exactly the tip's, so its distance is
        // at least that).
        let corners = [[0.0, 0.0], [p.width, 0.0], [p.width, p.height], [0.0, p.height]];
        let across = [w[1], p.width - w[0], p.height - w[1], w[0]];
        let far = p.sector_radius + SLACK;
        for k in 0..4 {
            if across[k].abs() > far {
                continue;
            }
            let (a, z) = (corners[k], corners[(k + 1) % 4]);
            if let Some((v, d)) = self.nearest_in_sector(w, direction, rays, a, z) {
                let normal = self.normal_towards(a, z, v, d);
                closer(d, normal);
                let k = p.crack_attraction / (d * d);
                f[0] += k * normal[0];
                f[1] += k * normal[1];
            }
        }
        let ring = u.ring;
        // Rule 5: a ring crack's course runs along its circle; it pulls with ring_adherence.
        if ring {
            f[0] += p.ring_adherence * direction[0];
            f[1] += p.ring_adherence * direction[1];
        }
        let course = u.course;
        let full = c.speed / ceil(c.speed / UPDATE_LENGTH).max(1.0);
        let planned = full.min(u.left);
        // Near a crack, an update covers a quarter of the distance to it, and at least
        // MIN_UPDATE scaled by how squarely the tip heads at it (down to a quarter): a tip
        // coming in at a shallow angle needs more turns before it arrives; a radial crack
        // heading at it nearly squarely is not slowed.
        let (gap, squareness) = nearest;
        let least = MIN_UPDATE * squareness.max(MIN_SQUARENESS);
        let length =
            if !ring && squareness >= SQUARE { planned } else { (APPROACH_SHARE * gap).max(least).min(planned) };
        // F3: a unit force whose direction is a normal draw, with standard deviation `wander`
        // per 10 px (scaled by the square root of the update's length, so that the random
        // turning per unit length does not depend on how a step is cut, and for a radial crack
        // by weight(t), so that young cracks wander little, rule 3), around the direction
        // the crack started in (a radial crack keeps its course on the whole: adjacent large
        // cracks stay at nearly equal angles) or, for a ring crack, around its course.
        let age = c.age as f32 + u.done / c.speed;
        let weight = 1.0 - libm::expf(-age / p.turn_delay);
        let spread = p.wander * crate::scalar::sqrtf(length / UPDATE_LENGTH) * if ring { 1.0 } else { weight };
        let mean = if ring { course } else { c.start_heading };
        let angle = mean + spread * self.forces.normal_f32();
        f[0] += libm::cosf(angle);
        f[1] += libm::sinf(angle);
        // Eqs. 12–15: turn towards F, at most θ_th, weighted by 1 − exp(−t/T).
        let turn = wrap(libm::atan2f(f[1], f[0]) - course);
        // Forces of FLT_MAX can meet as inf − inf: a force with no direction turns the tip
        // nowhere (fuzzing found NaN vertices from `tip_repulsion` = `crack_attraction` = FLT_MAX).
        let turn = if turn.is_nan() { 0.0 } else { turn };
        let difference = turn.clamp(-p.turn_limit, p.turn_limit);
        let mut heading = wrap(course + difference * weight);
        if ring {
            // Rule 5: a ring crack never turns outwards of the chord of its circle (about the
            // impact, through its tip) that this update spans, so that it turns at least as
            // much as the arc it runs along, right up to where it meets a crack.
            let (angle, r, sense) = Self::ring_frame(&c);
            let chord = angle + sense * (core::f32::consts::FRAC_PI_2 + libm::asinf((0.5 * length / r).min(1.0)));
            if sense * wrap(heading - chord) < 0.0 {
                heading = wrap(chord);
            }
        }
        // Eqs. 16–17: w(t + dt) = w(t) + v(t + dt)·dt.
        let next = [w[0] + length * libm::cosf(heading), w[1] + length * libm::sinf(heading)];
        // The plate's edge: where the move leaves [0, W] × [0, H], the crossed coordinate exact.
        let mut hit = (Hit::Nothing, 1.0f32);
        for (axis, limit) in [(0usize, 0.0f32), (0, p.width), (1, 0.0), (1, p.height)] {
            let (from, to) = (w[axis], next[axis]);
            // A move that ends exactly on the edge reaches it too (t = 1): the tip stops there,
            // rather than going on from the edge with a segment of length 0 along it.
            let outside = if limit == 0.0 { to <= 0.0 } else { to >= limit };
            if outside && from != to {
                let t = (limit - from) / (to - from);
                if t < hit.1 || hit.0 == Hit::Nothing {
                    let other = 1 - axis;
                    let mut at = [0.0; 2];
                    at[axis] = limit;
                    at[other] = w[other] + (next[other] - w[other]) * t;
                    hit = (Hit::Edge(at), t);
                }
            }
        }
        let (x0, x1) = (w[0].min(next[0]), w[0].max(next[0]));
        let (y0, y1) = (w[1].min(next[1]), w[1].max(next[1]));
        u.heading = heading;
        u.length = length;
        u.next = next;
        u.hit = hit;
        u.found = (NONE, hit.1, [0.0; 2]);
        u.bounds = [x0, y0, x1, y1];
        u.scan = self.start_scan(Filed::Segments, self.index.grid.span(x0, y0, x1, y1));
    }

    /// Whether segment `a`–`z` lies beyond one side of the wedge of the sector S (φ ≤ 180°)
    /// ahead of a tip at `w` whose boundary rays are `rays` ([`Self::wedge`]): both its ends
    /// on the outer side of one ray, by the very products with which
    /// [`Self::nearest_in_sector`] then finds no point of it in S. False for a wider sector.
    #[inline(always)]
    fn beyond_a_side(&self, w: [f32; 2], rays: [[f32; 2]; 2], a: [f32; 2], z: [f32; 2]) -> bool {
        if self.sector.cosine < 0.0 {
            return false;
        }
        let (ea, ez) = ([a[0] - w[0], a[1] - w[1]], [z[0] - w[0], z[1] - w[1]]);
        let [left, right] = rays;
        let beyond = |ray: [f32; 2], sign: f32| {
            sign * (ray[0] * ea[1] - ray[1] * ea[0]) < 0.0 && sign * (ray[0] * ez[1] - ray[1] * ez[0]) < 0.0
        };
        beyond(right, 1.0) || beyond(left, -1.0)
    }

    /// Whether a tip at `w` heading `direction` runs alongside or away from the line of segment
    /// `a`–`z` for certain: the test F2 makes of a segment's normal at its nearest point in S
    /// ([`Self::normal_towards`], "a pull to meet it at a right angle", §4.2.2 (2), for a crack
    /// the tip closes in on) decided from the ends alone, before the costly nearest point. That
    /// normal is the segment's unit normal n on the tip's side of its line, and the test fails
    /// when n·direction ≤ 0, so with t = z − a: when the cross products t × (a − w) (the tip's
    /// side, times |t|) and t × direction (n·direction, times |t|) have opposite signs. True
    /// only when both are larger than their rounding (and that of the computed normal) by far:
    /// 10⁻⁵ of the terms they are formed from, about 170 times f32's epsilon. Otherwise (a tip
    /// on or near the line, a segment parallel to the heading or of length 0) the full test
    /// decides, so F2 is the same to the bit.
    #[inline(always)]
    fn moving_away(&self, w: [f32; 2], direction: [f32; 2], a: [f32; 2], z: [f32; 2]) -> bool {
        const ROUNDING: f32 = 1e-5;
        let t = [z[0] - a[0], z[1] - a[1]];
        let (ea, ez) = ([a[0] - w[0], a[1] - w[1]], [z[0] - w[0], z[1] - w[1]]);
        let side = t[0] * ea[1] - t[1] * ea[0];
        let heading = t[0] * direction[1] - t[1] * direction[0];
        let length = t[0].abs() + t[1].abs();
        let reach = ea[0].abs() + ea[1].abs() + ez[0].abs() + ez[1].abs();
        (side < 0.0) != (heading < 0.0) && side.abs() > ROUNDING * length * reach && heading.abs() > ROUNDING * length
    }

    /// The unit normal of segment `a`–`z` pointing from the tip towards it; `v` is the offset
    /// from the tip to its nearest point, at distance `d`.
    fn normal_towards(&self, a: [f32; 2], z: [f32; 2], v: [f32; 2], d: f32) -> [f32; 2] {
        let t = [z[0] - a[0], z[1] - a[1]];
        let length = crate::scalar::sqrtf(t[0] * t[0] + t[1] * t[1]);
        if length.is_nan() || length <= 0.0 {
            return [v[0] / d, v[1] / d];
        }
        let n = [-t[1] / length, t[0] / length];
        // The side of the segment's line the tip is on (a and z in the tip's frame: v lies on
        // the segment, so its offset along n is the tip's distance from the line).
        let side = n[0] * v[0] + n[1] * v[1];
        if side > 0.0 {
            n
        } else if side < 0.0 {
            [-n[0], -n[1]]
        } else {
            [v[0] / d, v[1] / d]
        }
    }

    /// Where ring crack `c`'s tip is on its circle: its angle and distance about the impact,
    /// and the sense it grows in (1 counter-clockwise, −1 clockwise).
    fn ring_frame(c: &super::CrackSlot) -> (f32, f32, f32) {
        let centre = c.ring.0;
        let rel = [c.tip[0] - centre[0], c.tip[1] - centre[1]];
        let r = crate::scalar::sqrtf(rel[0] * rel[0] + rel[1] * rel[1]).max(1e-3);
        let angle = libm::atan2f(rel[1], rel[0]);
        let sense = if c.is(CrackKind::RingCounterClockwise) { 1.0 } else { -1.0 };
        (angle, r, sense)
    }

    /// The course of ring crack `c` (rule 5: ring cracks grow along their circle): the
    /// direction of the chord of the circle through its tip (about the impact) that spans one
    /// full update, |v| cut into pieces of at most 10 px, turned towards radius d_i by up to a
    /// quarter of that chord's angle. The course is thus always turned inwards from the
    /// tangent, so that a ring crack turns at least as much as the arc it runs along, and
    /// returns to its circle without ever turning outwards.
    fn ring_course(c: &super::CrackSlot) -> f32 {
        let radius = c.ring.1;
        let (angle, r, sense) = Self::ring_frame(c);
        let update = c.speed / ceil(c.speed / UPDATE_LENGTH).max(1.0);
        // Half the angle the chord of length `update` subtends.
        let half = libm::asinf((0.5 * update / r).min(1.0));
        let pull = ((r - radius) / update).clamp(-0.5, 0.5) * half;
        angle + sense * (core::f32::consts::FRAC_PI_2 + half + pull)
    }

    /// The first crack the move meets, from where the scan of the segments along it stopped:
    /// the nearest crossing (or overlap) past the tip, nearer than the plate's edge. True when
    /// every segment along the move has been seen.
    fn trace_path(&mut self, i: usize, u: &mut Update, deadline: u64) -> bool {
        let own_last = self.cracks[i].last_segment;
        let w = self.cracks[i].tip;
        let path = Segment::new(Point::new(w[0], w[1]), Point::new(u.next[0], u.next[1]));
        let bounds = u.bounds;
        if self.trace_whole(&path, own_last, u, deadline) {
            return true;
        }
        let found = &mut u.found;
        self.go_on::<true, false>(
            &mut u.scan,
            deadline,
            |_, _| false,
            // Boxes apart: no meeting. Tested before the segment is marked as seen, as most
            // segments along the move fail it; on 64-bit targets only: with soft floats (the
            // Cortex-M3 of `targets/run`) the test again in each further cell of a segment
            // costs more than the mark it saves, and it is made in `visit`.
            #[cfg_attr(target_pointer_width = "64", inline(always))]
            |glass, e| {
                let (a, z) = glass.edge_points(e);
                !cfg!(target_pointer_width = "64") || !apart(a, z, bounds)
            },
            #[cfg_attr(target_pointer_width = "64", inline(always))]
            |glass, e| glass.cross(&path, own_last, bounds, found, e),
        )
    }

    /// The scan of [`Self::trace_path`] in one go, by plain loops over its cells, for a scan
    /// that has not started and cannot reach the deadline (on 64-bit targets): the same visits
    /// and units. False (nothing done) otherwise.
    fn trace_whole(&mut self, path: &Segment<f32>, own_last: u32, u: &mut Update, deadline: u64) -> bool {
        let cells = u.scan.cells();
        let (cx0, cy0, cx1, cy1) = cells;
        if !cfg!(target_pointer_width = "64") || u.scan != Scan::new(cells) || cx0 > cx1 {
            return false;
        }
        let count = (cy1 + 1).saturating_sub(cy0).saturating_mul(cx1 + 1 - cx0);
        if deadline.saturating_sub(self.clock.work) <= (count as u64).saturating_add(self.index.segments.used as u64) {
            return false;
        }
        let bounds = u.bounds;
        let columns = self.index.grid.columns;
        let mut work = self.clock.work;
        for cy in cy0..=cy1 {
            let heads = &self.index.segments.heads[cy * columns + cx0..=cy * columns + cx1];
            work += heads.len() as u64;
            for &head in heads {
                let mut entry = head;
                while entry != NONE {
                    work += 1;
                    let [item, next] = self.index.segments.entries[entry as usize];
                    entry = next;
                    let (a, z) = self.edge_points(item);
                    if apart(a, z, bounds) || self.index.stamps[item as usize] == self.index.stamp {
                        continue;
                    }
                    self.index.stamps[item as usize] = self.index.stamp;
                    self.cross(path, own_last, bounds, &mut u.found, item);
                }
            }
        }
        self.clock.work = work;
        true
    }

    /// Keeps segment `e` in `found` when the move `path` (box `bounds`) meets it nearer than
    /// what `found` holds (see [`Self::trace_path`]).
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    fn cross(&self, path: &Segment<f32>, own_last: u32, bounds: [f32; 4], found: &mut (u32, f32, [f32; 2]), e: u32) {
        if e == own_last {
            return;
        }
        let (a, z) = self.edge_points(e);
        if !cfg!(target_pointer_width = "64") && apart(a, z, bounds) {
            return;
        }
        let other = Segment::new(Point::new(a[0], a[1]), Point::new(z[0], z[1]));
        let (t, at) = match path.intersect(other) {
            Intersection::None => return,
            Intersection::Point { point, along_first, .. } => (along_first, point),
            Intersection::Overlap { start, .. } => (path.closest_parameter(start), start),
        };
        if t > 0.0 && t < found.1 {
            *found = (e, t, [at.x, at.y]);
        }
    }

    /// Makes the move (Eqs. 16–17): the tip goes to where it ends, stopping exactly on a
    /// crack or the edge it met. The half-edge of the new segment when it closed a cycle (stop
    /// condition 2 walks its faces next).
    fn make_move(&mut self, i: usize, u: &mut Update) -> Option<HalfEdge> {
        let c = self.cracks[i];
        let (hit, along) = if u.found.0 == NONE {
            u.hit
        } else {
            let (edge, at) = (u.found.0, u.found.2);
            let (a, z) = self.edge_points(edge);
            let along = Segment::new(Point::new(a[0], a[1]), Point::new(z[0], z[1]))
                .closest_parameter(Point::new(at[0], at[1]));
            (Hit::Crack { edge, at, along }, u.found.1)
        };
        let tip_vertex = if c.last_segment == NONE { c.start_vertex } else { self.edges[c.last_segment as usize].to };
        let time = self.clock.time as f32 + u.done / c.speed;
        if hit == Hit::Nothing && u.next == c.tip {
            // A move too short to change the tip's position in f32 (a speed of 1e-30 px a step):
            // the crack turns where it stands, with no segment of length 0.
            self.cracks[i].heading = u.heading;
            u.stopped = false;
            return None;
        }
        u.stopped = true;
        let (end, stop) = match hit {
            Hit::Nothing => (self.add_vertex(u.next), CrackEnd::Growing),
            Hit::Edge(at) => (self.add_vertex(at), CrackEnd::Edge),
            Hit::Crack { edge, at, along } => (self.meeting_vertex(edge, at, along), CrackEnd::Crack),
        };
        if end == NONE {
            return None; // capacity reached; the step loop finishes
        }
        if end == tip_vertex {
            // Met a crack exactly at its own tip (a rounding tie): it stops there.
            self.stop(i, CrackEnd::Crack);
            return None;
        }
        let segment = Edge::new(tip_vertex, end, i as u32, [time, time + along * u.length / c.speed]);
        let e = self.add_edge(segment)?;
        let closes_cycle = self.join(tip_vertex, end);
        let c = &mut self.cracks[i];
        c.tip = self.vertices[end as usize].at;
        c.heading = u.heading;
        u.stopped = stop != CrackEnd::Growing;
        if u.stopped {
            self.stop(i, stop);
        }
        closes_cycle.then_some(2 * e)
    }

    /// Ends the update of crack `i`: its time step is complete when it stopped or has moved
    /// |v|; then the step loop goes on (or finishes, when the plate's capacity ran out).
    fn end_update(&mut self, i: usize, u: &Update) {
        let stopped = u.stopped || !self.cracks[i].growing();
        let left = u.left - u.length;
        let c = &mut self.cracks[i];
        if stopped || left <= 1e-3 * c.speed {
            c.left = 0.0;
            c.age += 1;
            self.clock.cursor += 1;
        } else {
            c.left = left;
        }
        self.clock.phase = Phase::Advance;
        if self.clock.capacity_reached {
            self.finish();
        }
    }

    /// The vertex a crack starting at `at` (an impact point, or a ring crack's start point
    /// C_i) grows from: the vertex already there, else a new one that splits the crack `at`
    /// lies on, else a new one. A move sees no crack at its very start (see
    /// [`Self::trace_path`]), so a crack starting on an earlier one must share its vertex for
    /// the cracks to stay a plane graph: a second hub at the first one's point, unjoined,
    /// would let their cracks cross and the fragments' rings cross themselves. Looks at every
    /// vertex and segment once (bounded by the capacities). NONE when full.
    pub(super) fn vertex_at(&mut self, at: [f32; 2]) -> u32 {
        if let Some(v) = self.vertices[..self.vertex_count].iter().position(|v| v.at == at) {
            return v as u32;
        }
        let p = Point::new(at[0], at[1]);
        for e in 0..self.edge_count as u32 {
            let (a, z) = self.edge_points(e);
            let segment = Segment::new(Point::new(a[0], a[1]), Point::new(z[0], z[1]));
            if segment.contains(p) {
                return self.meeting_vertex(e, at, segment.closest_parameter(p));
            }
        }
        self.add_vertex(at)
    }

    /// The vertex where a tip meets edge `e` at point `at` (parameter `along` on the edge): one
    /// of its ends if it meets it there, else a new vertex that splits it. NONE when full.
    fn meeting_vertex(&mut self, e: u32, at: [f32; 2], along: f32) -> u32 {
        let edge = self.edges[e as usize];
        if along <= 0.0 || at == self.vertices[edge.from as usize].at {
            return edge.from;
        }
        if along >= 1.0 || at == self.vertices[edge.to as usize].at {
            return edge.to;
        }
        let v = self.add_vertex(at);
        if v != NONE && !self.split(e, v, along) {
            return NONE;
        }
        v
    }

    /// Splits edge `e` at vertex `v` (a point on it at parameter `along`), so that the crack
    /// meeting it there shares the vertex. False when full.
    fn split(&mut self, e: u32, v: u32, along: f32) -> bool {
        let old = self.edges[e as usize];
        let time = old.time[0] + (old.time[1] - old.time[0]) * along;
        let tail = Edge { next: old.next, ..Edge::new(v, old.to, old.crack, [time, old.time[1]]) };
        let Some(t) = self.push_edge(tail) else { return false };
        // The head now ends at v: out of the old end's incidence list, into v's, and again into
        // its first vertex's at its (recomputed) angle.
        self.unlink(old.to, e);
        self.unlink(old.from, e);
        let head = &mut self.edges[e as usize];
        head.to = v;
        head.next = t;
        head.time[1] = time;
        head.orient(self.vertices[old.from as usize].at, self.vertices[v as usize].at);
        let at = self.vertices[v as usize].at;
        head.ends[2] = at[0];
        head.ends[3] = at[1];
        self.link(old.from, e);
        self.link(v, e);
        self.join(v, old.from);
        let owner = &mut self.cracks[old.crack as usize];
        if owner.last_segment == e {
            owner.last_segment = t;
        }
        true
    }

    /// Removes edge `e` from vertex `v`'s incidence list.
    fn unlink(&mut self, v: u32, e: u32) {
        let (previous, after) = {
            let g = self.crack_graph();
            let mut previous = NONE;
            let mut x = self.vertices[v as usize].first_edge;
            while x != e && x != NONE {
                previous = x;
                x = g.next_at(v, x);
            }
            (previous, g.next_at(v, e))
        };
        if previous == NONE {
            self.vertices[v as usize].first_edge = after;
        } else {
            let p = &mut self.edges[previous as usize];
            p.links[usize::from(p.from != v)] = after;
        }
    }

    /// Appends a new segment to its crack's chain; its index, or None when full.
    fn add_edge(&mut self, edge: Edge) -> Option<u32> {
        let crack = edge.crack as usize;
        let e = self.push_edge(edge)?;
        let c = &mut self.cracks[crack];
        if c.last_segment == NONE {
            c.first_segment = e;
        } else {
            self.edges[c.last_segment as usize].next = e;
        }
        self.cracks[crack].last_segment = e;
        Some(e)
    }

    /// Stores an edge, links it into its vertices' incidence lists and files it in the grid;
    /// None (capacity reached) when full.
    fn push_edge(&mut self, mut edge: Edge) -> Option<u32> {
        if self.edge_count == self.edges.len() {
            self.clock.capacity_reached = true;
            return None;
        }
        let e = self.edge_count as u32;
        // No segment query has seen it yet (a stamp is never 0).
        self.index.stamps[self.edge_count] = 0;
        edge.links = [NONE; 2];
        let (a, z) = (self.vertices[edge.from as usize].at, self.vertices[edge.to as usize].at);
        edge.orient(a, z);
        edge.ends = [a[0], a[1], z[0], z[1]];
        self.edges[self.edge_count] = edge;
        self.edge_count += 1;
        self.link(edge.from, e);
        self.link(edge.to, e);
        let (a, z) = self.edge_points(e);
        let (cx0, cy0, cx1, cy1) = self.index.grid.span(a[0].min(z[0]), a[1].min(z[1]), a[0].max(z[0]), a[1].max(z[1]));
        // Whether F2 passes the segment over in this time step by its time (as `sum_segments`
        // tests it): F2 then starts a cell's list past it (`SpatialIndex::earlier`).
        let passed_over = edge.time[0] >= self.clock.time as f32;
        for cy in cy0..=cy1 {
            for cx in cx0..=cx1 {
                let cell = cy * self.index.grid.columns + cx;
                let (head, entry) = (self.index.segments.heads[cell], self.index.segments.used as u32);
                if !self.index.segments.insert(cell, e) {
                    self.clock.capacity_reached = true;
                    return None;
                }
                if !passed_over {
                    self.index.earlier[cell] = entry;
                } else if head == NONE || head < self.index.fresh {
                    self.index.earlier[cell] = head;
                }
            }
        }
        Some(e)
    }
}

/// The cell tests of a sector S (apex `w`, wedge boundary rays `rays`, radius B): which grid
/// cells lie wholly outside it, by more than `margin`.
#[derive(Clone, Copy)]
struct SectorCells {
    w: [f32; 2],
    rays: [[f32; 2]; 2],
    cell: f32,
    /// (B + margin)².
    reach2: f32,
    /// φ ≤ 180°: the wedge is convex, and a cell beyond one side of it is outside.
    wedge: bool,
    margin: f32,
}

/// A column's share of [`SectorCells::outside`]: its corners' offset from the apex in x,
/// squared as for the disc at its nearest, and times the rays for the wedge.
#[derive(Clone, Copy)]
struct SectorColumn {
    nx2: f32,
    right_x: [f32; 2],
    left_x: [f32; 2],
}

/// A row's share of [`SectorCells::outside`]: its corners' offset from the apex in y, that
/// offset's square for the disc, and its products with the rays for the wedge (formed once a
/// row, the very products the per-corner tests use).
#[derive(Clone, Copy)]
struct SectorRow {
    ny2: f32,
    right_y: [f32; 2],
    left_y: [f32; 2],
}

impl SectorCells {
    /// The share of the tests of the cells of row `cy`. A cell's index reaches f32 through
    /// u32 here and in [`Self::outside`]: at most 256 a side, so the same value, by a shorter
    /// conversion than a 64-bit index's.
    #[inline(always)]
    fn row(&self, cy: usize) -> SectorRow {
        let [left, right] = self.rays;
        let ay = cy as u32 as f32 * self.cell - self.w[1];
        let by = ay + self.cell;
        let ny = nearest_to_zero(ay, by);
        SectorRow { ny2: ny * ny, right_y: [right[0] * ay, right[0] * by], left_y: [left[0] * ay, left[0] * by] }
    }

    /// The test of a scan's cells (whether cell (cx, cy) lies outside the sector by more than
    /// the margin), forming each row's share once for a row's cells in turn.
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    fn test(self) -> impl FnMut(usize, usize) -> bool {
        let mut row: Option<(usize, SectorRow)> = None;
        move |cx, cy| {
            let share = match row {
                Some((y, share)) if y == cy => share,
                _ => {
                    let share = self.row(cy);
                    row = Some((cy, share));
                    share
                }
            };
            self.outside(share, cx)
        }
    }

    /// The share of the tests of the cells of column `cx`, as [`Self::row`] for a row (it
    /// does not depend on the margin either, so one serves the tests of both margins).
    #[inline(always)]
    fn column(&self, cx: usize) -> SectorColumn {
        let [left, right] = self.rays;
        // The cell's corners relative to the apex, in x.
        let ax = cx as u32 as f32 * self.cell - self.w[0];
        let bx = ax + self.cell;
        let nx = nearest_to_zero(ax, bx);
        SectorColumn { nx2: nx * nx, right_x: [right[1] * ax, right[1] * bx], left_x: [left[1] * ax, left[1] * bx] }
    }

    /// Whether cell `cx` of `row` lies outside the sector by more than the margin: its nearest
    /// point farther than B from the apex, or (φ ≤ 180°) every corner beyond one side of the
    /// wedge.
    #[inline(always)]
    fn outside(&self, row: SectorRow, cx: usize) -> bool {
        self.outside_at(row, self.column(cx))
    }

    /// [`Self::outside`] for the cell of `row` and `column`.
    #[inline(always)]
    fn outside_at(&self, row: SectorRow, column: SectorColumn) -> bool {
        if column.nx2 + row.ny2 > self.reach2 {
            return true;
        }
        if !self.wedge {
            return false;
        }
        // Beyond a side of the wedge: every corner (x, y) on the outer side of it, by the
        // cross product ray × corner = ray_x·y − ray_y·x.
        let m = self.margin;
        let (right_x, left_x) = (column.right_x, column.left_x);
        let outside_right = row.right_y.iter().all(|&y| right_x.iter().all(|&x| y - x < -m));
        let outside_left = row.left_y.iter().all(|&y| left_x.iter().all(|&x| y - x > m));
        outside_right || outside_left
    }
}

/// The point of the interval [a, b] (a ≤ b) nearest 0: a cell's nearest offset from the sector's
/// apex along one axis.
fn nearest_to_zero(a: f32, b: f32) -> f32 {
    if a > 0.0 {
        a
    } else if b < 0.0 {
        b
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::glass::{CrackSlot, GlassBuffers, GlassParams, Vertex};
    extern crate std;
    use std::vec;
    use std::vec::Vec;

    /// Calls `f` with a plate of parameters `p` over fresh buffers, their words all `word`.
    fn with_plate(p: &GlassParams, word: u32, f: impl FnOnce(&mut Glass)) {
        let m = p.memory().unwrap();
        let (mut cracks, mut vertices) = (vec![CrackSlot::default(); m.cracks], vec![Vertex::default(); m.vertices]);
        let (mut edges, mut words) = (vec![Edge::default(); m.edges], vec![word; m.words]);
        let buffers =
            GlassBuffers { cracks: &mut cracks, vertices: &mut vertices, edges: &mut edges, words: &mut words };
        f(&mut Glass::new(p, buffers).unwrap());
    }

    /// A segment query visits each edge filed in its cells once, whatever its stamp held
    /// before it was added (here the very stamp the query takes).
    #[test]
    fn a_segment_query_visits_an_edge_added_over_any_stamp() {
        with_plate(&GlassParams::default(), 1, |glass| {
            while glass.clock.phase == Phase::Clear {
                glass.step(1);
            }
            let (a, z) = (glass.add_vertex([100.0, 100.0]), glass.add_vertex([105.0, 103.0]));
            let e = glass.push_edge(Edge::new(a, z, 0, [0.0, 1.0])).unwrap();
            let (columns, rows) = (glass.index.grid.columns, glass.index.grid.rows);
            let mut scan = glass.start_scan(Filed::Segments, (0, 0, columns - 1, rows - 1));
            assert_eq!(glass.index.stamp, 1);
            let mut visited = Vec::new();
            assert!(glass.go_on::<true, false>(
                &mut scan,
                u64::MAX,
                |_, _| false,
                |_, _| true,
                |_, item| visited.push(item)
            ));
            assert_eq!(visited, [e]);
        });
    }

    /// F2's scan of the segments visits, in the same order, every segment a full scan visits
    /// but those F2 passes over by their time (grown in the time step under way), and skips
    /// some of those unseen: checked between the updates of a run stopped every 13 units.
    #[test]
    fn f2_scans_every_segment_but_this_time_steps() {
        let p = GlassParams { radial_mean: 100.0, ..GlassParams::default() };
        with_plate(&p, 0, f2_scans_against_full_scans);
    }

    fn f2_scans_against_full_scans(glass: &mut Glass) {
        let (mut checks, mut skipped) = (0, 0);
        while !glass.step(13).finished {
            if glass.clock.phase != Phase::Advance {
                continue; // a scan of an update under way holds the stamp
            }
            let now = glass.clock.time as f32;
            let cells = (0, 0, glass.index.grid.columns - 1, glass.index.grid.rows - 1);
            let mut seen = [Vec::new(), Vec::new()];
            let mut units = [0, 0];
            for (k, filed) in [Filed::Segments, Filed::Earlier].into_iter().enumerate() {
                let before = glass.clock.work;
                let mut scan = glass.start_scan(filed, cells);
                let seen = &mut seen[k];
                let counted = |g: &Glass, e: u32| {
                    // (Earlier than now, or not a number: what F2 reads.)
                    let t = g.edges[e as usize].time[0];
                    if t.partial_cmp(&now).is_none_or(|o| o == core::cmp::Ordering::Less) {
                        seen.push(e);
                    }
                };
                let over = if filed == Filed::Segments {
                    glass.go_on::<true, false>(&mut scan, u64::MAX, |_, _| false, |_, _| true, counted)
                } else {
                    glass.go_on::<true, true>(&mut scan, u64::MAX, |_, _| false, |_, _| true, counted)
                };
                assert!(over);
                units[k] = glass.clock.work - before;
            }
            assert_eq!(seen[0], seen[1], "time step {now}");
            skipped += units[0] - units[1];
            checks += 1;
        }
        assert!(checks > 100 && skipped > 1000, "{checks} checks, {skipped} entries skipped");
    }
}
