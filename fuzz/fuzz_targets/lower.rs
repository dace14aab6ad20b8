//! Feeds arbitrary bytes through parsing and lowering with every shipped
//! machine profile and checks what every lowering must satisfy: no panic,
//! a document that ends with `end`, every instruction's source span inside
//! the input with `start <= end` and on the line it names, every
//! diagnostic labelled in bounds (the lint rules' too), and JSON that
//! serialises.

#![no_main]

use gcodec_ail::Op;
use libfuzzer_sys::fuzz_target;

mod shipped;
use shipped::shipped_profiles;

fuzz_target!(|data: &[u8]| {
    let parse = gcodec_parser::parse_bytes("fuzz.mpf", data);
    let program = &parse.program;
    let len = data.len() as u32;
    for profile in shipped_profiles() {
        let lowered = gcodec_sema::lower(program, profile);
        let instructions = &lowered.document.instructions;
        assert!(
            matches!(instructions.last().map(|i| &i.op), Some(Op::End)),
            "the document ends with `end`"
        );
        for instruction in instructions {
            let source = &instruction.source;
            assert!(source.span.start <= source.span.end && source.span.end <= len);
            let (line, _) = program.line_col(source.span.start);
            assert_eq!(line, source.line, "{:?}", instruction.op);
        }
        for diagnostic in &lowered.diagnostics {
            for label in &diagnostic.labels {
                assert!(label.span.start <= label.span.end && label.span.end <= len);
            }
        }
        serde_json::to_vec(&lowered.document).expect("the document serialises");
        // The lint rules of `gcodec check` on the same document.
        let kind = gcodec_sema::ProgramKind::Main;
        for diagnostic in &gcodec_sema::lint::lint(program, &lowered.document, kind, profile) {
            for label in &diagnostic.labels {
                assert!(label.span.start <= label.span.end && label.span.end <= len);
            }
        }
    }
});
