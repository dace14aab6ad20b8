//! The machine each file is checked for: the profile and definition
//! files its `[[files]]` sections assign, each file read and checked once
//! before any program is.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use gcodec_profile::Profile;
use gcodec_sema::Definitions;
use gcodec_source::{Diagnostic, SourceFile, Span};

use super::config::{CheckConfig, unusable};
use crate::diagnostics::FileReport;

/// What the files of one set of sections are checked with.
#[derive(Debug)]
pub(super) struct Machine {
    pub profile: Arc<Profile>,
    /// The profile's file (`None`: the built-in profile): a run takes
    /// its relative `subprogram_paths` against its folder.
    pub profile_file: Option<PathBuf>,
    pub definitions: Arc<Definitions>,
}

impl Machine {
    /// How the machine's files are read: at most the profile's
    /// `[program] max_file_size`, in its code page where not UTF-8.
    pub fn read(&self, path: &Path) -> Result<SourceFile, Diagnostic> {
        read(&self.profile, path)
    }
}

fn read(profile: &Profile, path: &Path) -> Result<SourceFile, Diagnostic> {
    crate::read_source(
        path,
        *profile.program.max_file_size.get_ref(),
        profile.program.text_encoding(),
    )
}

/// The machines of every set of sections some file matches, loaded once
/// each; every problem with a profile or definition file is collected
/// (against the configuration and against the file itself).
pub(super) struct Machines<'c> {
    config: &'c CheckConfig,
    builtin: Profile,
    profiles: HashMap<PathBuf, Option<Profile>>,
    machines: Vec<Machine>,
    /// The index in `machines` of each set of sections, `None` where it
    /// could not be loaded.
    index: HashMap<Vec<usize>, Option<usize>>,
    pub problems: Vec<FileReport>,
}

impl<'c> Machines<'c> {
    pub fn new(config: &'c CheckConfig, builtin: Profile) -> Self {
        Self {
            config,
            builtin,
            profiles: HashMap::new(),
            machines: Vec::new(),
            index: HashMap::new(),
            problems: Vec::new(),
        }
    }

    /// The index of the machine of `sections`, loaded on first use;
    /// `None` where it cannot be loaded (the problems say why).
    pub fn load(&mut self, sections: &[usize]) -> Option<usize> {
        if let Some(&index) = self.index.get(sections) {
            return index;
        }
        let index = self.machine_of(sections).map(|machine| {
            self.machines.push(machine);
            self.machines.len() - 1
        });
        self.index.insert(sections.to_vec(), index);
        index
    }

    /// The machine [`Machines::load`] gave the index of.
    pub fn machine(&self, index: usize) -> &Machine {
        &self.machines[index]
    }

    /// The profile of the last section that names one (the built-in one
    /// where none does), with the definition files of every section in
    /// order and the names they assume defined.
    fn machine_of(&mut self, sections: &[usize]) -> Option<Machine> {
        let config = self.config;
        let named = sections
            .iter()
            .rev()
            .find_map(|&i| config.sections[i].profile.as_ref());
        let (profile, profile_file) = match named {
            Some((path, span)) => (self.profile(path, *span)?, Some(path.clone())),
            None => (self.builtin.clone(), None),
        };
        let mut definitions = Definitions::new();
        let mut usable = true;
        for &i in sections {
            let section = &config.sections[i];
            for (path, span) in &section.definitions {
                usable &= self.definitions(&profile, &mut definitions, path, *span);
            }
            for name in &section.assume_defined {
                definitions.assume_defined(name);
            }
        }
        usable.then(|| Machine {
            profile: Arc::new(profile),
            profile_file,
            definitions: Arc::new(definitions),
        })
    }

    fn profile(&mut self, path: &Path, span: Span) -> Option<Profile> {
        if let Some(loaded) = self.profiles.get(path) {
            return loaded.clone();
        }
        let loaded = self.load_profile(path, span);
        self.profiles.insert(path.to_path_buf(), loaded.clone());
        loaded
    }

    fn load_profile(&mut self, path: &Path, span: Span) -> Option<Profile> {
        let file = match SourceFile::read(path) {
            Ok(file) => file,
            Err(e) => {
                self.unusable(
                    path,
                    span,
                    &format!("cannot be read: {e}"),
                    Vec::new(),
                    None,
                );
                return None;
            }
        };
        match crate::load_profile(&file) {
            Ok((profile, warnings)) => {
                if !warnings.is_empty() {
                    self.problems.push(FileReport::new(
                        file.name().to_owned(),
                        Some(file),
                        warnings,
                    ));
                }
                Some(profile)
            }
            Err(error) => {
                let text = "is a profile with errors";
                self.unusable(path, span, text, error.diagnostics, Some(file));
                None
            }
        }
    }

    /// Loads one definition file, read as `profile` says, into
    /// `definitions`; false where it cannot be read or has errors.
    fn definitions(
        &mut self,
        profile: &Profile,
        definitions: &mut Definitions,
        path: &Path,
        span: Span,
    ) -> bool {
        let file = match read(profile, path) {
            Ok(file) => file,
            Err(d) => {
                self.unusable(path, span, "cannot be read", vec![d], None);
                return false;
            }
        };
        let diagnostics = definitions.load(&file);
        if diagnostics.has_errors() {
            let found = diagnostics.to_vec();
            self.unusable(
                path,
                span,
                "is a definition file with errors",
                found,
                Some(file),
            );
            return false;
        }
        true
    }

    /// Reports a file the configuration names as unusable (at `span` in
    /// the configuration), with the file's own problems.
    fn unusable(
        &mut self,
        path: &Path,
        span: Span,
        what: &str,
        own: Vec<Diagnostic>,
        file: Option<SourceFile>,
    ) {
        let d = unusable(span, format!("`{}` {what}", path.display()));
        let config_file = self.config.file.as_deref().cloned();
        let config_name = config_file
            .as_ref()
            .map_or_else(String::new, |f| f.name().to_owned());
        self.problems
            .push(FileReport::new(config_name, config_file, vec![d]));
        if !own.is_empty() {
            let name = path.display().to_string();
            self.problems.push(FileReport::new(name, file, own));
        }
    }
}
