//! M functions per the M-function design: the accepted forms, the value range,
//! the extended address, the per-block limit, classes and the unknown-code
//! policy.

use std::collections::HashMap;

use gcodec_ail::{MTiming, Op};
use gcodec_lang::MClass;
use gcodec_lang::mfunctions::{acts_after_motion, standard_class};
use gcodec_parser::ast::{Extension, Word, WordValue};
use gcodec_profile::{Policy, Profile};
use gcodec_source::{Diagnostic, Diagnostics, Span, codes};

use crate::policy::by_policy;
use crate::tools::{not_a_spindle_number, spindle_exists, unknown_spindle};
use crate::values::{constant, source_text, tree, whole_number, written, written_number};
/// Largest M value (the M-function design: a 32-bit non-negative INT).
const MAX_M: f64 = gcodec_lang::mfunctions::MAX_M_VALUE as f64;

/// A checked M word.
pub(crate) struct MWord {
    /// `None` for a computed value (`M1=DIR`).
    pub value: Option<u32>,
    pub expr: Option<gcodec_ail::Expr>,
    pub extension: Option<u32>,
    /// `M[SPINU]=3`: the spindle, computed when the block runs.
    pub extension_expr: Option<gcodec_ail::Expr>,
    pub class: MClass,
    pub raw: String,
    pub span: Span,
}

impl MWord {
    pub(crate) fn into_op(self, timing: MTiming) -> Op {
        Op::MFunction(Box::new(gcodec_ail::MFunction {
            m_value: self.value,
            m_expr: self.expr,
            address_extension: self.extension,
            address_extension_expr: self.extension_expr,
            class: self.class,
            timing,
            raw: self.raw,
        }))
    }
}

/// Checks one M word; `None` when it is rejected (its diagnostic pushed).
pub(crate) fn check(
    word: &Word,
    value: &WordValue,
    span: Span,
    profile: &Profile,
    overrides: &HashMap<u32, MClass>,
    source: &[u8],
    diagnostics: &mut Diagnostics,
) -> Option<MWord> {
    let number = match (whole_number(value), value) {
        (Some(number), _) => number,
        // `M1=DIR`: computed when the block runs; the executor checks the
        // value then.
        (
            None,
            WordValue::Assigned {
                modifier: None,
                expr,
            },
        ) if constant(expr).is_none() => {
            let (extension, extension_expr) = extension(word, span, profile, source, diagnostics)?;
            let text = source_text(expr);
            let raw = format!("M{}={text}", extension_text(word, extension));
            return Some(MWord {
                value: None,
                expr: Some(tree(expr)),
                extension,
                extension_expr,
                class: MClass::Custom,
                raw,
                span,
            });
        }
        _ => {
            diagnostics.push(
                Diagnostic::new(
                    codes::lower::INVALID_VALUE,
                    "an M function takes a whole number",
                )
                .with_label(span, "not a whole number")
                .with_help("write e.g. `M3` or `M2=3`; M values are 0…2147483647"),
            );
            return None;
        }
    };
    if !(0.0..=MAX_M).contains(&number) {
        diagnostics.push(
            Diagnostic::new(
                codes::lower::INVALID_VALUE,
                format!("M{} is out of range", written_number(source, value)),
            )
            .with_label(span, "out of range")
            .with_help("M values are 0…2147483647"),
        );
        return None;
    }
    // Whole (`whole_number`) and in 0…`MAX_M`, checked above.
    let m = number as u32;
    if acts_after_motion(m) && word.extension().is_some() {
        diagnostics.push(
            Diagnostic::new(
                codes::lower::M_EXTENSION_FORBIDDEN,
                format!("M{m} takes no address extension"),
            )
            .with_label(span, "extended address")
            .with_help("M0, M1, M2, M17 and M30 are written without a spindle number"),
        );
        return None;
    }
    let (extension, extension_expr) = extension(word, span, profile, source, diagnostics)?;
    let change_m = *profile.tool_change.change_m_code.get_ref();
    let overridden = overrides.get(&m).copied();
    let class = match overridden.or_else(|| standard_class(m, change_m)) {
        Some(class) => class,
        None => {
            let message = format!("M{m} is not a predefined M function");
            let help =
                "machine-specific M functions are listed in the profile's `mcode_class_overrides`";
            let severity = match profile.m_functions.unknown_mcode_policy {
                Policy::Error => Some(true),
                Policy::Warning => Some(false),
                Policy::Ignore => None,
            };
            if let Some(error) = severity {
                diagnostics.push(
                    by_policy(error, codes::lower::UNKNOWN_M_FUNCTION, message)
                        .with_label(span, "unknown")
                        .with_help(help),
                );
            }
            MClass::Custom
        }
    };
    let raw = match word.extension() {
        Some(_) => format!("M{}={m}", extension_text(word, extension)),
        None => format!("M{m}"),
    };
    Some(MWord {
        value: Some(m),
        expr: None,
        extension,
        extension_expr,
        class,
        raw,
        span,
    })
}

/// The extension as the `raw` form writes it: `2` for `M2=` (and a
/// constant `M[2]=`), `[SPINU]` for a computed one.
fn extension_text(word: &Word, extension: Option<u32>) -> String {
    match (extension, word.extension()) {
        (Some(ext), _) => ext.to_string(),
        (None, Some(Extension::Index { index, .. })) => format!("[{}]", source_text(index)),
        _ => String::new(),
    }
}

/// The spindle extension of an M word (`M2=…`, `M[SPINU]=…`), checked:
/// `None` when it is rejected (its diagnostic pushed); a computed one is
/// the expression.
fn extension(
    word: &Word,
    span: Span,
    profile: &Profile,
    source: &[u8],
    diagnostics: &mut Diagnostics,
) -> Option<(Option<u32>, Option<gcodec_ail::Expr>)> {
    let (ext, ext_span) = match word.extension() {
        None => return Some((None, None)),
        Some(Extension::Number { value, span }) => (*value, *span),
        Some(Extension::Index { index, span: at }) => match constant(index) {
            Some(n) if n.fract() == 0.0 && (0.0..=99.0).contains(&n) => (n as u32, *at),
            Some(_) => {
                diagnostics.push(not_a_spindle_number(
                    "M",
                    &written(source, *at),
                    "0…99",
                    *at,
                ));
                return None;
            }
            // `M[SPINU]=3`: a spindle chosen when the block runs.
            None => {
                if !profile.m_functions.enable_extended_m_address {
                    diagnostics.push(no_extended_address(span));
                    return None;
                }
                return Some((None, Some(tree(index))));
            }
        },
    };
    if !profile.m_functions.enable_extended_m_address {
        diagnostics.push(no_extended_address(span));
        return None;
    }
    // Extension 0 is the master spindle (reference §4.2).
    if ext != 0 && !spindle_exists(profile, ext) {
        diagnostics.push(unknown_spindle(ext, ext_span));
        return None;
    }
    Some((Some(ext), None))
}

fn no_extended_address(span: Span) -> Diagnostic {
    Diagnostic::new(
        codes::lower::M_EXTENSION_FORBIDDEN,
        "this machine has no extended M addresses",
    )
    .with_label(span, "extended address")
    .with_help("the profile sets `enable_extended_m_address = false`")
}

/// Reports the M words past the profile's per-block limit.
pub(crate) fn check_count(words: &[MWord], profile: &Profile, diagnostics: &mut Diagnostics) {
    let max = *profile.m_functions.max_m_per_block.get_ref() as usize;
    if let Some(first_excess) = words.get(max) {
        diagnostics.push(
            Diagnostic::new(
                codes::lower::TOO_MANY_M_FUNCTIONS,
                format!("more than {max} M functions in one block"),
            )
            .with_label(first_excess.span, "one too many")
            .with_help("split the block; the limit is `max_m_per_block` in the profile"),
        );
    }
}

/// Two M functions of one auxiliary-function group of the master spindle
/// in a block (`S1000 M3 M5`, `M0 M30`): alarm 14760. Computed values and
/// spindles are checked when the block runs.
pub(crate) fn check_groups(words: &[MWord], profile: &Profile, diagnostics: &mut Diagnostics) {
    let groups = &profile.m_functions;
    let master = profile.machine.spindles.first().map(|s| *s.get_ref());
    let grouped = |m: &MWord| {
        let of_master = match m.extension {
            None | Some(0) => m.extension_expr.is_none(),
            Some(n) => Some(n) == master,
        };
        m.value
            .filter(|_| of_master)
            .and_then(|v| groups.auxiliary_group(v))
    };
    for (i, later) in words.iter().enumerate() {
        let Some(group) = grouped(later) else {
            continue;
        };
        if let Some(first) = words[..i].iter().find(|m| grouped(m) == Some(group)) {
            diagnostics.push(
                Diagnostic::new(
                    codes::lower::M_GROUP_CONFLICT,
                    format!(
                        "`{}` and `{}` are both of auxiliary-function group {group}",
                        first.raw, later.raw
                    ),
                )
                .with_label(first.span, "first")
                .with_label(later.span, "same group")
                .with_help("the control outputs one M function of a group per block (alarm 14760); split the block or drop one (the groups are the profile's `auxiliary_groups`)"),
            );
        }
    }
}

/// The profile's `mcode_class_overrides` by M value, read once.
pub(crate) fn overrides(profile: &Profile) -> HashMap<u32, MClass> {
    profile
        .m_functions
        .mcode_class_overrides
        .iter()
        .filter_map(|(k, class)| Some((k.get_ref().parse::<u32>().ok()?, *class)))
        .collect()
}
