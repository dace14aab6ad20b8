//! The scheduling priority of a pipeline's workers.
//!
//! A streamed run has three busy threads on a machine that often has two
//! cores: the run, which is the critical path (every block passes through
//! it in order), and pass 2's two workers, which parse and lower ahead of
//! it. Scheduled alike, the three shared the two cores evenly whenever
//! all were runnable: the run got two thirds of a core, fell behind, and
//! then waited for pages the workers were still sharing a core for, while
//! they in turn waited for room in the window: each core stood idle
//! about a sixth of the million-line benchmark (`perf sched timehist`:
//! the run blocked 26 % of its time, each worker 52 %). With the workers' nice
//! value raised, the scheduler gives the run a core of its own and the
//! workers the rest (docs/performance.md, "Issue 20: the workers behind
//! the run").

/// How the workers of [`crate::map_chunks`] are scheduled beside the
/// process's other threads.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WorkerPriority {
    /// As the thread that starts them.
    #[default]
    Normal,
    /// Below the thread that takes their results and what it feeds: on
    /// Linux each worker's nice value is raised by [`BACKGROUND_NICE`]
    /// (a thread's own there); elsewhere, where the nice value is the
    /// whole process's, as [`WorkerPriority::Normal`].
    Background,
}

/// How much a background worker's nice value is raised: enough that two
/// workers weigh less than one thread at the default priority (a weight
/// of 335 each against 1024), so that the scheduler keeps the consumer
/// alone on a core; more gave nothing in the measurements and would only
/// yield more to other processes.
pub const BACKGROUND_NICE: i32 = 5;

impl WorkerPriority {
    /// Applies the priority to the calling thread, a worker. A failure
    /// leaves the priority as it was, which is only slower.
    pub(crate) fn apply_to_this_thread(self) {
        if self == WorkerPriority::Background {
            lower_this_threads_priority();
        }
    }
}

#[cfg(target_os = "linux")]
fn lower_this_threads_priority() {
    // SAFETY: `nice` takes an integer and touches no memory of ours. On
    // Linux it changes the calling thread only (glibc and musl implement
    // it with `setpriority(PRIO_PROCESS, 0, …)`, and the kernel's 0 is the
    // calling task); its result (-1 both for an error and for a nice
    // value of -1) is not needed.
    unsafe {
        libc::nice(BACKGROUND_NICE);
    }
}

#[cfg(not(target_os = "linux"))]
fn lower_this_threads_priority() {}
