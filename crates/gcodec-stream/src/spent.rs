//! Freeing what a streamed run has spent on the thread that made it.
//!
//! A streamed run lowers its chunks on worker threads and runs them on
//! another; the run forgets a page once it is past it. Freed there, every
//! box and vector of the page is a free across threads, which the
//! allocator makes dearer on both sides (the freeing thread hands the
//! block over, the owning thread collects it later): about a tenth of the
//! CPU of the 1,000,000-block benchmark (docs/performance.md). So each
//! chunk carries the [`SpentBin`] of the thread that lowered it; the run
//! puts the page's instructions there, and that thread frees them before
//! its next chunk, reusing the memory while it is still in its cache.
//!
//! A bin takes anything that can cross threads: one box per page is
//! nothing beside the page.

use std::any::Any;
use std::sync::{Arc, Mutex, PoisonError};

/// What a bin holds: any value that may be dropped on another thread.
type Spent = Box<dyn Any + Send>;

/// Where spent instructions wait for the thread that allocated them.
/// Cloning shares the bin.
#[derive(Clone, Debug)]
pub struct SpentBin(Arc<Mutex<Bin>>);

#[derive(Debug, Default)]
struct Bin {
    /// `false` once the thread has ended: what comes then is freed at
    /// once, by whoever gives it.
    open: bool,
    spent: Vec<Spent>,
}

impl SpentBin {
    /// Gives `spent` back to the thread that allocated it.
    pub fn give_back<T: Send + 'static>(&self, spent: T) {
        let spent: Spent = Box::new(spent);
        let mut bin = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        if bin.open {
            bin.spent.push(spent);
        }
        // Otherwise `spent` is dropped here, after the lock.
    }

    /// The bin of this thread.
    pub fn of_this_thread() -> SpentBin {
        THIS_THREAD.with(|bin| bin.0.clone())
    }

    /// Frees what was given back to this thread's bin.
    pub fn free_this_threads() {
        THIS_THREAD.with(|bin| drop(bin.0.take(false)));
    }

    /// Takes what waits in the bin (dropped by the caller, after the
    /// lock), and closes the bin if `close`.
    fn take(&self, close: bool) -> Vec<Spent> {
        let mut bin = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        bin.open &= !close;
        std::mem::take(&mut bin.spent)
    }
}

/// A thread's bin, closed and emptied when the thread ends.
struct ThreadBin(SpentBin);

impl Drop for ThreadBin {
    fn drop(&mut self) {
        drop(self.0.take(true));
    }
}

thread_local! {
    static THIS_THREAD: ThreadBin = ThreadBin(SpentBin(Arc::new(Mutex::new(Bin {
        open: true,
        spent: Vec::new(),
    }))));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn instructions() -> Vec<String> {
        vec!["L@1".to_owned()]
    }

    fn held(bin: &SpentBin) -> usize {
        bin.0.lock().unwrap().spent.len()
    }

    /// What is given back waits for its thread, which frees it before its
    /// next chunk, and when it ends; once it has ended, nothing waits.
    #[test]
    fn spent_instructions_wait_for_their_thread_while_it_lives() {
        use std::sync::mpsc::channel;
        let (to_worker, worker_gets) = channel::<()>();
        let (to_test, test_gets) = channel();
        let worker = std::thread::spawn(move || {
            to_test.send(Some(SpentBin::of_this_thread())).unwrap();
            // The next chunk.
            worker_gets.recv().unwrap();
            SpentBin::free_this_threads();
            to_test.send(None).unwrap();
            // The end.
            worker_gets.recv().unwrap();
        });
        let spent = test_gets.recv().unwrap().unwrap();
        spent.give_back(instructions());
        spent.give_back(instructions());
        assert_eq!(held(&spent), 2);
        to_worker.send(()).unwrap();
        assert!(test_gets.recv().unwrap().is_none());
        assert_eq!(held(&spent), 0, "freed before the next chunk");
        spent.give_back(instructions());
        assert_eq!(held(&spent), 1);
        to_worker.send(()).unwrap();
        worker.join().unwrap();
        assert_eq!(held(&spent), 0, "freed when the thread ends");
        spent.give_back(instructions());
        assert_eq!(held(&spent), 0, "closed");
    }
}
