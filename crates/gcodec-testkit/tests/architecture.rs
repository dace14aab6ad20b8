//! The code map's layering (`docs/ARCHITECTURE.md`), checked: which
//! gcodec crates a crate may depend on, what the CLI's sources may name,
//! and no `use` cycle between sibling modules of a crate.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

fn crates_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("crates/")
        .to_path_buf()
}

/// The gcodec crates `krate` depends on outside its tests.
fn gcodec_dependencies(krate: &str) -> BTreeSet<String> {
    let manifest = crates_dir().join(krate).join("Cargo.toml");
    let text = fs::read_to_string(&manifest).expect("manifest");
    let manifest: toml::Table = toml::from_str(&text).expect("manifest is TOML");
    manifest
        .get("dependencies")
        .and_then(toml::Value::as_table)
        .map(|deps| {
            deps.keys()
                .filter(|name| name.starts_with("gcodec-"))
                .cloned()
                .collect()
        })
        .unwrap_or_default()
}

fn workspace_crates() -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(crates_dir())
        .expect("crates/")
        .filter_map(Result::ok)
        .filter(|e| e.path().join("Cargo.toml").is_file())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn crates_depend_only_downwards() {
    let set =
        |names: &[&str]| -> BTreeSet<String> { names.iter().map(|n| (*n).to_owned()).collect() };
    // The vocabulary and the source model are the bottom of the stack.
    for bottom in ["gcodec-lang", "gcodec-source"] {
        assert_eq!(gcodec_dependencies(bottom), set(&[]), "{bottom}");
    }
    // The executor runs AIL; compiling is the driver's job.
    let exec = gcodec_dependencies("gcodec-exec");
    for compiler in [
        "gcodec-lexer",
        "gcodec-parser",
        "gcodec-sema",
        "gcodec-driver",
    ] {
        assert!(
            !exec.contains(compiler),
            "gcodec-exec depends on {compiler}"
        );
    }
    // The CLI is thin over the facade (and the picture of a run).
    assert_eq!(
        gcodec_dependencies("gcodec-cli"),
        set(&[
            "gcodec-driver",
            "gcodec-plot",
            "gcodec-profile",
            "gcodec-source"
        ])
    );
    // The picture reads the public events, nothing of the pipeline.
    assert_eq!(gcodec_dependencies("gcodec-plot"), set(&["gcodec-exec"]));
    for krate in workspace_crates() {
        assert!(
            !gcodec_dependencies(&krate).contains("gcodec-testkit"),
            "{krate} depends on the test kit outside its tests"
        );
    }
}

/// Every `.rs` file below `dir`.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in fs::read_dir(&dir).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

/// `text` without its line comments and without what follows the first
/// `#[cfg(test)]` (unit tests may use any module).
fn code_of(text: &str) -> String {
    let text = text.split("#[cfg(test)]").next().unwrap_or_default();
    text.lines()
        .map(|line| line.split("//").next().unwrap_or_default())
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_cli_names_no_gcodec_crate_but_its_dependencies() {
    let allowed = [
        "gcodec_driver",
        "gcodec_plot",
        "gcodec_profile",
        "gcodec_source",
    ];
    for file in rust_files(&crates_dir().join("gcodec-cli/src")) {
        let code = code_of(&fs::read_to_string(&file).expect("source"));
        for (at, _) in code.match_indices("gcodec_") {
            let name: String = code[at..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            assert!(
                allowed.contains(&name.as_str()),
                "{} names {name}",
                file.display()
            );
        }
    }
}

#[test]
fn the_picture_reads_only_the_executor_s_events() {
    for file in rust_files(&crates_dir().join("gcodec-plot/src")) {
        let code = code_of(&fs::read_to_string(&file).expect("source"));
        for (at, _) in code.match_indices("gcodec_exec") {
            assert!(
                code[at..].starts_with("gcodec_exec::event::"),
                "{} names more of gcodec_exec than its events",
                file.display()
            );
        }
    }
}

/// The module path of `file` in its crate's `src` (`lower/mod.rs` is
/// `["lower"]`, `lib.rs` is `[]`).
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let relative = file.strip_prefix(src).expect("below src");
    let mut path: Vec<String> = relative
        .with_extension("")
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(
        path.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        path.pop();
    }
    path
}

/// The module paths `code`, in module `module`, refers to through
/// `crate::…` and `super::…`.
fn references(module: &[String], code: &str) -> Vec<Vec<String>> {
    let ident = |s: &str| -> Vec<String> {
        let mut parts = Vec::new();
        let mut rest = s;
        loop {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if name.is_empty() {
                break;
            }
            rest = &rest[name.len()..];
            parts.push(name);
            match rest.strip_prefix("::") {
                Some(more) => rest = more,
                None => break,
            }
        }
        parts
    };
    let bytes = code.as_bytes();
    let starts_word =
        |at: usize| at == 0 || !(bytes[at - 1].is_ascii_alphanumeric() || bytes[at - 1] == b'_');
    let mut found = Vec::new();
    for (at, _) in code.match_indices("crate::") {
        if starts_word(at) {
            found.push(ident(&code[at + "crate::".len()..]));
        }
    }
    for (at, _) in code.match_indices("super::") {
        // Only the first `super::` of a run.
        if !starts_word(at) || code[..at].ends_with("super::") {
            continue;
        }
        let mut rest = &code[at..];
        let mut ups = 0;
        while let Some(more) = rest.strip_prefix("super::") {
            ups += 1;
            rest = more;
        }
        let mut path: Vec<String> = module[..module.len().saturating_sub(ups)].to_vec();
        path.extend(ident(rest));
        found.push(path);
    }
    found
}

#[test]
fn no_use_cycle_between_sibling_modules() {
    let mut cycles = Vec::new();
    for krate in workspace_crates() {
        let src = crates_dir().join(&krate).join("src");
        // An edge from a module to a sibling it refers to, both named by
        // their full paths.
        let mut edges: BTreeMap<Vec<String>, BTreeSet<Vec<String>>> = BTreeMap::new();
        for file in rust_files(&src) {
            let module = module_of(&src, &file);
            let code = code_of(&fs::read_to_string(&file).expect("source"));
            for target in references(&module, &code) {
                let common = module
                    .iter()
                    .zip(&target)
                    .take_while(|(a, b)| a == b)
                    .count();
                if common < module.len() && common < target.len() {
                    edges
                        .entry(module[..=common].to_vec())
                        .or_default()
                        .insert(target[..=common].to_vec());
                }
            }
        }
        for (from, targets) in &edges {
            for to in targets {
                // A path back from `to` to `from`.
                let mut seen = BTreeSet::new();
                let mut pending = vec![to.clone()];
                while let Some(at) = pending.pop() {
                    if &at == from {
                        cycles.push(format!(
                            "{krate}: {} -> {} -> … -> {}",
                            from.join("::"),
                            to.join("::"),
                            from.join("::")
                        ));
                        break;
                    }
                    if seen.insert(at.clone()) {
                        pending.extend(edges.get(&at).into_iter().flatten().cloned());
                    }
                }
            }
        }
    }
    assert!(cycles.is_empty(), "use cycles:\n{}", cycles.join("\n"));
}
