//! Compiling one program: parse it, lower it against a machine profile and
//! the global names of definition files, and gather every diagnostic of
//! both stages in source order.

use std::sync::Arc;

use gcodec_ail::Document;
use gcodec_exec::loader::Loaded;
use gcodec_exec::program::Program;
use gcodec_parser::Parse;
use gcodec_profile::Profile;
use gcodec_sema::{Definitions, ProgramKind};
use gcodec_source::{Diagnostics, SourceFile};

use crate::diagnostics::diagnostic_event;

/// A program compiled: its instructions and what parsing and lowering
/// found wrong.
#[derive(Debug)]
pub struct Compiled {
    /// The program's file.
    pub file: Arc<SourceFile>,
    /// The AIL document (always one, even for a program with errors).
    pub document: Document,
    /// Every diagnostic of parsing and lowering, in source order (a
    /// stable sort: at one place, the parser's come first), as many as
    /// are kept.
    pub diagnostics: Diagnostics,
}

impl Compiled {
    /// True if any diagnostic, kept or not, is an error.
    pub fn has_errors(&self) -> bool {
        self.diagnostics.has_errors()
    }

    /// The executor's program named `name` (upper case by convention),
    /// with the diagnostics as events in source order (`file`, `line`
    /// and `col` set; line 1, column 1 for one without a place; `level`
    /// 0: the channel sets it).
    pub fn into_loaded(self, name: impl Into<String>) -> Loaded {
        let has_errors = self.has_errors();
        let file_name: Arc<str> = Arc::from(self.file.name());
        let diagnostics = self
            .diagnostics
            .into_iter()
            .map(|d| diagnostic_event(d, &self.file, &file_name))
            .collect();
        Loaded {
            program: Arc::new(Program::new(name, self.file, self.document)),
            diagnostics,
            has_errors,
        }
    }
}

/// Trees of more blocks than this are freed on a thread of their own:
/// freeing them node by node would hold up the caller (for `gcodec
/// lower`, the exit) for longer than the thread costs.
const FREE_APART: usize = 100_000;

/// Parses the program in `file` with the macros of `definitions`
/// expanded, as [`compile`] parses it.
pub fn parse_with(file: &SourceFile, definitions: &Definitions) -> Parse {
    gcodec_parser::parse_with_macros(file, definitions.macros())
}

/// Parses and lowers the program in `file`, started as `kind`, for the
/// machine `profile` describes, with the global names of `definitions`.
pub fn compile(
    file: Arc<SourceFile>,
    kind: ProgramKind,
    profile: &Profile,
    definitions: &Definitions,
) -> Compiled {
    compile_then_lint(file, kind, profile, definitions, false)
}

/// [`compile`], with the findings of the lint rules
/// ([`gcodec_sema::lint`]) among the diagnostics: what `gcodec check`
/// reports of a program.
pub fn compile_linted(
    file: Arc<SourceFile>,
    kind: ProgramKind,
    profile: &Profile,
    definitions: &Definitions,
) -> Compiled {
    compile_then_lint(file, kind, profile, definitions, true)
}

fn compile_then_lint(
    file: Arc<SourceFile>,
    kind: ProgramKind,
    profile: &Profile,
    definitions: &Definitions,
    lint: bool,
) -> Compiled {
    let parsed = parse_with(&file, definitions);
    let lowered = gcodec_sema::lower_program(&parsed.program, kind, profile, definitions);
    let linted =
        lint.then(|| gcodec_sema::lint::lint(&parsed.program, &lowered.document, kind, profile));
    let tree = parsed.program;
    if tree.blocks.len() > FREE_APART {
        std::thread::spawn(move || drop(tree));
    } else {
        drop(tree);
    }
    let mut lowering_diagnostics = lowered.diagnostics;
    definitions
        .macros()
        .label_expansions(file.bytes(), &mut lowering_diagnostics);
    let mut diagnostics = parsed.diagnostics;
    diagnostics.append(lowering_diagnostics);
    if let Some(linted) = linted {
        diagnostics.append(linted);
    }
    diagnostics.sort_by_start();
    Compiled {
        file,
        document: lowered.document,
        diagnostics,
    }
}

/// [`compile`] for a program given as text, in a file called `file_name`.
pub fn compile_text(
    file_name: &str,
    text: impl Into<Vec<u8>>,
    kind: ProgramKind,
    profile: &Profile,
    definitions: &Definitions,
) -> Compiled {
    let file = Arc::new(SourceFile::new(file_name, text));
    compile(file, kind, profile, definitions)
}
