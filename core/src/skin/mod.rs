//! Model C: skin surface texture from hierarchical Voronoi cells (Ishii, Yasuda, Yokoi,
//! Toriwaki, "Human skin rendering based on the surface microstructures"; `docs/src/models/papers.md`,
//! Model C).
//!
//! Furrows form a net; the ridges they enclose rise from their base polygon's edges towards
//! its centre point. The base polygons are Voronoi cells of jittered lattice points, their
//! edges perturbed by midpoint displacement and stretched along a direction; inside each
//! polygon the division repeats for the next level. A ridge's cross-section is a Bézier
//! profile along the ray from its centre point to its edge; heights add up over the levels
//! and normals come from the profiles' slopes.
//!
//! [`Skin::step`] builds the cell outlines into caller memory, one cell at a time, depth
//! first (fixed point, 1/2^(8+12·level) px, shared edges bit for bit);
//! [`Skin::render`] evaluates height, normal and cell maps into caller buffers; [`shade`]
//! lights a normal map for a preview.
//!
//! ```
//! # #[cfg(feature = "alloc")] { // `allocate` needs the `alloc` feature
//! use hibi_core::skin::{Skin, SkinLayers, SkinParams, SkinRender};
//!
//! let params = SkinParams { width: 64, height: 64, ..SkinParams::default() };
//! let mut memory = params.memory().unwrap().allocate(); // or SkinStorage, or your own buffers
//! let mut skin: Skin = Skin::new(&params, memory.buffers()).unwrap(); // Skin<Q16> for fixed point
//! while !skin.step(100_000).finished {}
//! let mut height = vec![0.0f32; 64 * 64];
//! let render = SkinRender::default();
//! skin.render(&render, SkinLayers { height: Some(&mut height), ..SkinLayers::default() }).unwrap();
//! assert!(height.iter().any(|&h| h > 2.0));
//! # }
//! ```

mod cell;
mod grid;
mod nearest;
mod params;
mod presets;
mod profile;
mod scan;
mod shade;
mod shared;
mod sites;
mod surface;

pub use cell::{ClipVertex, MAX_OUTLINE};
pub use params::{
    LevelParams, MAX_LEVELS, MAX_PERTURBATION_DEPTH, MAX_SEGMENTS, Profile, SiteLayout, SkinParamError, SkinParams,
};
pub use presets::{PRESETS, preset};
pub use shade::{ShadeError, ShadeParams, shade};
pub use sites::Site;
pub use surface::{FURROWS, SkinLayers, SkinRender, Wedge};

use cell::{Builder, Frame, Parent};
use grid::EdgeGrid;
use nearest::Buckets;
use profile::{ProfileTable, SAMPLES};
use shared::SharedEdges;
use sites::Lattice;

use core::marker::PhantomData;

use crate::scalar::Scalar;

/// Most rows and columns on each side of a level-0 centre that its neighbour window reaches
/// ([`Window`]), and the reach of the box a periodic level-0 cell is clipped to, in lattice
/// steps (less one).
const WINDOW: i64 = 4;
/// Most centre points one parent can hold, or one level-1 window.
pub const MAX_CHILDREN: usize = 4096;
/// No cell (a parent of a level-1 cell).
pub const NO_CELL: u32 = u32::MAX;

/// One cell: its level, its parent (index in [`Skin::cells`]), its centre point and its
/// outline (counter-clockwise in fixed point of [`Skin::fixed_point_bits`] fractional bits, in
/// [`Skin::vertices`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(C)]
pub struct SkinCell {
    /// Hierarchy level, 0 for the coarsest.
    pub level: u32,
    /// Index of the parent cell, [`NO_CELL`] at level 0.
    pub parent: u32,
    /// The centre point's id, unique within the level.
    pub site: u32,
    /// Index of the outline's first vertex.
    pub first_vertex: u32,
    /// Vertices in the outline.
    pub vertex_count: u32,
    /// The centre point in fixed point.
    pub centre: [i64; 2],
}

/// One level's state in caller memory (opaque; caller memory for [`SkinBuffers`]): its
/// profile table, which every level reads (its cells' heights and slopes).
#[derive(Clone, Default)]
pub struct SkinLevel {
    table: ProfileTable,
}

/// The state of one level from 1 in caller memory (opaque; caller memory for
/// [`SkinBuffers`], one per level below the first): its parent outline's edge grid and the
/// scratch that splits a bisector edge where that outline crosses it. Only these levels read
/// them: a level-0 cell's parent is a rectangle (the surface, or a box around a periodic
/// centre) that is never stored nor binned, and its
/// bisector edges end on that rectangle, crossing none of its edges (one piece each, and no
/// parent edge to list near it). A level's grid stays filled while all its siblings are built,
/// between the cells of finer levels: one per level.
#[derive(Clone)]
pub struct SkinDivision {
    grid: EdgeGrid,
    crossing: cell::CrossingScratch,
    /// How the parent's children are bucketed (their places in `words` at
    /// [`Layout::words_at`]), when they are more than [`cell::FEW`].
    buckets: Buckets,
}

impl Default for SkinDivision {
    fn default() -> Self {
        SkinDivision { grid: EdgeGrid::new(), crossing: cell::CrossingScratch::new(), buckets: Buckets::default() }
    }
}

/// The edges one level keeps for its cells' neighbours, in caller memory (opaque; caller
/// memory for [`SkinBuffers`], one per level that keeps edges: perturbed to depth 1 or 2 at
/// level 0, not perturbed deeper than 2 below it).
#[derive(Clone)]
pub struct SkinSharedEdges(SharedEdges);

impl Default for SkinSharedEdges {
    fn default() -> Self {
        SkinSharedEdges(SharedEdges::new())
    }
}

/// Whether level `level` of `p` keeps its bisector edges for its cells' neighbours (and so
/// needs a [`SkinSharedEdges`]). An edge is kept only when the inner points it writes number
/// at most [`shared::KEPT_POINTS`] (`finish` in [`cell`]; fewer slots would change nothing but
/// what is recomputed): each piece of an edge writes `2^depth − 1` inner points when
/// perturbed ([`level0_pieces`]' condition), none otherwise, and each piece after the first
/// one more, its start where a parent edge crosses. So:
/// - a level perturbed deeper than 2 writes 7 or more per piece: it keeps no edge;
/// - level 0's edges are one piece each (nothing crosses them: [`SkinDivision`]); unperturbed
///   they have no inner point, and keeping one would save nothing (its neighbour writes
///   nothing between the edge's corners either way, the same vertices): it keeps edges only
///   when perturbed to depth 1 or 2;
/// - a finer level's edges keep their crossings even when unperturbed.
fn keeps_edges(p: &SkinParams, level: usize) -> bool {
    let l = &p.level[level];
    let inner = if l.perturbation > 0.0 && l.perturbation_depth > 0 { (1usize << l.perturbation_depth) - 1 } else { 0 };
    inner <= shared::KEPT_POINTS && (level > 0 || inner > 0)
}

/// The level-0 centre points a cell is clipped among: rows `−rows..=rows` around the centre's
/// own, row `dj` holding the columns `−columns[dj]..=columns[dj]` around its own, listed row by
/// row (the order of ids, which breaks ties in the clipping).
///
/// It holds every centre point within 2ρ of the centre a ([`Lattice::reach`]: every point of
/// the plane lies within ρ of some centre; [`Lattice::columns_within`] bounds the rows and
/// columns that can lie within 2ρ), and those are all that can bound a's cell. Proof: a cell
/// is clipped by its neighbours' bisectors nearest first ([`cell`]). Once every centre within
/// 2ρ has clipped, the outline lies in W = {p : |p − a| ≤ |p − c| for each of them}, which is
/// convex and holds a. A point p of W nearer a than 2ρ − ρ′ (ρ′ < ρ the true reach, ρ adding a
/// hundredth of a step) has its nearest centre c within ρ′ of it, hence within 2ρ of a, so c
/// is among them and |p − a| ≤ |p − c| ≤ ρ′. So no point of W lies between ρ′ and 2ρ − ρ′ > ρ′
/// from a, and being convex and holding a, W lies within ρ′ of a. The bisector of a farther
/// centre is more than ρ from a: it leaves the outline as it is, and a larger window (as the
/// 81 centres of WINDOW = 4 once were) builds the very same outline.
///
/// Each side is capped at [`WINDOW`] rows or columns. On a lattice of the spacing's own steps
/// the bound stays within it (4 rows and columns at most, for jitter 1 on a triangular
/// lattice); a periodic lattice's steps are fitted to the period, and where that squeezes one
/// axis's step far below the other's (a period of a few spacings or less) the bound can pass
/// it. There the window is capped, as every skin's was before, and not proven.
#[derive(Clone, Copy, Debug)]
struct Window {
    rows: i64,
    /// Per row from `−WINDOW` (index 0), the columns on either side (0 beyond `rows`; bytes:
    /// the window is part of every `Skin`, which callers keep on a small stack).
    columns: [u8; 2 * WINDOW as usize + 1],
}

impl Window {
    fn of(lattice: &Lattice) -> Window {
        let radius = 2.0 * lattice.reach();
        let mut columns = [0; 2 * WINDOW as usize + 1];
        let mut rows = 0;
        for dj in 0..=WINDOW {
            // (Row 0 always holds the centre itself; a row beyond reach has no farther one
            // within it: its distance grows with |dj|.)
            let Some(c) = lattice.columns_within(dj, radius) else { break };
            rows = dj;
            columns[(WINDOW + dj) as usize] = c.clamp(0, WINDOW) as u8;
            columns[(WINDOW - dj) as usize] = c.clamp(0, WINDOW) as u8;
        }
        Window { rows, columns }
    }

    /// The columns on either side in row `dj` (|dj| ≤ `rows`).
    fn columns(&self, dj: i64) -> i64 {
        i64::from(self.columns[(WINDOW + dj) as usize])
    }

    /// The centre points it holds.
    fn sites(&self) -> usize {
        (-self.rows..=self.rows).map(|dj| 2 * self.columns(dj) as usize + 1).sum()
    }

    /// Where the centre itself lies among them.
    fn centre(&self) -> usize {
        (-self.rows..0).map(|dj| 2 * self.columns(dj) as usize + 1).sum::<usize>() + self.columns(0) as usize
    }
}

/// Where each level's scratch lies in the caller's arrays, sized by the parameters: the
/// longest outline a level can have, and from it the clip vertices and chunk boxes.
#[derive(Clone, Copy, Debug)]
struct Layout {
    /// Level 0's neighbour window.
    window: Window,
    /// Per level, the most vertices one of its outlines can have: at level 0, a cell is
    /// clipped to a rectangle (4 corners, convex) by the bisectors of at most
    /// `window.sites() − 1` neighbours, each adding at most one edge (a convex polygon meets a
    /// line in one segment), each bisector edge written as [`level0_pieces`] vertices and
    /// each piece of a side as one (level 0 crosses no parent edges); finer levels inherit
    /// their parent's corners and cross its edges: [`MAX_OUTLINE`].
    outline: [usize; MAX_LEVELS],
    /// The most vertices an outline being clipped can have (each of the clip and spare
    /// buffers): at level 0 the rectangle's 4 and one more per neighbour's bisector (clipping
    /// a convex polygon by a half-plane adds at most one vertex); finer levels start from a
    /// parent outline that need not be convex: [`MAX_OUTLINE`].
    clip: usize,
    /// Per level, its [`SkinSharedEdges`] among the levels that keep edges ([`keeps_edges`]),
    /// none where it keeps none.
    shared: [Option<usize>; MAX_LEVELS],
}

/// Vertices one level-0 bisector edge writes (its start and its inner points): `2^depth`
/// when perturbed, else 1 (an edge is perturbed only when the ratio and the depth are both
/// above 0: [`cell`]'s `finish`).
fn level0_pieces(p: &SkinParams) -> usize {
    let l = &p.level[0];
    if l.perturbation > 0.0 && l.perturbation_depth > 0 { 1 << l.perturbation_depth } else { 1 }
}

impl Layout {
    fn of(p: &SkinParams) -> Layout {
        Layout::around(p, Window::of(&Lattice::new(p, 0)))
    }

    /// The layout of `p` with level-0 neighbour window `window`.
    fn around(p: &SkinParams, window: Window) -> Layout {
        let neighbours = window.sites() - 1;
        let first = (neighbours * level0_pieces(p) + 4).min(MAX_OUTLINE);
        let outline = core::array::from_fn(|l| if l == 0 { first } else { MAX_OUTLINE });
        let clip = if p.levels > 1 { MAX_OUTLINE } else { (neighbours + 4).min(MAX_OUTLINE) };
        let mut shared = [None; MAX_LEVELS];
        let mut count = 0;
        for (l, s) in shared.iter_mut().enumerate().take(p.levels as usize) {
            if keeps_edges(p, l) {
                *s = Some(count);
                count += 1;
            }
        }
        Layout { window, outline, clip, shared }
    }

    /// The vertices of a level's parent outline: the 4 corners of a rectangle at level 0.
    fn parent(&self, level: usize) -> usize {
        if level == 0 { 4 } else { self.outline[level - 1] }
    }

    /// Where level `level`'s parent outline, as clip vertices, starts in `parent_frames`.
    fn frames_at(&self, level: usize) -> usize {
        (0..level).map(|l| self.parent(l)).sum()
    }

    /// Chunk boxes of level `level`'s parent outline (levels from 1).
    fn boxes(&self, level: usize) -> usize {
        self.parent(level) / cell::CHUNK + 1
    }

    /// Where level `level`'s chunk boxes (those of its parent outline) start in `boxes`
    /// (levels from 1).
    fn boxes_at(&self, level: usize) -> usize {
        (1..level).map(|l| self.boxes(l)).sum()
    }

    /// The levels that keep edges ([`SkinSharedEdges`] records).
    fn shared_edges(&self) -> usize {
        self.shared.iter().flatten().count()
    }

    /// Where level `level`'s centre points start in `sites`: level 0 holds one neighbour
    /// window, each finer level one parent's children.
    fn sites_at(&self, level: usize) -> usize {
        if level == 0 { 0 } else { self.window.sites() + (level - 1) * MAX_CHILDREN }
    }

    /// Where level `level`'s buckets (its parent's children bucketed: [`nearest::WORDS`])
    /// start in `words`, after the [`MAX_CHILDREN`] words of a cell's walk (levels from 1).
    fn words_at(&self, level: usize) -> usize {
        MAX_CHILDREN + (level - 1) * nearest::WORDS
    }
}

/// How much caller memory a skin needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SkinMemory {
    /// [`SkinCell`] records.
    pub cells: usize,
    /// Outline vertices (`[i64; 2]`).
    pub vertices: usize,
    /// [`Site`] records.
    pub sites: usize,
    /// [`ClipVertex`] records.
    pub clip: usize,
    /// `u32` words.
    pub words: usize,
    /// [`SkinLevel`] records, one per level.
    pub levels: usize,
    /// [`SkinDivision`] records, one per level from 1 (none for one level).
    pub divisions: usize,
    /// [`SkinSharedEdges`] records, one per level that keeps edges (none for an unperturbed
    /// one-level skin).
    pub shared_edges: usize,
    /// Chunk boxes (`[i64; 4]`) of the parent outlines being divided.
    pub boxes: usize,
    /// [`Wedge`] records: per cell, one per outline vertex and one more (what a render reads
    /// of each cell, made as it is built).
    pub wedges: usize,
}

/// Caller memory for a skin.
pub struct SkinBuffers<'a> {
    /// At least [`SkinMemory::cells`].
    pub cells: &'a mut [SkinCell],
    /// At least [`SkinMemory::vertices`].
    pub vertices: &'a mut [[i64; 2]],
    /// At least [`SkinMemory::sites`].
    pub sites: &'a mut [Site],
    /// At least [`SkinMemory::clip`].
    pub clip: &'a mut [ClipVertex],
    /// At least [`SkinMemory::words`].
    pub words: &'a mut [u32],
    /// At least [`SkinMemory::levels`].
    pub levels: &'a mut [SkinLevel],
    /// At least [`SkinMemory::divisions`].
    pub divisions: &'a mut [SkinDivision],
    /// At least [`SkinMemory::shared_edges`].
    pub shared_edges: &'a mut [SkinSharedEdges],
    /// At least [`SkinMemory::boxes`].
    pub boxes: &'a mut [[i64; 4]],
    /// At least [`SkinMemory::wedges`].
    pub wedges: &'a mut [Wedge],
}

/// The buffers of a [`SkinStore`] or [`SkinStorage`], field by field.
macro_rules! buffers_of {
    ($store:expr) => {
        SkinBuffers {
            cells: &mut $store.cells,
            vertices: &mut $store.vertices,
            sites: &mut $store.sites,
            clip: &mut $store.clip,
            words: &mut $store.words,
            levels: &mut $store.levels,
            divisions: &mut $store.divisions,
            shared_edges: &mut $store.shared_edges,
            boxes: &mut $store.boxes,
            wedges: &mut $store.wedges,
        }
    };
}

/// Owned memory for a skin (the `alloc` feature), from [`SkinMemory::allocate`].
#[cfg(feature = "alloc")]
pub struct SkinStore {
    cells: alloc::vec::Vec<SkinCell>,
    vertices: alloc::vec::Vec<[i64; 2]>,
    sites: alloc::vec::Vec<Site>,
    clip: alloc::vec::Vec<ClipVertex>,
    words: alloc::vec::Vec<u32>,
    levels: alloc::vec::Vec<SkinLevel>,
    divisions: alloc::vec::Vec<SkinDivision>,
    shared_edges: alloc::vec::Vec<SkinSharedEdges>,
    boxes: alloc::vec::Vec<[i64; 4]>,
    wedges: alloc::vec::Vec<Wedge>,
}

#[cfg(feature = "alloc")]
impl SkinMemory {
    /// Owned buffers of this size.
    pub fn allocate(&self) -> SkinStore {
        SkinStore {
            cells: alloc::vec![SkinCell::default(); self.cells],
            vertices: alloc::vec![[0; 2]; self.vertices],
            sites: alloc::vec![Site::default(); self.sites],
            clip: alloc::vec![ClipVertex::default(); self.clip],
            words: alloc::vec![0; self.words],
            levels: alloc::vec![SkinLevel::default(); self.levels],
            divisions: alloc::vec![SkinDivision::default(); self.divisions],
            shared_edges: alloc::vec![SkinSharedEdges::default(); self.shared_edges],
            boxes: alloc::vec![[0; 4]; self.boxes],
            wedges: alloc::vec![Wedge::default(); self.wedges],
        }
    }
}

#[cfg(feature = "alloc")]
impl SkinStore {
    /// The buffers, for [`Skin::new`].
    pub fn buffers(&mut self) -> SkinBuffers<'_> {
        buffers_of!(self)
    }
}

/// Fixed-size storage for callers without a heap: the sizes are those of
/// [`SkinParams::memory`].
pub struct SkinStorage<
    const CELLS: usize,
    const VERTICES: usize,
    const SITES: usize,
    const CLIP: usize,
    const WORDS: usize,
    const LEVELS: usize,
    const DIVISIONS: usize,
    const SHARED_EDGES: usize,
    const BOXES: usize,
    const WEDGES: usize,
> {
    /// Cell records.
    pub cells: [SkinCell; CELLS],
    /// Outline vertices.
    pub vertices: [[i64; 2]; VERTICES],
    /// Site records.
    pub sites: [Site; SITES],
    /// Clip vertices.
    pub clip: [ClipVertex; CLIP],
    /// Words.
    pub words: [u32; WORDS],
    /// Level records.
    pub levels: [SkinLevel; LEVELS],
    /// Division records.
    pub divisions: [SkinDivision; DIVISIONS],
    /// Shared-edge records.
    pub shared_edges: [SkinSharedEdges; SHARED_EDGES],
    /// Chunk boxes.
    pub boxes: [[i64; 4]; BOXES],
    /// Wedges.
    pub wedges: [Wedge; WEDGES],
}

// (Unformatted: one line per five sizes, not one per size.)
#[rustfmt::skip]
impl<const C: usize, const V: usize, const S: usize, const K: usize, const W: usize,
     const L: usize, const D: usize, const E: usize, const B: usize, const G: usize>
    SkinStorage<C, V, S, K, W, L, D, E, B, G> {
    /// Empty storage.
    pub fn new() -> Self {
        SkinStorage {
            cells: [SkinCell::default(); C],
            vertices: [[0; 2]; V],
            sites: [Site::default(); S],
            clip: [ClipVertex::default(); K],
            words: [0; W],
            levels: core::array::from_fn(|_| SkinLevel::default()),
            divisions: core::array::from_fn(|_| SkinDivision::default()),
            shared_edges: core::array::from_fn(|_| SkinSharedEdges::default()),
            boxes: [[0; 4]; B],
            wedges: [Wedge::default(); G],
        }
    }

    /// The buffers, for [`Skin::new`].
    pub fn buffers(&mut self) -> SkinBuffers<'_> {
        buffers_of!(self)
    }
}

#[rustfmt::skip]
impl<const C: usize, const V: usize, const S: usize, const K: usize, const W: usize,
     const L: usize, const D: usize, const E: usize, const B: usize, const G: usize>
    Default for SkinStorage<C, V, S, K, W, L, D, E, B, G> {
    fn default() -> Self {
        Self::new()
    }
}

/// Why a skin could not be built or rendered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SkinError {
    /// A parameter is out of range.
    Param(SkinParamError),
    /// A caller buffer is too small: `needed` elements are required.
    BufferTooSmall {
        /// Elements the buffer must hold.
        needed: usize,
    },
    /// The requested cell-map level is not below `levels`.
    Level,
    /// A shading parameter is out of range.
    Shade(ShadeError),
    /// A render's tile or layers are refused.
    Raster(crate::raster::RasterError),
}

impl From<SkinParamError> for SkinError {
    fn from(e: SkinParamError) -> Self {
        SkinError::Param(e)
    }
}

impl core::fmt::Display for SkinError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            SkinError::Param(e) => e.fmt(f),
            SkinError::BufferTooSmall { needed } => write!(f, "skin: a caller buffer is too small ({needed} needed)"),
            SkinError::Level => f.write_str("skin: the cell-map level must be below levels"),
            SkinError::Shade(e) => e.fmt(f),
            SkinError::Raster(e) => e.fmt(f),
        }
    }
}

impl core::error::Error for SkinError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            SkinError::Param(e) => Some(e),
            SkinError::Shade(e) => Some(e),
            SkinError::Raster(e) => Some(e),
            _ => None,
        }
    }
}

impl SkinParams {
    /// The lattice index range of level 0 (inclusive) that can reach the surface.
    fn level0_indices(&self, lattice: &Lattice) -> [i64; 4] {
        if self.periodic {
            [0, 0, lattice.count[0] - 1, lattice.count[1] - 1]
        } else {
            // The lattice points within about two steps of the surface: one farther out
            // always has nearer ones between it and the surface.
            [-3, -3, lattice.count[0] + 1, lattice.count[1] + 1]
        }
    }

    /// The most level-0 cells and the most outline vertices they can have in all.
    ///
    /// Periodic: every centre point of the period has a cell; the Voronoi edges of n points
    /// on the torus number at most 3n (Euler), each in two cells, written as
    /// [`level0_pieces`] vertices each, plus 16 per cell to spare.
    ///
    /// Otherwise only a centre whose cell meets the surface keeps one. A point of the
    /// surface lies in the cell of its nearest centre, which is at most [`Lattice::reach`]
    /// (ρ) away: so a cell that meets the surface has its centre within ρ of it, and one that
    /// meets a side of the surface within ρ of that side (the window a cell is clipped among
    /// holds every centre that can bound it: [`Window`]). Counting the n lattice indices
    /// whose centre can lie within ρ of the surface ([`Lattice::count_over`]), and the n_k
    /// that can lie within ρ of side k (all within [`SkinParams::level0_indices`]: ρ is under
    /// 1.6 steps of either axis, the rows being at least √3/2 of a column step apart, and an
    /// index beyond that range lies at least 2.5 steps of its axis from the surface):
    /// - each cell is convex (the surface clipped by half-planes), so it has at most one edge
    ///   along each neighbour's bisector and one piece of each side;
    /// - an edge of positive length between two cells is a Voronoi edge, between two centres
    ///   that are both counted in n (its points lie on the surface, as near to either
    ///   centre as to any); the Voronoi (Delaunay) adjacency of n points is a planar graph,
    ///   of at most 3n − 6 edges (n ≥ 3; one for n = 2), each in two cells, each written as
    ///   [`level0_pieces`] vertices (a zero-length one writes nothing new: its corners and
    ///   inner points repeat the point before, and repeats are not written);
    /// - the pieces of side k belong to distinct cells that meet it: at most n_k of them,
    ///   one vertex each.
    ///
    /// So the vertices number at most 2·pieces·(3n − 6) + Σ n_k.
    ///
    /// Counted over the surface instead: its c ≤ n cells divide the rectangle into c convex
    /// faces, a connected plane graph with one face more outside (the sides split where edges
    /// meet them). Every vertex of it but the 4 corners has degree 3 or more (a Voronoi vertex,
    /// or an edge meeting a side), the corners 2 or more, so 2E ≥ 3(V − 4) + 8; with Euler's
    /// V − E + (c + 1) = 2 that gives E ≤ 3c + 1. The outlines write each of the E − E_s inner
    /// edges twice, as `pieces` vertices each, and each of the E_s ≥ 4 edges along the sides
    /// once: 2·pieces·E − (2·pieces − 1)·E_s ≤ 6·pieces·(c − 1) + 4 ≤ 6·pieces·(n − 1) + 4
    /// vertices (4 for one cell, the rectangle).
    ///
    /// The need is the least of these and n times the longest outline ([`Layout`]). (In exact
    /// arithmetic; a build that finds more, through rounding, stops with `capacity_reached`.)
    fn level0_need(&self, lattice: &Lattice, outline: usize) -> Option<(usize, usize)> {
        let r = self.level0_indices(lattice);
        let pieces = level0_pieces(self);
        if self.periodic {
            let cells = usize::try_from((r[2] - r[0] + 1).checked_mul(r[3] - r[1] + 1)?).ok()?;
            let vertices = cells.checked_mul((6 * pieces + 16).min(outline))?;
            return Some((cells, vertices));
        }
        let rho = lattice.reach();
        let [w, h] = lattice.period;
        let near = |min: [f64; 2], max: [f64; 2]| usize::try_from(lattice.count_over(min, max, r)).ok();
        let cells = near([-rho, -rho], [w + rho, h + rho])?;
        let sides = [
            near([-rho, -rho], [w + rho, rho])?,
            near([-rho, h - rho], [w + rho, h + rho])?,
            near([-rho, -rho], [rho, h + rho])?,
            near([w - rho, -rho], [w + rho, h + rho])?,
        ];
        let edges = match cells {
            0 | 1 => 0,
            2 => 1,
            n => n.checked_mul(3)? - 6,
        };
        let euler =
            edges.checked_mul(2 * pieces)?.checked_add(sides.iter().try_fold(0usize, |s, &n| s.checked_add(n))?)?;
        let faces = (6 * pieces).checked_mul(cells.saturating_sub(1))?.checked_add(4)?;
        let vertices = euler.min(faces).min(cells.checked_mul(outline)?);
        Some((cells, vertices))
    }

    /// Validates the parameters and returns the memory a skin needs.
    pub fn memory(&self) -> Result<SkinMemory, SkinParamError> {
        self.validate()?;
        let levels = self.levels as usize;
        let layout = Layout::of(self);
        let (mut cells, mut vertices, mut previous) = (0usize, 0usize, 0usize);
        for l in 0..levels {
            let lattice = Lattice::new(self, l);
            // A tiny stretch puts up to i64::MAX centre points across an axis: more than any
            // memory holds, and more than the products below could count. Named as the stretch
            // when one below 1 is what packs them (a spacing is at least 1 px).
            if lattice.count.iter().any(|&c| c > i64::from(i32::MAX)) {
                let squeezed = self.level[..=l].iter().any(|v| v.stretch.iter().any(|&s| s < 1.0));
                return Err(if squeezed { SkinParamError::Stretch } else { SkinParamError::Capacity });
            }
            let (sites, level_vertices) = if l == 0 {
                self.level0_need(&lattice, layout.outline[0]).ok_or(SkinParamError::Capacity)?
            } else {
                // Every lattice point that can lie on the surface (or its margin), plus one
                // stand-in child for each parent that holds no point.
                let margin = 2 * (WINDOW + 4);
                let sites = usize::try_from((lattice.count[0] + margin) * (lattice.count[1] + margin))
                    .ok()
                    .and_then(|n| n.checked_add(previous))
                    .ok_or(SkinParamError::Capacity)?;
                // Euler: the Voronoi edges of n points number at most 3n; each is in two
                // cells, perturbed into 2^depth pieces, plus corners on the parent's outline,
                // which every child inherits from its parent.
                let pieces = 1usize << self.level[l].perturbation_depth;
                let own = sites.checked_mul(6 * pieces + 16).ok_or(SkinParamError::Capacity)?;
                (sites, own.checked_add(vertices).ok_or(SkinParamError::Capacity)?)
            };
            vertices = vertices.checked_add(level_vertices).ok_or(SkinParamError::Capacity)?;
            cells = cells.checked_add(sites).ok_or(SkinParamError::Capacity)?;
            previous = sites;
        }
        if vertices > i32::MAX as usize || cells > i32::MAX as usize {
            return Err(SkinParamError::Capacity);
        }
        Ok(SkinMemory {
            cells,
            vertices,
            sites: layout.sites_at(levels),
            // Two outlines being clipped, and each level's parent outline as its children start.
            clip: 2 * layout.clip + layout.frames_at(levels),
            // A parent's children below level 0, when there are more than a few: each level's
            // bucketed, and the siblings a cell's walk has found (level 0's window is few:
            // picked without them).
            words: if levels > 1 { layout.words_at(levels) } else { 0 },
            levels,
            divisions: levels - 1,
            shared_edges: layout.shared_edges(),
            boxes: layout.boxes_at(levels),
            // (Both counts are below i32::MAX.)
            wedges: vertices + cells,
        })
    }
}

/// A skin surface: every cell outline of every level, over caller memory, built by
/// [`Skin::step`] one cell after another, depth first (each level-0 cell, then its
/// descendants, before the next level-0 cell). `S` is the scalar backend the maps are
/// computed in (`f32`, `micromath::F32`, `Q16`).
pub struct Skin<'a, S: Scalar = f32> {
    params: SkinParams,
    build: Build<'a>,
    /// The level-0 lattice indices that can reach the surface (inclusive: i0, j0, i1, j1).
    range: [i64; 4],
    /// The level-0 index (i, j) whose tree is being built, or the next to build.
    next: [i64; 2],
    /// The level-0 index whose neighbour window (the first [`Window::sites`] of `sites`)
    /// holds, if any.
    window: Option<[i64; 2]>,
    /// The depth-first walk's cursors: entry `d` (of the first `open`) the children of level
    /// `d + 1` being built, of the level-`d` cell last built at that level. The walk goes on
    /// with the next child of the finest open entry, or with the next level-0 index when none
    /// is open.
    siblings: [Siblings; MAX_LEVELS - 1],
    /// How many `siblings` entries are open.
    open: usize,
    /// The division under way, if any: the cell last built is being divided, and its
    /// children's entry opens when the division is done.
    dividing: Option<Dividing>,
    /// The setup under way (each level's profile table), until it is done: the first
    /// [`Skin::step`] calls do it, within their budgets, before any cell.
    setup: Option<Setup>,
    /// Level-0 cells whose trees are built.
    done: u32,
    finished: bool,
    capacity_reached: bool,
    /// What [`Skin::step`]'s budget counts: outline vertices written so far, one per level-0
    /// centre point tried, and the units of the divisions (centre points tried and pieces of
    /// bucketing).
    work: u64,
    backend: PhantomData<S>,
}

/// The children of one parent cell, as the build walks them ([`Skin`]'s `siblings`). The rest
/// of what they are built from stays in caller memory, in places of their level alone
/// ([`Build::prepare`], [`Build::divide`]): the parent's outline in `vertices` (its cell
/// record says where), their centre points in `sites`, the parent's chunk boxes, edge grid
/// and parent frame.
#[derive(Clone, Copy, Debug, Default)]
struct Siblings {
    /// The parent's index in `cells`.
    parent: u32,
    /// Its children's centre points ([`Build::divide`]; at most [`MAX_CHILDREN`]).
    count: u16,
    /// The next of them to build.
    next: u16,
}

/// A division under way ([`Build::prepare`], [`Build::divide`]): the lattice sites of the
/// children's level in the parent's box are tried one a unit, in rows, those inside the parent
/// listed as its children's centre points; then, when they are more than [`cell::FEW`], they
/// are bucketed one piece a unit ([`nearest::Filling`]).
#[derive(Clone, Copy, Debug)]
struct Dividing {
    /// The children's level.
    level: u8,
    /// The parent's index in `cells`.
    parent: u32,
    /// The lattice indices to try (inclusive: i0, j0, i1, j1), and the next one (none once
    /// all are tried).
    range: [i64; 4],
    next: Option<[i64; 2]>,
    /// The parent outline's box, fixed point.
    low: [i64; 2],
    high: [i64; 2],
    /// The centre points listed so far.
    count: u16,
    /// The bucketing, once the centre points are all listed (if they need one).
    filling: Option<nearest::Filling>,
}

/// The setup, which the first [`Skin::step`] calls do (so that [`Skin::new`] does the same
/// work at any size and level count): each level's profile table ([`ProfileTable`]), sampled
/// one sample a piece, then completed one level a piece. Levels whose profiles place their
/// samples alike (a run of them: [`ProfileTable::shares_places`]) share each sample's place,
/// found once for the run.
#[derive(Clone, Copy, Debug)]
enum Setup {
    /// Sample `sample` of the levels `first..end` (a run).
    Sampling { first: u8, end: u8, sample: u16 },
    /// The completion of level `level`'s table.
    Finishing { level: u8 },
}

/// Units one sample of a run of levels counts ([`Setup::Sampling`]): its place on the curve
/// (a bisection of 48 halvings, a Bézier evaluation each) and each level's sample there.
const SETUP_SAMPLE_UNITS: u64 = 2;
/// Units the completion of one level's table counts ([`Setup::Finishing`]: a pass over its
/// [`SAMPLES`] + 1 samples).
const SETUP_FINISH_UNITS: u64 = 4;

impl Setup {
    /// The end of the run of levels that starts at `first`.
    fn run_end(p: &SkinParams, first: usize) -> u8 {
        let levels = p.levels as usize;
        let mut end = first + 1;
        while end < levels && ProfileTable::shares_places(&p.level[end - 1].profile, &p.level[end].profile) {
            end += 1;
        }
        end as u8
    }

    /// Does this piece into `levels` (the tables); returns the units it counts and the setup
    /// after it (None when done).
    fn piece(self, p: &SkinParams, levels: &mut [SkinLevel]) -> (u64, Option<Setup>) {
        let profile = |l: usize| &p.level[l].profile;
        match self {
            Setup::Sampling { first, end, sample } => {
                let (first, end, k) = (usize::from(first), usize::from(end), usize::from(sample));
                let (s, t) = ProfileTable::place(profile(first), k);
                for (l, level) in levels.iter_mut().enumerate().take(end).skip(first) {
                    level.table.sample_at(profile(l), k, s, t);
                }
                let next = if k < SAMPLES {
                    Setup::Sampling { first: first as u8, end: end as u8, sample: sample + 1 }
                } else if end < levels.len() {
                    Setup::Sampling { first: end as u8, end: Setup::run_end(p, end), sample: 0 }
                } else {
                    Setup::Finishing { level: 0 }
                };
                (SETUP_SAMPLE_UNITS, Some(next))
            }
            Setup::Finishing { level } => {
                let l = usize::from(level);
                levels[l].table.finish(profile(l));
                let next = (l + 1 < levels.len()).then_some(Setup::Finishing { level: level + 1 });
                (SETUP_FINISH_UNITS, next)
            }
        }
    }
}

// (`Skin::step` states the bucketing's threshold and piece.)
const _: () = assert!(cell::FEW == 96 && nearest::PIECE == 256);

// (A parent's children are counted in 16 bits: the cursors are part of every `Skin`.)
const _: () = assert!(MAX_CHILDREN <= u16::MAX as usize);

/// Where a build stands, as [`Skin::step`] reports it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SkinProgress {
    /// Cells built, all levels.
    pub cells: u32,
    /// Level-0 centre points whose cells (with all their descendants) are built.
    pub roots: u32,
    /// Level-0 centre points in all.
    pub root_total: u32,
    /// Every cell is built.
    pub finished: bool,
    /// A cell outline or a parent's centre points outgrew their capacity ([`MAX_OUTLINE`],
    /// [`MAX_CHILDREN`]) or the cell buffer filled: the build stopped there, and what was
    /// built stays usable (lower the perturbation depth or the spacing ratio).
    pub capacity_reached: bool,
    /// Work done since the build began, in the units of [`Skin::step`]'s budget.
    pub work: u64,
}

// Level 0's neighbours are few enough to be picked nearest first without sorting them in
// `words` (a one-level skin needs none): the window holds at most (2·WINDOW + 1)² of them.
const _: () = assert!(((2 * WINDOW + 1) * (2 * WINDOW + 1)) as usize <= cell::FEW);

/// The state of a build: the buffers and how far they are filled.
struct Build<'b> {
    params: SkinParams,
    layout: Layout,
    frames: [Frame; MAX_LEVELS],
    lattices: [Lattice; MAX_LEVELS],
    cells: &'b mut [SkinCell],
    cell_count: usize,
    vertices: &'b mut [[i64; 2]],
    vertex_count: usize,
    sites: &'b mut [Site],
    /// Per level, the parent outline of the cells being built, as their clipping starts from
    /// it ([`Layout::frames_at`]).
    parent_frames: &'b mut [ClipVertex],
    /// Per level, its profile table.
    levels: &'b mut [SkinLevel],
    /// Per level from 1 (index level − 1): the edges of the parent outline of the cells being
    /// built, binned (when it is short enough: [`EdgeGrid::of`]), and its crossing scratch.
    divisions: &'b mut [SkinDivision],
    /// Per level that keeps edges ([`Layout`]'s `shared`), its shared edges.
    shared_edges: &'b mut [SkinSharedEdges],
    /// Per level from 1, the chunk boxes of the parent outline being divided
    /// ([`Layout::boxes`] each, from [`Layout::boxes_at`]).
    boxes: &'b mut [[i64; 4]],
    /// Per cell, from its first vertex's index plus its own, its fan: one wedge per outline
    /// vertex and one in front ([`surface::fan`]).
    wedges: &'b mut [Wedge],
    builder: Builder<'b>,
}

impl Build<'_> {
    /// The fans of the cells built so far.
    fn wedges(&self) -> &[Wedge] {
        &self.wedges[..self.vertex_count + self.cell_count]
    }

    /// Builds `site`'s outline in level `level` among `neighbours` (sites[range]) inside the
    /// outline `parent` (vertices[parent range], with level `level`'s chunk boxes and parent
    /// frame, or the given rectangle) and stores the cell; returns its index, or `None` when
    /// its outline is empty (fewer than 3 vertices: no cell). `own` is the site's place among
    /// `neighbours` when they are built in that order (a parent's children), for the shared
    /// edges ([`cell::EdgeWork`]).
    fn cell(
        &mut self,
        level: usize,
        (site, own): (Site, Option<usize>),
        neighbours: (usize, usize),
        (parent, parent_index): (ParentOutline, u32),
    ) -> Result<Option<usize>, Full> {
        let f = &self.frames[level];
        let (head, tail) = self.vertices.split_at_mut(self.vertex_count);
        let mut box_chunks = [[0i64; 4]; 1];
        let (grid, crossing, buckets) = match level.checked_sub(1) {
            Some(d) => {
                let SkinDivision { grid, crossing, buckets } = &mut self.divisions[d];
                (Some(&*grid), Some(crossing), Some((&*buckets, self.layout.words_at(level))))
            }
            None => (None, None, None),
        };
        let shared = match self.layout.shared[level] {
            Some(k) => Some(&mut self.shared_edges[k].0),
            None => None,
        };
        let outline = match parent {
            ParentOutline::Stored(first, count) => Parent {
                outline: &head[first..first + count],
                chunks: &self.boxes[self.layout.boxes_at(level)..][..cell::chunk_count(count)],
                grid: grid.and_then(|g| g.of(count)),
                frame: &self.parent_frames[self.layout.frames_at(level)..][..count],
            },
            ParentOutline::Box(ref b) => {
                let count = cell::chunk_boxes(b, &mut box_chunks);
                let frame = &mut self.parent_frames[self.layout.frames_at(level)..][..b.len()];
                for (k, v) in frame.iter_mut().enumerate() {
                    *v = cell::parent_vertex(f, b, k);
                }
                Parent { outline: b, chunks: &box_chunks[..count], grid: None, frame }
            }
        };
        let n = self
            .builder
            .outline(f, &site, (&self.sites[neighbours.0..neighbours.0 + neighbours.1], buckets), outline, {
                let room = tail.len().min(self.layout.outline[level]);
                (&mut tail[..room], cell::EdgeWork { shared, crossing, own })
            })
            .map_err(|_| Full)?;
        if n < 3 {
            return Ok(None);
        }
        let index = self.cell_count;
        // (With buffers of exactly the need neither runs out; larger cell or vertex buffers
        // than the need do not make room for more fans than the wedges hold.)
        if index == self.cells.len() || self.vertex_count + index + n + 1 > self.wedges.len() {
            return Err(Full);
        }
        self.cells[index] = SkinCell {
            level: level as u32,
            parent: parent_index,
            site: site.id,
            first_vertex: self.vertex_count as u32,
            vertex_count: n as u32,
            centre: f.site_fixed(&site),
        };
        self.cell_count += 1;
        let first = self.vertex_count;
        self.vertex_count += n;
        let fan = &mut self.wedges[first + index..][..n + 1];
        let bits = cell::fixed_point_bits(self.params.levels);
        surface::fan(&self.vertices[first..first + n], self.cells[index].centre, bits, fan);
        Ok(Some(index))
    }

    /// Prepares the division of cell `parent` into the cells of `level`: its outline's chunk
    /// boxes at [`Layout::boxes_at`], its edge grid in `divisions[level − 1]` and its outline
    /// as the children's clipping starts from it at [`Layout::frames_at`] (O(its vertices));
    /// returns the division, whose centre points [`Build::divide`] then lists. All of these
    /// are level `level`'s alone: building a child's own descendants, which reads and writes
    /// only those of finer levels, leaves them as they are for its siblings.
    fn prepare(&mut self, level: usize, parent: u32) -> Dividing {
        let (f, lattice) = (self.frames[level], self.lattices[level]);
        let c = self.cells[parent as usize];
        let (first, n) = (c.first_vertex as usize, c.vertex_count as usize);
        let outline = &self.vertices[first..first + n];
        let (mut low, mut high) = ([i64::MAX; 2], [i64::MIN; 2]);
        for v in outline {
            low = [low[0].min(v[0]), low[1].min(v[1])];
            high = [high[0].max(v[0]), high[1].max(v[1])];
        }
        let range = lattice.indices_over(f.in_frame(low), f.in_frame(high));
        // Its edges' boxes, for every child's outline too.
        let boxes = &mut self.boxes[self.layout.boxes_at(level)..][..self.layout.boxes(level)];
        cell::chunk_boxes(outline, boxes);
        self.divisions[level - 1].grid.fill(outline, (low, high));
        // Its outline as every child's clipping starts from it.
        for (k, v) in self.parent_frames[self.layout.frames_at(level)..][..n].iter_mut().enumerate() {
            *v = cell::parent_vertex(&f, outline, k);
        }
        let empty = range[0] > range[2] || range[1] > range[3];
        Dividing {
            level: level as u8,
            parent,
            range,
            next: (!empty).then_some([range[0], range[1]]),
            low,
            high,
            count: 0,
            filling: None,
        }
    }

    /// Goes on with division `d`: tries up to `room` (at least one) of the lattice sites in
    /// its parent's box, listing those inside the parent at `sites[Layout::sites_at(level)..]`
    /// (a stand-in at the parent's centre when none falls inside it), then buckets them (when
    /// more than [`cell::FEW`]), one piece of at most [`nearest::PIECE`] children or buckets
    /// a unit, up to `room` pieces. Adds the units done to `work`; returns whether the
    /// division is done.
    fn divide(&mut self, d: &mut Dividing, room: u64, work: &mut u64) -> Result<bool, Full> {
        let level = d.level as usize;
        let base = self.layout.sites_at(level);
        let room = room.max(1);
        let mut done = 0;
        if let Some(mut next) = d.next {
            let (f, lattice) = (self.frames[level], self.lattices[level]);
            let c = self.cells[d.parent as usize];
            let (first, n) = (c.first_vertex as usize, c.vertex_count as usize);
            let outer = Parent {
                outline: &self.vertices[first..first + n],
                chunks: &self.boxes[self.layout.boxes_at(level)..][..cell::chunk_count(n)],
                grid: self.divisions[level - 1].grid.of(n),
                frame: &[],
            };
            let (low, high, r) = (d.low, d.high, d.range);
            let mut count = usize::from(d.count);
            let mut more = true;
            while more && done < room {
                let [i, j] = next;
                done += 1;
                if i < r[2] {
                    next = [i + 1, j];
                } else {
                    more = j < r[3];
                    next = [r[0], j.wrapping_add(1)];
                }
                let s = lattice.site(i, j);
                let p = f.site_fixed(&s);
                let in_box = (low[0] <= p[0]) & (p[0] <= high[0]) & (low[1] <= p[1]) & (p[1] <= high[1]);
                if in_box {
                    let inside = outer.contains(p);
                    if count == MAX_CHILDREN {
                        if inside {
                            *work += done;
                            return Err(Full);
                        }
                        continue;
                    }
                    // (On 64-bit targets written whether or not it is inside, and counted only
                    // if it is: which sites are inside follows the parent's shape, no pattern a
                    // processor could learn. The slot past the count is free.)
                    #[cfg(target_pointer_width = "64")]
                    {
                        self.sites[base + count] = s;
                        count += usize::from(inside);
                    }
                    #[cfg(not(target_pointer_width = "64"))]
                    if inside {
                        self.sites[base + count] = s;
                        count += 1;
                    }
                }
            }
            d.count = count as u16;
            d.next = more.then_some(next);
            if more {
                *work += done;
                return Ok(false);
            }
        }
        if d.count == 0 {
            // No centre point fell inside: the parent is one cell of this level, centred
            // where the parent is.
            let at = self.frames[level].in_frame(self.cells[d.parent as usize].centre);
            self.sites[base] = Site { at, base: at, id: 0x8000_0000 | d.parent, image: [0, 0] };
            d.count = 1;
        }
        if usize::from(d.count) <= cell::FEW {
            *work += done;
            return Ok(true);
        }
        let filling = d.filling.get_or_insert(nearest::Filling::new());
        // Bucketed, for each child's walk to its nearest siblings.
        let sites = &self.sites[base..base + usize::from(d.count)];
        let words = &mut self.builder.words[self.layout.words_at(level)..][..nearest::WORDS];
        let buckets = &mut self.divisions[level - 1].buckets;
        while done < room {
            done += 1;
            if filling.piece(buckets, sites, words) {
                *work += done;
                return Ok(true);
            }
        }
        *work += done;
        Ok(false)
    }

    /// Builds child `k` of the `count` that [`Build::divide`] listed for cell `parent` at
    /// `level`; returns its index, or `None` when its outline is empty.
    fn child(&mut self, level: usize, parent: u32, (k, count): (usize, usize)) -> Result<Option<usize>, Full> {
        let base = self.layout.sites_at(level);
        let s = self.sites[base + k];
        let c = self.cells[parent as usize];
        let outline = ParentOutline::Stored(c.first_vertex as usize, c.vertex_count as usize);
        self.cell(level, (s, Some(k)), (base, count), (outline, parent))
    }
}

/// A cell outline, a parent's centre points or the cell buffer outgrew its capacity.
struct Full;

/// The outline a cell is clipped to.
enum ParentOutline {
    /// Stored vertices (first, count), the parent of the level being built (its chunk boxes
    /// and parent frame are the level's: [`Build::prepare`]).
    Stored(usize, usize),
    /// A rectangle (the surface, or a box around a periodic centre).
    Box([[i64; 2]; 4]),
}

impl<'a, S: Scalar> Skin<'a, S> {
    /// Sets up a skin of `params` in caller memory of at least [`SkinParams::memory`]
    /// elements; [`Skin::step`] builds its cells. The work is the same at any size and level
    /// count: the first steps sample the levels' profile tables ([`Skin::is_setting_up`]).
    /// Nothing is written to the buffers on failure (and on success only the level records
    /// and the shared-edge records, a few per level: every other array is written by the
    /// steps before it is read, and may hold any bytes).
    pub fn new(params: &SkinParams, buffers: SkinBuffers<'a>) -> Result<Self, SkinError> {
        Skin::new_in(params, buffers, Layout::of(params))
    }

    /// [`Skin::new`] with the scratch laid out as `layout` says (the buffers at least the need).
    fn new_in(params: &SkinParams, buffers: SkinBuffers<'a>, layout: Layout) -> Result<Self, SkinError> {
        let m = params.memory()?;
        let short = [
            (buffers.cells.len(), m.cells),
            (buffers.vertices.len(), m.vertices),
            (buffers.sites.len(), m.sites),
            (buffers.clip.len(), m.clip),
            (buffers.words.len(), m.words),
            (buffers.levels.len(), m.levels),
            (buffers.divisions.len(), m.divisions),
            (buffers.shared_edges.len(), m.shared_edges),
            (buffers.boxes.len(), m.boxes),
            (buffers.wedges.len(), m.wedges),
        ];
        if let Some(&(_, needed)) = short.iter().find(|(have, need)| have < need) {
            return Err(SkinError::BufferTooSmall { needed });
        }
        let size = [params.width, params.height];
        let frames = core::array::from_fn(|l| {
            Frame::new(l, &params.level[l.min(params.levels as usize - 1)], params.seed, size, params.levels)
        });
        let lattices = core::array::from_fn(|l| Lattice::new(params, l.min(params.levels as usize - 1)));
        let (clip, rest) = buffers.clip.split_at_mut(layout.clip);
        let (spare, parent_frames) = rest.split_at_mut(layout.clip);
        let levels = &mut buffers.levels[..params.levels as usize];
        // (The profile tables are sampled by the first steps: `Setup`.)
        // (A division is left as it is: its grid is filled for each parent before the parent's
        // children read it, and its crossing scratch written for each edge before it is read.)
        let divisions = &mut buffers.divisions[..m.divisions];
        let shared_edges = &mut buffers.shared_edges[..m.shared_edges];
        for s in shared_edges.iter_mut() {
            s.0.clear();
        }
        let build = Build {
            params: *params,
            layout,
            frames,
            lattices,
            cells: buffers.cells,
            cell_count: 0,
            vertices: buffers.vertices,
            vertex_count: 0,
            sites: buffers.sites,
            parent_frames,
            builder: Builder { clip, spare, words: &mut buffers.words[..m.words] },
            levels,
            divisions,
            shared_edges,
            boxes: buffers.boxes,
            wedges: buffers.wedges,
        };
        let range = params.level0_indices(&lattices[0]);
        Ok(Skin {
            params: *params,
            build,
            range,
            next: [range[0], range[1]],
            window: None,
            siblings: [Siblings::default(); MAX_LEVELS - 1],
            open: 0,
            dividing: None,
            setup: Some(Setup::Sampling { first: 0, end: Setup::run_end(params, 0), sample: 0 }),
            done: 0,
            finished: false,
            capacity_reached: false,
            work: 0,
            backend: PhantomData,
        })
    }

    /// Builds cells, one at a time at any level, until about `budget` units of work have been
    /// done in this call. The first calls do the setup: each level's profile table, 2 units a
    /// sample of its 257 (levels that place their samples alike share one) and 4 units a level
    /// to complete it ([`Skin::is_setting_up`]). Then the units are outline vertices written; one per level-0 centre point
    /// tried (whether or not its cell reaches the surface); and, as a cell is divided into the
    /// next level's, one per centre point tried in its bounding box (whether or not it falls
    /// inside the cell) and, for a cell of more than 96 children, one per piece of bucketing
    /// them (a piece handles at most 256 children or buckets in one of six passes over
    /// them). A unit stands for about the same work at any parameters: a cell's neighbours
    /// are handed to its clipping nearest first from among those near it (a parent's children
    /// are bucketed once, when it is divided), not sorted from all of its siblings, so a
    /// cell's work follows its own neighbours and outline, not how many children its parent
    /// holds; and a division's work follows its centre points tried (`tests/skin.rs` measures
    /// the instructions per unit from one child a parent to 1 800, `tests/unit_cost.rs` each
    /// kind of unit at ordinary and extreme parameters: within 10 times of each other). The
    /// work is done in pieces: a cell (with the start of its division: its outline's boxes
    /// and grid, in work that follows its vertices), a centre point tried, or a piece of
    /// bucketing. The budget is checked between pieces, so a call does at least one and
    /// overruns the budget by less than one piece: at most [`MAX_OUTLINE`] vertices and one
    /// unit (a cell; the other pieces are one unit each). The cells do not depend on the
    /// budgets. Call until `finished`.
    pub fn step(&mut self, budget: u64) -> SkinProgress {
        let start = self.work;
        while !self.finished && (self.work == start || self.work - start < budget) {
            if self.advance(budget - (self.work - start).min(budget)).is_err() {
                self.capacity_reached = true;
                self.finished = true;
                break;
            }
        }
        self.progress()
    }

    /// Builds every cell.
    pub fn run(&mut self) -> SkinProgress {
        self.step(u64::MAX)
    }

    /// Where the build stands.
    pub fn progress(&self) -> SkinProgress {
        let r = self.range;
        SkinProgress {
            cells: self.build.cell_count as u32,
            roots: self.done,
            root_total: ((r[2] - r[0] + 1) * (r[3] - r[1] + 1)) as u32,
            finished: self.finished,
            capacity_reached: self.capacity_reached,
            work: self.work,
        }
    }

    /// Does the next piece and counts its work: a piece of the setup while it is under way;
    /// else the next piece of the depth-first walk: with a division under
    /// way, its next centre points tried or pieces of bucketing (up to `room` units, at least
    /// one), opening the children once it is done; else the next cell, the next child of the
    /// finest open parent or else the level-0 cell of `next`: prepares its division if it has
    /// children, or else closes each parent whose children are all built, and with the last
    /// the level-0 cell's tree (moving `next` on, and finishing after the last).
    fn advance(&mut self, room: u64) -> Result<(), Full> {
        if let Some(setup) = self.setup {
            let (units, next) = setup.piece(&self.params, self.build.levels);
            self.work += units;
            self.setup = next;
            return Ok(());
        }
        if let Some(mut d) = self.dividing {
            let done = self.build.divide(&mut d, room, &mut self.work)?;
            self.dividing = Some(d);
            if done {
                let level = usize::from(d.level);
                self.siblings[level - 1] = Siblings { parent: d.parent, count: d.count, next: 0 };
                self.open = level;
                self.dividing = None;
            }
            return Ok(());
        }
        let before = self.build.vertex_count;
        let (level, built) = match self.open.checked_sub(1) {
            Some(d) => {
                let s = &mut self.siblings[d];
                let k = s.next;
                s.next += 1;
                (d + 1, self.build.child(d + 1, s.parent, (k as usize, s.count as usize)))
            }
            None => {
                self.work += 1;
                (0, self.root())
            }
        };
        self.work += (self.build.vertex_count - before) as u64;
        if let Some(index) = built?
            && level + 1 < self.params.levels as usize
        {
            // Its division goes on in the next calls; the walk waits for it.
            self.dividing = Some(self.build.prepare(level + 1, index as u32));
            return Ok(());
        }
        while let Some(d) = self.open.checked_sub(1)
            && self.siblings[d].next == self.siblings[d].count
        {
            self.open = d;
        }
        if self.open == 0 {
            let [i, j] = self.next;
            self.done += 1;
            self.next = if i < self.range[2] { [i + 1, j] } else { [self.range[0], j + 1] };
            self.finished = self.next[1] > self.range[3];
        }
        Ok(())
    }

    /// Builds the level-0 cell of lattice index `next` (its neighbour window first); returns
    /// its index, or `None` when it does not reach the surface.
    fn root(&mut self) -> Result<Option<usize>, Full> {
        let [i, j] = self.next;
        let (lattice, f) = (self.build.lattices[0], self.build.frames[0]);
        // The centre's neighbours: the window around it, row by row (level 0 keeps them in the
        // first block of `sites`), slid along the row one column at a time.
        let window = &self.build.layout.window;
        let slide = self.window == Some([i - 1, j]);
        let mut at = 0;
        for dj in -window.rows..=window.rows {
            let c = window.columns(dj);
            let row = &mut self.build.sites[at..][..2 * c as usize + 1];
            at += row.len();
            if slide {
                row.copy_within(1.., 0);
                row[2 * c as usize] = lattice.site(i + c, j + dj);
            } else {
                for (s, di) in row.iter_mut().zip(-c..) {
                    *s = lattice.site(i + di, j + dj);
                }
            }
        }
        self.window = Some([i, j]);
        let site = self.build.sites[window.centre()];
        let shift = f.shift;
        let parent = if self.params.periodic {
            let reach = [(WINDOW as f64 + 1.0) * lattice.step[0], (WINDOW as f64 + 1.0) * lattice.step[1]];
            let corner = |dx: f64, dy: f64| {
                let q = |k: usize, d: f64| {
                    crate::geom::round_to_i64((site.at[k] + d) * f.stretch[k] * 256.0) << (shift - 8)
                };
                [q(0, dx), q(1, dy)]
            };
            ParentOutline::Box([
                corner(-reach[0], -reach[1]),
                corner(reach[0], -reach[1]),
                corner(reach[0], reach[1]),
                corner(-reach[0], reach[1]),
            ])
        } else {
            let (w, h) = (i64::from(self.params.width) << shift, i64::from(self.params.height) << shift);
            ParentOutline::Box([[0, 0], [w, 0], [w, h], [0, h]])
        };
        self.build.cell(0, (site, None), (0, at), (parent, NO_CELL))
    }

    /// Whether the setup (each level's profile table, sampled by the first [`Skin::step`]
    /// calls) is still under way: no cell is built until it is done.
    pub fn is_setting_up(&self) -> bool {
        self.setup.is_some()
    }

    /// The parameters.
    pub fn params(&self) -> &SkinParams {
        &self.params
    }

    /// Every cell, depth first in the order [`Skin::step`] builds them: each level-0 cell,
    /// then its descendants (a parent comes before its children, and a cell's descendants
    /// before its next sibling).
    pub fn cells(&self) -> &[SkinCell] {
        &self.build.cells[..self.build.cell_count]
    }

    /// Every outline vertex in fixed point.
    pub fn vertices(&self) -> &[[i64; 2]] {
        &self.build.vertices[..self.build.vertex_count]
    }

    /// Fractional bits of the fixed point outlines are in: 8 + 12·(levels − 1) (a pixel is
    /// `1 << bits` units).
    pub fn fixed_point_bits(&self) -> u32 {
        cell::fixed_point_bits(self.params.levels)
    }

    /// The outline of `cell`.
    pub fn outline(&self, cell: &SkinCell) -> &[[i64; 2]] {
        &self.vertices()[cell.first_vertex as usize..][..cell.vertex_count as usize]
    }

    /// Calls `visit(column, row)` for every pixel whose centre lies in `cell` (wrapped onto
    /// the surface when periodic). Across the cells of one level every pixel is visited
    /// exactly once. The skin is only read.
    pub fn for_each_pixel(&self, cell: &SkinCell, mut visit: impl FnMut(u32, u32)) {
        self.for_each_pixel_unwrapped(cell, |_, _, x, y| visit(x, y));
    }
}

#[cfg(all(test, feature = "alloc"))]
mod tests {
    use super::*;
    use crate::rng::{Rng, Spread};

    #[test]
    fn the_window_builds_what_the_widest_window_builds() {
        // Every layout, jitter, stretch, perturbation, size and period, some with a second
        // level: the outlines built among the centres within 2ρ ([`Window`]) are those built
        // among all 81 of WINDOW = 4, bit for bit; and off a period the window is never capped.
        let mut rng = Rng::from_key(11, 12);
        let mut unit = move || rng.uniform_f64() as f32;
        let widest = Window { rows: WINDOW, columns: [WINDOW as u8; 2 * WINDOW as usize + 1] };
        for case in 0..200 {
            let mut p = SkinParams { seed: case, ..SkinParams::default() };
            (p.width, p.height) = (1 + (unit() * 120.0) as u32, 1 + (unit() * 120.0) as u32);
            p.layout = [SiteLayout::Triangular, SiteLayout::Square, SiteLayout::Random][case as usize % 3];
            p.jitter = if unit() < 0.5 { Spread::Uniform } else { Spread::Normal };
            p.jitter_ratio = if unit() < 0.3 { 1.0 } else { unit() };
            p.periodic = unit() < 0.25;
            p.levels = if unit() < 0.15 { 2 } else { 1 };
            let l = &mut p.level[0];
            l.spacing = 3.0 + unit() * unit() * 50.0;
            l.stretch = [0.5 + unit() * 2.0, 0.5 + unit() * 2.0];
            l.perturbation = if unit() < 0.5 { 0.0 } else { unit() * 0.4 };
            l.perturbation_depth = (unit() * 4.0) as u32;
            p.level[1].spacing = p.level[0].spacing / 3.0;
            let window = Window::of(&Lattice::new(&p, 0));
            if !p.periodic {
                let lattice = Lattice::new(&p, 0);
                let radius = 2.0 * lattice.reach();
                assert!(lattice.columns_within(window.rows + 1, radius).is_none(), "case {case}: rows capped");
                for dj in -window.rows..=window.rows {
                    assert!(lattice.columns_within(dj, radius).is_some_and(|c| c <= WINDOW), "case {case}");
                }
            }
            let m = p.memory().expect("valid");
            let wide =
                SkinMemory { sites: m.sites + 81, clip: m.clip + 2 * MAX_OUTLINE, boxes: m.boxes + MAX_OUTLINE, ..m };
            let (mut near, mut far) = (m.allocate(), wide.allocate());
            let mut a: Skin = Skin::new(&p, near.buffers()).expect("its need");
            let mut b: Skin = Skin::new_in(&p, far.buffers(), Layout::around(&p, widest)).expect("more than its need");
            let (pa, pb) = (a.run(), b.run());
            assert!(!pa.capacity_reached && !pb.capacity_reached, "case {case}: {pa:?} {pb:?}");
            assert_eq!((a.cells(), a.vertices()), (b.cells(), b.vertices()), "case {case}: {p:?}");
        }
    }

    #[test]
    fn steps_of_any_budget_build_the_same_cells_one_cell_at_a_time() {
        // Layouts, jitters, periods, perturbations and 1 to 3 levels: budgets of 1, 7 and 100
        // build what one `run` builds, bit for bit (cells, vertices, wedges and work); each
        // call overruns its budget by less than one cell's work, and a budget-1 call does one
        // piece: one cell (its vertices, and one unit more at level 0), or one unit that
        // builds none (a level-0 centre point whose cell misses the surface, a centre point
        // tried in a parent being divided, or a piece of its children's bucketing).
        let mut rng = Rng::from_key(26, 5);
        let mut unit = move || rng.uniform_f64() as f32;
        for case in 0..27 {
            let mut p = SkinParams { seed: 100 + case, ..SkinParams::default() };
            (p.width, p.height) = (8 + (unit() * 40.0) as u32, 8 + (unit() * 40.0) as u32);
            p.layout = [SiteLayout::Triangular, SiteLayout::Square, SiteLayout::Random][case as usize % 3];
            p.jitter = if unit() < 0.5 { Spread::Uniform } else { Spread::Normal };
            p.jitter_ratio = if unit() < 0.3 { 1.0 } else { unit() };
            p.periodic = case % 4 == 1;
            p.levels = 1 + case as u32 % 3;
            p.level[0].spacing = 12.0 + unit() * 12.0;
            // (The last cases' parents hold a few hundred children: bucketed in pieces.)
            let ratio = if case < 24 { 3.0 } else { 20.0 };
            if case >= 24 {
                (p.width, p.height, p.levels, p.level[0].spacing) = (64, 64, 2, 30.0 + unit() * 10.0);
            }
            for l in 0..p.levels as usize {
                let spacing = if l > 0 { p.level[l - 1].spacing / ratio } else { p.level[0].spacing };
                let level = &mut p.level[l];
                level.spacing = spacing;
                level.stretch = [0.7 + unit(), 0.7 + unit()];
                level.perturbation = if unit() < 0.4 { 0.0 } else { unit() * 0.3 };
                level.perturbation_depth = (unit() * 3.0) as u32;
            }
            let m = p.memory().expect("valid");
            let mut whole = m.allocate();
            let mut one_go: Skin = Skin::new(&p, whole.buffers()).expect("its need");
            let end = one_go.run();
            assert!(end.finished && !end.capacity_reached && end.roots == end.root_total, "case {case}");
            if p.levels > 1 {
                assert!(one_go.cells().iter().any(|c| c.level == p.levels - 1), "case {case}: a finest cell");
            }
            let level0 = one_go.cells().iter().filter(|c| c.level == 0).count() as u32;
            for budget in [1, 7, 100] {
                let mut store = m.allocate();
                let mut skin: Skin = Skin::new(&p, store.buffers()).expect("its need");
                let (mut before, mut calls) = (skin.progress(), 0u32);
                let (mut setup_calls, mut setup_work) = (0u64, 0u64);
                while !before.finished {
                    let setting_up = skin.is_setting_up();
                    let now = skin.step(budget);
                    let done = now.work - before.work;
                    assert!(done > 0 && done < budget + MAX_OUTLINE as u64 + 1, "case {case}: {done} for {budget}");
                    if budget == 1 && setting_up {
                        // A sample or a level's completion, no cell.
                        assert!(
                            now.cells == 0 && [SETUP_SAMPLE_UNITS, SETUP_FINISH_UNITS].contains(&done),
                            "case {case}"
                        );
                        setup_calls += 1;
                        setup_work += done;
                    } else if budget == 1 {
                        let cells = now.cells - before.cells;
                        assert!(cells <= 1, "case {case}: {cells} cells in one call");
                        // One cell's work: its vertices, and one unit more for a level-0 cell;
                        // else one unit.
                        let last = skin.cells().last().filter(|_| cells == 1);
                        let own = last.map_or(0, |c| u64::from(c.vertex_count))
                            + u64::from(cells == 0 || last.is_some_and(|c| c.level == 0));
                        assert_eq!(done, own, "case {case}");
                    }
                    before = now;
                    calls += 1;
                }
                assert_eq!(before, end, "case {case}, budget {budget}");
                assert_eq!((skin.cells(), skin.vertices()), (one_go.cells(), one_go.vertices()), "case {case}");
                // (Wedges hold floats: compared as printed, which tells every value apart.)
                let wedges = |s: &Skin| alloc::format!("{:?}", s.build.wedges());
                assert!(wedges(&skin) == wedges(&one_go), "case {case}: wedges");
                if budget == 1 {
                    // A call for each cell, and one for each unit outside the cells.
                    let vertices = skin.vertices().len() as u64;
                    // (The setup: one call a piece, each sample of each run of levels and each
                    // level's completion.)
                    let runs = {
                        let mut runs = 1;
                        for l in 1..p.levels as usize {
                            if !ProfileTable::shares_places(&p.level[l - 1].profile, &p.level[l].profile) {
                                runs += 1;
                            }
                        }
                        runs
                    };
                    assert_eq!(setup_calls, runs * (SAMPLES as u64 + 1) + u64::from(p.levels), "case {case}");
                    let calls_due = setup_calls + u64::from(end.cells - level0) + end.work - setup_work - vertices;
                    assert_eq!(u64::from(calls), calls_due, "case {case}: one piece a call");
                }
            }
        }
    }
    #[test]
    fn a_capacity_stops_a_stepped_build_where_it_stops_a_run() {
        // A parent holding more centre points than the core can sort: with budget 1 as in one
        // `run`, the build stops at the same cell with `capacity_reached`, and what it built
        // renders.
        let mut p = SkinParams { width: 128, height: 128, levels: 2, ..SkinParams::default() };
        (p.level[0].spacing, p.level[1].spacing) = (128.0, 1.5);
        (p.level[0].perturbation_depth, p.level[1].perturbation_depth) = (0, 0);
        let m = p.memory().expect("valid");
        let (mut whole, mut store) = (m.allocate(), m.allocate());
        let mut one_go: Skin = Skin::new(&p, whole.buffers()).expect("its need");
        let end = one_go.run();
        assert!(end.finished && end.capacity_reached && end.roots < end.root_total, "{end:?}");
        let mut skin: Skin = Skin::new(&p, store.buffers()).expect("its need");
        while !skin.step(1).finished {}
        assert_eq!(skin.progress(), end);
        assert_eq!((skin.cells(), skin.vertices()), (one_go.cells(), one_go.vertices()));
        assert_eq!(skin.step(1), end, "a stopped build stays stopped");
        let mut height = alloc::vec![0.0f32; 128 * 128];
        let layers = SkinLayers { height: Some(&mut height), ..SkinLayers::default() };
        skin.render(&SkinRender::default(), layers).expect("what was built renders");
        assert!(height.iter().any(|&h| h > 0.0));
    }
}
