//! Ctrl-C as the flag a run reads before each block
//! (`RunOptions::interrupt`): the first sets it, a second ends the
//! process with status 130 as an interrupted command does.
//!
//! On Unix the flag is set by a signal handler of its own: the `ctrlc`
//! crate's handler runs on a thread it spawns at installation, a thread
//! and a 2 MB stack on every start of `gcodec run`, about a twentieth
//! of a one-line program's time (docs/performance.md).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// The flag Ctrl-C sets, installed on first use and shared by every run
/// of the process. Failing to install the handler only loses the clean
/// stop: the flag is returned all the same.
pub fn ctrl_c_flag() -> Arc<AtomicBool> {
    imp::ctrl_c_flag()
}

/// Sets `flag`; true when it was already set (the second Ctrl-C).
fn set(flag: &AtomicBool) -> bool {
    flag.swap(true, Ordering::Relaxed)
}

#[cfg(unix)]
mod imp {
    use std::sync::atomic::AtomicBool;
    use std::sync::{Arc, Once, OnceLock};

    static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();

    /// Async-signal-safe: an atomic load of the initialised `FLAG`, an
    /// atomic swap and `_exit`.
    extern "C" fn on_sigint(_: libc::c_int) {
        if let Some(flag) = FLAG.get()
            && super::set(flag)
        {
            // SAFETY: `_exit` is async-signal-safe and ends the process.
            unsafe { libc::_exit(130) };
        }
    }

    pub fn ctrl_c_flag() -> Arc<AtomicBool> {
        let flag = FLAG.get_or_init(|| Arc::new(AtomicBool::new(false)));
        static INSTALL: Once = Once::new();
        // SAFETY: a zeroed `sigaction` is a valid value; the handler only
        // touches `FLAG`, set before it is installed.
        INSTALL.call_once(|| unsafe {
            let mut action: libc::sigaction = std::mem::zeroed();
            action.sa_sigaction = on_sigint as extern "C" fn(libc::c_int) as libc::sighandler_t;
            action.sa_flags = libc::SA_RESTART;
            libc::sigemptyset(&mut action.sa_mask);
            libc::sigaction(libc::SIGINT, &action, std::ptr::null_mut());
        });
        Arc::clone(flag)
    }
}

#[cfg(not(unix))]
mod imp {
    use std::sync::atomic::AtomicBool;
    use std::sync::{Arc, OnceLock};

    static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();

    pub fn ctrl_c_flag() -> Arc<AtomicBool> {
        Arc::clone(FLAG.get_or_init(|| {
            let flag = Arc::new(AtomicBool::new(false));
            let handled = Arc::clone(&flag);
            let _ = ctrlc::set_handler(move || {
                if super::set(&handled) {
                    std::process::exit(130);
                }
            });
            flag
        }))
    }
}
