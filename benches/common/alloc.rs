//! A counting global allocator for peak-memory figures, shared by the
//! benchmarks and the integration tests (`tests/it/main.rs`): it wraps `std::alloc::System`, keeps
//! the live heap bytes and the most live at once since the last reset.
//! Every allocation costs a few relaxed atomic operations, in graftal and
//! the baselines alike. Each benchmark declares
//! `#[global_allocator] static ALLOC: alloc::Counting = alloc::Counting;`;
//! the test binary declares [`CountingWhenStarted`], which costs nothing
//! in the processes that do not measure.

#![allow(dead_code)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicIsize, Ordering::Relaxed};

// Signed: under `CountingWhenStarted`, memory allocated before counting
// started may be freed after, which takes the count below zero; a peak is
// a difference of counts, so it is the same.
static CURRENT: AtomicIsize = AtomicIsize::new(0);
static PEAK: AtomicIsize = AtomicIsize::new(0);

pub struct Counting;

fn grew(bytes: usize) {
    let bytes = bytes as isize;
    let now = CURRENT.fetch_add(bytes, Relaxed) + bytes;
    PEAK.fetch_max(now, Relaxed);
}

fn shrank(bytes: usize) {
    CURRENT.fetch_sub(bytes as isize, Relaxed);
}

// SAFETY: every call is forwarded unchanged to `System`; only counters are
// updated besides.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            grew(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            grew(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        shrank(layout.size());
    }

    // Forwarded (not alloc + copy + dealloc) so growing a buffer in place is
    // not counted twice; a moving realloc's brief overlap is not counted.
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            if new_size >= layout.size() {
                grew(new_size - layout.size());
            } else {
                shrank(layout.size() - new_size);
            }
        }
        p
    }
}

/// [`Counting`] from [`start_counting`] on, [`System`] alone before: for a
/// binary that measures peaks only in some of its processes.
pub struct CountingWhenStarted;

static STARTED: AtomicBool = AtomicBool::new(false);

/// Makes [`CountingWhenStarted`] count in this process from now on.
pub fn start_counting() {
    STARTED.store(true, Relaxed);
}

/// Makes [`CountingWhenStarted`] stop counting (so that timings on many
/// threads do not share the counters' cache lines).
pub fn stop_counting() {
    STARTED.store(false, Relaxed);
}

// SAFETY: every call goes to `Counting` or to `System`, which `Counting`
// forwards to unchanged; a block allocated by either is freed by `System`.
unsafe impl GlobalAlloc for CountingWhenStarted {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if STARTED.load(Relaxed) {
            unsafe { Counting.alloc(layout) }
        } else {
            unsafe { System.alloc(layout) }
        }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if STARTED.load(Relaxed) {
            unsafe { Counting.alloc_zeroed(layout) }
        } else {
            unsafe { System.alloc_zeroed(layout) }
        }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if STARTED.load(Relaxed) {
            unsafe { Counting.dealloc(ptr, layout) }
        } else {
            unsafe { System.dealloc(ptr, layout) }
        }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if STARTED.load(Relaxed) {
            unsafe { Counting.realloc(ptr, layout, new_size) }
        } else {
            unsafe { System.realloc(ptr, layout, new_size) }
        }
    }
}

/// Runs `f` once; returns its result and the peak of live heap bytes during
/// the call above those live before it (the result itself included).
pub fn peak_during<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let base = CURRENT.load(Relaxed);
    PEAK.store(base, Relaxed);
    let out = f();
    let peak = (PEAK.load(Relaxed) - base).max(0) as usize;
    (out, peak)
}

pub fn mib(bytes: usize) -> String {
    let m = bytes as f64 / (1024.0 * 1024.0);
    if m >= 0.1 {
        format!("{m:.1} MiB")
    } else {
        format!("{:.1} KiB", bytes as f64 / 1024.0)
    }
}
