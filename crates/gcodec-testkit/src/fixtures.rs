//! A fixture program of `tests/fixtures/KIND/` (the scheme is in
//! `tests/fixtures/README.md`): its file, named relative to the
//! repository root as diagnostics and snapshots show it, what its
//! `; KIND:` line names, and the settings of its snapshot.

use std::path::{Path, PathBuf};

use gcodec_profile::Profile;
use gcodec_source::SourceFile;

use crate::paths::repo;

/// The folder of the fixtures of `kind` (`parse`, `lower`, `run`), as the
/// `root` of a `datatest_stable::harness!`.
pub fn root(kind: &str) -> String {
    dir(kind).display().to_string()
}

fn dir(kind: &str) -> PathBuf {
    repo().join("tests/fixtures").join(kind)
}

/// One fixture program.
pub struct Fixture {
    /// The folder below `tests/fixtures/`: `parse`, `lower` or `run`.
    pub kind: &'static str,
    /// The path inside that folder, with `/` (`errors/unclosed_if.mpf`).
    pub relative: String,
    /// The file, named `tests/fixtures/KIND/RELATIVE`.
    pub file: SourceFile,
}

/// What a fixture's `; KIND:` line names
/// (`; run: profile=mill.toml no-stop`).
pub struct Header {
    /// `profile=FILE`, a file relative to the fixture's folder; the
    /// built-in profile without one.
    pub profile: Profile,
    /// The other words, which the harness of the kind reads.
    pub options: Vec<String>,
}

impl Fixture {
    /// Reads the fixture at `path`, a file below [`root`]`(kind)`.
    pub fn read(kind: &'static str, path: &Path) -> Self {
        let relative = path
            .strip_prefix(dir(kind))
            .unwrap_or_else(|_| panic!("{} is not a {kind} fixture", path.display()))
            .display()
            .to_string()
            .replace('\\', "/");
        let bytes = std::fs::read(path)
            .unwrap_or_else(|e| panic!("cannot read fixture {}: {e}", path.display()));
        let file = SourceFile::new(format!("tests/fixtures/{kind}/{relative}"), bytes);
        Self {
            kind,
            relative,
            file,
        }
    }

    /// The profile and options of the fixture's `; KIND:` line; the
    /// built-in profile and no options without one.
    pub fn header(&self) -> Header {
        let text = String::from_utf8_lossy(self.file.bytes());
        let prefix = format!("; {}:", self.kind);
        let words: Vec<&str> = text
            .lines()
            .find_map(|l| l.strip_prefix(&prefix))
            .map(|h| h.split_whitespace().collect())
            .unwrap_or_default();
        let mut profile_file = None;
        let mut options = Vec::new();
        for word in words {
            match word.strip_prefix("profile=") {
                Some(file) => profile_file = Some(file),
                None => options.push(word.to_owned()),
            }
        }
        let profile = match profile_file {
            Some(file) => {
                let folder = repo().join(self.file.name());
                let path = folder.parent().expect("a fixture's folder").join(file);
                let text = std::fs::read_to_string(&path)
                    .unwrap_or_else(|e| panic!("profile {}: {e}", path.display()));
                gcodec_profile::load(&text)
                    .unwrap_or_else(|d| panic!("profile {}: {d:#?}", path.display()))
            }
            None => gcodec_profile::builtin().expect("built-in profile"),
        };
        Header { profile, options }
    }

    /// The settings of the fixture's snapshot, which the harness asserts
    /// as `KIND` (insta places a snapshot by the assertion's file): named
    /// `KIND@RELATIVE` (`/` as `__`) in the test's `snapshots/` folder,
    /// with the fixture as its input file and no expression.
    pub fn snapshot_settings(&self) -> insta::Settings {
        let mut settings = insta::Settings::clone_current();
        settings.set_prepend_module_to_snapshot(false);
        settings.set_snapshot_suffix(&self.relative);
        settings.set_input_file(repo().join(self.file.name()));
        settings.set_omit_expression(true);
        settings
    }
}
