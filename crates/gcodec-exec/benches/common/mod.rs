//! What the executor's benches share: the `gcodec` binary's allocator,
//! configured as it configures it (crates/gcodec-cli/src/main.rs), so
//! that the figures are what users get; and the peer benchmark's flood.

use std::sync::Arc;

use gcodec_driver::{Definitions, FileLoader, ProgramKind, SearchPath, compile_text};
use gcodec_exec::channel::{Channel, RunOptions};
use gcodec_exec::event::EventSink;
use gcodec_exec::program::Program;
use gcodec_profile::Profile;

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;

/// Sets the allocator's options as the CLI does; first thing in a bench.
pub fn configure_allocator() {
    // SAFETY: `mi_option_set` only stores the value (see the CLI's main).
    unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
}

/// `lines` blocks `G1 X… Y… F1000`, as the peer benchmark's generator
/// (`scripts/bench-peer/generate.py`, `flood`) writes them.
pub fn flood(lines: usize) -> Vec<u8> {
    let mut src = String::new();
    for i in 0..lines {
        let x = 100.0 + (i * 37 % 100_000) as f64 / 1000.0;
        let y = 200.0 + (i * 53 % 100_000) as f64 / 1000.0;
        src.push_str(&format!("G1 X{x:.3} Y{y:.3} F1000\n"));
    }
    src.into_bytes()
}

/// Parses and lowers `src` (outside the timing).
pub fn lowered(name: &str, src: &[u8], profile: &Profile) -> Arc<Program> {
    let definitions = Definitions::new();
    let compiled = compile_text(name, src, ProgramKind::Main, profile, &definitions);
    assert!(!compiled.has_errors(), "{:?}", compiled.diagnostics);
    compiled.into_loaded("MAIN").program
}

/// A channel on `profile` that runs to the program's end, however many
/// steps it takes, with no subprogram folders and no definitions.
pub fn channel<'r>(
    profile: &Arc<Profile>,
    loader: &'r mut FileLoader,
    sink: &'r mut dyn EventSink,
    direct_motions: bool,
) -> Channel<'r> {
    let mut options = RunOptions::for_profile(profile);
    options.max_steps = u64::MAX;
    options.direct_motions = direct_motions;
    Channel::new(Arc::clone(profile), options, loader, sink)
}

/// The loader of [`channel`].
pub fn loader(profile: &Arc<Profile>) -> FileLoader {
    FileLoader::new(
        SearchPath::new(),
        Arc::clone(profile),
        Arc::new(Definitions::new()),
    )
}
