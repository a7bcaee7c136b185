//! Parameter validation of the three models through the C ABI: presets by any name, params
//! with any field values (cookie-correct or not), `*_memory_size` with NULL arguments, and
//! every status's message. Cheap: no object is created.
#![no_main]

use arbitrary::{Result, Unstructured};
use hibi::*;
use hibi_fuzz::*;
use libfuzzer_sys::fuzz_target;

/// Calls `memory_size` on `params` (or NULL) into a sentinel (or NULL); checks the contract.
fn memory_size<P: core::fmt::Debug>(
    u: &mut Unstructured,
    params: &P,
    size: unsafe extern "C" fn(*const P, *mut usize) -> hibi_status,
) -> Result<()> {
    let null_params = u.ratio(1u8, 32)?;
    let null_size = u.ratio(1u8, 32)?;
    let mut out = usize::MAX - 7;
    let p: *const P = if null_params { core::ptr::null() } else { params };
    let o: *mut usize = if null_size { core::ptr::null_mut() } else { &mut out };
    // SAFETY: valid or NULL pointers.
    let status = unsafe { size(p, o) };
    if status == HIBI_ERROR_PANIC {
        eprintln!("panic on {params:?}");
    }
    if check(status) {
        assert!(!null_params && !null_size);
        assert!(out > 0 && out != usize::MAX - 7);
    } else {
        assert_eq!(out, usize::MAX - 7, "a failing memory_size wrote its output");
        if null_params || null_size {
            assert_eq!(status, HIBI_ERROR_NULL_POINTER);
        }
    }
    Ok(())
}

fn run(u: &mut Unstructured) -> Result<()> {
    match u.int_in_range(0u8..=3)? {
        0 => {
            let p = mud_params(u)?;
            memory_size(u, &p, hibi_mud_memory_size)?
        }
        1 => {
            let p = glass_params(u)?;
            memory_size(u, &p, hibi_glass_memory_size)?
        }
        2 => {
            let p = skin_params(u)?;
            memory_size(u, &p, hibi_skin_memory_size)?
        }
        _ => {
            // Messages of any code; NULL names and NULL outputs of the presets.
            let status: u32 = u.arbitrary()?;
            // SAFETY: static strings.
            assert!(!unsafe { core::ffi::CStr::from_ptr(hibi_status_string(status)) }.is_empty());
            let name = name(u, MUD_PRESETS)?;
            let name = if u.ratio(1u8, 8)? { core::ptr::null() } else { name.as_ptr().cast() };
            // SAFETY: NULL or NUL-terminated names; NULL outputs.
            let refused = unsafe {
                [
                    hibi_mud_params_preset(name, core::ptr::null_mut()),
                    hibi_glass_params_preset(name, core::ptr::null_mut()),
                    hibi_skin_params_preset(name, core::ptr::null_mut()),
                ]
            };
            for status in refused {
                assert!(!check(status));
            }
        }
    }
    Ok(())
}

fuzz_target!(|data: &[u8]| {
    let _ = run(&mut Unstructured::new(data));
});
