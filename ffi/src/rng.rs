//! `hibi_rng`: the deterministic random source, exported so that C can drive the frame end
//! to end and draw numbers that match hibi's own streams bit for bit.

use core::ffi::c_void;
use core::mem::{align_of, size_of};

use hibi_core::{Rng, Spread};

use crate::guard::{buffer, guard, object, write_out};
use crate::memory::{Origin, place_in, place_new, release};
use crate::status::{HIBI_ERROR_BAD_ENUM, hibi_status, rng_status};

/// `Rand(x)` spread: uniform over [(1 − z)x, (1 + z)x].
pub const HIBI_SPREAD_UNIFORM: u32 = 0;
/// `Rand(x)` spread: normal, σ = z·x/3, redrawn until within [(1 − z)x, (1 + z)x].
pub const HIBI_SPREAD_NORMAL: u32 = 1;
const _: () = assert!(
    HIBI_SPREAD_UNIFORM == Spread::Uniform as u32 && HIBI_SPREAD_NORMAL == Spread::Normal as u32
);

/// A random stream (Xoshiro128++ seeded through SplitMix64). Opaque.
pub struct hibi_rng {
    rng: Rng,
    origin: Origin,
}

/// Bytes a `hibi_rng` needs in caller memory (for `hibi_rng_create_in`).
#[unsafe(no_mangle)]
pub extern "C" fn hibi_rng_memory_size() -> usize {
    guard(size_of::<hibi_rng>)
}

/// Alignment, in bytes, that caller memory for `hibi_rng_create_in` must have.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_rng_memory_align() -> usize {
    guard(align_of::<hibi_rng>)
}

/// Creates the stream `stream` of the run seeded with `seed`, in library memory; free it
/// with `hibi_rng_destroy`. `*out` is written only on success.
///
/// # Safety
/// `out` must be NULL or valid for writing a pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_create(
    seed: u64,
    stream: u64,
    out: *mut *mut hibi_rng,
) -> hibi_status {
    guard(|| {
        crate::guard::check_pointer(out)?;
        let rng = place_new(hibi_rng {
            rng: Rng::from_key(seed, stream),
            origin: Origin::Library,
        })?;
        // SAFETY: checked above; the caller's contract.
        unsafe { write_out(out, rng) }
    })
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
    guard(|| {
        crate::guard::check_pointer(out)?;
        let value = hibi_rng {
            rng: Rng::from_key(seed, stream),
            origin: Origin::Caller,
        };
        // SAFETY: the caller's contract on `memory`.
        let rng = unsafe { place_in(memory, memory_len, value) }?;
        // SAFETY: checked above; the caller's contract.
        unsafe { write_out(out, rng) }
    })
}

/// Destroys a stream; frees its memory if `hibi_rng_create` allocated it. NULL is ignored.
///
/// # Safety
/// `rng` must be NULL or a live stream, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_destroy(rng: *mut hibi_rng) {
    guard(|| {
        // SAFETY: the caller's contract.
        if let Ok(live) = unsafe { object(rng) } {
            let origin = live.origin;
            // SAFETY: made by place_new or place_in with this origin.
            unsafe { release(rng, origin) };
        }
    })
}

/// The next 32 raw bits of the stream.
///
/// # Safety
/// `rng` must be NULL or a live stream; `out` NULL or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_next_u32(rng: *mut hibi_rng, out: *mut u32) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let rng = unsafe { object(rng) }?;
        crate::guard::check_pointer(out)?;
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(out, rng.rng.next_u32()) }
    })
}

/// Fills `values[0..len]` with uniform draws in [0, 1).
///
/// # Safety
/// `rng` must be NULL or a live stream; `values` NULL (only with `len` 0) or valid for `len` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_uniform(
    rng: *mut hibi_rng,
    values: *mut f32,
    len: usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let (rng, values) = unsafe { (object(rng)?, buffer(values, len)?) };
        values.iter_mut().for_each(|v| *v = rng.rng.uniform_f32());
        Ok(())
    })
}

/// Fills `values[0..len]` with standard normal draws.
///
/// # Safety
/// As `hibi_rng_uniform`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_normal(
    rng: *mut hibi_rng,
    values: *mut f32,
    len: usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let (rng, values) = unsafe { (object(rng)?, buffer(values, len)?) };
        values.iter_mut().for_each(|v| *v = rng.rng.normal_f32());
        Ok(())
    })
}

/// A Poisson draw with mean `mean` (0 ≤ mean ≤ 1e6), exact.
///
/// # Safety
/// `rng` must be NULL or a live stream; `out` NULL or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_poisson(
    rng: *mut hibi_rng,
    mean: f64,
    out: *mut u32,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let rng = unsafe { object(rng) }?;
        crate::guard::check_pointer(out)?;
        let value = rng.rng.poisson(mean).map_err(rng_status)?;
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(out, value) }
    })
}

/// The papers' `Rand(x)`: a value within [(1 − z)x, (1 + z)x], `spread` one of
/// `HIBI_SPREAD_UNIFORM` or `HIBI_SPREAD_NORMAL`.
///
/// # Safety
/// `rng` must be NULL or a live stream; `out` NULL or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_rng_rand(
    rng: *mut hibi_rng,
    x: f32,
    z: f32,
    spread: u32,
    out: *mut f32,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let rng = unsafe { object(rng) }?;
        crate::guard::check_pointer(out)?;
        let spread = match spread {
            HIBI_SPREAD_UNIFORM => Spread::Uniform,
            HIBI_SPREAD_NORMAL => Spread::Normal,
            _ => return Err(HIBI_ERROR_BAD_ENUM),
        };
        let value = rng.rng.rand(x, z, spread).map_err(rng_status)?;
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(out, value) }
    })
}
