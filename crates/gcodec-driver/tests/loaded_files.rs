//! A run keeps the files of the programs it loads, so that its diagnostic
//! events can be labelled without reading a file again.

use std::sync::Arc;

use gcodec_driver::event::{Event, EventKind, EventSink};
use gcodec_driver::{RunSetup, builtin_profile_file, load_profile, read_source, run_main};

/// Keeps the file name of every diagnostic event.
#[derive(Default)]
struct DiagnosticFiles(Vec<Arc<str>>);

impl EventSink for DiagnosticFiles {
    fn event(&mut self, event: &Event) -> std::io::Result<()> {
        if let EventKind::Diagnostic(_) = event.kind {
            self.0.push(Arc::clone(&event.source.file));
        }
        Ok(())
    }
}

#[test]
fn a_run_keeps_the_main_and_each_called_program_file() {
    let dir = std::env::temp_dir().join(format!("gcodec-driver-loaded-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let main = dir.join("main.mpf");
    std::fs::write(&main, "N10 SUB_DIV\nN20 M30\n").expect("write");
    std::fs::write(dir.join("SUB_DIV.SPF"), "N10 R1=0\nN20 R2=5/R1\nN30 M17\n").expect("write");
    let (profile, _) = load_profile(&builtin_profile_file()).expect("built-in profile");
    let max_len = *profile.program.max_file_size.get_ref();
    let setup = RunSetup::new(profile);
    let encoding = gcodec_source::TextEncoding::default();
    let main = Arc::new(read_source(&main, max_len, encoding).expect("read"));
    let mut sink = DiagnosticFiles::default();
    run_main(Arc::clone(&main), &setup, &mut sink, None);
    let files = &setup.loaded_files;
    assert!(Arc::ptr_eq(&files.get(main.name()).expect("main"), &main));
    // The division by zero is in the subprogram, whose file is kept.
    let [called] = sink.0.as_slice() else {
        panic!("one diagnostic: {:?}", sink.0);
    };
    let kept = files.get(called).expect("the called program's file");
    assert_eq!(kept.bytes(), b"N10 R1=0\nN20 R2=5/R1\nN30 M17\n");
    assert!(files.get("NOT_LOADED.SPF").is_none());
}
