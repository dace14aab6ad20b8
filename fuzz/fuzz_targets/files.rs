//! Feeds arbitrary bytes through the file loader and the writers, as
//! `gcodec run` goes: the input is split at NUL bytes into a main program
//! and the texts of the subprograms `SUB1` and `SUB2` (each missing text
//! is the one before it), which are written into a fresh temporary
//! directory in the shapes the first byte chooses; the main program is
//! read from its file and run streamed (`run_main`) with that directory
//! on the search path and at most 2,000 blocks. The events are written
//! as JSONL, as the text trace (through the terminal's escaping) and as
//! CSV rows, all into memory, and every runtime diagnostic is rendered
//! against the file it names, as the CLI renders it.
//!
//! Checks: no panic, no hang, exactly one `program_end` and it is the last
//! event, one JSONL line per event and each parses as JSON, the CSV starts
//! with its header, and no control character but tab and line feed
//! reaches the text trace or a rendered diagnostic.
//!
//! The layout (`root` is the temporary directory):
//!
//! ```text
//! root/prog/MAIN.MPF       the main program; its directory is searched first
//! root/prog/…SUB1…         SUB1, in the caller's directory
//! root/sp/…SUB2…           SUB2, in the `search_dirs` directory
//! root/outside/            where a link out of the search path points
//! ```

#![no_main]

use std::fs;
use std::io::BufRead;
use std::path::Path;
use std::sync::Arc;

use gcodec_driver::event::{CsvWriter, EventKind, EventSink, JsonlSink, TextSink, VecSink};
use gcodec_driver::{RunSetup, read_source, run_main, runtime_diagnostic};
use gcodec_source::{EscapeControls, RenderOptions, is_escaped, render_diagnostics, render_kept};
use libfuzzer_sys::fuzz_target;

mod running;
use running::{assert_one_program_end_last, run_profiles};

const MAX_STEPS: u64 = 2_000;

/// How a subprogram's file is put into its search directory.
#[derive(Clone, Copy)]
enum Shape {
    /// `NAME.SPF`, a regular file.
    Plain,
    /// `NAME.SPF`, a link to `lib/NAME.SPF` below the same directory
    /// (allowed: inside the search path).
    LinkInside,
    /// `NAME.SPF`, a link to `root/outside/NAME.SPF` (refused:
    /// `gcodec::io::outside_search_path`).
    LinkOutside,
    /// `_N_NAME_SPF`, the control's internal name.
    InternalName,
}

impl Shape {
    fn from_bits(bits: u8) -> Self {
        match bits & 3 {
            0 => Self::Plain,
            1 => Self::LinkInside,
            2 => Self::LinkOutside,
            _ => Self::InternalName,
        }
    }
}

/// Writes the subprogram `name` with `text` into `dir` in `shape`.
fn write_subprogram(root: &Path, dir: &Path, name: &str, text: &[u8], shape: Shape) {
    let file_name = format!("{name}.SPF");
    match shape {
        Shape::Plain => fs::write(dir.join(&file_name), text).expect("write"),
        Shape::LinkInside => {
            let lib = dir.join("lib");
            fs::create_dir_all(&lib).expect("mkdir");
            fs::write(lib.join(&file_name), text).expect("write");
            std::os::unix::fs::symlink(Path::new("lib").join(&file_name), dir.join(&file_name))
                .expect("symlink");
        }
        Shape::LinkOutside => {
            let target = root.join("outside").join(&file_name);
            fs::write(&target, text).expect("write");
            std::os::unix::fs::symlink(&target, dir.join(&file_name)).expect("symlink");
        }
        Shape::InternalName => fs::write(dir.join(format!("_N_{name}_SPF")), text).expect("write"),
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&choice, rest)) = data.split_first() else {
        return;
    };
    let mut texts = rest.splitn(3, |&b| b == 0);
    let main_text = texts.next().unwrap_or_default();
    let sub1_text = texts.next().unwrap_or(main_text);
    let sub2_text = texts.next().unwrap_or(sub1_text);
    let profile = &run_profiles()[usize::from(choice >> 4 & 3)];

    let root = tempfile::Builder::new()
        .prefix("gcodec-fuzz-files")
        .tempdir()
        .expect("a temporary directory");
    let (prog, sp) = (root.path().join("prog"), root.path().join("sp"));
    for dir in [&prog, &sp, &root.path().join("outside")] {
        fs::create_dir(dir).expect("mkdir");
    }
    let main_path = prog.join("MAIN.MPF");
    fs::write(&main_path, main_text).expect("write");
    write_subprogram(
        root.path(),
        &prog,
        "SUB1",
        sub1_text,
        Shape::from_bits(choice),
    );
    write_subprogram(
        root.path(),
        &sp,
        "SUB2",
        sub2_text,
        Shape::from_bits(choice >> 2),
    );

    let max_len = *profile.program.max_file_size.get_ref();
    let Ok(main) = read_source(&main_path, max_len, profile.program.text_encoding()) else {
        // UTF-16 text is refused before it is run.
        return;
    };
    let main = Arc::new(main);
    let mut setup = RunSetup::new(Arc::clone(profile));
    setup.search_dirs = vec![sp];
    setup.options.max_steps = MAX_STEPS;
    setup.options.stop_at_m0 = false;
    let mut events = VecSink::new();
    let mut rows = CsvWriter::for_profile(Vec::new(), profile).expect("the header goes to memory");
    let report = run_main(Arc::clone(&main), &setup, &mut events, Some(&mut rows));
    let outcome = report.outcome.expect("events go to memory");
    assert!(outcome.summary.blocks <= MAX_STEPS + 1);

    assert_one_program_end_last(&events.events);

    let mut jsonl = JsonlSink::new(Vec::new());
    let mut trace = Vec::new();
    let mut text = TextSink::new(EscapeControls::new(&mut trace));
    let options = RenderOptions {
        color: false,
        limit: None,
    };
    let mut rendered = String::new();
    for event in &events.events {
        jsonl.event(event).expect("memory");
        text.event(event).expect("memory");
        if let EventKind::Diagnostic(d) = &event.kind {
            let file = setup.loaded_files.get(&event.source.file);
            let diagnostic = runtime_diagnostic(d, &event.source, file.as_deref());
            rendered.push_str(&render_diagnostics(&[diagnostic], file.as_deref(), options));
        }
    }
    rendered.push_str(&render_kept(&report.diagnostics, Some(&main), options));

    let jsonl = jsonl.into_inner().expect("memory");
    let mut lines = 0;
    for line in jsonl.lines() {
        let line = line.expect("JSONL is UTF-8");
        serde_json::from_str::<serde_json::Value>(&line).expect("every JSONL line is JSON");
        lines += 1;
    }
    assert_eq!(lines, events.events.len(), "one JSONL line per event");

    text.into_inner().expect("the trace goes to memory");
    let text = std::str::from_utf8(&trace).expect("the trace is UTF-8");
    assert!(
        !text.chars().any(is_escaped),
        "a raw control character in the trace"
    );
    assert!(
        !rendered.chars().any(is_escaped),
        "a raw control character in a diagnostic"
    );

    let csv = rows.into_inner().expect("memory");
    assert!(csv.starts_with(b"block,file,line,level,"), "the CSV header");
});
