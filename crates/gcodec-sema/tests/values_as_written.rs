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
    for (program, message) in [
        ("T99999999999", "T99999999999 is out of range"),
        ("T=99999999999", "T99999999999 is out of range"),
        ("T0099999999999", "T0099999999999 is out of range"),
        (
            "T=000099999999999999999999",
            "T000099999999999999999999 is out of range",
        ),
    ] {
        assert_eq!(
            error(program),
            ("gcodec::lower::invalid_value", message.to_owned()),
            "{program}"
        );
    }
}

#[test]
fn g_commands_are_named_as_written_not_through_their_real() {
    for (program, written) in [
        ("G99999999999", "G99999999999"),
        // Its REAL reads 100000000000000000000; the saturated `u64`,
        // 18446744073709551615.
        ("G99999999999999999999", "G99999999999999999999"),
        ("G0999", "G0999"),
        ("G=0999", "G0999"),
    ] {
        let message = format!("`{written}` is not a G command of the control");
        assert_eq!(
            error(program),
            ("gcodec::lower::unknown_g", message),
            "{program}"
        );
    }
}

#[test]
fn indirect_g_groups_and_indices_are_named_as_written() {
    assert_eq!(
        error("G[065]=1"),
        (
            "gcodec::lower::invalid_indirect_g",
            "`G[065]`: G groups are numbered 1…64".to_owned()
        )
    );
    assert_eq!(
        error("G[8]=00999"),
        (
            "gcodec::lower::invalid_indirect_g",
            "G group 8 has no command with index 00999".to_owned()
        )
    );
}

#[test]
fn cutting_edges_and_m_functions_name_the_value_as_written() {
    for (program, message) in [
        ("D99999999999", "D99999999999 is out of range"),
        ("D=40000", "D40000 is out of range"),
        ("D040000", "D040000 is out of range"),
        ("M99999999999", "M99999999999 is out of range"),
        ("M002147483648", "M002147483648 is out of range"),
        (
            "M2=99999999999999999999",
            "M99999999999999999999 is out of range",
        ),
    ] {
        assert_eq!(
            error(program),
            ("gcodec::lower::invalid_value", message.to_owned()),
            "{program}"
        );
    }
}

#[test]
fn extension_constants_out_of_range_name_the_value_as_written() {
    for (program, message) in [
        (
            "S[0100]=1000",
            "`S[0100]`: a spindle number is a whole number 0…99",
        ),
        (
            "M[100]=3",
            "`M[100]`: a spindle number is a whole number 0…99",
        ),
        (
            "M[2.5]=3",
            "`M[2.5]`: a spindle number is a whole number 0…99",
        ),
        (
            "SPOS[99999999999]=90",
            "`SPOS[99999999999]`: a spindle number is a whole number 0…99",
        ),
        ("H0100=5", "H extension 0100 is out of range"),
        ("H[100]=5", "H extension 100 is out of range"),
        ("H1EX39", "H value 1EX39 is out of range"),
        ("H2=-1EX39", "H value -1EX39 is out of range"),
    ] {
        assert_eq!(
            error(program),
            ("gcodec::lower::invalid_value", message.to_owned()),
            "{program}"
        );
    }
}

#[test]
fn declarations_name_lengths_counts_and_characters_as_written() {
    for (program, code, message) in [
        (
            "DEF STRING[99999999999] TXT",
            "gcodec::lower::invalid_value",
            "`STRING[99999999999]`: a string length is a whole number 1…4294967295",
        ),
        (
            "DEF STRING[0] TXT",
            "gcodec::lower::invalid_value",
            "`STRING[0]`: a string length is a whole number 1…4294967295",
        ),
        (
            "PROC TST(STRING[099999999999] TXT)",
            "gcodec::lower::invalid_value",
            "`STRING[099999999999]`: a string length is a whole number 1…4294967295",
        ),
        (
            "DEF REAL AA[3]=REP(0,99999999999999999999)",
            "gcodec::lower::index_out_of_range",
            "99999999999999999999 values do not fit in `AA`, which has 3 elements",
        ),
        (
            "DEF REAL AA[3]=REP(0,-0.50)",
            "gcodec::lower::invalid_value",
            "the count of `REP` must be a whole number of at least 1, not -0.50",
        ),
        (
            "DEF CHAR CC=0256",
            "gcodec::lower::type_mismatch",
            "`CC` is CHAR (0…255); 0256 is outside",
        ),
    ] {
        assert_eq!(
            error(&format!("{program}\nM30")),
            (code, message.to_owned()),
            "{program}"
        );
    }
}

#[test]
fn array_sizes_beyond_64_bits_are_left_to_the_run() {
    // 3 × (2^32 − 1) elements overflow a `u64`: lowering must neither
    // panic nor wrap the count, and the run refuses the declaration.
    let lowered = lower_with(
        &profile(""),
        "DEF REAL AA[4294967295,4294967295,4294967295]=(1,2)\nM30",
    );
    assert!(!lowered.has_errors(), "{:?}", lowered.diagnostics);
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
