//! Global user data (GUD) and macros from definition files.
//!
//! On the control, global variables are defined in definition files
//! (`_N_SGUD_DEF`, `_N_MGUD_DEF`, `_N_UGUD_DEF`, `_N_GUD4_DEF` …
//! `_N_GUD9_DEF` in `/_N_DEF_DIR`) and macros in `_N_SMAC_DEF`,
//! `_N_MMAC_DEF`, `_N_UMAC_DEF` (reference §7.3). A part program may use
//! them without a `DEF` of its own. [`Definitions`] holds what such files
//! define, for [`crate::lower_with`]: the names with their types and
//! array dimensions, and the macros, which the parser expands in the
//! programs (`gcodec_parser::parse_with_macros`).
//!
//! A definition file holds `DEF`, `DEFINE` and `REDEF` statements, comment
//! lines, and usually `M17` or `M30` at its end; anything else in it is an
//! error (`gcodec::definitions::not_a_definition`), and so is a name
//! defined twice (`gcodec::definitions::duplicate`).

use gcodec_lang::DataType;
use gcodec_parser::ast::{self, StatementKind};
use gcodec_parser::{Macro, Macros};
use gcodec_source::{Diagnostic, Diagnostics, SourceFile, Span, codes};

use crate::types::{self, NameMap, constant_count};
use gcodec_lang::sysvars;
/// Where a global variable lives (`DEF NCK …`, `DEF CHAN …`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GlobalRange {
    /// `NCK`: one for the whole control.
    Nck,
    /// `CHAN`, or no range given: one per channel.
    Chan,
}

/// One global variable of a definition file.
#[derive(Clone, Debug, PartialEq)]
pub struct GlobalVariable {
    /// The name as written in the definition file.
    pub name: String,
    pub data_type: DataType,
    /// The array dimensions; `None` for a dimension that is not a
    /// constant. Empty for a single value.
    pub dims: Vec<Option<u32>>,
    pub range: GlobalRange,
    /// The attributes of the `DEF` and of later `REDEF`s, upper case
    /// (`SYNR`, `APW`, `INIPO` …).
    pub attributes: Vec<String>,
    /// The definition file.
    pub file: String,
    /// Where the variable is defined in that file.
    pub span: Span,
    /// The 1-based line and byte column of `span`'s start, for what
    /// reports it without the file at hand (the run's diagnostic events).
    pub line: u32,
    pub col: u32,
}

/// The global names a program may use without defining them: global user
/// data and macros, read from definition files.
#[derive(Clone, Debug, Default)]
pub struct Definitions {
    variables: NameMap<GlobalVariable>,
    macros: Macros,
    assumed: NameMap<()>,
}

impl Definitions {
    /// No definitions: what [`crate::lower`] uses.
    pub fn new() -> Self {
        Self::default()
    }

    /// Parses a definition file and adds what it defines; returns the
    /// parser's diagnostics and the problems of the file. What is defined
    /// correctly is added even when other lines are wrong.
    pub fn load(&mut self, file: &SourceFile) -> Diagnostics {
        let parsed = gcodec_parser::parse(file);
        let mut diagnostics = parsed.diagnostics;
        diagnostics.append(self.add_program(&parsed.program));
        diagnostics
    }

    /// [`Definitions::load`] for a file's bytes under a name.
    pub fn load_bytes(&mut self, name: &str, bytes: &[u8]) -> Diagnostics {
        self.load(&SourceFile::new(name, bytes))
    }

    /// Definitions from source text: the definitions and the diagnostics
    /// of the file.
    pub fn from_source(name: &str, text: &str) -> (Self, Diagnostics) {
        let mut definitions = Self::new();
        let diagnostics = definitions.load_bytes(name, text.as_bytes());
        (definitions, diagnostics)
    }

    /// Adds the definitions of a parsed definition file.
    pub fn add_program(&mut self, program: &ast::Program) -> Diagnostics {
        let mut diagnostics = Diagnostics::new();
        for block in &program.blocks {
            // One `not_a_definition` per block: `G1 X10` is one mistake.
            let mut reported = false;
            for statement in &block.statements {
                let definition = self.statement(program, statement, &mut diagnostics);
                if !definition && !std::mem::replace(&mut reported, true) {
                    diagnostics.push(
                        Diagnostic::new(
                            codes::definitions::NOT_A_DEFINITION,
                            "a definition file holds only `DEF`, `DEFINE` and `REDEF`",
                        )
                        .with_label(statement.span, "not a definition")
                        .with_help("move this statement into a part program"),
                    );
                }
            }
        }
        diagnostics
    }

    /// Adds what `statement` defines; false if it is not a definition.
    fn statement(
        &mut self,
        program: &ast::Program,
        statement: &ast::Statement,
        diagnostics: &mut Diagnostics,
    ) -> bool {
        match &statement.kind {
            StatementKind::Def(def) => {
                let data_type = types::from_ast(&def.ty.kind);
                let mut range = GlobalRange::Chan;
                let mut attributes = Vec::new();
                for attribute in &def.attributes {
                    if attribute.name.eq_ignore_ascii_case("NCK") {
                        range = GlobalRange::Nck;
                    } else if !attribute.name.eq_ignore_ascii_case("CHAN") {
                        attributes.push(attribute.name.to_ascii_uppercase().to_string());
                    }
                }
                for var in &def.vars {
                    if let Some(init) = &var.init {
                        check_constant_initializer(
                            data_type,
                            &var.name,
                            init,
                            program.source.bytes(),
                            diagnostics,
                        );
                    }
                    let (line, col) = program.line_col(var.span.start);
                    let global = GlobalVariable {
                        name: var.name.to_string(),
                        data_type,
                        dims: var.dims.iter().map(constant_count).collect(),
                        range,
                        attributes: attributes.clone(),
                        file: program.file.clone(),
                        span: var.span,
                        line,
                        col,
                    };
                    if let Some(first) = self.variables.insert_new(&var.name, global) {
                        let mut d = Diagnostic::new(
                            codes::definitions::DUPLICATE,
                            format!("`{}` is defined twice", var.name),
                        )
                        .with_label(var.span, "defined again here")
                        .with_help("the control rejects a definition file that defines a name twice; remove one of them");
                        if first.file == program.file {
                            d = d.with_label(first.span, "first defined here");
                        }
                        diagnostics.push(d);
                    }
                }
            }
            StatementKind::Define(define) => {
                if !is_expandable_name(&define.name) {
                    diagnostics.push(
                        Diagnostic::new(
                            codes::lower::NOT_LOWERED,
                            format!("the macro `{}` is named like a DIN word and is not expanded", define.name),
                        )
                        .with_label(statement.span, "not expanded")
                        .with_help("gcodec expands macros named by identifiers (two letters or `_` first); `M6` and the like are read as the words they spell"),
                    );
                }
                let item = Macro {
                    name: define.name.to_string(),
                    body: define.body.to_string(),
                    file: program.file.clone(),
                    line: program.line_col(statement.span.start).0,
                };
                if !self.macros.insert(item) {
                    diagnostics.push(
                        Diagnostic::new(
                            codes::definitions::DUPLICATE,
                            format!("the macro `{}` is defined twice", define.name),
                        )
                        .with_label(statement.span, "defined again here")
                        .with_help("remove one of the definitions"),
                    );
                }
            }
            StatementKind::Redef(redef) => {
                let known = if redef.name.starts_with('$') {
                    sysvars::lookup(&redef.name).is_some()
                } else {
                    self.variables.contains(&redef.name)
                };
                if let Some(global) = self.variables.get_mut(&redef.name) {
                    global.attributes.extend(
                        redef
                            .attributes
                            .iter()
                            .map(|a| a.name.to_ascii_uppercase().to_string()),
                    );
                } else if !known {
                    diagnostics.push(
                        Diagnostic::new(
                            codes::lower::UNDEFINED_VARIABLE,
                            format!("`REDEF` of `{}`, which is not defined", redef.name),
                        )
                        .with_label(statement.span, "not defined before")
                        .with_help("`REDEF` changes the attributes of a variable defined earlier (in this or a definition file loaded before it)"),
                    );
                }
            }
            // The end of the file.
            StatementKind::Word(word) if is_program_end(word, statement.span) => {}
            _ => return false,
        }
        true
    }

    /// Makes `name` known without a definition: for a name the control
    /// knows from a definition file that is not at hand. Its type and
    /// dimensions are unknown, so its uses are not checked.
    pub fn assume_defined(&mut self, name: &str) {
        self.assumed.insert_new(name, ());
    }

    /// Whether `name` was made known by [`Definitions::assume_defined`].
    pub fn is_assumed(&self, name: &str) -> bool {
        self.assumed.contains(name)
    }

    /// The global variable `name` (any case).
    pub fn variable(&self, name: &str) -> Option<&GlobalVariable> {
        self.variables.get(name)
    }

    /// The macro `name` (any case).
    pub fn macro_named(&self, name: &str) -> Option<&Macro> {
        self.macros.get(name)
    }

    /// The macros, for the parser to expand.
    pub fn macros(&self) -> &Macros {
        &self.macros
    }

    /// How many variables are defined.
    pub fn len(&self) -> usize {
        self.variables.len()
    }

    /// Whether nothing is defined (neither variables nor macros).
    pub fn is_empty(&self) -> bool {
        self.variables.len() == 0 && self.macros.is_empty() && self.assumed.len() == 0
    }

    /// The variables, in no particular order.
    pub fn variables(&self) -> impl Iterator<Item = &GlobalVariable> {
        self.variables.values()
    }
}

/// Whether the parser expands uses of a macro of this name: the
/// identifiers, whose first two characters are letters or `_`.
fn is_expandable_name(name: &str) -> bool {
    let bytes = name.as_bytes();
    bytes.len() >= 2
        && bytes[..2]
            .iter()
            .all(|b| b.is_ascii_alphabetic() || *b == b'_')
}

/// `M2`, `M17`, `M30`: the end of a program or definition file.
pub(crate) fn is_program_end(word: &ast::Word, span: Span) -> bool {
    word.address() == "M"
        && word.extension().is_none()
        && crate::values::whole_number(&word.value(span))
            .is_some_and(|m| m == 2.0 || m == 17.0 || m == 30.0)
}

/// Checks what a constant initialiser can show without a profile: a
/// string constant too long for its `STRING[n]`, a string for a number
/// and a number for a string.
fn check_constant_initializer(
    data_type: DataType,
    name: &str,
    init: &ast::Initializer,
    source: &[u8],
    diagnostics: &mut Diagnostics,
) {
    let items: Vec<&ast::Expr> = match init {
        ast::Initializer::Expr(e) => vec![e],
        ast::Initializer::List { items, .. } => items.iter().flatten().collect(),
        ast::Initializer::Rep { args, .. } => args.first().into_iter().collect(),
    };
    for expr in items {
        if let Some((found, constant)) = types::literal(expr) {
            diagnostics.extend(types::mismatch(
                data_type, name, found, constant, expr.span, source,
            ));
        }
    }
}
