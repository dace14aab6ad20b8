//! Finding, reading, parsing and lowering the programs a running program
//! calls (subprograms and cycles).
//!
//! The channel asks a [`ProgramLoader`] for a program by the name in the
//! AIL `call` (`CYCLE81`, `L100`, a `PCALL`/`CALL` path) and gets it lowered
//! and shared ([`Loaded`]), or a [`LoadError`] it turns into an alarm.
//! [`FileLoader`] looks for files along a [`SearchPath`]; [`MemoryLoader`]
//! holds programs given as text, for tests and embedders.
//!
//! # The search path
//!
//! A call from the program in the file `caller_file` looks, in this order,
//! in
//!
//! 1. the directory of `caller_file` (the current directory when it has
//!    none);
//! 2. the profile's `[program] subprogram_paths`: a relative one against
//!    the directory of the profile's file, or, for a profile without a
//!    file (the built-in one), against the current directory;
//! 3. the `--subprogram-path` directories, in the order given (relative
//!    ones against the current directory).
//!
//! Only the files directly inside these directories count (no
//! recursion). A directory that does not exist or cannot be read is
//! skipped, but named in [`LoadError::searched`]. A directory met twice
//! (the same canonical path) is searched once. The first directory that
//! holds the program wins.
//!
//! # Links and special files
//!
//! A program's file may be a symbolic link, but only to a file inside
//! a directory of the caller's search path (at any depth) or of the
//! profile's `[program] link_target_paths` (relative ones as for
//! `subprogram_paths`): its real path (every link resolved) is checked
//! before it is opened, and a link elsewhere is
//! `gcodec::io::outside_search_path`, naming the link and its target. The
//! program keeps the link's name, so the calls it makes search the link's
//! directory, not its target's. What is read is the real path, so the
//! link cannot be swapped between the check and the read.
//!
//! The file is read as [`SourceFile::read_capped`] reads it, at most the
//! profile's `[program] max_file_size` bytes: a FIFO or a device is
//! `gcodec::io::not_a_file` (before anything is read from it), a larger
//! file `gcodec::io::too_large`, UTF-16 text `gcodec::io::utf16`; any other
//! failure to read it (no permission, a broken link) is
//! `gcodec::run::program_unreadable`.
//!
//! # Matching names to files
//!
//! Program names are compared case-insensitively (ASCII) and otherwise
//! exactly: `L7` and `L007` are different programs (reference §8.4). In a
//! directory, the program `NAME` is the file `NAME.SPF` or `NAME.MPF`
//! (any case), or `_N_NAME_SPF` / `_N_NAME_MPF` (the control's internal
//! names, also with an extension: `_N_NAME_SPF.SPF`). When a directory
//! holds both, the SPF is taken; when it holds two files for one program
//! and type (`SUB.SPF` and `sub.spf`, or `SUB.SPF` and `_N_SUB_SPF`), the
//! first in byte order of the file name is taken and the load reports
//! `gcodec::run::program_ambiguous` (a warning).
//!
//! A requested name may carry the control's decorations (reference §1.1):
//! `_N_SUB_SPF`, `SUB_SPF` and `SUB.SPF` ask for the SPF `SUB` only,
//! `_N_SUB_MPF`, `SUB_MPF` and `SUB.MPF` for the MPF, `_N_SUB` and `SUB`
//! for either. In a directory with no program `MY` of that type, a name
//! with a type suffix but no `_N_` also matches the program named as
//! written, of either type (`MY_SPF` finds `MY_SPF.SPF`).
//!
//! A path (`PCALL /_N_WKS_DIR/_N_W_WPD/_N_SUB_SPF`, `CALL
//! "/_N_SPF_DIR/_N_SUB_SPF"`, any name with a `/`) is looked up by its last
//! component along the same search path: the control's directories do not
//! exist on disk here. A name is letters, digits and `_` (at most
//! [`MAX_NAME_LEN`] bytes, plus an optional `.SPF`/`.MPF`), a path's
//! components likewise; anything else (`..`, `\`, a NUL, a space, an empty
//! component) is `gcodec::run::program_not_found` without touching the
//! file system, so that no name reaches outside the search directories.
//!
//! # Caching
//!
//! A run sees the file system as it was at the first look: every
//! directory is listed once, every name is resolved once per calling
//! directory (misses too), and every program (by its place on the search
//! path: the canonical directory and the file's name) is read, parsed and
//! lowered once. A cycle called a million times costs two hash lookups per
//! call after the first. A loader given
//! [`LoadedFiles`] ([`FileLoader::with_loaded_files`]) records each file
//! it reads there, so that the run's diagnostics are labelled from it.
//!
//! # Lowering
//!
//! A called program is compiled as `gcodec lower` compiles it
//! ([`crate::compile()`] with the run's profile and definitions), as a
//! [`ProgramKind::Subprogram`]: it starts in its caller's (unknown) modal
//! state whatever its file is called. A program with parse or lowering
//! errors is still returned ([`Loaded::has_errors`]): the channel decides
//! what to do (it raises an alarm).

use std::borrow::Cow;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use gcodec_exec::event::{DiagnosticEvent, Event, EventKind, EventSource};
use gcodec_exec::loader::{LoadError, LoadRequest, Loaded, ProgramLoader};
use gcodec_exec::program::Program;
use gcodec_profile::Profile;
use gcodec_sema::{Definitions, ProgramKind};
use gcodec_source::{ReadError, Severity, SourceFile, TextEncoding, codes};
use rustc_hash::FxHashMap;

use crate::compile;
use crate::loaded_files::LoadedFiles;
use crate::meant_command::not_found_help;

/// The longest program name looked for, in bytes (the control allows
/// far fewer). Longer names are not found.
pub const MAX_NAME_LEN: usize = 128;

/// The longest requested name or path considered at all.
const MAX_REQUEST_LEN: usize = 1024;

// ---------------------------------------------------------------------------
// The search path

/// Where called programs are looked for, after the directory of the
/// calling program's file: the profile's `subprogram_paths`, then the
/// `--subprogram-path` directories (see the [module](self) documentation).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SearchPath {
    /// The profile's `subprogram_paths`, resolved.
    profile_dirs: Vec<PathBuf>,
    /// `--subprogram-path`, as given.
    extra_dirs: Vec<PathBuf>,
    /// The profile's `link_target_paths`, resolved.
    link_dirs: Vec<PathBuf>,
    /// The profile's `external_program_path`, resolved: searched first
    /// for `EXTCALL`.
    external_dir: Option<PathBuf>,
}

impl SearchPath {
    /// Only the calling program's directory.
    pub fn new() -> Self {
        Self::default()
    }

    /// With the profile's `[program] subprogram_paths` and
    /// `link_target_paths`, replacing any set before. A relative path is
    /// taken against the directory of `profile_file` (the profile's TOML)
    /// when it is given, else against the current directory.
    pub fn with_profile(mut self, profile: &Profile, profile_file: Option<&Path>) -> Self {
        self.profile_dirs = resolve_profile_paths(&profile.program.subprogram_paths, profile_file);
        self.link_dirs = resolve_profile_paths(&profile.program.link_target_paths, profile_file);
        self.external_dir = resolve_profile_paths(
            profile.program.external_program_path.as_slice(),
            profile_file,
        )
        .pop();
        self
    }

    /// With more directories searched last (`--subprogram-path`), in order.
    /// A relative one is taken against the current directory.
    pub fn with_dirs<I>(mut self, dirs: I) -> Self
    where
        I: IntoIterator,
        I::Item: Into<PathBuf>,
    {
        self.extra_dirs.extend(dirs.into_iter().map(Into::into));
        self
    }

    /// The directories searched after the caller's, in order.
    pub fn dirs(&self) -> impl Iterator<Item = &Path> {
        self.profile_dirs
            .iter()
            .chain(&self.extra_dirs)
            .map(PathBuf::as_path)
    }

    /// The directories, besides those searched, that a program's file may
    /// be a symbolic link into.
    pub fn link_dirs(&self) -> impl Iterator<Item = &Path> {
        self.link_dirs.iter().map(PathBuf::as_path)
    }

    /// Every directory searched for a call from the program in
    /// `caller_file`, in order: its directory first. Duplicates are left
    /// in; the loader searches a directory once.
    pub fn for_caller(&self, caller_file: &str) -> Vec<PathBuf> {
        let mut all = vec![caller_dir(caller_file).to_path_buf()];
        all.extend(self.dirs().map(Path::to_path_buf));
        all
    }

    /// [`Self::for_caller`] for an `EXTCALL`: the external program path
    /// first.
    pub fn for_external_call(&self, caller_file: &str) -> Vec<PathBuf> {
        let mut all: Vec<PathBuf> = self.external_dir.iter().cloned().collect();
        all.extend(self.for_caller(caller_file));
        all
    }
}

fn resolve_profile_paths(paths: &[String], profile_file: Option<&Path>) -> Vec<PathBuf> {
    let base = profile_file
        .and_then(Path::parent)
        .filter(|p| !p.as_os_str().is_empty());
    paths
        .iter()
        .map(|p| match base {
            Some(base) => base.join(p),
            None => PathBuf::from(p),
        })
        .collect()
}

/// The directory of a program's file: `.` for a bare file name.
fn caller_dir(caller_file: &str) -> &Path {
    match Path::new(caller_file).parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    }
}

// ---------------------------------------------------------------------------
// Names

/// Program types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Spf,
    Mpf,
}

impl Kind {
    fn extension(self) -> &'static str {
        match self {
            Self::Spf => "SPF",
            Self::Mpf => "MPF",
        }
    }

    fn index(self) -> usize {
        match self {
            Self::Spf => 0,
            Self::Mpf => 1,
        }
    }
}

/// `.SPF` / `.MPF` at the end of `text`, any case: the text before and
/// the type.
fn strip_type(text: &str, separator: u8) -> Option<(&str, Kind)> {
    let bytes = text.as_bytes();
    if bytes.len() < 4 || bytes[bytes.len() - 4] != separator {
        return None;
    }
    let (stem, suffix) = text.split_at(text.len() - 4);
    let kind = if suffix[1..].eq_ignore_ascii_case("SPF") {
        Kind::Spf
    } else if suffix[1..].eq_ignore_ascii_case("MPF") {
        Kind::Mpf
    } else {
        return None;
    };
    Some((stem, kind))
}

fn strip_prefix_ci<'a>(text: &'a str, prefix: &str) -> Option<&'a str> {
    let head = text.get(..prefix.len())?;
    head.eq_ignore_ascii_case(prefix)
        .then(|| &text[prefix.len()..])
}

/// `_N_NAME_SPF`: `NAME` and the type.
fn internal_name(text: &str) -> Option<(&str, Kind)> {
    let rest = strip_prefix_ci(text, "_N_")?;
    let (name, kind) = strip_type(rest, b'_')?;
    (!name.is_empty()).then_some((name, kind))
}

/// The name callers use for the program in the file `path`, as the
/// search path names it: `PART` for `part.mpf`, `_N_PART_MPF` and
/// `_N_PART_MPF.MPF`; the file stem in upper case for other names.
pub fn program_name(path: &std::path::Path) -> String {
    let file_name = path.file_name().map(|n| n.to_string_lossy());
    file_name
        .as_deref()
        .and_then(classify)
        .map(|(name, _)| name)
        .unwrap_or_else(|| {
            path.file_stem()
                .map(|s| s.to_string_lossy().to_ascii_uppercase())
                .unwrap_or_default()
        })
}

/// The program a directory entry holds: its name in upper case and its
/// type. `NAME.SPF`, `NAME.MPF`, `_N_NAME_SPF`, `_N_NAME_MPF`,
/// `_N_NAME_SPF.SPF`; any case. Other files hold none.
fn classify(file_name: &str) -> Option<(String, Kind)> {
    let (name, kind) = match strip_type(file_name, b'.') {
        Some((stem, kind)) => match internal_name(stem) {
            Some((name, inner)) if inner == kind => (name, kind),
            _ => (stem, kind),
        },
        None => internal_name(file_name)?,
    };
    (!name.is_empty()).then(|| (name.to_ascii_uppercase(), kind))
}

/// What a request looks for.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Wanted {
    /// The program's name, upper case.
    name: String,
    /// The type the request asks for; `None`: SPF, else MPF.
    kind: Option<Kind>,
    /// Looked for (either type) when `name` is not in a directory: the
    /// name as written when a type suffix was taken off (`MY_SPF`).
    literal: Option<String>,
}

impl Wanted {
    /// Finds the wanted program in an index of programs by name (upper
    /// case), each with a slot per type: the type asked for, else an SPF
    /// before an MPF; then the literal name, of either type.
    fn find_in<'i, T>(&self, index: &'i FxHashMap<String, [Option<T>; 2]>) -> Option<&'i T> {
        let pick = |name: &str, kind: Option<Kind>| {
            let slots = index.get(name)?;
            match kind {
                Some(kind) => slots[kind.index()].as_ref(),
                None => slots[0].as_ref().or(slots[1].as_ref()),
            }
        };
        pick(&self.name, self.kind).or_else(|| self.literal.as_deref().and_then(|l| pick(l, None)))
    }

    /// The file name to suggest: `NAME.SPF`.
    fn file_name(&self) -> String {
        format!(
            "{}.{}",
            self.name,
            self.kind.unwrap_or(Kind::Spf).extension()
        )
    }
}

fn is_name(text: &str) -> bool {
    !text.is_empty()
        && text.len() <= MAX_NAME_LEN
        && text.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
}

/// Reads a requested name or path; `Err` says why it names no program.
fn parse_request(raw: &str) -> Result<Wanted, &'static str> {
    if raw.is_empty() {
        return Err("the name is empty");
    }
    if raw.len() > MAX_REQUEST_LEN {
        return Err("the name is too long");
    }
    let mut last = raw;
    if raw.contains('/') {
        let mut components = raw.split('/').peekable();
        if raw.starts_with('/') {
            components.next();
        }
        while let Some(component) = components.next() {
            if component == "." || component == ".." {
                return Err("`.` and `..` are not allowed in a program path");
            }
            if component.is_empty() {
                return Err("the path has an empty component");
            }
            if components.peek().is_none() {
                last = component;
            } else if !is_name(component) {
                return Err("a directory of the path is not a name of letters, digits and `_`");
            }
        }
    }
    let (stem, extension) = match strip_type(last, b'.') {
        Some((stem, kind)) => (stem, Some(kind)),
        None => (last, None),
    };
    if !is_name(stem) {
        return Err("a program name has letters, digits and `_` only");
    }
    let upper = stem.to_ascii_uppercase();
    let wanted = if let Some(rest) = strip_prefix_ci(&upper, "_N_").filter(|r| !r.is_empty()) {
        match strip_type(rest, b'_').filter(|(name, _)| !name.is_empty()) {
            Some((name, kind)) if extension.is_none_or(|e| e == kind) => Wanted {
                name: name.to_owned(),
                kind: Some(kind),
                literal: None,
            },
            Some(_) => return Err("the name's type suffix and extension disagree"),
            None => Wanted {
                name: rest.to_owned(),
                kind: extension,
                literal: None,
            },
        }
    } else {
        match strip_type(&upper, b'_').filter(|(name, _)| !name.is_empty()) {
            Some((name, kind)) if extension.is_none_or(|e| e == kind) => Wanted {
                name: name.to_owned(),
                kind: Some(kind),
                literal: Some(upper.clone()),
            },
            _ => Wanted {
                name: upper,
                kind: extension,
                literal: None,
            },
        }
    };
    Ok(wanted)
}

/// A requested name for a message: at most 64 characters, control
/// characters escaped.
fn shown(name: &str) -> String {
    let mut out = String::new();
    for (count, c) in name.chars().enumerate() {
        if count == 64 {
            out.push('…');
            break;
        }
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

fn invalid_name(request: &LoadRequest<'_>, why: &str) -> LoadError {
    LoadError {
        code: codes::run::PROGRAM_NOT_FOUND,
        message: format!(
            "{} `{}` names no program: {why}",
            what(request),
            shown(request.name)
        ),
        searched: Vec::new(),
        help: Some(
            "a program is called by its name (letters, digits, `_`) or a control path like \
             `/_N_SPF_DIR/_N_NAME_SPF`, which is looked up by its last component"
                .to_owned(),
        ),
    }
}

fn what(request: &LoadRequest<'_>) -> &'static str {
    if request.by_path {
        "program path"
    } else {
        "subprogram"
    }
}

// ---------------------------------------------------------------------------
// Directories

/// One listed directory: the programs directly inside it.
#[derive(Debug, Default)]
struct DirIndex {
    /// Why it could not be listed (`None`: listed).
    problem: Option<DirProblem>,
    /// Program name (upper case) → the file of each type.
    programs: FxHashMap<String, [Option<DirFile>; 2]>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum DirProblem {
    Missing,
    Unreadable,
}

/// The file holding a program of one type in a directory.
#[derive(Debug)]
struct DirFile {
    file_name: String,
    /// Other files naming the same program and type, in byte order.
    others: Vec<String>,
}

impl DirIndex {
    fn list(dir: &Path) -> Self {
        let entries = match fs::read_dir(dir) {
            Ok(entries) => entries,
            Err(e) => {
                let problem = if e.kind() == io::ErrorKind::NotFound {
                    DirProblem::Missing
                } else {
                    DirProblem::Unreadable
                };
                return Self {
                    problem: Some(problem),
                    programs: FxHashMap::default(),
                };
            }
        };
        let mut found = Vec::new();
        for entry in entries.flatten() {
            let os_name = entry.file_name();
            // Program names are ASCII: other names hold none.
            let Some(file_name) = os_name.to_str() else {
                continue;
            };
            let Some((name, kind)) = classify(file_name) else {
                continue;
            };
            let is_dir = match entry.file_type() {
                Ok(t) if t.is_symlink() => fs::metadata(entry.path()).is_ok_and(|m| m.is_dir()),
                Ok(t) => t.is_dir(),
                Err(_) => false,
            };
            if !is_dir {
                found.push((file_name.to_owned(), name, kind));
            }
        }
        // Byte order of the file names: the first of several wins.
        found.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        let mut programs: FxHashMap<String, [Option<DirFile>; 2]> = FxHashMap::default();
        for (file_name, name, kind) in found {
            let slot = &mut programs.entry(name).or_default()[kind.index()];
            match slot {
                Some(first) => first.others.push(file_name),
                None => {
                    *slot = Some(DirFile {
                        file_name,
                        others: Vec::new(),
                    });
                }
            }
        }
        Self {
            problem: None,
            programs,
        }
    }

    /// The file holding `wanted` here (an SPF before an MPF when the
    /// request names no type).
    fn find(&self, wanted: &Wanted) -> Option<&DirFile> {
        wanted.find_in(&self.programs)
    }
}

/// A directory of a caller's search path.
#[derive(Debug)]
struct SearchDir {
    /// As configured (for messages and the program's file name).
    shown: PathBuf,
    /// Its canonical path (`shown` where it has none).
    canonical: PathBuf,
    index: Arc<DirIndex>,
}

/// What one calling directory sees: its search path and the names
/// resolved from it.
#[derive(Debug)]
struct CallerDir {
    dirs: Vec<SearchDir>,
    /// Requested name as given → outcome (misses too).
    names: FxHashMap<String, Outcome>,
}

type Outcome = Result<(Arc<Program>, bool), LoadError>;

// ---------------------------------------------------------------------------
// FileLoader

/// Loads called programs from files along a [`SearchPath`]; see the
/// [module](self) documentation for the rules.
#[derive(Debug)]
pub struct FileLoader {
    search: SearchPath,
    profile: Arc<Profile>,
    definitions: Arc<Definitions>,
    /// Canonical directory → its listing.
    listings: FxHashMap<PathBuf, Arc<DirIndex>>,
    /// Calling program's directory → its search path and resolved names.
    /// (an `EXTCALL` has a search path of its own).
    callers: FxHashMap<(PathBuf, bool), CallerDir>,
    /// A file's place on the search path (canonical directory and file
    /// name) → the program (or why it cannot be read).
    programs: FxHashMap<PathBuf, Outcome>,
    /// The canonical `link_target_paths` that exist.
    link_roots: Vec<PathBuf>,
    /// Where each program file read is recorded (`None`: nowhere).
    loaded_files: Option<LoadedFiles>,
    /// How the files read are decoded (the profile's code page, unless
    /// [`FileLoader::with_encoding`] says otherwise).
    encoding: TextEncoding,
}

impl FileLoader {
    /// A loader searching `search`, lowering with `profile` and
    /// `definitions`.
    pub fn new(
        search: SearchPath,
        profile: impl Into<Arc<Profile>>,
        definitions: impl Into<Arc<Definitions>>,
    ) -> Self {
        let link_roots = search
            .link_dirs()
            .filter_map(|dir| fs::canonicalize(dir).ok())
            .collect();
        let profile = profile.into();
        Self {
            search,
            encoding: profile.program.text_encoding(),
            profile,
            definitions: definitions.into(),
            listings: FxHashMap::default(),
            callers: FxHashMap::default(),
            programs: FxHashMap::default(),
            link_roots,
            loaded_files: None,
        }
    }

    /// Decoding every file it reads as `encoding` says (`--encoding`).
    pub fn with_encoding(mut self, encoding: TextEncoding) -> Self {
        self.encoding = encoding;
        self
    }

    /// Recording each program file it reads in `files`, for labelling the
    /// run's diagnostics without reading the file again.
    pub fn with_loaded_files(mut self, files: LoadedFiles) -> Self {
        self.loaded_files = Some(files);
        self
    }

    /// The search path of a caller in `caller_file` (of its `EXTCALL`s
    /// when `external`): each directory once, listed.
    fn caller(&mut self, caller_file: &str, external: bool) -> CallerDir {
        let mut dirs: Vec<SearchDir> = Vec::new();
        let mut seen: Vec<PathBuf> = Vec::new();
        let search = if external {
            self.search.for_external_call(caller_file)
        } else {
            self.search.for_caller(caller_file)
        };
        for shown in search {
            let key = fs::canonicalize(&shown).unwrap_or_else(|_| shown.clone());
            if seen.contains(&key) {
                continue;
            }
            let index = self
                .listings
                .entry(key.clone())
                .or_insert_with(|| Arc::new(DirIndex::list(&shown)))
                .clone();
            seen.push(key.clone());
            dirs.push(SearchDir {
                shown,
                canonical: key,
                index,
            });
        }
        CallerDir {
            dirs,
            names: FxHashMap::default(),
        }
    }

    /// Finds, reads and lowers `request` (not cached yet).
    fn resolve(
        &mut self,
        dirs: &[SearchDir],
        request: &LoadRequest<'_>,
        wanted: &Wanted,
    ) -> Result<Loaded, LoadError> {
        let mut searched = Vec::new();
        for dir in dirs {
            searched.push(dir.shown.clone());
            let Some(found) = dir.index.find(wanted) else {
                continue;
            };
            let path = dir.shown.join(&found.file_name);
            let place = dir.canonical.join(&found.file_name);
            if let Some(outcome) = self.programs.get(&place) {
                return cached(outcome);
            }
            let result = match self.read_confined(&path, dirs) {
                Ok(file) => {
                    let file = Arc::new(file);
                    if let Some(files) = &self.loaded_files {
                        files.insert(Arc::clone(&file));
                    }
                    let mut loaded = compile(
                        file,
                        ProgramKind::Subprogram,
                        &self.profile,
                        &self.definitions,
                    )
                    .into_loaded(found_program_name(wanted, &found.file_name));
                    if !found.others.is_empty() {
                        loaded
                            .diagnostics
                            .insert(0, ambiguity(&dir.shown, found, &loaded.program));
                    }
                    Ok(loaded)
                }
                Err(Unread::Outside(target)) => Err(outside(request, &path, &target, searched)),
                Err(Unread::Read(e)) => Err(unreadable(request, &path, &e, searched)),
            };
            self.programs.insert(place, to_cache(&result));
            return result;
        }
        Err(not_found(request, wanted, dirs, searched))
    }

    /// Reads the program's file at `path`, found in one of `dirs`, if its
    /// real path is inside them or the link directories; named `path`.
    fn read_confined(&self, path: &Path, dirs: &[SearchDir]) -> Result<SourceFile, Unread> {
        let real = fs::canonicalize(path).map_err(|e| Unread::Read(e.into()))?;
        let inside = dirs
            .iter()
            .filter(|dir| dir.index.problem.is_none())
            .map(|dir| &dir.canonical)
            .chain(&self.link_roots)
            .any(|root| real.starts_with(root));
        if !inside {
            return Err(Unread::Outside(real));
        }
        // The real path, so a link swapped after the check is not followed.
        let max_len = *self.profile.program.max_file_size.get_ref();
        SourceFile::read_capped(&real, max_len)
            .map(|file| file.named(path).decoded(self.encoding))
            .map_err(Unread::Read)
    }
}

/// Why a program's file was not read.
enum Unread {
    /// It is a link to this real path, outside the directories allowed.
    Outside(PathBuf),
    Read(ReadError),
}

fn outside(
    request: &LoadRequest<'_>,
    link: &Path,
    target: &Path,
    searched: Vec<PathBuf>,
) -> LoadError {
    LoadError {
        code: codes::io::OUTSIDE_SEARCH_PATH,
        message: format!(
            "{} `{}` is `{}`, a symbolic link to `{}`, which is outside the search path",
            what(request),
            shown(request.name),
            link.display(),
            target.display()
        ),
        searched,
        help: Some(
            "list the directory the link points into in the profile's `[program] \
             link_target_paths`, or put the file itself on the search path"
                .to_owned(),
        ),
    }
}

/// A found file that cannot be read: the read error's own code, but an
/// IO error is the run's `program_unreadable`.
fn unreadable(
    request: &LoadRequest<'_>,
    path: &Path,
    error: &ReadError,
    searched: Vec<PathBuf>,
) -> LoadError {
    let (code, help) = match error {
        ReadError::Io(_) => (
            codes::run::PROGRAM_UNREADABLE,
            "check that the file is readable",
        ),
        _ => (error.code(), error.help()),
    };
    LoadError {
        code,
        message: format!(
            "{} `{}` is `{}`, which cannot be read: {error}",
            what(request),
            shown(request.name),
            path.display()
        ),
        searched,
        help: Some(help.to_owned()),
    }
}

/// The program's name, upper case: the one its file's name gives
/// (`_N_SUB_SPF`: `SUB`).
fn found_program_name(wanted: &Wanted, file_name: &str) -> String {
    match classify(file_name) {
        Some((name, _)) => name,
        None => wanted.name.clone(),
    }
}

fn ambiguity(dir: &Path, found: &DirFile, program: &Program) -> Event {
    let mut files = found.file_name.clone();
    for other in &found.others {
        files.push_str(", ");
        files.push_str(other);
    }
    Event {
        kind: EventKind::Diagnostic(DiagnosticEvent {
            code: codes::run::PROGRAM_AMBIGUOUS,
            severity: Severity::Warning,
            message: Cow::Owned(format!(
                "`{}` holds more than one file for the program `{}` ({files}); `{}` is used",
                dir.display(),
                program.name,
                found.file_name
            )),
            alarm: None,
            help: Some(Cow::Borrowed(
                "remove or rename the other files: on the control one program has one file",
            )),
        }),
        source: EventSource {
            file: program.file.clone(),
            line: 1,
            col: 1,
            level: 0,
        },
    }
}

fn not_found(
    request: &LoadRequest<'_>,
    wanted: &Wanted,
    dirs: &[SearchDir],
    searched: Vec<PathBuf>,
) -> LoadError {
    let mut list = String::new();
    for (i, dir) in dirs.iter().enumerate() {
        if i > 0 {
            list.push_str(", ");
        }
        list.push_str(&dir.shown.display().to_string());
        match dir.index.problem {
            Some(DirProblem::Missing) => list.push_str(" (does not exist)"),
            Some(DirProblem::Unreadable) => list.push_str(" (cannot be read)"),
            None => {}
        }
    }
    let looked_up = if !request.name.eq_ignore_ascii_case(&wanted.name) {
        match wanted.kind {
            Some(kind) => format!(" (looked up as `{}`, {})", wanted.name, kind.extension()),
            None => format!(" (looked up as `{}`)", wanted.name),
        }
    } else {
        String::new()
    };
    LoadError {
        code: codes::run::PROGRAM_NOT_FOUND,
        message: format!(
            "{} `{}`{looked_up} is not on the search path (searched: {list})",
            what(request),
            shown(request.name),
        ),
        searched,
        help: Some(not_found_help(
            request.name,
            format!(
                "pass the directory holding {} with --subprogram-path \
                 (`gcodec check`: list it in gcodec.toml's `search_paths`)",
                wanted.file_name()
            ),
        )),
    }
}

impl ProgramLoader for FileLoader {
    /// On the caller's search path, each directory listed as `load` lists
    /// it (a listing made before is reused, none is kept).
    fn exists(&self, request: &LoadRequest<'_>) -> Option<bool> {
        let wanted = parse_request(request.name).ok()?;
        let found = self
            .search
            .for_caller(request.caller_file)
            .iter()
            .any(|dir| {
                let key = fs::canonicalize(dir).unwrap_or_else(|_| dir.clone());
                match self.listings.get(&key) {
                    Some(index) => index.find(&wanted).is_some(),
                    None => DirIndex::list(dir).find(&wanted).is_some(),
                }
            });
        Some(found)
    }

    fn load(&mut self, request: &LoadRequest<'_>) -> Result<Loaded, LoadError> {
        let key = (
            caller_dir(request.caller_file).to_path_buf(),
            request.external,
        );
        if let Some(outcome) = self
            .callers
            .get(&key)
            .and_then(|c| c.names.get(request.name))
        {
            return cached(outcome);
        }
        let wanted = parse_request(request.name).map_err(|why| invalid_name(request, why))?;
        let caller = match self.callers.remove(&key) {
            Some(caller) => caller,
            None => self.caller(request.caller_file, request.external),
        };
        let result = self.resolve(&caller.dirs, request, &wanted);
        let caller = self.callers.entry(key).or_insert(caller);
        caller
            .names
            .insert(request.name.to_owned(), to_cache(&result));
        result
    }
}

/// A program loaded before: its diagnostics were reported then.
fn cached(outcome: &Outcome) -> Result<Loaded, LoadError> {
    outcome
        .as_ref()
        .map(|(program, has_errors)| Loaded {
            program: Arc::clone(program),
            diagnostics: Vec::new(),
            has_errors: *has_errors,
        })
        .map_err(Clone::clone)
}

/// What the caches keep of a load.
fn to_cache(result: &Result<Loaded, LoadError>) -> Outcome {
    result
        .as_ref()
        .map(|l| (Arc::clone(&l.program), l.has_errors))
        .map_err(Clone::clone)
}

// ---------------------------------------------------------------------------
// MemoryLoader

/// Programs given as (file name, text) pairs, for tests and embedders.
/// The file name says the program and its type as a directory entry
/// would (`SUB.SPF`, `_N_SUB_SPF`, `MAIN.MPF`); a bare name (`SUB`) is an
/// SPF. The caller's directory plays no part; the matching rules are
/// those of [`FileLoader`] within one directory. Each program is parsed
/// and lowered on its first load.
#[derive(Debug)]
pub struct MemoryLoader {
    profile: Arc<Profile>,
    definitions: Arc<Definitions>,
    files: Vec<MemoryFile>,
    /// Program name → the index in `files` of each type.
    index: FxHashMap<String, [Option<usize>; 2]>,
}

#[derive(Debug)]
struct MemoryFile {
    name: String,
    file: Arc<SourceFile>,
    loaded: Option<Outcome>,
}

impl MemoryLoader {
    /// No programs yet; lowering with `profile` and `definitions`.
    pub fn new(profile: impl Into<Arc<Profile>>, definitions: impl Into<Arc<Definitions>>) -> Self {
        Self {
            profile: profile.into(),
            definitions: definitions.into(),
            files: Vec::new(),
            index: FxHashMap::default(),
        }
    }

    /// With the program in the file `file_name` holding `text`.
    pub fn with_program(mut self, file_name: &str, text: impl Into<Vec<u8>>) -> Self {
        self.insert(file_name, text);
        self
    }

    /// Adds the program in the file `file_name` holding `text`; it
    /// replaces one of the same name and type.
    pub fn insert(&mut self, file_name: &str, text: impl Into<Vec<u8>>) {
        let base = file_name.rsplit('/').next().unwrap_or(file_name);
        let (name, kind) = classify(base).unwrap_or_else(|| (base.to_ascii_uppercase(), Kind::Spf));
        let file = Arc::new(SourceFile::new(file_name, text));
        let slot = &mut self.index.entry(name.clone()).or_default()[kind.index()];
        let entry = MemoryFile {
            name,
            file,
            loaded: None,
        };
        match slot {
            Some(existing) => self.files[*existing] = entry,
            None => {
                *slot = Some(self.files.len());
                self.files.push(entry);
            }
        }
    }
}

impl ProgramLoader for MemoryLoader {
    fn exists(&self, request: &LoadRequest<'_>) -> Option<bool> {
        let wanted = parse_request(request.name).ok()?;
        Some(wanted.find_in(&self.index).is_some())
    }

    fn load(&mut self, request: &LoadRequest<'_>) -> Result<Loaded, LoadError> {
        let wanted = parse_request(request.name).map_err(|why| invalid_name(request, why))?;
        let Some(&index) = wanted.find_in(&self.index) else {
            return Err(LoadError {
                code: codes::run::PROGRAM_NOT_FOUND,
                message: format!(
                    "{} `{}` is not among the {} program(s) given",
                    what(request),
                    shown(request.name),
                    self.files.len()
                ),
                searched: Vec::new(),
                help: Some(not_found_help(
                    request.name,
                    format!("add {} to the loader", wanted.file_name()),
                )),
            });
        };
        let entry = &mut self.files[index];
        if let Some(outcome) = &entry.loaded {
            return cached(outcome);
        }
        let loaded = compile(
            Arc::clone(&entry.file),
            ProgramKind::Subprogram,
            &self.profile,
            &self.definitions,
        )
        .into_loaded(entry.name.clone());
        entry.loaded = Some(Ok((Arc::clone(&loaded.program), loaded.has_errors)));
        Ok(loaded)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wanted(name: &str, kind: Option<Kind>, literal: Option<&str>) -> Wanted {
        Wanted {
            name: name.to_owned(),
            kind,
            literal: literal.map(str::to_owned),
        }
    }

    #[test]
    fn requests_read_as_the_control_names_programs() {
        use Kind::*;
        let cases = [
            ("CYCLE81", wanted("CYCLE81", None, None)),
            ("cycle81", wanted("CYCLE81", None, None)),
            ("L007", wanted("L007", None, None)),
            ("_N_SUB_SPF", wanted("SUB", Some(Spf), None)),
            ("_N_SUB_MPF", wanted("SUB", Some(Mpf), None)),
            ("_N_SUB", wanted("SUB", None, None)),
            ("SUB_SPF", wanted("SUB", Some(Spf), Some("SUB_SPF"))),
            ("SUB.spf", wanted("SUB", Some(Spf), None)),
            (
                "/_N_WKS_DIR/_N_W_WPD/_N_SUB_SPF",
                wanted("SUB", Some(Spf), None),
            ),
            (
                "/_N_CUS_DIR/L5_SPF",
                wanted("L5", Some(Spf), Some("L5_SPF")),
            ),
            ("_DRESSING", wanted("_DRESSING", None, None)),
        ];
        for (raw, expected) in cases {
            assert_eq!(parse_request(raw), Ok(expected), "{raw}");
        }
        for bad in [
            "",
            "../x",
            "a/../x",
            "./x",
            "/",
            "x/",
            "a//b",
            "SUB\0",
            "SUB X",
            "a\\b",
            "x.txt",
            "_N_SUB_SPF.MPF",
            "é",
        ] {
            assert!(parse_request(bad).is_err(), "{bad:?}");
        }
        assert!(parse_request(&"A".repeat(MAX_NAME_LEN + 1)).is_err());
        assert!(parse_request(&"A".repeat(MAX_NAME_LEN)).is_ok());
    }

    #[test]
    fn files_hold_programs_by_their_names() {
        use Kind::*;
        let cases = [
            ("CYCLE81.SPF", Some(("CYCLE81", Spf))),
            ("kanavka_sfera.spf", Some(("KANAVKA_SFERA", Spf))),
            ("MAIN.MPF", Some(("MAIN", Mpf))),
            ("_N_SUB_SPF", Some(("SUB", Spf))),
            ("_n_sub_mpf", Some(("SUB", Mpf))),
            ("_N_SUB_SPF.SPF", Some(("SUB", Spf))),
            ("_N_SUB_SPF.MPF", Some(("_N_SUB_SPF", Mpf))),
            ("MY_SPF.SPF", Some(("MY_SPF", Spf))),
            ("_DRESSING.SPF", Some(("_DRESSING", Spf))),
            ("MGUD.DEF", None),
            ("_N_SPF", None),
            (".SPF", None),
            ("SUB", None),
        ];
        for (file, expected) in cases {
            assert_eq!(
                classify(file),
                expected.map(|(n, k)| (n.to_owned(), k)),
                "{file}"
            );
        }
    }

    #[test]
    fn relative_profile_paths_follow_the_profile_file() {
        let paths = ["subprograms".to_owned(), "/abs".to_owned()];
        assert_eq!(
            resolve_profile_paths(&paths, Some(Path::new("cfg/machine.toml"))),
            [PathBuf::from("cfg/subprograms"), PathBuf::from("/abs")]
        );
        assert_eq!(
            resolve_profile_paths(&paths, Some(Path::new("machine.toml"))),
            [PathBuf::from("subprograms"), PathBuf::from("/abs")]
        );
        assert_eq!(
            resolve_profile_paths(&paths, None),
            [PathBuf::from("subprograms"), PathBuf::from("/abs")]
        );
        assert_eq!(caller_dir("MAIN.MPF"), Path::new("."));
        assert_eq!(caller_dir(""), Path::new("."));
        assert_eq!(caller_dir("a/b/MAIN.MPF"), Path::new("a/b"));
    }
}
