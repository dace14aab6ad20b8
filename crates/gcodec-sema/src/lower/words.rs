//! Address words: G commands, M functions, tools, cutting edges, feed,
//! spindle speeds, circle data and axis targets.

use gcodec_ail::{AxisValue, Suppression, Value};
use gcodec_parser::ast::{self, Extension, Word};
use gcodec_source::{Diagnostic, Span};

use crate::{ggroups, mfunc, tools, values};

use super::{
    BlockPlan, G_GROUP_CONFLICT, INVALID_VALUE, Lowering, UNKNOWN_ADDRESS, UNKNOWN_G,
    UNSUPPORTED_OFFSET, axis_name, g_code_text,
};

impl Lowering<'_> {
    pub(super) fn word(&mut self, word: &Word, span: Span, plan: &mut BlockPlan) {
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

    pub(super) fn is_axis(&self, name: &str) -> bool {
        self.profile
            .axes
            .iter()
            .any(|a| a.name.get_ref().eq_ignore_ascii_case(name))
    }

    /// A G command at its registry position (`group`, 1-based `index`).
    pub(super) fn g_code(&mut self, group: u8, index: u8, span: Span, plan: &mut BlockPlan) {
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
}
