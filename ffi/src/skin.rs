//! `hibi_skin`: model C, skin from hierarchical Voronoi cells (Ishii et al.), from C.
//!
//! ```c
//! hibi_skin_params params = hibi_skin_params_default();
//! hibi_skin *skin = NULL;
//! if (hibi_skin_create(&params, &skin) != HIBI_OK) { ... }
//! hibi_skin_progress progress;
//! hibi_status status;
//! do { status = hibi_skin_step(skin, 100000, &progress); } while (status == HIBI_OK && !progress.finished);
//! hibi_skin_render_params render = hibi_skin_render_params_default();
//! hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_HEIGHT, pixels, params.width * params.height);
//! hibi_skin_destroy(skin);
//! ```
//!
//! The same sequence drives mud and glass but for the names (a skin renders at its params'
//! size). A preview: render `HIBI_SKIN_LAYER_NORMAL` too, then `hibi_skin_shade` the two maps;
//! each layer is its own render (in Rust, `Skin::render` draws several layers in one pass).
//!
//! `hibi_skin_step` builds the cell outlines one cell at a time, depth first (a level-0 cell,
//! then its descendants); rendering only reads them (it draws what is built so far). An object is one block:
//! the header, then the core's cell, vertex, site, clip-vertex, word, level-record,
//! chunk-box and wedge arrays.

use core::ffi::{c_char, c_void};
use core::mem::size_of;

use hibi_core::skin::{
    ClipVertex, LevelParams, MAX_LEVELS, MAX_PERTURBATION_DEPTH, MAX_SEGMENTS, NO_CELL, Profile, ShadeError,
    ShadeParams, Site, Skin, SkinBuffers, SkinCell, SkinError, SkinLayers, SkinMemory, SkinParams, SkinProgress,
    SkinRender, Wedge, preset, shade,
};

use crate::constants::param_status;
use crate::fields::{Field, convert};
use crate::guard::{Outcome, buffer, check_pointer, guard, input, object_ref, query, update, write_out};
use crate::object::{AnyBits, Arena, Object, Origin, lifecycle};
use crate::raster::{Pixels, render};
use crate::status::{
    HIBI_ERROR_BAD_ENUM, HIBI_ERROR_BUFFER_TOO_SMALL, HIBI_ERROR_SKIN_CAPACITY, HIBI_ERROR_SKIN_CELL_INDEX,
    HIBI_ERROR_SKIN_LEVEL, HIBI_ERROR_SKIN_RENDER_LAYER, HIBI_ERROR_SKIN_SHADE, HIBI_ERROR_SKIN_SHADE_AMBIENT,
    HIBI_ERROR_SKIN_SHADE_FURROW, HIBI_ERROR_SKIN_SHADE_RIDGE, HIBI_ERROR_SKIN_SHADE_SPECULAR, hibi_status,
};

/// Most hierarchy levels a skin can have (the length of `hibi_skin_params.level`).
pub const HIBI_SKIN_MAX_LEVELS: usize = 4;
/// Most cubic Bézier segments in one level's cross-section.
pub const HIBI_SKIN_MAX_SEGMENTS: u32 = 4;
/// Control points a profile holds: 3 · `HIBI_SKIN_MAX_SEGMENTS` + 1.
pub const HIBI_SKIN_PROFILE_POINTS: usize = 13;
/// Most midpoint-displacement subdivisions of an edge.
pub const HIBI_SKIN_MAX_PERTURBATION_DEPTH: u32 = 5;

/// `hibi_skin_cell.parent` of a level-0 cell, and the cell map's value where no cell is.
pub const HIBI_SKIN_NO_CELL: u32 = u32::MAX;

const _: () = {
    assert!(HIBI_SKIN_MAX_LEVELS == MAX_LEVELS);
    assert!(HIBI_SKIN_MAX_SEGMENTS as usize == MAX_SEGMENTS);
    assert!(HIBI_SKIN_PROFILE_POINTS == 3 * MAX_SEGMENTS + 1);
    assert!(HIBI_SKIN_MAX_PERTURBATION_DEPTH == MAX_PERTURBATION_DEPTH);
    assert!(HIBI_SKIN_NO_CELL == NO_CELL);
    // No padding: C code may compare or hash params structs byte by byte.
    assert!(size_of::<hibi_skin_level>() == 7 * 4 + size_of::<hibi_skin_profile>());
    assert!(size_of::<hibi_skin_params>() == 40 + HIBI_SKIN_MAX_LEVELS * size_of::<hibi_skin_level>());
};

/// Marks a params struct that came from `hibi_skin_params_default` or
/// `hibi_skin_params_preset` ("SKN1").
const PARAMS_COOKIE: u32 = 0x534B_4E31;

/// Parameter 5, a ridge's cross-section: cubic Bézier segments in the body plane (x' from the
/// centre point at 0 to the polygon's edge at the last point's x', z' the height). Segment k
/// has control points `points[3k]` to `points[3k + 3]`; consecutive segments share an end
/// point.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct hibi_skin_profile {
    /// Number of segments, 1..=`HIBI_SKIN_MAX_SEGMENTS`.
    pub segments: u32,
    /// Control points (x', z'); the first 3 · `segments` + 1 are used.
    pub points: [[f32; 2]; HIBI_SKIN_PROFILE_POINTS],
}

/// One hierarchy level: its polygons and its cross-section.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct hibi_skin_level {
    /// Lattice spacing of the centre points [px, before stretch] (default 40, then a third of
    /// it at each finer level).
    pub spacing: f32,
    /// Parameter 2, the perturbation ratio A in V = A·2^(−n·h)·Rnd·L (default 0: straight edges).
    pub perturbation: f32,
    /// h in V = A·2^(−n·h)·Rnd·L, the decay per subdivision (default 1).
    pub perturbation_decay: f32,
    /// Subdivisions of every edge, 0..=`HIBI_SKIN_MAX_PERTURBATION_DEPTH` (default 3).
    pub perturbation_depth: u32,
    /// Parameter 3, the stretch (Sx, Sy) of this level's polygons (default 1, 1).
    pub stretch: [f32; 2],
    /// Parameter 5, the cross-section (default the paper's Fig. 13 b).
    pub profile: hibi_skin_profile,
    /// Parameter 6, the roundness ratio in [0, 1]: 0 polygonal height contours, 1 nearly
    /// circular (default 0.2).
    pub roundness: f32,
}

/// The parameters of a skin surface, in pixels. Get them from `hibi_skin_params_default` or
/// `hibi_skin_params_preset`, then change fields; `hibi_skin_create` rejects a struct that
/// did not come from there.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct hibi_skin_params {
    /// Set by `hibi_skin_params_default` and `hibi_skin_params_preset`; leave it alone.
    pub cookie: u32,
    /// Parameter 1: `HIBI_SKIN_LAYOUT_TRIANGULAR` (default), `_SQUARE` or `_RANDOM`.
    pub layout: u32,
    /// Parameter 1: the jitter of lattice centres, `HIBI_SPREAD_UNIFORM` (default) or
    /// `HIBI_SPREAD_NORMAL`.
    pub jitter: u32,
    /// 1: the surface repeats with period (width, height), a tileable texture (each level
    /// then has a whole number of spacings, at least two, across each axis); 0: it does not
    /// (default).
    pub periodic: u32,
    /// Width of the surface and of its rasters [px], 1..=32768 (default 400).
    pub width: u32,
    /// Height [px] (default 400).
    pub height: u32,
    /// Seed of every random draw (default 1).
    pub seed: u64,
    /// Parameter 1: largest jitter per axis / lattice spacing, in [0, 1] (default 0.5).
    pub jitter_ratio: f32,
    /// Parameter 4: number of hierarchy levels, 1..=`HIBI_SKIN_MAX_LEVELS` (default 1).
    pub levels: u32,
    /// The levels, coarsest first; the first `levels` are used.
    pub level: [hibi_skin_level; HIBI_SKIN_MAX_LEVELS],
}

/// Light and palette for `hibi_skin_shade`. Defaults from `hibi_skin_shade_params_default`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct hibi_skin_shade_params {
    /// Direction towards the light (x right, y up, z out of the surface); need not be unit
    /// (default from the upper left).
    pub light: [f32; 3],
    /// Ridge-top colour, linear RGB in [0, 1].
    pub ridge: [f32; 3],
    /// Furrow colour, linear RGB in [0, 1].
    pub furrow: [f32; 3],
    /// Light that reaches every pixel, in [0, 1] (default 0.35).
    pub ambient: f32,
    /// Strength of the highlight (Blinn–Phong), >= 0 (default 0.12).
    pub specular: f32,
}

/// Where a build stands.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct hibi_skin_progress {
    /// Cells built, all levels.
    pub cells: u32,
    /// Level-0 centre points whose cells (with all their descendants) are built.
    pub roots: u32,
    /// Level-0 centre points in all.
    pub root_total: u32,
    /// 1 when every cell is built, else 0.
    pub finished: u32,
    /// 1 when a cell outgrew its capacity (the build then stopped; what was built is usable).
    pub capacity_reached: u32,
    /// Always 0: the struct has no padding, so every byte a call writes is defined (an
    /// output can be hashed or compared as bytes).
    pub reserved: u32,
    /// Work done since the build began (units of the step budget).
    pub work: u64,
}

/// One cell of the hierarchy.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct hibi_skin_cell {
    /// Hierarchy level, 0 for the coarsest.
    pub level: u32,
    /// Index of the parent cell; `HIBI_SKIN_NO_CELL` at level 0.
    pub parent: u32,
    /// The centre point's id, unique within the level.
    pub site: u32,
    /// Vertices in the outline (`hibi_skin_outline` writes twice as many doubles).
    pub vertex_count: u32,
    /// The centre point [px].
    pub centre: [f64; 2],
}

impl Outcome for hibi_skin_shade_params {
    type C = hibi_skin_shade_params;
    fn into_c(self) -> Self {
        self
    }
    /// No light, which shading rejects.
    fn on_panic() -> Self {
        hibi_skin_shade_params { light: [0.0; 3], ..hibi_skin_shade_params::from_core(&ShadeParams::default()) }
    }
}

/// A skin surface: every cell outline of every level. Opaque.
pub struct hibi_skin {
    skin: Skin<'static>,
    origin: Origin,
}

convert!(hibi_skin_profile <=> Profile { segments, points });
convert!(hibi_skin_level <=> LevelParams {
    spacing, perturbation, perturbation_decay, perturbation_depth, stretch, profile, roundness,
});
convert!(hibi_skin_params <=> SkinParams, cookie: PARAMS_COOKIE {
    layout, jitter, periodic, width, height, seed, jitter_ratio, levels, level,
});
convert!(hibi_skin_progress <=> SkinProgress, reserved: reserved { cells, roots, root_total, finished, capacity_reached, work });
convert!(hibi_skin_shade_params <=> ShadeParams { light, ridge, furrow, ambient, specular });

lifecycle!(
    hibi_skin (skin: "skin", "no cell built yet, `hibi_skin_step` builds them"),
    hibi_skin_params <=> SkinParams, cookie PARAMS_COOKIE,
    errors (HIBI_ERROR_SKIN_PARAMS_NOT_INITIALISED, HIBI_ERROR_SKIN_ENUM, HIBI_ERROR_SKIN_UNKNOWN_PRESET),
    presets "`\"fig13a\"` … `\"fig19f\"`" in hibi_core::skin::PRESETS,
    hibi_skin_params_default, hibi_skin_params_preset, hibi_skin_preset_name, hibi_skin_memory_size,
    hibi_skin_memory_align,
    hibi_skin_create, hibi_skin_create_in, hibi_skin_destroy,
);

// SAFETY: a cell is five u32 and two i64 (padding between them holds no value); a centre point
// f64, u32 and i32 fields; a clip vertex two f64 and a u32; a wedge four f32 (sizes checked
// below): every bit pattern of each is a value.
unsafe impl AnyBits for SkinCell {}
// SAFETY: as above.
unsafe impl AnyBits for Site {}
// SAFETY: as above.
unsafe impl AnyBits for ClipVertex {}
// SAFETY: as above.
unsafe impl AnyBits for Wedge {}
const _: () = assert!(
    size_of::<SkinCell>() == 40 && size_of::<Site>() == 48 && size_of::<ClipVertex>() == 24 && size_of::<Wedge>() == 16,
    "only integer and float fields"
);

impl Object for hibi_skin {
    type Input = *const hibi_skin_params;
    type Plan = (SkinParams, SkinMemory);
    type Arrays = SkinBuffers<'static>;
    const TOO_LARGE: hibi_status = crate::constants::HIBI_ERROR_SKIN_CAPACITY_PARAMS;

    unsafe fn plan(params: *const hibi_skin_params) -> Result<Self::Plan, hibi_status> {
        // SAFETY: the caller's contract.
        let params = from_c(unsafe { object_ref(params, c"params") }?)?;
        let memory = params.memory().map_err(param_status)?;
        Ok((params, memory))
    }

    /// The skin reads no cell, vertex, centre point, clip vertex, word, chunk box or wedge it
    /// did not write (`Skin::step` writes each before reading it), so those arrays, which grow
    /// with the surface, are taken as they are: creation writes only the per-level records
    /// (at most `HIBI_SKIN_MAX_LEVELS` of each), and its work does not grow with the surface.
    fn arrays((_, m): &Self::Plan, arena: &mut Arena) -> Self::Arrays {
        SkinBuffers {
            cells: arena.take_as_is(m.cells),
            vertices: arena.take_as_is(m.vertices),
            sites: arena.take_as_is(m.sites),
            clip: arena.take_as_is(m.clip),
            words: arena.take_as_is(m.words),
            levels: arena.take(m.levels),
            divisions: arena.take(m.divisions),
            shared_edges: arena.take(m.shared_edges),
            boxes: arena.take_as_is(m.boxes),
            wedges: arena.take_as_is(m.wedges),
        }
    }

    fn make((params, _): &Self::Plan, buffers: Self::Arrays, origin: Origin) -> Result<Self, hibi_status> {
        Ok(hibi_skin { skin: Skin::new(params, buffers).map_err(skin_status)?, origin })
    }

    fn origin(&self) -> Origin {
        self.origin
    }
}

/// The status of a core skin error.
fn skin_status(error: SkinError) -> hibi_status {
    match error {
        SkinError::Param(p) => param_status(p),
        SkinError::BufferTooSmall { .. } => HIBI_ERROR_BUFFER_TOO_SMALL,
        SkinError::Level => HIBI_ERROR_SKIN_LEVEL,
        SkinError::Shade(ShadeError::Light) => HIBI_ERROR_SKIN_SHADE,
        SkinError::Shade(ShadeError::Ridge) => HIBI_ERROR_SKIN_SHADE_RIDGE,
        SkinError::Shade(ShadeError::Furrow) => HIBI_ERROR_SKIN_SHADE_FURROW,
        SkinError::Shade(ShadeError::Ambient) => HIBI_ERROR_SKIN_SHADE_AMBIENT,
        SkinError::Shade(ShadeError::Specular) => HIBI_ERROR_SKIN_SHADE_SPECULAR,
        SkinError::Raster(e) => crate::raster::layers_status(e),
    }
}

/// Pixels per fixed-point unit of `skin`'s outlines.
fn pixels_per_unit(skin: &Skin) -> f64 {
    1.0 / (1u64 << skin.fixed_point_bits()) as f64
}

/// How to draw a skin's maps: which level the cell layer shows. Defaults from
/// `hibi_skin_render_params_default`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct hibi_skin_render_params {
    /// The level `HIBI_SKIN_LAYER_CELLS` shows (below `levels`; default 0, the coarsest).
    pub cell_level: u32,
    /// Light and palette of the preview layer (default `hibi_skin_shade_params_default()`).
    pub shade: hibi_skin_shade_params,
}

impl crate::guard::Outcome for hibi_skin_render_params {
    type C = hibi_skin_render_params;
    fn into_c(self) -> Self {
        self
    }
    /// A level past every skin's (the cell layer rejects it; the others do not read it).
    fn on_panic() -> Self {
        hibi_skin_render_params {
            cell_level: u32::MAX,
            shade: hibi_skin_shade_params::from_core(&ShadeParams::default()),
        }
    }
}

convert!(hibi_skin_render_params <=> SkinRender { cell_level, shade });

/// The default render params (the cell layer shows level 0).
#[unsafe(no_mangle)]
pub extern "C" fn hibi_skin_render_params_default() -> hibi_skin_render_params {
    guard(|| hibi_skin_render_params::from_core(&SkinRender::default()))
}

/// `hibi_skin_render` layer: height, one `float` per pixel, the sum over levels of the
/// profile heights.
pub const HIBI_SKIN_LAYER_HEIGHT: u32 = 0;
/// `hibi_skin_render` layer: normal, three `float`s per pixel, a unit tangent-space normal
/// with x right, y up, z out, as in OpenGL normal maps.
pub const HIBI_SKIN_LAYER_NORMAL: u32 = 1;
/// `hibi_skin_render` layer: cells, one `uint32_t` per pixel, the index of its cell at
/// `cell_level` (`HIBI_SKIN_NO_CELL` where none is).
pub const HIBI_SKIN_LAYER_CELLS: u32 = 2;

render! {
    /// Draws `layer` into `pixels` (row-major over the params' `width × height`; `float` for
    /// `HIBI_SKIN_LAYER_HEIGHT`, three `float`s per pixel for `HIBI_SKIN_LAYER_NORMAL`,
    /// `uint32_t` for `HIBI_SKIN_LAYER_CELLS`). `pixels_len` counts values (floats for the
    /// normal layer), not bytes. The skin is only read: several threads may render one skin at
    /// once. Nothing is written on failure.
    hibi_skin_render(skin: hibi_skin, "skin", hibi_skin_render_params) = skin_layers, skin_status
}

crate::raster::render_layers! {
    /// Draws every layer `layers` gives (mask, height, height16, normal, normal_rgb8, cell,
    /// preview; see `hibi_layers`) of `tile` (NULL: the whole surface, the params' `width ×
    /// height`) in one pass, each pixel bit for bit as the whole surface has it. The skin is
    /// only read: several threads may render one skin at once. Nothing is written on failure;
    /// `hibi_error_argument()` names a refused layer (`"layers.time"`, ...) or `"tile"`.
    hibi_skin_render_layers(skin: hibi_skin, "skin", hibi_skin_render_params) =
        |s: &hibi_skin, _| hibi_core::raster::Tile::whole(s.skin.params().width, s.skin.params().height), skin_status
}

/// Skin's layers with `layer` to be drawn into `pixels`.
fn skin_layers(layer: u32, pixels: Pixels<'_>) -> Result<SkinLayers<'_>, hibi_status> {
    // SAFETY (every arm): the layer's type, as the header gives it for that layer.
    Ok(match layer {
        HIBI_SKIN_LAYER_HEIGHT => SkinLayers { height: Some(unsafe { pixels.values() }?), ..SkinLayers::default() },
        HIBI_SKIN_LAYER_NORMAL => {
            // Whole pixels of three floats (a trailing partial one is not used).
            let (normal, _) = unsafe { pixels.values::<f32>() }?.as_chunks_mut::<3>();
            SkinLayers { normal: Some(normal), ..SkinLayers::default() }
        }
        HIBI_SKIN_LAYER_CELLS => SkinLayers { cell: Some(unsafe { pixels.values() }?), ..SkinLayers::default() },
        _ => return Err(HIBI_ERROR_SKIN_RENDER_LAYER),
    })
}

/// Advances the build by about `budget` units of work: outline vertices written, one per
/// level-0 centre point tried, and, as a cell is divided into the next level's, one per centre
/// point tried in its bounding box and (for more than 96 children) one per piece of bucketing
/// its children (at most 256 children or buckets each). The work is done in pieces (a cell, a
/// centre point tried, a piece of bucketing) and the budget is checked between them, so a call
/// does at least one piece and overruns the budget by less than one (at most 2 049 units: a
/// cell, an outline's most vertices and one; the other pieces are one unit each). A unit
/// stands for about the same work at any parameters: a cell's neighbours are found among those
/// near it, not sorted from all of its parent's children, so its time follows its own outline,
/// not the number of its siblings, and a division's follows the centre points it tries.
/// The cells do not depend on the budgets. Writes where it stands to `*progress` unless it is
/// NULL. Returns `HIBI_ERROR_SKIN_CAPACITY` (and writes nothing) once a cell outgrew its
/// capacity; what was built stays usable.
///
/// # Safety
/// `skin` must be NULL or a live skin; `progress` optional: NULL (not written) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_skin_step(
    skin: *mut hibi_skin,
    budget: u64,
    progress: *mut hibi_skin_progress,
) -> hibi_status {
    let step = |skin: &mut hibi_skin| match skin.skin.step(budget) {
        p if p.capacity_reached => Err(HIBI_ERROR_SKIN_CAPACITY),
        p => Ok(hibi_skin_progress::from_core(&p)),
    };
    // SAFETY: the caller's contract.
    guard(|| unsafe { update(skin, c"skin", (progress, c"progress"), step) })
}

/// The default light (from the upper left) and palette (a light skin tone).
#[unsafe(no_mangle)]
pub extern "C" fn hibi_skin_shade_params_default() -> hibi_skin_shade_params {
    guard(|| hibi_skin_shade_params::from_core(&ShadeParams::default()))
}

/// A shaded preview: lights `normal` (three floats per pixel, as `hibi_skin_render` writes
/// it; `normal_len` counts floats) and darkens towards the furrows by `height` (one float
/// per pixel) into 8-bit sRGB in `rgb` (three bytes per pixel; `rgb_len` counts bytes).
/// The pixels are `height_len`; `normal` and `rgb` must hold as many (`normal_len` and
/// `rgb_len` at least 3 · `height_len`); if not, or if a parameter is out of range (a light
/// component not finite, or all three zero; a colour channel or `ambient` outside [0, 1];
/// `specular` negative), nothing is written. Any other light is a direction, however large
/// or small its components.
///
/// # Safety
/// `height`, `normal` NULL (only with length 0) or readable for their lengths; `params` NULL
/// or readable; `rgb` NULL (only with length 0) or writable for `rgb_len` bytes, overlapping
/// neither input.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_skin_shade(
    height: *const f32,
    height_len: usize,
    normal: *const f32,
    normal_len: usize,
    params: *const hibi_skin_shade_params,
    rgb: *mut u8,
    rgb_len: usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let params: ShadeParams = unsafe { object_ref(params, c"params") }?
            .to_core()
            .ok_or_else(|| crate::status::refuse_argument(c"params", HIBI_ERROR_BAD_ENUM))?;
        // NULL with a length (even one too short for a whole pixel) is refused, as for every
        // buffer (fuzzing found `rgb_len` 1 or 2 with NULL accepted).
        if normal_len > 0 {
            check_pointer(normal, c"normal")?;
        }
        if rgb_len > 0 {
            check_pointer(rgb.cast_const(), c"rgb")?;
        }
        // SAFETY (all three): the caller's contract; `[f32; 3]` has the alignment of `f32`.
        let (height, normal, rgb) = unsafe {
            (
                input(height, height_len, c"height")?,
                input(normal.cast::<[f32; 3]>(), normal_len / 3, c"normal")?,
                buffer(rgb.cast::<[u8; 3]>(), rgb_len / 3, c"rgb")?,
            )
        };
        let pixels = height.len();
        let lengths = (normal.len(), rgb.len());
        shade(height, normal, &params, rgb).map_err(|e| match e {
            SkinError::BufferTooSmall { .. } => {
                crate::status::first_short(&[(c"normal", lengths.0, pixels), (c"rgb", lengths.1, pixels)])
            }
            e => skin_status(e),
        })
    })
}

/// Writes the number of cells over all levels.
///
/// # Safety
/// `skin` must be NULL or a live skin; `count` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_skin_cell_count(skin: *const hibi_skin, count: *mut usize) -> hibi_status {
    let read = |skin: &hibi_skin| Ok(skin.skin.cells().len());
    // SAFETY: the caller's contract.
    guard(|| unsafe { query(skin, c"skin", (count, c"count"), read) })
}

/// Describes cell `index` (below `hibi_skin_cell_count`). Cells come depth first, in the
/// order they are built: each level-0 cell, then its descendants (a parent before its
/// children, and a cell's descendants before its next sibling).
///
/// # Safety
/// `skin` must be NULL or a live skin; `cell` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_skin_cell_info(
    skin: *const hibi_skin,
    index: usize,
    cell: *mut hibi_skin_cell,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let skin = unsafe { object_ref(skin, c"skin") }?;
        check_pointer(cell, c"cell")?;
        let c = skin.skin.cells().get(index).ok_or(HIBI_ERROR_SKIN_CELL_INDEX)?;
        let unit = pixels_per_unit(&skin.skin);
        let value = hibi_skin_cell {
            level: c.level,
            parent: c.parent,
            site: c.site,
            vertex_count: c.vertex_count,
            centre: [c.centre[0] as f64 * unit, c.centre[1] as f64 * unit],
        };
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(cell, c"cell", value) }
    })
}

/// Writes cell `index`'s outline into `xy[0..len]` as x, y pairs in the raster's pixels (x
/// right, y down the rows, pixel (i, j) covering [i, i + 1] × [j, j + 1]), in the order that
/// gives a positive signed area (counter-clockwise were y up), and the number of doubles
/// written (2 · `vertex_count`) into `*written`. On a periodic surface an outline may reach
/// past the edges; wrap it modulo (width, height). If `len` is too small, nothing is written
/// and the status is `HIBI_ERROR_BUFFER_TOO_SMALL`.
///
/// # Safety
/// `skin` must be NULL or a live skin; `xy` NULL (only with `len` 0) or writable for `len`
/// doubles; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_skin_outline(
    skin: *const hibi_skin,
    index: usize,
    xy: *mut f64,
    len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let skin = unsafe { object_ref(skin, c"skin") }?;
        check_pointer(written, c"written")?;
        let cell = skin.skin.cells().get(index).ok_or(HIBI_ERROR_SKIN_CELL_INDEX)?;
        // SAFETY: the caller's contract.
        let out = unsafe { buffer(xy, len, c"xy") }?;
        let outline = skin.skin.outline(cell);
        let needed = 2 * outline.len();
        if out.len() < needed {
            return Err(crate::status::refuse_argument(c"xy", HIBI_ERROR_BUFFER_TOO_SMALL));
        }
        let unit = pixels_per_unit(&skin.skin);
        for (pair, v) in out.chunks_exact_mut(2).zip(outline) {
            pair[0] = v[0] as f64 * unit;
            pair[1] = v[1] as f64 * unit;
        }
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(written, c"written", needed) }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::*;
    use crate::status::*;
    use core::ptr::{null, null_mut};

    /// A small two-level skin.
    fn small() -> hibi_skin_params {
        let mut p = hibi_skin_params_default();
        (p.width, p.height, p.levels) = (64, 48, 2);
        p
    }

    #[test]
    fn bad_fields_and_enums_are_specific_statuses_and_nothing_is_created() {
        type Spoil = fn(&mut hibi_skin_params);
        let cases: [(Spoil, hibi_status); 16] = [
            (|p| p.cookie = 0, HIBI_ERROR_SKIN_PARAMS_NOT_INITIALISED),
            (|p| p.layout = 3, HIBI_ERROR_SKIN_ENUM),
            (|p| p.jitter = 2, HIBI_ERROR_SKIN_ENUM),
            (|p| p.periodic = 2, HIBI_ERROR_SKIN_ENUM),
            (|p| p.width = 0, HIBI_ERROR_SKIN_SIZE),
            (|p| p.height = 40_000, HIBI_ERROR_SKIN_SIZE),
            (|p| p.jitter_ratio = f32::NAN, HIBI_ERROR_SKIN_JITTER_RATIO),
            (|p| p.levels = 5, HIBI_ERROR_SKIN_LEVELS),
            (|p| p.level[1].spacing = 0.5, HIBI_ERROR_SKIN_SPACING),
            (|p| p.level[0].perturbation_decay = -1.0, HIBI_ERROR_SKIN_PERTURBATION),
            (|p| p.level[0].perturbation_depth = 6, HIBI_ERROR_SKIN_PERTURBATION_DEPTH),
            (|p| p.level[1].stretch[0] = 0.0, HIBI_ERROR_SKIN_STRETCH),
            (|p| p.level[0].profile.segments = 0, HIBI_ERROR_SKIN_PROFILE_SEGMENTS),
            (|p| p.level[0].profile.points[1][0] = f32::INFINITY, HIBI_ERROR_SKIN_PROFILE_POINTS),
            (|p| p.level[1].roundness = 1.5, HIBI_ERROR_SKIN_ROUNDNESS),
            (|p| (p.width, p.height, p.levels) = (32_768, 32_768, 4), HIBI_ERROR_SKIN_CAPACITY_PARAMS),
        ];
        for (k, (spoil, expected)) in cases.into_iter().enumerate() {
            let mut p = small();
            spoil(&mut p);
            let mut out = null_mut();
            let mut size = 99usize;
            // SAFETY: valid pointers; failing calls write nothing.
            unsafe {
                assert_eq!(hibi_skin_create(&p, &mut out), expected, "case {k}");
                assert_eq!(hibi_skin_memory_size(&p, &mut size), expected, "case {k}");
            }
            assert!(out.is_null() && size == 99, "case {k}");
            let message = message(expected).to_str().unwrap();
            assert!(message.starts_with("skin: "), "{message}");
        }
    }

    #[test]
    fn a_build_that_outgrows_a_capacity_stops_and_says_so() {
        let mut p = small();
        // A parent holding more centre points than the core can sort.
        (p.width, p.height, p.level[0].spacing, p.level[1].spacing) = (128, 128, 128.0, 1.5);
        (p.level[0].perturbation_depth, p.level[1].perturbation_depth) = (0, 0);
        let mut skin = null_mut();
        let mut progress = hibi_skin_progress { cells: 77, ..Default::default() };
        // SAFETY: valid pointers; a failing step writes nothing.
        unsafe {
            assert_eq!(hibi_skin_create(&p, &mut skin), HIBI_OK);
            assert_eq!(hibi_skin_step(skin, u64::MAX, &mut progress), HIBI_ERROR_SKIN_CAPACITY);
            assert_eq!(progress.cells, 77);
            let mut count = 0;
            assert_eq!(hibi_skin_cell_count(skin, &mut count), HIBI_OK);
            hibi_skin_destroy(skin);
        }
    }

    #[test]
    fn steps_of_any_budget_build_the_same_cells() {
        let p = small();
        let outlines = |budget: u64| {
            let mut skin = null_mut();
            let mut progress = hibi_skin_progress::default();
            let (mut steps, mut setup_steps, mut setup_work) = (0, 0, 0);
            // SAFETY: valid pointers throughout.
            unsafe {
                assert_eq!(hibi_skin_create(&p, &mut skin), HIBI_OK);
                while progress.finished == 0 {
                    let setting_up = (*skin).skin.is_setting_up();
                    let before = progress.work;
                    assert_eq!(hibi_skin_step(skin, budget, &mut progress), HIBI_OK);
                    steps += 1;
                    if setting_up {
                        setup_steps += 1;
                        setup_work += progress.work - before;
                    }
                }
                let skin = &*skin;
                let cells: Vec<_> = skin.skin.cells().iter().map(|c| (c.level, c.parent, c.vertex_count)).collect();
                let vertices = skin.skin.vertices().to_vec();
                hibi_skin_destroy(skin as *const hibi_skin as *mut hibi_skin);
                (cells, vertices, steps, progress, (setup_steps, setup_work))
            }
        };
        let (cells, vertices, one_go, done, _) = outlines(u64::MAX);
        let (cells_1, vertices_1, many, done_1, (setup_steps, setup_work)) = outlines(1);
        assert_eq!(one_go, 1);
        // A budget-1 step does one piece of the setup (a sample of the profile tables, or a
        // table's completion), builds one cell, or does one unit that builds none (a level-0
        // centre point whose cell misses the surface, or a unit of a division).
        assert!(setup_steps > 256 && setup_work > setup_steps, "{setup_steps} setup steps, {setup_work} units");
        let level0 = cells.iter().filter(|c| c.0 == 0).count() as u64;
        assert!(level0 < u64::from(done.cells), "two levels");
        let due = setup_steps + u64::from(done.cells) - level0 + done.work - setup_work - vertices.len() as u64;
        assert_eq!(many as u64, due, "{many} steps of one piece each");
        assert!(cells == cells_1 && vertices == vertices_1);
        assert_eq!((done.cells, done.roots, done.work), (done_1.cells, done_1.roots, done_1.work));
    }

    #[test]
    fn every_skin_status_has_its_own_message() {
        let codes: Vec<hibi_status> = (1280..=1290).chain(1343..=1354).collect();
        // SAFETY: hibi_status_string returns static NUL-terminated strings.
        let text = |code| unsafe { core::ffi::CStr::from_ptr(hibi_status_string(code)) }.to_str().unwrap();
        for (i, a) in codes.iter().enumerate() {
            assert!(text(*a).starts_with("skin: "), "{a}: {}", text(*a));
            for b in &codes[i + 1..] {
                assert_ne!(text(*a), text(*b));
            }
        }
        assert_eq!(text(1291), "unknown status code");
        assert_eq!(text(1355), "unknown status code");
    }

    #[test]
    fn caller_memory_is_checked_and_left_untouched_on_failure() {
        let p = small();
        let mut size = 0;
        // SAFETY: valid pointers.
        assert_eq!(unsafe { hibi_skin_memory_size(&p, &mut size) }, HIBI_OK);
        assert_eq!(hibi_skin_memory_align() % 8, 0);
        let mut memory = vec![0xA5A5_A5A5_A5A5_A5A5u64; size / 8 + 2];
        let base = memory.as_mut_ptr().cast::<c_void>();
        let untouched = |m: &[u64]| m.iter().all(|&w| w == 0xA5A5_A5A5_A5A5_A5A5);
        let mut out = null_mut();
        // SAFETY: `memory` is valid for its length; failing calls write nothing.
        unsafe {
            assert_eq!(hibi_skin_create_in(&p, base, size - 1, &mut out), HIBI_ERROR_BUFFER_TOO_SMALL);
            assert!(untouched(&memory), "short");
            let odd = base.cast::<u8>().add(4).cast::<c_void>();
            assert_eq!(hibi_skin_create_in(&p, odd, size, &mut out), HIBI_ERROR_MISALIGNED);
            assert!(untouched(&memory), "misaligned");
            assert_eq!(hibi_skin_create_in(&p, null_mut(), size, &mut out), HIBI_ERROR_NULL_POINTER);
            assert_eq!(hibi_skin_create_in(&p, base, size, null_mut()), HIBI_ERROR_NULL_POINTER);
            assert!(untouched(&memory) && out.is_null());
            assert_eq!(hibi_skin_create_in(&p, base, size, &mut out), HIBI_OK);
            assert_eq!(out.cast::<c_void>(), base);
            assert_eq!(hibi_skin_step(out, u64::MAX, null_mut()), HIBI_OK);
            let mut count = 0;
            assert_eq!(hibi_skin_cell_count(out, &mut count), HIBI_OK);
            assert!(count > 2);
            hibi_skin_destroy(out);
            hibi_skin_destroy(null_mut());
        }
    }

    #[test]
    fn render_draws_one_layer_and_leaves_a_refused_one_untouched() {
        let p = small();
        let pixels = (p.width * p.height) as usize;
        let mut skin = null_mut();
        // SAFETY: valid pointers throughout; failing calls write nothing.
        unsafe {
            assert_eq!(hibi_skin_create(&p, &mut skin), HIBI_OK);
            assert_eq!(hibi_skin_step(skin, u64::MAX, null_mut()), HIBI_OK);
            let mut height = vec![7.0f32; pixels];
            let mut normal = vec![7.0f32; 3 * pixels];
            let mut cells = vec![7u32; pixels];
            let (h, n, c) = (height.as_mut_ptr(), normal.as_mut_ptr(), cells.as_mut_ptr());
            let (hv, nv, cv) = (h.cast::<c_void>(), n.cast::<c_void>(), c.cast::<c_void>());
            let untouched = |h: &[f32], n: &[f32], c: &[u32]| {
                h.iter().all(|&v| v == 7.0) && n.iter().all(|&v| v == 7.0) && c.iter().all(|&v| v == 7)
            };
            let mut render = hibi_skin_render_params_default();
            assert_eq!(render.cell_level, 0);
            let refused = [
                (HIBI_SKIN_LAYER_HEIGHT, hv, pixels - 1, HIBI_ERROR_BUFFER_TOO_SMALL, ""),
                (HIBI_SKIN_LAYER_NORMAL, nv, 3 * pixels - 1, HIBI_ERROR_BUFFER_TOO_SMALL, ""),
                (HIBI_SKIN_LAYER_CELLS, cv, pixels - 1, HIBI_ERROR_BUFFER_TOO_SMALL, ""),
                (HIBI_SKIN_LAYER_HEIGHT, null_mut(), pixels, HIBI_ERROR_NULL_POINTER, "pixels"),
                (HIBI_SKIN_LAYER_NORMAL, n.cast::<u8>().add(1).cast(), 3 * pixels - 3, HIBI_ERROR_MISALIGNED, "pixels"),
                (3, hv, pixels, HIBI_ERROR_SKIN_RENDER_LAYER, ""),
            ];
            for (layer, ptr, len, status, argument) in refused {
                assert_eq!(hibi_skin_render(skin, &render, layer, ptr, len), status, "layer {layer}, length {len}");
                if !argument.is_empty() {
                    let named = core::ffi::CStr::from_ptr(crate::status::hibi_error_argument());
                    assert_eq!(named.to_str(), Ok(argument));
                }
            }
            assert_eq!(
                hibi_skin_render(null_mut(), &render, HIBI_SKIN_LAYER_HEIGHT, hv, pixels),
                HIBI_ERROR_NULL_POINTER
            );
            assert_eq!(hibi_skin_render(skin, null_mut(), HIBI_SKIN_LAYER_HEIGHT, hv, pixels), HIBI_ERROR_NULL_POINTER);
            render.cell_level = 2;
            assert_eq!(hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_CELLS, cv, pixels), HIBI_ERROR_SKIN_LEVEL);
            assert!(untouched(&height, &normal, &cells));

            // The cell level matters only to the cell layer.
            render.cell_level = 1;
            assert_eq!(hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_CELLS, cv, pixels), HIBI_OK);
            assert!(untouched(&height, &normal, &[]));
            let mut count = 0;
            assert_eq!(hibi_skin_cell_count(skin, &mut count), HIBI_OK);
            let mut info = hibi_skin_cell::default();
            for &index in &cells {
                assert_eq!(hibi_skin_cell_info(skin, index as usize, &mut info), HIBI_OK);
                assert_eq!(info.level, 1);
            }
            render.cell_level = 9;
            assert_eq!(hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_HEIGHT, hv, pixels), HIBI_OK);
            assert_eq!(hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_NORMAL, nv, 3 * pixels), HIBI_OK);
            assert!(height.iter().all(|&v| v >= 0.0) && height.iter().any(|&v| v > 2.0));
            assert!(normal.chunks(3).all(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - 1.0).abs() < 1e-4));

            let light = hibi_skin_shade_params_default();
            let mut rgb = vec![1u8; 3 * pixels];
            let (hc, nc) = (height.as_ptr(), normal.as_ptr());
            let r = rgb.as_mut_ptr();
            // A normal buffer one value short of the heights' pixels is refused (not shaded one
            // pixel fewer with OK).
            assert_eq!(
                hibi_skin_shade(hc, pixels, nc, 3 * pixels - 1, &light, r, 3 * pixels),
                HIBI_ERROR_BUFFER_TOO_SMALL
            );
            assert_eq!(hibi_skin_shade(hc, 2, nc, 5, &light, r, 6), HIBI_ERROR_BUFFER_TOO_SMALL);
            assert_eq!(
                hibi_skin_shade(hc, pixels, nc, 3 * pixels, &light, r, 3 * pixels - 1),
                HIBI_ERROR_BUFFER_TOO_SMALL
            );
            let refused = [
                (hibi_skin_shade_params { light: [0.0, 0.0, f32::NAN], ..light }, HIBI_ERROR_SKIN_SHADE),
                (hibi_skin_shade_params { ridge: [0.5, 1.5, 0.5], ..light }, HIBI_ERROR_SKIN_SHADE_RIDGE),
                (hibi_skin_shade_params { furrow: [f32::NAN, 0.5, 0.5], ..light }, HIBI_ERROR_SKIN_SHADE_FURROW),
                (hibi_skin_shade_params { ambient: -0.1, ..light }, HIBI_ERROR_SKIN_SHADE_AMBIENT),
                (hibi_skin_shade_params { specular: f32::INFINITY, ..light }, HIBI_ERROR_SKIN_SHADE_SPECULAR),
            ];
            for (bad, status) in refused {
                assert_eq!(hibi_skin_shade(hc, pixels, nc, 3 * pixels, &bad, r, 3 * pixels), status);
            }
            assert_eq!(hibi_skin_shade(hc, pixels, nc, 3 * pixels, null(), r, 3 * pixels), HIBI_ERROR_NULL_POINTER);
            assert_eq!(hibi_skin_shade(null(), pixels, nc, 3 * pixels, &light, r, 3 * pixels), HIBI_ERROR_NULL_POINTER);
            assert!(rgb.iter().all(|&v| v == 1));
            assert_eq!(hibi_skin_shade(hc, pixels, nc, 3 * pixels, &light, r, 3 * pixels), HIBI_OK);
            assert!(rgb.iter().any(|&v| v != 1));
            hibi_skin_destroy(skin);
        }
    }

    #[test]
    fn cells_and_outlines_come_in_pixels_and_tile_each_level() {
        let p = small();
        let mut skin = null_mut();
        // SAFETY: valid pointers throughout; failing calls write nothing.
        unsafe {
            assert_eq!(hibi_skin_create(&p, &mut skin), HIBI_OK);
            assert_eq!(hibi_skin_step(skin, u64::MAX, null_mut()), HIBI_OK);
            let mut count = 0;
            assert_eq!(hibi_skin_cell_count(skin, &mut count), HIBI_OK);
            let mut info = hibi_skin_cell { level: 9, ..Default::default() };
            assert_eq!(hibi_skin_cell_info(skin, count, &mut info), HIBI_ERROR_SKIN_CELL_INDEX);
            assert_eq!(hibi_skin_cell_info(skin, 0, null_mut()), HIBI_ERROR_NULL_POINTER);
            assert_eq!(info.level, 9);
            let mut area = [0.0f64; 2];
            let mut xy = Vec::new();
            for index in 0..count {
                assert_eq!(hibi_skin_cell_info(skin, index, &mut info), HIBI_OK);
                assert_eq!(info.parent == HIBI_SKIN_NO_CELL, info.level == 0);
                let n = 2 * info.vertex_count as usize;
                xy.clear();
                xy.resize(n, -1.0);
                let mut written = 5;
                let short = hibi_skin_outline(skin, index, xy.as_mut_ptr(), n - 1, &mut written);
                assert_eq!(short, HIBI_ERROR_BUFFER_TOO_SMALL);
                assert!(written == 5 && xy.iter().all(|&v| v == -1.0));
                assert_eq!(hibi_skin_outline(skin, index, xy.as_mut_ptr(), n, null_mut()), HIBI_ERROR_NULL_POINTER);
                assert_eq!(hibi_skin_outline(skin, index, xy.as_mut_ptr(), n, &mut written), HIBI_OK);
                assert_eq!(written, n);
                let m = n / 2;
                let twice: f64 = (0..m)
                    .map(|i| {
                        let j = (i + 1) % m;
                        xy[2 * i] * xy[2 * j + 1] - xy[2 * j] * xy[2 * i + 1]
                    })
                    .sum();
                area[info.level as usize] += twice / 2.0;
            }
            let mut xy = [0.0f64; 2];
            let mut written = 5;
            assert_eq!(hibi_skin_outline(skin, count, xy.as_mut_ptr(), 2, &mut written), HIBI_ERROR_SKIN_CELL_INDEX);
            assert_eq!(written, 5);
            let surface = f64::from(p.width * p.height);
            for a in area {
                assert!((a - surface).abs() < 1e-6, "{a} of {surface}");
            }
            hibi_skin_destroy(skin);
        }
    }
}
