//! The vocabulary's tables against the control's catalogue of names
//! (`catalogue` in the shared reference, `gcodec_testkit::reference_dir`;
//! skipped with a notice where it is absent): every name gcodec knows is
//! one the control knows, or is listed here with the reason it is not in
//! the catalogue. What the catalogue has and gcodec lacks is printed;
//! for the tables issue 16 completed (procedures, functions, system
//! variables) it fails the test, unless it is listed with its reason.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use gcodec_lang::addresses::NAMED_ADDRESSES;
use gcodec_lang::ggroups::G_GROUPS;
use gcodec_lang::keywords::{KEYWORDS, WORD_CONSTANTS, WORD_OPERATORS};
use gcodec_lang::procedures::PROCEDURES;
use gcodec_lang::{functions, sysvars};

/// The catalogue in the shared reference; `None`, with a notice, where
/// it is absent.
fn catalogue_dir() -> Option<PathBuf> {
    gcodec_testkit::reference_dir().map(|dir| dir.join("catalogue"))
}

/// The names of one catalogue list: the first column, upper case, without
/// the header of the `.tsv`.
fn names(dir: &Path, file: &str) -> BTreeSet<String> {
    let text = std::fs::read_to_string(dir.join(file))
        .unwrap_or_else(|e| panic!("{}: {e}", dir.join(file).display()));
    let skip = usize::from(file.ends_with(".tsv"));
    text.lines()
        .skip(skip)
        .filter_map(|line| line.split('\t').next())
        .map(|name| name.trim().to_ascii_uppercase())
        .filter(|name| !name.is_empty())
        .collect()
}

/// Checks that every name of `ours` is in `catalogue`, in another list
/// of the catalogue (`elsewhere`) or in `not_listed` (each with its
/// reason), and reports how many names of `catalogue` gcodec lacks.
fn check(
    what: &str,
    ours: &BTreeSet<String>,
    catalogue: &BTreeSet<String>,
    elsewhere: &BTreeSet<String>,
    not_listed: &[(&str, &str)],
) {
    let known: BTreeSet<String> = catalogue.union(elsewhere).cloned().collect();
    covers(
        &format!("{what}: not in the catalogue"),
        &known,
        ours,
        not_listed,
    );
    let lacking = catalogue.iter().filter(|n| !ours.contains(*n)).count();
    eprintln!(
        "{what}: {} known, {lacking} of the catalogue's {} not yet",
        ours.len(),
        catalogue.len()
    );
}

/// Checks that every name of `catalogue` is in `ours`, except those in
/// `left_out` (each with its reason).
fn check_complete(
    what: &str,
    ours: &BTreeSet<String>,
    catalogue: &BTreeSet<String>,
    left_out: &[(&str, &str)],
) {
    covers(
        &format!("{what}: the catalogue's names gcodec lacks"),
        ours,
        catalogue,
        left_out,
    );
}

/// Every name of `names` is in `set` or excused (each with its reason);
/// an excused name is one of `names` and not in `set`, so that an excuse
/// no longer needed fails.
fn covers(what: &str, set: &BTreeSet<String>, names: &BTreeSet<String>, excused: &[(&str, &str)]) {
    let excused_names: BTreeSet<&str> = excused.iter().map(|(name, _)| *name).collect();
    let missing: Vec<&String> = names
        .iter()
        .filter(|n| !set.contains(*n) && !excused_names.contains(n.as_str()))
        .collect();
    assert!(missing.is_empty(), "{what}: {missing:?}");
    for (name, _) in excused {
        assert!(
            names.contains(*name),
            "{what}: {name} is excused but not listed"
        );
        assert!(
            !set.contains(*name),
            "{what}: {name} is excused but no longer needs to be"
        );
    }
}

#[test]
fn g_commands_are_the_controls() {
    let Some(dir) = catalogue_dir() else { return };
    let ours: BTreeSet<String> = G_GROUPS
        .iter()
        .flat_map(|g| g.members)
        .filter(|m| !m.is_empty())
        .map(|m| m.to_string())
        .collect();
    let newer =
        "group 58 (relief cut) of the reference §3.2, newer than the catalogue's lists of 05/2017";
    check(
        "commands",
        &ours,
        &names(&dir, "commands.txt"),
        &BTreeSet::new(),
        &[("RELIEVEON", newer), ("RELIEVEOF", newer)],
    );
}

#[test]
fn keywords_are_the_controls() {
    let Some(dir) = catalogue_dir() else { return };
    let ours: BTreeSet<String> = [KEYWORDS, WORD_OPERATORS, WORD_CONSTANTS]
        .concat()
        .into_iter()
        .map(str::to_owned)
        .collect();
    // The catalogue lists the word operators, `VAR`, `RET`, `SET` and
    // `REP` with the operators, data types, procedures and functions.
    let elsewhere: BTreeSet<String> = [
        "operators.txt",
        "data-types.txt",
        "procedures.txt",
        "functions.txt",
    ]
    .into_iter()
    .flat_map(|file| names(&dir, file))
    .collect();
    check(
        "keywords",
        &ours,
        &names(&dir, "keywords.txt"),
        &elsewhere,
        &[
            ("TO", "`FOR … TO`, `CALL … BLOCK … TO` (reference §8)"),
            ("OF", "`CASE … OF` (reference §8)"),
            ("DEFAULT", "`CASE … DEFAULT` (reference §8)"),
            ("AS", "`DEFINE … AS` (reference §7.5)"),
            ("PROC", "`PROC` opens a subprogram (reference §8.1)"),
            ("BLOCK", "`CALL … BLOCK` (reference §8)"),
            ("TRUE", "a BOOL constant (reference §7.1)"),
            ("FALSE", "a BOOL constant (reference §7.1)"),
        ],
    );
}

#[test]
fn functions_are_the_controls() {
    let Some(dir) = catalogue_dir() else { return };
    let ours: BTreeSet<String> = functions::FUNCTIONS
        .iter()
        .map(|(_, name, _)| name.to_string())
        .collect();
    check(
        "functions",
        &ours,
        &names(&dir, "functions.txt"),
        &BTreeSet::new(),
        &[],
    );
    let modifier = "a dimension modifier of a value, `X=IC(5)` (`gcodec_lang::DimensionMode`)";
    let mut left_out: Vec<(&str, &str)> = [
        "AC", "ACN", "ACP", "CAC", "CACN", "CACP", "CDC", "CIC", "DAC", "DC", "DIC", "IC", "RAC",
        "RIC",
    ]
    .into_iter()
    .map(|name| (name, modifier))
    .collect();
    left_out.extend([
        (
            "QU",
            "quick output of an auxiliary function, `H=QU(7)`, read with it (SPEC §10.10)",
        ),
        (
            "SET",
            "a keyword of array initialisation, `A[0]=SET(1,2)` (reference §7.3)",
        ),
        (
            "REP",
            "a keyword of array initialisation, `A[0]=REP(0)` (reference §7.3)",
        ),
    ]);
    check_complete("functions", &ours, &names(&dir, "functions.txt"), &left_out);
}

#[test]
fn system_variables_are_the_controls() {
    let Some(dir) = catalogue_dir() else { return };
    let ours: BTreeSet<String> = sysvars::all().map(|v| v.name.to_owned()).collect();
    let catalogue = names(&dir, "system-variables.tsv");
    // The catalogue lists few machine or setting data (`$MC_…`, `$SN_…`):
    // the control has thousands, of which the registry holds the ones
    // programs use.
    let registry_only: BTreeSet<String> = ours
        .iter()
        .filter(|name| sysvars::is_machine_or_setting_data(name) && !catalogue.contains(*name))
        .cloned()
        .collect();
    check(
        "system variables",
        &ours,
        &catalogue,
        &registry_only,
        &[(
            "$R",
            "`$R[n]`, the R parameters as an array (reference §7.2)",
        )],
    );
    let mut left_out = vec![("R", "the R parameters, `R1` (reference §7.2), no `$` name")];
    let synact =
        "user data of synchronized actions (`SYG_…`), declared in a definition file, no `$` name";
    left_out.extend(
        catalogue
            .iter()
            .filter(|name| name.starts_with("SYG_"))
            .map(|name| (name.as_str(), synact)),
    );
    check_complete("system variables", &ours, &catalogue, &left_out);
}

/// The crate's copy of the catalogue's system variables, from which the
/// table is generated, is the shared reference's.
#[test]
fn the_generated_catalogue_is_the_references() {
    let Some(dir) = catalogue_dir() else { return };
    let reference = std::fs::read_to_string(dir.join("system-variables.tsv")).unwrap();
    let ours = include_str!("../data/system-variables.tsv");
    assert!(
        ours == reference,
        "data/system-variables.tsv differs from the reference's catalogue"
    );
}

#[test]
fn named_addresses_are_the_controls() {
    let Some(dir) = catalogue_dir() else { return };
    let ours: BTreeSet<String> = NAMED_ADDRESSES
        .iter()
        .map(|(_, name, _)| name.to_string())
        .collect();
    let catalogue = names(&dir, "addresses.txt");
    // The catalogue lists `AX` with the keywords.
    check(
        "named addresses",
        &ours,
        &catalogue,
        &names(&dir, "keywords.txt"),
        &[],
    );
    // Every address of the catalogue is a named address, or one of these.
    let din = "a letter of DIN words, lowered as that word (SPEC §4)";
    let orientation = "the letter of a DIN word with an extension: the lexer reads `A2=` as the axis word `A2` (SPEC §4); orientation by angles and vectors is not built";
    let circle = "circle data, lowered with the motion (SPEC §10.10)";
    let elsewhere: &[(&str, &str)] = &[
        ("A2", orientation),
        ("A3", orientation),
        ("A4", orientation),
        ("A5", orientation),
        ("B2", orientation),
        ("B3", orientation),
        ("B4", orientation),
        ("B5", orientation),
        ("C2", orientation),
        ("C3", orientation),
        ("C4", orientation),
        ("C5", orientation),
        ("D", din),
        (
            "D0",
            "`D0`, the cutting edge word `D` deselecting the offset (SPEC §10.4)",
        ),
        ("F", din),
        ("I", din),
        ("I1", din),
        ("J", din),
        ("J1", din),
        ("K", din),
        ("K1", din),
        ("N", din),
        ("P", din),
        ("R", din),
        ("S", din),
        ("T", din),
        ("AR", circle),
        ("CR", circle),
        ("TURN", circle),
        (
            "RPL",
            "the rotation of `ROT`/`AROT`, a value of the frame instruction (SPEC §10.9)",
        ),
        (
            "PO",
            "polynomial coefficients `PO[X]=(…)`, not lowered yet (SPEC §10.13)",
        ),
        (
            "PRIO",
            "the priority of `SETINT`, taken with its block (SPEC §10.9)",
        ),
    ];
    let excused: BTreeSet<&str> = elsewhere.iter().map(|(name, _)| *name).collect();
    let lacking: Vec<&String> = catalogue
        .iter()
        .filter(|n| !ours.contains(*n) && !excused.contains(n.as_str()))
        .collect();
    assert!(
        lacking.is_empty(),
        "named addresses: the catalogue's {lacking:?} are missing"
    );
    for (name, _) in elsewhere {
        assert!(catalogue.contains(*name), "{name} is not in the catalogue");
        assert!(!ours.contains(*name), "{name} is a named address now");
    }
}

#[test]
fn procedures_are_the_controls() {
    let Some(dir) = catalogue_dir() else { return };
    let ours: BTreeSet<String> = PROCEDURES
        .iter()
        .map(|(_, name, ..)| name.to_string())
        .collect();
    // The catalogue lists `CTABEND` with the keywords, `FGREF` with the
    // addresses, `PROTD` with the functions and `STARTFIFO`, `STOPFIFO`
    // with the commands.
    let elsewhere: BTreeSet<String> = [
        "keywords.txt",
        "addresses.txt",
        "functions.txt",
        "commands.txt",
    ]
    .into_iter()
    .flat_map(|file| names(&dir, file))
    .collect();
    check(
        "procedures",
        &ours,
        &names(&dir, "procedures.txt"),
        &elsewhere,
        &[(
            "ACTIVATE",
            "a procedure without effect in the simulation (SPEC §11, calls); not in the lists of 05/2017",
        )],
    );
    check_complete(
        "procedures",
        &ours,
        &names(&dir, "procedures.txt"),
        &[
            ("MSG", "lowered to a message of its own (SPEC §10.9)"),
            ("STOPRE", "lowered to a stop of its own (SPEC §10.9)"),
            ("RET", "a return, lowered as `ENDPROC` is (SPEC §10.9)"),
            ("L", "the address of a call by number, `L123` (SPEC §10.9)"),
        ],
    );
}
