//! Every program of the shared corpus lowers without an error diagnostic,
//! with the default profile or the profile of the machine it was written
//! for, and the definition files of that machine. Warnings (constructs not
//! lowered yet, M functions the profile does not know) are allowed.
//! `SYNTAX_CHECK.SPF` is excluded: its machine-dependent lines are errors
//! by design (`syntax_check.rs`). Lines written for interpreters more
//! lenient than the control are errors on the control too
//! ([`EXPECTED_ERRORS`]): the test requires exactly those.

use std::path::PathBuf;

mod common;

use gcodec_testkit::corpus::{definitions, machine_profile};

/// Errors the control raises too, in programs written for more lenient
/// interpreters: `(file, line, code)`.
///
/// - `edge_cases.mpf:40` declares `DEPTH` after motion blocks; the control
///   accepts `DEF` only before the first executable statement (alarm
///   14500).
/// - `proc1_test.mpf:18` writes `_X=500` for an AXIS variable `_X`; on the
///   control that assigns a number to the variable, which has no such
///   conversion (alarm 14096); moving the axis it names is `AX[_X]=500`,
///   as the Siemens cycles in the same corpus write it.
/// - `simple.mpf:2,3` (a parser test of the CEAD interpreter) programs
///   `G2`/`G3` end points without centre or radius (the control cannot
///   build the circle) and `X` twice in one block (alarm 12010).
/// - `multiple_m_codes.mpf:4` (a test of the CEAD interpreter's M codes)
///   writes `M3 M4 M5` in one block, three functions of the master
///   spindle's auxiliary-function group (alarm 14760).
const EXPECTED_ERRORS: &[(&str, u32, &str)] = &[
    (
        "peer-cead/simple.mpf",
        2,
        "gcodec::lower::missing_circle_data",
    ),
    ("peer-cead/simple.mpf", 3, "gcodec::lower::repeated_axis"),
    (
        "peer-cead/simple.mpf",
        3,
        "gcodec::lower::missing_circle_data",
    ),
    (
        "peer-cead/multiple_m_codes.mpf",
        4,
        "gcodec::lower::m_group_conflict",
    ),
    (
        "peer-cead/edge_cases.mpf",
        40,
        "gcodec::lower::misplaced_definition",
    ),
    (
        "SinumerikLanguage/test/proc1_test.mpf",
        18,
        "gcodec::lower::type_mismatch",
    ),
];

#[test]
fn the_corpus_lowers_without_errors() {
    let Some(dir) = common::corpus_dir() else {
        return;
    };
    // Part programs only: the corpus's `.DEF` files are definitions.
    let files: Vec<PathBuf> = common::programs(&dir)
        .into_iter()
        .filter(|p| !p.extension().is_some_and(|e| e.eq_ignore_ascii_case("def")))
        .collect();
    assert!(files.len() >= 50, "found only {} programs", files.len());
    let mut failures = Vec::new();
    let mut expected_seen = [false; EXPECTED_ERRORS.len()];
    for path in files.iter().filter(|p| !p.ends_with("SYNTAX_CHECK.SPF")) {
        let shown = path.display().to_string();
        let bytes = std::fs::read(path).expect("readable");
        let parsed = gcodec_parser::parse_bytes(&shown, &bytes);
        let (machine, profile) = machine_profile(&shown);
        let definitions = definitions(&dir, &shown);
        let lowered = gcodec_sema::lower_with(&parsed.program, &profile, &definitions);
        for d in lowered.diagnostics.iter().filter(|d| d.is_error()) {
            let line = d.span().map_or(0, |s| parsed.program.line_col(s.start).0);
            let expected = EXPECTED_ERRORS.iter().position(|(file, l, code)| {
                shown.contains(file) && *l == line && *code == d.code.name()
            });
            if let Some(i) = expected {
                expected_seen[i] = true;
                continue;
            }
            failures.push(format!(
                "{shown}:{line} ({machine}): {} {}",
                d.code, d.message
            ));
        }
    }
    for (seen, (file, line, code)) in expected_seen.iter().zip(EXPECTED_ERRORS) {
        if !seen {
            failures.push(format!("{file}:{line}: expected {code}, not reported"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
