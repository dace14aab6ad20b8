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
