//! The one guard every exported function runs in, and the checks of what C hands in.
//!
//! [`guard`] catches any panic so that none unwinds into C (which is undefined behaviour) and
//! turns it into `HIBI_ERROR_PANIC` or the function's neutral value. The pointer helpers turn
//! NULL, misaligned and overflowing arguments into statuses before anything is touched.

use core::ffi::c_char;
use core::mem::{align_of, size_of};
use std::panic::{AssertUnwindSafe, catch_unwind};

use crate::status::{
    HIBI_ERROR_MISALIGNED, HIBI_ERROR_NULL_POINTER, HIBI_ERROR_PANIC, HIBI_ERROR_SIZE_OVERFLOW, HIBI_OK, hibi_status,
    message,
};

/// What an exported function's body gives back, and what C sees instead if it panics.
pub trait Outcome {
    /// The C return type.
    type C;
    /// The value C sees on success.
    fn into_c(self) -> Self::C;
    /// The value C sees when the body panicked.
    fn on_panic() -> Self::C;
}

impl Outcome for Result<(), hibi_status> {
    type C = hibi_status;
    fn into_c(self) -> hibi_status {
        self.err().unwrap_or(HIBI_OK)
    }
    fn on_panic() -> hibi_status {
        HIBI_ERROR_PANIC
    }
}

impl Outcome for () {
    type C = ();
    fn into_c(self) {}
    fn on_panic() {}
}

impl Outcome for usize {
    type C = usize;
    fn into_c(self) -> usize {
        self
    }
    fn on_panic() -> usize {
        0
    }
}

impl Outcome for *const c_char {
    type C = *const c_char;
    fn into_c(self) -> *const c_char {
        self
    }
    fn on_panic() -> *const c_char {
        message(HIBI_ERROR_PANIC).as_ptr()
    }
}

/// Runs an exported function's body; no panic crosses into C.
pub(crate) fn guard<T: Outcome>(body: impl FnOnce() -> T) -> T::C {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(outcome) => outcome.into_c(),
        Err(_) => T::on_panic(),
    }
}

/// Checks that `ptr` is non-null and aligned for `T`.
pub(crate) fn check_pointer<T>(ptr: *const T) -> Result<(), hibi_status> {
    if ptr.is_null() {
        Err(HIBI_ERROR_NULL_POINTER)
    } else if !ptr.cast::<u8>().align_offset(align_of::<T>()).eq(&0) {
        Err(HIBI_ERROR_MISALIGNED)
    } else {
        Ok(())
    }
}

/// The object behind a handle passed in by C.
///
/// # Safety
/// A non-null, aligned `ptr` must point to a live `T` that nothing else uses during the call.
pub(crate) unsafe fn object<'a, T>(ptr: *mut T) -> Result<&'a mut T, hibi_status> {
    check_pointer(ptr)?;
    // SAFETY: non-null and aligned (checked); liveness and exclusivity are the caller's contract.
    Ok(unsafe { &mut *ptr })
}

/// The object behind a `const` handle passed in by C, for the read-only functions: a shared
/// reference, so that threads may call them on one object at once.
///
/// # Safety
/// A non-null, aligned `ptr` must point to a live `T` that nothing mutates during the call.
pub(crate) unsafe fn object_ref<'a, T>(ptr: *const T) -> Result<&'a T, hibi_status> {
    check_pointer(ptr)?;
    // SAFETY: non-null and aligned (checked); liveness and no concurrent mutation are the
    // caller's contract.
    Ok(unsafe { &*ptr })
}

/// The body of the `hibi_*_params_preset` functions: looks `name` up with `preset` and writes
/// its C form to `*out`; an unknown name gives `unknown` and writes nothing.
///
/// # Safety
/// `name` must be NULL or a NUL-terminated string; `out` NULL or writable.
pub(crate) unsafe fn write_preset<P, C>(
    name: *const core::ffi::c_char,
    out: *mut C,
    preset: impl FnOnce(&str) -> Option<P>,
    to_c: impl FnOnce(&P) -> C,
    unknown: hibi_status,
) -> Result<(), hibi_status> {
    check_pointer(name)?;
    check_pointer(out)?;
    // SAFETY: non-null (checked); NUL-terminated by the caller's contract.
    let name = unsafe { core::ffi::CStr::from_ptr(name) };
    let params = name.to_str().ok().and_then(preset).ok_or(unknown)?;
    // SAFETY: checked; the caller's contract.
    unsafe { write_out(out, to_c(&params)) }
}

/// Writes `value` through an out-parameter. Call it only once everything else succeeded, so
/// that nothing is written on failure.
///
/// # Safety
/// A non-null, aligned `ptr` must be valid for a write of `T`.
pub(crate) unsafe fn write_out<T>(ptr: *mut T, value: T) -> Result<(), hibi_status> {
    check_pointer(ptr)?;
    // SAFETY: non-null and aligned (checked); validity is the caller's contract.
    unsafe { ptr.write(value) };
    Ok(())
}

/// Checks a caller buffer of `len` elements of `T` at a non-empty `ptr`: non-null, aligned,
/// and its size in bytes fits `isize`.
fn check_buffer<T>(ptr: *const T, len: usize) -> Result<(), hibi_status> {
    check_pointer(ptr)?;
    if len.checked_mul(size_of::<T>()).is_none_or(|bytes| bytes > isize::MAX as usize) {
        return Err(HIBI_ERROR_SIZE_OVERFLOW);
    }
    Ok(())
}

/// The caller buffer `ptr[0..len]`; NULL is accepted for an empty buffer.
///
/// # Safety
/// A non-null, aligned `ptr` must be valid for reads and writes of `len` elements of `T`, not
/// aliased during the call.
pub(crate) unsafe fn buffer<'a, T>(ptr: *mut T, len: usize) -> Result<&'a mut [T], hibi_status> {
    if len == 0 {
        return Ok(&mut []);
    }
    check_buffer(ptr, len)?;
    // SAFETY: non-null, aligned, size fits isize (checked); validity is the caller's contract.
    Ok(unsafe { core::slice::from_raw_parts_mut(ptr, len) })
}

/// The read-only caller buffer `ptr[0..len]`; NULL is accepted for an empty buffer.
///
/// # Safety
/// A non-null, aligned `ptr` must be valid for reads of `len` elements of `T`, not written
/// during the call.
pub(crate) unsafe fn input<'a, T>(ptr: *const T, len: usize) -> Result<&'a [T], hibi_status> {
    if len == 0 {
        return Ok(&[]);
    }
    check_buffer(ptr, len)?;
    // SAFETY: non-null, aligned, size fits isize (checked); validity is the caller's contract.
    Ok(unsafe { core::slice::from_raw_parts(ptr, len) })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::status::HIBI_ERROR_BUFFER_TOO_SMALL;

    #[test]
    fn a_panic_becomes_a_status_and_never_unwinds() {
        let status = guard(|| -> Result<(), hibi_status> { panic!("deliberate") });
        assert_eq!(status, HIBI_ERROR_PANIC);
        assert_eq!(guard(|| -> usize { panic!("deliberate") }), 0);
        assert_eq!(guard(|| Err(HIBI_ERROR_BUFFER_TOO_SMALL)), HIBI_ERROR_BUFFER_TOO_SMALL);
        assert_eq!(guard(|| Ok(())), HIBI_OK);
    }

    #[test]
    fn pointer_checks_name_the_problem() {
        let mut words = [0u32; 4];
        let base = words.as_mut_ptr();
        assert_eq!(check_pointer(core::ptr::null::<u32>()), Err(HIBI_ERROR_NULL_POINTER));
        assert_eq!(check_pointer(base.cast::<u8>().wrapping_add(1).cast::<u32>()), Err(HIBI_ERROR_MISALIGNED));
        assert_eq!(check_pointer(base), Ok(()));
        // SAFETY: a null pointer with length 0 is the empty buffer; no access happens.
        assert_eq!(unsafe { buffer(core::ptr::null_mut::<u32>(), 0) }.map(|b| b.len()), Ok(0));
        // SAFETY: the checks fail before any access.
        assert_eq!(unsafe { buffer(base, usize::MAX / 2) }.err(), Some(HIBI_ERROR_SIZE_OVERFLOW));
        // SAFETY: `words` is valid for 4 u32.
        assert_eq!(unsafe { buffer(base, 4) }.map(|b| b.len()), Ok(4));
        // SAFETY: as above, read only; the failing checks happen before any access.
        unsafe {
            assert_eq!(input(core::ptr::null::<u32>(), 0).map(<[u32]>::len), Ok(0));
            assert_eq!(input(core::ptr::null::<u32>(), 1).err(), Some(HIBI_ERROR_NULL_POINTER));
            assert_eq!(input(base.cast_const(), usize::MAX / 2).err(), Some(HIBI_ERROR_SIZE_OVERFLOW));
            assert_eq!(input(base.cast_const(), 4).map(<[u32]>::len), Ok(4));
        }
    }
}
