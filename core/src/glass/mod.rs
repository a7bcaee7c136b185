//! Model B: a glass plate hit by a ball (Agui, Moriyama, Nagao, Nakajima, "Representation of
//! cracks in plate glass by CG"; `docs/src/models/papers.md`, Model B).
//!
//! An impact starts M radial cracks at the impact point (N of them large) and R ring start
//! points, each growing a counter-clockwise and a clockwise crack. Every step each growing
//! tip turns towards the sum of three forces found in the sector ahead of it: a push away
//! from other tips (F1), a pull to meet cracks and edges at right angles (F2), and a random
//! one (F3). A tip that reaches a crack or the edge stops exactly on it. Generation ends when
//! every large and ring crack has stopped. A stop that closes a region bounded by cracks alone
//! stops every crack growing inside it. [`Glass::fragments`] gives the regions the network
//! cuts the plate into, as polygons.
//!
//! ```
//! # #[cfg(feature = "alloc")] { // `allocate` needs the `alloc` feature
//! use hibi_core::glass::{Glass, GlassLayers, GlassParams, GlassRender};
//!
//! let params = GlassParams { width: 160.0, height: 160.0, impact: [80.0, 80.0], ..GlassParams::default() };
//! let mut memory = params.memory().unwrap().allocate(); // or GlassStorage, or your own buffers
//! let mut glass: Glass = Glass::new(&params, memory.buffers()).unwrap(); // computes in f32
//! while !glass.step(100_000).finished {}
//! let mut mask = vec![0u8; 64 * 64];
//! let render = GlassRender { width: 64, height: 64, ..GlassRender::default() };
//! glass.render(&render, GlassLayers { mask: Some(&mut mask), ..GlassLayers::default() }).unwrap();
//! assert!(mask.iter().any(|&m| m > 0));
//! # }
//! ```

use crate::enumeration::enumeration;

mod grid;
mod params;
mod presets;

pub use params::{GlassParamError, GlassParams, MAX_CAPACITY, MAX_SIDE, MAX_TIME_STEPS};
pub use presets::{PRESETS, preset};

use grid::{Buckets, Grid, NONE};
use growth::{Phase, Update};

use crate::rng::{Rng, Stream};

enumeration! {
    /// What kind of crack a polyline is.
    pub enum CrackKind {
        /// A large radial crack: fast, reaches the edge (speed V1).
        Large,
        /// Another radial crack (speed V2).
        Radial,
        /// A ring crack growing counter-clockwise from its start point (speed V3).
        RingCounterClockwise,
        /// A ring crack growing clockwise from its start point (speed V3).
        RingClockwise,
    }
    default Large
}

enumeration! {
    /// Why a crack is no longer growing.
    pub enum CrackEnd {
        /// It still grows.
        Growing,
        /// Its tip reached the plate's edge and stops exactly on it.
        Edge,
        /// Its tip reached another crack and stops on it, sharing the vertex.
        Crack,
        /// Generation of its impact ended (every large and ring crack had stopped), or a later
        /// impact began.
        Generation,
        /// Other cracks closed a region around its tip (paper §4.2.3, stop condition 2).
        Enclosed,
    }
    default Growing
}

/// One crack: its kind, its tip and how it grows, as [`Glass::crack`] reads it from its
/// [`CrackSlot`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct Crack {
    /// Large, radial or ring.
    pub kind: CrackKind,
    /// Still growing.
    pub growing: bool,
    /// Why it stopped.
    pub end: CrackEnd,
    /// Which impact started it (0 for the first).
    pub impact: u32,
    /// The tip w, a vertex of the crack.
    pub tip: [f32; 2],
    /// The direction of growth \[radians\].
    pub heading: f32,
    /// |v|, pixels per step.
    pub speed: f32,
    /// Steps grown (t in weight(t)).
    pub age: u32,
    /// The step at which the crack starts growing (ring cracks wait for the large ones).
    pub wake: u32,
    /// Ring cracks: the impact point and the ring's radius d_i.
    pub ring: ([f32; 2], f32),
}

/// Where a plate keeps one crack: its state as plain numbers (`u32` and `f32` fields only,
/// its kind, end and growing flag as their numbers), so that any bytes are a slot and caller
/// memory can be handed in as it is. Opaque: read a crack with [`Glass::crack`]. The plate
/// writes a slot before it reads it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CrackSlot {
    /// [`CrackKind`] as its number.
    kind: u32,
    /// 1 while it grows, else 0.
    growing: u32,
    /// [`CrackEnd`] as its number.
    end: u32,
    impact: u32,
    tip: [f32; 2],
    heading: f32,
    speed: f32,
    age: u32,
    wake: u32,
    ring: ([f32; 2], f32),
    /// First and last segment of the crack's chain (NONE before the first step).
    first_segment: u32,
    last_segment: u32,
    /// The crack's start vertex.
    start_vertex: u32,
    /// The tip at the start of the current time step: what other tips' F1 sees, so that all
    /// tips move at once (Eq. 17) whatever order they are advanced in. Kept while it grows.
    before: [f32; 2],
    /// Its direction at the start of the current time step (unit vector).
    before_direction: [f32; 2],
    /// The direction the crack started in: F3's mean for a radial crack.
    start_heading: f32,
    /// What is left of the current time step's move (0 between steps) \[px\].
    left: f32,
}

impl CrackSlot {
    /// Still growing.
    fn growing(&self) -> bool {
        self.growing != 0
    }

    /// Of `kind`.
    fn is(&self, kind: CrackKind) -> bool {
        self.kind == kind as u32
    }

    /// A ring crack, either way round.
    fn is_ring(&self) -> bool {
        self.is(CrackKind::RingCounterClockwise) || self.is(CrackKind::RingClockwise)
    }

    /// Stops growing, for `end`.
    fn stop(&mut self, end: CrackEnd) {
        self.growing = 0;
        self.end = end as u32;
    }

    /// The crack a written slot holds (its numbers are those `Glass::add_crack` and
    /// `CrackSlot::stop` write; a number out of range, which the plate never writes, would
    /// read as the default).
    fn crack(&self) -> Crack {
        Crack {
            kind: CrackKind::from_u32(self.kind).unwrap_or_default(),
            growing: self.growing(),
            end: CrackEnd::from_u32(self.end).unwrap_or_default(),
            impact: self.impact,
            tip: self.tip,
            heading: self.heading,
            speed: self.speed,
            age: self.age,
            wake: self.wake,
            ring: self.ring,
        }
    }
}

/// A crack vertex. Where cracks meet, both share the vertex.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vertex {
    /// Position (x, y) in pixels.
    pub at: [f32; 2],
    /// The first edge of the vertex's incidence list (NONE when it has none).
    first_edge: u32,
}

/// A straight piece of a crack between two vertices, chained in growth order, with the time
/// (steps since its impact) the crack front passed each end.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Edge {
    from: u32,
    to: u32,
    crack: u32,
    next: u32,
    time: [f32; 2],
    /// The next edge in the incidence lists of `from` and of `to`.
    links: [u32; 2],
    /// The pseudo-angle of the edge's direction leaving `from` and leaving `to`, for ordering
    /// edges around a vertex.
    angles: [f32; 2],
    /// The positions of `from` and `to` (x, y, x, y), kept beside the edge for the queries.
    ends: [f32; 4],
}

/// How much caller memory a plate needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GlassMemory {
    /// [`CrackSlot`]s.
    pub cracks: usize,
    /// [`Vertex`] records.
    pub vertices: usize,
    /// [`Edge`] records.
    pub edges: usize,
    /// `u32` words (spatial grids).
    pub words: usize,
    /// `u32` words of scratch for one fragment query ([`Glass::fragment_counts`],
    /// [`Glass::fragments`]): the caller's, not the plate's, so that queries only read the
    /// plate and may run at once on one plate, each with its own scratch.
    pub scratch: usize,
}

/// Caller memory for a plate.
pub struct GlassBuffers<'a> {
    /// At least [`GlassMemory::cracks`].
    pub cracks: &'a mut [CrackSlot],
    /// At least [`GlassMemory::vertices`].
    pub vertices: &'a mut [Vertex],
    /// At least [`GlassMemory::edges`].
    pub edges: &'a mut [Edge],
    /// At least [`GlassMemory::words`].
    pub words: &'a mut [u32],
}

/// The buffers of a [`GlassStore`] or [`GlassStorage`], field by field.
macro_rules! buffers_of {
    ($store:expr) => {
        GlassBuffers {
            cracks: &mut $store.cracks,
            vertices: &mut $store.vertices,
            edges: &mut $store.edges,
            words: &mut $store.words,
        }
    };
}

/// Owned memory for a plate (the `alloc` feature), from [`GlassMemory::allocate`].
#[cfg(feature = "alloc")]
pub struct GlassStore {
    cracks: alloc::vec::Vec<CrackSlot>,
    vertices: alloc::vec::Vec<Vertex>,
    edges: alloc::vec::Vec<Edge>,
    words: alloc::vec::Vec<u32>,
}

#[cfg(feature = "alloc")]
impl GlassMemory {
    /// Owned buffers of this size.
    pub fn allocate(&self) -> GlassStore {
        GlassStore {
            cracks: alloc::vec![CrackSlot::default(); self.cracks],
            vertices: alloc::vec![Vertex::default(); self.vertices],
            edges: alloc::vec![Edge::default(); self.edges],
            words: alloc::vec![0; self.words],
        }
    }
}

#[cfg(feature = "alloc")]
impl GlassStore {
    /// The buffers, for [`Glass::new`].
    pub fn buffers(&mut self) -> GlassBuffers<'_> {
        buffers_of!(self)
    }
}

/// Fixed-size storage for callers without a heap: the sizes are those of
/// [`GlassParams::memory`] (edges as many as vertices).
pub struct GlassStorage<const CRACKS: usize, const VERTICES: usize, const WORDS: usize> {
    /// Crack slots.
    pub cracks: [CrackSlot; CRACKS],
    /// Vertex records.
    pub vertices: [Vertex; VERTICES],
    /// Edge records.
    pub edges: [Edge; VERTICES],
    /// Words.
    pub words: [u32; WORDS],
}

impl<const CRACKS: usize, const VERTICES: usize, const WORDS: usize> GlassStorage<CRACKS, VERTICES, WORDS> {
    /// Empty storage.
    pub fn new() -> Self {
        GlassStorage {
            cracks: [CrackSlot::default(); CRACKS],
            vertices: [Vertex::default(); VERTICES],
            edges: [Edge::default(); VERTICES],
            words: [0; WORDS],
        }
    }

    /// The buffers, for [`Glass::new`].
    pub fn buffers(&mut self) -> GlassBuffers<'_> {
        buffers_of!(self)
    }
}

impl<const CRACKS: usize, const VERTICES: usize, const WORDS: usize> Default for GlassStorage<CRACKS, VERTICES, WORDS> {
    fn default() -> Self {
        Self::new()
    }
}

/// Why a plate could not be set up or an output written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GlassError {
    /// A parameter is out of range.
    Param(GlassParamError),
    /// A caller buffer is too small: `needed` elements are required.
    BufferTooSmall {
        /// Elements the buffer must hold.
        needed: usize,
    },
    /// An impact point outside the plate.
    Impact,
    /// An impact on a plate whose capacity ran out (`max_cracks`, `max_vertices` or the grid's
    /// entries): generation stopped for good.
    Capacity,
}

impl From<GlassParamError> for GlassError {
    fn from(e: GlassParamError) -> Self {
        GlassError::Param(e)
    }
}

impl core::fmt::Display for GlassError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            GlassError::Param(e) => e.fmt(f),
            GlassError::BufferTooSmall { needed } => write!(f, "glass: a caller buffer is too small ({needed} needed)"),
            GlassError::Impact => f.write_str("glass: the impact point must lie inside the plate"),
            GlassError::Capacity => f.write_str("glass: a capacity ran out; the plate takes no more impacts"),
        }
    }
}

impl core::error::Error for GlassError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            GlassError::Param(e) => Some(e),
            _ => None,
        }
    }
}

/// Where generation stands, as [`Glass::step`] reports it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GlassProgress {
    /// Steps taken for the current impact, at most [`MAX_TIME_STEPS`]. A run of steps in which
    /// no crack is awake to grow (ring cracks waiting for the large ones) is counted, not done.
    pub time: u32,
    /// Cracks on the plate.
    pub cracks: u32,
    /// Cracks still growing.
    pub growing: u32,
    /// Vertices used.
    pub vertices: u32,
    /// Generation of the current impact has ended.
    pub finished: bool,
    /// A capacity (`max_cracks`, `max_vertices`, grid entries) ran out: generation stopped
    /// early, with everything drawn so far consistent, and [`Glass::impact`] is refused.
    pub capacity_reached: bool,
    /// Work done since the plate was created, in the units of [`Glass::step`]'s budget.
    pub work: u64,
}

/// The counts an impact drew (paper Eqs. 3, 5, 6).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ImpactCounts {
    /// M: radial cracks.
    pub radial: u32,
    /// N: large cracks among them.
    pub large: u32,
    /// R: ring start points (each grows two cracks).
    pub rings: u32,
}

/// Side of a grid cell \[px\]: longer than any segment (updates are at most 10 px), so a
/// segment touches at most four cells.
const GRID_CELL: f32 = 16.0;

/// Grid entries per vertex: a segment is at most one cell long, so it touches at most four
/// cells; splitting adds a segment per hit.
const ENTRIES_PER_VERTEX: usize = 5;

impl GlassParams {
    /// Validates the parameters and returns the memory a plate needs.
    pub fn memory(&self) -> Result<GlassMemory, GlassParamError> {
        self.validate()?;
        let grid = Grid::new(self.width, self.height, GRID_CELL);
        let (cracks, vertices) = (self.max_cracks as usize, self.max_vertices as usize);
        // Segment grid: heads, the heads F2 starts from, entry item and next; tip grid: heads,
        // entry item and next; one stamp per edge (to visit each segment once per query); per
        // vertex a face mark and a component root.
        let words = (|| {
            let segment = grid.cells().checked_mul(2)?.checked_add(vertices.checked_mul(2 * ENTRIES_PER_VERTEX)?)?;
            let tip = grid.cells().checked_add(cracks.checked_mul(2)?)?;
            segment.checked_add(tip)?.checked_add(vertices.checked_mul(3)?)
        })()
        .filter(|&w| w <= isize::MAX as usize / 64)
        .ok_or(GlassParamError::Capacity)?;
        let scratch = FragmentScratch::words(vertices)
            .filter(|&w| w <= isize::MAX as usize / 64)
            .ok_or(GlassParamError::Capacity)?;
        Ok(GlassMemory { cracks, vertices, edges: vertices, words, scratch })
    }
}

/// A glass plate and the cracks growing in it, over caller memory.
pub struct Glass<'a> {
    params: GlassParams,
    cracks: &'a mut [CrackSlot],
    crack_count: usize,
    /// Cracks still growing (kept, so that [`Glass::progress`] does not count them: a call of
    /// [`Glass::step`] costs its units, not the cracks on the plate).
    growing: usize,
    vertices: &'a mut [Vertex],
    vertex_count: usize,
    edges: &'a mut [Edge],
    edge_count: usize,
    /// Which segments and tips lie where.
    index: SpatialIndex<'a>,
    /// Where generation stands.
    clock: Clock,
    /// Scratch of the face walks (stop condition 2, fragments).
    walk: FaceWalk<'a>,
    /// The sector S ahead of a tip.
    sector: Sector,
    impacts: u32,
    counts: ImpactCounts,
    forces: Rng,
}

/// The grids that find the segments and tips near a point.
struct SpatialIndex<'a> {
    grid: Grid,
    segments: Buckets<'a>,
    /// Per segment cell whose list holds entries filed in the time step under way (its head
    /// at `fresh` or later): the first entry of that list that F2 has to look at, past the
    /// segments grown in this time step, which F2 passes over (all tips move at once). Read
    /// only for such a cell, so written only as such a cell gets its first entry of the step.
    earlier: &'a mut [u32],
    /// The first segment entry filed in the time step under way.
    fresh: u32,
    tips: Buckets<'a>,
    /// Per edge: the stamp of the latest query that visited it (to visit each segment once).
    stamps: &'a mut [u32],
    stamp: u32,
}

/// Where generation of the current impact stands.
struct Clock {
    time: u32,
    /// The next crack to advance in the current step.
    cursor: usize,
    /// The step count after which generation ends regardless (no crack grows forever): at most
    /// [`MAX_TIME_STEPS`].
    time_limit: u32,
    /// A crack was advanced in the time step under way.
    awake: bool,
    /// The earliest step at which a growing crack passed over in it wakes (`u32::MAX` if none).
    next_wake: u32,
    finished: bool,
    capacity_reached: bool,
    /// Units of work done so far (grid cells and entries examined, cracks looked at, face
    /// walks' steps): what [`Glass::step`]'s budget counts.
    work: u64,
    /// What the time step under way is doing, and how far along it is ([`Glass::step`] stops
    /// between any two units of work and resumes here).
    phase: Phase,
    /// How far along `phase` is: grid cells emptied, tips unfiled, cracks filed, cracks checked.
    done: usize,
    /// The update of the tip under way.
    update: Update,
}

/// Scratch of the walks around faces of the crack network.
struct FaceWalk<'a> {
    /// Per vertex: the stamp of the latest face walk that passed it.
    marks: &'a mut [u32],
    mark: u32,
    /// Per vertex: its parent in the union–find forest of connected cracks.
    roots: &'a mut [u32],
}

/// The sector S ahead of a tip, angle φ (paper §4.2.2).
#[derive(Clone, Copy)]
struct Sector {
    /// cos(φ/2): a point is in a tip's sector when its direction's cosine with the heading
    /// is at least this.
    cosine: f32,
    /// sin(φ/2).
    sine: f32,
}

/// Cuts the first `n` elements off a buffer.
fn take<'a, T>(buffer: &mut &'a mut [T], n: usize) -> &'a mut [T] {
    let (head, tail) = core::mem::take(buffer).split_at_mut(n);
    *buffer = tail;
    head
}

/// ⌊x⌋, the very value of `libm::floorf` (−0.0, infinities and NaN included), without its call:
/// below 2²³ in magnitude through the integer part, else x (every such f32 is an integer).
fn floor(x: f32) -> f32 {
    if x.abs() < 8_388_608.0 {
        let i = x as i32 as f32;
        if i == x {
            x
        } else if i > x {
            i - 1.0
        } else {
            i
        }
    } else {
        x
    }
}

/// ⌈x⌉, the very value of `libm::ceilf`, as [`floor`] is `floorf`'s.
fn ceil(x: f32) -> f32 {
    if x.abs() < 8_388_608.0 {
        let i = x as i32 as f32;
        if i == x {
            x
        } else if i < x {
            i + 1.0
        } else {
            i.copysign(x)
        }
    } else {
        x
    }
}

/// `angle` wrapped into (−π, π].
fn wrap(angle: f32) -> f32 {
    let tau = 2.0 * core::f32::consts::PI;
    let mut a = angle - tau * floor(angle / tau);
    if a > core::f32::consts::PI {
        a -= tau;
    }
    a
}

impl<'a> Glass<'a> {
    /// Sets up the plate and the first impact (at `params.impact`). Nothing is written to the
    /// buffers on failure. Its work does not grow with the capacities or the plate: it writes
    /// the first impact's cracks and vertices (as [`Glass::impact`]) and nothing else, and
    /// reads nothing it did not write, so the buffers may hold anything; the grids are emptied
    /// by the first units of [`Glass::step`], within its budgets. Every query (render, points,
    /// counts, fragments, progress) and [`Glass::impact`] may be called at once.
    pub fn new(params: &GlassParams, buffers: GlassBuffers<'a>) -> Result<Self, GlassError> {
        let m = params.memory()?;
        let short = [
            (buffers.cracks.len(), m.cracks),
            (buffers.vertices.len(), m.vertices),
            (buffers.edges.len(), m.edges),
            (buffers.words.len(), m.words),
        ];
        if let Some(&(_, needed)) = short.iter().find(|(have, need)| have < need) {
            return Err(GlassError::BufferTooSmall { needed });
        }
        let grid = Grid::new(params.width, params.height, GRID_CELL);
        let mut words = buffers.words;
        let vertices = params.max_vertices as usize;
        let cracks = params.max_cracks as usize;
        let segments = Buckets {
            heads: take(&mut words, grid.cells()),
            entries: take(&mut words, 2 * vertices * ENTRIES_PER_VERTEX).as_chunks_mut().0,
            used: 0,
        };
        let earlier = take(&mut words, grid.cells());
        let tips = Buckets {
            heads: take(&mut words, grid.cells()),
            entries: take(&mut words, 2 * cracks).as_chunks_mut().0,
            used: 0,
        };
        // Nothing is cleared here, so that creation takes the same time whatever the
        // capacities: the grids' cells are emptied by the first units of `step`
        // (`Phase::Clear`), and a vertex's mark and root and an edge's stamp are set when it
        // is added. No word is read before it is written.
        let stamps = take(&mut words, vertices);
        let marks = take(&mut words, vertices);
        let roots = take(&mut words, vertices);
        let mut glass = Glass {
            params: *params,
            cracks: &mut buffers.cracks[..cracks],
            crack_count: 0,
            growing: 0,
            vertices: &mut buffers.vertices[..vertices],
            vertex_count: 0,
            edges: &mut buffers.edges[..vertices],
            edge_count: 0,
            index: SpatialIndex { grid, segments, earlier, fresh: 0, tips, stamps, stamp: 0 },
            clock: Clock {
                time: 0,
                cursor: 0,
                time_limit: 0,
                awake: false,
                next_wake: u32::MAX,
                finished: false,
                capacity_reached: false,
                work: 0,
                phase: Phase::Clear,
                done: 0,
                update: Update::IDLE,
            },
            walk: FaceWalk { marks, mark: 0, roots },
            sector: Sector {
                cosine: libm::cosf(0.5 * params.sector_angle),
                sine: libm::sinf(0.5 * params.sector_angle),
            },
            impacts: 0,
            counts: ImpactCounts { radial: 0, large: 0, rings: 0 },
            forces: Rng::new(params.seed, Stream::RandomForce),
        };
        glass.impact(params.impact)?;
        Ok(glass)
    }

    /// Adds an impact at `at`: draws M, N and R and starts its cracks (paper §4.2.1). Cracks
    /// of earlier impacts stay; new cracks stop where they meet them, and an impact (or a ring
    /// crack's start point) on an earlier crack starts from it. Growth of any earlier
    /// impact still running ends first. Its cost is bounded by the capacities: it starts at
    /// most M + 2R cracks, looks at no more than `max_cracks` ring start points, and for the
    /// impact and each start point looks once at every vertex and segment so far.
    ///
    /// Refused, with nothing changed: a point outside the plate ([`GlassError::Impact`]), and
    /// any impact once a capacity has run out ([`GlassError::Capacity`]: generation stopped
    /// for good, as every later [`Glass::step`] reports). An impact that runs out of capacity
    /// while it starts its cracks is made (its counts returned), and growth then stops at once.
    pub fn impact(&mut self, at: [f32; 2]) -> Result<ImpactCounts, GlassError> {
        let p = self.params;
        if !(at[0] > 0.0 && at[0] < p.width && at[1] > 0.0 && at[1] < p.height) {
            return Err(GlassError::Impact);
        }
        if self.clock.capacity_reached {
            return Err(GlassError::Capacity);
        }
        self.finish();
        let key = |stream: Stream| Rng::from_key(p.seed, stream.key() ^ (u64::from(self.impacts) << 32));
        let (mut count_rng, mut speed_rng, mut radius_rng, mut turn_rng) =
            (key(Stream::RadialCount), key(Stream::CrackSpeed), key(Stream::RingRadius), key(Stream::ImpactRotation));
        // Eq. 5: M = Poisson_Rand(M_ave); Eq. 6: N = ⌊e·M + f⌋; Eq. 3: R = ⌊a·M + b⌋ if M > A.
        let m = count_rng.poisson(f64::from(p.radial_mean)).unwrap_or(0);
        let mf = m as f32;
        let n = (libm::floorf(p.large_slope * mf + p.large_offset) as u32).min(m);
        let r = if mf > p.ring_threshold { libm::floorf(p.ring_slope * mf + p.ring_offset) as u32 } else { 0 };
        let counts = ImpactCounts { radial: m, large: n, rings: r };
        self.counts = counts;
        let impact = self.impacts;
        self.impacts += 1;
        self.clock.time = 0;
        self.clock.cursor = 0;
        if self.clock.phase != Phase::Clear {
            // A new plate's grids are still being emptied (no tip is filed yet): that goes on.
            self.clock.phase = Phase::Unfile;
            self.clock.done = 0;
        }
        self.clock.finished = false;
        // Long enough to cross the plate twice at the slowest speed Rand can draw, and at most
        // MAX_TIME_STEPS (a float past u32::MAX saturates).
        let slowest = p.large_speed.min(p.radial_speed).min(p.ring_speed) * (1.0 - p.spread_ratio);
        let crossing = libm::ceilf(2.0 * (p.width + p.height) / slowest) as u32;
        self.clock.time_limit = crossing.saturating_add(16).min(MAX_TIME_STEPS);
        self.clock.awake = false;
        self.clock.next_wake = u32::MAX;
        let tau = 2.0 * core::f32::consts::PI;
        let rotation = turn_rng.uniform_f32() * tau;
        // At most FLT_MAX: Rand((1 + z)·x) of a speed or radius near FLT_MAX is +inf, and an
        // infinite speed made the crack times NaN (inf − inf; found by fuzzing).
        let rand = |rng: &mut Rng, x: f32| rng.rand(x, p.spread_ratio, p.spread).unwrap_or(x).min(f32::MAX);
        let centre = self.vertex_at(at);
        // Radial cracks at equal angles; the N large ones spread as evenly as possible.
        for i in 0..m {
            let large = n > 0 && (i * n) / m != ((i + 1) * n) / m;
            let (kind, speed) = if large {
                (CrackKind::Large, rand(&mut speed_rng, p.large_speed))
            } else {
                (CrackKind::Radial, rand(&mut speed_rng, p.radial_speed))
            };
            let heading = wrap(rotation + tau * i as f32 / mf);
            self.add_crack(kind, impact, centre, heading, speed, ([0.0; 2], 0.0));
        }
        // Ring start points C_i at angles 2π·i/R (their own rotation, so that they do not line
        // up with the large cracks), radius d_i = Rand(g·M + h) (Eqs. 7, 8), each growing two
        // cracks with one speed V3_i (Eq. 11). A ring crack wakes once the large cracks have
        // passed its radius (step ⌈d_i / V1_ave⌉): radial cracks run first and the rings join
        // them, and large cracks, by definition, reach the edge.
        // The loop is bounded by the capacities, whatever R the floats give: it stops once the
        // cracks or the vertices are full (no ring crack can be added after that), and looks
        // at no more than `max_cracks` start points (each grows two cracks, so more than that
        // can never all be held: a larger R counts as running out of capacity).
        let ring_mean = p.ring_radius_slope * mf + p.ring_radius_offset;
        let ring_rotation = turn_rng.uniform_f32() * tau;
        if r > p.max_cracks {
            self.clock.capacity_reached = true;
        }
        for i in 0..r.min(p.max_cracks) {
            if self.crack_count == self.cracks.len() || self.vertex_count == self.vertices.len() {
                self.clock.capacity_reached = true;
                break;
            }
            let angle = ring_rotation + tau * i as f32 / r as f32;
            let radius = rand(&mut radius_rng, ring_mean);
            let start = [at[0] + radius * libm::cosf(angle), at[1] + radius * libm::sinf(angle)];
            if !(start[0] > 0.0 && start[0] < p.width && start[1] > 0.0 && start[1] < p.height) {
                continue; // off the plate: no ring crack there
            }
            let speed = rand(&mut speed_rng, p.ring_speed);
            let vertex = self.vertex_at(start);
            let quarter = core::f32::consts::FRAC_PI_2;
            let wake = libm::ceilf(radius / p.large_speed) as u32;
            for (kind, heading) in
                [(CrackKind::RingCounterClockwise, angle + quarter), (CrackKind::RingClockwise, angle - quarter)]
            {
                self.add_crack(kind, impact, vertex, wrap(heading), speed, (at, radius));
                if let Some(c) = self.cracks[..self.crack_count].last_mut() {
                    c.wake = wake;
                }
            }
        }
        if self.clock.capacity_reached {
            self.finish();
        }
        Ok(counts)
    }

    /// Adds a vertex; NONE (and capacity reached) when the pool is full.
    fn add_vertex(&mut self, at: [f32; 2]) -> u32 {
        if self.vertex_count == self.vertices.len() {
            self.clock.capacity_reached = true;
            return NONE;
        }
        self.vertices[self.vertex_count] = Vertex { at, first_edge: NONE };
        self.walk.roots[self.vertex_count] = self.vertex_count as u32;
        // No face walk has passed it yet (a mark is never 0).
        self.walk.marks[self.vertex_count] = 0;
        self.vertex_count += 1;
        (self.vertex_count - 1) as u32
    }

    fn add_crack(&mut self, kind: CrackKind, impact: u32, start: u32, heading: f32, speed: f32, ring: ([f32; 2], f32)) {
        if start == NONE || self.crack_count == self.cracks.len() {
            self.clock.capacity_reached = true;
            return;
        }
        self.cracks[self.crack_count] = CrackSlot {
            kind: kind as u32,
            growing: 1,
            end: CrackEnd::Growing as u32,
            impact,
            tip: self.vertices[start as usize].at,
            heading,
            speed,
            age: 0,
            wake: 0,
            ring,
            first_segment: NONE,
            last_segment: NONE,
            start_vertex: start,
            before: self.vertices[start as usize].at,
            before_direction: [libm::cosf(heading), libm::sinf(heading)],
            start_heading: heading,
            left: 0.0,
        };
        self.crack_count += 1;
        self.growing += 1;
    }

    /// Stops every crack: generation of the current impact has ended.
    fn finish(&mut self) {
        for crack in self.cracks[..self.crack_count].iter_mut().filter(|c| c.growing()) {
            crack.stop(CrackEnd::Generation);
        }
        self.growing = 0;
        self.clock.finished = true;
    }

    /// Stops crack `i`, for `end`.
    fn stop(&mut self, i: usize, end: CrackEnd) {
        let c = &mut self.cracks[i];
        self.growing -= usize::from(c.growing());
        c.stop(end);
    }

    /// The counts drawn by the latest impact.
    pub fn impact_counts(&self) -> ImpactCounts {
        self.counts
    }

    /// The parameters.
    pub fn params(&self) -> &GlassParams {
        &self.params
    }

    /// Number of cracks.
    pub fn crack_count(&self) -> usize {
        self.crack_count
    }

    /// Crack `i`.
    pub fn crack(&self, i: usize) -> Option<Crack> {
        self.cracks[..self.crack_count].get(i).map(CrackSlot::crack)
    }

    /// Where generation stands.
    pub fn progress(&self) -> GlassProgress {
        GlassProgress {
            time: self.clock.time,
            cracks: self.crack_count as u32,
            growing: self.growing as u32,
            vertices: self.vertex_count as u32,
            finished: self.clock.finished,
            capacity_reached: self.clock.capacity_reached,
            work: self.clock.work,
        }
    }
}

mod faces;
mod fragment_build;
mod fragments;
mod growth;
mod output;
mod render;
mod scan;

#[cfg(feature = "alloc")]
pub use fragment_build::FragmentBuildStore;
pub use fragment_build::{FragmentBuild, FragmentBuildBuffers, FragmentBuildMemory, FragmentProgress};
use fragments::FragmentScratch;
pub use growth::STEP_PIECE;
pub use output::CrackPoint;
pub use render::{GlassLayers, GlassRender};

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use std::vec;
    use std::vec::Vec;

    /// `floor` and `ceil` give libm's very bits: zeros of both signs, halves, values next to
    /// integers and to 2²³, huge values, infinities and NaN, and a sweep of 10⁵ values.
    #[test]
    fn floor_and_ceil_are_libms_to_the_bit() {
        let mut values = vec![0.0f32, -0.0, 0.5, -0.5, 1.0, -1.0, 1.5, -1.5, 8_388_607.5, -8_388_607.5];
        values.extend([8_388_608.0, -8_388_608.0, 1e20, -1e20, f32::INFINITY, f32::NEG_INFINITY, f32::NAN]);
        values.extend([f32::MIN_POSITIVE, -f32::MIN_POSITIVE, 1e-45, -1e-45, 3.0f32.next_up(), (-3.0f32).next_down()]);
        let mut x = 0x1234_5678u32;
        for _ in 0..100_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            values.push((x as i32) as f32 / 65_536.0);
        }
        for v in values {
            assert_eq!(floor(v).to_bits(), libm::floorf(v).to_bits(), "floor {v:e}");
            assert_eq!(ceil(v).to_bits(), libm::ceilf(v).to_bits(), "ceil {v:e}");
        }
    }

    /// Grows `p` to its end with `setup` applied to the new plate and `each` before every call
    /// of `step(budget)`: every crack's end and points (position and time bits), and the
    /// segment queries' stamp and the face walks' mark at the end.
    fn grown(
        p: &GlassParams,
        budget: u64,
        setup: impl FnOnce(&mut Glass),
        mut each: impl FnMut(&mut Glass),
    ) -> (Vec<u32>, u32, u32) {
        let m = p.memory().unwrap();
        let (mut cracks, mut vertices) = (vec![CrackSlot::default(); m.cracks], vec![Vertex::default(); m.vertices]);
        let (mut edges, mut words) = (vec![Edge::default(); m.edges], vec![0u32; m.words]);
        let buffers =
            GlassBuffers { cracks: &mut cracks, vertices: &mut vertices, edges: &mut edges, words: &mut words };
        let mut glass = Glass::new(p, buffers).unwrap();
        setup(&mut glass);
        loop {
            each(&mut glass);
            if glass.step(budget).finished {
                break;
            }
        }
        let mut bits = Vec::new();
        for i in 0..glass.crack_count() {
            bits.push(glass.cracks[i].end);
            glass.for_each_point(i, |q| bits.extend([q.at[0], q.at[1], q.time].map(f32::to_bits)));
        }
        (bits, glass.index.stamp, glass.walk.mark)
    }

    /// Creation clears no word, and an edge's stamp and a vertex's mark are set when it is
    /// added: garbage in the grids and their entries when the plate is created, and in the
    /// stamps and marks of the edges and vertices not yet added the stamp and mark one of the
    /// next queries and walks takes (set before every unit of work), give the same plate
    /// (`growth::tests` checks the stamp of an edge added over the very next query's). So do
    /// stamps and marks that start over (after 2³² − 1 of them) half way through the run.
    #[test]
    fn garbage_in_the_words_and_stamps_and_marks_that_start_over_leave_the_plate_as_it_was() {
        let p = GlassParams { seed: 7, ..GlassParams::default() };
        let (plain, stamps, marks) = grown(&p, u64::MAX, |_| {}, |_| {});
        assert!(stamps > 1000 && marks > 10, "{stamps} segment queries, {marks} face walks");
        let garbage = grown(
            &p,
            1,
            |g| {
                g.index.segments.heads.fill(7);
                g.index.segments.entries.fill([3, 5]);
                g.index.earlier.fill(11);
                g.index.tips.heads.fill(9);
                g.index.tips.entries.fill([1, 2]);
            },
            |g| {
                // The next 64 edges and vertices: edge e the stamp of the query 1 + (37e mod 256)
                // ahead, vertex v the mark of the walk 1 + (v mod 8) ahead.
                let (stamp, mark) = (g.index.stamp, g.walk.mark);
                let (edges, vertices) = (g.edge_count, g.vertex_count);
                for (e, s) in g.index.stamps.iter_mut().enumerate().skip(edges).take(64) {
                    *s = stamp.wrapping_add(1 + (37 * e as u32) % 256);
                }
                for (v, m) in g.walk.marks.iter_mut().enumerate().skip(vertices).take(64) {
                    *m = mark.wrapping_add(1 + v as u32 % 8);
                }
            },
        );
        assert_eq!(garbage.0, plain, "garbage in the words");
        let start_over = |g: &mut Glass| {
            g.index.stamp = u32::MAX - stamps / 2;
            g.walk.mark = u32::MAX - marks / 2;
        };
        // Run once: the query that first visits each edge after the stamps start over.
        let mut first = vec![0u32; p.max_vertices as usize];
        let wrapped = grown(&p, 1, start_over, |g| {
            if g.index.stamp < stamps {
                for (e, &s) in g.index.stamps[..g.edge_count].iter().enumerate() {
                    if first[e] == 0 && s < stamps {
                        first[e] = s;
                    }
                }
            }
        });
        assert!(wrapped.1 < stamps && wrapped.2 < marks, "{}, {}: they did not start over", wrapped.1, wrapped.2);
        assert_eq!(wrapped.0, plain, "stamps and marks that start over");
        // Run again, with the stamps and marks of the edges and vertices there just before they
        // start over (those not of the query or walk under way) made those of queries and walks
        // 2³² − 1 earlier: each edge's, the query that first visits it after the start; each
        // vertex's, one of the first eight walks. The queries and walks after the start must
        // not take them for their own.
        let long_ago = |g: &mut Glass| {
            let (stamp, mark) = (g.index.stamp, g.walk.mark);
            if stamp >= u32::MAX - 2 {
                for (e, s) in g.index.stamps[..g.edge_count].iter_mut().enumerate() {
                    if *s != stamp {
                        *s = first[e];
                    }
                }
            }
            if mark == u32::MAX {
                for (v, m) in g.walk.marks[..g.vertex_count].iter_mut().enumerate() {
                    if *m != mark {
                        *m = 1 + v as u32 % 8;
                    }
                }
            }
        };
        let wrapped = grown(&p, 1, start_over, long_ago);
        assert_eq!(wrapped.0, plain, "stamps and marks that start over, with those of long ago");
    }
}
