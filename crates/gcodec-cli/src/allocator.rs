//! The global allocator: mimalloc, asked for alignment only when the
//! layout needs more than every mimalloc block has, and its options.
//!
//! `mimalloc::MiMalloc` passes every allocation to `mi_malloc_aligned`,
//! whose quick path holds only for blocks up to 1 KiB whose free block
//! happens to be aligned; everything else (a chunk's block vector, a
//! page of instructions, a refill of an empty free list) took its
//! generic aligned path, about 150 instructions an allocation on the
//! streamed run of the million-line program (docs/performance.md).
//! mimalloc's blocks are all aligned to a word, so a layout aligned to a
//! word or less goes to `mi_malloc`, as Rust's own `System` allocator
//! uses `malloc` below the alignment `malloc` guarantees.

use std::alloc::{GlobalAlloc, Layout};
use std::ffi::c_void;

use libmimalloc_sys as mi;

/// mimalloc's `mi_option_purge_delay` (`mimalloc.h`, the same in v2 and
/// v3; `libmimalloc-sys` has no constant for it).
const MI_OPTION_PURGE_DELAY: mi::mi_option_t = 15;

/// mimalloc v3's `mi_option_arena_reserve` (`mimalloc.h`; no constant in
/// `libmimalloc-sys` either), in KiB.
const MI_OPTION_ARENA_RESERVE: mi::mi_option_t = 23;

/// The first arena mimalloc reserves: 64 MiB instead of 1 GiB. An arena's
/// bitmaps are sized for all of it and written at its creation: about 40
/// page faults of a start for 1 GiB, a sixth of a short program's run
/// (docs/performance.md, "Issue 20: the third measurement"). Later arenas
/// grow by themselves (mimalloc doubles the reserve every eight), and a
/// large allocation gets an arena its size.
const FIRST_ARENA_KIB: std::ffi::c_long = 64 * 1024;

/// Sets mimalloc's options for a process that runs once and exits.
pub extern "C" fn set_options() {
    // Memory freed between stages is kept for reuse instead of being
    // handed back to the OS and faulted in again, which cost a fifth of a
    // large lowering.
    // SAFETY: `mi_option_set` only stores the value, and may be called at
    // any time, before mimalloc's own start too.
    unsafe { mi::mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
    // SAFETY: as above.
    unsafe { mi::mi_option_set(MI_OPTION_ARENA_RESERVE, FIRST_ARENA_KIB) };
}

/// On Linux the options are set before `main`: the standard library's
/// start allocates (the main thread's information), and mimalloc reserves
/// its first arena then. A function in `.init_array` runs before it.
#[cfg(target_os = "linux")]
#[used]
#[unsafe(link_section = ".init_array")]
static SET_OPTIONS_AT_LOAD: extern "C" fn() = set_options;

/// The alignment of every block `mi_malloc` returns (`MI_INTPTR_SIZE`).
const BLOCK_ALIGN: usize = std::mem::size_of::<usize>();

pub struct Mimalloc;

fn plain(align: usize) -> bool {
    align <= BLOCK_ALIGN
}

// SAFETY: each method hands the layout's size (and, when it needs more
// than a word, its alignment) to the mimalloc function that honours it;
// mimalloc returns null on failure as `GlobalAlloc` requires, and `mi_free`
// and the `mi_realloc` functions take any pointer mimalloc returned.
unsafe impl GlobalAlloc for Mimalloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: see the impl.
        unsafe {
            if plain(layout.align()) {
                mi::mi_malloc(layout.size()).cast()
            } else {
                mi::mi_malloc_aligned(layout.size(), layout.align()).cast()
            }
        }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: see the impl.
        unsafe {
            if plain(layout.align()) {
                mi::mi_zalloc(layout.size()).cast()
            } else {
                mi::mi_zalloc_aligned(layout.size(), layout.align()).cast()
            }
        }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, _layout: Layout) {
        // SAFETY: see the impl.
        unsafe { mi::mi_free(ptr.cast::<c_void>()) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: see the impl.
        unsafe {
            if plain(layout.align()) {
                mi::mi_realloc(ptr.cast::<c_void>(), new_size).cast()
            } else {
                mi::mi_realloc_aligned(ptr.cast::<c_void>(), new_size, layout.align()).cast()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn allocations_have_their_alignment_and_keep_their_bytes() {
        let allocator = Mimalloc;
        for align in [1, 2, 4, 8, 16, 32, 64, 4096] {
            for size in [1, 7, 8, 24, 100, 1500, 70_000] {
                let layout = Layout::from_size_align(size, align).expect("layout");
                // SAFETY: a non-zero size; each pointer is freed once with
                // its layout.
                unsafe {
                    let p = allocator.alloc(layout);
                    assert!(!p.is_null());
                    assert_eq!(p as usize % align, 0, "{size} {align}");
                    p.write_bytes(0xA5, size);
                    let q = allocator.realloc(p, layout, size * 3);
                    assert_eq!(q as usize % align, 0, "{size} {align} grown");
                    assert!(
                        std::slice::from_raw_parts(q, size)
                            .iter()
                            .all(|&b| b == 0xA5)
                    );
                    allocator.dealloc(q, Layout::from_size_align(size * 3, align).expect("layout"));
                    let z = allocator.alloc_zeroed(layout);
                    assert_eq!(z as usize % align, 0);
                    assert!(std::slice::from_raw_parts(z, size).iter().all(|&b| b == 0));
                    allocator.dealloc(z, layout);
                }
            }
        }
    }
}
