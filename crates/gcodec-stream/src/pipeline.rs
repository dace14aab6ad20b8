//! The ordered worker pipeline of a streamed run: chunks are worked on
//! several threads and their results taken in the chunks' order, with a
//! bounded number of results in flight.
//!
//! Workers take the next chunk as they become free rather than a fixed
//! share (chunk `k`, `k + workers`, …): with fixed shares, a worker whose
//! chunks happened to be quick filled its queue and waited for the other,
//! while the consumer waited for the slow chunk too, and a core sat idle
//! about a sixth of pass 2 of the 1,000,000-block benchmark
//! (docs/performance.md).

use std::collections::VecDeque;
use std::sync::{Condvar, Mutex, MutexGuard, PoisonError};

use crate::{Chunk, WorkerPriority};

/// Results per worker that may wait for `each` (done or being worked on):
/// enough to ride out chunks of uneven cost, few enough that memory does
/// not grow with the program.
const AHEAD_PER_WORKER: usize = 4;

/// Does `work` on each of `chunks` on `workers` threads, scheduled at
/// `priority`, and hands the results to `each` in the chunks' order. At
/// most `4 × workers` chunks are taken and not yet handed on, so memory
/// does not grow with the program. On one worker (or one chunk)
/// everything happens on this thread, at its priority. A panic in `work`
/// or `each` stops the other threads and is raised again here.
pub fn map_chunks<'c, T: Send>(
    chunks: &'c [Chunk],
    workers: usize,
    priority: WorkerPriority,
    work: impl Fn(&'c Chunk) -> T + Sync,
    mut each: impl FnMut(T),
) {
    if workers <= 1 || chunks.len() <= 1 {
        for chunk in chunks {
            each(work(chunk));
        }
        return;
    }
    let window = Window {
        state: Mutex::new(State {
            next: 0,
            slots: VecDeque::new(),
            stopped: false,
        }),
        done: Condvar::new(),
        room: Condvar::new(),
        limit: AHEAD_PER_WORKER * workers,
    };
    let (window, work) = (&window, &work);
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(move || {
                priority.apply_to_this_thread();
                let _stop = StopOnDrop {
                    window,
                    only_when_panicking: true,
                };
                while let Some(index) = window.take(chunks.len()) {
                    let result = work(&chunks[index]);
                    window.put(index, result);
                }
            });
        }
        // The workers stop when this ends, normally or by a panic in
        // `each`; the scope then waits for them and re-raises theirs.
        let _stop = StopOnDrop {
            window,
            only_when_panicking: false,
        };
        for _ in chunks {
            match window.next_result() {
                Some(result) => each(result),
                // A worker panicked.
                None => break,
            }
        }
    });
}

/// The chunks in flight.
struct Window<T> {
    state: Mutex<State<T>>,
    /// A result came, or the pipeline stopped.
    done: Condvar,
    /// A result was taken, or the pipeline stopped.
    room: Condvar,
    /// How many chunks may be taken and not handed on.
    limit: usize,
}

struct State<T> {
    /// The next chunk to take.
    next: usize,
    /// The chunks taken and not handed on, oldest first: `None` while
    /// being worked on. The first is chunk `next - slots.len()`.
    slots: VecDeque<Option<T>>,
    /// A thread panicked, or the consumer ended.
    stopped: bool,
}

impl<T> Window<T> {
    fn lock(&self) -> MutexGuard<'_, State<T>> {
        // A panic while locked leaves consistent state: only `stopped`
        // matters then, and it is set by the guards.
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The index of the next chunk to work on, once there is room;
    /// `None` when every chunk is taken or the pipeline stopped.
    fn take(&self, chunks: usize) -> Option<usize> {
        let mut state = self.lock();
        loop {
            if state.stopped || state.next >= chunks {
                return None;
            }
            if state.slots.len() < self.limit {
                let index = state.next;
                state.next += 1;
                state.slots.push_back(None);
                return Some(index);
            }
            state = self
                .room
                .wait(state)
                .unwrap_or_else(PoisonError::into_inner);
        }
    }

    /// The result of chunk `index`.
    fn put(&self, index: usize, result: T) {
        let mut state = self.lock();
        let first = state.next - state.slots.len();
        if let Some(slot) = index
            .checked_sub(first)
            .and_then(|i| state.slots.get_mut(i))
        {
            *slot = Some(result);
        }
        if index == first {
            self.done.notify_one();
        }
    }

    /// The next result in chunk order, waiting for it; `None` if the
    /// pipeline stopped first.
    fn next_result(&self) -> Option<T> {
        let mut state = self.lock();
        loop {
            if let Some(Some(_)) = state.slots.front() {
                let result = state.slots.pop_front().flatten();
                self.room.notify_one();
                return result;
            }
            if state.stopped {
                return None;
            }
            state = self
                .done
                .wait(state)
                .unwrap_or_else(PoisonError::into_inner);
        }
    }

    fn stop(&self) {
        self.lock().stopped = true;
        self.done.notify_all();
        self.room.notify_all();
    }
}

/// Stops the pipeline when dropped: a worker's when it panics, the
/// consumer's always (so no worker waits for room that never comes).
struct StopOnDrop<'w, T> {
    window: &'w Window<T>,
    only_when_panicking: bool,
}

impl<T> Drop for StopOnDrop<'_, T> {
    fn drop(&mut self) {
        if !self.only_when_panicking || std::thread::panicking() {
            self.window.stop();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chunk_list(n: usize) -> Vec<Chunk> {
        (0..n)
            .map(|i| Chunk {
                bytes: i..i + 1,
                first_block: i,
                blocks: 1,
            })
            .collect()
    }

    /// Results come in order, whatever order the workers finish in.
    #[test]
    fn results_come_in_chunk_order() {
        let chunks = chunk_list(200);
        for workers in [1, 2, 3, 8] {
            let mut seen = Vec::new();
            map_chunks(
                &chunks,
                workers,
                WorkerPriority::Normal,
                |chunk| {
                    // Uneven work: later chunks of each ten are quicker.
                    let spin = (10 - chunk.first_block % 10) * 2_000;
                    std::hint::black_box((0..spin).sum::<usize>());
                    chunk.first_block
                },
                |index| seen.push(index),
            );
            assert_eq!(seen, (0..200).collect::<Vec<_>>(), "{workers} workers");
        }
    }

    /// No more than the window's chunks are taken ahead of the consumer.
    #[test]
    fn the_window_bounds_the_chunks_in_flight() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let chunks = chunk_list(100);
        let started = AtomicUsize::new(0);
        let mut taken = 0;
        map_chunks(
            &chunks,
            2,
            WorkerPriority::Normal,
            |chunk| {
                started.fetch_add(1, Ordering::SeqCst);
                chunk.first_block
            },
            |_| {
                taken += 1;
                // Slow consumer: the workers run into the limit.
                std::thread::sleep(std::time::Duration::from_micros(200));
                let ahead = started.load(Ordering::SeqCst) - taken;
                assert!(ahead <= 2 * AHEAD_PER_WORKER, "{ahead} chunks ahead");
            },
        );
        assert_eq!(taken, 100);
    }

    /// Background workers run at a raised nice value (on Linux a
    /// thread's own), normal ones at the caller's, and the caller's stays
    /// as it was.
    #[cfg(target_os = "linux")]
    #[test]
    fn background_workers_run_below_the_caller() {
        use crate::BACKGROUND_NICE;
        // SAFETY: `getpriority` takes integers and touches no memory.
        let nice = || unsafe { libc::getpriority(libc::PRIO_PROCESS, 0) };
        let caller = nice();
        let chunks = chunk_list(8);
        for (priority, expected) in [
            (WorkerPriority::Normal, caller),
            (
                WorkerPriority::Background,
                (caller + BACKGROUND_NICE).min(19),
            ),
        ] {
            let mut seen = Vec::new();
            map_chunks(&chunks, 2, priority, |_| nice(), |n| seen.push(n));
            assert_eq!(seen, vec![expected; 8], "{priority:?}");
        }
        assert_eq!(nice(), caller);
    }

    /// A panic in a worker reaches the caller instead of hanging it.
    #[test]
    fn a_panicking_worker_stops_the_pipeline() {
        let chunks = chunk_list(50);
        let outcome = std::panic::catch_unwind(|| {
            map_chunks(
                &chunks,
                2,
                WorkerPriority::Normal,
                |chunk| {
                    assert!(chunk.first_block != 17, "chunk 17 fails");
                    chunk.first_block
                },
                |_| {},
            );
        });
        assert!(outcome.is_err());
    }

    /// A panic in the consumer stops the workers too.
    #[test]
    fn a_panicking_consumer_stops_the_workers() {
        let chunks = chunk_list(50);
        let outcome = std::panic::catch_unwind(|| {
            map_chunks(
                &chunks,
                2,
                WorkerPriority::Background,
                |chunk| chunk.first_block,
                |index| assert!(index != 5, "consumer fails at 5"),
            );
        });
        assert!(outcome.is_err());
    }
}
