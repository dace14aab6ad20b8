//! Lowers a parsed program block by block into AIL, checking each word
//! against the machine profile and tracking the modal state of
//! straight-line code.
//!
//! Within a block, instructions come in the order the control acts on
//! them: work offset and other modal G commands, feed, spindle speed, tool
//! selection and cutting edge, M functions acting before the motion, the
//! motion, then `M0 M1 M2 M17 M30` after it (seed 001).

use std::borrow::Cow;
use std::collections::HashMap;
use std::sync::Arc;

use gcodec_ail::{
    AxisValue, ByteRange, Circle, Document, Instruction, MTiming, MotionKind, Op, Source,
    Suppression, SuppressionScope, ToolChangeTrigger, Value,
};
use gcodec_parser::ast::{
    self, Block, CallTarget, Extension, GotoKind, Program, StatementKind, StructureKind, Word,
};
use gcodec_profile::{DuplicateSuppressionPolicy, Profile};
use gcodec_source::{Diagnostic, Span};

use crate::flow::{self, Flow, Resolved, Role};
use crate::{ggroups, mfunc, sysvars, tools, values};

/// The result of lowering: always a document, plus what was wrong.
#[derive(Clone, Debug)]
pub struct Lowered {
    pub document: Document,
    pub diagnostics: Vec<Diagnostic>,
}

impl Lowered {
    /// True if any diagnostic is an error.
    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(Diagnostic::is_error)
    }
}

/// Lowers `program` for the machine `profile` describes.
pub fn lower(program: &Program, profile: &Profile) -> Lowered {
    let mut lowering = Lowering::new(program, profile);
    lowering.report_duplicate_labels();
    for (index, block) in program.blocks.iter().enumerate() {
        lowering.block(index, block);
    }
    let end = program.blocks.last().map_or(0, |b| b.span.end);
    let source = lowering.source_at(program.blocks.len().max(1) - 1, Span::new(end, end));
    lowering.document.instructions.push(Instruction {
        op: Op::End,
        source,
    });
    Lowered {
        document: lowering.document,
        diagnostics: lowering.diagnostics,
    }
}

const NOT_LOWERED: &str = "gcodec::lower::not_lowered";
const UNKNOWN_G: &str = "gcodec::lower::unknown_g";
const G_GROUP_CONFLICT: &str = "gcodec::lower::g_group_conflict";
const UNSUPPORTED_OFFSET: &str = "gcodec::lower::unsupported_offset";
const DUPLICATE_SUPPRESSION: &str = "gcodec::lower::duplicate_suppression";
const UNKNOWN_ADDRESS: &str = "gcodec::lower::unknown_address";
pub(crate) const UNKNOWN_SPINDLE: &str = "gcodec::lower::unknown_spindle";
const BLOCK_TOO_LONG: &str = "gcodec::lower::block_too_long";
pub(crate) const INVALID_VALUE: &str = "gcodec::lower::invalid_value";
const UNKNOWN_SYSTEM_VARIABLE: &str = "gcodec::lower::unknown_system_variable";
const MISSING_JUMP_TARGET: &str = "gcodec::lower::missing_jump_target";
const DUPLICATE_LABEL: &str = "gcodec::lower::duplicate_label";

/// The warning for a construct lowering does not translate yet: it is
/// named, never dropped in silence.
pub(crate) fn not_lowered(span: Span, what: &str) -> Diagnostic {
    Diagnostic::warning(NOT_LOWERED, format!("{what} is not lowered yet"))
        .with_label(span, "left out of the instruction list")
        .with_help(
            "gcodec does not translate this construct yet; the program cannot be run as written",
        )
}

/// A diagnostic at the severity a profile policy chose: an error or a
/// warning.
pub(crate) fn by_policy(error: bool, code: &'static str, message: String) -> Diagnostic {
    if error {
        Diagnostic::error(code, message)
    } else {
        Diagnostic::warning(code, message)
    }
}

/// `G<n>` for a G word's value, written into `buf`: no allocation and no
/// float formatting for the commonest word of all.
fn g_code_text(n: f64, buf: &mut [u8; 24]) -> &str {
    use std::io::Write as _;
    let mut rest = &mut buf[..];
    let _ = write!(rest, "G{}", n as u64);
    let len = 24 - rest.len();
    std::str::from_utf8(&buf[..len]).unwrap_or("G")
}

/// An address as an AIL axis name: single letters without allocating.
fn axis_name(address: &str) -> Cow<'static, str> {
    match address.as_bytes() {
        [b @ b'A'..=b'Z'] => Cow::Borrowed(ast::letter_str(*b)),
        _ => Cow::Owned(address.to_owned()),
    }
}

/// Where a jump searches, for messages.
fn direction(kind: GotoKind) -> &'static str {
    match kind {
        GotoKind::GotoF => "forward (towards the program end)",
        GotoKind::GotoB => "backward (towards the program start)",
        _ => "forward or backward",
    }
}

/// The state carried from block to block.
struct Lowering<'a> {
    program: &'a Program,
    profile: &'a Profile,
    file: Arc<str>,
    document: Document,
    diagnostics: Vec<Diagnostic>,
    /// Modal code of each G group (index = group − 1).
    modal: [Option<&'static str>; 64],
    /// The Group 8 selection (index per `$P_UIFR`).
    group8: u8,
    flow: Flow,
    /// `mcode_class_overrides` by M value.
    m_overrides: HashMap<u32, gcodec_ail::MClass>,
    /// The Group 8 indices the machine has.
    group8_supported: [bool; 100],
}

/// What one block says, collected before instructions are emitted.
#[derive(Default)]
struct BlockPlan {
    g_codes: Vec<(u8, &'static str, Span)>,
    suppressions: Vec<(Suppression, Span)>,
    feed: Option<(Value, Span)>,
    spindle: Vec<(Option<u32>, Value, Span)>,
    tools: Vec<(Op, Span)>,
    edge: Option<(Value, Span)>,
    m_functions: Vec<mfunc::MWord>,
    targets: Vec<(AxisValue, Span)>,
    circle: Circle,
    circle_span: Option<Span>,
    other: Vec<(Op, Span)>,
    /// Subprogram and cycle calls: they run after the block's motion.
    calls: Vec<(Op, Span)>,
    /// Labels and jumps that act when the block is entered, before
    /// anything else in it.
    head: Vec<(Op, Span)>,
    /// Jumps and labels that act after everything else in the block.
    tail: Vec<(Op, Span)>,
}

impl<'a> Lowering<'a> {
    fn new(program: &'a Program, profile: &'a Profile) -> Self {
        let mut modal = [None; 64];
        for (i, slot) in modal.iter_mut().enumerate() {
            *slot = ggroups::default_member(i as u8 + 1);
        }
        for (group, code) in &profile.modal_defaults {
            let lookup = ggroups::lookup(code.get_ref());
            if let (Ok(g), Some((found, index))) = (group.get_ref().parse::<u8>(), lookup) {
                if g == found {
                    modal[usize::from(g) - 1] = ggroups::member(g, index);
                }
            }
        }
        let group8 =
            gcodec_profile::group8_index(profile.work_offsets.default_group8_offset.get_ref())
                .unwrap_or(0);
        Self {
            program,
            profile,
            file: Arc::from(program.file.as_str()),
            document: Document {
                // About one instruction per statement, plus labels, jumps and
                // modal changes: reserving avoids copying a large vector.
                instructions: Vec::with_capacity(
                    program
                        .blocks
                        .iter()
                        .map(|b| b.statements.len())
                        .sum::<usize>()
                        * 5
                        / 4
                        + 16,
                ),
                ..Document::new()
            },
            diagnostics: Vec::new(),
            modal,
            group8,
            flow: Flow::new(program),
            m_overrides: mfunc::overrides(profile),
            group8_supported: profile.work_offsets.supported_group8(),
        }
    }

    /// Labels defined twice: allowed (jumps find the nearest in their
    /// direction), but rarely meant.
    fn report_duplicate_labels(&mut self) {
        let mut duplicates: Vec<(String, Vec<usize>)> = self
            .flow
            .duplicate_labels()
            .map(|(name, blocks)| (name.clone(), blocks.clone()))
            .collect();
        duplicates.sort_by_key(|(_, blocks)| blocks[0]);
        for (name, blocks) in duplicates {
            let span = |b: usize| {
                self.program.blocks[b]
                    .label
                    .as_ref()
                    .map_or(self.program.blocks[b].span, |l| l.span)
            };
            let mut diagnostic = Diagnostic::warning(
                DUPLICATE_LABEL,
                format!("label `{name}` is defined {} times", blocks.len()),
            )
            .with_label(span(blocks[0]), "first")
            .with_help("a jump goes to the nearest one in its search direction");
            for &b in &blocks[1..] {
                diagnostic = diagnostic.with_label(span(b), "again");
            }
            self.diagnostics.push(diagnostic);
        }
    }

    fn source_at(&self, block: usize, span: Span) -> Source {
        let start = self.program.blocks.get(block).map_or(0, |b| b.span.start);
        Source {
            file: self.file.clone(),
            line: block as u32 + 1,
            col: span.start.saturating_sub(start) + 1,
            span: ByteRange {
                start: span.start,
                end: span.end,
            },
        }
    }

    fn emit(&mut self, block: usize, span: Span, op: Op) {
        let source = self.source_at(block, span);
        self.document.instructions.push(Instruction { op, source });
    }

    fn block(&mut self, index: usize, block: &Block) {
        let max = *self.profile.program.max_block_length.get_ref();
        if block.span.len() > max {
            self.diagnostics.push(
                Diagnostic::error(
                    BLOCK_TOO_LONG,
                    format!(
                        "the block is {} characters long; the control accepts {max}",
                        block.span.len()
                    ),
                )
                .with_label(block.span, "this block")
                .with_help("split the block; the limit is `max_block_length` in the profile"),
            );
        }
        let mut plan = BlockPlan::default();
        self.structure_parts(index, block, &mut plan);
        for statement in &block.statements {
            self.statement(index, statement, &mut plan);
        }
        self.emit_block(index, block, plan);
    }

    /// The labels and jumps a block carries as a jump target and as a
    /// part of structures; the conditions are added by [`Self::statement`].
    fn structure_parts(&mut self, index: usize, block: &Block, plan: &mut BlockPlan) {
        let at = block.span;
        for name in self.flow.targets(index) {
            plan.head.push((Op::Label { name: name.clone() }, at));
        }
        for &(structure, role) in self.flow.roles(index) {
            let s = &self.program.structures[structure];
            let line = s.open as usize + 1;
            let label = |part: &str| flow::structure_label(s.kind, line, part);
            let jump = |target: String| Op::Jump {
                target,
                condition: None,
            };
            match (s.kind, role) {
                (
                    StructureKind::While | StructureKind::Loop | StructureKind::Repeat,
                    Role::Open,
                ) => {
                    plan.head.push((
                        Op::Label {
                            name: label("start"),
                        },
                        at,
                    ));
                }
                (StructureKind::If, Role::Middle) => {
                    plan.head.push((jump(label("end")), at));
                    plan.head.push((
                        Op::Label {
                            name: label("else"),
                        },
                        at,
                    ));
                }
                (StructureKind::If, Role::Close) => {
                    plan.head.push((Op::Label { name: label("end") }, at));
                }
                (StructureKind::While | StructureKind::Loop, Role::Close) => {
                    plan.tail.push((jump(label("start")), at));
                    plan.tail.push((Op::Label { name: label("end") }, at));
                }
                // The FOR counter and the UNTIL condition come with their
                // statements.
                _ => {}
            }
        }
    }

    /// The structure of `kind` that block `index` plays `role` in.
    fn structure_at(
        &self,
        index: usize,
        kind: StructureKind,
        role: Role,
    ) -> Option<&'a ast::ControlStructure> {
        let program = self.program;
        self.flow
            .roles(index)
            .iter()
            .find(|(s, r)| *r == role && program.structures[*s].kind == kind)
            .map(|(s, _)| &program.structures[*s])
    }

    /// `IF`, `WHILE`, `UNTIL`, `FOR`, `ENDFOR` and jumps.
    fn flow_statement(&mut self, index: usize, statement: &ast::Statement, plan: &mut BlockPlan) {
        let span = statement.span;
        let not = |cond: &ast::Expr| {
            Some(Box::new(gcodec_ail::Expr::Unary {
                operator: gcodec_ail::UnaryOp::Not,
                operand: Box::new(values::tree(cond)),
            }))
        };
        match &statement.kind {
            StatementKind::If(c) => {
                self.check_variables(&c.condition);
                if let Some(s) = self.structure_at(index, StructureKind::If, Role::Open) {
                    let line = s.open as usize + 1;
                    let part = if s.middle.is_some() { "else" } else { "end" };
                    plan.tail.push((
                        Op::Jump {
                            target: flow::structure_label(StructureKind::If, line, part),
                            condition: not(&c.condition),
                        },
                        span,
                    ));
                }
            }
            StatementKind::While(c) => {
                self.check_variables(&c.condition);
                if let Some(s) = self.structure_at(index, StructureKind::While, Role::Open) {
                    let line = s.open as usize + 1;
                    plan.head.push((
                        Op::Jump {
                            target: flow::structure_label(StructureKind::While, line, "end"),
                            condition: not(&c.condition),
                        },
                        span,
                    ));
                }
            }
            StatementKind::Until(c) => {
                self.check_variables(&c.condition);
                if let Some(s) = self.structure_at(index, StructureKind::Repeat, Role::Close) {
                    let line = s.open as usize + 1;
                    plan.tail.push((
                        Op::Jump {
                            target: flow::structure_label(StructureKind::Repeat, line, "start"),
                            condition: not(&c.condition),
                        },
                        span,
                    ));
                }
            }
            StatementKind::For(f) => {
                self.check_variable(&f.var);
                self.check_variables(&f.start);
                self.check_variables(&f.end);
                let Some(s) = self.structure_at(index, StructureKind::For, Role::Open) else {
                    return;
                };
                let line = s.open as usize + 1;
                let var = values::variable(&f.var);
                // The counter is set, then checked before every pass
                // (reference §8.2: the loop ends once it exceeds the end).
                plan.head.push((
                    Op::Assign {
                        target: Box::new(var.clone()),
                        value: values::value(&f.start),
                    },
                    span,
                ));
                plan.head.push((
                    Op::Label {
                        name: flow::structure_label(StructureKind::For, line, "start"),
                    },
                    span,
                ));
                plan.head.push((
                    Op::Jump {
                        target: flow::structure_label(StructureKind::For, line, "end"),
                        condition: Some(Box::new(gcodec_ail::Expr::Binary {
                            operator: gcodec_ail::BinaryOp::Gt,
                            lhs: Box::new(var),
                            rhs: Box::new(values::tree(&f.end)),
                        })),
                    },
                    span,
                ));
            }
            StatementKind::EndFor => {
                let Some(s) = self.structure_at(index, StructureKind::For, Role::Close) else {
                    return;
                };
                let line = s.open as usize + 1;
                let open = &self.program.blocks[s.open as usize];
                let var = open.statements.iter().find_map(|st| match &st.kind {
                    StatementKind::For(f) => Some(values::variable(&f.var)),
                    _ => None,
                });
                if let Some(var) = var {
                    plan.tail.push((
                        Op::Assign {
                            target: Box::new(var.clone()),
                            value: gcodec_ail::Value::Expr(Box::new(gcodec_ail::Expr::Binary {
                                operator: gcodec_ail::BinaryOp::Add,
                                lhs: Box::new(var),
                                rhs: Box::new(gcodec_ail::Expr::Number { value: 1.0 }),
                            })),
                        },
                        span,
                    ));
                }
                plan.tail.push((
                    Op::Jump {
                        target: flow::structure_label(StructureKind::For, line, "start"),
                        condition: None,
                    },
                    span,
                ));
                plan.tail.push((
                    Op::Label {
                        name: flow::structure_label(StructureKind::For, line, "end"),
                    },
                    span,
                ));
            }
            StatementKind::Goto(jump) => self.jump(index, jump, None, span, plan),
            StatementKind::IfGoto(g) => {
                self.check_variables(&g.condition);
                let condition = Some(Box::new(values::tree(&g.condition)));
                self.jump(index, &g.jump, condition, span, plan);
            }
            _ => {}
        }
    }

    fn jump(
        &mut self,
        index: usize,
        jump: &ast::Jump,
        condition: Option<Box<gcodec_ail::Expr>>,
        span: Span,
        plan: &mut BlockPlan,
    ) {
        let Some(target) = &jump.target else {
            return self.not_lowered(span, "`GOTOS`");
        };
        match self.flow.resolve(index, jump.goto, target) {
            Resolved::Label(target) => plan.tail.push((Op::Jump { target, condition }, span)),
            Resolved::Computed => self.not_lowered(span, "a jump to a computed target"),
            Resolved::Missing(name) if jump.goto == GotoKind::GotoC => {
                // GOTOC goes on with the next block: nothing to do.
                let _ = name;
            }
            Resolved::Missing(name) => {
                self.diagnostics.push(
                    Diagnostic::warning(
                        MISSING_JUMP_TARGET,
                        format!("`{name}` is not found {}", direction(jump.goto)),
                    )
                    .with_label(span, "this jump")
                    .with_help("the control stops with alarm 14080 when this jump runs; GOTOC would go on instead"),
                );
                plan.tail.push((
                    Op::Jump {
                        target: format!("{name}@missing"),
                        condition,
                    },
                    span,
                ));
            }
        }
    }

    fn statement(&mut self, index: usize, statement: &ast::Statement, plan: &mut BlockPlan) {
        let span = statement.span;
        match &statement.kind {
            StatementKind::If(_)
            | StatementKind::While(_)
            | StatementKind::Until(_)
            | StatementKind::For(_)
            | StatementKind::EndFor
            | StatementKind::Goto(_)
            | StatementKind::IfGoto(_) => self.flow_statement(index, statement, plan),
            // Their labels and jumps come from the structure pairing.
            StatementKind::Else
            | StatementKind::EndIf
            | StatementKind::EndWhile
            | StatementKind::Loop
            | StatementKind::EndLoop
            | StatementKind::Repeat => {}
            StatementKind::Def(def) => self.declare(def, span, plan),
            // `TRANS X10 Y5`, `AROT RPL=45`, `MIRROR X0`; the bare keyword
            // resets. The executor composes the frame chain.
            StatementKind::Frame(frame) => {
                let values = frame
                    .words
                    .iter()
                    .map(|w| {
                        let value = w.word.value(w.span);
                        if let ast::WordValue::Assigned { expr, .. } = &*value {
                            self.check_variables(expr);
                        }
                        let (value, mode) = values::word_value(&value);
                        AxisValue {
                            axis: axis_name(w.word.address()),
                            value,
                            mode,
                        }
                    })
                    .collect();
                plan.other.push((
                    Op::Frame {
                        op: frame.op.keyword().to_owned(),
                        values,
                    },
                    span,
                ));
            }
            StatementKind::Ret(ret) => {
                let values = ret
                    .args
                    .iter()
                    .flatten()
                    .map(|a| a.as_ref().map_or(Value::Const(0.0), values::value))
                    .collect();
                plan.tail.push((Op::Return { values }, span));
            }
            StatementKind::Word(word) => self.word(word, span, plan),
            StatementKind::Assign(assign) => match &assign.value {
                ast::Initializer::Expr(e) => {
                    self.check_variable(&assign.target);
                    self.check_variables(e);
                    plan.other.push((
                        Op::Assign {
                            target: Box::new(values::variable(&assign.target)),
                            value: values::value(e),
                        },
                        span,
                    ));
                }
                _ => self.not_lowered(span, "an assignment of a list of values"),
            },
            StatementKind::Call(call) => self.call(call, span, plan),
            kind => self.not_lowered(span, statement_name(kind)),
        }
    }

    /// `DEF TYPE name[dims]=init, …`: one declaration per variable.
    fn declare(&mut self, def: &ast::Def, span: Span, plan: &mut BlockPlan) {
        let data_type = match &def.ty.kind {
            ast::TypeKind::Int => "INT",
            ast::TypeKind::Real => "REAL",
            ast::TypeKind::Bool => "BOOL",
            ast::TypeKind::Char => "CHAR",
            ast::TypeKind::String { .. } => "STRING",
            ast::TypeKind::Axis => "AXIS",
            ast::TypeKind::Frame => "FRAME",
        };
        for var in &def.vars {
            let init = match &var.init {
                None => Vec::new(),
                Some(ast::Initializer::Expr(e)) => vec![Some(values::value(e))],
                Some(ast::Initializer::List { items, .. }) => items
                    .iter()
                    .map(|i| i.as_ref().map(values::value))
                    .collect(),
                Some(ast::Initializer::Rep { .. }) => {
                    self.not_lowered(var.span, "a `REP` initialiser");
                    continue;
                }
            };
            plan.other.push((
                Op::Declare(Box::new(gcodec_ail::Declare {
                    name: var.name.to_ascii_uppercase().to_string(),
                    data_type: data_type.to_owned(),
                    dims: var.dims.iter().map(values::value).collect(),
                    init,
                })),
                span,
            ));
        }
    }

    fn call(&mut self, call: &ast::Call, span: Span, plan: &mut BlockPlan) {
        let name = match &call.target {
            CallTarget::Name { name, .. } => name.clone(),
            // `L123`: the program `L123`, digits as written.
            CallTarget::Number { digits, .. } => format!("L{digits}").into(),
        };
        let upper = name.to_ascii_uppercase();
        let upper = upper.as_str();
        if call.args.is_none() {
            // `DIAMON`, `SUPA`, `CFC`: G commands written as names.
            if let Some((group, index)) = ggroups::lookup(upper) {
                return self.g_code(group, index, span, plan);
            }
            if upper == "STOPRE" {
                return plan.other.push((
                    Op::Stop {
                        reason: upper.to_string(),
                    },
                    span,
                ));
            }
        }
        if upper == "MSG" {
            if let Some(args) = &call.args {
                let text = match args.as_slice() {
                    [] => Some(Value::Expr(Box::new(gcodec_ail::Expr::String {
                        value: String::new(),
                    }))),
                    [Some(text)] | [Some(text), _] => {
                        self.check_variables(text);
                        Some(Value::Expr(Box::new(values::tree(text))))
                    }
                    _ => None,
                };
                if let Some(text) = text {
                    return plan.other.push((Op::Message { text }, span));
                }
            }
        }
        // A subprogram, cycle or predefined procedure: the executor finds
        // it on the search path or knows it.
        let args = call.args.as_deref().unwrap_or_default();
        for arg in args.iter().flatten() {
            self.check_variables(arg);
        }
        let passes = call
            .passes
            .as_ref()
            .map(|p| values::word_value(&p.word.value(p.span)).0);
        plan.calls.push((
            Op::Call(Box::new(gcodec_ail::Call {
                target: upper.to_string(),
                args: args.iter().map(|a| a.as_ref().map(values::value)).collect(),
                passes,
                modal: false,
            })),
            span,
        ));
    }

    /// Reports the unknown system variables of an expression. Recursion
    /// follows the parser's bounded expression depth.
    fn check_variables(&mut self, expr: &ast::Expr) {
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

    fn check_variable(&mut self, var: &ast::VarRef) {
        if var.kind == ast::VarKind::System && sysvars::lookup(&var.name).is_none() {
            self.diagnostics.push(
                Diagnostic::error(
                    UNKNOWN_SYSTEM_VARIABLE,
                    format!("`{}` is not a system variable of the control", var.name),
                )
                .with_label(var.span, "unknown")
                .with_help("check the spelling against the SINUMERIK lists of system variables and machine data"),
            );
        }
        for index in &var.indices {
            self.check_variables(index);
        }
    }

    fn word(&mut self, word: &Word, span: Span, plan: &mut BlockPlan) {
        let address = word.address();
        let value = word.value(span);
        if let ast::WordValue::Assigned { expr, .. } = &*value {
            self.check_variables(expr);
        }
        match address {
            "G" => match (word.extension(), values::whole_number(&value)) {
                (None, Some(n)) if n >= 0.0 => {
                    let mut buf = [0; 24];
                    let code = g_code_text(n, &mut buf);
                    match ggroups::lookup(code) {
                        Some((group, index)) => self.g_code(group, index, span, plan),
                        None => self.diagnostics.push(
                            Diagnostic::error(
                                UNKNOWN_G,
                                format!("`{code}` is not a G command of the control"),
                            )
                            .with_label(span, "unknown G command"),
                        ),
                    }
                }
                _ => self.not_lowered(span, "a G command with an extension or a computed value"),
            },
            "M" => {
                if let Some(m) = mfunc::check(
                    word,
                    &value,
                    span,
                    self.profile,
                    &self.m_overrides,
                    &mut self.diagnostics,
                ) {
                    plan.m_functions.push(m);
                }
            }
            "T" => {
                if let Some(op) =
                    tools::select(word, &value, span, self.profile, &mut self.diagnostics)
                {
                    plan.tools.push((op, span));
                }
            }
            "D" => match (word.extension(), values::whole_number(&value), &*value) {
                (None, Some(d), _) if (0.0..=32_000.0).contains(&d) => {
                    plan.edge = Some((Value::Const(d), span))
                }
                (None, Some(_), _) => self.diagnostics.push(
                    Diagnostic::error(INVALID_VALUE, "cutting edges are D0…D32000")
                        .with_label(span, "out of range"),
                ),
                // `D=EDGES[I]`: computed when the block runs.
                (
                    None,
                    None,
                    ast::WordValue::Assigned {
                        modifier: None,
                        expr,
                    },
                ) if values::constant(expr).is_none() => {
                    plan.edge = Some((values::value(expr), span))
                }
                (None, None, _) => self.diagnostics.push(
                    Diagnostic::error(INVALID_VALUE, "a cutting edge is a whole number")
                        .with_label(span, "not a whole number"),
                ),
                _ => self.not_lowered(span, "an extended D number"),
            },
            "F" if word.extension().is_none() => {
                plan.feed = Some((values::word_value(&value).0, span));
            }
            "S" => {
                let spindle = match word.extension() {
                    None => None,
                    Some(Extension::Number { value, span }) => {
                        if !tools::spindle_exists(self.profile, *value) {
                            self.diagnostics.push(tools::unknown_spindle(*value, *span));
                            return;
                        }
                        Some(*value)
                    }
                    Some(Extension::Index { .. }) => {
                        return self
                            .not_lowered(span, "a spindle speed with a computed spindle number");
                    }
                };
                plan.spindle
                    .push((spindle, values::word_value(&value).0, span));
            }
            "I" | "J" | "K" => {
                let (v, mode) = values::word_value(&value);
                let target = AxisValue {
                    axis: axis_name(address),
                    value: v,
                    mode,
                };
                match word.extension() {
                    None => plan.circle.centre.push(target),
                    Some(Extension::Number { value: 1, .. }) => {
                        plan.circle.intermediate.push(target)
                    }
                    Some(_) => return self.not_lowered(span, "this circle parameter"),
                }
                plan.circle_span.get_or_insert(span);
            }
            "CR" | "AR" | "TURN" => {
                let v = values::word_value(&value).0;
                match address {
                    "CR" => plan.circle.radius = Some(v),
                    "AR" => plan.circle.opening_angle = Some(v),
                    _ => plan.circle.turns = Some(v),
                }
                plan.circle_span.get_or_insert(span);
            }
            _ if self.is_axis(address) && word.extension().is_none() => {
                let (v, mode) = values::word_value(&value);
                plan.targets.push((
                    AxisValue {
                        axis: axis_name(address),
                        value: v,
                        mode,
                    },
                    span,
                ));
            }
            // An axis letter the machine does not have: the control
            // rejects the block.
            "A" | "B" | "C" | "U" | "V" | "W" | "X" | "Y" | "Z" => self.diagnostics.push(
                Diagnostic::error(
                    UNKNOWN_ADDRESS,
                    format!("`{address}` is not an axis or address of this machine"),
                )
                .with_label(word.address_span(span), "unknown here")
                .with_help("the profile's `[[axes]]` lists the machine's axes"),
            ),
            _ => self.not_lowered(span, &format!("the address `{address}`")),
        }
    }

    fn is_axis(&self, name: &str) -> bool {
        self.profile
            .axes
            .iter()
            .any(|a| a.name.get_ref().eq_ignore_ascii_case(name))
    }

    /// A G command at its registry position (`group`, 1-based `index`).
    fn g_code(&mut self, group: u8, index: u8, span: Span, plan: &mut BlockPlan) {
        let Some(member) = ggroups::member(group, index) else {
            return;
        };
        if group == 9 {
            let suppression = match member {
                "G53" => Suppression::G53,
                "G153" => Suppression::G153,
                "SUPA" => Suppression::Supa,
                _ => return self.not_lowered(span, "`SUPD`"),
            };
            return plan.suppressions.push((suppression, span));
        }
        if group == 8 {
            let supported = self
                .group8_supported
                .get(usize::from(index) - 1)
                .is_some_and(|s| *s);
            if !supported {
                return self.diagnostics.push(
                    Diagnostic::error(
                        UNSUPPORTED_OFFSET,
                        format!("`{member}` is not a settable offset of this machine"),
                    )
                    .with_label(span, "not among `supported_group8_offsets`")
                    .with_help("the Group 8 selection stays as it was; the profile lists the offsets the machine has"),
                );
            }
        }
        if let Some((_, first, first_span)) = plan.g_codes.iter().find(|(g, _, _)| *g == group) {
            return self.diagnostics.push(
                Diagnostic::error(
                    G_GROUP_CONFLICT,
                    format!("`{member}` and `{first}` are both in G group {group}; a block holds one command of a group"),
                )
                .with_label(span, "second command of the group")
                .with_label(*first_span, "first"),
            );
        }
        plan.g_codes.push((group, member, span));
    }

    fn not_lowered(&mut self, span: Span, what: &str) {
        self.diagnostics.push(not_lowered(span, what));
    }

    fn emit_block(&mut self, index: usize, block: &Block, mut plan: BlockPlan) {
        for (op, span) in std::mem::take(&mut plan.head) {
            self.emit(index, span, op);
        }
        let tail = std::mem::take(&mut plan.tail);
        // Work offset: the Group 8 selection and the block's suppression.
        let group8 = plan.g_codes.iter().find(|(g, _, _)| *g == 8);
        let suppression = self.suppression(&plan.suppressions);
        if let Some((_, code, _)) = group8 {
            self.group8 = gcodec_profile::group8_index(code).unwrap_or(self.group8);
        }
        if group8.is_some() || suppression.is_some() {
            let span = group8
                .map(|(_, _, s)| *s)
                .or(plan.suppressions.first().map(|(_, s)| *s))
                .unwrap_or(block.span);
            let selected = gcodec_profile::group8_code(self.group8)
                .unwrap_or_default()
                .to_ascii_lowercase();
            self.emit(
                index,
                span,
                Op::WorkOffset {
                    group8_selected: selected,
                    suppression,
                    suppression_scope: suppression.map(|_| SuppressionScope::Block),
                },
            );
        }
        for &(group, code, span) in &plan.g_codes {
            if group == 8 {
                continue;
            }
            let modal = ggroups::group(group).is_some_and(|g| g.effect == ggroups::Effect::Modal);
            if modal {
                self.modal[usize::from(group) - 1] = Some(code);
            }
            self.emit(
                index,
                span,
                Op::ModalChange {
                    group,
                    code: Cow::Borrowed(code),
                },
            );
        }
        if let Some((value, span)) = plan.feed {
            self.emit(index, span, Op::Feed { value });
        }
        for (spindle, speed, span) in plan.spindle {
            self.emit(index, span, Op::SpindleSpeed { spindle, speed });
        }
        for (op, span) in plan.tools {
            let direct = matches!(
                op,
                Op::ToolSelect(ref t) if t.timing == gcodec_ail::ToolTiming::Immediate
            );
            self.emit(index, span, op);
            if direct {
                self.emit(
                    index,
                    span,
                    Op::ToolChange {
                        trigger: ToolChangeTrigger::TWord,
                    },
                );
            }
        }
        if let Some((edge, span)) = plan.edge {
            self.emit(index, span, Op::CuttingEdge { edge });
        }
        let has_motion = !plan.targets.is_empty();
        mfunc::check_count(&plan.m_functions, self.profile, &mut self.diagnostics);
        let deferred =
            self.profile.tool_change.tool_change_mode == gcodec_profile::ToolChangeMode::DeferredM6;
        let (after, before): (Vec<_>, Vec<_>) = plan
            .m_functions
            .into_iter()
            .partition(|m| has_motion && m.value.is_some_and(mfunc::acts_after_motion));
        for m in before {
            self.emit_m(index, m, MTiming::InBlock, deferred);
        }
        for (op, span) in plan.other {
            self.emit(index, span, op);
        }
        if has_motion || plan.circle_span.is_some() {
            let first = plan
                .targets
                .first()
                .map(|(_, s)| *s)
                .or(plan.circle_span)
                .unwrap_or(block.span);
            let motion = match self.modal[0] {
                Some("G0") => MotionKind::Rapid,
                Some("G2") => MotionKind::ArcCw,
                Some("G3") => MotionKind::ArcCcw,
                Some("CIP") => MotionKind::ArcThroughPoint,
                Some("CT") => MotionKind::ArcTangential,
                Some("G1") => MotionKind::Linear,
                other => {
                    self.not_lowered(first, &format!("motion under `{}`", other.unwrap_or("?")));
                    MotionKind::Linear
                }
            };
            let arc = matches!(
                motion,
                MotionKind::ArcCw
                    | MotionKind::ArcCcw
                    | MotionKind::ArcThroughPoint
                    | MotionKind::ArcTangential
            );
            let circle = arc.then(|| Box::new(plan.circle));
            self.emit(
                index,
                first,
                Op::Motion {
                    motion,
                    targets: plan.targets.into_iter().map(|(t, _)| t).collect(),
                    circle,
                },
            );
        }
        for m in after {
            self.emit_m(index, m, MTiming::PostMotion, deferred);
        }
        for (op, span) in std::mem::take(&mut plan.calls) {
            self.emit(index, span, op);
        }
        for (op, span) in tail {
            self.emit(index, span, op);
        }
    }

    /// An M function, and the tool change when it is the change M code in
    /// `deferred_m6` mode.
    fn emit_m(&mut self, index: usize, m: mfunc::MWord, timing: MTiming, deferred: bool) {
        let is_change = deferred
            && m.value == Some(*self.profile.tool_change.change_m_code.get_ref())
            && m.extension.is_none();
        let span = m.span;
        self.emit(index, span, m.into_op(timing));
        if is_change {
            self.emit(
                index,
                span,
                Op::ToolChange {
                    trigger: ToolChangeTrigger::M6,
                },
            );
        }
    }

    /// The strongest suppression of a block, per the profile's policy for
    /// several in one block (seed 003).
    fn suppression(&mut self, found: &[(Suppression, Span)]) -> Option<Suppression> {
        let (first, first_span) = *found.first()?;
        if found.len() == 1 {
            return Some(first);
        }
        let strongest = found.iter().map(|(s, _)| *s).max().unwrap_or(first);
        let policy = self.profile.work_offsets.duplicate_suppression_policy;
        let message = "several of G53, G153 and SUPA in one block";
        let diagnostic = match policy {
            DuplicateSuppressionPolicy::FirstWins => return Some(first),
            DuplicateSuppressionPolicy::Warn => Diagnostic::warning(DUPLICATE_SUPPRESSION, message)
                .with_help("the strongest one acts (SUPA > G153 > G53); write only that one"),
            DuplicateSuppressionPolicy::Error => Diagnostic::error(DUPLICATE_SUPPRESSION, message)
                .with_help("the profile forbids this (`duplicate_suppression_policy = \"error\"`); write only one"),
        };
        let mut diagnostic = diagnostic.with_label(first_span, "first");
        for (_, span) in &found[1..] {
            diagnostic = diagnostic.with_label(*span, "again");
        }
        self.diagnostics.push(diagnostic);
        Some(strongest)
    }
}

/// How a statement kind [`Lowering::statement`] does not lower is named
/// in its warning.
fn statement_name(kind: &StatementKind) -> &'static str {
    use StatementKind as S;
    match kind {
        S::Redef(_) => "`REDEF`",
        S::Define(_) => "`DEFINE`",
        S::Proc(_) => "`PROC`",
        S::EndProc => "`ENDPROC`",
        S::Extern(_) => "`EXTERN`",
        S::IndirectCall(_) => "`CALL`",
        S::PCall(_) => "`PCALL`",
        S::MCall(_) => "`MCALL`",
        S::RepeatSection(_) => "`REPEAT` of a section",
        S::Case(_) => "`CASE`",
        S::SyncAction(_) => "a synchronous action",
        _ => "this statement",
    }
}
