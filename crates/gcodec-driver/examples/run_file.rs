//! Runs a program with the built-in profile, events to a sink that counts
//! them (or, with a second argument, to JSONL over `io::sink()`), and
//! prints how long each stage took and the resident set after it (a
//! development aid; `gcodec run` is the tool). Uses the allocator of the
//! `gcodec` binary, configured the same way.
use std::sync::Arc;
use std::time::Instant;

use gcodec_driver::{Definitions, FileLoader, ProgramKind, SearchPath};
use gcodec_exec::channel::{Channel, RunOptions};
use gcodec_exec::event::{CountingSink, JsonlSink};
use gcodec_exec::program::Program;
use gcodec_source::SourceFile;

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;

/// The resident set of this process in MB (Linux; 0 elsewhere).
fn rss() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmRSS:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        })
        .map_or(0, |kb| kb / 1024)
}

fn main() {
    // SAFETY: `mi_option_set` only stores the value (see the CLI's main).
    unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
    let path = std::env::args()
        .nth(1)
        .expect("usage: run_file FILE [jsonl]");
    let jsonl = std::env::args().nth(2).is_some();
    let profile = Arc::new(gcodec_profile::builtin().expect("profile"));
    let t = Instant::now();
    let file = SourceFile::read(std::path::Path::new(&path)).expect("read");
    let parsed = gcodec_parser::parse(&file);
    let t_parse = t.elapsed();
    let rss_parse = rss();
    let lowered = gcodec_sema::lower_program(
        &parsed.program,
        ProgramKind::of_file(&path),
        &profile,
        &Definitions::new(),
    );
    let t_lower = t.elapsed();
    let rss_lower = rss();
    std::mem::forget(parsed.program);
    let instructions = lowered.document.instructions.len();
    let main = Arc::new(Program::new("MAIN", Arc::new(file), lowered.document));
    let mut loader = FileLoader::new(
        SearchPath::new(),
        Arc::clone(&profile),
        Arc::new(Definitions::new()),
    );
    // `RUNS=n` runs the program n times (for profiling the executor).
    let runs: usize = std::env::var("RUNS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(1);
    let mut outcome = None;
    for _ in 0..runs {
        let mut options = RunOptions::for_profile(&profile);
        options.max_steps = u64::MAX;
        let profile = Arc::clone(&profile);
        let main = Arc::clone(&main);
        outcome = Some(
            if jsonl {
                let mut sink = JsonlSink::new(std::io::sink());
                Channel::new(profile, options, &mut loader, &mut sink).run(main)
            } else {
                let mut sink = CountingSink::default();
                Channel::new(profile, options, &mut loader, &mut sink).run(main)
            }
            .expect("io"),
        );
    }
    let outcome = outcome.expect("RUNS is at least 1");
    let t_run = t.elapsed();
    // The program is not dropped: `gcodec run` does not drop it either.
    std::mem::forget(main);
    eprintln!(
        "parse {:?} ({} MB), lower {:?} ({} MB, {} instructions), run {:?} ({} MB); {} blocks",
        t_parse,
        rss_parse,
        t_lower - t_parse,
        rss_lower,
        instructions,
        t_run - t_lower,
        rss(),
        outcome.summary.blocks
    );
}
