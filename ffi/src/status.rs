//! `hibi_status`: what every fallible function returns, and its message.

use core::ffi::{CStr, c_char};

use hibi_core::RngError;

use crate::guard::guard;

/// The result of a fallible call: `HIBI_OK` (0) or one of the `HIBI_ERROR_*` codes.
/// Codes below 256 are about the call itself (pointers, buffers, enums); codes from 256 up
/// name the argument or parameter field that is wrong. `hibi_status_string` gives the message.
pub type hibi_status = u32;

/// Success.
pub const HIBI_OK: hibi_status = 0;
/// A required pointer argument is NULL.
pub const HIBI_ERROR_NULL_POINTER: hibi_status = 1;
/// A pointer argument is not aligned for the type it points to.
pub const HIBI_ERROR_MISALIGNED: hibi_status = 2;
/// A caller buffer is shorter than the call needs.
pub const HIBI_ERROR_BUFFER_TOO_SMALL: hibi_status = 3;
/// An enumeration passed as an integer has no such value.
pub const HIBI_ERROR_BAD_ENUM: hibi_status = 4;
/// The library could not allocate the memory an object needs.
pub const HIBI_ERROR_OUT_OF_MEMORY: hibi_status = 5;
/// A buffer length in elements overflows the address space when converted to bytes.
pub const HIBI_ERROR_SIZE_OVERFLOW: hibi_status = 6;
/// An internal error: a panic inside hibi was caught at the C boundary (a bug; please report).
pub const HIBI_ERROR_PANIC: hibi_status = 7;
/// `hibi_rng_poisson`: the mean is negative, not finite, or above 1e6.
pub const HIBI_ERROR_POISSON_MEAN: hibi_status = 256;
/// `hibi_rng_rand`: x is not finite or z is outside [0, 1).
pub const HIBI_ERROR_RAND_ARGUMENT: hibi_status = 257;

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
        _ => c"unknown status code",
    }
}

/// A static, NUL-terminated English message for `status`; never NULL (unknown codes give
/// "unknown status code"). The string lives as long as the library.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_status_string(status: hibi_status) -> *const c_char {
    guard(|| message(status).as_ptr())
}
