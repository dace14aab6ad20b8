//! Tool selection per the tool-change design: the selector forms each
//! tool-management mode accepts, normalised into one selector model, with the
//! timing the profile's tool-change mode gives; and spindle numbers.

use gcodec_ail::{Op, SelectorKind, ToolTiming};
use gcodec_parser::ast::{ExprKind, Extension, Word, WordValue};
use gcodec_profile::{Profile, ToolChangeMode, UnresolvedToolPolicy};
use gcodec_source::{Diagnostic, Diagnostics, Span, codes};

use crate::policy::by_policy;
use crate::values::{source_text, whole_number, written_number};
/// Whether the machine has spindle `number`.
pub(crate) fn spindle_exists(profile: &Profile, number: u32) -> bool {
    profile
        .machine
        .spindles
        .iter()
        .any(|s| *s.get_ref() == number)
}

/// The diagnostic for a spindle number the machine does not have.
pub(crate) fn unknown_spindle(number: u32, span: Span) -> Diagnostic {
    Diagnostic::new(
        codes::lower::UNKNOWN_SPINDLE,
        format!("this machine has no spindle {number}"),
    )
    .with_label(span, "spindle number")
    .with_help("the profile's `[machine] spindles` lists the spindles")
}

/// The diagnostic for a constant spindle extension that is no spindle
/// number (`S[100]=`, `M[2.5]=`), the extension `written` as the program
/// writes it after `address`; spindles are `range` (`1…99`, `0…99` where
/// 0 is the master spindle).
pub(crate) fn not_a_spindle_number(
    address: &str,
    written: &str,
    range: &str,
    span: Span,
) -> Diagnostic {
    Diagnostic::new(
        codes::lower::INVALID_VALUE,
        format!("`{address}[{written}]`: a spindle number is a whole number {range}"),
    )
    .with_label(span, "not a spindle number")
}

/// What a `T` word selects, before the mode is applied.
enum Selector {
    Number(u32),
    Name(String),
    /// `T=NAMES[I]`: known when the block runs.
    Computed(gcodec_ail::Expr, String),
}

/// A whole tool number `n ≥ 0`, if it is one the control holds
/// (0…4294967295); a larger one is [`codes::lower::INVALID_VALUE`] naming
/// it as `written`, never a wrapped or saturated number.
fn tool_number(n: f64, written: &str, span: Span, diagnostics: &mut Diagnostics) -> Option<u32> {
    if n <= f64::from(u32::MAX) {
        // Whole (`whole_number`), ≥ 0 (the caller) and at most `u32::MAX`.
        return Some(n as u32);
    }
    diagnostics.push(
        Diagnostic::new(
            codes::lower::INVALID_VALUE,
            format!("T{written} is out of range"),
        )
        .with_label(span, "out of range")
        .with_help("tool numbers are 0…4294967295"),
    );
    None
}

/// Checks a `T` word and returns its `tool_select`; `None` when it is
/// rejected (its diagnostic pushed).
pub(crate) fn select(
    word: &Word,
    value: &WordValue,
    span: Span,
    profile: &Profile,
    source: &[u8],
    diagnostics: &mut Diagnostics,
) -> Option<Op> {
    let management = profile.tool_change.tool_management_enabled;
    let spindle = match word.extension() {
        None => None,
        Some(Extension::Number { value, span }) => {
            if !spindle_exists(profile, *value) {
                diagnostics.push(unknown_spindle(*value, *span));
                return None;
            }
            Some(*value)
        }
        Some(Extension::Index { .. }) => {
            diagnostics.push(form_error(
                span,
                "a `T` extension is a spindle number, e.g. `T1=5`",
            ));
            return None;
        }
    };
    let written = || written_number(source, value);
    let (selector, assigned) = match (value, whole_number(value)) {
        (WordValue::Constant(_), Some(n)) if n >= 0.0 => (
            Selector::Number(tool_number(n, &written(), span, diagnostics)?),
            false,
        ),
        (WordValue::Assigned { .. }, Some(n)) if n >= 0.0 => (
            Selector::Number(tool_number(n, &written(), span, diagnostics)?),
            true,
        ),
        (
            WordValue::Assigned {
                modifier: None,
                expr,
            },
            _,
        ) => match &expr.kind {
            ExprKind::String { value } => (Selector::Name(value.to_string()), true),
            ExprKind::Number { .. } => {
                diagnostics.push(form_error(
                    span,
                    "select a tool by a whole number or a name in quotes",
                ));
                return None;
            }
            _ => (
                Selector::Computed(crate::values::tree(expr), source_text(expr)),
                true,
            ),
        },
        _ => {
            diagnostics.push(
                Diagnostic::new(
                    codes::lower::INVALID_VALUE,
                    "a tool number is a whole number",
                )
                .with_label(span, "not a tool number"),
            );
            return None;
        }
    };
    let (kind, selector_value) = match (&selector, management) {
        (Selector::Computed(_, text), _) => (SelectorKind::Computed, text.clone()),
        (Selector::Name(_), false) => {
            diagnostics.push(form_error(
                span,
                "tools are selected by name only with tool management; this machine selects by number (`T5`)",
            ));
            return None;
        }
        // `T0` empties the spindle with tool management too.
        (Selector::Number(0), true) if !assigned => (SelectorKind::Number, "0".to_owned()),
        (Selector::Number(_), true) if !assigned => {
            diagnostics.push(form_error(
                span,
                "with tool management, select a tool by name (`T=\"DRILL_10\"`) or location (`T=5`)",
            ));
            return None;
        }
        (Selector::Number(n), false) => (SelectorKind::Number, n.to_string()),
        (Selector::Number(n), true) => (SelectorKind::Location, n.to_string()),
        (Selector::Name(name), true) => (SelectorKind::Name, name.clone()),
    };
    resolve(profile, kind, &selector_value, span, diagnostics);
    let timing = match profile.tool_change.tool_change_mode {
        ToolChangeMode::Direct => ToolTiming::Immediate,
        ToolChangeMode::DeferredM6 => ToolTiming::DeferredUntilM6,
    };
    let raw = match (&selector, spindle, assigned) {
        (Selector::Computed(_, text), Some(s), _) => format!("T{s}={text}"),
        (Selector::Computed(_, text), None, _) => format!("T={text}"),
        (Selector::Name(name), Some(s), _) => format!("T{s}=\"{name}\""),
        (Selector::Name(name), None, _) => format!("T=\"{name}\""),
        (Selector::Number(n), Some(s), _) => format!("T{s}={n}"),
        (Selector::Number(n), None, true) => format!("T={n}"),
        (Selector::Number(n), None, false) => format!("T{n}"),
    };
    let selector_expr = match selector {
        Selector::Computed(expr, _) => Some(expr),
        _ => None,
    };
    Some(Op::ToolSelect(Box::new(gcodec_ail::ToolSelect {
        selector_kind: kind,
        selector_value,
        selector_expr,
        spindle_extension: spindle,
        timing,
        raw,
    })))
}

/// Checks a selection against the tool table, when the profile has one:
/// `on_unresolved_tool` says what an unknown tool is. `T0` deselects.
fn resolve(
    profile: &Profile,
    kind: SelectorKind,
    value: &str,
    span: Span,
    diagnostics: &mut Diagnostics,
) {
    if profile.tools.is_empty() || value == "0" || kind == SelectorKind::Computed {
        return;
    }
    let found = profile.tools.iter().any(|t| t.is_selected_by(kind, value));
    if found {
        return;
    }
    let message = format!("no tool `{value}` in the machine's tool table");
    let help = "the profile's `[[tools]]` lists the tools";
    let severity = match profile.tool_change.on_unresolved_tool {
        UnresolvedToolPolicy::Error => Some(true),
        UnresolvedToolPolicy::Warning => Some(false),
        UnresolvedToolPolicy::Fallback => None,
    };
    if let Some(error) = severity {
        diagnostics.push(
            by_policy(error, codes::lower::UNRESOLVED_TOOL, message)
                .with_label(span, "unknown tool")
                .with_help(help),
        );
    }
}

fn form_error(span: Span, help: &'static str) -> Diagnostic {
    Diagnostic::new(
        codes::lower::TOOL_SELECTOR_FORM,
        "this tool selection is not accepted on this machine",
    )
    .with_label(span, "tool selection")
    .with_help(help)
}
