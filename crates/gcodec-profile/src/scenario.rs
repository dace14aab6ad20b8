//! Toolchanger scenario files: how the simulated changer answers the
//! toolchanger protocol and which faults, aborts and missing
//! acknowledgements a run meets (`docs/toolchanger.md`).
//!
//! [`load_scenario`] reads the TOML as [`load`](crate::load) reads a
//! profile: every problem is a [`Diagnostic`] pointing into the text, all
//! of them in one pass. The [`Scenario`] it returns holds only what makes
//! sense: an injection's place and action are enums that carry exactly
//! the values they use.

use gcodec_source::{Diagnostic, codes};
use serde::Deserialize;
use toml::Spanned;

use crate::toml_file::{TomlKind, read_toml};
use crate::validate::error;

/// A scenario: the changer's behaviour and the faults to inject.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// Cycles before each acknowledgement of the changer, at least 1.
    pub ack_cycles: u32,
    /// Overrides the profile's `[toolchanger] timeout_cycles`.
    pub timeout_cycles: Option<u32>,
    /// The tool in the spindle when the run starts (its number); the span
    /// is into the scenario's TOML, for the check against the tool table.
    pub initial_tool: Option<Spanned<u32>>,
    /// The fault reason latched when the run starts (`initial_fault`).
    pub initial_fault: Option<i32>,
    /// What happens during the run, in the order written.
    pub inject: Vec<Injection>,
}

impl Default for Scenario {
    /// A changer that acknowledges every handshake after one cycle and
    /// never faults.
    fn default() -> Self {
        Self {
            ack_cycles: 1,
            timeout_cycles: None,
            initial_tool: None,
            initial_fault: None,
            inject: Vec::new(),
        }
    }
}

/// One `[[inject]]`: when and what.
#[derive(Clone, Debug, PartialEq)]
pub struct Injection {
    pub at: InjectAt,
    /// Cycles into the operation (for a block: after its start) at which
    /// the action happens.
    pub after_cycles: u32,
    pub action: InjectAction,
}

/// Where an injection happens: the n-th operation of its kind in the run
/// (from 1), or the `pass`-th start of a line of the main program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InjectAt {
    Prepare(u32),
    StartChange(u32),
    Change(u32),
    Abort(u32),
    Block { line: u32, pass: u32 },
}

/// What the injection does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InjectAction {
    /// The changer raises its fault line with `reason` (> 0 soft, ≤ 0
    /// hard) for `hold_cycles`, or until a `Clear` when `None`.
    Fault {
        reason: i32,
        hold_cycles: Option<u32>,
    },
    /// The changer raises clear-fault for one cycle (and drops a fault line
    /// held until cleared).
    Clear,
    /// The executor's side aborts with `reason` (an operator's abort is 8).
    Abort { reason: i32 },
    /// The changer never acknowledges the operation.
    NeverAck,
    /// The changer acknowledges the operation `cycles` cycles late.
    DelayAck { cycles: u32 },
}

/// Reads and checks a scenario. On error, every diagnostic found, with
/// spans into `text`.
pub fn load_scenario(text: &str) -> Result<Scenario, Vec<Diagnostic>> {
    let raw: RawScenario = read_toml(text, SCENARIO_TOML).map_err(|d| vec![d])?;
    let mut problems = Vec::new();
    let scenario = check(raw, &mut problems);
    problems.sort_by_key(|d| d.span().map_or(0, |s| s.start));
    if problems.is_empty() {
        Ok(scenario)
    } else {
        Err(problems)
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenario {
    ack_cycles: Option<Spanned<u32>>,
    timeout_cycles: Option<Spanned<u32>>,
    initial_tool: Option<Spanned<u32>>,
    initial_fault: Option<Spanned<bool>>,
    initial_fault_reason: Option<Spanned<i32>>,
    #[serde(default)]
    inject: Vec<RawInjection>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawInjection {
    at: Spanned<RawAt>,
    n: Spanned<u32>,
    pass: Option<Spanned<u32>>,
    after_cycles: Option<Spanned<u32>>,
    action: Spanned<RawAction>,
    hold_cycles: Option<Spanned<u32>>,
    fault_reason: Option<Spanned<i32>>,
    abort_reason: Option<Spanned<i32>>,
}

#[derive(Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
enum RawAt {
    Prepare,
    StartChange,
    Change,
    Abort,
    Block,
}

#[derive(Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
enum RawAction {
    Fault,
    Clear,
    Abort,
    NeverAck,
    DelayAck,
}

impl RawAction {
    fn name(self) -> &'static str {
        match self {
            Self::Fault => "fault",
            Self::Clear => "clear",
            Self::Abort => "abort",
            Self::NeverAck => "never_ack",
            Self::DelayAck => "delay_ack",
        }
    }
}

fn check(raw: RawScenario, out: &mut Vec<Diagnostic>) -> Scenario {
    let ack_cycles = raw.ack_cycles.as_ref().map_or(1, |a| at_least_one(a, out));
    let timeout_cycles = raw.timeout_cycles.as_ref().map(|t| at_least_one(t, out));
    let initial_fault = match (&raw.initial_fault, &raw.initial_fault_reason) {
        (Some(fault), Some(reason)) if *fault.get_ref() => Some(*reason.get_ref()),
        (Some(fault), None) if *fault.get_ref() => {
            out.push(missing(
                fault,
                "`initial_fault = true` needs `initial_fault_reason`",
            ));
            None
        }
        (_, Some(reason)) => {
            out.push(not_applicable(
                reason,
                "`initial_fault_reason` is read only with `initial_fault = true`",
            ));
            None
        }
        _ => None,
    };
    let inject = raw
        .inject
        .iter()
        .filter_map(|injection| check_injection(injection, out))
        .collect();
    Scenario {
        ack_cycles,
        timeout_cycles,
        initial_tool: raw.initial_tool,
        initial_fault,
        inject,
    }
}

fn check_injection(raw: &RawInjection, out: &mut Vec<Diagnostic>) -> Option<Injection> {
    let n = at_least_one(&raw.n, out);
    let pass = match (raw.pass.as_ref(), *raw.at.get_ref()) {
        (Some(pass), RawAt::Block) => at_least_one(pass, out),
        (Some(pass), _) => {
            out.push(not_applicable(
                pass,
                "`pass` counts the runs of a line: it is for `at = \"block\"` only",
            ));
            1
        }
        (None, _) => 1,
    };
    let at = match raw.at.get_ref() {
        RawAt::Prepare => InjectAt::Prepare(n),
        RawAt::StartChange => InjectAt::StartChange(n),
        RawAt::Change => InjectAt::Change(n),
        RawAt::Abort => InjectAt::Abort(n),
        RawAt::Block => InjectAt::Block { line: n, pass },
    };
    let action = *raw.action.get_ref();
    let unused = |key: &str| format!("`{key}` is not used by `action = \"{}\"`", action.name());
    if let (Some(reason), false) = (&raw.fault_reason, action == RawAction::Fault) {
        out.push(not_applicable(reason, &unused("fault_reason")));
    }
    if let (Some(reason), false) = (&raw.abort_reason, action == RawAction::Abort) {
        out.push(not_applicable(reason, &unused("abort_reason")));
    }
    let holds = matches!(action, RawAction::Fault | RawAction::DelayAck);
    if let (Some(hold), false) = (&raw.hold_cycles, holds) {
        out.push(not_applicable(hold, &unused("hold_cycles")));
    }
    let acks = matches!(action, RawAction::NeverAck | RawAction::DelayAck);
    if let (Some(after), true) = (&raw.after_cycles, acks) {
        out.push(not_applicable(after, &unused("after_cycles")));
    }
    let hold_cycles = raw.hold_cycles.as_ref().map(|h| at_least_one(h, out));
    let action = match action {
        RawAction::Fault => match &raw.fault_reason {
            Some(reason) => InjectAction::Fault {
                reason: *reason.get_ref(),
                hold_cycles,
            },
            None => {
                out.push(
                    missing(&raw.action, "a fault needs `fault_reason`")
                        .with_help("above 0 a soft fault (the change is skipped), 0 or below a hard one (the program aborts)"),
                );
                return None;
            }
        },
        RawAction::Clear => InjectAction::Clear,
        RawAction::Abort => match &raw.abort_reason {
            Some(reason) if *reason.get_ref() >= 1 => InjectAction::Abort {
                reason: *reason.get_ref(),
            },
            Some(reason) => {
                out.push(
                    error(
                        codes::scenario::OUT_OF_RANGE,
                        reason,
                        "an abort reason is 1 or more".into(),
                        "here",
                    )
                    .with_help("an operator's abort is 8; see docs/toolchanger.md for the reasons"),
                );
                return None;
            }
            None => {
                out.push(
                    missing(&raw.action, "an abort needs `abort_reason`")
                        .with_help("an operator's abort is `abort_reason = 8`"),
                );
                return None;
            }
        },
        RawAction::NeverAck => InjectAction::NeverAck,
        RawAction::DelayAck => match hold_cycles {
            Some(cycles) => InjectAction::DelayAck { cycles },
            None => {
                out.push(missing(
                    &raw.action,
                    "a delayed acknowledgement needs `hold_cycles`, the delay",
                ));
                return None;
            }
        },
    };
    Some(Injection {
        at,
        after_cycles: raw.after_cycles.as_ref().map_or(0, |a| *a.get_ref()),
        action,
    })
}

/// The value, reported when it is 0.
fn at_least_one(value: &Spanned<u32>, out: &mut Vec<Diagnostic>) -> u32 {
    if *value.get_ref() == 0 {
        out.push(error(
            codes::scenario::OUT_OF_RANGE,
            value,
            "this value counts from 1".into(),
            "0 here",
        ));
    }
    *value.get_ref()
}

fn missing<T>(at: &Spanned<T>, message: &str) -> Diagnostic {
    error(
        codes::scenario::MISSING_VALUE,
        at,
        message.to_owned(),
        "here",
    )
}

fn not_applicable<T>(at: &Spanned<T>, message: &str) -> Diagnostic {
    error(
        codes::scenario::KEY_NOT_APPLICABLE,
        at,
        message.to_owned(),
        "not used",
    )
    .with_help("remove the key, or change the entry it belongs to")
}

const SCENARIO_TOML: TomlKind = TomlKind {
    syntax: codes::scenario::SYNTAX,
    schema: codes::scenario::SCHEMA,
    what: "toolchanger scenario",
    help: "see docs/toolchanger.md for the scenario format",
};
