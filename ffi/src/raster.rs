//! The renders of the three models, `hibi_mud_render`, `hibi_glass_render` and
//! `hibi_skin_render`: one C shape (the object, its render params, a layer number and one
//! raster of that layer's values), written once by [`render!`]; each model says only how a
//! layer number picks its core layers and which status each core error is.

use core::ffi::c_void;
use core::marker::PhantomData;

use crate::guard::buffer;
use crate::status::hibi_status;

/// The caller's raster: `len` values of whichever type its layer has, at `ptr`.
pub(crate) struct Pixels<'a> {
    ptr: *mut c_void,
    len: usize,
    values: PhantomData<&'a mut [u8]>,
}

impl<'a> Pixels<'a> {
    /// # Safety
    /// `ptr` must be NULL (only with `len` 0) or writable for `len` values of the type the
    /// raster is read as ([`Pixels::values`]), and not aliased during the call.
    pub(crate) unsafe fn new(ptr: *mut c_void, len: usize) -> Self {
        Pixels { ptr, len, values: PhantomData }
    }

    /// The raster as values of `T` (NULL, alignment and size checked; named `pixels`).
    ///
    /// # Safety
    /// `T` must be the type of the layer the caller chose (the header names each layer's).
    pub(crate) unsafe fn values<T>(self) -> Result<&'a mut [T], hibi_status> {
        // SAFETY: the contract of `new`, with `T` the layer's type (this function's contract).
        unsafe { buffer(self.ptr.cast::<T>(), self.len, c"pixels") }
    }
}

/// A render `$name` of the object `$arg` (a `$what`), whose field `$arg` is the core model:
/// reads the render params (`$params`, converted to the core's), picks the core layers with
/// `$layers(layer, pixels)` and draws them, reporting a core error as `$status(error)`. The doc comment is the caller's; the signature,
/// the checks and the Safety notes are here.
macro_rules! render {
    (
        $(#[$doc:meta])*
        $name:ident($arg:ident: $object:ty, $what:literal, $params:ty) = $layers:path, $status:path
    ) => {
        $(#[$doc])*
        ///
        /// # Safety
        #[doc = concat!(" `", stringify!($arg), "` must be NULL or a live ", $what, "; `render` NULL or readable;")]
        /// `pixels` NULL (only with `pixels_len` 0) or writable for `pixels_len` values of the
        /// layer's type, and overlapping neither the object nor `render`.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(
            $arg: *const $object,
            render: *const $params,
            layer: u32,
            pixels: *mut core::ffi::c_void,
            pixels_len: usize,
        ) -> $crate::status::hibi_status {
            $crate::guard::guard(|| {
                const NAME: &core::ffi::CStr = $crate::guard::c_name(concat!(stringify!($arg), "\0"));
                // SAFETY: the caller's contract.
                let (object, render) = unsafe { $crate::raster::render_inputs($arg, NAME, render) }?;
                // SAFETY: the caller's contract.
                let layers = $layers(layer, unsafe { $crate::raster::Pixels::new(pixels, pixels_len) })?;
                object.$arg.render(&render, layers).map_err(|e| $crate::status::short_buffer($status(e), c"pixels"))
            })
        }
    };
}
pub(crate) use render;

/// The object and the render params of a render call, checked: the object (named `name`), and
/// the params in the core's form (`HIBI_ERROR_BAD_ENUM` naming `render` for a field holding no
/// valid value).
///
/// # Safety
/// `object` must be NULL or a live object; `render` NULL or readable.
pub(crate) unsafe fn render_inputs<'a, O, P: crate::fields::Field<C>, C>(
    object: *const O,
    name: &'static core::ffi::CStr,
    render: *const P,
) -> Result<(&'a O, C), crate::status::hibi_status> {
    // SAFETY: the caller's contract.
    let object = unsafe { crate::guard::object_ref(object, name) }?;
    // SAFETY: the caller's contract.
    let render = unsafe { crate::guard::object_ref(render, c"render") }?;
    let render = render
        .to_core()
        .ok_or_else(|| crate::status::refuse_argument(c"render", crate::status::HIBI_ERROR_BAD_ENUM))?;
    Ok((object, render))
}

/// The rasters one layered render writes (`hibi_mud_render_layers`, `hibi_glass_render_layers`,
/// `hibi_skin_render_layers`): any of them, each NULL (not drawn) or `pixels_len` pixels of the
/// tile, row-major, row 0 at the top. One pass draws every layer given. A model refuses a
/// layer it does not draw with `HIBI_ERROR_RENDER_NO_LAYER` (mud and glass have no `cell`,
/// skin no `time`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct hibi_layers {
    /// Coverage, one `uint8_t` per pixel, 0 (none) to 255 (full); skin: the furrow net.
    pub mask: *mut u8,
    /// Height, one `float` per pixel.
    pub height: *mut f32,
    /// Height, one `uint16_t` per pixel, 0 to 65535 over the model's height range.
    pub height16: *mut u16,
    /// Unit tangent-space normal, three `float`s per pixel (x right, y up, z out).
    pub normal: *mut f32,
    /// The normal as 8-bit RGB, three bytes per pixel: round((c + 1) / 2 · 255).
    pub normal_rgb8: *mut u8,
    /// Time, one `float` per pixel (mud: break time; glass: the step the front passed);
    /// +infinity where no crack covers at least half of the pixel.
    pub time: *mut f32,
    /// Skin: the cell index at `cell_level`, one `uint32_t` per pixel.
    pub cell: *mut u32,
    /// A shaded preview, four bytes per pixel: 8-bit sRGB and alpha 255.
    pub preview: *mut u8,
    /// Pixels each non-NULL layer holds (at least the tile's width × height).
    pub pixels_len: usize,
    /// Working memory of `hibi_render_scratch_len` `uint32_t`s: needed for `height16`,
    /// `normal`, `normal_rgb8` and `preview` of mud and glass, and for skin's `mask`; NULL
    /// otherwise.
    pub scratch: *mut u32,
    /// `uint32_t`s at `scratch`.
    pub scratch_len: usize,
}

/// Writes the `uint32_t`s of scratch a layered render of a `width` × `height` tile works in
/// (the tile and a one-pixel margin).
///
/// # Safety
/// `len` must be NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_render_scratch_len(width: u32, height: u32, len: *mut usize) -> hibi_status {
    crate::guard::guard(|| {
        let n = hibi_core::raster::scratch_len(width, height)
            .filter(|&n| n.checked_mul(4).is_some_and(|b| b <= isize::MAX as usize))
            .ok_or_else(|| crate::status::refuse_argument(c"width", crate::status::HIBI_ERROR_SIZE_OVERFLOW))?;
        // SAFETY: the caller's contract.
        unsafe { crate::guard::write_out(len, c"len", n) }
    })
}

impl hibi_layers {
    /// The core's layers over the caller's buffers (each checked: alignment, size).
    ///
    /// # Safety
    /// Every non-NULL pointer must be writable for `pixels_len` pixels of its layer's type
    /// (`scratch` for `scratch_len` values), none overlapping another or the object.
    pub(crate) unsafe fn to_core<'a>(self) -> Result<hibi_core::raster::Layers<'a>, hibi_status> {
        let n = self.pixels_len;
        // A layer: NULL is absent.
        // SAFETY (each): the caller's contract.
        unsafe fn layer<'a, T>(
            ptr: *mut T,
            n: usize,
            name: &'static core::ffi::CStr,
        ) -> Result<Option<&'a mut [T]>, hibi_status> {
            if ptr.is_null() {
                return Ok(None);
            }
            // SAFETY: the caller's contract.
            unsafe { buffer(ptr, n, name) }.map(Some)
        }
        unsafe {
            Ok(hibi_core::raster::Layers {
                mask: layer(self.mask, n, c"layers.mask")?,
                height: layer(self.height, n, c"layers.height")?,
                height16: layer(self.height16, n, c"layers.height16")?,
                normal: layer(self.normal.cast::<[f32; 3]>(), n, c"layers.normal")?,
                normal_rgb8: layer(self.normal_rgb8.cast::<[u8; 3]>(), n, c"layers.normal_rgb8")?,
                time: layer(self.time, n, c"layers.time")?,
                cell: layer(self.cell, n, c"layers.cell")?,
                preview: layer(self.preview.cast::<[u8; 4]>(), n, c"layers.preview")?,
                scratch: layer(self.scratch, self.scratch_len, c"layers.scratch")?,
            })
        }
    }
}

/// The C name of a layer's field.
pub(crate) fn layer_name(layer: hibi_core::raster::Layer) -> &'static core::ffi::CStr {
    use hibi_core::raster::Layer;
    match layer {
        Layer::Mask => c"layers.mask",
        Layer::Height => c"layers.height",
        Layer::Height16 => c"layers.height16",
        Layer::Normal => c"layers.normal",
        Layer::NormalRgb8 => c"layers.normal_rgb8",
        Layer::Time => c"layers.time",
        Layer::Cell => c"layers.cell",
        Layer::Preview => c"layers.preview",
        Layer::Scratch => c"layers.scratch",
    }
}

/// The status of a refused layered render, naming the C argument or field it is about.
pub(crate) fn layers_status(error: hibi_core::raster::RasterError) -> hibi_status {
    use hibi_core::raster::RasterError;
    let status = crate::status::raster_status(error);
    match error {
        RasterError::BufferTooSmall { layer, .. } | RasterError::NoLayer(layer) => {
            crate::status::refuse_argument(layer_name(layer), status)
        }
        RasterError::Tile => crate::status::refuse_argument(c"tile", status),
        _ => status,
    }
}

/// A layered render `$name` of the object `$arg` (a `$what`): reads the render params
/// (`$params`, converted to the core's), the tile (NULL: the whole image, `$whole` of the
/// render params) and the layers, and draws them with the core's `render_tile`, reporting a
/// core error as `$status(error)`.
macro_rules! render_layers {
    (
        $(#[$doc:meta])*
        $name:ident($arg:ident: $object:ty, $what:literal, $params:ty) = $whole:expr, $status:path
    ) => {
        $(#[$doc])*
        ///
        /// # Safety
        #[doc = concat!(" `", stringify!($arg), "` must be NULL or a live ", $what, "; `render` and `layers` NULL or")]
        /// readable; `tile` NULL (the whole image) or readable; each non-NULL pointer of
        /// `layers` writable for `pixels_len` pixels of its layer (`scratch` for `scratch_len`
        /// values), none overlapping another, the object, `render` or `layers`.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(
            $arg: *const $object,
            render: *const $params,
            tile: *const hibi_core::raster::Tile,
            layers: *const $crate::raster::hibi_layers,
        ) -> $crate::status::hibi_status {
            $crate::guard::guard(|| {
                const NAME: &core::ffi::CStr = $crate::guard::c_name(concat!(stringify!($arg), "\0"));
                // SAFETY: the caller's contract.
                let (object, render) = unsafe { $crate::raster::render_inputs($arg, NAME, render) }?;
                // SAFETY: the caller's contract.
                let layers = unsafe { $crate::guard::object_ref(layers, c"layers") }?;
                let tile = if tile.is_null() {
                    let whole: fn(&_, &_) -> hibi_core::raster::Tile = $whole;
                    whole(object, &render)
                } else {
                    // SAFETY: the caller's contract (non-NULL here).
                    *unsafe { $crate::guard::object_ref(tile, c"tile") }?
                };
                // SAFETY: the caller's contract.
                let layers = unsafe { (*layers).to_core() }?;
                object.$arg.render_tile(&render, &tile, layers).map_err($status)
            })
        }
    };
}
pub(crate) use render_layers;
