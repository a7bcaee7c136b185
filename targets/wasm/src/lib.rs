//! The golden scenes as a WebAssembly module (see Cargo.toml).
#![no_std]

use core::fmt::Write;

#[link(wasm_import_module = "env")]
unsafe extern "C" {
    /// Prints `len` bytes of UTF-8 at `ptr` (the host reads them from the module's memory).
    fn hibi_print(ptr: *const u8, len: usize);
}

struct Out;

impl Write for Out {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        // SAFETY: the host only reads the `s.len()` bytes at `s.as_ptr()`.
        unsafe { hibi_print(s.as_ptr(), s.len()) };
        Ok(())
    }
}

/// Runs every scene and prints the report; returns how many scenes differ (`u32::MAX` if the
/// scenes' memory was already taken or the report could not be written).
#[unsafe(no_mangle)]
pub extern "C" fn hibi_scenes_run() -> u32 {
    let Some(mut memory) = hibi_scenes::Memory::take() else {
        return u32::MAX;
    };
    // SAFETY: the module's stack is its first MiB of linear memory (the linker's default),
    // growing down; this call is its outermost frame, so the STACK_MEASURED bytes below it are
    // that stack's, unused.
    let (differ, peak) = unsafe {
        hibi_scenes::stack::measured(STACK_MEASURED, || hibi_scenes::check(&mut memory, "wasm32-unknown-unknown", &mut Out))
    };
    let _ = writeln!(Out, "stack peak {peak} bytes (painted below the scenes' caller)");
    differ.map_or(u32::MAX, |n| n as u32)
}

/// Bytes of stack painted below the scenes' caller: far more than the scenes need (about
/// 32 KiB), within the module's 1 MiB stack.
const STACK_MEASURED: usize = 512 * 1024;

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    let _ = writeln!(Out, "panic: {info}");
    core::arch::wasm32::unreachable()
}
