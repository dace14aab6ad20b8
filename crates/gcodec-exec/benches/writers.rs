//! Throughput of the two output writers alone, in bytes of output a
//! second: the events and CSV rows of a run are recorded once (outside
//! the timing), then handed to a fresh `JsonlSink` or `CsvWriter` over
//! `io::sink()` per iteration. Issue 20 asks the CSV writer to be no
//! slower per byte than the JSONL writer; this is where that is
//! measured. `cargo bench -p gcodec-exec --bench writers`; see
//! docs/performance.md.
//!
//! - `flood_100k`: 100,000 lines `G1 X… Y… F…` as the peer benchmark's
//!   floods have them (`scripts/bench-peer/generate.py`): a motion
//!   event, and a CSV row, a block.
//! - `program_100k`: the front end's generated program
//!   (`crates/gcodec-parser/benches/program/`): motions, modal changes,
//!   structures.

use std::hint::black_box;
use std::io::{self, Write};
use std::sync::Arc;
use std::time::Duration;

use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use gcodec_exec::channel::BlockObserver;
use gcodec_exec::event::{BlockRow, CsvWriter, Event, EventSink, JsonlSink, axis_names};
use gcodec_profile::Profile;

mod common;

#[path = "../../gcodec-parser/benches/program/mod.rs"]
mod program;

/// Every event of a run.
#[derive(Default)]
struct Events(Vec<Event>);

impl EventSink for Events {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        self.0.push(event.clone());
        Ok(())
    }
}

/// Every block's CSV row of a run.
#[derive(Default)]
struct Rows(Vec<BlockRow>);

impl BlockObserver for Rows {
    fn block(&mut self, row: &BlockRow) -> io::Result<()> {
        self.0.push(row.clone());
        Ok(())
    }
}

/// The events and rows of a run of `src` to its end.
fn record(name: &str, src: &[u8], profile: &Arc<Profile>) -> (Events, Rows) {
    let program = common::lowered(name, src, profile);
    let mut loader = common::loader(profile);
    let (mut events, mut rows) = (Events::default(), Rows::default());
    common::channel(profile, &mut loader, &mut events, true)
        .with_observer(&mut rows)
        .run(program)
        .expect("no output error");
    (events, rows)
}

/// Counts the bytes written, and drops them.
#[derive(Default)]
struct ByteCount(u64);

impl Write for ByteCount {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        self.0 += bytes.len() as u64;
        Ok(bytes.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

fn write_jsonl<W: Write>(events: &Events, out: W) -> W {
    let mut sink = JsonlSink::new(out);
    for event in &events.0 {
        sink.event(event).expect("written");
    }
    sink.into_inner().expect("flushed")
}

fn write_csv<W: Write>(rows: &Rows, profile: &Profile, out: W) -> W {
    let mut csv = CsvWriter::new(out, axis_names(profile)).expect("header");
    for row in &rows.0 {
        csv.row(row).expect("written");
    }
    csv.into_inner().expect("flushed")
}

fn bench(c: &mut Criterion) {
    common::configure_allocator();
    let profile = Arc::new(gcodec_profile::builtin().expect("built-in profile"));
    let programs = [
        ("flood_100k", common::flood(100_000)),
        ("program_100k", program::generate(100_000)),
    ];
    for (name, src) in programs {
        let (events, rows) = record(&format!("{name}.mpf"), &src, &profile);
        let jsonl_bytes = write_jsonl(&events, ByteCount::default()).0;
        let csv_bytes = write_csv(&rows, &profile, ByteCount::default()).0;
        let mut group = c.benchmark_group(format!("writers/{name}"));
        group.sampling_mode(SamplingMode::Flat);
        group.sample_size(10);
        group.warm_up_time(Duration::from_secs(1));
        group.measurement_time(Duration::from_secs(4));
        group.throughput(Throughput::BytesDecimal(jsonl_bytes));
        group.bench_function("jsonl", |b| {
            b.iter(|| black_box(write_jsonl(&events, io::sink())))
        });
        group.throughput(Throughput::BytesDecimal(csv_bytes));
        group.bench_function("csv", |b| {
            b.iter(|| black_box(write_csv(&rows, &profile, io::sink())))
        });
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
