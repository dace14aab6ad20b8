//! G commands whose axis words do not traverse: the group 3 settings
//! (`G25`/`G26` working-area limits, `G110`/`G111`/`G112` the pole,
//! `G58`/`G59` axial programmable offsets) and the approach of a point of
//! the machine data (`G74` reference point, `G75 FP=n` fixed point), whose
//! words name machine axes (`X1=0`).

use std::borrow::Cow;

use gcodec_ail::{ApproachPoint, AxisSetting, Op, SpindleLimit, Value};
use gcodec_lang::addresses::NamedAddress;
use gcodec_lang::ggroups::GCommand;
use gcodec_parser::ast::{Extension, Word};
use gcodec_source::{Diagnostic, Span, codes};

use super::{BlockPlan, Lowering};

/// What a G command does with the block's axis words, if not traverse.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum AxisCommand {
    /// Group 3: the words are values of a setting.
    Setting,
    /// `G74`/`G75`: the words select machine axes.
    Approach,
}

impl AxisCommand {
    pub(super) fn of(command: GCommand) -> Option<Self> {
        match (command.group(), command.name()) {
            (3, "G25" | "G26" | "G110" | "G111" | "G112" | "G58" | "G59") => Some(Self::Setting),
            (2, "G74" | "G75") => Some(Self::Approach),
            _ => None,
        }
    }
}

/// An axis word whose name is no channel axis but a machine axis of one
/// (`X1` of `X`), kept until the block shows whether it approaches a point.
pub(super) struct MachineAxisWord {
    /// The channel axis, upper case.
    pub axis: Cow<'static, str>,
    /// The name as written.
    pub written: String,
    /// The address's span.
    pub span: Span,
}

impl Lowering<'_> {
    /// The channel axis whose machine axis `word` names: `X1` is the
    /// machine axis of `X` (MD10000's standard names, the channel axis
    /// with the digit 1).
    pub(super) fn machine_axis_of(&self, word: &Word) -> Option<Cow<'static, str>> {
        match word.extension() {
            Some(Extension::Number { value: 1, .. }) if self.is_axis(word.address()) => {
                Some(super::axis_name(word.address()))
            }
            _ => None,
        }
    }

    /// Emits the block's `command` with the axis words it takes; `false`
    /// when the command is no such one.
    pub(super) fn emit_axis_command(
        &mut self,
        index: usize,
        command: GCommand,
        span: Span,
        plan: &mut BlockPlan,
    ) -> bool {
        let op = match AxisCommand::of(command) {
            None => return false,
            Some(AxisCommand::Setting) => self.axis_setting(command, plan),
            Some(AxisCommand::Approach) => approach_point(command, plan),
        };
        if !plan.indirect_targets.is_empty() {
            plan.indirect_targets.clear();
            self.not_lowered(
                span,
                &format!(
                    "an axis named when the block runs, with `{}`",
                    command.name()
                ),
            );
        }
        plan.target_span = None;
        self.report_repeated_axes(plan);
        self.emit(index, span, op);
        true
    }

    fn axis_setting(&mut self, command: GCommand, plan: &mut BlockPlan) -> Op {
        let mut spindle_limits = Vec::new();
        if matches!(command.name(), "G25" | "G26") {
            for (spindle, expr, speed, at) in std::mem::take(&mut plan.spindle) {
                if expr.is_some() {
                    self.not_lowered(at, "a spindle-speed limit of a computed spindle");
                    continue;
                }
                spindle_limits.push(SpindleLimit { spindle, speed });
            }
        }
        Op::AxisSetting(Box::new(AxisSetting {
            command,
            values: plan.targets.drain(..).collect(),
            spindle_limits,
        }))
    }

    /// Machine-axis words of a block that approaches no point name no axis
    /// of the machine.
    pub(super) fn unknown_machine_axes(&mut self, plan: &mut BlockPlan) {
        for word in std::mem::take(&mut plan.machine_axis_words) {
            let help = format!(
                "{}; `{}` names the machine axis of `{}` only with `G74`/`G75`",
                self.axes_help(&word.written),
                word.written,
                word.axis
            );
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::UNKNOWN_ADDRESS,
                    format!(
                        "`{}` is not an axis or address of this machine",
                        word.written
                    ),
                )
                .with_label(word.span, "unknown here")
                .with_help(help),
            );
        }
    }
}

/// `G74`/`G75`: the axes the block names (machine or channel names), and
/// for `G75` its `FP=`, taken out of the block's addresses.
fn approach_point(command: GCommand, plan: &mut BlockPlan) -> Op {
    let mut axes: Vec<Cow<'static, str>> = plan.targets.drain(..).map(|t| t.axis).collect();
    axes.extend(plan.machine_axis_words.drain(..).map(|w| w.axis));
    let fixed_point = (command.name() == "G75").then(|| {
        let at = plan
            .addresses
            .iter()
            .position(|(op, _)| matches!(op, Op::Address(a) if a.address == NamedAddress::Fp));
        match at.map(|at| plan.addresses.remove(at).0) {
            Some(Op::Address(a)) => a.value,
            _ => Value::Const(1.0),
        }
    });
    Op::ApproachPoint(Box::new(ApproachPoint {
        command,
        fixed_point,
        axes,
    }))
}
