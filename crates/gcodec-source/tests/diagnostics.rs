//! The registry of diagnostic codes against the rest of the workspace:
//! `docs/diagnostics.md` is generated from it, and every code named in the
//! crates is one of it.

use std::path::{Path, PathBuf};

use gcodec_source::codes;

const WORKSPACE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
const REFERENCE_PATH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/diagnostics.md");
const REGISTRY_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/src/codes");

/// Fails when `docs/diagnostics.md` is stale. To regenerate:
/// `GCODEC_UPDATE_DIAGNOSTICS=1 cargo test -p gcodec-source --test diagnostics`.
#[test]
fn the_checked_in_reference_is_current() {
    let generated = codes::reference();
    if std::env::var_os("GCODEC_UPDATE_DIAGNOSTICS").is_some() {
        std::fs::write(REFERENCE_PATH, &generated).expect("write docs/diagnostics.md");
    }
    let checked_in = std::fs::read_to_string(REFERENCE_PATH).unwrap_or_default();
    assert!(
        checked_in == generated,
        "docs/diagnostics.md is stale: run \
         `GCODEC_UPDATE_DIAGNOSTICS=1 cargo test -p gcodec-source --test diagnostics` and commit it"
    );
}

/// Every `gcodec::AREA::NAME` written in the crates (sources, tests,
/// snapshots, fixtures, explanations) is a registered code, so no code is
/// emitted or expected without its documentation. A name ending in `_` is
/// a prefix a test matches codes with; the registry's own sources are left
/// out (their tests name codes that do not exist on purpose).
#[test]
fn every_code_named_in_the_crates_is_registered() {
    let mut unknown = Vec::new();
    for (path, text) in crate_files(|path, in_registry| {
        !(in_registry && path.extension().is_some_and(|e| e == "rs"))
    }) {
        for name in code_names(&text) {
            let registered = codes::all().iter().any(|code| code.name() == name);
            if !registered && !name.ends_with('_') {
                unknown.push(format!("{}: {name}", path.display()));
            }
        }
    }
    assert!(
        unknown.is_empty(),
        "codes not in the registry:\n{}",
        unknown.join("\n")
    );
}

/// No code is spelt out in the sources outside the registry: every
/// diagnostic is built from a registry constant, so none is composed at
/// run time or missing from it. Unit tests (after `#[cfg(test)]`) may
/// compare with names.
#[test]
fn no_code_is_spelt_out_outside_the_registry() {
    let mut spelt = Vec::new();
    for (path, text) in crate_files(|path, in_registry| {
        let in_sources = path.components().any(|c| c.as_os_str() == "src");
        in_sources && !in_registry && path.extension().is_some_and(|e| e == "rs")
    }) {
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        for line in code.lines().filter(|l| l.contains("\"gcodec::")) {
            spelt.push(format!("{}: {}", path.display(), line.trim()));
        }
    }
    assert!(
        spelt.is_empty(),
        "codes spelt out instead of taken from gcodec_source::codes:\n{}",
        spelt.join("\n")
    );
}

/// Every explanation file belongs to a registered code (a file whose name
/// is misspelt would be documentation nobody reads).
#[test]
fn every_explanation_file_is_a_code() {
    let mut orphans = Vec::new();
    for path in files(Path::new(REGISTRY_DIR)) {
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let area = path.parent().and_then(Path::file_name);
        let (Some(area), Some(name)) = (area, path.file_stem()) else {
            continue;
        };
        let name = format!(
            "gcodec::{}::{}",
            area.to_string_lossy(),
            name.to_string_lossy()
        );
        if !codes::all().iter().any(|code| code.name() == name) {
            orphans.push(path.display().to_string());
        }
    }
    assert!(
        orphans.is_empty(),
        "explanations of no code:\n{}",
        orphans.join("\n")
    );
}

/// The text files under `crates/` that `wanted` keeps, told whether a
/// file is in the registry's own directory.
fn crate_files(wanted: impl Fn(&Path, bool) -> bool) -> Vec<(PathBuf, String)> {
    let registry = Path::new(REGISTRY_DIR)
        .canonicalize()
        .expect("the registry");
    let crates = Path::new(WORKSPACE)
        .join("crates")
        .canonicalize()
        .expect("crates/");
    files(&crates)
        .into_iter()
        .filter(|path| wanted(path, path.starts_with(&registry)))
        .filter_map(|path| {
            let text = std::fs::read_to_string(&path).ok()?;
            Some((path, text))
        })
        .collect()
}

/// The files under `dir`, recursively, without build output.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                if path.file_name().is_none_or(|n| n != "target") {
                    pending.push(path);
                }
            } else {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// The `gcodec::AREA::NAME` names in `text`.
fn code_names(text: &str) -> Vec<&str> {
    let is_name = |b: &u8| b.is_ascii_lowercase() || b.is_ascii_digit() || *b == b'_';
    let prefix = "gcodec::".len();
    let mut out = Vec::new();
    for (start, _) in text.match_indices("gcodec::") {
        let rest = &text.as_bytes()[start + prefix..];
        let area = rest.iter().take_while(|b| is_name(b)).count();
        if area == 0 || !rest[area..].starts_with(b"::") {
            continue;
        }
        let name = rest[area + 2..].iter().take_while(|b| is_name(b)).count();
        if name > 0 {
            out.push(&text[start..start + prefix + area + 2 + name]);
        }
    }
    out
}
