//! Times the two passes of a streamed run over a program (a development
//! aid for the streaming work; docs/ARCHITECTURE.md, "Streaming"): pass 1
//! parses every chunk and builds the outline, dropping each tree; pass 2
//! parses every chunk again and lowers it, dropping each chunk's
//! instructions. One thread; the CLI's allocator and settings.
//!
//! `stream_passes FILE [LINES_PER_CHUNK]`
use std::time::{Duration, Instant};

use gcodec_parser::parse_chunk;
use gcodec_sema::ProgramKind;
use gcodec_sema::{ChunkLowering, Definitions, outline_chunks};
use gcodec_stream::chunks;

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;

fn main() {
    // SAFETY: `mi_option_set` only stores the value (see the CLI's main).
    unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .expect("usage: stream_passes FILE [LINES_PER_CHUNK]");
    let lines: usize = args.next().map_or(16_384, |l| l.parse().expect("a number"));
    let profile = gcodec_profile::builtin().expect("profile");
    let definitions = Definitions::new();
    let file = gcodec_source::SourceFile::read(std::path::Path::new(&path)).expect("read");
    let src = file.bytes();
    let t = Instant::now();
    let chunks = chunks(src, lines);
    let t_chunks = t.elapsed();

    let t = Instant::now();
    let (outline, _) = outline_chunks(
        &file,
        ProgramKind::of_file(&path),
        &chunks,
        1,
        &profile,
        &definitions,
    );
    let t_outline = t.elapsed();

    let t = Instant::now();
    let mut parsing = Duration::ZERO;
    let mut instructions = 0;
    let mut lowering = ChunkLowering::new(&outline, &profile, src);
    for chunk in &chunks {
        let started = Instant::now();
        let parsed = parse_chunk(src, file.encoding(), chunk, definitions.macros());
        parsing += started.elapsed();
        let lowered = lowering
            .lower(parsed.first_block, &parsed.blocks)
            .expect("chunks in order");
        instructions += lowered.instructions.len();
    }
    let t_lower = t.elapsed();
    eprintln!(
        "{} chunks of {lines} lines ({t_chunks:?}); pass 1 {t_outline:?}; pass 2 {t_lower:?} \
         (parsing {parsing:?}, lowering {:?}); {instructions} instructions",
        chunks.len(),
        t_lower - parsing
    );
}
