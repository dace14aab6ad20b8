//! Throughput of lex + parse + lower, in MB/s (`Throughput::BytesDecimal`),
//! on the front end's generated 1,000,000-block program, with the built-in
//! profile. `cargo bench -p gcodec-sema --bench lower`; see
//! docs/performance.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};

// The allocator of the `gcodec` binary, configured as it configures it
// (crates/gcodec-cli/src/main.rs), so that the figure is what users get.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;

#[path = "../../gcodec-parser/benches/program/mod.rs"]
mod program;

fn bench(c: &mut Criterion) {
    // SAFETY: `mi_option_set` only stores the value (see the CLI's main).
    unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
    let src = program::generate(1_000_000);
    let profile = gcodec_profile::builtin().expect("built-in profile");
    let mut group = c.benchmark_group("lex+parse+lower");
    group.throughput(Throughput::BytesDecimal(src.len() as u64));
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(15));
    group.bench_function("1M_blocks", |b| {
        // Both trees are dropped outside the timed part.
        b.iter_with_large_drop(|| {
            let parsed = gcodec_parser::parse_bytes("bench.mpf", black_box(&src));
            let lowered = gcodec_sema::lower(&parsed.program, &profile);
            (parsed, lowered)
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
