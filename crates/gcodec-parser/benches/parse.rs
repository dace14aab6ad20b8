//! Throughput of the lexer and of lexing + parsing, reported in MB/s
//! (`Throughput::BytesDecimal`: 10^6 bytes per second).
//!
//! `cargo bench -p gcodec-parser --bench parse`
//!
//! Two inputs from the deterministic generator in `program/`: 10,000 and
//! 1,000,000 blocks. Each is generated once. The "lex" group drains the
//! token iterator; the "lex+parse" group runs `parse_bytes` (which lexes,
//! parses, pairs control structures and drops nothing until the end); the
//! returned AST is dropped outside the timing. See docs/performance.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{
    BenchmarkId, Criterion, SamplingMode, Throughput, criterion_group, criterion_main,
};

mod program;

const SIZES: &[(usize, &str)] = &[(10_000, "10k_blocks"), (1_000_000, "1M_blocks")];

fn inputs() -> Vec<(&'static str, Vec<u8>)> {
    SIZES
        .iter()
        .map(|&(blocks, name)| (name, program::generate(blocks)))
        .collect()
}

fn configure(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    len: usize,
) {
    group.throughput(Throughput::BytesDecimal(len as u64));
    if len > 1_000_000 {
        // Whole seconds per iteration: one iteration per sample, ten samples.
        group.sampling_mode(SamplingMode::Flat);
        group.sample_size(10);
        group.warm_up_time(Duration::from_secs(1));
        group.measurement_time(Duration::from_secs(10));
    } else {
        group.sample_size(20);
        group.warm_up_time(Duration::from_secs(1));
        group.measurement_time(Duration::from_secs(5));
    }
}

fn bench(c: &mut Criterion) {
    let inputs = inputs();

    for (name, src) in &inputs {
        let mut group = c.benchmark_group("lex");
        configure(&mut group, src.len());
        group.bench_with_input(BenchmarkId::from_parameter(name), src, |b, src| {
            b.iter(|| gcodec_lexer::Lexer::new(black_box(src)).count())
        });
        group.finish();
    }

    for (name, src) in &inputs {
        let mut group = c.benchmark_group("lex+parse");
        configure(&mut group, src.len());
        group.bench_with_input(BenchmarkId::from_parameter(name), src, |b, src| {
            // The AST is dropped outside the timed part: lex + parse is
            // what is measured (dropping is reported by `parse_file`).
            b.iter_with_large_drop(|| {
                let parsed = gcodec_parser::parse_bytes("bench.mpf", black_box(src));
                assert!(parsed.diagnostics.is_empty());
                parsed
            })
        });
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
