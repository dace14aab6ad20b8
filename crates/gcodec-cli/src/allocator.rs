//! The global allocator: mimalloc, asked for alignment only when the
//! layout needs more than every mimalloc block has.
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
