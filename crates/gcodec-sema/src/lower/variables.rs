//! Variables: which names a program may use, their types and array
//! dimensions, and the checks of every read and write, `DEF`,
//! assignments, `REDEF` and `DEFINE`.
//!
//! # Scopes
//!
//! A name without `$` must be known to the control (alarm 12550 "name not
//! defined" otherwise): a `DEF` of the program part it is used in (local
//! user data), a parameter of the enclosing `PROC`, a global variable or
//! macro of the definition files ([`Definitions`]), a `DEFINE` macro of the
//! program, or an axis of the machine (profile `[[axes]]`, and the machine
//! axis names `AX1`, `AX2` … of MD10000).
//!
//! A file is cut into *sections*, each with its own local names: the file
//! start, every `PROC` (its parameters are its first names), the block
//! after `ENDPROC`, and a `DEF` that follows the end of a program part
//! (`RET`, `M17`, `M2`, `M30` outside any control structure) — the shape of
//! a file holding a procedure and then a main program. `RET` and `M17`
//! alone do not end a section: code after them may be reached by a jump.
//!
//! `DEF`s belong in the definition part at the start of a section, before
//! the first executable statement (reference §7.3); one after it is the
//! control's alarm 14500, here `gcodec::lower::misplaced_definition`. The
//! sections and their names are collected once before lowering; a name is
//! known from the end of its `DEF` on.

use std::sync::atomic::{AtomicUsize, Ordering};

use gcodec_ail::Op;
use gcodec_lang::addresses::NamedAddress;
use gcodec_lang::{DataType, UnaryOp, identifiers};
use gcodec_parser::ast::{self, StatementKind};
use gcodec_profile::Profile;
use gcodec_source::{Diagnostic, Diagnostics, Span, codes};

use crate::definitions::{Definitions, is_program_end};
use crate::types::{self, Constant, NameMap, constant_count};
use crate::values;
use gcodec_lang::sysvars::{self, IndexShape};

use super::{BlockPlan, Lowering};
/// Array dimensions tracked per variable (the language allows three).
const MAX_DIMS: usize = 3;

/// The type and dimensions of a variable.
#[derive(Clone, Copy, Debug)]
struct Shape {
    ty: DataType,
    /// Number of dimensions.
    rank: u8,
    /// The first `MAX_DIMS` dimensions; `None` where not a constant.
    dims: [Option<u32>; MAX_DIMS],
}

impl Shape {
    fn new(ty: DataType, dims: impl ExactSizeIterator<Item = Option<u32>>) -> Self {
        let rank = u8::try_from(dims.len()).unwrap_or(u8::MAX);
        let mut shape = Shape {
            ty,
            rank,
            dims: [None; MAX_DIMS],
        };
        for (slot, d) in shape.dims.iter_mut().zip(dims) {
            *slot = d;
        }
        shape
    }

    fn dim(&self, i: usize) -> Option<u32> {
        self.dims.get(i).copied().flatten()
    }

    /// All elements, if every dimension is known.
    fn elements(&self) -> Option<u64> {
        if usize::from(self.rank) > MAX_DIMS {
            return None;
        }
        // Three dimensions of up to 2^32 − 1 each can pass 64 bits: then
        // unknown, as the run refuses such a declaration anyway.
        (0..usize::from(self.rank)).try_fold(1u64, |n, i| n.checked_mul(u64::from(self.dim(i)?)))
    }

    /// The type of a reference with `count` indices: an element, a
    /// character of a STRING element, a component of a FRAME element.
    fn element_type(&self, count: usize) -> Option<DataType> {
        let rank = usize::from(self.rank);
        match self.ty {
            _ if count == rank => Some(self.ty),
            DataType::String { .. } if count == rank + 1 => Some(DataType::Char),
            DataType::Frame if count > rank => Some(DataType::Real),
            _ => None,
        }
    }
}

/// A local name: a `DEF` or a `PROC` parameter.
#[derive(Clone, Copy, Debug)]
struct Local {
    shape: Shape,
    /// The name is known from this byte offset on.
    defined_at: u32,
    span: Span,
}

/// The names of one section of the file.
#[derive(Default)]
struct Section {
    /// Byte offset of the section's first block.
    start: u32,
    locals: NameMap<Local>,
    /// `DEFINE` macros, with the offset they are known from.
    macros: NameMap<u32>,
}

/// What a name is.
#[derive(Clone, Copy, Debug)]
enum Resolved {
    Variable(Shape),
    /// A macro, an address, or a name assumed known: no type.
    Untyped,
    Axis,
    /// Defined, but only further on.
    Later(Span),
    Undefined,
}

/// The names a program may use, by section, collected before lowering.
pub(super) struct Names<'a> {
    definitions: &'a Definitions,
    axes: NameMap<()>,
    sections: Vec<Section>,
    /// The section of the last lookup (lowering goes forward): a hint
    /// only, shared by the threads that lower parts of the program.
    current: AtomicUsize,
}

/// Collects the sections and local names of a program fed block by block
/// in order; reports `DEF`s after the first executable statement and
/// names defined twice.
pub(super) struct NameCollector<'a> {
    names: Names<'a>,
    diagnostics: Diagnostics,
    /// Still in the definition part of the section; else the first
    /// executable statement.
    first_executable: Option<Span>,
    /// The last block with statements ended a program part.
    after_end: bool,
    new_section_next: bool,
}

impl<'a> NameCollector<'a> {
    pub(super) fn new(profile: &Profile, definitions: &'a Definitions) -> Self {
        let mut axes = NameMap::default();
        for axis in &profile.axes {
            axes.insert_new(axis.name.get_ref(), ());
        }
        NameCollector {
            names: Names {
                definitions,
                axes,
                sections: vec![Section::default()],
                current: AtomicUsize::new(0),
            },
            diagnostics: Diagnostics::new(),
            first_executable: None,
            after_end: false,
            new_section_next: false,
        }
    }

    /// The names and what was wrong with them.
    pub(super) fn finish(self) -> (Names<'a>, Diagnostics) {
        (self.names, self.diagnostics)
    }

    /// Takes in the next block of the program (its depth set).
    pub(super) fn block(&mut self, block: &ast::Block) {
        if block.statements.is_empty() {
            return;
        }
        let names = &mut self.names;
        let diagnostics = &mut self.diagnostics;
        if std::mem::take(&mut self.new_section_next) {
            names.start_section(block.span.start);
            self.first_executable = None;
        }
        let mut ends = false;
        for statement in block.statements.iter() {
            let span = statement.span;
            match &statement.kind {
                StatementKind::Proc(proc) => {
                    names.start_section(block.span.start);
                    self.first_executable = None;
                    for param in &proc.params {
                        let shape = Shape::new(
                            types::from_ast(&param.ty.kind),
                            param.dims.iter().map(constant_count),
                        );
                        names.define(param.span, &param.name, shape, span.start, diagnostics);
                    }
                }
                StatementKind::Def(def) => {
                    if let Some(executable) = self.first_executable {
                        if self.after_end {
                            names.start_section(block.span.start);
                            self.first_executable = None;
                        } else {
                            diagnostics.push(
                                Diagnostic::new(
                                    codes::lower::MISPLACED_DEFINITION,
                                    "`DEF` after the first executable statement",
                                )
                                .with_label(span, "defined here")
                                .with_label(executable, "the program part starts here")
                                .with_help("definitions belong at the start of the program or procedure, before any other statement; the control rejects this `DEF` (alarm 14500)"),
                            );
                        }
                    }
                    let ty = types::from_ast(&def.ty.kind);
                    for var in &def.vars {
                        let shape = Shape::new(ty, var.dims.iter().map(constant_count));
                        names.define(var.span, &var.name, shape, var.span.end, diagnostics);
                    }
                }
                StatementKind::Define(define) => {
                    let section = names.sections.last_mut().expect("one section");
                    section.macros.insert_new(&define.name, span.end);
                }
                StatementKind::Redef(_) | StatementKind::Extern(_) => {}
                StatementKind::EndProc => {
                    ends = true;
                    self.new_section_next = true;
                    self.first_executable.get_or_insert(span);
                }
                StatementKind::Ret(_) => {
                    ends = true;
                    self.first_executable.get_or_insert(span);
                }
                StatementKind::Word(word) if is_program_end(word, span) => {
                    ends = true;
                    self.first_executable.get_or_insert(span);
                }
                _ => {
                    self.first_executable.get_or_insert(span);
                }
            }
        }
        self.after_end = ends && block.depth == 0;
    }
}

impl<'a> Names<'a> {
    pub(super) fn macros(&self) -> &'a gcodec_parser::Macros {
        self.definitions.macros()
    }

    fn start_section(&mut self, start: u32) {
        self.sections.push(Section {
            start,
            ..Section::default()
        });
    }

    fn define(
        &mut self,
        span: Span,
        name: &str,
        shape: Shape,
        defined_at: u32,
        diagnostics: &mut Diagnostics,
    ) {
        if self.axes.contains(name) || is_machine_axis(name) {
            diagnostics.push(
                Diagnostic::new(
                    codes::lower::NAME_IS_AXIS,
                    format!("`{name}` is an axis of this machine and cannot name a variable"),
                )
                .with_label(span, "declared here")
                .with_help("the control reads the name as the axis (`NAME=5` moves it); rename the variable, e.g. `U_VALUE`"),
            );
        }
        let section = self.sections.last_mut().expect("one section");
        let local = Local {
            shape,
            defined_at,
            span,
        };
        if let Some(first) = section.locals.insert_new(name, local) {
            diagnostics.push(
                Diagnostic::new(codes::lower::DUPLICATE_DEFINITION, format!("`{name}` is defined twice"))
                    .with_label(span, "defined again here")
                    .with_label(first.span, "first defined here")
                    .with_help("the control rejects a second definition of a name in one program; rename or remove one"),
            );
        }
    }

    /// The section a byte offset lies in.
    fn section_at(&self, at: u32) -> &Section {
        let current = self.current.load(Ordering::Relaxed);
        let fits = |i: usize| {
            self.sections[i].start <= at
                && self.sections.get(i + 1).is_none_or(|next| at < next.start)
        };
        if current < self.sections.len() && fits(current) {
            return &self.sections[current];
        }
        let i = self
            .sections
            .partition_point(|s| s.start <= at)
            .saturating_sub(1);
        self.current.store(i, Ordering::Relaxed);
        &self.sections[i]
    }

    /// The defined variable nearest to the undefined `name` used at `at`:
    /// a local of its section defined before `at`, or a global one.
    pub(super) fn nearest(&self, name: &str, at: u32) -> Option<String> {
        let section = self.section_at(at);
        let locals = section
            .locals
            .iter()
            .filter(|(_, local)| local.defined_at <= at)
            .map(|(name, _)| name.to_owned());
        let globals = self
            .definitions
            .variables()
            .map(|g| g.name.to_ascii_uppercase());
        let mut candidates: Vec<String> = locals.chain(globals).collect();
        candidates.sort_unstable();
        gcodec_source::nearest(name, candidates.iter().map(String::as_str)).map(str::to_owned)
    }

    /// What `name`, used at byte offset `at`, is.
    /// Whether the program declares `name` at `at` (a `DEF` before or
    /// after, a parameter, global user data, a macro or a name assumed
    /// defined): then it is that, even where it spells an address.
    pub(super) fn declares(&self, name: &str, at: u32) -> bool {
        let section = self.section_at(at);
        section.locals.get(name).is_some()
            || self.definitions.variable(name).is_some()
            || section.macros.get(name).is_some_and(|&from| from <= at)
            || self.definitions.macro_named(name).is_some()
            || self.definitions.is_assumed(name)
    }

    /// Whether `name` is a STRING variable at `at` (a jump target it
    /// names is the label the string holds).
    pub(super) fn is_string_variable(&self, name: &str, at: u32) -> bool {
        matches!(
            self.resolve(name, at),
            Resolved::Variable(Shape {
                ty: DataType::String { .. },
                rank: 0,
                ..
            })
        )
    }

    fn resolve(&self, name: &str, at: u32) -> Resolved {
        let section = self.section_at(at);
        let mut later = None;
        if let Some(local) = section.locals.get(name) {
            if local.defined_at <= at {
                return Resolved::Variable(local.shape);
            }
            later = Some(local.span);
        }
        if let Some(global) = self.definitions.variable(name) {
            return Resolved::Variable(Shape::new(global.data_type, global.dims.iter().copied()));
        }
        if section.macros.get(name).is_some_and(|&from| from <= at)
            || self.definitions.macro_named(name).is_some()
            || self.definitions.is_assumed(name)
        {
            return Resolved::Untyped;
        }
        if self.axes.contains(name) || is_machine_axis(name) {
            return Resolved::Axis;
        }
        if is_address_name(name) {
            return Resolved::Untyped;
        }
        later.map_or(Resolved::Undefined, Resolved::Later)
    }
}

/// `AX1`, `AX12`: the machine axis names of MD10000
/// `$MN_AXCONF_MACHAX_NAME_TAB` (their defaults; alarm 4012 lists them as
/// the valid machine axis identifiers).
fn is_machine_axis(name: &str) -> bool {
    let bytes = name.as_bytes();
    bytes.len() > 2
        && bytes[..2].eq_ignore_ascii_case(b"AX")
        && bytes[2] != b'0'
        && bytes[2..].iter().all(u8::is_ascii_digit)
}

/// A named address (`MEAS`, `OS`, `FMA`, reference §2.6) or the
/// polynomial coefficients `PO`: known to the control, not undefined
/// names; their lowering belongs to the addresses.
fn is_address_name(name: &str) -> bool {
    NamedAddress::named(name).is_some() || name.eq_ignore_ascii_case("PO")
}

/// `TR`, `FI`, `RT`, `SC`, `MI`: a component index of a frame
/// (`$P_UIFR[1,X,TR]`).
fn frame_component(expr: &ast::Expr) -> bool {
    match &expr.kind {
        ast::ExprKind::Var { var } if var.kind == ast::VarKind::Name && var.indices.is_empty() => {
            ["TR", "FI", "RT", "SC", "MI"]
                .iter()
                .any(|c| c.eq_ignore_ascii_case(&var.name))
        }
        _ => false,
    }
}

/// A constant whole-number index; a larger one than 10^15 is left to the
/// run, which names it (`index_out_of_range`, `overflow`).
fn constant_index(expr: &ast::Expr) -> Option<i64> {
    let v = values::constant(expr)?;
    // Whole and below 10^15 < 2^63: the cast is exact.
    (v.fract() == 0.0 && v.abs() < 1e15).then_some(v as i64)
}

impl Lowering<'_> {
    /// Checks the variables an expression reads. Recursion follows the
    /// parser's bounded expression depth.
    pub(super) fn check_variables(&mut self, expr: &ast::Expr) {
        match &expr.kind {
            ast::ExprKind::Var { var } => self.check_variable(var),
            ast::ExprKind::Call(call) => {
                for arg in call.args.iter().flatten() {
                    self.check_variables(arg);
                }
            }
            ast::ExprKind::Unary { operand, .. } => self.check_variables(operand),
            ast::ExprKind::Binary(b) => {
                self.check_variables(&b.lhs);
                self.check_variables(&b.rhs);
            }
            _ => {}
        }
    }

    /// Checks a variable read or written: the name is known, its indices
    /// fit its declaration or the system variable's shape.
    pub(super) fn check_variable(&mut self, var: &ast::VarRef) {
        match var.kind {
            ast::VarKind::System => self.check_system_variable(var),
            ast::VarKind::Name => self.check_user_variable(var),
            ast::VarKind::RParameter => {
                for index in &var.indices {
                    self.check_variables(index);
                }
            }
        }
    }

    fn check_system_variable(&mut self, var: &ast::VarRef) {
        let Some(known) = sysvars::lookup(&var.name) else {
            let spelling = "check the spelling against the SINUMERIK lists of system variables and machine data";
            let written = var.name.trim_start_matches('$');
            let help = match gcodec_source::nearest(
                written,
                sysvars::all().map(|v| v.name.trim_start_matches('$')),
            ) {
                Some(near) => format!("did you mean `${near}`? {spelling}"),
                None => spelling.to_owned(),
            };
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::UNKNOWN_SYSTEM_VARIABLE,
                    format!("`{}` is not a system variable of the control", var.name),
                )
                .with_label(var.span, "unknown")
                .with_help(help),
            );
            for index in &var.indices {
                self.check_variables(index);
            }
            return;
        };
        let count = var.indices.len();
        if !known.shape.accepts(count) {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::SYSTEM_VARIABLE_INDEX,
                    format!(
                        "`{}` takes {}; {} written",
                        var.name,
                        shape_text(known.shape),
                        match count {
                            0 => "none is".to_owned(),
                            1 => "1 is".to_owned(),
                            n => format!("{n} are"),
                        }
                    ),
                )
                .with_label(var.span, "wrong number of indices")
                .with_help(format!("`{}`: {}", known.name, known.description)),
            );
            for index in &var.indices {
                self.check_variables(index);
            }
            return;
        }
        // What each index must be: an axis, a number, a frame component.
        #[derive(Clone, Copy, PartialEq)]
        enum Kind {
            Axis,
            Number,
            Component,
            Any,
        }
        let kinds: &[Kind] = match (known.shape, count) {
            (IndexShape::Axis, _) => &[Kind::Axis],
            (IndexShape::Number | IndexShape::Numbers(_), _) => &[Kind::Number; 8],
            (IndexShape::Frame, 2) => &[Kind::Axis, Kind::Component],
            (IndexShape::FrameComponent, 1) => &[Kind::Number],
            (IndexShape::FrameComponent, 3) => &[Kind::Number, Kind::Axis, Kind::Component],
            _ => &[],
        };
        for (i, index) in var.indices.iter().enumerate() {
            let kind = kinds.get(i).copied().unwrap_or(Kind::Any);
            if kind == Kind::Component {
                if !frame_component(index) {
                    self.system_index_error(var, index, "a frame component: `TR` translation, `FI` fine offset, `RT` rotation, `SC` scale or `MI` mirror");
                }
                continue;
            }
            self.check_variables(index);
            let ty = self.expr_type(index);
            let wrong = match kind {
                Kind::Axis => ty.is_some_and(|t| t != DataType::Axis),
                Kind::Number => ty.is_some_and(|t| {
                    matches!(
                        t,
                        DataType::Axis | DataType::Frame | DataType::String { .. }
                    )
                }),
                _ => false,
            };
            if wrong {
                let what = if kind == Kind::Axis {
                    "an axis (`X`, `AX1`, an AXIS variable)"
                } else {
                    "a number"
                };
                self.system_index_error(var, index, what);
            }
        }
    }

    fn system_index_error(&mut self, var: &ast::VarRef, index: &ast::Expr, what: &str) {
        self.diagnostics.push(
            Diagnostic::new(
                codes::lower::SYSTEM_VARIABLE_INDEX,
                format!("this index of `{}` must be {what}", var.name),
            )
            .with_label(index.span, "wrong kind of index")
            .with_help(format!(
                "`{}` takes {}",
                var.name,
                sysvars::lookup(&var.name).map_or("other indices", |v| shape_text(v.shape))
            )),
        );
    }

    fn check_user_variable(&mut self, var: &ast::VarRef) {
        let resolved = self.outline.names.resolve(&var.name, var.span.start);
        let mut components_from = usize::MAX;
        match resolved {
            Resolved::Variable(shape) => {
                let rank = usize::from(shape.rank);
                if shape.ty == DataType::Frame {
                    components_from = rank;
                }
                self.check_indices(var, shape);
            }
            Resolved::Untyped | Resolved::Axis => {}
            Resolved::Later(defined) => self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::UNDEFINED_VARIABLE,
                    format!("`{}` is used before its definition", var.name),
                )
                .with_label(var.span, "not defined yet")
                .with_label(defined, "defined here")
                .with_help(
                    "the control knows a name from its `DEF` on (alarm 12550); move the `DEF` up",
                ),
            ),
            Resolved::Undefined
                if let Some((message, help)) = identifiers::invalid_name(&var.name) =>
            {
                // A program written for a lenient interpreter (`FOR m=…`): the
                // name is the language's, never a missing definition.
                self.diagnostics.push(
                    Diagnostic::new(codes::lower::NOT_A_VARIABLE, message)
                        .with_label(var.span, "not a variable")
                        .with_help(help),
                );
            }
            Resolved::Undefined => {
                let label = match self.outline.names.nearest(&var.name, var.span.start) {
                    Some(near) => format!("unknown name: did you mean `{near}`?"),
                    None => "unknown name".to_owned(),
                };
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::UNDEFINED_VARIABLE,
                        format!("`{}` is not defined", var.name),
                    )
                    .with_label(var.span, label)
                    .with_help("define it with `DEF` at the start of the program (or as a `PROC` parameter); for global user data pass its definition file (`--definitions FILE.DEF`); the control raises alarm 12550 \"name not defined\""),
                )
            }
        }
        for (i, index) in var.indices.iter().enumerate() {
            if i >= components_from && frame_component(index) {
                continue;
            }
            self.check_variables(index);
        }
    }

    /// The number of indices fits the declaration; constant indices lie
    /// within the declared bounds.
    fn check_indices(&mut self, var: &ast::VarRef, shape: Shape) {
        let count = var.indices.len();
        let rank = usize::from(shape.rank);
        let fits = count == 0
            || count == rank
            || matches!(shape.ty, DataType::String { .. }) && count == rank + 1
            || shape.ty == DataType::Frame && count > rank && count <= rank + 2;
        if !fits {
            let declared = if rank == 0 {
                "a single value (no index)".to_owned()
            } else {
                format!(
                    "an array of {rank} dimension{}",
                    if rank == 1 { "" } else { "s" }
                )
            };
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::INDEX_COUNT,
                    format!(
                        "`{}` is {declared}; {count} ind{} written",
                        var.name,
                        if count == 1 { "ex is" } else { "ices are" }
                    ),
                )
                .with_label(var.span, "wrong number of indices")
                .with_help(
                    "write one index per declared dimension (`TAB[I_ROW,I_COL]` for `DEF REAL TAB[3,4]`)",
                ),
            );
            return;
        }
        for (i, index) in var.indices.iter().enumerate().take(rank) {
            let (Some(dim), Some(value)) = (shape.dim(i), constant_index(index)) else {
                continue;
            };
            if value < 0 || value >= i64::from(dim) {
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::INDEX_OUT_OF_RANGE,
                        format!(
                            "index {value} is outside `{}`: {} indices run from 0 to {}",
                            var.name,
                            ordinal(i, rank),
                            dim - 1
                        ),
                    )
                    .with_label(index.span, "out of range")
                    .with_help("indices count from 0; the control stops with an alarm (17020 \"illegal array index\")"),
                );
            }
        }
    }

    /// The static type of an expression, where it is known: constants,
    /// declared variables, R parameters (REAL), system variables the
    /// registry types, built-in functions, operators. `None` is unknown
    /// (never an error).
    pub(super) fn expr_type(&self, expr: &ast::Expr) -> Option<DataType> {
        use gcodec_lang::BinaryOp as B;
        match &expr.kind {
            ast::ExprKind::Number { integer, .. } => Some(if *integer {
                DataType::Int
            } else {
                DataType::Real
            }),
            ast::ExprKind::String { value } => Some(DataType::String {
                length: u32::try_from(value.len()).ok(),
            }),
            ast::ExprKind::Bool { .. } => Some(DataType::Bool),
            ast::ExprKind::Var { var } => self.var_type(var),
            ast::ExprKind::Call(call) => gcodec_lang::functions::function_type(&call.name),
            ast::ExprKind::Unary { op, operand } => match op {
                UnaryOp::Neg | UnaryOp::Plus => self.expr_type(operand).filter(|t| t.is_number()),
                UnaryOp::Not => Some(DataType::Bool),
                UnaryOp::BNot => Some(DataType::Int),
                UnaryOp::ToString => Some(DataType::String { length: None }),
            },
            ast::ExprKind::Binary(b) => match b.op {
                B::Add | B::Sub | B::Mul | B::Mod | B::Div | B::IntDiv => {
                    let (l, r) = (self.expr_type(&b.lhs)?, self.expr_type(&b.rhs)?);
                    if !(l.is_number() && r.is_number()) {
                        return None;
                    }
                    Some(match b.op {
                        B::IntDiv => DataType::Int,
                        B::Div => DataType::Real,
                        _ if l == DataType::Int && r == DataType::Int => DataType::Int,
                        _ => DataType::Real,
                    })
                }
                B::BAnd | B::BOr | B::BXor => Some(DataType::Int),
                B::And | B::Or | B::Xor => Some(DataType::Bool),
                B::Concat => Some(DataType::String { length: None }),
                B::Eq | B::Ne | B::Lt | B::Gt | B::Le | B::Ge => Some(DataType::Bool),
                B::Chain => Some(DataType::Frame),
            },
        }
    }

    /// The static type of a variable reference, where it is known.
    fn var_type(&self, var: &ast::VarRef) -> Option<DataType> {
        match var.kind {
            ast::VarKind::RParameter => Some(DataType::Real),
            ast::VarKind::System => {
                sysvars::lookup(&var.name).and_then(|v| v.data_type(var.indices.len()))
            }
            ast::VarKind::Name => match self.outline.names.resolve(&var.name, var.span.start) {
                Resolved::Variable(shape) => shape.element_type(var.indices.len()),
                Resolved::Axis if var.indices.is_empty() => Some(DataType::Axis),
                _ => None,
            },
        }
    }

    /// Reports a value that cannot be assigned to `name` of type `target`.
    fn check_value(&mut self, target: DataType, name: &str, value: &ast::Expr) {
        let (found, constant) = match types::literal(value) {
            Some(found) => found,
            None => match self.expr_type(value) {
                Some(t) => (t, Constant::None),
                None => return,
            },
        };
        self.diagnostics.extend(types::mismatch(
            target,
            name,
            found,
            constant,
            value.span,
            self.source,
        ));
    }

    /// The length of a `STRING[n]` a `DEF` or a `PROC` parameter names:
    /// the instruction holds a constant length only, and one that is no
    /// count (0, 2.5, beyond `u32`) would silently be the default 200.
    pub(super) fn check_string_length(&mut self, kind: &ast::TypeKind) {
        let ast::TypeKind::String {
            length: Some(length),
        } = kind
        else {
            return;
        };
        self.check_variables(length);
        if values::constant(length).is_some() && constant_count(length).is_none() {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::INVALID_VALUE,
                    format!(
                        "`STRING[{}]`: a string length is a whole number 1…4294967295",
                        values::written(self.source, length.span)
                    ),
                )
                .with_label(length.span, "not a string length"),
            );
        }
    }

    /// `DEF TYPE name[dims]=init, …`: one declaration per variable, its
    /// initialiser checked against the type and the number of elements.
    pub(super) fn declare(&mut self, def: &ast::Def, span: Span, plan: &mut BlockPlan) {
        let ty = types::from_ast(&def.ty.kind);
        self.check_string_length(&def.ty.kind);
        for var in &def.vars {
            for dim in &var.dims {
                self.check_variables(dim);
            }
            let shape = Shape::new(ty, var.dims.iter().map(constant_count));
            let mut init = Vec::new();
            let mut init_repeat = None;
            match &var.init {
                None => {}
                Some(ast::Initializer::Expr(e)) => {
                    self.check_variables(e);
                    self.check_value(ty, &var.name, e);
                    init.push(Some(values::value(e)));
                }
                Some(ast::Initializer::List {
                    span: at, items, ..
                }) => {
                    if shape.rank == 0 && items.len() > 1 {
                        self.diagnostics.push(not_an_array(&var.name, *at));
                    } else if let Some(total) = shape.elements() {
                        let count = items.len();
                        let shown = count.to_string();
                        self.check_count(&var.name, count as u64, &shown, 0, total, *at);
                    }
                    for item in items.iter().flatten() {
                        self.check_variables(item);
                        self.check_value(ty, &var.name, item);
                    }
                    init = items
                        .iter()
                        .map(|i| i.as_ref().map(values::value))
                        .collect();
                }
                Some(ast::Initializer::Rep { span: at, args }) => {
                    init_repeat = self.repeat(&var.name, ty, shape, 0, args, *at);
                    if init_repeat.is_none() {
                        continue;
                    }
                }
            }
            plan.other.push((
                Op::Declare(Box::new(gcodec_ail::Declare {
                    name: var.name.to_ascii_uppercase().to_string(),
                    data_type: ty,
                    dims: var.dims.iter().map(values::value).collect(),
                    init,
                    init_repeat,
                })),
                span,
            ));
        }
    }

    /// `REP(value[, count])` for `name` from element `start` on: checks
    /// and lowers it; `None` (after an error) if it cannot be.
    fn repeat(
        &mut self,
        name: &str,
        ty: DataType,
        shape: Shape,
        start: u64,
        args: &[ast::Expr],
        span: Span,
    ) -> Option<gcodec_ail::Repeat> {
        for arg in args {
            self.check_variables(arg);
        }
        let (value, count) = match args {
            [value] => (value, None),
            [value, count] => (value, Some(count)),
            _ => {
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::INVALID_VALUE,
                        format!("`REP` takes a value and a count; {} arguments are written", args.len()),
                    )
                    .with_label(span, "here")
                    .with_help("write `REP(value)` for every element or `REP(value, count)` for `count` elements"),
                );
                return None;
            }
        };
        if shape.rank == 0 {
            self.diagnostics.push(not_an_array(name, span));
        }
        self.check_value(ty, name, value);
        if let Some(count) = count {
            match values::constant(count) {
                Some(n) if n.fract() != 0.0 || n < 1.0 => {
                    self.diagnostics.push(
                        Diagnostic::new(
                            codes::lower::INVALID_VALUE,
                            format!(
                                "the count of `REP` must be a whole number of at least 1, not {}",
                                values::written(self.source, count.span)
                            ),
                        )
                        .with_label(count.span, "here")
                        .with_help("the count is the number of elements that get the value"),
                    );
                }
                Some(n) => {
                    if let Some(total) = shape.elements() {
                        // From 2^64 on the cast saturates, still more than
                        // any array holds; the message names the count as
                        // written.
                        let written = values::written(self.source, count.span);
                        self.check_count(name, n as u64, &written, start, total, count.span);
                    }
                }
                None => {}
            }
        }
        Some(gcodec_ail::Repeat {
            value: values::value(value),
            count: count.map(values::value),
        })
    }

    /// `count` values from element `start` on must fit in `total`; the
    /// message names the count as `written`.
    fn check_count(
        &mut self,
        name: &str,
        count: u64,
        written: &str,
        start: u64,
        total: u64,
        span: Span,
    ) {
        if start.saturating_add(count) > total {
            let from = if start == 0 {
                String::new()
            } else {
                format!(" from element {start} on")
            };
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::INDEX_OUT_OF_RANGE,
                    format!("{written} values{from} do not fit in `{name}`, which has {total} elements"),
                )
                .with_label(span, "too many values")
                .with_help("the control stops with an alarm (17020 \"illegal array index\"); write fewer values or enlarge the array"),
            );
        }
    }

    /// `R1=5`, `A[2,3]=7`, `$P_UIFR[1,X,TR]=10`, `NAME=…`, and the list
    /// forms `A[0]=SET(1,2,3)`, `A[0]=(1,2,3)`, `A[0]=REP(0,5)`.
    pub(super) fn assign(&mut self, assign: &ast::Assign, span: Span, plan: &mut BlockPlan) {
        let target = &assign.target;
        self.check_variable(target);
        let target_type = self.var_type(target);
        let op = match &assign.value {
            ast::Initializer::Expr(e) => {
                self.check_variables(e);
                if let Some(ty) = target_type {
                    self.check_value(ty, &display_name(target), e);
                }
                Op::Assign {
                    target: Box::new(values::variable(target)),
                    value: values::value(e),
                }
            }
            ast::Initializer::List {
                span: at, items, ..
            } => {
                for item in items.iter().flatten() {
                    self.check_variables(item);
                    if let Some(ty) = target_type {
                        self.check_value(ty, &target.name, item);
                    }
                }
                if let Some((shape, start)) = self.list_target(target, *at)
                    && let Some(total) = shape.elements()
                {
                    let count = items.len();
                    let shown = count.to_string();
                    self.check_count(&target.name, count as u64, &shown, start, total, *at);
                }
                Op::AssignList(Box::new(gcodec_ail::AssignList {
                    target: values::variable(target),
                    values: items
                        .iter()
                        .map(|i| i.as_ref().map(values::value))
                        .collect(),
                    repeat: None,
                }))
            }
            ast::Initializer::Rep { span: at, args } => {
                let (shape, start) = self
                    .list_target(target, *at)
                    .unwrap_or((Shape::new(DataType::Real, [None].into_iter()), 0));
                let ty = target_type.unwrap_or(shape.ty);
                let Some(repeat) = self.repeat(&target.name, ty, shape, start, args, *at) else {
                    return;
                };
                Op::AssignList(Box::new(gcodec_ail::AssignList {
                    target: values::variable(target),
                    values: Vec::new(),
                    repeat: Some(repeat),
                }))
            }
        };
        plan.other.push((op, span));
    }

    /// The array a list of values is written into and the storage index
    /// of the first element written (`A[2,1]` of `A[3,4]` is 9), where
    /// known. A declared single value is an error.
    fn list_target(&mut self, target: &ast::VarRef, at: Span) -> Option<(Shape, u64)> {
        if target.kind != ast::VarKind::Name {
            return None;
        }
        let Resolved::Variable(shape) = self.outline.names.resolve(&target.name, target.span.start)
        else {
            return None;
        };
        if shape.rank == 0 {
            self.diagnostics.push(not_an_array(&target.name, at));
            return None;
        }
        if target.indices.len() != usize::from(shape.rank) {
            return None;
        }
        let mut start = 0u64;
        for (i, index) in target.indices.iter().enumerate() {
            let dim = u64::from(shape.dim(i)?);
            let value = u64::try_from(constant_index(index)?).ok()?;
            start = start * dim + value;
        }
        Some((shape, start))
    }

    /// `REDEF name attributes`: the name must be known; the attributes
    /// (initialisation time, access levels, limits, unit, preprocessing
    /// stop) are not modelled.
    pub(super) fn redefine(&mut self, redef: &ast::Redef, span: Span) {
        let known = if redef.name.starts_with('$') {
            sysvars::lookup(&redef.name).is_some()
        } else {
            !matches!(
                self.outline.names.resolve(&redef.name, span.start),
                Resolved::Undefined | Resolved::Later(_)
            )
        };
        if !known {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::UNDEFINED_VARIABLE,
                    format!("`REDEF` of `{}`, which is not defined", redef.name),
                )
                .with_label(span, "unknown name")
                .with_help("`REDEF` changes the attributes of a variable defined before (a `DEF` above, global user data, a system variable); the control raises alarm 12550"),
            );
        }
        let attributes: Vec<String> = redef
            .attributes
            .iter()
            .map(|a| a.name.to_ascii_uppercase().to_string())
            .collect();
        self.diagnostics.push(
            Diagnostic::new(
                codes::lower::NOT_LOWERED,
                format!(
                    "`REDEF {}{}{}` is not lowered yet",
                    redef.name,
                    if attributes.is_empty() { "" } else { " " },
                    attributes.join(" ")
                ),
            )
            .with_label(span, "left out of the instruction list")
            .with_help("the attributes `REDEF` changes (initialisation at reset or power-on INIPO/INIRE/INICF/PRLOC, access levels APR/APW…, limits LLI/ULI, unit PHU, preprocessing stop SYNR/SYNW/SYNRW) are not modelled: the variable keeps the attributes of its `DEF`"),
        );
    }

    /// `DEFINE NAME AS text`: the name is known to later blocks, but its
    /// uses are not expanded.
    pub(super) fn define_macro(&mut self, define: &ast::Define, span: Span) {
        self.diagnostics.push(
            Diagnostic::new(
                codes::lower::NOT_LOWERED,
                format!(
                    "the macro `{}` is not expanded: macro expansion is not lowered yet",
                    define.name
                ),
            )
            .with_label(span, "left out of the instruction list")
            .with_help("uses of the macro name are lowered as a variable of that name, not as the text it stands for; the program cannot be run as written"),
        );
    }
}

/// A variable as messages name it: `R1` for an R parameter with a
/// constant index, else its name.
fn display_name(var: &ast::VarRef) -> std::borrow::Cow<'_, str> {
    match (var.kind, var.indices.as_slice()) {
        (ast::VarKind::RParameter, [index]) => match constant_index(index) {
            Some(n) => format!("R{n}").into(),
            None => "R[…]".into(),
        },
        _ => var.name.as_str().into(),
    }
}

/// A list of values for a single value.
fn not_an_array(name: &str, span: Span) -> Diagnostic {
    Diagnostic::new(
        codes::lower::TYPE_MISMATCH,
        format!("`{name}` is a single value: a list of values needs an array"),
    )
    .with_label(span, "a list of values")
    .with_help("`SET(…)`, `(…)` and `REP(…)` fill array elements; declare an array (`DEF REAL TAB[3]`) or assign one value")
}

/// "first", "second", … of `rank` indices, for messages.
fn ordinal(i: usize, rank: usize) -> String {
    if rank == 1 {
        return "its".to_owned();
    }
    let name = ["first", "second", "third"]
        .get(i)
        .copied()
        .unwrap_or("further");
    format!("the {name}")
}

/// The indices a system variable takes, for messages.
fn shape_text(shape: IndexShape) -> &'static str {
    match shape {
        IndexShape::None => "no index",
        IndexShape::Axis => "one axis index (`[X]`)",
        IndexShape::Number => "one number index (`[1]`)",
        IndexShape::Numbers(2) => "two number indices (`[t,d]`)",
        IndexShape::Numbers(_) => "several number indices",
        IndexShape::Frame => "no index (the whole frame) or `[axis, component]`",
        IndexShape::FrameComponent => "`[n]` (a whole frame) or `[n, axis, component]`",
        IndexShape::Dims(1) => "one index",
        IndexShape::Dims(2) => "two indices",
        IndexShape::Dims(3) => "three indices",
        IndexShape::Dims(_) => "several indices",
        IndexShape::Any => "any indices",
    }
}
