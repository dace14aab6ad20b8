//! The machines and definitions the programs of the shared corpus were
//! written for, shared by the corpus tests of lowering
//! (`gcodec-sema/tests/corpus.rs`) and running
//! (`gcodec-exec/tests/corpus.rs`), and the errors they expect, which
//! the corpus check of `gcodec check` expects too
//! (`gcodec-cli/tests/check.rs`, `tests/corpus-check/gcodec.toml`).

use gcodec_source::{Code, codes};

/// The machine a part of the corpus was written for; the default profile
/// for everything else. `tool.mpf` selects tools by name, so its machine
/// has tool management; its tool table is unknown, so the shipped table is
/// left out (see `profile`).
pub const MACHINES: &[(&str, &str)] = &[
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
pub const DEFINITION_FILES: &[(&str, &str)] = &[(
    "NadjImre+NC-Programi-za-FB422",
    "real/NadjImre+NC-Programi-za-FB422/DEF.DIR/MGUD.DEF",
)];

/// Names programs use that are defined where the corpus cannot show them;
/// a real control has them, so they are made known without a type
/// (`Definitions::assume_defined`). None is a word of the language (a
/// keyword, an address, a G command, a predefined name): those are never
/// missing definitions, and a test checks it.
///
/// - FB422: its other definition files (the global data of its grinding,
///   dressing and measuring cycles such as `NazivToc_A[…]`, the macros
///   `M_ROLIK_START`/`M_ROLIK_STOP`) are not in the corpus; the programs
///   ran on that machine.
/// - CEAD: its interpreter creates a variable on its first assignment and
///   runs every example after `defaults.mpf` (its README), which defines
///   `aa` and `bb`; on a control these would be global user data
///   (`nn`, `E_MULTIPLIER`, `F_MULTI` likewise). Its one-letter loop
///   variables and printer axes are errors on the control, listed with
///   their reasons in the corpus tests, not assumed here.
pub const ASSUMED_NAMES: &[(&str, &[&str])] = &[
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
    ("peer-cead/", &["aa", "bb", "nn", "E_MULTIPLIER", "F_MULTI"]),
];

/// Errors the control raises too, in programs written for more lenient
/// interpreters, found by parsing: `(file, line, code)`.
///
/// - `r_param.mpf:1` (a test of the CEAD interpreter) declares
///   `DEF REAL R0`: `R0` is the R parameter's address and number, not a
///   name, whose first two characters are letters or `_` (Fundamentals
///   10/2004, p. 60).
pub const EXPECTED_PARSE_ERRORS: &[(&str, u32, &Code)] =
    &[("peer-cead/r_param.mpf", 1, codes::parse::INVALID_NAME)];

/// Errors the control raises too, in programs written for more lenient
/// interpreters, found by lowering: `(file, line, code)`.
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
/// - `arrays.mpf:9…12` counts with `FOR m=…` and `FOR o=…`: the CEAD
///   interpreter creates a variable on its first assignment; on the
///   control a one-letter name is an address, never a variable.
/// - `axis_index_assignment.mpf:4,6` reads `ACC[E]` of the printer the
///   CEAD examples were written for: `E` is its extruder axis, and on the
///   control a one-letter name other than a machine axis is an address.
/// - `edge_cases.mpf:18` moves `ELX`, another axis of that printer, which
///   no shipped profile has (alarm 12550 "name not defined").
pub const EXPECTED_LOWERING_ERRORS: &[(&str, u32, &Code)] = &[
    ("peer-cead/arrays.mpf", 9, codes::lower::NOT_A_VARIABLE),
    ("peer-cead/arrays.mpf", 10, codes::lower::NOT_A_VARIABLE),
    ("peer-cead/arrays.mpf", 11, codes::lower::NOT_A_VARIABLE),
    ("peer-cead/arrays.mpf", 12, codes::lower::NOT_A_VARIABLE),
    (
        "peer-cead/axis_index_assignment.mpf",
        4,
        codes::lower::NOT_A_VARIABLE,
    ),
    (
        "peer-cead/axis_index_assignment.mpf",
        6,
        codes::lower::NOT_A_VARIABLE,
    ),
    (
        "peer-cead/edge_cases.mpf",
        18,
        codes::lower::UNDEFINED_VARIABLE,
    ),
    ("peer-cead/simple.mpf", 2, codes::lower::MISSING_CIRCLE_DATA),
    ("peer-cead/simple.mpf", 3, codes::lower::REPEATED_AXIS),
    ("peer-cead/simple.mpf", 3, codes::lower::MISSING_CIRCLE_DATA),
    (
        "peer-cead/multiple_m_codes.mpf",
        4,
        codes::lower::M_GROUP_CONFLICT,
    ),
    (
        "peer-cead/edge_cases.mpf",
        40,
        codes::lower::MISPLACED_DEFINITION,
    ),
    (
        "SinumerikLanguage/test/proc1_test.mpf",
        18,
        codes::lower::TYPE_MISMATCH,
    ),
];

/// The definitions a program of the corpus is lowered with.
pub fn definitions(dir: &std::path::Path, shown: &str) -> gcodec_sema::Definitions {
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

/// The profile a program of the corpus (`shown`: its path) runs with.
/// `tool.mpf` selects tools by name, so its machine has tool management;
/// its tool table is unknown, so the shipped table is left out.
pub fn machine_profile(shown: &str) -> (&'static str, gcodec_profile::Profile) {
    let machine = MACHINES
        .iter()
        .find(|(part, _)| shown.contains(part))
        .map_or("default.toml", |(_, p)| p);
    let mut profile = crate::profiles::profile(machine);
    if shown.contains("peer-cead/tool.mpf") {
        profile.tools.clear();
    }
    (machine, profile)
}
