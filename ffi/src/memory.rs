//! Where C-held objects live: in memory the library allocates (`*_create` / `*_destroy`) or
//! in memory the caller hands in (`*_memory_size` + `*_create_in`), as engines with their own
//! allocators need.

use core::ffi::c_void;
use core::mem::size_of;
use std::alloc::{Layout, alloc, dealloc};

use crate::guard::check_pointer;
use crate::status::{HIBI_ERROR_BUFFER_TOO_SMALL, HIBI_ERROR_OUT_OF_MEMORY, hibi_status};

/// Who owns an object's memory, recorded in the object so that `*_destroy` frees only what
/// the library allocated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Origin {
    /// Allocated by `*_create`; `*_destroy` frees it.
    Library,
    /// Placed in caller memory by `*_create_in`; `*_destroy` only drops it.
    Caller,
}

/// Moves `value` into caller memory, checking pointer, alignment and length first.
///
/// # Safety
/// A non-null `memory` must be valid for writes of `memory_len` bytes and stay untouched by
/// the caller while the object lives.
pub(crate) unsafe fn place_in<T>(
    memory: *mut c_void,
    memory_len: usize,
    value: T,
) -> Result<*mut T, hibi_status> {
    let ptr = memory.cast::<T>();
    check_pointer(ptr)?;
    if memory_len < size_of::<T>() {
        return Err(HIBI_ERROR_BUFFER_TOO_SMALL);
    }
    // SAFETY: non-null, aligned, long enough (checked); validity is the caller's contract.
    unsafe { ptr.write(value) };
    Ok(ptr)
}

/// Moves `value` into memory the library allocates; `HIBI_ERROR_OUT_OF_MEMORY` if it can't.
pub(crate) fn place_new<T>(value: T) -> Result<*mut T, hibi_status> {
    let layout = Layout::new::<T>();
    // SAFETY: every object type placed here has a non-zero size.
    let ptr = unsafe { alloc(layout) }.cast::<T>();
    if ptr.is_null() {
        return Err(HIBI_ERROR_OUT_OF_MEMORY);
    }
    // SAFETY: freshly allocated with T's layout.
    unsafe { ptr.write(value) };
    Ok(ptr)
}

/// Drops the object, and frees its memory if the library allocated it.
///
/// # Safety
/// `ptr` must come from [`place_new`] or [`place_in`] with `origin` recorded truthfully, and
/// must not be used afterwards.
pub(crate) unsafe fn release<T>(ptr: *mut T, origin: Origin) {
    // SAFETY: the caller's contract: a live object made by place_new or place_in.
    unsafe { ptr.drop_in_place() };
    if origin == Origin::Library {
        // SAFETY: allocated by place_new with this layout.
        unsafe { dealloc(ptr.cast(), Layout::new::<T>()) };
    }
}
