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
use gcodec_exec::event::{CountingSink, EventSink, JsonlSink};
use gcodec_exec::program::Program;
use gcodec_profile::Profile;

mod common;

#[path = "../../gcodec-parser/benches/program/mod.rs"]
mod program;

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
    let mut loader = common::loader(profile);
    let outcome = common::channel(profile, &mut loader, sink, direct_motions)
        .run(Arc::clone(program))
        .expect("no output error");
    outcome.summary.blocks
}

fn bench(c: &mut Criterion) {
    common::configure_allocator();
    let profile = Arc::new(gcodec_profile::builtin().expect("built-in profile"));
    let while_loop = common::lowered(
        "while.mpf",
        b"R1=0\nWHILE R1<1000000\nR2=R2+R1*0.5\nR1=R1+1\nENDWHILE\nM30\n",
        &profile,
    );
    let generated = common::lowered("bench.mpf", &program::generate(100_000), &profile);
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
    let flood = common::lowered("flood.mpf", &common::flood(100_000), &profile);
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
