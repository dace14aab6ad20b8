//! Throughput of the modal-state analysis (`gcodec_sema::modal`), in
//! blocks per second (`Throughput::Elements`), on the front end's generated
//! 1,000,000-block program lowered with the built-in profile. Lexing,
//! parsing and lowering happen once, outside the timed part.
//! `cargo bench -p gcodec-sema --bench modal`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use gcodec_sema::modal::{ModalStates, Start};

// The allocator of the `gcodec` binary, configured as it configures it
// (crates/gcodec-cli/src/main.rs), so that the figure is what users get.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;

#[path = "../../gcodec-parser/benches/program/mod.rs"]
mod program;

const BLOCKS: usize = 1_000_000;

fn bench(c: &mut Criterion) {
    // SAFETY: `mi_option_set` only stores the value (see the CLI's main).
    unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
    let src = program::generate(BLOCKS);
    let profile = gcodec_profile::builtin().expect("built-in profile");
    let parsed = gcodec_parser::parse_bytes("bench.mpf", &src);
    let document = gcodec_sema::lower(&parsed.program, &profile).document;
    drop(parsed);
    let mut group = c.benchmark_group("modal");
    group.throughput(Throughput::Elements(BLOCKS as u64));
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(20);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(10));
    group.bench_function("1M_blocks", |b| {
        b.iter_with_large_drop(|| {
            ModalStates::analyse(black_box(&document), Start::Reset(&profile))
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
