//! Runs a program with the built-in profile, events to a sink that counts
//! them, and prints how long each stage took (a development aid; `gcodec
//! run` is the tool).
use std::sync::Arc;
use std::time::Instant;

use gcodec_exec::channel::{Channel, RunOptions};
use gcodec_exec::event::{CountingSink, JsonlSink};
use gcodec_exec::loader::{FileLoader, SearchPath};
use gcodec_exec::program::Program;
use gcodec_sema::Definitions;
use gcodec_source::SourceFile;

fn main() {
    let path = std::env::args()
        .nth(1)
        .expect("usage: run_file FILE [jsonl]");
    let jsonl = std::env::args().nth(2).is_some();
    let profile = Arc::new(gcodec_profile::builtin().expect("profile"));
    let t = Instant::now();
    let file = SourceFile::read(std::path::Path::new(&path)).expect("read");
    let parsed = gcodec_parser::parse(&file);
    let t_parse = t.elapsed();
    let lowered = gcodec_sema::lower_with(&parsed.program, &profile, &Definitions::new());
    let t_lower = t.elapsed();
    std::mem::forget(parsed.program);
    let main = Arc::new(Program::new(
        "MAIN",
        Arc::from(file.name()),
        lowered.document,
    ));
    let mut loader = FileLoader::new(
        SearchPath::new(),
        Arc::clone(&profile),
        Arc::new(Definitions::new()),
    );
    let options = RunOptions::for_profile(&profile);
    let outcome = if jsonl {
        let mut sink = JsonlSink::new(std::io::sink());
        Channel::new(profile, options, &mut loader, &mut sink).run(main)
    } else {
        let mut sink = CountingSink::default();
        Channel::new(profile, options, &mut loader, &mut sink).run(main)
    }
    .expect("io");
    let t_run = t.elapsed();
    eprintln!(
        "parse {:?}, lower {:?}, run {:?}; {} blocks",
        t_parse,
        t_lower - t_parse,
        t_run - t_lower,
        outcome.summary.blocks
    );
}
