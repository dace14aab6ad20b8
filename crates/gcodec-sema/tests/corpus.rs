//! Every program of the shared corpus lowers without an error diagnostic,
//! with the default profile or the profile of the machine it was written
//! for, and the definition files of that machine. Warnings (constructs not
//! lowered yet, M functions the profile does not know) are allowed.
//! `SYNTAX_CHECK.SPF` is excluded: its machine-dependent lines are errors
//! by design (`syntax_check.rs`). Two lines written for interpreters more
//! lenient than the control are errors on the control too
//! ([`EXPECTED_ERRORS`]): the test requires exactly those.

use std::path::PathBuf;

mod common;

/// The machine a part of the corpus was written for; the default profile
/// for everything else. `tool.mpf` selects tools by name, so its machine
/// has tool management; its tool table is unknown, so the shipped table is
/// left out (see `profile`).
const MACHINES: &[(&str, &str)] = &[
    ("NadjImre+NC-Programi-za-FB422", "grinder_fb422.toml"),
    (
        "PDubovikov+SinumerikLanguage/SinumerikLanguage/test/slot.mpf",
        "mill_5axis.toml",
    ),
    ("peer-cead/edge_cases.mpf", "mill_5axis.toml"),
    ("peer-cead/for_loop.mpf", "mill_5axis.toml"),
    ("peer-cead/repeat.mpf", "mill_5axis.toml"),
    ("peer-cead/tool.mpf", "mill_tool_management.toml"),
];

/// The definition files of a machine: the FB422 programs use the global
/// user data of its `MGUD.DEF`.
const DEFINITION_FILES: &[(&str, &str)] = &[(
    "NadjImre+NC-Programi-za-FB422",
    "real/NadjImre+NC-Programi-za-FB422/DEF.DIR/MGUD.DEF",
)];

/// Names programs use that are defined where the corpus cannot show them;
/// a real control has them, so they are made known without a type
/// (`Definitions::assume_defined`).
///
/// - FB422: its other definition files (the global data of its grinding,
///   dressing and measuring cycles such as `NazivToc_A[…]`, the macros
///   `M_ROLIK_START`/`M_ROLIK_STOP`) are not in the corpus; the programs
///   ran on that machine.
/// - CEAD: its interpreter creates a variable on its first assignment and
///   runs every example after `defaults.mpf` (its README), which defines
///   `aa` and `bb`; on a control these would be global user data. `ELX`
///   and `E` are axes of the printer it was written for (`ELX=3087.0`,
///   `ACC[E]=50`), which no shipped profile has.
const ASSUMED_NAMES: &[(&str, &[&str])] = &[
    (
        "NadjImre+NC-Programi-za-FB422",
        &[
            "NazivToc_A",
            "NazivAbriht",
            "BrojIviceToc_A",
            "BrojIviceAbriht",
            "NACIN_A",
            "RADUDUB",
            "CEN_X",
            "PREKIDU",
            "Oblikam_a",
            "M_ROLIK_STOP",
            "M_ROLIK_START",
            "KorakX",
            "PODHODZ",
            "PREKIDXA",
            "PODHODX",
            "PRIO",
            "PREOSTALO",
            "BROJPROL",
            "komentar_a",
            "KOMADA",
            "BRZA",
            "CEN_Z",
            "PADAJUCI",
            "OPERACIJA_BROJ",
            "RAZLIKA",
            "BEZBEDNIX",
            "BEZBEDNIZ",
            "OBLIKAM",
            "komentar",
            "BRUS",
            "KORC",
            "KORX",
            "KORZ",
            "BRUSSMER",
            "NazivToc",
            "BrojIviceToc",
            "ODSKOK_SKROZ",
            "parkprec",
            "parkpoz",
            "ODSKOK_BRUS",
            "PREKIDX",
            "PREKIDZ",
            "RABHOD",
            "XMERENJA",
            "UMERENJA",
            "ReturnDist",
            "DiamCorr",
            "AKTIVNIKOORDSIS",
            "AKTIVNIALAT",
            "AKTIVNAOSTRICA",
            "AKTIVNIBROJ",
            "AKTIVNOUNUTRASNJE",
            "AKTIVNASTRANACEONOG",
            "AKTIVNASTRANAUNUTRASNJEG",
            "PosCorr",
            "DISPR",
            "MaxFaza",
            "ThHa",
            "KordSys",
            "THPI",
            "THST",
            "THD2",
            "POZZ",
            "HLADJENJE",
            "PREC",
            "DODB",
            "BRZU",
        ],
    ),
    (
        "peer-cead/",
        &[
            "aa",
            "bb",
            "nn",
            "m",
            "o",
            "E_MULTIPLIER",
            "F_MULTI",
            "ELX",
            "E",
        ],
    ),
];

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
const EXPECTED_ERRORS: &[(&str, u32, &str)] = &[
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

/// The definitions a program of the corpus is lowered with.
fn definitions(dir: &std::path::Path, shown: &str) -> gcodec_sema::Definitions {
    let mut definitions = gcodec_sema::Definitions::new();
    for (part, file) in DEFINITION_FILES {
        if shown.contains(part) {
            let bytes = std::fs::read(dir.join(file)).expect("definition file");
            let diagnostics = definitions.load_bytes(file, &bytes);
            assert!(diagnostics.is_empty(), "{file}: {diagnostics:#?}");
        }
    }
    for (part, names) in ASSUMED_NAMES {
        if shown.contains(part) {
            for name in *names {
                definitions.assume_defined(name);
            }
        }
    }
    definitions
}

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
        let machine = MACHINES
            .iter()
            .find(|(part, _)| shown.contains(part))
            .map_or("default.toml", |(_, p)| p);
        let bytes = std::fs::read(path).expect("readable");
        let parsed = gcodec_parser::parse_bytes(&shown, &bytes);
        let mut profile = common::profile(machine);
        if shown.contains("peer-cead/tool.mpf") {
            profile.tools.clear();
        }
        let definitions = definitions(&dir, &shown);
        let lowered = gcodec_sema::lower_with(&parsed.program, &profile, &definitions);
        for d in lowered.diagnostics.iter().filter(|d| d.is_error()) {
            let line = d.span().map_or(0, |s| parsed.program.line_col(s.start).0);
            let expected = EXPECTED_ERRORS
                .iter()
                .position(|(file, l, code)| shown.contains(file) && *l == line && *code == d.code);
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
