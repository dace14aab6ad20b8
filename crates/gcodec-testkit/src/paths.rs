//! Where the programs are: the repository, its fixtures and examples, the
//! shared corpus and the shared reference.

use std::path::{Path, PathBuf};

/// The repository root.
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The shared corpus beside the checkout (`../shared/corpus`) or
/// `GCODEC_CORPUS_DIR`; `None`, with a notice, where it is absent.
pub fn corpus_dir() -> Option<PathBuf> {
    shared_dir("GCODEC_CORPUS_DIR", "corpus")
}

/// The shared reference beside the checkout (`../shared/reference`: the
/// control's catalogue of names, the language notes) or
/// `GCODEC_REFERENCE_DIR`; `None`, with a notice, where it is absent.
pub fn reference_dir() -> Option<PathBuf> {
    shared_dir("GCODEC_REFERENCE_DIR", "reference")
}

/// `../shared/NAME` beside the checkout, or the directory the variable
/// `var` names; `None`, with a notice, where it is absent.
fn shared_dir(var: &str, name: &str) -> Option<PathBuf> {
    let dir = std::env::var_os(var)
        .map(PathBuf::from)
        .unwrap_or_else(|| repo().join("../shared").join(name));
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!(
            "notice: {name} not found at {}; {name} checks skipped",
            dir.display()
        );
        None
    }
}

/// Every `.mpf`, `.spf` and `.def` file below `dir`, sorted.
pub fn programs(dir: &Path) -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| {
                ["mpf", "spf", "def"].contains(&e.to_string_lossy().to_ascii_lowercase().as_str())
            }) {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, &mut out);
    out.sort();
    out
}

/// Our fixtures and examples, plus the corpus where it is present.
pub fn all_programs() -> Vec<PathBuf> {
    let mut all = programs(&repo().join("tests/fixtures"));
    all.extend(programs(&repo().join("examples")));
    if let Some(corpus) = corpus_dir() {
        all.extend(programs(&corpus));
    }
    all
}

/// Calls `check` with the name and bytes of every program of
/// [`all_programs`] (at least our own 30).
pub fn each_program(mut check: impl FnMut(&str, &[u8])) {
    let all = all_programs();
    assert!(all.len() >= 30, "found only {} programs", all.len());
    for path in all {
        let bytes = std::fs::read(&path).expect("readable");
        check(&path.display().to_string(), &bytes);
    }
}

/// [`each_program`] on each of `machines` (a name and a profile): `check`
/// gets the program's name with `on <machine>`, its bytes and the
/// machine's profile.
pub fn each_program_on<P>(machines: &[(&str, P)], mut check: impl FnMut(&str, &[u8], &P)) {
    for (machine, profile) in machines {
        each_program(|name, src| check(&format!("{name} on {machine}"), src, profile));
    }
}

/// `path` as the corpus tests show it: relative to the corpus, with `/`.
pub fn shown(corpus: &Path, path: &Path) -> String {
    path.strip_prefix(corpus)
        .unwrap_or(path)
        .display()
        .to_string()
        .replace('\\', "/")
}
