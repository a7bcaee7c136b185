//! The one lifecycle of every C-held object (`*_memory_size`, `*_memory_align`, `*_create`,
//! `*_create_in`, `*_destroy`), written once over the [`Object`] trait that the random
//! source and the three models implement.
//!
//! An object lives in one block: its header (the Rust value) at the start, then the arrays it
//! computes in, laid out by an [`Arena`]. The block is allocated by the library
//! (`*_create`, freed by `*_destroy`) or handed in by the caller (`*_create_in`), as engines
//! with their own allocators need.

use core::ffi::{CStr, c_void};
use core::mem::{align_of, size_of};
use std::alloc::{Layout, alloc_zeroed, dealloc};

use crate::guard::{check_pointer, object, write_out};
use crate::status::{
    HIBI_ERROR_BUFFER_TOO_SMALL, HIBI_ERROR_MISALIGNED, HIBI_ERROR_NULL_POINTER, HIBI_ERROR_OUT_OF_MEMORY,
    HIBI_ERROR_SIZE_OVERFLOW, hibi_status, refuse_argument,
};

/// Alignment of every object's block: enough for the header and every array element.
pub(crate) const BLOCK_ALIGN: usize = 8;

/// Who owns an object's block, recorded in the object so that `*_destroy` frees only what
/// the library allocated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Origin {
    /// Allocated by `*_create` with this size; `*_destroy` frees it.
    Library {
        /// Block size in bytes.
        size: usize,
    },
    /// Placed in caller memory by `*_create_in`; `*_destroy` only drops it.
    Caller,
}

/// Element types every bit pattern of which is a value: integers, floats, and structs of
/// them without padding. An array of them may be handed out over a block's bytes as they are,
/// for a model that reads no element before it writes it.
///
/// # Safety
/// Every bit pattern of `size_of::<Self>()` bytes must be a valid `Self`.
pub(crate) unsafe trait AnyBits: Copy {}

// SAFETY: integers and floats: every bit pattern is a value.
unsafe impl AnyBits for u32 {}
// SAFETY: as u32.
unsafe impl AnyBits for f32 {}
// SAFETY: as u32.
unsafe impl AnyBits for i64 {}
// SAFETY: an array of values of such a type, without padding between them.
unsafe impl<T: AnyBits, const N: usize> AnyBits for [T; N] {}

/// Lays out the arrays of a block after its header. Measuring, it only counts the bytes;
/// placing, it also hands out the arrays: [`Arena::take`] sets each element to its default,
/// [`Arena::take_as_is`] leaves the bytes as they are.
pub(crate) struct Arena {
    /// The block, or null when measuring.
    base: *mut u8,
    /// Bytes laid out so far.
    at: usize,
    /// An array's size overflowed.
    overflow: bool,
}

impl Arena {
    /// Takes the next `n` elements of `T`, each set to its default: work in proportion to `n`.
    pub(crate) fn take<T: Default>(&mut self, n: usize) -> &'static mut [T] {
        let Some(first) = self.next::<T>(n) else { return &mut [] };
        // SAFETY: `next`'s range of `n` elements, each written before the slice is made.
        unsafe {
            for i in 0..n {
                first.add(i).write(T::default());
            }
            core::slice::from_raw_parts_mut(first, n)
        }
    }

    /// Takes the next `n` elements of `T` over the block's bytes as they are (zero in a block
    /// the library allocated, the caller's bytes in caller memory), writing nothing: the same
    /// work for any `n`. For the arrays a model reads no element of before writing it.
    pub(crate) fn take_as_is<T: AnyBits>(&mut self, n: usize) -> &'static mut [T] {
        let Some(first) = self.next::<T>(n) else { return &mut [] };
        // SAFETY: `next`'s range of `n` elements, whose bytes are initialised (zeroed by
        // `create`'s allocation, or the caller's memory, which Rust sees only through a
        // pointer) and, whatever they hold, valid values of `T` (`AnyBits`).
        unsafe { core::slice::from_raw_parts_mut(first, n) }
    }

    /// Lays out room for one `T` that the caller places itself (a header): where it starts
    /// when placing, null when measuring.
    pub(crate) fn reserve<T>(&mut self) -> *mut T {
        self.next::<T>(1).unwrap_or(core::ptr::null_mut())
    }

    /// Lays out the next `n` elements of `T`: where they start when placing, `None` when
    /// measuring or when their size overflows (then recorded).
    fn next<T>(&mut self, n: usize) -> Option<*mut T> {
        const { assert!(align_of::<T>() <= BLOCK_ALIGN) };
        let start = (self.at + align_of::<T>() - 1) & !(align_of::<T>() - 1);
        match n.checked_mul(size_of::<T>()).and_then(|bytes| bytes.checked_add(start)) {
            Some(end) if end <= isize::MAX as usize / 2 => self.at = end,
            _ => {
                self.overflow = true;
                return None;
            }
        }
        if self.base.is_null() {
            return None;
        }
        // SAFETY: placing, the block was checked to hold every byte the measuring pass counted
        // (the same layout): the range is inside it, aligned (the block is BLOCK_ALIGN-aligned),
        // disjoint from every other array and the header, and lives as long as the object
        // (the callers' contract).
        Some(unsafe { self.base.add(start).cast::<T>() })
    }
}

/// An object C holds: how its parameters are checked, what arrays it needs and how it is
/// made from them.
pub(crate) trait Object: Sized + 'static {
    /// What `*_create` takes besides the out-pointer (a params pointer, or a seed and stream).
    type Input: Copy;
    /// The checked parameters.
    type Plan;
    /// The arrays it computes in.
    type Arrays;

    /// The status of valid parameters whose arrays do not fit in the address space (the
    /// model's "too large" parameter status; fuzzing found the generic
    /// `HIBI_ERROR_SIZE_OVERFLOW` here, which names no argument).
    const TOO_LARGE: hibi_status;

    /// Checks the input; every parameter error is reported here (mud's irregular explicit
    /// stability aside, which needs the built mesh: see `HIBI_ERROR_MUD_SHORT_STEP_STABILITY`).
    ///
    /// # Safety
    /// Pointers in the input must be NULL or readable.
    unsafe fn plan(input: Self::Input) -> Result<Self::Plan, hibi_status>;

    /// Takes the arrays the plan needs from `arena`, in one fixed order.
    fn arrays(plan: &Self::Plan, arena: &mut Arena) -> Self::Arrays;

    /// Makes the object from its arrays.
    fn make(plan: &Self::Plan, arrays: Self::Arrays, origin: Origin) -> Result<Self, hibi_status>;

    /// Where its block came from.
    fn origin(&self) -> Origin;
}

/// Bytes of the header before the arrays.
const fn header<T>() -> usize {
    (size_of::<T>() + BLOCK_ALIGN - 1) & !(BLOCK_ALIGN - 1)
}

/// The checked input and the size of its block.
///
/// # Safety
/// As [`Object::plan`].
unsafe fn plan<T: Object>(input: T::Input) -> Result<(T::Plan, usize), hibi_status> {
    const { assert!(align_of::<T>() <= BLOCK_ALIGN) };
    // SAFETY: the caller's contract, passed on.
    let plan = unsafe { T::plan(input) }?;
    let mut arena = Arena { base: core::ptr::null_mut(), at: header::<T>(), overflow: false };
    T::arrays(&plan, &mut arena);
    if arena.overflow {
        return Err(T::TOO_LARGE);
    }
    Ok((plan, arena.at))
}

/// Makes the object in `block` (checked to hold the plan's `size` bytes, aligned).
///
/// # Safety
/// `block` must be valid for writes of `size` bytes and outlive the object.
unsafe fn place<T: Object>(block: *mut u8, plan: &T::Plan, origin: Origin) -> Result<*mut T, hibi_status> {
    let mut arena = Arena { base: block, at: header::<T>(), overflow: false };
    let arrays = T::arrays(plan, &mut arena);
    let object = T::make(plan, arrays, origin)?;
    let ptr = block.cast::<T>();
    // SAFETY: the header fits at the block's start (the plan counted it), aligned.
    unsafe { ptr.write(object) };
    Ok(ptr)
}

/// The bytes an object of this input needs in caller memory.
///
/// # Safety
/// As [`Object::plan`].
pub(crate) unsafe fn block_size<T: Object>(input: T::Input) -> Result<usize, hibi_status> {
    // SAFETY: the caller's contract, passed on.
    unsafe { plan::<T>(input) }.map(|(_, bytes)| bytes)
}

/// `*_memory_size`: writes [`block_size`] to `*size`.
///
/// # Safety
/// As [`Object::plan`]; `size` NULL or writable.
pub(crate) unsafe fn memory_size<T: Object>(input: T::Input, size: *mut usize) -> Result<(), hibi_status> {
    check_pointer(size, c"size")?;
    // SAFETY: the caller's contract, passed on.
    let bytes = unsafe { block_size::<T>(input) }?;
    // SAFETY: checked; the caller's contract.
    unsafe { write_out(size, c"size", bytes) }
}

/// `*_create`: the object in library memory.
///
/// # Safety
/// As [`Object::plan`]; `out` NULL or writable.
pub(crate) unsafe fn create<T: Object>(input: T::Input, out: *mut *mut T) -> Result<(), hibi_status> {
    check_pointer(out, c"out")?;
    // SAFETY: the caller's contract, passed on.
    let (plan, size) = unsafe { plan::<T>(input) }?;
    let layout = Layout::from_size_align(size, BLOCK_ALIGN).map_err(|_| HIBI_ERROR_SIZE_OVERFLOW)?;
    // Zeroed, so that the arrays taken as they are hold values; the allocator gives large
    // blocks as fresh zero pages, so creation does not write the block.
    // SAFETY: the layout has a non-zero size (the header is not empty).
    let block = unsafe { alloc_zeroed(layout) };
    if block.is_null() {
        return Err(HIBI_ERROR_OUT_OF_MEMORY);
    }
    // SAFETY: a fresh block of the planned size and alignment.
    match unsafe { place::<T>(block, &plan, Origin::Library { size }) } {
        // SAFETY: checked above; the caller's contract.
        Ok(object) => unsafe { write_out(out, c"out", object) },
        Err(status) => {
            // SAFETY: allocated above with this layout, never handed out.
            unsafe { dealloc(block, layout) };
            Err(status)
        }
    }
}

/// `*_create_in`: the object in caller memory of `memory_len` bytes.
///
/// # Safety
/// As [`Object::plan`]; `memory` NULL or writable for `memory_len` bytes and untouched while
/// the object lives; `out` NULL or writable.
pub(crate) unsafe fn create_in<T: Object>(
    input: T::Input,
    memory: *mut c_void,
    memory_len: usize,
    out: *mut *mut T,
) -> Result<(), hibi_status> {
    check_pointer(out, c"out")?;
    // SAFETY: the caller's contract, passed on.
    let (plan, size) = unsafe { plan::<T>(input) }?;
    let block = caller_block(memory, memory_len, size, c"memory")?;
    // SAFETY: checked to hold the planned size, aligned; the caller's contract.
    let object = unsafe { place::<T>(block, &plan, Origin::Caller) }?;
    // SAFETY: checked above; the caller's contract.
    unsafe { write_out(out, c"out", object) }
}

/// Caller memory `memory` of `len` bytes, checked to be non-null, aligned to [`BLOCK_ALIGN`]
/// and at least `needed` bytes long (each refusal names `name`).
fn caller_block(memory: *mut c_void, len: usize, needed: usize, name: &'static CStr) -> Result<*mut u8, hibi_status> {
    let block = memory.cast::<u8>();
    if block.is_null() {
        return Err(refuse_argument(name, HIBI_ERROR_NULL_POINTER));
    }
    if block.align_offset(BLOCK_ALIGN) != 0 {
        return Err(refuse_argument(name, HIBI_ERROR_MISALIGNED));
    }
    if len < needed {
        return Err(refuse_argument(name, HIBI_ERROR_BUFFER_TOO_SMALL));
    }
    Ok(block)
}

/// The bytes of a call's scratch whose arrays `carve` takes (`*_scratch_size`).
pub(crate) fn scratch_size<A>(carve: impl Fn(&mut Arena) -> A) -> Result<usize, hibi_status> {
    let mut arena = Arena { base: core::ptr::null_mut(), at: 0, overflow: false };
    carve(&mut arena);
    if arena.overflow { Err(HIBI_ERROR_SIZE_OVERFLOW) } else { Ok(arena.at) }
}

/// A call's scratch in caller memory (`scratch`, `scratch_size` bytes, checked as in
/// `*_create_in`): the arrays `carve` takes, each element set to its default. Scratch makes a
/// read-only query's working memory the caller's, so that the object itself is only read.
///
/// # Safety
/// `memory` must be NULL or writable for `len` bytes, and not otherwise used while the
/// arrays live.
pub(crate) unsafe fn scratch<A>(
    memory: *mut c_void,
    len: usize,
    carve: impl Fn(&mut Arena) -> A,
) -> Result<A, hibi_status> {
    let needed = scratch_size(&carve)?;
    let base = caller_block(memory, len, needed, c"scratch")?;
    Ok(carve(&mut Arena { base, at: 0, overflow: false }))
}

/// The arrays `carve` takes from caller memory `memory` of `len` bytes, checked (named
/// `memory`) as in `*_create_in`; nothing is written here (`carve` takes its arrays as they
/// are, and places its header itself).
///
/// # Safety
/// `memory` must be NULL or writable for `len` bytes, and not otherwise used while the
/// arrays live.
pub(crate) unsafe fn caller_arrays<A>(
    memory: *mut c_void,
    len: usize,
    carve: impl Fn(&mut Arena) -> A,
) -> Result<A, hibi_status> {
    let needed = scratch_size(&carve)?;
    let base = caller_block(memory, len, needed, c"memory")?;
    Ok(carve(&mut Arena { base, at: 0, overflow: false }))
}

/// `*_destroy`: drops the object and frees its block if the library allocated it; NULL is
/// ignored (nothing is put on record for `hibi_error_argument`). A misaligned pointer is left
/// alone and named by `name`, the C argument.
///
/// # Safety
/// `ptr` must be NULL or a live object made by [`create`] or [`create_in`], not used afterwards.
pub(crate) unsafe fn destroy<T: Object>(ptr: *mut T, name: &'static CStr) {
    if ptr.is_null() {
        return;
    }
    // SAFETY: the caller's contract.
    if let Ok(live) = unsafe { object(ptr, name) } {
        let origin = live.origin();
        // SAFETY: a live object at the start of its block; dropped once, then its block freed
        // with the layout it was allocated with.
        unsafe {
            ptr.drop_in_place();
            if let Origin::Library { size } = origin {
                dealloc(ptr.cast(), Layout::from_size_align_unchecked(size, BLOCK_ALIGN));
            }
        }
    }
}

/// A model's C lifecycle, written once for the three: its params struct's conversions
/// (`to_c`, `from_c`, and the cookie-less struct a panic returns), then `*_params_default`,
/// `*_params_preset`, `*_memory_size`, `*_memory_align`, `*_create`, `*_create_in` and
/// `*_destroy`, each a thin wrapper over the generic functions above. The header's text for
/// them is written here too, with the model's names put in. The invoking module provides
/// `preset` (the core's preset lookup) and the type's [`Object`] impl.
macro_rules! lifecycle {
    (
        $object:ident ($arg:ident: $what:literal, $created:literal),
        $params:ident <=> $core:ident, cookie $cookie:ident,
        errors ($not_initialised:ident, $bad_enum:ident, $unknown:ident),
        presets $presets:literal in $list:path,
        $default:ident, $preset:ident, $preset_name:ident, $memory_size:ident, $memory_align:ident,
        $create:ident, $create_in:ident, $destroy:ident
        $(, only create: $only_create:literal)? $(,)?
    ) => {
        impl $crate::guard::Outcome for $params {
            type C = $params;
            fn into_c(self) -> Self {
                self
            }
            /// A struct without the cookie, which every function rejects.
            fn on_panic() -> Self {
                $params { cookie: 0, ..to_c(&<$core>::default()) }
            }
        }

        /// Core parameters as the C struct, with the cookie set.
        fn to_c(p: &$core) -> $params {
            $crate::fields::Field::from_core(p)
        }

        /// The core parameters of a C params struct: cookie, enumerations, fields.
        fn from_c(p: &$params) -> Result<$core, hibi_status> {
            if p.cookie != $cookie {
                return Err($crate::status::$not_initialised);
            }
            $crate::fields::Field::to_core(p).ok_or($crate::status::$bad_enum)
        }

        /// The default parameters (the paper's, and ours where it gives none; see each field),
        /// with the cookie set.
        #[unsafe(no_mangle)]
        pub extern "C" fn $default() -> $params {
            $crate::guard::guard(|| to_c(&<$core>::default()))
        }

        #[doc = concat!(" Writes the parameters of the preset `name` (", $presets, ", the paper's")]
        /// figures, see the guide's model pages) to `*out`, with the cookie set; change fields afterwards as
        #[doc = concat!(" with the defaults. An unknown name gives `", stringify!($unknown), "` and writes")]
        /// nothing.
        ///
        /// # Safety
        /// `name` must be NULL or a NUL-terminated string; `out` NULL or writable.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $preset(name: *const c_char, out: *mut $params) -> hibi_status {
            // SAFETY: the caller's contract, passed on.
            $crate::guard::guard(|| unsafe {
                $crate::guard::write_preset(name, out, preset, to_c, $crate::status::$unknown)
            })
        }

        /// The presets' names, NUL-terminated, for C.
        static PRESET_NAMES: [[u8; $crate::object::PRESET_NAME_BYTES]; $list.len()] =
            $crate::object::nul_terminated($list);

        #[doc = concat!(" The name of preset `index` (", $presets, "), a static NUL-terminated string for")]
        #[doc = concat!(" `", stringify!($preset), "`, or NULL past the last: list them by counting up from 0")]
        /// until NULL.
        #[unsafe(no_mangle)]
        pub extern "C" fn $preset_name(index: usize) -> *const c_char {
            $crate::guard::guard(|| match PRESET_NAMES.get(index) {
                Some(name) => name.as_ptr().cast::<c_char>(),
                None => core::ptr::null(),
            })
        }

        #[doc = concat!(" Checks `params` and writes the bytes a ", $what, " needs in caller memory (for")]
        #[doc = concat!(" `", stringify!($create_in), "`). Every parameter error is reported here.")]
        $(#[doc = concat!(" ", $only_create)])?
        ///
        /// # Safety
        /// `params` must be NULL or readable; `size` NULL or writable.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $memory_size(params: *const $params, size: *mut usize) -> hibi_status {
            // SAFETY: the caller's contract, passed on.
            $crate::guard::guard(|| unsafe { $crate::object::memory_size::<$object>(params, size) })
        }

        #[doc = concat!(" Alignment, in bytes, that caller memory for `", stringify!($create_in), "` must have (8).")]
        #[unsafe(no_mangle)]
        pub extern "C" fn $memory_align() -> usize {
            $crate::guard::guard(|| $crate::object::BLOCK_ALIGN)
        }

        #[doc = concat!(" Creates a ", $what, " in library memory: ", $created, ".")]
        #[doc = concat!(" Free it with `", stringify!($destroy), "`. `*out` is written only on success. Every array")]
        /// it computes in is in its block: the calling thread's stack needs no more than 16 KiB.
        ///
        /// # Safety
        /// `params` must be NULL or readable; `out` NULL or writable.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $create(params: *const $params, out: *mut *mut $object) -> hibi_status {
            // SAFETY: the caller's contract, passed on.
            $crate::guard::guard(|| unsafe { $crate::object::create(params, out) })
        }

        #[doc = concat!(" Creates a ", $what, " in caller memory of at least `", stringify!($memory_size), "` bytes")]
        #[doc = concat!(" aligned to `", stringify!($memory_align), "()`, as `", stringify!($create), "` does. The memory stays")]
        #[doc = concat!(" the caller's (keep it untouched while the ", $what, " lives); `", stringify!($destroy), "` is")]
        /// optional. Nothing is written on failure.
        $(#[doc = concat!(" ", $only_create)])?
        ///
        /// # Safety
        /// `params` must be NULL or readable; `memory` NULL or writable for `memory_len` bytes;
        /// `out` NULL or writable.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $create_in(
            params: *const $params,
            memory: *mut c_void,
            memory_len: usize,
            out: *mut *mut $object,
        ) -> hibi_status {
            // SAFETY: the caller's contract, passed on.
            $crate::guard::guard(|| unsafe { $crate::object::create_in(params, memory, memory_len, out) })
        }

        #[doc = concat!(" Destroys a ", $what, "; frees its memory if `", stringify!($create), "` allocated it.")]
        /// NULL is ignored.
        ///
        /// # Safety
        #[doc = concat!(" `", stringify!($arg), "` must be NULL or a live ", $what, ", not used afterwards.")]
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $destroy($arg: *mut $object) {
            // SAFETY: the caller's contract, passed on.
            const NAME: &core::ffi::CStr =
                match core::ffi::CStr::from_bytes_with_nul(concat!(stringify!($arg), "\0").as_bytes()) {
                    Ok(name) => name,
                    Err(_) => c"",
                };
            $crate::guard::guard(|| unsafe { $crate::object::destroy($arg, NAME) })
        }

        /// Every preset comes with the cookie and converts back to the core's; an unknown or
        /// non-UTF-8 name gives the model's status and NULL pointers are refused, each writing
        /// nothing; the defaults convert back to the core's.
        #[cfg(test)]
        #[test]
        fn presets_come_with_the_cookie_and_unknown_names_write_nothing() {
            let mut p = $default();
            p.seed = 77;
            let before = format!("{p:?}");
            // SAFETY: valid or NULL pointers, NUL-terminated names.
            unsafe {
                assert_eq!($preset(c"fig99".as_ptr(), &mut p), $crate::status::$unknown);
                assert_eq!($preset(c"\xff".as_ptr(), &mut p), $crate::status::$unknown);
                assert_eq!(format!("{p:?}"), before, "nothing written");
                let first = std::ffi::CString::new($list[0]).unwrap();
                assert_eq!($preset(first.as_ptr(), core::ptr::null_mut()), $crate::status::HIBI_ERROR_NULL_POINTER);
                assert_eq!($preset(core::ptr::null(), &mut p), $crate::status::HIBI_ERROR_NULL_POINTER);
                assert_eq!(format!("{p:?}"), before, "nothing written");
                for name in $list {
                    let c_name = std::ffi::CString::new(name).unwrap();
                    assert_eq!($preset(c_name.as_ptr(), &mut p), $crate::status::HIBI_OK, "{name}");
                    assert_eq!(from_c(&p), Ok(preset(name).unwrap()), "{name}");
                }
            }
            assert_eq!(from_c(&$default()), Ok(<$core>::default()));
        }

        /// The preset names C lists are the core's, in its order, each accepted by
        #[doc = concat!(" `", stringify!($preset), "`; NULL follows the last.")]
        #[cfg(test)]
        #[test]
        fn preset_names_list_every_preset_then_null() {
            let mut p = $default();
            for (i, name) in $list.iter().enumerate() {
                let listed = $preset_name(i);
                assert!(!listed.is_null(), "{name}");
                // SAFETY: a static NUL-terminated string.
                let listed = unsafe { core::ffi::CStr::from_ptr(listed) };
                assert_eq!(listed.to_str(), Ok(*name));
                // SAFETY: valid pointers.
                assert_eq!(unsafe { $preset(listed.as_ptr(), &mut p) }, $crate::status::HIBI_OK, "{name}");
            }
            assert!($preset_name($list.len()).is_null());
            assert!($preset_name(usize::MAX).is_null());
        }
    };
}
pub(crate) use lifecycle;

/// Room for a preset's name and its NUL (a longer name fails to compile).
pub(crate) const PRESET_NAME_BYTES: usize = 16;

/// The names of `list`, each NUL-terminated in [`PRESET_NAME_BYTES`] bytes.
pub(crate) const fn nul_terminated<const N: usize>(list: [&str; N]) -> [[u8; PRESET_NAME_BYTES]; N] {
    let mut out = [[0u8; PRESET_NAME_BYTES]; N];
    let mut i = 0;
    while i < N {
        let bytes = list[i].as_bytes();
        assert!(bytes.len() < PRESET_NAME_BYTES, "a preset name too long for PRESET_NAME_BYTES");
        let mut j = 0;
        while j < bytes.len() {
            assert!(bytes[j] != 0, "a NUL inside a preset name");
            out[i][j] = bytes[j];
            j += 1;
        }
        i += 1;
    }
    out
}
