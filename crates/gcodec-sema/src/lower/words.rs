//! Address words: G commands (also indirect, `G[8]=2`, and the
//! profile's legacy aliases), M functions, tools, cutting edges, feed,
//! spindle speeds, circle data, axis targets, `H` functions and the named
//! addresses of `addresses.rs`.

use std::borrow::Cow;

use gcodec_ail::{AxisValue, Suppression, Value};
use gcodec_lang::ggroups::{self, GCommand};
use gcodec_parser::ast::{self, Extension, Word};
use gcodec_source::{Diagnostic, Span, codes};

use crate::{mfunc, tools, values};

use super::axis_commands::MachineAxisWord;
use super::{BlockPlan, Lowering, axis_name};
impl Lowering<'_> {
    pub(super) fn word(&mut self, word: &Word, span: Span, plan: &mut BlockPlan) {
        let address = word.address();
        let value = word.value(span);
        if let ast::WordValue::Assigned { expr, .. } = &*value {
            self.check_variables(expr);
        }
        if !self.check_modifier(word, &value) {
            return;
        }
        match address {
            "G" => self.g_word(word, &value, span, plan),
            "H" => self.h_word(word, &value, span, plan),
            "M" => {
                if let Some(Extension::Index { index, .. }) = word.extension() {
                    self.check_variables(index);
                }
                if let Some(m) = mfunc::check(
                    word,
                    &value,
                    span,
                    self.profile,
                    &self.outline.m_overrides,
                    self.source,
                    &mut self.diagnostics,
                ) {
                    plan.m_functions.push(m);
                }
            }
            "T" => {
                if let Some(op) = tools::select(
                    word,
                    &value,
                    span,
                    self.profile,
                    self.source,
                    &mut self.diagnostics,
                ) {
                    plan.tools.push((op, span));
                }
            }
            "D" => match (word.extension(), values::whole_number(&value), &*value) {
                (None, Some(d), _) if (0.0..=32_000.0).contains(&d) => {
                    plan.edge = Some((Value::Const(d), span))
                }
                (None, Some(_), _) => self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::INVALID_VALUE,
                        format!(
                            "D{} is out of range",
                            values::written_number(self.source, &value)
                        ),
                    )
                    .with_label(span, "out of range")
                    .with_help("cutting edges are D0…D32000"),
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
                    Diagnostic::new(
                        codes::lower::INVALID_VALUE,
                        "a cutting edge is a whole number",
                    )
                    .with_label(span, "not a whole number"),
                ),
                _ => self.not_lowered(span, "an extended D number"),
            },
            "F" if word.extension().is_none() => {
                plan.feed = Some((values::word_value(&value).0, span));
            }
            "S" => {
                let (spindle, spindle_expr) = match word.extension() {
                    None => (None, None),
                    // Extension 0 is the master spindle, as for `M0=3` and
                    // `SPOS0=` (reference §4.2).
                    Some(Extension::Number { value, span }) => {
                        if *value != 0 && !tools::spindle_exists(self.profile, *value) {
                            self.diagnostics.push(tools::unknown_spindle(*value, *span));
                            return;
                        }
                        (Some(*value), None)
                    }
                    // `S[SPINU]=…`: the spindle is chosen when the block runs.
                    Some(Extension::Index { index, span }) => match values::constant(index) {
                        Some(n) if n.fract() == 0.0 && (0.0..=99.0).contains(&n) => {
                            if n != 0.0 && !tools::spindle_exists(self.profile, n as u32) {
                                self.diagnostics
                                    .push(tools::unknown_spindle(n as u32, *span));
                                return;
                            }
                            (Some(n as u32), None)
                        }
                        Some(_) => {
                            let written = values::written(self.source, *span);
                            return self
                                .diagnostics
                                .push(tools::not_a_spindle_number("S", &written, "0…99", *span));
                        }
                        None => {
                            self.check_variables(index);
                            (None, Some(Box::new(values::tree(index))))
                        }
                    },
                };
                plan.spindle
                    .push((spindle, spindle_expr, values::word_value(&value).0, span));
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
            // Named addresses have more than one letter; axis words, the
            // commonest, skip the table.
            _ if address.len() > 1 && self.named_address(word, &value, span, plan) => {}
            // `X10`, `X1=10` (axis X1), `E=0` on a machine with an axis E.
            _ if match word.extension() {
                None => self.is_axis(address),
                Some(Extension::Number { .. }) => self.is_axis(&self.axis_word_name(word)),
                Some(Extension::Index { .. }) => false,
            } =>
            {
                let (v, mode) = values::word_value(&value);
                let axis = match word.extension() {
                    None => axis_name(address),
                    Some(_) => Cow::Owned(self.axis_word_name(word).to_ascii_uppercase()),
                };
                plan.add_target(
                    AxisValue {
                        axis,
                        value: v,
                        mode,
                    },
                    span,
                );
            }
            "A" | "B" | "C" | "E" | "Q" | "U" | "V" | "W" | "X" | "Y" | "Z"
                if matches!(word.extension(), Some(Extension::Index { .. })) =>
            {
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::EXTENSION_NOT_ALLOWED,
                        format!("`{address}[…]` is not an axis"),
                    )
                    .with_label(span, "bracketed extension")
                    .with_help(
                        "an axis is named with digits (`X1=10`) or indirectly with `AX[…]=`",
                    ),
                )
            }
            // `E`: reserved on the control; the CEAD interpreter's extruder.
            "E" => self.reserved_e(span),
            // An axis letter the machine does not have: the control
            // rejects the block.
            "A" | "B" | "C" | "Q" | "U" | "V" | "W" | "X" | "Y" | "Z" => {
                let name = self.axis_word_name(word);
                if let Some(axis) = self.machine_axis_of(word) {
                    return plan.machine_axis_words.push(MachineAxisWord {
                        axis,
                        written: name,
                        span: word.address_span(span),
                    });
                }
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::UNKNOWN_ADDRESS,
                        format!("`{name}` is not an axis or address of this machine"),
                    )
                    .with_label(word.address_span(span), "unknown here")
                    .with_help(self.axes_help(&name)),
                )
            }
            _ => self.not_lowered(span, &format!("the address `{address}`")),
        }
    }

    pub(super) fn is_axis(&self, name: &str) -> bool {
        self.axis_kind(name).is_some()
    }

    /// A G command at its registry position (`group`, 1-based `index`).
    pub(super) fn g_code(&mut self, group: u8, index: u8, span: Span, plan: &mut BlockPlan) {
        let Some(command) = GCommand::new(group, index) else {
            return;
        };
        let member = command.name();
        if let Some(key) = self.g_unsupported(group, member) {
            return self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::UNSUPPORTED_G,
                    format!("this control does not have `{member}`"),
                )
                .with_label(span, "not supported")
                .with_help(format!("the profile rules it out in `[g_codes] {key}`")),
            );
        }
        if matches!(member, "DIAMON" | "DIAM90") && !self.profile.axes.iter().any(|a| a.diameter) {
            return self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::NO_TRANSVERSE_AXIS,
                    format!("`{member}` programs the transverse axis in diameter, and this machine has none"),
                )
                .with_label(span, "no transverse axis")
                .with_help("on a lathe, run with its profile (`--profile profiles/lathe_828d.toml`); a profile marks its transverse axis with `diameter = true` in `[[axes]]`"),
            );
        }
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
                    Diagnostic::new(
                        codes::lower::UNSUPPORTED_OFFSET,
                        format!("`{member}` is not a settable offset of this machine"),
                    )
                    .with_label(span, "not among `supported_group8_offsets`")
                    .with_help("the Group 8 selection stays as it was; the profile lists the offsets the machine has"),
                );
            }
        }
        if let Some((_, _, first_span)) = plan.indirect_g.iter().find(|(g, _, _)| *g == group) {
            return self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::G_GROUP_CONFLICT,
                    format!("`{member}` and `G[{group}]=…` are both in G group {group}; a block holds one command of a group"),
                )
                .with_label(span, "second command of the group")
                .with_label(*first_span, "first"),
            );
        }
        if let Some((first, first_span)) = plan.g_codes.iter().find(|(c, _)| c.group() == group) {
            return self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::G_GROUP_CONFLICT,
                    format!("`{member}` and `{}` are both in G group {group}; a block holds one command of a group", first.name()),
                )
                .with_label(span, "second command of the group")
                .with_label(*first_span, "first"),
            );
        }
        plan.g_codes.push((command, span));
    }
}

/// A whole G number `n ≥ 0` as a `u64`; from 2^64 on `None` (no command
/// and no alias has it), where the `as` cast would saturate.
fn g_number(n: f64) -> Option<u64> {
    (n < u64::MAX as f64).then_some(n as u64)
}

impl Lowering<'_> {
    /// A `G` word: `G1`, `G=1`, a legacy alias of a Group 8 code
    /// (`G58` → `G505` per `legacy_aliases`), or indirect `G[8]=2`.
    fn g_word(&mut self, word: &Word, value: &ast::WordValue, span: Span, plan: &mut BlockPlan) {
        match word.extension() {
            None => match values::whole_number(value) {
                Some(n) if n >= 0.0 => {
                    if let Some(target) = self.legacy_alias(n)
                        && let Some((group, index)) = ggroups::lookup(&target)
                    {
                        return self.g_code(group, index, span, plan);
                    }
                    match g_number(n).and_then(ggroups::lookup_g) {
                        Some((group, index)) => self.g_code(group, index, span, plan),
                        None => self.diagnostics.push(
                            Diagnostic::new(
                                codes::lower::UNKNOWN_G,
                                format!(
                                    "`G{}` is not a G command of the control",
                                    values::written_number(self.source, value)
                                ),
                            )
                            .with_label(span, "unknown G command"),
                        ),
                    }
                }
                _ => match value {
                    ast::WordValue::Assigned { expr, .. } if values::constant(expr).is_none() => {
                        self.diagnostics.push(
                            Diagnostic::new(
                                codes::lower::COMPUTED_G,
                                "a computed G command needs its group",
                            )
                            .with_label(span, "no G group")
                            .with_help(
                                "program it indirectly as `G[<group>]=<index>`, e.g. `G[8]=KORD`",
                            ),
                        )
                    }
                    _ => self.diagnostics.push(
                        Diagnostic::new(
                            codes::lower::UNKNOWN_G,
                            "a G command is a whole number ≥ 0",
                        )
                        .with_label(span, "unknown G command"),
                    ),
                },
            },
            Some(Extension::Index { index, span: at }) => {
                self.indirect_g(index, *at, value, span, plan)
            }
            Some(Extension::Number { .. }) => {
                self.not_lowered(span, "a G command with a numeric extension")
            }
        }
    }

    /// The Group 8 code a legacy alias (`legacy_aliases`, per the work-offset
    /// design) stands for, if `G<n>` is one.
    pub(super) fn legacy_alias(&self, n: f64) -> Option<String> {
        let aliases = &self.profile.work_offsets.legacy_aliases;
        if aliases.is_empty() {
            return None;
        }
        let number = g_number(n)?;
        aliases.iter().find_map(|(alias, target)| {
            let digits = alias.get_ref().get(1..)?;
            (digits.parse::<u64>().ok()? == number).then(|| target.get_ref().clone())
        })
    }

    /// `G[<group>]=<index>` (indirect G programming): the command at
    /// that index of the group. A constant index lowers as the command;
    /// a variable one to `modal_change_indirect`. The control allows
    /// neither arithmetic in the value nor the syntax-determining groups
    /// 2 and 3, and of group 1 only `G0`…`G3`.
    fn indirect_g(
        &mut self,
        group_expr: &ast::Expr,
        group_span: Span,
        value: &ast::WordValue,
        span: Span,
        plan: &mut BlockPlan,
    ) {
        let group = match values::constant(group_expr) {
            Some(g) if g.fract() == 0.0 && (1.0..=64.0).contains(&g) => g as u8,
            Some(_) => {
                return self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::INVALID_INDIRECT_G,
                        format!(
                            "`G[{}]`: G groups are numbered 1…64",
                            values::written(self.source, group_span)
                        ),
                    )
                    .with_label(group_span, "not a G group"),
                );
            }
            None => {
                return self.not_lowered(span, "a G command whose group is computed");
            }
        };
        let invalid = |message: String, help: &'static str| {
            Diagnostic::new(codes::lower::INVALID_INDIRECT_G, message)
                .with_label(span, "indirect G command")
                .with_help(help)
        };
        if ggroups::group(group).is_none_or(|g| g.members.is_empty()) {
            return self.diagnostics.push(invalid(
                format!("G group {group} has no commands"),
                "see the G-group table, reference §3.2",
            ));
        }
        if matches!(group, 2 | 3) {
            return self.diagnostics.push(invalid(
                format!("the commands of G group {group} cannot be programmed indirectly"),
                "syntax-determining G commands are written directly",
            ));
        }
        if let Some(n) = values::whole_number(value) {
            let member = (1.0..=255.0)
                .contains(&n)
                .then(|| ggroups::member(group, n as u8))
                .flatten();
            return match member {
                Some(_) if group == 1 && n > 4.0 => self.diagnostics.push(invalid(
                    "of G group 1 only G0, G1, G2 and G3 can be programmed indirectly".into(),
                    "write the motion command directly",
                )),
                // A member is found only for `n` in 1…255.
                Some(_) => self.g_code(group, n as u8, span, plan),
                None => self.diagnostics.push(invalid(
                    format!(
                        "G group {group} has no command with index {}",
                        values::written_number(self.source, value)
                    ),
                    "the index counts the group's commands from 1 (reference §3.2)",
                )),
            };
        }
        let ast::WordValue::Assigned {
            modifier: None,
            expr,
        } = value
        else {
            return self.diagnostics.push(invalid(
                "an indirect G command takes a whole number or a variable".into(),
                "write e.g. `G[8]=2` or `G[8]=KORD`",
            ));
        };
        if !matches!(expr.kind, ast::ExprKind::Var { .. }) {
            return self.diagnostics.push(invalid(
                "an indirect G command takes a whole number or a variable, no arithmetic".into(),
                "compute the index into a variable in an earlier block",
            ));
        }
        if group == 1 {
            return self.not_lowered(span, "a motion command chosen when the block runs");
        }
        if let Some((first, first_span)) = plan.g_codes.iter().find(|(c, _)| c.group() == group) {
            return self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::G_GROUP_CONFLICT,
                    format!("`G[{group}]=…` and `{}` are both in G group {group}; a block holds one command of a group", first.name()),
                )
                .with_label(span, "second command of the group")
                .with_label(*first_span, "first"),
            );
        }
        if let Some((_, _, first)) = plan.indirect_g.iter().find(|(g, _, _)| *g == group) {
            return self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::G_GROUP_CONFLICT,
                    format!("two commands of G group {group} in one block"),
                )
                .with_label(span, "second command of the group")
                .with_label(*first, "first"),
            );
        }
        plan.indirect_g.push((group, values::value(expr), span));
    }
}
