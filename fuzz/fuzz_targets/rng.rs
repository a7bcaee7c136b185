//! The random streams through the C ABI: `hibi_rng_create` or `hibi_rng_create_in` (any
//! memory length and alignment), then draws with any arguments and buffer lengths.
#![no_main]

use core::ffi::c_void;

use arbitrary::{Result, Unstructured};
use hibi::*;
use hibi_fuzz::*;
use libfuzzer_sys::fuzz_target;

fn run(u: &mut Unstructured) -> Result<()> {
    let (seed, stream): (u64, u64) = (u.arbitrary()?, u.arbitrary()?);
    let dangling = core::ptr::NonNull::<hibi_rng>::dangling().as_ptr();
    let mut rng = dangling;
    let mut memory = Vec::new();
    if u.arbitrary()? {
        // SAFETY: a writable pointer.
        assert!(check(unsafe { hibi_rng_create(seed, stream, &mut rng) }));
    } else {
        let (size, align) = (hibi_rng_memory_size(), hibi_rng_memory_align());
        let (m, ptr, len): (Vec<u64>, *mut c_void, usize) = caller_memory(u, size, align)?;
        memory = m;
        // SAFETY: `ptr` NULL or writable for `len` bytes.
        let status = unsafe { hibi_rng_create_in(seed, stream, ptr, len, &mut rng) };
        let fits = !ptr.is_null() && len >= size && (ptr as usize) % align == 0;
        if !check(status) {
            assert!(!fits && rng == dangling, "create_in refused memory that fits, or wrote");
            return Ok(());
        }
        assert!(fits);
    }
    let result = (|| {
        for _ in 0..16 {
            match u.int_in_range(0u8..=4)? {
                0 => {
                    let mut x = 0u32;
                    // SAFETY: a live stream.
                    assert!(check(unsafe { hibi_rng_next_u32(rng, &mut x) }));
                }
                1 | 2 => {
                    let uniform = u.arbitrary()?;
                    let len = length(u, 16, 64)?;
                    let mut values = Buffer::pick(u, len, len, 4)?;
                    let n = if u.ratio(1u8, 32)? { usize::MAX / 2 } else { values.len };
                    // SAFETY: `values` NULL or writable for `values.len` floats (a huge `n`
                    // must be refused before anything is written).
                    let status = unsafe {
                        if uniform {
                            hibi_rng_uniform(rng, values.ptr(), n)
                        } else {
                            hibi_rng_normal(rng, values.ptr(), n)
                        }
                    };
                    if check(status) {
                        assert!(n == values.len && values.fits(n, 4).0 && values.untouched_past(n));
                        for i in 0..n {
                            let v: f32 = values.get(i);
                            assert!(v.is_finite() && (!uniform || (0.0..1.0).contains(&v)), "{v}");
                        }
                    } else {
                        assert!(n != values.len || !values.fits(n, 4).1, "refused: {status}");
                        assert!(values.untouched());
                    }
                }
                3 => {
                    let mean = match u.int_in_range(0u8..=3)? {
                        0 => f64::from_bits(u.arbitrary()?),
                        1 => f64::from(float(u, 10.0)?),
                        _ => f64::from(u.int_in_range(0u32..=2_000_000)?) / 2.0,
                    };
                    let mut x = u32::MAX;
                    // SAFETY: a live stream.
                    let status = unsafe { hibi_rng_poisson(rng, mean, &mut x) };
                    let valid = mean.is_finite() && (0.0..=1e6).contains(&mean);
                    assert_eq!(check(status), valid, "poisson({mean}): {status}");
                    if !valid {
                        assert!(status == HIBI_ERROR_POISSON_MEAN && x == u32::MAX);
                    }
                }
                _ => {
                    let x = float(u, 40.0)?;
                    let z = float(u, 0.3)?;
                    let spread = enumeration(u, 2)?;
                    let mut v = f32::NAN;
                    // SAFETY: a live stream.
                    let status = unsafe { hibi_rng_rand(rng, x, z, spread, &mut v) };
                    // Refused too: a range whose far end (1 + z)·|x| is past FLT_MAX.
                    let fits = (1.0 + f64::from(z)) * f64::from(x).abs() <= f64::from(f32::MAX);
                    let valid = x.is_finite() && (0.0..1.0).contains(&z) && fits && spread < 2;
                    assert_eq!(check(status), valid, "rand({x}, {z}, {spread}): {status}");
                    if valid {
                        // The range's ends in f64, each rounded to f32 as the draw is: rounding
                        // keeps order, so the draw lies between them.
                        let (x64, z64) = (f64::from(x), f64::from(z));
                        let (a, b) = (((1.0 - z64) * x64) as f32, ((1.0 + z64) * x64) as f32);
                        assert!(v.is_finite() && v >= a.min(b) && v <= a.max(b), "rand({x}, {z}) = {v}");
                    } else {
                        assert!(v.is_nan());
                    }
                }
            }
        }
        Ok(())
    })();
    if memory.is_empty() || u.arbitrary().unwrap_or(true) {
        // SAFETY: a live stream, not used afterwards.
        unsafe { hibi_rng_destroy(rng) };
    }
    drop(memory);
    result
}

fuzz_target!(|data: &[u8]| {
    let _ = run(&mut Unstructured::new(data));
});
