//! `hibi_rng`: the deterministic random source, exported so that C can drive the frame end
//! to end and draw numbers that match hibi's own streams bit for bit.

use core::ffi::c_void;

use hibi_core::{Rng, Spread};

use crate::guard::{buffer, guard, object, write_out};
use crate::object::{self, Arena, BLOCK_ALIGN, Object, Origin};
use crate::status::{HIBI_ERROR_BAD_ENUM, hibi_status, refuse_argument, rng_status};

/// A random stream (Xoshiro128++ seeded through SplitMix64). Opaque.
pub struct hibi_rng {
    rng: Rng,
    origin: Origin,
}

impl Object for hibi_rng {
    type Input = (u64, u64);
    type Plan = (u64, u64);
    type Arrays = ();
    /// Unreachable: a stream's block has a fixed size.
    const TOO_LARGE: hibi_status = crate::status::HIBI_ERROR_SIZE_OVERFLOW;

    unsafe fn plan(key: (u64, u64)) -> Result<(u64, u64), hibi_status> {
        Ok(key)
    }

    fn arrays(_: &(u64, u64), _: &mut Arena) {}

    fn make(&(seed, stream): &(u64, u64), _: (), origin: Origin) -> Result<Self, hibi_status> {
        Ok(hibi_rng { rng: Rng::from_key(seed, stream), origin })
    }

    fn origin(&self) -> Origin {
        self.origin
    }
}

/// Bytes a `hibi_rng` needs in caller memory (for `hibi_rng_create_in`).
#[unsafe(no_mangle)]
pub extern "C" fn hibi_rng_memory_size() -> usize {
    // SAFETY: the input holds no pointer.
    guard(|| unsafe { object::block_size::<hibi_rng>((0, 0)) }.unwrap_or(0))
}

/// Alignment, in bytes, that caller memory for `hibi_rng_create_in` must have.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_rng_memory_align() -> usize {
    guard(|| BLOCK_ALIGN)
}

/// Creates the stream `stream` of the run seeded with `seed`, in library memory; free it
/// with `hibi_rng_destroy`. `*out` is written only on success.
///
/// # Safety
/// `out` must be NULL or valid for writing a pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_create(seed: u64, stream: u64, out: *mut *mut hibi_rng) -> hibi_status {
    // SAFETY: the caller's contract, passed on.
    guard(|| unsafe { object::create((seed, stream), out) })
}

/// Creates the stream in caller memory of at least `hibi_rng_memory_size()` bytes aligned to
/// `hibi_rng_memory_align()`. The memory stays the caller's; `hibi_rng_destroy` is optional.
/// `*out` is written only on success.
///
/// # Safety
/// `memory` must be NULL or valid for writes of `memory_len` bytes, untouched while the stream
/// lives; `out` must be NULL or valid for writing a pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_create_in(
    seed: u64,
    stream: u64,
    memory: *mut c_void,
    memory_len: usize,
    out: *mut *mut hibi_rng,
) -> hibi_status {
    // SAFETY: the caller's contract, passed on.
    guard(|| unsafe { object::create_in((seed, stream), memory, memory_len, out) })
}

/// Destroys a stream; frees its memory if `hibi_rng_create` allocated it. NULL is ignored.
///
/// # Safety
/// `rng` must be NULL or a live stream, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_destroy(rng: *mut hibi_rng) {
    // SAFETY: the caller's contract, passed on.
    guard(|| unsafe { object::destroy(rng, c"rng") })
}

/// The next 32 raw bits of the stream.
///
/// # Safety
/// `rng` must be NULL or a live stream; `out` NULL or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_next_u32(rng: *mut hibi_rng, out: *mut u32) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let rng = unsafe { object(rng, c"rng") }?;
        crate::guard::check_pointer(out, c"out")?;
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(out, c"out", rng.rng.next_u32()) }
    })
}

/// Fills `values[0..len]` with uniform draws in [0, 1).
///
/// # Safety
/// `rng` must be NULL or a live stream; `values` NULL (only with `len` 0) or valid for `len` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_uniform(rng: *mut hibi_rng, values: *mut f32, len: usize) -> hibi_status {
    // SAFETY: the caller's contract, passed on.
    unsafe { fill(rng, values, len, Rng::uniform_f32) }
}

/// Fills `values[0..len]` with standard normal draws.
///
/// # Safety
/// As `hibi_rng_uniform`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_normal(rng: *mut hibi_rng, values: *mut f32, len: usize) -> hibi_status {
    // SAFETY: the caller's contract, passed on.
    unsafe { fill(rng, values, len, Rng::normal_f32) }
}

/// Fills a caller buffer with draws of one distribution.
///
/// # Safety
/// As `hibi_rng_uniform`.
unsafe fn fill(rng: *mut hibi_rng, values: *mut f32, len: usize, draw: fn(&mut Rng) -> f32) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let (rng, values) = unsafe { (object(rng, c"rng")?, buffer(values, len, c"values")?) };
        values.iter_mut().for_each(|v| *v = draw(&mut rng.rng));
        Ok(())
    })
}

/// A Poisson draw with mean `mean` (0 ≤ mean ≤ 1e6), exact.
///
/// # Safety
/// `rng` must be NULL or a live stream; `out` NULL or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_poisson(rng: *mut hibi_rng, mean: f64, out: *mut u32) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let rng = unsafe { object(rng, c"rng") }?;
        crate::guard::check_pointer(out, c"out")?;
        let value = rng.rng.poisson(mean).map_err(rng_status)?;
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(out, c"out", value) }
    })
}

/// The papers' `Rand(x)`: a value within [(1 − z)x, (1 + z)x], `spread` one of
/// `HIBI_SPREAD_UNIFORM` or `HIBI_SPREAD_NORMAL`.
///
/// # Safety
/// `rng` must be NULL or a live stream; `out` NULL or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_rand(rng: *mut hibi_rng, x: f32, z: f32, spread: u32, out: *mut f32) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let rng = unsafe { object(rng, c"rng") }?;
        crate::guard::check_pointer(out, c"out")?;
        let spread = Spread::from_u32(spread).ok_or_else(|| refuse_argument(c"spread", HIBI_ERROR_BAD_ENUM))?;
        let value = rng.rng.rand(x, z, spread).map_err(rng_status)?;
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(out, c"out", value) }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::*;
    use crate::status::*;
    use core::ffi::CStr;
    use core::ptr::null_mut;

    fn create(seed: u64, stream: u64) -> *mut hibi_rng {
        let mut rng = null_mut();
        // SAFETY: `rng` is a valid out-pointer.
        assert_eq!(unsafe { hibi_rng_create(seed, stream, &mut rng) }, HIBI_OK);
        rng
    }

    #[test]
    fn draws_match_the_core_stream() {
        let rng = create(3, 99);
        let mut core = Rng::from_key(3, 99);
        let mut bits = 0;
        let mut values = [0.0f32; 5];
        // SAFETY: live stream and valid buffers throughout.
        unsafe {
            assert_eq!(hibi_rng_next_u32(rng, &mut bits), HIBI_OK);
            assert_eq!(bits, core.next_u32());
            assert_eq!(hibi_rng_uniform(rng, values.as_mut_ptr(), values.len()), HIBI_OK);
            assert_eq!(values, core::array::from_fn::<f32, 5, _>(|_| core.uniform_f32()));
            assert_eq!(hibi_rng_normal(rng, values.as_mut_ptr(), values.len()), HIBI_OK);
            assert_eq!(values, core::array::from_fn::<f32, 5, _>(|_| core.normal_f32()));
            hibi_rng_destroy(rng);
        }
    }

    #[test]
    fn failures_write_nothing_and_name_the_problem() {
        let rng = create(1, 2);
        let mut count = 77u32;
        let mut value = -1.0f32;
        // SAFETY: live stream; the failing calls are rejected before any access.
        unsafe {
            assert_eq!(hibi_rng_poisson(rng, f64::NAN, &mut count), HIBI_ERROR_POISSON_MEAN);
            assert_eq!(hibi_rng_poisson(rng, 1e7, &mut count), HIBI_ERROR_POISSON_MEAN);
            assert_eq!(count, 77);
            assert_eq!(hibi_rng_rand(rng, 1.0, 1.5, HIBI_SPREAD_UNIFORM, &mut value), HIBI_ERROR_RAND_ARGUMENT);
            assert_eq!(hibi_rng_rand(rng, 1.0, 0.5, 2, &mut value), HIBI_ERROR_BAD_ENUM);
            assert_eq!(value, -1.0);
            assert_eq!(hibi_rng_uniform(rng, null_mut(), 4), HIBI_ERROR_NULL_POINTER);
            assert_eq!(hibi_rng_uniform(rng, null_mut(), 0), HIBI_OK);
            assert_eq!(hibi_rng_next_u32(rng, null_mut()), HIBI_ERROR_NULL_POINTER);
            assert_eq!(hibi_rng_next_u32(null_mut(), &mut count), HIBI_ERROR_NULL_POINTER);
            assert_eq!(hibi_rng_create(0, 0, null_mut()), HIBI_ERROR_NULL_POINTER);
            hibi_rng_destroy(rng);
            hibi_rng_destroy(null_mut());
        }
    }

    #[test]
    fn caller_memory_is_checked_then_used() {
        let mut memory = [0u64; 8];
        assert!(hibi_rng_memory_size() <= size_of_val(&memory));
        assert!(hibi_rng_memory_align() <= align_of::<u64>());
        let base = memory.as_mut_ptr().cast::<c_void>();
        let mut out = null_mut();
        // SAFETY: `memory` outlives the stream; failing calls are rejected before any access.
        unsafe {
            let size = hibi_rng_memory_size();
            assert_eq!(hibi_rng_create_in(5, 6, null_mut(), size, &mut out), HIBI_ERROR_NULL_POINTER);
            assert_eq!(hibi_rng_create_in(5, 6, base, size - 1, &mut out), HIBI_ERROR_BUFFER_TOO_SMALL);
            let odd = base.cast::<u8>().add(1).cast::<c_void>();
            assert_eq!(hibi_rng_create_in(5, 6, odd, size, &mut out), HIBI_ERROR_MISALIGNED);
            assert!(out.is_null());
            assert_eq!(hibi_rng_create_in(5, 6, base, size, &mut out), HIBI_OK);
            assert_eq!(out.cast::<c_void>(), base);
            let mut bits = 0;
            assert_eq!(hibi_rng_next_u32(out, &mut bits), HIBI_OK);
            assert_eq!(bits, Rng::from_key(5, 6).next_u32());
            hibi_rng_destroy(out); // drops only; the memory stays ours
        }
    }

    #[test]
    fn every_status_has_its_own_message() {
        let codes = [
            HIBI_OK,
            HIBI_ERROR_NULL_POINTER,
            HIBI_ERROR_MISALIGNED,
            HIBI_ERROR_BUFFER_TOO_SMALL,
            HIBI_ERROR_BAD_ENUM,
            HIBI_ERROR_OUT_OF_MEMORY,
            HIBI_ERROR_SIZE_OVERFLOW,
            HIBI_ERROR_PANIC,
            HIBI_ERROR_POISSON_MEAN,
            HIBI_ERROR_RAND_ARGUMENT,
        ];
        // SAFETY: hibi_status_string returns static NUL-terminated strings.
        let text = |code| unsafe { CStr::from_ptr(hibi_status_string(code)) }.to_str().unwrap();
        for (i, a) in codes.iter().enumerate() {
            assert_ne!(text(*a), "unknown status code");
            for b in &codes[i + 1..] {
                assert_ne!(text(*a), text(*b));
            }
        }
        assert_eq!(text(9999), "unknown status code");
        // SAFETY: static NUL-terminated string.
        let version = unsafe { CStr::from_ptr(crate::hibi_version()) };
        assert_eq!(version.to_str(), Ok(env!("CARGO_PKG_VERSION")));
    }
}
