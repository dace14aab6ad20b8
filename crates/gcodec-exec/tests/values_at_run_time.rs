//! Computed values are never wrapped into range when the block runs: one
//! outside its range is a run-time diagnostic naming it (issue 14).

use gcodec_exec::event::{EventKind, ProgramEndReason};
use gcodec_source::Severity;

mod common;

/// The run's error diagnostics (code, message, line) and how it ended.
fn run(program: &str) -> (Vec<(&'static str, String, u32)>, ProgramEndReason) {
    let profile = gcodec_profile::builtin().expect("the built-in profile");
    let events = common::runs::events_of_text(profile, "VALUES.MPF", program);
    let mut errors = Vec::new();
    let mut end = None;
    for event in &events {
        match &event.kind {
            EventKind::Diagnostic(d) if d.severity == Severity::Error => {
                errors.push((d.code.name(), d.message.to_string(), event.source.line))
            }
            EventKind::ProgramEnd(e) => end = Some(e.reason),
            _ => {}
        }
    }
    (errors, end.expect("the program ends"))
}

#[test]
fn computed_address_extensions_outside_0_to_99_are_named() {
    for (value, word) in [
        ("-1", "S[NN]=100"),
        ("-1", "M[NN]=3"),
        ("100", "H[NN]=1"),
        ("-7", "SPOS[NN]=90"),
    ] {
        let program = format!("DEF INT NN={value}\nN10 {word}\nN20 M30\n");
        let (errors, end) = run(&program);
        let message = format!("the address extension {value} is outside 0…99");
        assert_eq!(errors, [("gcodec::run::overflow", message, 2)], "{word}");
        assert_eq!(end, ProgramEndReason::Alarm, "{word}");
    }
}

#[test]
fn tool_numbers_beyond_the_int_range_read_back_unwrapped() {
    // 4294967295 is a tool number (SPEC §10) but no INT: `$P_TOOLNO`
    // gives it as a REAL, never as −1.
    let (errors, end) = run(
        "T4294967295\nIF $P_TOOLP<>4294967295\nSETAL(61000)\nENDIF\nM6\nIF $P_TOOLNO<>4294967295\nSETAL(61001)\nENDIF\nM30\n",
    );
    assert_eq!(errors, []);
    assert_eq!(end, ProgramEndReason::M30);
}
