//! The stack a call uses, measured by painting: the words below the caller's frame are filled
//! with a pattern, the call runs, and the deepest word it overwrote gives its peak. One way for
//! every target that has no runtime of its own to do it (Cortex-M's `cortex-m-rt` paints its
//! whole stack at reset) and for the host's stack test.

/// What the painted words hold.
const PAINT: u64 = 0x5eed_57ac_c0de_d00d;

/// An address in the caller's frame (about its stack pointer).
#[inline(never)]
pub fn stack_pointer() -> usize {
    let marker = 0u8;
    core::hint::black_box(&marker) as *const u8 as usize
}

/// Paints the stack from `bottom` up to a little below this function's own frame.
///
/// # Safety
/// `[bottom, stack pointer)` must be this thread's stack, below every live frame.
#[inline(never)]
unsafe fn paint(bottom: usize) {
    let top = (stack_pointer() - 256) & !7;
    let mut at = bottom;
    while at < top {
        // SAFETY: the caller's promise: [bottom, top) is unused stack of this thread.
        unsafe { core::ptr::with_exposed_provenance_mut::<u64>(at).write_volatile(PAINT) };
        at += 8;
    }
}

/// The lowest address above `bottom` whose paint was overwritten.
///
/// # Safety
/// As for [`paint`], which must have painted from `bottom`.
#[inline(never)]
unsafe fn deepest(bottom: usize) -> usize {
    let mut at = bottom;
    // SAFETY: reads of this thread's stack below every live frame (the caller's promise).
    while unsafe { core::ptr::with_exposed_provenance::<u64>(at).read_volatile() } == PAINT {
        at += 8;
    }
    at
}

/// Runs `f` with `depth` bytes of stack painted below this frame; returns its result and the
/// bytes of stack it used, from this frame down (its own frames and all they called). A call
/// that used all `depth` bytes reports `depth`: its peak is at least that.
///
/// # Safety
/// The `depth` bytes below the caller's stack pointer must be this thread's stack (mapped,
/// and used by nothing but the calls `f` makes).
#[inline(never)]
pub unsafe fn measured<R>(depth: usize, f: impl FnOnce() -> R) -> (R, usize) {
    let base = stack_pointer();
    let bottom = (base - depth) & !7;
    // SAFETY: the caller's promise covers [bottom, base).
    unsafe { paint(bottom) };
    let result = core::hint::black_box(f());
    // SAFETY: as above; `paint` painted from `bottom`.
    let peak = base - unsafe { deepest(bottom) };
    (result, peak)
}
