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
                let object = unsafe { $crate::guard::object_ref($arg, NAME) }?;
                // SAFETY: the caller's contract.
                let render = unsafe { $crate::guard::object_ref(render, c"render") }?;
                let render = $crate::fields::Field::to_core(render)
                    .ok_or_else(|| $crate::status::refuse_argument(c"render", $crate::status::HIBI_ERROR_BAD_ENUM))?;
                // SAFETY: the caller's contract.
                let layers = $layers(layer, unsafe { $crate::raster::Pixels::new(pixels, pixels_len) })?;
                object.$arg.render(&render, layers).map_err(|e| $crate::status::short_buffer($status(e), c"pixels"))
            })
        }
    };
}
pub(crate) use render;
