//! The lint rules on every program of the workspace and the corpus, as a
//! main program and as a subprogram: no panic, every label inside the
//! file, and no rule reporting at error level (a lint finding is an
//! opinion about a program the control accepts).

use gcodec_sema::ProgramKind;
use gcodec_source::Severity;

#[test]
fn the_rules_hold_on_every_program() {
    let profile = gcodec_profile::builtin().expect("built-in profile");
    gcodec_testkit::paths::each_program(|name, bytes| {
        let parsed = gcodec_parser::parse_bytes(name, bytes);
        let len = bytes.len() as u32;
        for kind in [ProgramKind::Main, ProgramKind::Subprogram] {
            let lowered = gcodec_sema::lower_program(
                &parsed.program,
                kind,
                &profile,
                &gcodec_sema::Definitions::new(),
            );
            for d in &gcodec_sema::lint::lint(&parsed.program, &lowered.document, kind, &profile) {
                assert_eq!(d.code.area(), "lint", "{name}: {d:?}");
                assert_ne!(d.severity, Severity::Error, "{name}: {d:?}");
                for label in &d.labels {
                    assert!(
                        label.span.start <= label.span.end && label.span.end <= len,
                        "{name}: {d:?}"
                    );
                }
            }
        }
    });
}

/// A finding in nearly every block (block numbers that repeat) is kept
/// up to what a file may keep and counted beyond, not held whole.
#[test]
fn findings_beyond_what_a_file_keeps_are_counted() {
    let profile = gcodec_profile::builtin().expect("built-in profile");
    let blocks = gcodec_source::MAX_KEPT_PER_FILE + 5;
    let text = "N1 G0 X0\n".repeat(blocks) + "M30\n";
    let parsed = gcodec_parser::parse_bytes("wrapped.mpf", text.as_bytes());
    let kind = ProgramKind::Main;
    let lowered = gcodec_sema::lower_program(
        &parsed.program,
        kind,
        &profile,
        &gcodec_sema::Definitions::new(),
    );
    let found = gcodec_sema::lint::lint(&parsed.program, &lowered.document, kind, &profile);
    assert_eq!(found.total(), blocks as u64 - 1);
    assert_eq!(found.iter().count(), gcodec_source::MAX_KEPT_PER_FILE);
}
