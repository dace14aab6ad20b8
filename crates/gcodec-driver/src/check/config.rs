//! `gcodec.toml`, the configuration of a check: read and checked in full,
//! every problem a diagnostic into its text (area `config`), relative
//! paths made relative to its folder.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use std::collections::BTreeMap;

use gcodec_profile::{TomlKind, read_toml};
use gcodec_source::{Diagnostic, Diagnostics, SourceFile, Span, codes};
use globset::{GlobBuilder, GlobSet, GlobSetBuilder};
use serde::Deserialize;
use toml::Spanned;

use super::levels::Levels;
use super::{RuleLevel, Selection, Selector};

/// The file name a configuration is found by.
pub const CONFIG_NAME: &str = "gcodec.toml";

/// A check's configuration: which files are checked, against which
/// profile and definition files, and at which rule levels.
#[derive(Debug)]
pub struct CheckConfig {
    /// The configuration's text (none for the default configuration).
    pub file: Option<Arc<SourceFile>>,
    /// Its folder, absolute: globs match paths relative to it, and
    /// relative paths in it are relative to it.
    pub root: PathBuf,
    /// Files checked besides `.mpf`, `.spf` and `.def` when a folder is
    /// walked.
    pub(super) include: GlobSet,
    /// Files and folders left out when a folder is walked.
    pub(super) exclude: GlobSet,
    /// Folders the subprograms that programs call are found in, for the
    /// runs a check will make (`--run`, not built yet); each is a folder.
    pub search_paths: Vec<PathBuf>,
    /// `[rules]`: levels by code or area, each named once.
    pub(super) rules: Vec<(Selector, RuleLevel)>,
    /// `[[files]]`, in the order written.
    pub(super) sections: Vec<FileSection>,
}

/// One `[[files]]` section: what the files its glob matches are checked
/// with.
#[derive(Debug)]
pub(super) struct FileSection {
    pub glob: GlobSet,
    /// The profile (absolute), with the span of its key's value.
    pub profile: Option<(PathBuf, Span)>,
    pub definitions: Vec<(PathBuf, Span)>,
    pub assume_defined: Vec<String>,
    pub ignore: Vec<Selector>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    #[serde(default)]
    include: Vec<Spanned<String>>,
    #[serde(default)]
    exclude: Vec<Spanned<String>>,
    #[serde(default)]
    search_paths: Vec<Spanned<String>>,
    #[serde(default)]
    rules: BTreeMap<Spanned<String>, Spanned<RuleLevel>>,
    #[serde(default)]
    files: Vec<RawSection>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSection {
    glob: Spanned<String>,
    profile: Option<Spanned<String>>,
    #[serde(default)]
    definitions: Vec<Spanned<String>>,
    #[serde(default)]
    assume_defined: Vec<String>,
    #[serde(default)]
    ignore: Vec<Spanned<String>>,
}

impl CheckConfig {
    /// The configuration where no `gcodec.toml` is found: every file
    /// against the built-in profile, every code at its own level; paths
    /// relative to `root`.
    pub fn default_in(root: PathBuf) -> Self {
        Self {
            file: None,
            root,
            include: GlobSet::empty(),
            exclude: GlobSet::empty(),
            search_paths: Vec::new(),
            rules: Vec::new(),
            sections: Vec::new(),
        }
    }

    /// Reads the configuration in `file` (its path gives the folder);
    /// every problem found, against its text.
    pub fn load(file: SourceFile) -> Result<Self, Vec<Diagnostic>> {
        let text = std::str::from_utf8(file.bytes()).map_err(|_| {
            vec![
                Diagnostic::new(
                    codes::config::SYNTAX,
                    format!("`{}` is not UTF-8 text", file.name()),
                )
                .with_help("TOML files are UTF-8"),
            ]
        })?;
        let raw: RawConfig = read_toml(text, CONFIG_TOML).map_err(|d| vec![d])?;
        let root = file
            .path()
            .and_then(Path::parent)
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let root = std::path::absolute(&root).unwrap_or(root);
        let mut problems = Vec::new();
        let mut config = Self::default_in(root);
        config.include = glob_set(&raw.include, &mut problems);
        config.exclude = glob_set(&raw.exclude, &mut problems);
        config.search_paths = raw
            .search_paths
            .iter()
            .filter_map(|path| {
                let dir = config.root.join(path.get_ref());
                if dir.is_dir() {
                    Some(dir)
                } else {
                    problems.push(unusable(
                        span(path),
                        format!("`{}` is not a folder", path.get_ref()),
                    ));
                    None
                }
            })
            .collect();
        for (name, level) in &raw.rules {
            let Some(selector) = selector(name, &mut problems) else {
                continue;
            };
            if config.rules.iter().any(|(seen, _)| *seen == selector) {
                problems.push(
                    Diagnostic::new(
                        codes::config::SCHEMA,
                        format!(
                            "`{}` names a code or area another rule names",
                            name.get_ref()
                        ),
                    )
                    .with_label(span(name), "named again here")
                    .with_help("give each code or area one level"),
                );
                continue;
            }
            config.rules.push((selector, *level.get_ref()));
        }
        config.sections = raw
            .files
            .iter()
            .map(|section| FileSection {
                glob: glob_set(std::slice::from_ref(&section.glob), &mut problems),
                profile: section.profile.as_ref().map(|p| config.resolved(p)),
                definitions: section
                    .definitions
                    .iter()
                    .map(|d| config.resolved(d))
                    .collect(),
                assume_defined: section.assume_defined.clone(),
                ignore: section
                    .ignore
                    .iter()
                    .filter_map(|name| selector(name, &mut problems))
                    .collect(),
            })
            .collect();
        config.file = Some(Arc::new(file));
        if problems.is_empty() {
            Ok(config)
        } else {
            problems.sort_by_key(|d| d.span().map_or(0, |s| s.start));
            Err(problems)
        }
    }

    /// A path the configuration names, relative to its folder, with the
    /// span of where it is named.
    fn resolved(&self, path: &Spanned<String>) -> (PathBuf, Span) {
        (self.root.join(path.get_ref()), span(path))
    }

    /// The path globs match `path` by: relative to the configuration's
    /// folder where it is inside it, else relative to `walked`, the path
    /// given on the command line it was found under.
    pub(super) fn relative(&self, path: &Path, walked: &Path) -> PathBuf {
        relative_to(&self.root, path, walked)
    }

    /// Whether a walked file is checked for its name: a program or
    /// definition file, or one `include` matches.
    pub(super) fn includes(&self, relative: &Path) -> bool {
        let known = relative.extension().is_some_and(|e| {
            ["mpf", "spf", "def"]
                .iter()
                .any(|known| e.eq_ignore_ascii_case(known))
        });
        known || self.include.is_match(relative)
    }

    /// The indices of the `[[files]]` sections whose glob matches.
    pub(super) fn sections_of(&self, relative: &Path) -> Vec<usize> {
        (self.sections.iter().enumerate())
            .filter(|(_, s)| s.glob.is_match(relative))
            .map(|(i, _)| i)
            .collect()
    }

    /// The codes the `[[files]]` sections whose glob matches ignore.
    pub(super) fn ignores_of(&self, relative: &Path) -> Vec<Selector> {
        (self.sections.iter())
            .filter(|s| s.glob.is_match(relative))
            .flat_map(|s| s.ignore.iter().copied())
            .collect()
    }
}

/// What the configuration assigns one program that `gcodec lower` or
/// `gcodec run` is given: its `[[files]]` sections' profile, definition
/// files and names assumed defined (as `check` would check it with).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ProgramSettings {
    /// The last matching section's profile.
    pub profile: Option<PathBuf>,
    /// The definition files of every matching section, in order.
    pub definitions: Vec<PathBuf>,
    pub assume_defined: Vec<String>,
}

impl CheckConfig {
    /// What the `[[files]]` sections that match the program at `path`
    /// assign it.
    pub fn program_settings(&self, path: &Path) -> ProgramSettings {
        let relative = self.relative(path, Path::new(""));
        let sections: Vec<&FileSection> = (self.sections.iter())
            .filter(|s| s.glob.is_match(&relative))
            .collect();
        ProgramSettings {
            profile: (sections.iter().rev())
                .find_map(|s| s.profile.as_ref())
                .map(|(path, _)| path.clone()),
            definitions: (sections.iter())
                .flat_map(|s| s.definitions.iter().map(|(path, _)| path.clone()))
                .collect(),
            assume_defined: (sections.iter())
                .flat_map(|s| s.assume_defined.iter().cloned())
                .collect(),
        }
    }

    /// The diagnostics of the file at `path` at the levels the
    /// configuration sets for it (`[rules]`, its sections' `ignore`), as
    /// `check` reports them without options of its command line.
    pub fn releveled(&self, path: &Path, diagnostics: Diagnostics) -> Diagnostics {
        let file_ignores = self.ignores_of(&self.relative(path, Path::new("")));
        let levels = Levels {
            rules: &self.rules,
            file_ignores: &file_ignores,
            selection: &Selection::default(),
        };
        diagnostics.releveled(|code, severity| levels.level(code, severity))
    }
}

/// `path` relative to `root` where it is inside it, else relative to
/// `walked`.
pub(super) fn relative_to(root: &Path, path: &Path, walked: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    if let Ok(inside) = absolute.strip_prefix(root) {
        return inside.to_path_buf();
    }
    path.strip_prefix(walked).unwrap_or(path).to_path_buf()
}

/// The configuration found for `start` (a path to check): the nearest
/// `gcodec.toml` in its folder or a folder above it.
pub fn find_config(start: &Path) -> Option<PathBuf> {
    let absolute = std::path::absolute(start).ok()?;
    let first = if absolute.is_dir() {
        absolute.as_path()
    } else {
        absolute.parent()?
    };
    first
        .ancestors()
        .map(|dir| dir.join(CONFIG_NAME))
        .find(|candidate| candidate.is_file())
}

/// The globs as one set: a glob without `/` matches a file's name in
/// any folder, one with `/` the path from the configuration's folder.
fn glob_set(globs: &[Spanned<String>], problems: &mut Vec<Diagnostic>) -> GlobSet {
    let mut set = GlobSetBuilder::new();
    for glob in globs {
        let text = glob.get_ref();
        let pattern = if text.contains('/') {
            text.clone()
        } else {
            format!("**/{text}")
        };
        let built: Result<Vec<_>, _> = super::alternatives::spelt_out(&pattern)
            .iter()
            .map(|glob| GlobBuilder::new(glob).literal_separator(true).build())
            .collect();
        match built {
            Ok(built) => {
                for glob in built {
                    set.add(glob);
                }
            }
            Err(e) => problems.push(
                Diagnostic::new(
                    codes::config::BAD_GLOB,
                    format!("`{text}` is not a glob: {}", e.kind()),
                )
                .with_label(span(glob), "this glob"),
            ),
        }
    }
    set.build().unwrap_or_else(|_| {
        // Every glob was built alone already; a set of them only fails
        // for a regex too large, which no glob here makes.
        GlobSet::empty()
    })
}

fn selector(name: &Spanned<String>, problems: &mut Vec<Diagnostic>) -> Option<Selector> {
    Selector::parse(name.get_ref())
        .map_err(|message| {
            problems.push(
                Diagnostic::new(codes::config::UNKNOWN_CODE, message)
                    .with_label(span(name), "this name")
                    .with_help("`gcodec explain --list` lists every code"),
            );
        })
        .ok()
}

/// A file or folder the configuration names at `span` that cannot be
/// used, `message` saying why.
pub(super) fn unusable(span: Span, message: String) -> Diagnostic {
    Diagnostic::new(codes::config::UNUSABLE_FILE, message)
        .with_label(span, "named here")
        .with_help("relative paths are relative to the folder of the configuration")
}

const CONFIG_TOML: TomlKind = TomlKind {
    syntax: codes::config::SYNTAX,
    schema: codes::config::SCHEMA,
    what: "check configuration",
    help: "docs/linting.md lists the keys of `gcodec.toml`",
};

fn span<T>(value: &Spanned<T>) -> Span {
    let range = value.span();
    Span::new(range.start as u32, range.end as u32)
}
