//! Runs a program with the built-in profile and prints the text trace
//! (a development aid until `gcodec run` exists).
use std::sync::Arc;

use gcodec_exec::channel::{Channel, RunOptions};
use gcodec_exec::event::TextSink;
use gcodec_exec::loader::{FileLoader, SearchPath, compile};
use gcodec_sema::Definitions;
use gcodec_source::SourceFile;

fn main() {
    let path = std::env::args().nth(1).expect("file");
    let profile = Arc::new(gcodec_profile::builtin().expect("profile"));
    let file = SourceFile::read(std::path::Path::new(&path)).expect("read");
    let loaded = compile("MAIN", &file, &profile, &Definitions::new(), false);
    for d in &loaded.diagnostics {
        eprintln!("{d:?}");
    }
    let mut loader = FileLoader::new(
        SearchPath::new(),
        Arc::clone(&profile),
        Arc::new(Definitions::new()),
    );
    let mut sink = TextSink::new(std::io::stdout());
    let options = RunOptions::for_profile(&profile);
    let outcome = Channel::new(profile, options, &mut loader, &mut sink)
        .run(loaded.program)
        .expect("io");
    eprintln!("{}", outcome.summary);
}
