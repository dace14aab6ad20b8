//! Throughput of the picture alone: the events of the front end's
//! generated program (`crates/gcodec-parser/benches/program/`, 100,000
//! blocks: straight moves, rapids, arcs, loops) collected once outside
//! the timing, then handed to a fresh `PlotSink` and rendered to SVG
//! per iteration. `cargo bench -p gcodec-plot --bench plot`; the
//! whole-process figure is in docs/performance.md.

use std::hint::black_box;
use std::sync::Arc;
use std::time::Duration;

use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use gcodec_driver::event::{Event, EventKind, VecSink};
use gcodec_driver::{RunSetup, run_main};
use gcodec_plot::PlotSink;
use gcodec_source::SourceFile;

#[path = "../../gcodec-parser/benches/program/mod.rs"]
mod program;

/// The events of the generated program of `blocks` blocks.
fn events(blocks: usize) -> Vec<Event> {
    let profile = gcodec_profile::builtin().expect("built-in profile");
    let mut setup = RunSetup::new(profile);
    setup.options.max_steps = u64::MAX;
    let file = SourceFile::new("bench.mpf", program::generate(blocks));
    let mut sink = VecSink::default();
    let report = run_main(Arc::new(file), &setup, &mut sink, None);
    report.outcome.expect("no output error");
    sink.events
}

fn bench(c: &mut Criterion) {
    let events = events(100_000);
    let motions = events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Motion(_)))
        .count();
    let mut group = c.benchmark_group("plot/program_100k");
    // Motion events per second.
    group.throughput(Throughput::Elements(motions as u64));
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(8));
    group.bench_function("sink", |b| {
        b.iter(|| {
            let mut sink = PlotSink::new(None);
            for event in &events {
                sink.plot(event);
            }
            black_box(sink.into_plot().model.elements().len())
        })
    });
    group.bench_function("sink_and_svg", |b| {
        b.iter(|| {
            let mut sink = PlotSink::new(None);
            for event in &events {
                sink.plot(event);
            }
            black_box(sink.into_plot().to_svg("bench.mpf").len())
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
