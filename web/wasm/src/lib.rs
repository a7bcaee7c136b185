//! hibi's WebAssembly module: raw `extern "C"` exports over hibi-core's public API for the
//! JavaScript package (web/hibi.js wraps them). No model logic lives here: parameters cross as
//! flat `f64` slots described by the core's own structs ([`slots`]), each model is a handle to
//! a boxed model and its owned buffers (hibi-core's `alloc` feature), and outputs are boxed
//! slices the glue copies out ([`out`]). Every fallible export returns 0 on success and 1 on
//! failure, the failure's message (the core's own text, naming the field) in the text buffer.
//!
//! Between calls the module's whole state lies in its linear memory (the statics, the
//! allocator's free lists and every model), and its one mutable global, the stack pointer, is
//! back at its start. So an instance of the same module whose memory is a copy of this one's
//! holds the same models at the same handles: hibi.js's `renderAsync` gives each worker such a
//! copy and has it draw one band of rows with the `*_render_tile` exports.
#![no_std]

extern crate alloc;

mod heap;
mod slots;

use alloc::boxed::Box;
use alloc::string::String;
use alloc::vec;
use alloc::vec::Vec;
use core::cell::UnsafeCell;
use core::fmt::Display;

use hibi_core::glass::{Glass, GlassParams, GlassRender, GlassStore};
use hibi_core::glass::{GlassProgress, ImpactCounts};
use hibi_core::mud::CrackStatistics;
use hibi_core::mud::{Mud, MudParams, MudProgress, MudRender, MudStore};
use hibi_core::polygon::Ring;
use hibi_core::raster::{Tile, scratch_len};
use hibi_core::skin::{SkinParams, SkinProgress, SkinRender, SkinStore};

use slots::{Slots, description};

#[global_allocator]
static HEAP: heap::Heap = heap::Heap::new();

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    core::arch::wasm32::unreachable()
}

/// Module state (one thread).
struct Global<T>(UnsafeCell<T>);
// SAFETY: a wasm32-unknown-unknown instance runs one thread.
unsafe impl<T> Sync for Global<T> {}
impl<T> Global<T> {
    #[allow(clippy::mut_from_ref, reason = "one thread, and no export holds it across another")]
    fn get(&self) -> &mut T {
        // SAFETY: see the impl of Sync.
        unsafe { &mut *self.0.get() }
    }
}

/// The text buffer: descriptions, preset names, error messages.
static TEXT: Global<String> = Global(UnsafeCell::new(String::new()));
/// The outputs of the last call that makes them: (address, bytes, how to drop).
static OUT: Global<Vec<Out>> = Global(UnsafeCell::new(Vec::new()));

struct Out {
    ptr: *mut u8,
    len: usize,
    bytes: usize,
    drop: unsafe fn(*mut u8, usize),
}

unsafe fn drop_slice<T>(ptr: *mut u8, len: usize) {
    // SAFETY: `ptr` and `len` came from `Box::<[T]>::into_raw` in `out`.
    drop(unsafe { Box::from_raw(core::ptr::slice_from_raw_parts_mut(ptr.cast::<T>(), len)) });
}

/// Adds `values` to the outputs.
fn out<T>(values: Vec<T>) {
    let len = values.len();
    let bytes = len * core::mem::size_of::<T>();
    let ptr = Box::into_raw(values.into_boxed_slice()).cast::<T>().cast::<u8>();
    OUT.get().push(Out { ptr, len, bytes, drop: drop_slice::<T> });
}

fn set_text(s: &str) {
    let t = TEXT.get();
    t.clear();
    t.push_str(s);
}

/// Sets the text to `e`'s message and returns 1.
fn fail(e: impl Display) -> u32 {
    use core::fmt::Write;
    let t = TEXT.get();
    t.clear();
    let _ = write!(t, "{e}");
    1
}

#[unsafe(no_mangle)]
pub extern "C" fn hibi_web_text_ptr() -> *const u8 {
    TEXT.get().as_ptr()
}

#[unsafe(no_mangle)]
pub extern "C" fn hibi_web_text_len() -> usize {
    TEXT.get().len()
}

/// How many outputs the last call made.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_web_out_count() -> usize {
    OUT.get().len()
}

#[unsafe(no_mangle)]
pub extern "C" fn hibi_web_out_ptr(i: usize) -> *const u8 {
    OUT.get().get(i).map_or(core::ptr::null(), |o| o.ptr)
}

/// Output `i`'s length in bytes.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_web_out_bytes(i: usize) -> usize {
    OUT.get().get(i).map_or(0, |o| o.bytes)
}

/// Frees every output.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_web_out_clear() {
    for o in OUT.get().drain(..) {
        // SAFETY: each output is dropped once, as the type it was made with.
        unsafe { (o.drop)(o.ptr, o.len) };
    }
}

/// `bytes` bytes aligned to 8 for the glue (parameter slots, names); 0 if memory ran out.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_web_alloc(bytes: usize) -> *mut u8 {
    match core::alloc::Layout::from_size_align(bytes.max(1), 8) {
        // SAFETY: the layout is not zero-sized.
        Ok(layout) => unsafe { alloc::alloc::alloc(layout) },
        Err(_) => core::ptr::null_mut(),
    }
}

/// Frees what [`hibi_web_alloc`] gave for `bytes`.
///
/// # Safety
/// `ptr` came from `hibi_web_alloc(bytes)` and is not used after.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_free(ptr: *mut u8, bytes: usize) {
    if let Ok(layout) = core::alloc::Layout::from_size_align(bytes.max(1), 8) {
        // SAFETY: the caller's contract.
        unsafe { alloc::alloc::dealloc(ptr, layout) };
    }
}

// --- Records: parameter structs, views, progress ------------------------------------------

const MUD_PARAMS: u32 = 0;
const GLASS_PARAMS: u32 = 1;
const SKIN_PARAMS: u32 = 2;
const MUD_VIEW: u32 = 3;
const GLASS_VIEW: u32 = 4;
const SKIN_VIEW: u32 = 5;
const MUD_PROGRESS: u32 = 6;
const GLASS_PROGRESS: u32 = 7;
const SKIN_PROGRESS: u32 = 8;
const MUD_STATISTICS: u32 = 9;
const IMPACT_COUNTS: u32 = 10;

/// Describes record `kind` into the text (see [`slots`]); returns its number of slots, 0 for
/// no such kind.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_web_describe(kind: u32) -> usize {
    let (text, count) = match kind {
        MUD_PARAMS => description(&MudParams::default()),
        GLASS_PARAMS => description(&GlassParams::default()),
        SKIN_PARAMS => description(&SkinParams::default()),
        MUD_VIEW => description(&MudRender::default()),
        GLASS_VIEW => description(&GlassRender::default()),
        SKIN_VIEW => description(&SkinRender::default()),
        MUD_PROGRESS => description(&MudProgress {
            shrink: 0.0,
            time: 0.0,
            broken_springs: 0,
            crack_density: 0.0,
            finished: false,
            work: 0,
        }),
        GLASS_PROGRESS => description(&GlassProgress {
            time: 0,
            cracks: 0,
            growing: 0,
            vertices: 0,
            finished: false,
            capacity_reached: false,
            work: 0,
        }),
        SKIN_PROGRESS => description(&SkinProgress {
            cells: 0,
            roots: 0,
            root_total: 0,
            finished: false,
            capacity_reached: false,
            work: 0,
        }),
        MUD_STATISTICS => description(&CrackStatistics::default()),
        IMPACT_COUNTS => description(&ImpactCounts { radial: 0, large: 0, rings: 0 }),
        _ => return 0,
    };
    set_text(&text);
    count
}

/// Writes the defaults of parameter or view record `kind` (0 to 5) at `to`; 1 for another kind.
///
/// # Safety
/// `to` holds the record's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_defaults(kind: u32, to: *mut f64) -> u32 {
    // SAFETY: the caller's contract.
    unsafe {
        match kind {
            MUD_PARAMS => put(&MudParams::default(), to),
            GLASS_PARAMS => put(&GlassParams::default(), to),
            SKIN_PARAMS => put(&SkinParams::default(), to),
            MUD_VIEW => put(&MudRender::default(), to),
            GLASS_VIEW => put(&GlassRender::default(), to),
            SKIN_VIEW => put(&SkinRender::default(), to),
            _ => return 1,
        }
    }
    0
}

/// Writes `value`'s slots at `to`.
///
/// # Safety
/// `to` holds the record's slot count of `f64`s.
unsafe fn put<T: Slots>(value: &T, to: *mut f64) {
    let mut v = Vec::new();
    value.put(&mut v);
    // SAFETY: the caller's contract.
    unsafe { core::ptr::copy_nonoverlapping(v.as_ptr(), to, v.len()) };
}

/// Reads a `T` from the slots at `from`, over `base`; false if a slot holds no valid value.
///
/// # Safety
/// `from` holds the record's slot count of `f64`s.
unsafe fn take<T: Slots>(mut base: T, from: *const f64) -> Result<T, u32> {
    let mut d = String::new();
    base.describe("", &mut d);
    let n: usize = d.lines().map(|l| if l.ends_with(" u64") { 2 } else { 1 }).sum();
    // SAFETY: the caller's contract.
    let mut slots = unsafe { core::slice::from_raw_parts(from, n) };
    if base.take(&mut slots) { Ok(base) } else { Err(fail("a parameter slot holds no valid value")) }
}

/// The name at `name`/`len` (UTF-8).
///
/// # Safety
/// `name` holds `len` bytes.
unsafe fn name<'a>(name: *const u8, len: usize) -> &'a str {
    // SAFETY: the caller's contract.
    core::str::from_utf8(unsafe { core::slice::from_raw_parts(name, len) }).unwrap_or("")
}

macro_rules! params_exports {
    ($presets:ident, $params:ident, $module:ident, $ty:ty, $unknown:literal) => {
        /// The model's preset names, one a line, into the text.
        #[unsafe(no_mangle)]
        pub extern "C" fn $presets() {
            set_text(&hibi_core::$module::PRESETS.join("\n"));
        }

        /// Writes the parameters of preset `name` (the defaults if `len` is 0) at `to`.
        ///
        /// # Safety
        /// `name` holds `len` bytes; `to` the parameters' slots.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $params(name_ptr: *const u8, len: usize, to: *mut f64) -> u32 {
            let params: $ty = if len == 0 {
                Default::default()
            } else {
                // SAFETY: the caller's contract.
                match hibi_core::$module::preset(unsafe { name(name_ptr, len) }) {
                    Some(p) => p,
                    None => return fail($unknown),
                }
            };
            // SAFETY: the caller's contract.
            unsafe { put(&params, to) };
            0
        }
    };
}

// The messages of HIBI_ERROR_{MUD,GLASS,SKIN}_UNKNOWN_PRESET.
params_exports!(hibi_web_mud_presets, hibi_web_mud_params, mud, MudParams, "mud: no preset has that name");
params_exports!(hibi_web_glass_presets, hibi_web_glass_params, glass, GlassParams, "glass: no preset has that name");
params_exports!(hibi_web_skin_presets, hibi_web_skin_params, skin, SkinParams, "skin: no preset has that name");

/// Layers asked of a render, as bits.
const MASK: u32 = 1;
const HEIGHT: u32 = 2;
const NORMAL: u32 = 4;
const TIME: u32 = 8;
const CELL: u32 = 16;
const PREVIEW: u32 = 32;
const HEIGHT16: u32 = 64;
const NORMAL_RGB8: u32 = 128;

/// The layer buffers of a `width × height` render, as asked by `bits`.
struct LayerBuffers {
    mask: Option<Vec<u8>>,
    height: Option<Vec<f32>>,
    normal: Option<Vec<[f32; 3]>>,
    time: Option<Vec<f32>>,
    cell: Option<Vec<u32>>,
    preview: Option<Vec<[u8; 4]>>,
    height16: Option<Vec<u16>>,
    normal_rgb8: Option<Vec<[u8; 3]>>,
    scratch: Vec<u32>,
}

impl LayerBuffers {
    fn new(width: u32, height: u32, bits: u32) -> Option<Self> {
        let n = (width as usize).checked_mul(height as usize)?;
        let scratch = scratch_len(width, height)?;
        let want = |bit: u32| bits & bit != 0;
        Some(LayerBuffers {
            mask: want(MASK).then(|| vec![0; n]),
            height: want(HEIGHT).then(|| vec![0.0; n]),
            normal: want(NORMAL).then(|| vec![[0.0; 3]; n]),
            time: want(TIME).then(|| vec![0.0; n]),
            cell: want(CELL).then(|| vec![0; n]),
            preview: want(PREVIEW).then(|| vec![[0; 4]; n]),
            height16: want(HEIGHT16).then(|| vec![0; n]),
            normal_rgb8: want(NORMAL_RGB8).then(|| vec![[0; 3]; n]),
            scratch: vec![0; scratch],
        })
    }

    fn layers(&mut self) -> hibi_core::raster::Layers<'_> {
        hibi_core::raster::Layers {
            mask: self.mask.as_deref_mut(),
            height: self.height.as_deref_mut(),
            normal: self.normal.as_deref_mut(),
            time: self.time.as_deref_mut(),
            cell: self.cell.as_deref_mut(),
            preview: self.preview.as_deref_mut(),
            height16: self.height16.as_deref_mut(),
            normal_rgb8: self.normal_rgb8.as_deref_mut(),
            scratch: Some(&mut self.scratch),
        }
    }

    /// The asked layers as outputs, in bit order.
    fn publish(self) {
        self.mask.map(out);
        self.height.map(out);
        self.normal.map(out);
        self.time.map(out);
        self.cell.map(out);
        self.preview.map(out);
        self.height16.map(out);
        self.normal_rgb8.map(out);
    }
}

/// A render's buffers, or the failure's status.
fn layer_buffers(width: u32, height: u32, bits: u32) -> Result<LayerBuffers, u32> {
    if bits & !(MASK | HEIGHT | NORMAL | TIME | CELL | PREVIEW | HEIGHT16 | NORMAL_RGB8) != 0 {
        return Err(fail("render: no such layer"));
    }
    LayerBuffers::new(width, height, bits).ok_or_else(|| fail(hibi_core::raster::RasterError::Size))
}

/// Reads a view (over `base`) from the slots at `view`, draws the layers `bits` of a
/// `size(view)` raster with `draw`, and publishes them as outputs; 0, or the failure's status.
///
/// # Safety
/// `view` holds the view's slots.
unsafe fn render_view<V: Slots, E: Display>(
    base: V,
    view: *const f64,
    bits: u32,
    size: impl FnOnce(&V) -> (u32, u32),
    draw: impl FnOnce(&V, hibi_core::raster::Layers<'_>) -> Result<(), E>,
) -> u32 {
    // SAFETY: the caller's contract.
    let view = match unsafe { take(base, view) } {
        Ok(v) => v,
        Err(s) => return s,
    };
    let (width, height) = size(&view);
    let mut buffers = match layer_buffers(width, height, bits) {
        Ok(b) => b,
        Err(s) => return s,
    };
    if let Err(e) = draw(&view, buffers.layers()) {
        return fail(e);
    }
    buffers.publish();
    0
}

/// Makes a handle of a model and the store its buffers live in.
fn handle<T>(value: T) -> usize {
    Box::into_raw(Box::new(value)) as usize
}

/// # Safety
/// `h` came from [`handle`] with the same `T` and is not freed.
unsafe fn borrow<'a, T>(h: usize) -> &'a mut T {
    // SAFETY: the caller's contract.
    unsafe { &mut *(h as *mut T) }
}

// --- Model A: mud --------------------------------------------------------------------------

struct MudHandle {
    /// Borrows `*store` (dropped first).
    mud: Mud<'static, f32>,
    store: *mut MudStore<f32>,
}

/// A mud run of the parameters at `params`; 0 on failure (the text says why).
///
/// # Safety
/// `params` holds the mud parameters' slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_new(params: *const f64) -> usize {
    // SAFETY: the caller's contract.
    let Ok(params) = (unsafe { take(MudParams::default(), params) }) else { return 0 };
    let memory = match params.memory() {
        Ok(m) => m,
        Err(e) => {
            fail(e);
            return 0;
        }
    };
    let store = Box::into_raw(Box::new(memory.allocate::<f32>()));
    // SAFETY: `store` lives until the handle is freed, after the model that borrows it.
    match Mud::new(&params, unsafe { &mut *store }.buffers()) {
        Ok(mud) => handle(MudHandle { mud, store }),
        Err(e) => {
            // SAFETY: nothing borrows the store any more.
            drop(unsafe { Box::from_raw(store) });
            fail(e);
            0
        }
    }
}

/// # Safety
/// `h` is a live mud handle; it is not used after.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_free(h: usize) {
    // SAFETY: the caller's contract.
    let handle = unsafe { Box::from_raw(h as *mut MudHandle) };
    let store = handle.store;
    drop(handle);
    // SAFETY: the model that borrowed it is gone.
    drop(unsafe { Box::from_raw(store) });
}

/// Runs at most `budget` units and writes the progress at `progress`.
///
/// # Safety
/// `h` is a live mud handle; `progress` holds the progress's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_step(h: usize, budget: f64, progress: *mut f64) -> u32 {
    // SAFETY: the caller's contract.
    let m = unsafe { borrow::<MudHandle>(h) };
    match m.mud.step(budget as u64) {
        // SAFETY: the caller's contract.
        Ok(p) => unsafe { put(&p, progress) },
        Err(e) => return fail(e),
    }
    0
}

/// # Safety
/// As [`hibi_web_mud_step`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_progress(h: usize, progress: *mut f64) {
    // SAFETY: the caller's contract.
    unsafe { put(&borrow::<MudHandle>(h).mud.progress(), progress) }
}

/// # Safety
/// `h` is a live mud handle; `to` holds the statistics' slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_statistics(h: usize, to: *mut f64) {
    // SAFETY: the caller's contract.
    unsafe { put(&borrow::<MudHandle>(h).mud.statistics(), to) }
}

/// The run's extent (lattice units) at `to` (2 slots).
///
/// # Safety
/// `h` is a live mud handle; `to` holds 2 slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_extent(h: usize, to: *mut f64) {
    // SAFETY: the caller's contract.
    let [w, e] = unsafe { borrow::<MudHandle>(h) }.mud.extent();
    // SAFETY: the caller's contract.
    unsafe { core::ptr::copy_nonoverlapping([f64::from(w), f64::from(e)].as_ptr(), to, 2) };
}

/// The default view `width` pixels wide (`MudRender::fit`) at `to`.
///
/// # Safety
/// `h` is a live mud handle; `to` holds the view's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_view(h: usize, width: u32, to: *mut f64) {
    // SAFETY: the caller's contract.
    let extent = unsafe { borrow::<MudHandle>(h) }.mud.extent();
    // SAFETY: the caller's contract.
    unsafe { put(&MudRender::fit(extent, width.max(1)), to) };
}

/// Renders the layers `bits` of the view at `view` into outputs (in bit order).
///
/// # Safety
/// `h` is a live mud handle; `view` holds the view's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_render(h: usize, view: *const f64, bits: u32) -> u32 {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let m = unsafe { borrow::<MudHandle>(h) };
    // SAFETY: the caller's contract.
    unsafe {
        render_view(MudRender::default(), view, bits, |v| (v.width, v.height), |v, layers| m.mud.render(v, layers))
    }
}

/// Renders the layers `bits` of tile (`x`, `y`, `width`, `height`) of the view at `view` into
/// outputs (in bit order), each pixel as the whole render has it.
///
/// # Safety
/// `h` is a live mud handle; `view` holds the view's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_render_tile(
    h: usize,
    view: *const f64,
    bits: u32,
    x: u32,
    y: u32,
    width: u32,
    height: u32,
) -> u32 {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let m = unsafe { borrow::<MudHandle>(h) };
    let tile = Tile { x, y, width, height };
    // SAFETY: the caller's contract.
    unsafe {
        render_view(
            MudRender::default(),
            view,
            bits,
            |_| (width, height),
            |v, layers| m.mud.render_tile(v, &tile, layers),
        )
    }
}

/// The traced segments as outputs: one `f32` array of 8 per segment (start x, y, end x, y,
/// width at each end, time at each end).
///
/// # Safety
/// `h` is a live mud handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_segments(h: usize) {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let m = unsafe { borrow::<MudHandle>(h) };
    let mut v = Vec::new();
    m.mud.for_each_segment(|s| v.extend([s.start, s.end, s.width, s.time].into_iter().flatten()));
    out(v);
}

/// The crack network as outputs: vertices (x, y as f32, degree, on_border as u32: 16 bytes
/// each), edges (from, to, first_point, point_count), points (x, y, width, time).
///
/// # Safety
/// `h` is a live mud handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_network(h: usize) -> u32 {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let m = unsafe { borrow::<MudHandle>(h) };
    let c = m.mud.network_counts();
    let mut vertices = vec![Default::default(); c.vertices];
    let mut edges = vec![Default::default(); c.edges];
    let mut points = vec![Default::default(); c.points];
    match m.mud.network(&mut vertices, &mut edges, &mut points) {
        Ok(_) => {
            out(vertices);
            out(edges);
            out(points);
            0
        }
        Err(e) => fail(e),
    }
}

/// The closed cells as outputs: rings (`hibi_ring`, 24 bytes each), points (x, y); returns
/// the number of cells that wrap around a periodic lattice's edges (or `u32::MAX` on failure).
///
/// # Safety
/// `h` is a live mud handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_mud_cells(h: usize) -> u32 {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let m = unsafe { borrow::<MudHandle>(h) };
    let c = m.mud.cell_counts();
    let mut rings = vec![Ring::default(); c.rings];
    let mut points = vec![[0.0f32; 2]; c.points];
    match m.mud.cells(&mut rings, &mut points) {
        Ok(c) => {
            out(rings);
            out(points);
            c.wrapping as u32
        }
        Err(e) => {
            fail(e);
            u32::MAX
        }
    }
}

// --- Model B: glass ------------------------------------------------------------------------

struct GlassHandle {
    /// Borrows `*store` (dropped first).
    glass: Glass<'static>,
    store: *mut GlassStore,
    /// Words the fragment walk needs.
    scratch: usize,
}

/// A plate of the parameters at `params`, hit at `impact`; 0 on failure.
///
/// # Safety
/// `params` holds the glass parameters' slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_glass_new(params: *const f64) -> usize {
    // SAFETY: the caller's contract.
    let Ok(params) = (unsafe { take(GlassParams::default(), params) }) else { return 0 };
    let memory = match params.memory() {
        Ok(m) => m,
        Err(e) => {
            fail(e);
            return 0;
        }
    };
    let store = Box::into_raw(Box::new(memory.allocate()));
    // SAFETY: `store` lives until the handle is freed, after the plate that borrows it.
    match Glass::new(&params, unsafe { &mut *store }.buffers()) {
        Ok(glass) => handle(GlassHandle { glass, store, scratch: memory.scratch }),
        Err(e) => {
            // SAFETY: nothing borrows the store any more.
            drop(unsafe { Box::from_raw(store) });
            fail(e);
            0
        }
    }
}

/// # Safety
/// `h` is a live glass handle; it is not used after.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_glass_free(h: usize) {
    // SAFETY: the caller's contract.
    let handle = unsafe { Box::from_raw(h as *mut GlassHandle) };
    let store = handle.store;
    drop(handle);
    // SAFETY: the plate that borrowed it is gone.
    drop(unsafe { Box::from_raw(store) });
}

/// # Safety
/// `h` is a live glass handle; `progress` holds the progress's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_glass_step(h: usize, budget: f64, progress: *mut f64) {
    // SAFETY: the caller's contract.
    let g = unsafe { borrow::<GlassHandle>(h) };
    // SAFETY: the caller's contract.
    unsafe { put(&g.glass.step(budget as u64), progress) };
}

/// # Safety
/// As [`hibi_web_glass_step`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_glass_progress(h: usize, progress: *mut f64) {
    // SAFETY: the caller's contract.
    unsafe { put(&borrow::<GlassHandle>(h).glass.progress(), progress) }
}

/// Another impact at (x, y): its crack counts at `counts`.
///
/// # Safety
/// `h` is a live glass handle; `counts` holds the impact counts' slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_glass_impact(h: usize, x: f32, y: f32, counts: *mut f64) -> u32 {
    // SAFETY: the caller's contract.
    let g = unsafe { borrow::<GlassHandle>(h) };
    match g.glass.impact([x, y]) {
        // SAFETY: the caller's contract.
        Ok(c) => unsafe { put(&c, counts) },
        Err(e) => return fail(e),
    }
    0
}

/// The default view of `width × height` pixels at `to`.
///
/// # Safety
/// `to` holds the view's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_glass_view(width: u32, height: u32, to: *mut f64) {
    // SAFETY: the caller's contract.
    unsafe { put(&GlassRender { width, height, ..GlassRender::default() }, to) };
}

/// Renders the layers `bits` of the view at `view` into outputs (in bit order).
///
/// # Safety
/// `h` is a live glass handle; `view` holds the view's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_glass_render(h: usize, view: *const f64, bits: u32) -> u32 {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let g = unsafe { borrow::<GlassHandle>(h) };
    // SAFETY: the caller's contract.
    unsafe {
        render_view(GlassRender::default(), view, bits, |v| (v.width, v.height), |v, layers| g.glass.render(v, layers))
    }
}

/// Renders the layers `bits` of tile (`x`, `y`, `width`, `height`) of the view at `view` into
/// outputs (in bit order), each pixel as the whole render has it.
///
/// # Safety
/// `h` is a live glass handle; `view` holds the view's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_glass_render_tile(
    h: usize,
    view: *const f64,
    bits: u32,
    x: u32,
    y: u32,
    width: u32,
    height: u32,
) -> u32 {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let g = unsafe { borrow::<GlassHandle>(h) };
    let tile = Tile { x, y, width, height };
    // SAFETY: the caller's contract.
    unsafe {
        render_view(
            GlassRender::default(),
            view,
            bits,
            |_| (width, height),
            |v, layers| g.glass.render_tile(v, &tile, layers),
        )
    }
}

/// The cracks as outputs: each crack's end (`u32`), each crack's point count (`u32`), and
/// every point (x, y, time as `f32`), crack after crack.
///
/// # Safety
/// `h` is a live glass handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_glass_cracks(h: usize) {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let g = unsafe { borrow::<GlassHandle>(h) };
    let n = g.glass.crack_count();
    let (mut ends, mut counts, mut points) = (Vec::with_capacity(n), Vec::with_capacity(n), Vec::new());
    for i in 0..n {
        ends.push(g.glass.crack(i).map_or(u32::MAX, |c| c.end as u32));
        let before = points.len();
        g.glass.for_each_point(i, |q| points.extend([q.at[0], q.at[1], q.time]));
        counts.push(((points.len() - before) / 3) as u32);
    }
    out(ends);
    out(counts);
    out(points);
}

/// The fragments as outputs: rings (`hibi_ring`, 24 bytes each), points (x, y).
///
/// # Safety
/// `h` is a live glass handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_glass_fragments(h: usize) -> u32 {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let g = unsafe { borrow::<GlassHandle>(h) };
    let mut scratch = vec![0u32; g.scratch];
    let (rings, points) = match g.glass.fragment_counts(&mut scratch) {
        Ok(c) => c,
        Err(e) => return fail(e),
    };
    let mut rings = vec![Ring::default(); rings];
    let mut points = vec![[0.0f32; 2]; points];
    match g.glass.fragments(&mut scratch, &mut rings, &mut points) {
        Ok(_) => {
            out(rings);
            out(points);
            0
        }
        Err(e) => fail(e),
    }
}

// --- Model C: skin -------------------------------------------------------------------------

struct SkinHandle {
    /// Borrows `*store` (dropped first).
    skin: hibi_core::skin::Skin<'static, f32>,
    store: *mut SkinStore,
}

/// A skin of the parameters at `params`; 0 on failure.
///
/// # Safety
/// `params` holds the skin parameters' slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_skin_new(params: *const f64) -> usize {
    // SAFETY: the caller's contract.
    let Ok(params) = (unsafe { take(SkinParams::default(), params) }) else { return 0 };
    let memory = match params.memory() {
        Ok(m) => m,
        Err(e) => {
            fail(e);
            return 0;
        }
    };
    let store = Box::into_raw(Box::new(memory.allocate()));
    // SAFETY: `store` lives until the handle is freed, after the skin that borrows it.
    match hibi_core::skin::Skin::new(&params, unsafe { &mut *store }.buffers()) {
        Ok(skin) => handle(SkinHandle { skin, store }),
        Err(e) => {
            // SAFETY: nothing borrows the store any more.
            drop(unsafe { Box::from_raw(store) });
            fail(e);
            0
        }
    }
}

/// # Safety
/// `h` is a live skin handle; it is not used after.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_skin_free(h: usize) {
    // SAFETY: the caller's contract.
    let handle = unsafe { Box::from_raw(h as *mut SkinHandle) };
    let store = handle.store;
    drop(handle);
    // SAFETY: the skin that borrowed it is gone.
    drop(unsafe { Box::from_raw(store) });
}

/// # Safety
/// `h` is a live skin handle; `progress` holds the progress's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_skin_step(h: usize, budget: f64, progress: *mut f64) {
    // SAFETY: the caller's contract.
    let s = unsafe { borrow::<SkinHandle>(h) };
    // SAFETY: the caller's contract.
    unsafe { put(&s.skin.step(budget as u64), progress) };
}

/// # Safety
/// As [`hibi_web_skin_step`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_skin_progress(h: usize, progress: *mut f64) {
    // SAFETY: the caller's contract.
    unsafe { put(&borrow::<SkinHandle>(h).skin.progress(), progress) }
}

/// Renders the layers `bits` with the view at `view` into outputs (in bit order); the
/// rasters are the skin's width × height.
///
/// # Safety
/// `h` is a live skin handle; `view` holds the view's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_skin_render(h: usize, view: *const f64, bits: u32) -> u32 {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let s = unsafe { borrow::<SkinHandle>(h) };
    let params = s.skin.params();
    let size = |_: &SkinRender| (params.width, params.height);
    // SAFETY: the caller's contract.
    unsafe { render_view(SkinRender::default(), view, bits, size, |v, layers| s.skin.render(v, layers)) }
}

/// Renders the layers `bits` of tile (`x`, `y`, `width`, `height`) of the surface with the
/// view at `view` into outputs (in bit order), each pixel as the whole render has it.
///
/// # Safety
/// `h` is a live skin handle; `view` holds the view's slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_skin_render_tile(
    h: usize,
    view: *const f64,
    bits: u32,
    x: u32,
    y: u32,
    width: u32,
    height: u32,
) -> u32 {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let s = unsafe { borrow::<SkinHandle>(h) };
    let tile = Tile { x, y, width, height };
    // SAFETY: the caller's contract.
    unsafe {
        render_view(
            SkinRender::default(),
            view,
            bits,
            |_| (width, height),
            |v, layers| s.skin.render_tile(v, &tile, layers),
        )
    }
}

/// The cells as outputs: per cell (level, parent, site, vertex_count) as `u32`, then every
/// outline vertex (x, y as `i64` fixed point), cell after cell. Returns the fixed point's
/// fractional bits.
///
/// # Safety
/// `h` is a live skin handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_skin_cells(h: usize) -> u32 {
    hibi_web_out_clear();
    // SAFETY: the caller's contract.
    let s = unsafe { borrow::<SkinHandle>(h) };
    let cells = s.skin.cells();
    let mut records = Vec::with_capacity(cells.len() * 4);
    let mut vertices: Vec<i64> = Vec::new();
    for c in cells {
        records.extend([c.level, c.parent, c.site, c.vertex_count]);
        vertices.extend(s.skin.outline(c).iter().flatten().copied());
    }
    out(records);
    out(vertices);
    s.skin.fixed_point_bits()
}

/// The skin's width and height in pixels at `to` (2 slots).
///
/// # Safety
/// `h` is a live skin handle; `to` holds 2 slots.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_web_skin_size(h: usize, to: *mut f64) {
    // SAFETY: the caller's contract.
    let p = unsafe { borrow::<SkinHandle>(h) }.skin.params();
    // SAFETY: the caller's contract.
    unsafe { core::ptr::copy_nonoverlapping([f64::from(p.width), f64::from(p.height)].as_ptr(), to, 2) };
}
