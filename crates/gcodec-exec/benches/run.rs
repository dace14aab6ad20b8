//! Throughput of the executor alone: programs parsed and lowered outside
//! the timing, then run by a fresh channel per iteration with the
//! built-in profile. `cargo bench -p gcodec-exec --bench run`; see
//! docs/performance.md.
//!
//! - `while_loop`: a `WHILE` loop of 1,000,000 passes with R-parameter
//!   arithmetic (4,000,004 blocks, one `m_function` and one
//!   `program_end` event): the per-instruction cost of the run loop and
//!   of expression evaluation.
//! - `program_100k`: the front end's generated program
//!   (`crates/gcodec-parser/benches/program/`), 100,000 blocks: motions,
//!   modal changes, structures; most blocks give an event.
//!
//! - `flood_100k`: 100,000 lines `G1 X… Y… F…` as the peer benchmark's
//!   floods have them (`scripts/bench-peer/generate.py`), run by the
//!   direct path of plain straight motions and, as `…_general`, with
//!   `RunOptions::direct_motions` off.
//!
//! Each with events to `CountingSink` (the executor alone) and to
//! `JsonlSink` over `io::sink()` (plus formatting the JSONL).

use std::hint::black_box;
use std::sync::Arc;
use std::time::Duration;

use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use gcodec_driver::{Definitions, FileLoader, ProgramKind, SearchPath, compile_text};
use gcodec_exec::channel::{Channel, RunOptions};
use gcodec_exec::event::{CountingSink, EventSink, JsonlSink};
use gcodec_exec::program::Program;
use gcodec_profile::Profile;

// The allocator of the `gcodec` binary, configured as it configures it
// (crates/gcodec-cli/src/main.rs), so that the figure is what users get.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;

#[path = "../../gcodec-parser/benches/program/mod.rs"]
mod program;

/// Parses and lowers `src` (outside the timing).
fn lowered(name: &str, src: &[u8], profile: &Profile) -> Arc<Program> {
    let definitions = Definitions::new();
    let compiled = compile_text(name, src, ProgramKind::Main, profile, &definitions);
    assert!(!compiled.has_errors(), "{:?}", compiled.diagnostics);
    compiled.into_loaded("MAIN").program
}

/// `lines` blocks `G1 X… Y… F1000`, as the peer benchmark's generator
/// (`scripts/bench-peer/generate.py`, `flood`) writes them.
fn flood(lines: usize) -> Vec<u8> {
    let mut src = String::new();
    for i in 0..lines {
        let x = 100.0 + (i * 37 % 100_000) as f64 / 1000.0;
        let y = 200.0 + (i * 53 % 100_000) as f64 / 1000.0;
        src.push_str(&format!("G1 X{x:.3} Y{y:.3} F1000\n"));
    }
    src.into_bytes()
}

/// One run of `program` to its end; the number of blocks executed.
fn run(program: &Arc<Program>, profile: &Arc<Profile>, sink: &mut dyn EventSink) -> u64 {
    run_with(program, profile, sink, true)
}

/// [`run`], by the direct path of plain motions or not.
fn run_with(
    program: &Arc<Program>,
    profile: &Arc<Profile>,
    sink: &mut dyn EventSink,
    direct_motions: bool,
) -> u64 {
    let mut loader = FileLoader::new(
        SearchPath::new(),
        Arc::clone(profile),
        Arc::new(Definitions::new()),
    );
    let mut options = RunOptions::for_profile(profile);
    options.max_steps = u64::MAX;
    options.direct_motions = direct_motions;
    let outcome = Channel::new(Arc::clone(profile), options, &mut loader, sink)
        .run(Arc::clone(program))
        .expect("no output error");
    outcome.summary.blocks
}

fn bench(c: &mut Criterion) {
    // SAFETY: `mi_option_set` only stores the value (see the CLI's main).
    unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
    let profile = Arc::new(gcodec_profile::builtin().expect("built-in profile"));
    let while_loop = lowered(
        "while.mpf",
        b"R1=0\nWHILE R1<1000000\nR2=R2+R1*0.5\nR1=R1+1\nENDWHILE\nM30\n",
        &profile,
    );
    let generated = lowered("bench.mpf", &program::generate(100_000), &profile);
    for (name, program) in [("while_loop", &while_loop), ("program_100k", &generated)] {
        let blocks = run(program, &profile, &mut CountingSink::default());
        let mut group = c.benchmark_group(format!("run/{name}"));
        // Blocks executed per second.
        group.throughput(Throughput::Elements(blocks));
        group.sampling_mode(SamplingMode::Flat);
        group.sample_size(10);
        group.warm_up_time(Duration::from_secs(1));
        group.measurement_time(Duration::from_secs(8));
        group.bench_function("counting", |b| {
            b.iter(|| {
                let mut sink = CountingSink::default();
                let blocks = run(program, &profile, &mut sink);
                black_box((blocks, sink.total()))
            })
        });
        group.bench_function("jsonl", |b| {
            b.iter(|| {
                let mut sink = JsonlSink::new(std::io::sink());
                black_box(run(program, &profile, &mut sink))
            })
        });
        group.finish();
    }
    let flood = lowered("flood.mpf", &flood(100_000), &profile);
    let mut group = c.benchmark_group("run/flood_100k");
    group.throughput(Throughput::Elements(100_000));
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(5));
    for direct in [true, false] {
        let path = if direct { "" } else { "_general" };
        group.bench_function(format!("counting{path}"), |b| {
            b.iter(|| {
                let mut sink = CountingSink::default();
                black_box(run_with(&flood, &profile, &mut sink, direct))
            })
        });
        group.bench_function(format!("jsonl{path}"), |b| {
            b.iter(|| {
                let mut sink = JsonlSink::new(std::io::sink());
                black_box(run_with(&flood, &profile, &mut sink, direct))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
