//! Where C-held objects live: in memory the library allocates (`*_create` / `*_destroy`) or
//! in memory the caller hands in (`*_memory_size` + `*_create_in`), as engines with their own
//! allocators need. An object is a header (the Rust value) followed, for the models, by the
//! arrays it computes in, all in one block.

use core::ffi::c_void;
use std::alloc::{Layout, alloc, dealloc};

use crate::status::{
    HIBI_ERROR_BUFFER_TOO_SMALL, HIBI_ERROR_MISALIGNED, HIBI_ERROR_NULL_POINTER, HIBI_ERROR_OUT_OF_MEMORY,
    HIBI_ERROR_SIZE_OVERFLOW, hibi_status,
};

/// Who owns an object's block, recorded in the object so that `*_destroy` frees only what
/// the library allocated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Origin {
    /// Allocated by `*_create` with this size and alignment; `*_destroy` frees it.
    Library {
        /// Block size in bytes.
        size: usize,
        /// Block alignment in bytes.
        align: usize,
    },
    /// Placed in caller memory by `*_create_in`; `*_destroy` only drops it.
    Caller,
}

/// Checks caller memory for a block of `size` bytes aligned to `align`.
pub(crate) fn caller_block(memory: *mut c_void, len: usize, size: usize, align: usize) -> Result<*mut u8, hibi_status> {
    let ptr = memory.cast::<u8>();
    if ptr.is_null() {
        return Err(HIBI_ERROR_NULL_POINTER);
    }
    if ptr.align_offset(align) != 0 {
        return Err(HIBI_ERROR_MISALIGNED);
    }
    if len < size {
        return Err(HIBI_ERROR_BUFFER_TOO_SMALL);
    }
    Ok(ptr)
}

/// Allocates a block; the origin to record in the object placed there.
pub(crate) fn library_block(size: usize, align: usize) -> Result<(*mut u8, Origin), hibi_status> {
    let layout = Layout::from_size_align(size.max(1), align).map_err(|_| HIBI_ERROR_SIZE_OVERFLOW)?;
    // SAFETY: the layout has a non-zero size.
    let ptr = unsafe { alloc(layout) };
    if ptr.is_null() {
        return Err(HIBI_ERROR_OUT_OF_MEMORY);
    }
    Ok((ptr, Origin::Library { size: size.max(1), align }))
}

/// Frees a block allocated by [`library_block`] if `origin` says so; nothing for caller memory.
///
/// # Safety
/// `ptr` must be the start of a block whose origin is `origin`, not used afterwards.
pub(crate) unsafe fn release_block(ptr: *mut u8, origin: Origin) {
    if let Origin::Library { size, align } = origin {
        // SAFETY: allocated by library_block with this size and alignment (the caller's contract).
        unsafe { dealloc(ptr, Layout::from_size_align_unchecked(size, align)) };
    }
}

/// `size` rounded up to a multiple of `align` (a power of two).
pub(crate) const fn round_up(size: usize, align: usize) -> usize {
    (size + align - 1) & !(align - 1)
}

/// Places `n` elements of `size` bytes aligned to `align` at or after byte `at` of a block:
/// their offset and the end of the range; None on overflow.
pub(crate) fn place(at: usize, align: usize, n: usize, size: usize) -> Option<(usize, usize)> {
    let start = round_up(at, align);
    Some((start, start.checked_add(n.checked_mul(size)?)?))
}

/// Fills `n` elements of type `T` at `block + offset` with `T::default()` and returns them.
///
/// # Safety
/// The range must lie in the block, aligned for `T`, and outlive every use of the slice.
pub(crate) unsafe fn array<T: Default>(block: *mut u8, offset: usize, n: usize) -> &'static mut [T] {
    // SAFETY: the caller's contract; every element is written before the slice is made.
    unsafe {
        let start = block.add(offset).cast::<T>();
        for i in 0..n {
            start.add(i).write(T::default());
        }
        core::slice::from_raw_parts_mut(start, n)
    }
}
