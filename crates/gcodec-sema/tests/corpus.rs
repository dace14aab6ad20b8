//! Every program of the shared corpus lowers without an error diagnostic,
//! with the default profile or the profile of the machine it was written
//! for. Warnings (constructs not lowered yet, M functions the profile does
//! not know) are allowed. `SYNTAX_CHECK.SPF` is excluded: its
//! machine-dependent lines are errors by design (`syntax_check.rs`).

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
        let lowered = gcodec_sema::lower(&parsed.program, &profile);
        for d in lowered.diagnostics.iter().filter(|d| d.is_error()) {
            let line = d.span().map_or(0, |s| parsed.program.line_col(s.start).0);
            failures.push(format!(
                "{shown}:{line} ({machine}): {} {}",
                d.code, d.message
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
