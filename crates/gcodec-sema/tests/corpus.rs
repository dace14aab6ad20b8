//! Every program of the shared corpus lowers without an error diagnostic,
//! with the default profile or the profile of the machine it was written
//! for. Warnings (constructs not lowered yet, M functions the profile does
//! not know) are allowed. `SYNTAX_CHECK.SPF` is excluded: its
//! machine-dependent lines are errors by design (`syntax_check.rs`).

use std::path::{Path, PathBuf};

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

fn corpus_dir() -> PathBuf {
    std::env::var_os("GCODEC_CORPUS_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../../shared/corpus"
            ))
        })
}

fn programs(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            programs(&path, out);
        } else if path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("mpf") || e.eq_ignore_ascii_case("spf"))
        {
            out.push(path);
        }
    }
}

fn profile(name: &str) -> gcodec_profile::Profile {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../profiles")
        .join(name);
    let text = std::fs::read_to_string(&path).expect("profile");
    gcodec_profile::load(&text).unwrap_or_else(|d| panic!("{name}: {d:#?}"))
}

#[test]
fn the_corpus_lowers_without_errors() {
    let dir = corpus_dir();
    if !dir.is_dir() {
        eprintln!(
            "notice: {} is absent; the corpus lowering test is skipped",
            dir.display()
        );
        return;
    }
    let mut files = Vec::new();
    programs(&dir, &mut files);
    files.sort();
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
        let mut profile = profile(machine);
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
