//! Every program of the shared corpus lowers without an error diagnostic,
//! with the default profile or the profile of the machine it was written
//! for, and the definition files of that machine. Warnings (constructs not
//! lowered yet, M functions the profile does not know) are allowed.
//! `SYNTAX_CHECK.SPF` is excluded: its machine-dependent lines are errors
//! by design (`syntax_check.rs`). Lines written for interpreters more
//! lenient than the control are errors on the control too
//! (`EXPECTED_LOWERING_ERRORS` of the test kit): the test requires
//! exactly those.

use std::collections::HashSet;
use std::path::PathBuf;
use std::sync::LazyLock;

mod common;

use gcodec_lang::functions::Function;
use gcodec_lang::identifiers::invalid_name;
use gcodec_lang::procedures::Procedure;
use gcodec_testkit::corpus::{
    ASSUMED_NAMES, EXPECTED_LOWERING_ERRORS as EXPECTED_ERRORS, definitions, machine_profile,
};

/// The words of the control's catalogue (addresses, keywords, commands,
/// procedures, functions), upper case; empty where the shared reference
/// is absent.
static CATALOGUE_WORDS: LazyLock<HashSet<String>> = LazyLock::new(|| {
    let Some(dir) = gcodec_testkit::reference_dir() else {
        return HashSet::new();
    };
    let lists = [
        "addresses.txt",
        "keywords.txt",
        "commands.txt",
        "procedures.txt",
        "functions.txt",
    ];
    lists
        .iter()
        .filter_map(|list| std::fs::read_to_string(dir.join("catalogue").join(list)).ok())
        .flat_map(|text| {
            text.lines()
                .map(|l| l.trim().to_ascii_uppercase())
                .filter(|l| !l.is_empty())
                .collect::<Vec<_>>()
        })
        .collect()
});

/// What a word of the language is, if `name` is one: such a name is never
/// a missing definition.
fn language_word(name: &str) -> Option<&'static str> {
    if invalid_name(name).is_some() {
        Some("a keyword, an address, a G command or no name at all")
    } else if Procedure::named(name).is_some() {
        Some("a predefined procedure")
    } else if Function::named(name).is_some() {
        Some("a predefined function")
    } else if CATALOGUE_WORDS.contains(&name.to_ascii_uppercase()) {
        Some("a word of the control's catalogue")
    } else {
        None
    }
}

/// The name a diagnostic quotes first (`` `NAME` is not defined ``).
fn quoted(message: &str) -> Option<&str> {
    message.split('`').nth(1)
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
            if d.code == gcodec_source::codes::lower::UNDEFINED_VARIABLE
                && let Some(word) = quoted(&d.message).and_then(language_word)
            {
                failures.push(format!(
                    "{shown}:{line}: {} reported as undefined, but it is {word}",
                    d.message
                ));
            }
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

/// The names assumed defined for the corpus are names a program may give:
/// a keyword, address or predefined name assumed there would hide the
/// misreading of a statement (as `PRIO` and `DISPR` once hid `SETINT` and
/// `DISPR=` read as variables).
#[test]
fn no_assumed_name_is_a_word_of_the_language() {
    let words: Vec<String> = ASSUMED_NAMES
        .iter()
        .flat_map(|(_, names)| names.iter())
        .filter_map(|name| language_word(name).map(|word| format!("{name}: {word}")))
        .collect();
    assert!(words.is_empty(), "{words:#?}");
}
