use gcodec_sema::Definitions;
use gcodec_source::SourceFile;
use std::sync::Arc;
use std::time::Instant;
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;
fn main() {
    unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, -1) };
    let path = std::env::args().nth(1).unwrap();
    let threads: usize = std::env::args().nth(2).map_or(2, |s| s.parse().unwrap());
    let profile = Arc::new(gcodec_profile::builtin().expect("profile"));
    let file = SourceFile::read(std::path::Path::new(&path)).expect("read");
    for round in 0..3 {
        let t = Instant::now();
        let parsed = gcodec_parser::parse_bytes_in_segments(file.name(), file.bytes(), threads);
        let tp = t.elapsed();
        let t = Instant::now();
        let lowered =
            gcodec_sema::lower_in_parts(&parsed.program, &profile, &Definitions::new(), threads);
        let tl = t.elapsed();
        eprintln!(
            "round {round}: parse {tp:?} lower {tl:?} ({} instr)",
            lowered.document.instructions.len()
        );
    }
}
