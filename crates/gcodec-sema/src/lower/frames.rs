//! Programmable frame instructions: `TRANS X10 Y5`, `AROT RPL=45`,
//! `MIRROR X0`; the bare keyword resets. The executor composes the frame
//! chain (language reference §9.2).

use std::borrow::Cow;

use gcodec_ail::{AxisValue, IndirectAxisValue, Op};
use gcodec_parser::ast;
use gcodec_source::{Diagnostic, Span, codes};

use crate::values;

use super::addresses::AxisRef;
use super::{BlockPlan, Lowering, axis_name};
impl Lowering<'_> {
    pub(super) fn frame(
        &mut self,
        block: &ast::Block,
        frame: &ast::Frame,
        span: Span,
        plan: &mut BlockPlan,
    ) {
        // Frame instructions need a block of their own (reference §9.1).
        if block.statements.len() > 1 {
            let mut diagnostic = Diagnostic::new(
                codes::lower::FRAME_NOT_ALONE,
                format!("`{}` must be alone in its block", frame.op.keyword()),
            )
            .with_label(span, "frame instruction");
            for other in block.statements.iter().filter(|s| s.span != span) {
                diagnostic = diagnostic.with_label(other.span, "also in the block");
            }
            self.diagnostics.push(diagnostic.with_help(
                "the control rejects the block; put the frame instruction in a block of its own",
            ));
        }
        let rotation = frame.op.is_rotation();
        let mut values = Vec::with_capacity(frame.words.len());
        let mut indirect_values = Vec::new();
        // A rejected word leaves the instruction out: without its values
        // it would read as the bare keyword, a reset.
        let mut rejected = false;
        for w in &frame.words {
            let address = w.word.address();
            if address.eq_ignore_ascii_case("AX") {
                // `AX[X]=…`, `AX[_XX]=…`: an axis named in brackets,
                // by a variable when the block runs.
                let axis = self.bracket_axis(&w.word, w.span);
                let value = w.word.value(w.span);
                if let ast::WordValue::Assigned { expr, .. } = &*value {
                    self.check_variables(expr);
                }
                let (value, mode) = values::word_value(&value);
                match axis {
                    Some(AxisRef::Named(name)) => values.push(AxisValue {
                        axis: Cow::Owned(name),
                        value,
                        mode,
                    }),
                    Some(AxisRef::Computed(axis)) => {
                        indirect_values.push(IndirectAxisValue { axis, value, mode })
                    }
                    None => rejected = true,
                }
                continue;
            }
            if !(self.is_axis(address) || rotation && address.eq_ignore_ascii_case("RPL")) {
                if is_command_word(address) {
                    // `TRANS X5 G0 Z10`: the parser reads every word after
                    // the keyword as the frame's; a G command, feed,
                    // spindle speed, tool or auxiliary function is another
                    // statement of the block.
                    let written = values::written(self.source, w.span);
                    self.diagnostics.push(
                        Diagnostic::new(
                            codes::lower::FRAME_NOT_ALONE,
                            format!("`{}` must be alone in its block", frame.op.keyword()),
                        )
                        .with_label(Span::new(span.start, w.span.start), "frame instruction")
                        .with_label(w.span, format!("`{written}` is also in the block"))
                        .with_help("the control rejects the block; put the frame instruction in a block of its own"),
                    );
                    rejected = true;
                    continue;
                }
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::UNKNOWN_ADDRESS,
                        format!("`{address}` is not an axis of this machine"),
                    )
                    .with_label(w.word.address_span(w.span), "not an axis")
                    .with_help(if rotation {
                        format!(
                            "{}; or `RPL=` for a rotation in the plane",
                            self.axes_help(address)
                        )
                    } else {
                        self.axes_help(address)
                    }),
                );
                rejected = true;
                continue;
            }
            let value = w.word.value(w.span);
            if let ast::WordValue::Assigned { expr, .. } = &*value {
                self.check_variables(expr);
            }
            let (value, mode) = values::word_value(&value);
            values.push(AxisValue {
                axis: axis_name(address),
                value,
                mode,
            });
        }
        if rejected {
            return;
        }
        plan.other.push((
            Op::Frame(Box::new(gcodec_ail::Frame {
                op: frame.op,
                values,
                indirect_values,
            })),
            span,
        ));
    }
}

/// A letter address that is a statement of its own in a block, never a
/// frame's value: `G`, `F`, `S`, `T`, `D`, `M`, `H` (reference §2.6).
fn is_command_word(address: &str) -> bool {
    matches!(
        address.as_bytes(),
        [b'G' | b'F' | b'S' | b'T' | b'D' | b'M' | b'H']
    )
}
