//! A counting global allocator: wraps the system allocator and keeps the number of heap
//! bytes in use, so that a program can measure what a data structure really occupies (the
//! particle maps' bytes per particle, kd-tree included) and the most it held at once. A binary opts in with
//! `#[global_allocator] static A: footprint::heap::CountingAlloc = footprint::heap::CountingAlloc;`.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

static HEAP_BYTES: AtomicUsize = AtomicUsize::new(0);
/// The most [`HEAP_BYTES`] has been since the last [`reset_peak`].
static HEAP_PEAK: AtomicUsize = AtomicUsize::new(0);

/// The counting allocator (see the module doc).
pub struct CountingAlloc;

unsafe impl GlobalAlloc for CountingAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = HEAP_BYTES.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            raise_peak(now);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        HEAP_BYTES.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            // The old block and the new one are both held while the data moves.
            let now = HEAP_BYTES.fetch_add(new_size, Ordering::Relaxed) + new_size;
            raise_peak(now);
            HEAP_BYTES.fetch_sub(layout.size(), Ordering::Relaxed);
        }
        p
    }
}

/// Heap bytes in use, when [`CountingAlloc`] is the global allocator (otherwise 0).
pub fn heap_bytes() -> usize {
    HEAP_BYTES.load(Ordering::Relaxed)
}

/// Raises the peak to `now`: a plain load where it is not higher (the steady state), so
/// that an allocation pays no second atomic write.
#[inline]
fn raise_peak(now: usize) {
    if now > HEAP_PEAK.load(Ordering::Relaxed) {
        HEAP_PEAK.fetch_max(now, Ordering::Relaxed);
    }
}

/// The most heap bytes in use since the last [`reset_peak`] (or the start).
pub fn heap_peak() -> usize {
    HEAP_PEAK.load(Ordering::Relaxed)
}

/// Starts a new peak at the bytes in use now.
pub fn reset_peak() {
    HEAP_PEAK.store(HEAP_BYTES.load(Ordering::Relaxed), Ordering::Relaxed);
}
