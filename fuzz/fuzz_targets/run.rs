//! Feeds arbitrary bytes through parsing, lowering and the channel with
//! every shipped machine profile, and checks what every run must satisfy:
//! no panic and no hang (the step limit is small), exactly one
//! `program_end`, the last event, and every event serialises. The input
//! also serves as the one subprogram `SUB` the program may call, so calls,
//! parameters and returns are exercised too.

#![no_main]

use std::sync::Arc;

use gcodec_driver::event::VecSink;
use gcodec_driver::{Definitions, MemoryLoader, ProgramKind, RunOptions, compile};
use gcodec_exec::channel::Channel;
use gcodec_source::SourceFile;
use libfuzzer_sys::fuzz_target;

mod running;
use running::{assert_one_program_end_last, run_profiles};

fuzz_target!(|data: &[u8]| {
    let file = Arc::new(SourceFile::new("fuzz.mpf", data));
    for profile in run_profiles() {
        let definitions = Arc::new(Definitions::new());
        let main = compile(Arc::clone(&file), ProgramKind::Main, profile, &definitions)
            .into_loaded("FUZZ");
        let mut loader = MemoryLoader::new(Arc::clone(profile), Arc::clone(&definitions))
            .with_program("SUB.SPF", data);
        let mut options = RunOptions::for_profile(profile);
        options.max_steps = 2_000;
        options.stop_at_m0 = false;
        let mut sink = VecSink::new();
        let outcome = Channel::new(Arc::clone(profile), options, &mut loader, &mut sink)
            .run(main.program)
            .expect("events go to memory");
        assert_one_program_end_last(&sink.events);
        assert!(outcome.summary.blocks <= 2_001);
        for event in &sink.events {
            serde_json::to_vec(event).expect("the event serialises");
        }
    }
});
