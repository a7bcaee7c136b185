//! The golden scenes: one list of small runs that covers every model and output of hibi-core
//! (the random streams and distributions, the scalar backends, a mud run on both backends with
//! its segments, network, cells and rasters, a glass plate with its cracks, fragments and
//! rasters, and a skin with its outlines, maps and shading), each with the FNV-1a hash of its
//! bytes.
//!
//! The same list runs on the host (`tests/goldens.rs`, in debug and release) and on every cross
//! target (`targets/run`): the hashes must be these exact numbers everywhere. A change here is
//! a deliberate, reviewed event: it changes the patterns hibi makes.
//!
//! `no_std` and allocation-free: the scenes run in static memory ([`Memory::take`]), so a
//! bare-metal runner needs no heap.
#![no_std]
#![deny(missing_docs)]

pub mod stack;

use core::cell::UnsafeCell;
use core::fmt::{self, Write};
use core::mem::MaybeUninit;
use core::sync::atomic::{AtomicBool, Ordering};

use hibi_core::glass::{CrackSlot, Edge, Glass, GlassBuffers, GlassLayers, GlassParams, GlassRender, Vertex};
use hibi_core::mud::{
    Mud, MudBuffers, MudLayers, MudParams, MudRender, NetworkEdge, NetworkPoint, NetworkVertex, Solver, Topology,
    memory_for,
};
use hibi_core::polygon::Ring;
use hibi_core::scalar::Q16;
use hibi_core::skin::{
    ClipVertex, ShadeParams, Site, Skin, SkinBuffers, SkinCell, SkinDivision, SkinLayers, SkinLevel, SkinParams,
    SkinRender, SkinSharedEdges, Wedge, shade,
};
use hibi_core::{Rng, Scalar, Spread, Stream};

/// Every scene's name and the FNV-1a 64 hash of its bytes, in the order [`run`] produces them.
pub const GOLDENS: [(&str, u64); 47] = [
    // The first four 32-bit outputs of each stream for seed 2026 (tests/goldens.rs lists them).
    ("rng.stream.break_stretch", 1769533495125578143),
    ("rng.stream.lattice_jitter", 9541135610860920612),
    ("rng.stream.radial_count", 9211861378282877062),
    ("rng.stream.crack_speed", 9694416965178276497),
    ("rng.stream.ring_radius", 18152018530877967533),
    ("rng.stream.random_force", 15151044015921617632),
    ("rng.stream.impact_rotation", 11372605455220050004),
    ("rng.stream.site_layout", 1476761589826598419),
    ("rng.stream.site_jitter", 10395575674932058571),
    ("rng.stream.edge_perturbation", 7775271193849704305),
    // 10 000 draws of each distribution, as raw bits.
    ("rng.distributions", 4447176120813173559),
    // Every function of each scalar backend over a fixed grid, as the bits of `to_f32`.
    ("scalar.f32", 2369291559573998798),
    ("scalar.micromath", 6723904205137209666),
    ("scalar.q16", 18042995786501796456),
    // tests/mud.rs's golden scene: the default parameters on a 64×64 lattice.
    ("mud.hex64.f32.segments", 16368562623663613091),
    ("mud.hex64.q16.segments", 17237121318573303088),
    // The default parameters on a 32×32 hexagonal lattice, each output.
    ("mud.hex32.f32.segments", 5318310461681098228),
    ("mud.hex32.f32.network", 17579777372880889056),
    ("mud.hex32.f32.cells", 12494728994536339962),
    ("mud.hex32.f32.mask", 14983504809257309222),
    ("mud.hex32.f32.time", 13048393439860089691),
    ("mud.hex32.f32.height", 15532859380764644820),
    ("mud.hex32.f32.statistics", 13565702520126542849),
    ("mud.hex32.q16.segments", 4589402447494758342),
    ("mud.hex32.q16.network", 17976837302588090231),
    ("mud.hex32.q16.cells", 3487615286383109367),
    ("mud.hex32.q16.mask", 15006236524517464945),
    ("mud.hex32.q16.time", 7557332345609429151),
    ("mud.hex32.q16.height", 8460315561065137150),
    ("mud.hex32.q16.statistics", 10864217287244272591),
    // The irregular (jittered Delaunay) lattice, 32×32.
    ("mud.irregular32.f32.segments", 14948481408847612946),
    // A 160×160 plate hit at its centre, seed 7.
    ("glass.plate160.cracks", 14434240461390534570),
    ("glass.plate160.fragments", 14891318822190072901),
    ("glass.plate160.mask", 18067325437012635602),
    ("glass.plate160.time", 18370315924294278147),
    // Skin fig19a at 64×64: outlines, height and normal maps on both backends, shading, the
    // cell map of every level.
    ("skin.fig19a64.outlines", 16065892686752697251),
    ("skin.fig19a64.f32.maps", 4427729296421534182),
    ("skin.fig19a64.q16.maps", 11898630028135427798),
    ("skin.fig19a64.shade", 4422298828594955254),
    ("skin.fig19a64.cell_maps", 8055995322159811074),
    // The 64 KiB scenes ([`run_small`], [`SMALL`]): one small run of each model in a 64 KiB
    // part's memory. Mud on a 16×16 lattice on both backends; glass on a 128×128 plate
    // (radial_mean lowered), its cracks and its 128×128 mask; the one-level skin fig13a 64×64, its
    // outlines and its height map on both backends.
    ("small.mud.hex16.f32.segments", 9881299432880165650),
    ("small.mud.hex16.q16.segments", 1540136574276529383),
    ("small.glass128.cracks", 2458715125343660676),
    ("small.glass128.mask", 3849161772214091367),
    ("small.skin64.outlines", 10842965642735640003),
    ("small.skin64.f32.height", 6430504447789897740),
    ("small.skin64.q16.height", 1162865796114504458),
];

/// Where the 64 KiB scenes ([`run_small`]) lie in [`GOLDENS`].
pub const SMALL: core::ops::Range<usize> = 40..47;

/// The streams in [`Stream::ALL`] order, with their scene names.
const STREAMS: [(Stream, &str); 10] = [
    (Stream::BreakStretch, "rng.stream.break_stretch"),
    (Stream::LatticeJitter, "rng.stream.lattice_jitter"),
    (Stream::RadialCount, "rng.stream.radial_count"),
    (Stream::CrackSpeed, "rng.stream.crack_speed"),
    (Stream::RingRadius, "rng.stream.ring_radius"),
    (Stream::RandomForce, "rng.stream.random_force"),
    (Stream::ImpactRotation, "rng.stream.impact_rotation"),
    (Stream::SiteLayout, "rng.stream.site_layout"),
    (Stream::SiteJitter, "rng.stream.site_jitter"),
    (Stream::EdgePerturbation, "rng.stream.edge_perturbation"),
];

/// Seed of the random-source scenes.
pub const SEED: u64 = 2026;

/// FNV-1a, 64-bit, fed piece by piece: the hash of golden snapshots.
#[derive(Clone, Copy, Debug)]
pub struct Fnv(u64);

impl Fnv {
    /// The empty hash.
    pub const fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }

    /// Feeds `bytes`.
    pub fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// Feeds a `u32`, little-endian.
    pub fn u32(&mut self, v: u32) {
        self.bytes(&v.to_le_bytes());
    }

    /// Feeds an `f32`'s bits, little-endian.
    pub fn f32(&mut self, v: f32) {
        self.u32(v.to_bits());
    }

    /// Feeds an `f64`'s bits, little-endian.
    pub fn f64(&mut self, v: f64) {
        self.bytes(&v.to_bits().to_le_bytes());
    }

    /// The hash of everything fed so far.
    pub const fn finish(&self) -> u64 {
        self.0
    }
}

/// Feeds formatted text (`write!(fnv, ...)`).
impl Write for Fnv {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.bytes(s.as_bytes());
        Ok(())
    }
}

impl Default for Fnv {
    fn default() -> Self {
        Fnv::new()
    }
}

/// FNV-1a, 64-bit, of `bytes`: the hash of golden snapshots.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h = Fnv::new();
    h.bytes(bytes);
    h.finish()
}

/// Lattice of the small mud scenes.
const MUD_SMALL: u32 = 32;
/// Lattice of tests/mud.rs's golden scene.
const MUD_LARGE: u32 = 64;
/// Side of the glass plate and of its rasters.
const PLATE: u32 = 160;
/// Side of the skin image.
const SKIN: u32 = 64;
/// Side of the mud rasters.
const MUD_RASTER: u32 = 128;

const fn max(a: usize, b: usize) -> usize {
    if a > b { a } else { b }
}

/// The mud memory of the largest scene (quasi-static, the default solver).
const MUD_LARGE_MEMORY: hibi_core::mud::MudMemory =
    memory_for(Topology::Hexagonal, Solver::QuasiStatic, MUD_LARGE, MUD_LARGE).unwrap();
const MUD_IRREGULAR_MEMORY: hibi_core::mud::MudMemory =
    memory_for(Topology::Irregular, Solver::QuasiStatic, MUD_SMALL, MUD_SMALL).unwrap();
const MUD_SCALARS: usize = max(MUD_LARGE_MEMORY.scalars, MUD_IRREGULAR_MEMORY.scalars);

// Capacities of the glass plate, the skin and the outputs, checked by each run (a scene that
// does not fit fails naming what is short). Measured on the host for the scenes above.
const GLASS_CRACKS: usize = 512;
const GLASS_VERTICES: usize = 16384;
const GLASS_EDGES: usize = 16384;
const GLASS_WORDS: usize = 214316;
const GLASS_SCRATCH: usize = 51725;
const SKIN_CELLS: usize = 2292;
const SKIN_VERTICES: usize = 108408;
const SKIN_SITES: usize = 8217;
const SKIN_CLIP: usize = 6344;
const SKIN_WORDS: usize = 4096;
const SKIN_LEVELS: usize = 3;
const SKIN_DIVISIONS: usize = 2;
const SKIN_SHARED_EDGES: usize = 2;
const SKIN_BOXES: usize = 563;
// A wedge per outline vertex and one per cell.
const SKIN_WEDGES: usize = SKIN_VERTICES + SKIN_CELLS;
const WORDS: usize =
    max(max(MUD_LARGE_MEMORY.words, MUD_IRREGULAR_MEMORY.words), max(GLASS_WORDS + GLASS_SCRATCH, SKIN_WORDS));
const NETWORK_VERTICES: usize = 2048;
const NETWORK_EDGES: usize = 2048;
const NETWORK_POINTS: usize = 8192;
const RINGS: usize = 1024;
const RING_POINTS: usize = 16384;
const PIXELS: usize = max((PLATE * PLATE) as usize, (MUD_RASTER * MUD_RASTER) as usize);
const SKIN_PIXELS: usize = (SKIN * SKIN) as usize;

/// One static array, handed out once as a slice of default values.
struct Slot<T, const N: usize>(UnsafeCell<MaybeUninit<[T; N]>>);

// SAFETY: a slot's contents are reached only through `Slot::init`, which `Memory::take` calls
// at most once per slot in the program's life.
unsafe impl<T, const N: usize> Sync for Slot<T, N> {}

impl<T: Default, const N: usize> Slot<T, N> {
    const fn new() -> Self {
        Slot(UnsafeCell::new(MaybeUninit::uninit()))
    }

    /// Fills the slot with default values (element by element: the array may be larger than
    /// the stack) and returns it.
    ///
    /// # Safety
    /// At most one call per slot.
    #[allow(clippy::mut_from_ref, reason = "the UnsafeCell pattern; the one-call contract makes it unique")]
    unsafe fn init(&'static self) -> &'static mut [T] {
        let first = self.0.get().cast::<T>();
        for i in 0..N {
            // SAFETY: `i < N` is inside the array, which nothing else references yet.
            unsafe { first.add(i).write(T::default()) };
        }
        // SAFETY: all N elements are initialised and this is the only reference.
        unsafe { core::slice::from_raw_parts_mut(first, N) }
    }
}

/// The static memory every scene runs in: model buffers and output buffers, reused scene
/// after scene.
pub struct Memory {
    mud_f32: &'static mut [f32],
    mud_q16: &'static mut [Q16],
    words: &'static mut [u32],
    out: Outputs,
    cracks: &'static mut [CrackSlot],
    vertices: &'static mut [Vertex],
    edges: &'static mut [Edge],
    skin_cells: &'static mut [SkinCell],
    skin_vertices: &'static mut [[i64; 2]],
    sites: &'static mut [Site],
    clip: &'static mut [ClipVertex],
    skin_levels: &'static mut [SkinLevel],
    skin_divisions: &'static mut [SkinDivision],
    skin_shared_edges: &'static mut [SkinSharedEdges],
    boxes: &'static mut [[i64; 4]],
    wedges: &'static mut [Wedge],
    normals: &'static mut [[f32; 3]],
    rgb: &'static mut [[u8; 3]],
    cell_map: &'static mut [u32],
    arena: &'static mut [u64],
}

/// Output buffers shared by the models.
struct Outputs {
    net_vertices: &'static mut [NetworkVertex],
    net_edges: &'static mut [NetworkEdge],
    net_points: &'static mut [NetworkPoint],
    rings: &'static mut [Ring],
    ring_points: &'static mut [[f32; 2]],
    mask: &'static mut [u8],
    floats: &'static mut [f32],
}

impl Memory {
    /// The scenes' static memory; `None` after the first call.
    pub fn take() -> Option<Memory> {
        static TAKEN: AtomicBool = AtomicBool::new(false);
        static MUD_F32: Slot<f32, MUD_SCALARS> = Slot::new();
        static MUD_Q16: Slot<Q16, MUD_SCALARS> = Slot::new();
        static WORD: Slot<u32, WORDS> = Slot::new();
        static NET_VERTICES: Slot<NetworkVertex, NETWORK_VERTICES> = Slot::new();
        static NET_EDGES: Slot<NetworkEdge, NETWORK_EDGES> = Slot::new();
        static NET_POINTS: Slot<NetworkPoint, NETWORK_POINTS> = Slot::new();
        static RING: Slot<Ring, RINGS> = Slot::new();
        static RING_POINT: Slot<[f32; 2], RING_POINTS> = Slot::new();
        static CRACKS: Slot<CrackSlot, GLASS_CRACKS> = Slot::new();
        static VERTICES: Slot<Vertex, GLASS_VERTICES> = Slot::new();
        static EDGES: Slot<Edge, GLASS_EDGES> = Slot::new();
        static SKIN_CELL: Slot<SkinCell, SKIN_CELLS> = Slot::new();
        static SKIN_VERTEX: Slot<[i64; 2], SKIN_VERTICES> = Slot::new();
        static SITES: Slot<Site, SKIN_SITES> = Slot::new();
        static CLIP: Slot<ClipVertex, SKIN_CLIP> = Slot::new();
        static SKIN_LEVEL: Slot<SkinLevel, SKIN_LEVELS> = Slot::new();
        static SKIN_DIVISION: Slot<SkinDivision, SKIN_DIVISIONS> = Slot::new();
        static SKIN_SHARED_EDGE: Slot<SkinSharedEdges, SKIN_SHARED_EDGES> = Slot::new();
        static BOXES: Slot<[i64; 4], SKIN_BOXES> = Slot::new();
        static WEDGES: Slot<Wedge, SKIN_WEDGES> = Slot::new();
        static MASK: Slot<u8, PIXELS> = Slot::new();
        static FLOATS: Slot<f32, PIXELS> = Slot::new();
        static NORMALS: Slot<[f32; 3], SKIN_PIXELS> = Slot::new();
        static RGB: Slot<[u8; 3], SKIN_PIXELS> = Slot::new();
        static CELL_MAP: Slot<u32, SKIN_PIXELS> = Slot::new();
        if TAKEN.swap(true, Ordering::AcqRel) {
            return None;
        }
        let arena = small_arena()?;
        // SAFETY: TAKEN was false, so this is the one call that reaches the slots.
        unsafe {
            Some(Memory {
                mud_f32: MUD_F32.init(),
                mud_q16: MUD_Q16.init(),
                words: WORD.init(),
                out: Outputs {
                    net_vertices: NET_VERTICES.init(),
                    net_edges: NET_EDGES.init(),
                    net_points: NET_POINTS.init(),
                    rings: RING.init(),
                    ring_points: RING_POINT.init(),
                    mask: MASK.init(),
                    floats: FLOATS.init(),
                },
                cracks: CRACKS.init(),
                vertices: VERTICES.init(),
                edges: EDGES.init(),
                skin_cells: SKIN_CELL.init(),
                skin_vertices: SKIN_VERTEX.init(),
                sites: SITES.init(),
                clip: CLIP.init(),
                skin_levels: SKIN_LEVEL.init(),
                skin_divisions: SKIN_DIVISION.init(),
                skin_shared_edges: SKIN_SHARED_EDGE.init(),
                boxes: BOXES.init(),
                wedges: WEDGES.init(),
                normals: NORMALS.init(),
                rgb: RGB.init(),
                cell_map: CELL_MAP.init(),
                arena,
            })
        }
    }

    /// Bytes of static memory the scenes use.
    pub const fn bytes() -> usize {
        use core::mem::size_of;
        MUD_SCALARS * (size_of::<f32>() + size_of::<Q16>())
            + WORDS * 4
            + NETWORK_VERTICES * size_of::<NetworkVertex>()
            + NETWORK_EDGES * size_of::<NetworkEdge>()
            + NETWORK_POINTS * size_of::<NetworkPoint>()
            + RINGS * size_of::<Ring>()
            + RING_POINTS * 8
            + GLASS_CRACKS * size_of::<CrackSlot>()
            + GLASS_VERTICES * size_of::<Vertex>()
            + GLASS_EDGES * size_of::<Edge>()
            + SKIN_CELLS * size_of::<SkinCell>()
            + SKIN_VERTICES * 16
            + SKIN_SITES * size_of::<Site>()
            + SKIN_CLIP * size_of::<ClipVertex>()
            + SKIN_LEVELS * size_of::<SkinLevel>()
            + SKIN_DIVISIONS * size_of::<SkinDivision>()
            + SKIN_SHARED_EDGES * size_of::<SkinSharedEdges>()
            + SKIN_BOXES * 32
            + SKIN_WEDGES * size_of::<Wedge>()
            + PIXELS * 5
            + SKIN_PIXELS * 19
            + SMALL_ARENA_WORDS * 8
    }
}

/// Why a scene produced no hash.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Failure(pub &'static str);

/// What one scene gave.
pub type Outcome = Result<u64, Failure>;

/// Runs every scene in [`GOLDENS`] order, calling `emit` with each scene's name and hash.
pub fn run(memory: &mut Memory, emit: &mut dyn FnMut(&'static str, Outcome)) {
    rng(emit);
    scalars(emit);
    let large = MudParams { columns: MUD_LARGE, rows: MUD_LARGE, ..MudParams::default() };
    emit("mud.hex64.f32.segments", mud_segments(&large, memory.mud_f32, memory.words));
    emit("mud.hex64.q16.segments", mud_segments(&large, memory.mud_q16, memory.words));
    let small = MudParams { columns: MUD_SMALL, rows: MUD_SMALL, ..MudParams::default() };
    let names = [
        "mud.hex32.f32.segments",
        "mud.hex32.f32.network",
        "mud.hex32.f32.cells",
        "mud.hex32.f32.mask",
        "mud.hex32.f32.time",
        "mud.hex32.f32.height",
        "mud.hex32.f32.statistics",
    ];
    mud_outputs(&small, memory.mud_f32, memory.words, &mut memory.out, names, emit);
    let names = [
        "mud.hex32.q16.segments",
        "mud.hex32.q16.network",
        "mud.hex32.q16.cells",
        "mud.hex32.q16.mask",
        "mud.hex32.q16.time",
        "mud.hex32.q16.height",
        "mud.hex32.q16.statistics",
    ];
    mud_outputs(&small, memory.mud_q16, memory.words, &mut memory.out, names, emit);
    let irregular = MudParams { topology: Topology::Irregular, ..small };
    emit("mud.irregular32.f32.segments", mud_segments(&irregular, memory.mud_f32, memory.words));
    glass(memory, emit);
    skin(memory, emit);
    run_small(memory.arena, emit);
}

/// Runs a mud scene to its end in `scalars` and `words`.
fn mud_run<'a, S: Scalar>(
    params: &MudParams,
    scalars: &'a mut [S],
    words: &'a mut [u32],
) -> Result<Mud<'a, S>, Failure> {
    let mut mud = Mud::new(params, MudBuffers { scalars, words })
        .map_err(|_| Failure("mud: Mud::new refused (memory too small?)"))?;
    while !mud.step(1_000_000).map_err(|_| Failure("mud: the run failed"))?.finished {}
    Ok(mud)
}

/// The hash of a run's segments (as tests/mud.rs's golden: start, end, width, time).
fn segments_hash<S: Scalar>(mud: &Mud<'_, S>) -> u64 {
    let mut h = Fnv::new();
    mud.for_each_segment(|s| {
        for v in [s.start, s.end, s.width, s.time].into_iter().flatten() {
            h.f32(v);
        }
    });
    h.finish()
}

#[inline(never)] // each scene's frame apart: the stack a run needs is its deepest scene's
fn mud_segments<S: Scalar>(params: &MudParams, scalars: &mut [S], words: &mut [u32]) -> Outcome {
    Ok(segments_hash(&mud_run(params, scalars, words)?))
}

/// One mud run and every output of it: segments, network, cells, the mask, time and height
/// rasters, and the statistics.
#[inline(never)] // each scene's frame apart: the stack a run needs is its deepest scene's
fn mud_outputs<S: Scalar>(
    params: &MudParams,
    scalars: &mut [S],
    words: &mut [u32],
    out: &mut Outputs,
    names: [&'static str; 7],
    emit: &mut dyn FnMut(&'static str, Outcome),
) {
    let mud = match mud_run(params, scalars, words) {
        Ok(mud) => mud,
        Err(e) => return names.into_iter().for_each(|name| emit(name, Err(e))),
    };
    emit(names[0], Ok(segments_hash(&mud)));
    let network = mud
        .network(out.net_vertices, out.net_edges, out.net_points)
        .map_err(|_| Failure("mud: network buffers too small"))
        .map(|c| {
            let mut h = Fnv::new();
            for v in &out.net_vertices[..c.vertices] {
                h.f32(v.at[0]);
                h.f32(v.at[1]);
                h.u32(v.degree);
                h.u32(v.on_border);
            }
            for e in &out.net_edges[..c.edges] {
                for x in [e.from, e.to, e.first_point, e.point_count] {
                    h.u32(x);
                }
            }
            for p in &out.net_points[..c.points] {
                for x in [p.at[0], p.at[1], p.width, p.time] {
                    h.f32(x);
                }
            }
            h.finish()
        });
    emit(names[1], network);
    let cells = mud.cells(out.rings, out.ring_points).map_err(|_| Failure("mud: cell buffers too small")).map(|c| {
        let mut h = rings_hash(&out.rings[..c.rings], &out.ring_points[..c.points]);
        h.u32(c.wrapping as u32);
        h.finish()
    });
    emit(names[2], cells);
    let render = MudRender { width: MUD_RASTER, height: MUD_RASTER, ..MudRender::default() };
    let pixels = (MUD_RASTER * MUD_RASTER) as usize;
    let refused = |_| Failure("mud: render refused");
    let mask = mud.render(&render, MudLayers { mask: Some(&mut out.mask[..pixels]), ..MudLayers::default() });
    emit(names[3], mask.map_err(refused).map(|()| fnv1a64(&out.mask[..pixels])));
    let time = mud.render(&render, MudLayers { time: Some(&mut out.floats[..pixels]), ..MudLayers::default() });
    emit(names[4], time.map_err(refused).map(|()| floats_hash(&out.floats[..pixels])));
    let height = mud.render(&render, MudLayers { height: Some(&mut out.floats[..pixels]), ..MudLayers::default() });
    emit(names[5], height.map_err(refused).map(|()| floats_hash(&out.floats[..pixels])));
    // Every statistic, as its `Debug` text (shortest round-trip decimals: one text per value).
    let mut h = Fnv::new();
    let statistics = write!(h, "{:?}", mud.statistics()).map_err(|_| Failure("mud: statistics not formatted"));
    emit(names[6], statistics.map(|()| h.finish()));
}

fn floats_hash(values: &[f32]) -> u64 {
    let mut h = Fnv::new();
    values.iter().for_each(|&v| h.f32(v));
    h.finish()
}

/// The hash of rings (mud's cells, glass's fragments) and their points.
fn rings_hash(rings: &[Ring], points: &[[f32; 2]]) -> Fnv {
    let mut h = Fnv::new();
    for r in rings {
        h.f64(r.area);
        for x in [r.first_point, r.point_count, r.hole_of] {
            h.u32(x);
        }
    }
    points.iter().flatten().for_each(|&v| h.f32(v));
    h
}

#[inline(never)] // each scene's frame apart: the stack a run needs is its deepest scene's
fn glass(memory: &mut Memory, emit: &mut dyn FnMut(&'static str, Outcome)) {
    let names = ["glass.plate160.cracks", "glass.plate160.fragments", "glass.plate160.mask", "glass.plate160.time"];
    let side = PLATE as f32;
    let params = GlassParams { width: side, height: side, impact: [side / 2.0; 2], seed: 7, ..GlassParams::default() };
    // The plate's words, then the fragment queries' scratch.
    let (words, scratch) = memory.words.split_at_mut(GLASS_WORDS);
    let buffers = GlassBuffers { cracks: memory.cracks, vertices: memory.vertices, edges: memory.edges, words };
    let mut glass = match Glass::new(&params, buffers) {
        Ok(glass) => glass,
        Err(_) => {
            return names
                .into_iter()
                .for_each(|name| emit(name, Err(Failure("glass: Glass::new refused (memory too small?)"))));
        }
    };
    while !glass.step(100_000).finished {}
    emit(names[0], Ok(cracks_hash(&glass)));
    let out = &mut memory.out;
    let fragments = glass
        .fragments(scratch, out.rings, out.ring_points)
        .map_err(|_| Failure("glass: fragment buffers too small"))
        .map(|(rings, points)| rings_hash(&out.rings[..rings], &out.ring_points[..points]).finish());
    emit(names[1], fragments);
    let render = GlassRender { width: PLATE, height: PLATE, ..GlassRender::default() };
    let pixels = (PLATE * PLATE) as usize;
    let refused = |_| Failure("glass: render refused");
    let mask = glass.render(&render, GlassLayers { mask: Some(&mut out.mask[..pixels]), ..GlassLayers::default() });
    emit(names[2], mask.map_err(refused).map(|()| fnv1a64(&out.mask[..pixels])));
    let time = glass.render(&render, GlassLayers { time: Some(&mut out.floats[..pixels]), ..GlassLayers::default() });
    emit(names[3], time.map_err(refused).map(|()| floats_hash(&out.floats[..pixels])));
}

#[inline(never)] // each scene's frame apart: the stack a run needs is its deepest scene's
fn skin(memory: &mut Memory, emit: &mut dyn FnMut(&'static str, Outcome)) {
    let names = [
        "skin.fig19a64.outlines",
        "skin.fig19a64.f32.maps",
        "skin.fig19a64.q16.maps",
        "skin.fig19a64.shade",
        "skin.fig19a64.cell_maps",
    ];
    let Some(preset) = hibi_core::skin::preset("fig19a") else {
        return names.into_iter().for_each(|name| emit(name, Err(Failure("skin: no preset fig19a"))));
    };
    let params = SkinParams { width: SKIN, height: SKIN, ..preset };
    let Memory {
        skin_cells,
        skin_vertices,
        sites,
        clip,
        words,
        skin_levels,
        skin_divisions,
        skin_shared_edges,
        boxes,
        wedges,
        out,
        normals,
        rgb,
        cell_map,
        ..
    } = memory;
    let pixels = SKIN_PIXELS;
    let (height, normals) = (&mut out.floats[..pixels], &mut normals[..pixels]);
    // The Q16 maps first, from a skin built in the same memory, so that the f32 maps are what
    // the shading reads.
    // The same static memory for both skins, one after the other.
    macro_rules! buffers {
        () => {
            SkinBuffers {
                cells: &mut **skin_cells,
                vertices: &mut **skin_vertices,
                sites: &mut **sites,
                clip: &mut **clip,
                words: &mut **words,
                levels: &mut **skin_levels,
                divisions: &mut **skin_divisions,
                shared_edges: &mut **skin_shared_edges,
                boxes: &mut **boxes,
                wedges: &mut **wedges,
            }
        };
    }
    let q16 = Skin::<Q16>::new(&params, buffers!())
        .map_err(|_| Failure("skin: Skin::new refused (memory too small?)"))
        .and_then(|mut skin| built(&mut skin).and_then(|()| maps(&skin, height, normals)));
    let mut skin = match Skin::<f32>::new(&params, buffers!()) {
        Ok(skin) => skin,
        Err(_) => {
            return names
                .into_iter()
                .for_each(|name| emit(name, Err(Failure("skin: Skin::new refused (memory too small?)"))));
        }
    };
    if let Err(e) = built(&mut skin) {
        return names.into_iter().for_each(|name| emit(name, Err(e)));
    }
    let mut h = Fnv::new();
    outlines_hash(&mut h, &skin);
    emit(names[0], Ok(h.finish()));
    let f32 = maps(&skin, height, normals);
    emit(names[1], f32);
    emit(names[2], q16);
    let rgb = &mut rgb[..pixels];
    let shaded = shade(height, normals, &ShadeParams::default(), rgb).map_err(|_| Failure("skin: shade refused"));
    emit(names[3], shaded.map(|()| fnv1a64(rgb.as_flattened())));
    let cell_maps = (|| {
        let mut h = Fnv::new();
        for level in 0..params.levels {
            let layers = SkinLayers { cell: Some(&mut **cell_map), ..SkinLayers::default() };
            skin.render(&SkinRender { cell_level: level, ..SkinRender::default() }, layers)
                .map_err(|_| Failure("skin: cell map refused"))?;
            cell_map.iter().for_each(|&c| h.u32(c));
        }
        Ok(h.finish())
    })();
    emit(names[4], cell_maps);
}

/// Builds every cell of `skin`.
fn built<S: Scalar>(skin: &mut Skin<'_, S>) -> Result<(), Failure> {
    if skin.run().capacity_reached { Err(Failure("skin: a capacity ran out")) } else { Ok(()) }
}

/// The hash of a skin's height and normal maps, rendered into `height` and `normals`.
fn maps<S: Scalar>(skin: &Skin<'_, S>, height: &mut [f32], normals: &mut [[f32; 3]]) -> Outcome {
    let layers = SkinLayers { height: Some(&mut *height), normal: Some(&mut *normals), ..SkinLayers::default() };
    skin.render(&SkinRender::default(), layers).map_err(|_| Failure("skin: render refused"))?;
    let mut h = Fnv::new();
    height.iter().for_each(|&v| h.f32(v));
    normals.iter().flatten().for_each(|&v| h.f32(v));
    Ok(h.finish())
}

#[inline(never)] // each scene's frame apart: the stack a run needs is its deepest scene's
fn rng(emit: &mut dyn FnMut(&'static str, Outcome)) {
    for (stream, name) in STREAMS {
        let mut rng = Rng::new(SEED, stream);
        let mut h = Fnv::new();
        for _ in 0..4 {
            h.u32(rng.next_u32());
        }
        emit(name, Ok(h.finish()));
    }
    let mut h = Fnv::new();
    let mut rng = Rng::new(SEED, Stream::BreakStretch);
    let outcome = (|| {
        for _ in 0..10_000 {
            h.f32(rng.uniform_f32());
            h.f64(rng.uniform_f64());
            h.f64(rng.normal());
            h.u32(rng.poisson(37.5).map_err(|_| Failure("poisson refused its mean"))?);
            h.f32(rng.rand(40.0, 0.3, Spread::Normal).map_err(|_| Failure("rand refused"))?);
            h.f32(rng.rand(40.0, 0.3, Spread::Uniform).map_err(|_| Failure("rand refused"))?);
        }
        Ok(h.finish())
    })();
    emit("rng.distributions", outcome);
}

/// Every function of a backend over a fixed grid, as the bits of `to_f32`.
fn backend_table<S: Scalar>() -> u64 {
    let mut h = Fnv::new();
    let mut push = |v: S| h.f32(v.to_f32());
    for i in -400..=400 {
        let x = S::from_f32(i as f32 * 0.037);
        let y = S::from_f32(i as f32 * -0.021 + 0.5);
        push(x.sqrt());
        push(x.sin());
        push(x.cos());
        push(y.atan2(x));
        push((x * S::from_f32(0.25)).exp());
        push(x.floor());
        push(x * y + x / (y + S::from_f32(3.0)));
    }
    h.finish()
}

#[inline(never)] // each scene's frame apart: the stack a run needs is its deepest scene's
fn scalars(emit: &mut dyn FnMut(&'static str, Outcome)) {
    emit("scalar.f32", Ok(backend_table::<f32>()));
    emit("scalar.micromath", Ok(backend_table::<micromath::F32>()));
    emit("scalar.q16", Ok(backend_table::<Q16>()));
}
// --- The 64 KiB scenes ------------------------------------------------------------------------

/// `u64` words of the arena the 64 KiB scenes share: each scene takes its model's memory and
/// its outputs from it and gives them back when it ends, so the arena is the largest scene's
/// need, not the sum: the glass plate (26,000 bytes at capacities equal to its use) and its
/// 128×128 mask (16,384), 42,384 bytes on x86_64 and on the M3 (the mud scenes take 38,624;
/// the 64×64 skin 8,608, with its 64×64 height map 24,992).
/// The rest of the 64 KiB is the stack's (`targets/run lm3s6965evb` reports its peak).
pub const SMALL_ARENA_WORDS: usize = 5298;

/// Lattice of the small mud scenes.
const SMALL_MUD: u32 = 16;
/// Side of the small glass plate.
const SMALL_PLATE: u32 = 128;
/// Side of its mask: the plate's own, one pixel per pixel (16 KiB, which fits beside the plate
/// only because the plate's capacities are what it uses).
const SMALL_MASK: u32 = 128;
/// M_ave of the small plate. The paper's 100 draws M = 102 here and needs 1313 vertices and
/// about 165 KiB; 40 draws M = 44 (no ring cracks: those need M > 70) and 175 vertices.
const SMALL_RADIAL_MEAN: f32 = 40.0;
/// Crack and vertex capacities of the small plate: exactly what it uses (44 and 175; the
/// scene fails if one runs out, so a change of the growth that needs more shows here).
const SMALL_GLASS_CRACKS: u32 = 44;
const SMALL_GLASS_VERTICES: u32 = 175;
/// Side of the small skin and its height map.
const SMALL_SKIN: u32 = 64;

/// The 64 KiB scenes' arena; `None` after the first call (and to the runner once
/// [`Memory::take`] has it).
pub fn small_arena() -> Option<&'static mut [u64]> {
    static TAKEN: AtomicBool = AtomicBool::new(false);
    static ARENA: Slot<u64, SMALL_ARENA_WORDS> = Slot::new();
    if TAKEN.swap(true, Ordering::AcqRel) {
        return None;
    }
    // SAFETY: TAKEN was false, so this is the one call that reaches the slot.
    Some(unsafe { ARENA.init() })
}

/// Typed slices cut from the front of a `u64` arena, each filled with default values.
struct Arena<'a> {
    rest: &'a mut [u64],
}

impl<'a> Arena<'a> {
    fn new(words: &'a mut [u64]) -> Self {
        Arena { rest: words }
    }

    /// `n` default values of `T` from the arena, or `Failure(short)` if it has too little left.
    fn take<T: Default>(&mut self, n: usize, short: &'static str) -> Result<&'a mut [T], Failure> {
        const {
            assert!(core::mem::align_of::<T>() <= core::mem::align_of::<u64>());
            assert!(!core::mem::needs_drop::<T>());
        }
        let words = n.checked_mul(core::mem::size_of::<T>()).ok_or(Failure(short))?.div_ceil(8);
        if words > self.rest.len() {
            return Err(Failure(short));
        }
        let (head, tail) = core::mem::take(&mut self.rest).split_at_mut(words);
        self.rest = tail;
        let first = head.as_mut_ptr().cast::<T>();
        for i in 0..n {
            // SAFETY: `head` holds `n` values of `T` (size checked above, alignment by the
            // const assertion) and nothing else references it.
            unsafe { first.add(i).write(T::default()) };
        }
        // SAFETY: all `n` values are initialised; `head`'s borrow moves into the slice (T
        // needs no drop, so the u64 words may simply be reused after it).
        Ok(unsafe { core::slice::from_raw_parts_mut(first, n) })
    }
}

/// Runs the 64 KiB scenes (`GOLDENS[SMALL]`) in `arena`, calling `emit` with each scene's
/// name and hash.
pub fn run_small(arena: &mut [u64], emit: &mut dyn FnMut(&'static str, Outcome)) {
    let mud = MudParams { columns: SMALL_MUD, rows: SMALL_MUD, ..MudParams::default() };
    emit("small.mud.hex16.f32.segments", small_mud::<f32>(&mud, arena));
    emit("small.mud.hex16.q16.segments", small_mud::<Q16>(&mud, arena));
    small_glass(arena, emit);
    small_skin(arena, emit);
}

#[inline(never)] // each scene's frame apart: the stack a run needs is its deepest scene's
fn small_mud<S: Scalar + Default>(params: &MudParams, arena: &mut [u64]) -> Outcome {
    let memory = params.memory().map_err(|_| Failure("mud: parameters refused"))?;
    let mut arena = Arena::new(arena);
    let scalars = arena.take::<S>(memory.scalars, "mud: arena too small for its scalars")?;
    let words = arena.take::<u32>(memory.words, "mud: arena too small for its words")?;
    Ok(segments_hash(&mud_run(params, scalars, words)?))
}

#[inline(never)] // each scene's frame apart: the stack a run needs is its deepest scene's
fn small_glass(arena: &mut [u64], emit: &mut dyn FnMut(&'static str, Outcome)) {
    let names = ["small.glass128.cracks", "small.glass128.mask"];
    let side = SMALL_PLATE as f32;
    let params = GlassParams {
        width: side,
        height: side,
        impact: [side / 2.0; 2],
        seed: 7,
        radial_mean: SMALL_RADIAL_MEAN,
        max_cracks: SMALL_GLASS_CRACKS,
        max_vertices: SMALL_GLASS_VERTICES,
        ..GlassParams::default()
    };
    let pixels = (SMALL_MASK * SMALL_MASK) as usize;
    let mut arena = Arena::new(arena);
    let glass = (|| {
        let memory = params.memory().map_err(|_| Failure("glass: parameters refused"))?;
        let buffers = GlassBuffers {
            cracks: arena.take(memory.cracks, "glass: arena too small for its cracks")?,
            vertices: arena.take(memory.vertices, "glass: arena too small for its vertices")?,
            edges: arena.take(memory.edges, "glass: arena too small for its edges")?,
            words: arena.take(memory.words, "glass: arena too small for its words")?,
        };
        let mut glass = Glass::new(&params, buffers).map_err(|_| Failure("glass: Glass::new refused"))?;
        while !glass.step(100_000).finished {}
        if glass.progress().capacity_reached {
            return Err(Failure("glass: a capacity ran out"));
        }
        Ok(glass)
    })();
    let glass = match glass {
        Ok(glass) => glass,
        Err(e) => return names.into_iter().for_each(|name| emit(name, Err(e))),
    };
    emit(names[0], Ok(cracks_hash(&glass)));
    let mask = arena.take::<u8>(pixels, "glass: arena too small for the mask").and_then(|mask| {
        let render = GlassRender { width: SMALL_MASK, height: SMALL_MASK, ..GlassRender::default() };
        glass
            .render(&render, GlassLayers { mask: Some(&mut *mask), ..GlassLayers::default() })
            .map_err(|_| Failure("glass: render refused"))?;
        Ok(fnv1a64(mask))
    });
    emit(names[1], mask);
}

/// The skin of the 64 KiB scenes: fig13a (one level) on `side`².
fn small_skin_params(side: u32) -> Result<SkinParams, Failure> {
    let mut params = hibi_core::skin::preset("fig13a").ok_or(Failure("skin: no preset fig13a"))?;
    params.width = side;
    params.height = side;
    Ok(params)
}

#[inline(never)] // each scene's frame apart: the stack a run needs is its deepest scene's
fn small_skin(arena: &mut [u64], emit: &mut dyn FnMut(&'static str, Outcome)) {
    emit("small.skin64.outlines", small_skin_run::<f32>(arena, SMALL_SKIN, false));
    emit("small.skin64.f32.height", small_skin_run::<f32>(arena, SMALL_SKIN, true));
    emit("small.skin64.q16.height", small_skin_run::<Q16>(arena, SMALL_SKIN, true));
}

/// Builds the small skin `side`² in `arena` with backend `S` and hashes its outlines, or
/// (`height`) its height map.
#[inline(never)] // each scene's frame apart: the stack a run needs is its deepest scene's
fn small_skin_run<S: Scalar>(arena: &mut [u64], side: u32, height: bool) -> Outcome {
    let params = small_skin_params(side)?;
    let memory = params.memory().map_err(|_| Failure("skin: parameters refused"))?;
    let mut arena = Arena::new(arena);
    let short = "skin: arena too small";
    let buffers = SkinBuffers {
        cells: arena.take(memory.cells, short)?,
        vertices: arena.take(memory.vertices, short)?,
        sites: arena.take(memory.sites, short)?,
        clip: arena.take(memory.clip, short)?,
        words: arena.take(memory.words, short)?,
        levels: arena.take(memory.levels, short)?,
        divisions: arena.take(memory.divisions, short)?,
        shared_edges: arena.take(memory.shared_edges, short)?,
        boxes: arena.take(memory.boxes, short)?,
        wedges: arena.take(memory.wedges, short)?,
    };
    let mut skin = Skin::<S>::new(&params, buffers).map_err(|_| Failure("skin: Skin::new refused"))?;
    built(&mut skin)?;
    let mut h = Fnv::new();
    if height {
        let map = arena.take::<f32>((side * side) as usize, "skin: arena too small for the height map")?;
        let layers = SkinLayers { height: Some(&mut *map), ..SkinLayers::default() };
        skin.render(&SkinRender::default(), layers).map_err(|_| Failure("skin: render refused"))?;
        map.iter().for_each(|&v| h.f32(v));
    } else {
        outlines_hash(&mut h, &skin);
    }
    Ok(h.finish())
}

/// As tests/glass.rs's golden: each crack's end, then its points (position and time).
fn cracks_hash(glass: &Glass<'_>) -> u64 {
    let mut h = Fnv::new();
    for i in 0..glass.crack_count() {
        h.u32(glass.crack(i).map_or(u32::MAX, |c| c.end as u32));
        glass.for_each_point(i, |q| {
            for v in [q.at[0], q.at[1], q.time] {
                h.f32(v);
            }
        });
    }
    h.finish()
}

/// As tests/skin.rs's golden: each cell's site id and outline.
fn outlines_hash<S: Scalar>(h: &mut Fnv, skin: &Skin<'_, S>) {
    for c in skin.cells() {
        h.u32(c.site);
        for v in skin.outline(c) {
            h.bytes(&v[0].to_le_bytes());
            h.bytes(&v[1].to_le_bytes());
        }
    }
}

/// Runs every scene and writes one line per scene to `out` (`ok`, `DIFFERS` with both hashes,
/// or `FAILED` with the reason, `MISSING` for a scene that did not run), the static memory the
/// scenes use, then a summary line
/// `hibi-scenes on TARGET: N scenes, M differ`. Returns the number of scenes that differ,
/// failed or are missing.
pub fn check(memory: &mut Memory, target: &str, out: &mut dyn Write) -> Result<usize, fmt::Error> {
    check_scenes(&GOLDENS, &mut |emit| run(memory, emit), Memory::bytes(), target, out, None)
}

/// Where a scene run hands each scene's name and outcome.
pub type Emit<'a> = dyn FnMut(&'static str, Outcome) + 'a;

/// A counter read after each scene (instructions, cycles, ticks) and its unit's name.
pub type Meter<'a> = (&'a mut dyn FnMut() -> u64, &'a str);

/// As [`check`], for the 64 KiB scenes only (`GOLDENS[SMALL]`) in `arena` (from
/// [`small_arena`]); with a meter, also a line `cost     NAME N UNIT` per scene, N the
/// meter's count since the previous scene ended.
pub fn check_small(
    arena: &mut [u64],
    target: &str,
    out: &mut dyn Write,
    meter: Option<Meter<'_>>,
) -> Result<usize, fmt::Error> {
    let bytes = arena.len() * 8;
    check_scenes(&GOLDENS[SMALL], &mut |emit| run_small(arena, emit), bytes, target, out, meter)
}

fn check_scenes(
    goldens: &[(&str, u64)],
    scenes: &mut dyn FnMut(&mut Emit<'_>),
    memory_bytes: usize,
    target: &str,
    out: &mut dyn Write,
    mut meter: Option<Meter<'_>>,
) -> Result<usize, fmt::Error> {
    let (mut index, mut differ) = (0, 0);
    let mut result = Ok(());
    let mut last = meter.as_mut().map_or(0, |(read, _)| read());
    scenes(&mut |name, outcome| {
        let expected = goldens.get(index).copied();
        index += 1;
        let line = match (expected, outcome) {
            (Some((want, hash)), Ok(got)) if want == name && hash == got => writeln!(out, "ok       {name} {got}"),
            (Some((want, _)), _) if want != name => {
                differ += 1;
                writeln!(out, "DIFFERS  {name}: scene out of order (the list expects {want} here)")
            }
            (None, _) => {
                differ += 1;
                writeln!(out, "DIFFERS  {name}: not in the list")
            }
            (Some((_, hash)), Ok(got)) => {
                differ += 1;
                writeln!(out, "DIFFERS  {name} {got} (expected {hash})")
            }
            (Some(_), Err(Failure(why))) => {
                differ += 1;
                writeln!(out, "FAILED   {name}: {why}")
            }
        };
        result = result.and(line);
        if let Some((read, unit)) = meter.as_mut() {
            let now = read();
            result = result.and(writeln!(out, "cost     {name} {} {unit}", now.wrapping_sub(last)));
            last = read();
        }
    });
    result?;
    for (name, _) in goldens.iter().skip(index) {
        differ += 1;
        writeln!(out, "MISSING  {name}")?;
    }
    writeln!(out, "scene memory {memory_bytes} bytes (static)")?;
    writeln!(out, "hibi-scenes on {target}: {} scenes, {differ} differ", goldens.len())?;
    Ok(differ)
}
