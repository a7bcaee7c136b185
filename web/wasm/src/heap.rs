//! The module's allocator: one free list per power-of-two size class over memory taken from
//! `memory.grow`. A block keeps its class for the module's life, so a model freed and made
//! again with the same sizes reuses the same blocks (wasm memory never shrinks; it stays
//! flat over create/free cycles). Single-threaded, as a wasm32-unknown-unknown instance is.

use core::alloc::{GlobalAlloc, Layout};
use core::cell::UnsafeCell;

/// Size classes: 2^4 to 2^31 bytes.
const CLASSES: usize = 32;
const PAGE: usize = 65536;

struct State {
    /// The first free block of each class (0: none); a free block's first word links the next.
    free: [usize; CLASSES],
    /// The untouched memory taken from `memory.grow`: `next..end`.
    next: usize,
    end: usize,
}

pub struct Heap(UnsafeCell<State>);

// SAFETY: a wasm32-unknown-unknown instance runs one thread.
unsafe impl Sync for Heap {}

impl Heap {
    pub const fn new() -> Self {
        Heap(UnsafeCell::new(State { free: [0; CLASSES], next: 0, end: 0 }))
    }
}

/// The class of a layout: the power of two that holds its size and its alignment.
fn class(layout: Layout) -> Option<usize> {
    let size = layout.size().max(layout.align()).max(16).checked_next_power_of_two()?;
    let class = size.trailing_zeros() as usize;
    (class < CLASSES).then_some(class)
}

unsafe impl GlobalAlloc for Heap {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let Some(class) = class(layout) else { return core::ptr::null_mut() };
        // SAFETY: one thread, and no call re-enters the allocator.
        let s = unsafe { &mut *self.0.get() };
        let head = s.free[class];
        if head != 0 {
            // SAFETY: `head` is a free block of this class; its first word links the next.
            s.free[class] = unsafe { *(head as *const usize) };
            return head as *mut u8;
        }
        let size = 1usize << class;
        // Blocks are aligned to their size up to a page (every alignment asked is at most
        // the size, so at most the block's alignment).
        let align = size.min(PAGE);
        let start = (s.next + align - 1) & !(align - 1);
        if start < s.next || start.checked_add(size).is_none_or(|e| e > s.end) {
            let need = size + align;
            let pages = need.div_ceil(PAGE);
            let old = core::arch::wasm32::memory_grow(0, pages);
            if old == usize::MAX {
                return core::ptr::null_mut();
            }
            let base = old * PAGE;
            if base != s.end {
                s.next = base;
            }
            s.end = base + pages * PAGE;
            // SAFETY: as above; the region now holds the block.
            return unsafe { self.alloc(layout) };
        }
        s.next = start + size;
        start as *mut u8
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        let Some(class) = class(layout) else { return };
        // SAFETY: one thread; `ptr` came from `alloc` with this layout, so it is a block of
        // this class that nothing uses any more.
        let s = unsafe { &mut *self.0.get() };
        unsafe { *(ptr as *mut usize) = s.free[class] };
        s.free[class] = ptr as usize;
    }
}
