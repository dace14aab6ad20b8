//! The machines and definitions the programs of the shared corpus were
//! written for, shared by the corpus tests of lowering
//! (`gcodec-sema/tests/corpus.rs`) and running
//! (`gcodec-exec/tests/corpus.rs`).

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
