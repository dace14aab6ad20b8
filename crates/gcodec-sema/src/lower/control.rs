//! Control structures and jumps: the labels, conditional jumps and loop
//! counters that `IF`, `WHILE`, `FOR`, `LOOP`, `REPEAT … UNTIL` and the
//! `GOTO` family lower to.

use gcodec_ail::{Op, Value};
use gcodec_parser::ast::{self, Block, GotoKind, StatementKind, StructureKind};
use gcodec_source::{Diagnostic, Span, codes};

use crate::flow::{self, BlockFlow, Resolved, Role, Search};
use crate::values;

use super::{BlockPlan, Lowering, direction};
impl<'a> Lowering<'a> {
    /// The labels and jumps a block carries as a jump target and as a
    /// part of structures; the conditions are added by [`Self::statement`].
    pub(super) fn structure_parts(
        &mut self,
        facts: &BlockFlow,
        block: &Block,
        plan: &mut BlockPlan,
    ) {
        let at = block.span;
        for name in &facts.targets {
            plan.head.push((Op::Label { name: name.clone() }, at));
        }
        for &(structure, role) in &facts.roles {
            let s = &self.outline.structures[structure];
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

    /// A block with a control-structure element carries no label and no
    /// skip mark (language reference §8.2, §1.7: the control does not allow
    /// them there).
    pub(super) fn check_structure_block(&mut self, facts: &BlockFlow, block: &Block) {
        if facts.roles.is_empty() {
            return;
        }
        let element = block.statements.first().map_or(block.span, |s| s.span);
        if let Some(label) = &block.label {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::LABEL_IN_STRUCTURE_BLOCK,
                    "a block with a control-structure element carries no label",
                )
                .with_label(label.span, "label")
                .with_label(element, "control-structure element")
                .with_help("put the label in a block of its own before this one"),
            );
        }
        if let Some(skip) = &block.skip {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::SKIPPED_STRUCTURE_BLOCK,
                    "a block with a control-structure element cannot be skipped",
                )
                .with_label(skip.span, "skip mark")
                .with_label(element, "control-structure element")
                .with_help("skip the blocks inside the structure instead, or jump around it"),
            );
        }
    }

    /// The structure of `kind` that block `index` plays `role` in.
    pub(super) fn structure_at(
        &self,
        index: usize,
        kind: StructureKind,
        role: Role,
    ) -> Option<&'a ast::ControlStructure> {
        let structures = &self.outline.structures;
        self.outline
            .flow
            .roles(index)
            .iter()
            .find(|(s, r)| *r == role && structures[*s].kind == kind)
            .map(|(s, _)| &structures[*s])
    }

    /// `IF`, `WHILE`, `UNTIL`, `FOR`, `ENDFOR` and jumps.
    pub(super) fn flow_statement(
        &mut self,
        index: usize,
        statement: &ast::Statement,
        plan: &mut BlockPlan,
    ) {
        let span = statement.span;
        let not = |cond: &ast::Expr| {
            Some(Box::new(gcodec_ail::Expr::Unary {
                operator: gcodec_lang::UnaryOp::Not,
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
                            operator: gcodec_lang::BinaryOp::Gt,
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
                if let Some(var) = self.outline.for_variables.get(&s.open).cloned() {
                    plan.tail.push((
                        Op::Assign {
                            target: Box::new(var.clone()),
                            value: gcodec_ail::Value::Expr(Box::new(gcodec_ail::Expr::Binary {
                                operator: gcodec_lang::BinaryOp::Add,
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
            StatementKind::Case(case) => self.case(index, case, span, plan),
            StatementKind::RepeatSection(repeat) => self.repeat_section(index, repeat, span, plan),
            _ => {}
        }
    }

    /// `CASE e OF 1 GOTOF A 2 GOTOF B DEFAULT GOTOF C`: one conditional
    /// jump per arm, in order, then the default. Without a default and
    /// without a match the program goes on with the next block.
    pub(super) fn case(
        &mut self,
        index: usize,
        case: &ast::Case,
        span: Span,
        plan: &mut BlockPlan,
    ) {
        self.check_variables(&case.selector);
        let selector = values::tree(&case.selector);
        for arm in &case.arms {
            if values::constant(&arm.value).is_none() {
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::CASE_VALUE_NOT_CONSTANT,
                        "a `CASE` arm compares with a constant",
                    )
                    .with_label(arm.value.span, "not a constant")
                    .with_help("write a number (decimal, 'H…' or 'B…') before the arm's GOTO"),
                );
                continue;
            }
            let condition = gcodec_ail::Expr::Binary {
                operator: gcodec_lang::BinaryOp::Eq,
                lhs: Box::new(selector.clone()),
                rhs: Box::new(values::tree(&arm.value)),
            };
            self.jump(index, &arm.jump, Some(Box::new(condition)), span, plan);
        }
        if let Some(default) = &case.default {
            self.jump(index, default, None, span, plan);
        }
    }

    /// `REPEAT L P=n`, `REPEAT A B P=n`, `REPEATB L P=n`: the section as
    /// [`crate::flow`] found it, run `n` times from here.
    pub(super) fn repeat_section(
        &mut self,
        index: usize,
        repeat: &ast::RepeatSection,
        span: Span,
        plan: &mut BlockPlan,
    ) {
        let passes = match &repeat.passes {
            None => Value::Const(1.0),
            Some(p) => {
                let value = p.word.value(p.span);
                if let ast::WordValue::Assigned { expr, .. } = &*value {
                    self.check_variables(expr);
                }
                let (passes, _) = values::word_value(&value);
                if let Value::Const(n) = passes
                    && (n < 1.0 || n.fract() != 0.0)
                {
                    self.diagnostics.push(
                        Diagnostic::new(
                            codes::lower::INVALID_VALUE,
                            "`P` of a `REPEAT` is a whole number of passes, at least 1",
                        )
                        .with_label(p.span, "not a whole number ≥ 1"),
                    );
                }
                passes
            }
        };
        let keyword = if repeat.single_block {
            "REPEATB"
        } else {
            "REPEAT"
        };
        match self.outline.flow.repeat_section(index) {
            Some(Ok(section)) => plan.tail.push((
                Op::RepeatSection(Box::new(gcodec_ail::RepeatSection {
                    start: section.start.clone(),
                    end: section.end.clone(),
                    passes,
                })),
                span,
            )),
            Some(Err(name)) => {
                let name = name.clone();
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::MISSING_JUMP_TARGET,
                        format!("`{name}`, where the section of this `{keyword}` starts or ends, is not found"),
                    )
                    .with_label(span, "this repetition")
                    .with_help("the control stops with alarm 14080 when this block runs; the start label is searched towards the program start first"),
                );
                plan.tail.push((
                    Op::Jump {
                        target: format!("{name}@missing"),
                        condition: None,
                    },
                    span,
                ));
            }
            None => self.not_lowered(span, "this `REPEAT`"),
        }
    }

    pub(super) fn jump(
        &mut self,
        index: usize,
        jump: &ast::Jump,
        condition: Option<Box<gcodec_ail::Expr>>,
        span: Span,
        plan: &mut BlockPlan,
    ) {
        let Some(target) = &jump.target else {
            // `GOTOS`; a condition (`IF … GOTOS`) guards it.
            return plan.tail.push((Op::GotoStart { condition }, span));
        };
        let search = Search::of(jump.goto);
        match self.outline.flow.resolve(index, search, target) {
            Resolved::Label(target) => plan.tail.push((Op::Jump { target, condition }, span)),
            Resolved::Computed => {
                let ast::JumpTarget::Expr(expr) = target else {
                    return;
                };
                self.check_variables(expr);
                plan.tail.push((
                    Op::ComputedJump(Box::new(gcodec_ail::ComputedJump {
                        target: values::tree(expr),
                        search: search.ail(),
                        continue_if_missing: jump.goto == GotoKind::GotoC,
                        condition: condition.map(|c| *c),
                    })),
                    span,
                ));
            }
            Resolved::Missing(_)
                if let ast::JumpTarget::Label { name, span: at } = target
                    && self.outline.names.is_string_variable(name, at.start) =>
            {
                // `GOTOF ZIEL` with `DEF STRING[8] ZIEL`: the string names
                // the label, found when the jump runs.
                plan.tail.push((
                    Op::ComputedJump(Box::new(gcodec_ail::ComputedJump {
                        target: gcodec_ail::Expr::Var {
                            var_kind: gcodec_ail::VarKind::User,
                            name: gcodec_ail::VarName::Text(name.to_ascii_uppercase().into()),
                            indices: Vec::new(),
                        },
                        search: search.ail(),
                        continue_if_missing: jump.goto == GotoKind::GotoC,
                        condition: condition.map(|c| *c),
                    })),
                    span,
                ));
            }
            Resolved::Missing(name) if jump.goto == GotoKind::GotoC => {
                // GOTOC goes on with the next block: nothing to do.
                let _ = name;
            }
            Resolved::Missing(name) => {
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::MISSING_JUMP_TARGET,
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
}
