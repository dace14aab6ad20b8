//! The files a check reads: the files named, the files of the folders
//! named (hidden and git-ignored paths skipped, as the `ignore` crate
//! does), or standard input.

use std::path::{Path, PathBuf};

use gcodec_source::{Diagnostic, codes};

use super::config::{CheckConfig, relative_to};

/// What the command line names to check.
#[derive(Clone, Debug)]
pub enum Input {
    /// A file (checked whatever its name) or a folder (walked).
    Path(PathBuf),
    /// A program read from standard input, named `name`.
    Stdin { name: String, bytes: Vec<u8> },
}

/// One file to check, with the path its globs are matched against.
#[derive(Debug)]
pub(super) struct Found {
    pub source: Source,
    pub relative: PathBuf,
}

#[derive(Debug)]
pub(super) enum Source {
    File(PathBuf),
    Stdin {
        name: String,
        bytes: Vec<u8>,
    },
    /// A path the walk could not read (a folder without permission).
    Unreadable {
        name: String,
        problem: Diagnostic,
    },
}

impl Found {
    /// The name the file is shown by.
    pub fn name(&self) -> String {
        match &self.source {
            Source::File(path) => path.display().to_string(),
            Source::Stdin { name, .. } | Source::Unreadable { name, .. } => name.clone(),
        }
    }
}

/// Every file to check, sorted by name, each once. A path named that does
/// not exist is a problem of the command line.
pub(super) fn files(config: &CheckConfig, inputs: Vec<Input>) -> Result<Vec<Found>, Diagnostic> {
    let mut found = Vec::new();
    for input in inputs {
        match input {
            Input::Stdin { name, bytes } => {
                let relative = config.relative(Path::new(&name), Path::new(""));
                found.push(Found {
                    source: Source::Stdin { name, bytes },
                    relative,
                });
            }
            Input::Path(path) => {
                let metadata = std::fs::metadata(&path).map_err(|e| {
                    Diagnostic::new(
                        codes::io::READ,
                        format!("cannot read `{}`: {e}", path.display()),
                    )
                })?;
                if metadata.is_dir() {
                    walk(config, &path, &mut found);
                } else {
                    let relative = config.relative(&path, Path::new(""));
                    found.push(Found {
                        source: Source::File(path),
                        relative,
                    });
                }
            }
        }
    }
    found.sort_by_cached_key(Found::name);
    found.dedup_by_key(|f| f.name());
    Ok(found)
}

fn walk(config: &CheckConfig, root: &Path, found: &mut Vec<Found>) {
    let walker = ignore::WalkBuilder::new(root)
        .standard_filters(true)
        .filter_entry({
            let exclude = config.exclude.clone();
            let root_dir = config.root.clone();
            let walked = root.to_path_buf();
            move |entry| {
                let relative = relative_to(&root_dir, entry.path(), &walked);
                !exclude.is_match(relative)
            }
        })
        .build();
    for entry in walker {
        match entry {
            Ok(entry) => {
                let is_file = entry.file_type().is_some_and(|t| !t.is_dir());
                let relative = config.relative(entry.path(), root);
                if is_file && config.includes(&relative) {
                    // `./a.mpf`, found by walking `.`, is read and shown
                    // as `a.mpf`.
                    let path = entry.path();
                    let path = path.strip_prefix(".").unwrap_or(path).to_path_buf();
                    found.push(Found {
                        source: Source::File(path),
                        relative,
                    });
                }
            }
            Err(error) => {
                let name = error_path(&error)
                    .map_or_else(|| root.display().to_string(), |p| p.display().to_string());
                let problem =
                    Diagnostic::new(codes::io::READ, format!("cannot read `{name}`: {error}"));
                found.push(Found {
                    source: Source::Unreadable { name, problem },
                    relative: PathBuf::new(),
                });
            }
        }
    }
}

/// The path a walk error is about, where it names one.
fn error_path(error: &ignore::Error) -> Option<&Path> {
    match error {
        ignore::Error::WithPath { path, .. } => Some(path),
        ignore::Error::WithDepth { err, .. } | ignore::Error::WithLineNumber { err, .. } => {
            error_path(err)
        }
        _ => None,
    }
}
