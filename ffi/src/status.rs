//! `hibi_status`: what every fallible function returns, and its message.

use core::cell::Cell;
use core::ffi::{CStr, c_char};

use hibi_core::RngError;
use hibi_core::glass::GlassParamError;
use hibi_core::mud::MudParamError;
use hibi_core::polygon::RingError;
use hibi_core::raster::RasterError;
use hibi_core::skin::{ShadeError, SkinParamError};

use crate::constants::param_error;
use crate::guard::guard_query;

/// The result of a fallible call: `HIBI_OK` (0) or one of the `HIBI_ERROR_*` codes.
/// Codes below 256 are about the call itself (pointers, buffers, enums); codes from 256 up
/// name the argument or parameter field that is wrong. `hibi_status_string` gives the message.
pub type hibi_status = u32;

/// Success.
pub const HIBI_OK: hibi_status = 0;
/// A required pointer argument is NULL (`hibi_error_argument` names it).
pub const HIBI_ERROR_NULL_POINTER: hibi_status = 1;
/// A pointer argument is not aligned for the type it points to (`hibi_error_argument` names
/// it).
pub const HIBI_ERROR_MISALIGNED: hibi_status = 2;
/// A caller buffer is shorter than the call needs.
pub const HIBI_ERROR_BUFFER_TOO_SMALL: hibi_status = 3;
/// An enumeration passed as an integer has no such value.
pub const HIBI_ERROR_BAD_ENUM: hibi_status = 4;
/// The library could not allocate the memory an object needs.
pub const HIBI_ERROR_OUT_OF_MEMORY: hibi_status = 5;
/// A buffer length in elements overflows the address space when converted to bytes
/// (`hibi_error_argument` names the buffer).
pub const HIBI_ERROR_SIZE_OVERFLOW: hibi_status = 6;
/// An internal error: a panic inside hibi was caught at the C boundary (a bug; please report).
/// Nothing is printed: hibi installs a panic hook that is silent inside its calls and hands
/// any other panic to the hook installed before it.
pub const HIBI_ERROR_PANIC: hibi_status = 7;
/// `hibi_rng_poisson`: the mean is negative, not finite, or above 1e6.
pub const HIBI_ERROR_POISSON_MEAN: hibi_status = 256;
/// `hibi_rng_rand`: x is not finite, z is outside [0, 1), or (1 + z)·|x| exceeds FLT_MAX (the
/// range would reach infinity).
pub const HIBI_ERROR_RAND_ARGUMENT: hibi_status = 257;

/// Mud parameters: the struct did not come from `hibi_mud_params_default` (its cookie is wrong).
pub const HIBI_ERROR_MUD_PARAMS_NOT_INITIALISED: hibi_status = 575;
/// Mud parameters: `topology`, `boundary`, `solver` or `drive` is not one of its constants.
pub const HIBI_ERROR_MUD_ENUM: hibi_status = 576;
/// `hibi_mud_params_preset`: no preset has that name.
pub const HIBI_ERROR_MUD_UNKNOWN_PRESET: hibi_status = 577;
/// Render: width and height must be > 0 and their product must fit in memory.
pub const HIBI_ERROR_RENDER_SIZE: hibi_status = 768;
/// Render: `width_scale` must be finite and >= 0.
pub const HIBI_ERROR_RENDER_WIDTH_SCALE: hibi_status = 769;
/// Render: `min_width` must be finite and >= 0.
pub const HIBI_ERROR_RENDER_MIN_WIDTH: hibi_status = 770;
/// Render: `groove_depth` must be finite and >= 0.
pub const HIBI_ERROR_RENDER_GROOVE_DEPTH: hibi_status = 771;
/// Render: `offset` must be finite.
pub const HIBI_ERROR_RENDER_OFFSET: hibi_status = 772;
/// Render: `line_width` must be finite and > 0.
pub const HIBI_ERROR_RENDER_LINE_WIDTH: hibi_status = 774;
/// `hibi_mud_render`: `layer` is not one of the `HIBI_MUD_LAYER_*` constants.
pub const HIBI_ERROR_RENDER_LAYER: hibi_status = 773;
/// Layered render: the model does not draw a layer that was given (mud and glass have no
/// `cell`, skin no `time`); `hibi_error_argument()` names it.
pub const HIBI_ERROR_RENDER_NO_LAYER: hibi_status = 775;
/// Layered render: the tile is empty or reaches past the image.
pub const HIBI_ERROR_RENDER_TILE: hibi_status = 776;
/// Render: `bump` must be finite and >= 0.
pub const HIBI_ERROR_RENDER_BUMP: hibi_status = 777;
/// Render: `until` must not be NaN (+infinity draws every crack).
pub const HIBI_ERROR_RENDER_UNTIL: hibi_status = 778;

/// Glass parameters: the struct did not come from `hibi_glass_params_default`.
pub const HIBI_ERROR_GLASS_PARAMS_NOT_INITIALISED: hibi_status = 1087;
/// Glass parameters: `spread` is not `HIBI_SPREAD_UNIFORM` or `HIBI_SPREAD_NORMAL`.
pub const HIBI_ERROR_GLASS_ENUM: hibi_status = 1088;
/// `hibi_glass_params_preset`: no preset has that name.
pub const HIBI_ERROR_GLASS_UNKNOWN_PRESET: hibi_status = 1093;
/// `hibi_glass_impact`: the point is not inside the plate.
pub const HIBI_ERROR_GLASS_IMPACT: hibi_status = 1089;
/// `hibi_glass_step`: `max_cracks`, `max_vertices` or the grid ran out; generation stopped
/// early and the plate stays usable as drawn. `hibi_glass_impact` on such a plate: refused,
/// nothing changed.
pub const HIBI_ERROR_GLASS_CAPACITY: hibi_status = 1090;
/// A crack index is not below `hibi_glass_crack_count`.
pub const HIBI_ERROR_GLASS_CRACK_INDEX: hibi_status = 1091;
/// `hibi_glass_render`: `layer` is not `HIBI_GLASS_LAYER_MASK` or `HIBI_GLASS_LAYER_TIME`.
pub const HIBI_ERROR_GLASS_RENDER_LAYER: hibi_status = 1094;

/// Skin parameters: the struct did not come from `hibi_skin_params_default` or
/// `hibi_skin_params_preset`.
pub const HIBI_ERROR_SKIN_PARAMS_NOT_INITIALISED: hibi_status = 1343;
/// Skin parameters: `layout` is not a `HIBI_SKIN_LAYOUT_*` constant, `jitter` not
/// `HIBI_SPREAD_UNIFORM` or `HIBI_SPREAD_NORMAL`, or `periodic` not 0 or 1.
pub const HIBI_ERROR_SKIN_ENUM: hibi_status = 1344;
/// `hibi_skin_step`: a cell outline or one parent's centre points outgrew their fixed
/// capacity (the build stopped there; what was built stays usable); lower the perturbation
/// depth or the ratio of a level's spacing to the next's.
pub const HIBI_ERROR_SKIN_CAPACITY: hibi_status = 1345;
/// `hibi_skin_render`: `cell_level` is not below the skin's `levels`.
pub const HIBI_ERROR_SKIN_LEVEL: hibi_status = 1346;
/// `hibi_skin_shade`: a `light` component is not finite, or all three are zero.
pub const HIBI_ERROR_SKIN_SHADE: hibi_status = 1347;
/// `hibi_skin_shade`: a `ridge` channel is outside [0, 1].
pub const HIBI_ERROR_SKIN_SHADE_RIDGE: hibi_status = 1350;
/// `hibi_skin_shade`: a `furrow` channel is outside [0, 1].
pub const HIBI_ERROR_SKIN_SHADE_FURROW: hibi_status = 1351;
/// `hibi_skin_shade`: `ambient` is outside [0, 1].
pub const HIBI_ERROR_SKIN_SHADE_AMBIENT: hibi_status = 1352;
/// `hibi_skin_shade`: `specular` is negative or not finite.
pub const HIBI_ERROR_SKIN_SHADE_SPECULAR: hibi_status = 1353;
/// `hibi_skin_params_preset`: no preset has that name.
pub const HIBI_ERROR_SKIN_UNKNOWN_PRESET: hibi_status = 1348;
/// A cell index is not below `hibi_skin_cell_count`.
pub const HIBI_ERROR_SKIN_CELL_INDEX: hibi_status = 1349;
/// `hibi_skin_render`: `layer` is not one of the `HIBI_SKIN_LAYER_*` constants.
pub const HIBI_ERROR_SKIN_RENDER_LAYER: hibi_status = 1354;

/// `hibi_pieces_*`, `hibi_triangulate`, `hibi_convex_pieces`: a ring's `first_point +
/// point_count` runs past `points_len`.
pub const HIBI_ERROR_RING_POINTS: hibi_status = 1536;
/// `hibi_pieces_*`, `hibi_triangulate`, `hibi_convex_pieces`: a ring's `hole_of` (below
/// `rings_len`) names a hole or the ring itself, not an outer ring.
pub const HIBI_ERROR_RING_HOLE_OF: hibi_status = 1537;
/// `hibi_pieces_*`, `hibi_triangulate`, `hibi_convex_pieces`: a ring's point is NaN or
/// infinite.
pub const HIBI_ERROR_RING_POINT_NOT_FINITE: hibi_status = 1538;
/// `hibi_pieces_*`, `hibi_triangulate`, `hibi_convex_pieces`: one polygon holds 2^30 or more
/// points with its holes (rings may share points), or there are 2^32 or more rings.
pub const HIBI_ERROR_RING_SIZE: hibi_status = 1539;
/// `hibi_pieces_counts`, `hibi_triangulate`, `hibi_convex_pieces`: a polygon's triangles do
/// not add up to its area (its outer ring's and its holes' signed areas, from their points):
/// a ring of it crosses itself or another ring of the polygon, so no pieces cover it.
pub const HIBI_ERROR_RING_CROSSES: hibi_status = 1540;

/// The status that reports a raster error.
pub(crate) fn raster_status(error: RasterError) -> hibi_status {
    match error {
        RasterError::Size => HIBI_ERROR_RENDER_SIZE,
        RasterError::BufferTooSmall { .. } => HIBI_ERROR_BUFFER_TOO_SMALL,
        RasterError::WidthScale => HIBI_ERROR_RENDER_WIDTH_SCALE,
        RasterError::MinWidth => HIBI_ERROR_RENDER_MIN_WIDTH,
        RasterError::GrooveDepth => HIBI_ERROR_RENDER_GROOVE_DEPTH,
        RasterError::Offset => HIBI_ERROR_RENDER_OFFSET,
        RasterError::LineWidth => HIBI_ERROR_RENDER_LINE_WIDTH,
        RasterError::NoLayer(_) => HIBI_ERROR_RENDER_NO_LAYER,
        RasterError::Tile => HIBI_ERROR_RENDER_TILE,
        RasterError::Bump => HIBI_ERROR_RENDER_BUMP,
        RasterError::Until => HIBI_ERROR_RENDER_UNTIL,
    }
}

/// The status that reports a core random-source error.
pub(crate) fn rng_status(error: RngError) -> hibi_status {
    match error {
        RngError::PoissonMean => HIBI_ERROR_POISSON_MEAN,
        RngError::RandArgument => HIBI_ERROR_RAND_ARGUMENT,
    }
}

/// The message of a status, as a static NUL-terminated string.
pub(crate) fn message(status: hibi_status) -> &'static CStr {
    match status {
        HIBI_OK => c"ok",
        HIBI_ERROR_NULL_POINTER => c"a required pointer argument is NULL",
        HIBI_ERROR_MISALIGNED => c"a pointer argument is not aligned for its type",
        HIBI_ERROR_BUFFER_TOO_SMALL => c"a buffer is smaller than the call needs",
        HIBI_ERROR_BAD_ENUM => c"an enumeration value is out of range",
        HIBI_ERROR_OUT_OF_MEMORY => c"out of memory",
        HIBI_ERROR_SIZE_OVERFLOW => c"a buffer length overflows the address space",
        HIBI_ERROR_PANIC => c"internal error: a panic was caught at the C boundary (a bug in hibi)",
        HIBI_ERROR_POISSON_MEAN => RngError::PoissonMean.message(),
        HIBI_ERROR_RAND_ARGUMENT => RngError::RandArgument.message(),
        HIBI_ERROR_MUD_PARAMS_NOT_INITIALISED => {
            c"mud: the params struct did not come from hibi_mud_params_default or hibi_mud_params_preset"
        }
        HIBI_ERROR_MUD_ENUM => c"mud: topology, boundary, solver or drive is not one of its HIBI_MUD_* constants",
        HIBI_ERROR_MUD_UNKNOWN_PRESET => c"mud: no preset has that name",
        HIBI_ERROR_RENDER_SIZE => RasterError::Size.message(),
        HIBI_ERROR_RENDER_WIDTH_SCALE => RasterError::WidthScale.message(),
        HIBI_ERROR_RENDER_MIN_WIDTH => RasterError::MinWidth.message(),
        HIBI_ERROR_RENDER_GROOVE_DEPTH => RasterError::GrooveDepth.message(),
        HIBI_ERROR_RENDER_OFFSET => RasterError::Offset.message(),
        HIBI_ERROR_RENDER_LINE_WIDTH => RasterError::LineWidth.message(),
        HIBI_ERROR_RENDER_NO_LAYER => RasterError::NoLayer(hibi_core::raster::Layer::Cell).message(),
        HIBI_ERROR_RENDER_TILE => RasterError::Tile.message(),
        HIBI_ERROR_RENDER_BUMP => RasterError::Bump.message(),
        HIBI_ERROR_RENDER_UNTIL => RasterError::Until.message(),
        HIBI_ERROR_RENDER_LAYER => c"hibi_mud_render: layer is not one of the HIBI_MUD_LAYER_* constants",
        HIBI_ERROR_GLASS_RENDER_LAYER => {
            c"hibi_glass_render: layer is not HIBI_GLASS_LAYER_MASK or HIBI_GLASS_LAYER_TIME"
        }
        HIBI_ERROR_GLASS_PARAMS_NOT_INITIALISED => {
            c"glass: the params struct did not come from hibi_glass_params_default or hibi_glass_params_preset"
        }
        HIBI_ERROR_GLASS_ENUM => c"glass: spread is not HIBI_SPREAD_UNIFORM or HIBI_SPREAD_NORMAL",
        HIBI_ERROR_GLASS_UNKNOWN_PRESET => c"glass: no preset has that name",
        HIBI_ERROR_GLASS_IMPACT => c"glass: the impact point is not inside the plate",
        HIBI_ERROR_GLASS_CAPACITY => c"glass: max_cracks or max_vertices ran out; generation stopped early",
        HIBI_ERROR_GLASS_CRACK_INDEX => c"glass: crack index out of range",
        HIBI_ERROR_SKIN_PARAMS_NOT_INITIALISED => {
            c"skin: the params struct did not come from hibi_skin_params_default or hibi_skin_params_preset"
        }
        HIBI_ERROR_SKIN_ENUM => {
            c"skin: layout, jitter or periodic is not one of its constants (HIBI_SKIN_LAYOUT_*, HIBI_SPREAD_*, 0 or 1)"
        }
        HIBI_ERROR_SKIN_CAPACITY => {
            c"skin: an outline or a parent's centre points outgrew their capacity (lower depth or spacing ratio)"
        }
        HIBI_ERROR_SKIN_LEVEL => c"skin: cell_level must be below levels",
        HIBI_ERROR_SKIN_RENDER_LAYER => {
            c"skin: hibi_skin_render's layer is not HIBI_SKIN_LAYER_HEIGHT, HIBI_SKIN_LAYER_NORMAL or HIBI_SKIN_LAYER_CELLS"
        }
        HIBI_ERROR_SKIN_SHADE => ShadeError::Light.message(),
        HIBI_ERROR_SKIN_SHADE_RIDGE => ShadeError::Ridge.message(),
        HIBI_ERROR_SKIN_SHADE_FURROW => ShadeError::Furrow.message(),
        HIBI_ERROR_SKIN_SHADE_AMBIENT => ShadeError::Ambient.message(),
        HIBI_ERROR_SKIN_SHADE_SPECULAR => ShadeError::Specular.message(),
        HIBI_ERROR_SKIN_UNKNOWN_PRESET => c"skin: no preset has that name",
        HIBI_ERROR_SKIN_CELL_INDEX => c"skin: cell index out of range",
        HIBI_ERROR_RING_POINTS => RingError::Points.message(),
        HIBI_ERROR_RING_HOLE_OF => RingError::HoleOf.message(),
        HIBI_ERROR_RING_POINT_NOT_FINITE => RingError::NotFinite.message(),
        HIBI_ERROR_RING_SIZE => RingError::Size.message(),
        HIBI_ERROR_RING_CROSSES => RingError::Crosses.message(),
        _ => match (
            param_error::<MudParamError>(status),
            param_error::<GlassParamError>(status),
            param_error::<SkinParamError>(status),
        ) {
            (Some(error), _, _) => error.message(),
            (_, Some(error), _) => error.message(),
            (_, _, Some(error)) => error.message(),
            _ => c"unknown status code",
        },
    }
}

/// A static, NUL-terminated English message for `status`; never NULL (unknown codes give
/// "unknown status code"). The string lives as long as the library.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_status_string(status: hibi_status) -> *const c_char {
    guard_query(|| message(status).as_ptr())
}

std::thread_local! {
    /// The argument the latest call on this thread refused, by its C name.
    static REFUSED: Cell<&'static CStr> = const { Cell::new(c"") };
}

/// `status`, with buffer `name` put on record when it is `HIBI_ERROR_BUFFER_TOO_SMALL`: for
/// the calls whose one output buffer is the only one that can be short.
pub(crate) fn short_buffer(status: hibi_status, name: &'static CStr) -> hibi_status {
    if status == HIBI_ERROR_BUFFER_TOO_SMALL { refuse_argument(name, status) } else { status }
}

/// `HIBI_ERROR_BUFFER_TOO_SMALL` naming the first of `buffers` (name, length, length needed)
/// that is short, for the calls that write into several.
pub(crate) fn first_short(buffers: &[(&'static CStr, usize, usize)]) -> hibi_status {
    let name = buffers.iter().find(|(_, have, needed)| have < needed).map_or(c"", |b| b.0);
    refuse_argument(name, HIBI_ERROR_BUFFER_TOO_SMALL)
}

/// Puts argument `name` on record as the one the current call refuses with `status`, and
/// returns `status`.
pub(crate) fn refuse_argument(name: &'static CStr, status: hibi_status) -> hibi_status {
    let _ = REFUSED.try_with(|r| r.set(name));
    status
}

/// Clears the record: a call begins.
pub(crate) fn clear_argument() {
    let _ = REFUSED.try_with(|r| r.set(c""));
}

/// The name of the argument that the latest call on this thread refused, as it is spelled in
/// this header (`"written"`, `"rings"`, `"mud"`, ...), when that call returned
/// `HIBI_ERROR_NULL_POINTER`, `HIBI_ERROR_MISALIGNED`, `HIBI_ERROR_SIZE_OVERFLOW`,
/// `HIBI_ERROR_BUFFER_TOO_SMALL` (the buffer that is short: `"memory"`, `"scratch"`,
/// `"pixels"`, `"points"`, ...) or `HIBI_ERROR_BAD_ENUM` (the enumeration argument, or the
/// struct that holds the bad value); `""` after any other outcome (a parameter error's status
/// names its field itself). Static and NUL-terminated, never NULL. Per thread: another
/// thread's calls do not change it, and neither do `hibi_status_string`,
/// `hibi_error_argument` and `hibi_version`.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_error_argument() -> *const c_char {
    guard_query(|| REFUSED.try_with(Cell::get).unwrap_or(c"").as_ptr())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::glass::{hibi_glass_crack_count, hibi_glass_params_default, hibi_glass_step};
    use core::ptr::{null, null_mut};

    fn refused() -> &'static str {
        // SAFETY: hibi_error_argument returns a static NUL-terminated string.
        unsafe { CStr::from_ptr(hibi_error_argument()) }.to_str().unwrap()
    }

    #[test]
    fn the_refused_argument_is_per_thread_and_per_call() {
        let mut count = 0usize;
        // SAFETY: NULL handles are refused before anything is touched.
        unsafe {
            assert_eq!(hibi_glass_crack_count(null(), &mut count), HIBI_ERROR_NULL_POINTER);
            assert_eq!(refused(), "glass");
            // Asking for the message or the version keeps the record.
            hibi_status_string(HIBI_ERROR_NULL_POINTER);
            crate::hibi_version();
            assert_eq!(refused(), "glass");
            std::thread::spawn(|| {
                assert_eq!(refused(), "", "another thread's record");
                let mut count = 0usize;
                let misaligned = (&raw mut count).cast::<u8>().wrapping_add(1).cast::<usize>();
                let params = hibi_glass_params_default();
                let mut glass = null_mut();
                assert_eq!(crate::glass::hibi_glass_create(&params, &mut glass), HIBI_OK);
                assert_eq!(hibi_glass_crack_count(glass, misaligned), HIBI_ERROR_MISALIGNED);
                assert_eq!(refused(), "count");
                crate::glass::hibi_glass_destroy(glass);
                assert_eq!(refused(), "", "a call that succeeds clears it");
            })
            .join()
            .unwrap();
            assert_eq!(refused(), "glass");
            assert_eq!(hibi_glass_step(null_mut(), 1, null_mut()), HIBI_ERROR_NULL_POINTER);
            assert_eq!(refused(), "glass");
            assert!(!hibi_status_string(9999).is_null());
            let _ = hibi_glass_params_default();
            assert_eq!(refused(), "", "any other call clears it");
        }
    }
}
