//! Out-of-range values are diagnosed as written, never as a wrapped or
//! saturated number (SPEC §10, issue 14): one test per address family.

mod common;

use common::{lower_with, machine as profile};

/// The one error of lowering `program`: its code and message.
fn error(program: &str) -> (&'static str, String) {
    let lowered = lower_with(&profile(""), program);
    let errors: Vec<_> = lowered
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .collect();
    assert_eq!(errors.len(), 1, "{program}: {:?}", lowered.diagnostics);
    (errors[0].code.name(), errors[0].message.to_string())
}

#[test]
fn tool_numbers_beyond_32_bits_are_invalid_values_as_written() {
    for (program, written) in [
        ("T99999999999", "T99999999999"),
        ("T=99999999999", "T99999999999"),
    ] {
        let (code, message) = error(program);
        assert_eq!(code, "gcodec::lower::invalid_value", "{program}");
        assert!(message.contains(written), "{program}: {message}");
        assert!(!message.contains("4294967295"), "{program}: {message}");
    }
}

#[test]
fn g_commands_beyond_64_bits_are_named_unsaturated() {
    let (code, message) = error("G99999999999");
    assert_eq!(code, "gcodec::lower::unknown_g");
    assert!(message.contains("G99999999999"), "{message}");
    let (_, message) = error("G99999999999999999999");
    assert!(!message.contains("18446744073709551615"), "{message}");
}

#[test]
fn cutting_edges_and_m_functions_name_the_value_as_written() {
    for (program, written) in [("D99999999999", "D99999999999"), ("D=40000", "D40000")] {
        let (code, message) = error(program);
        assert_eq!(code, "gcodec::lower::invalid_value", "{program}");
        assert!(message.contains(written), "{program}: {message}");
    }
    let (code, message) = error("M99999999999");
    assert_eq!(code, "gcodec::lower::invalid_value");
    assert!(message.contains("M99999999999"), "{message}");
}

#[test]
fn string_limits_count_characters_not_utf8_bytes() {
    let p = profile("");
    // "äöü" is 3 characters (6 UTF-8 bytes): it fits a STRING[3].
    let fits = lower_with(&p, "DEF STRING[3] TXT=\"äöü\"\nM30");
    assert!(!fits.has_errors(), "{:?}", fits.diagnostics);
    let (code, message) = error("DEF STRING[2] TXT=\"äöü\"\nM30");
    assert_eq!(code, "gcodec::lower::type_mismatch");
    assert!(message.contains("3 characters"), "{message}");
}
