//! The level each diagnostic is reported at: the configuration's rule
//! levels, then `--select`, `--ignore` and a file's own ignores, then
//! `--deny warnings`.

use gcodec_source::{Code, Severity};
use serde::Deserialize;

use super::Selector;

/// A rule level of `gcodec.toml`'s `[rules]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RuleLevel {
    /// Not reported.
    Allow,
    /// Reported as a warning.
    Warn,
    /// Reported as an error: the check fails.
    Deny,
}

/// The command line's choice of diagnostics.
#[derive(Clone, Debug, Default)]
pub struct Selection {
    /// Only diagnostics these select are reported (all when empty).
    pub select: Vec<Selector>,
    /// Diagnostics these select are not reported.
    pub ignore: Vec<Selector>,
    /// Warnings are reported as errors (`--deny warnings`).
    pub deny_warnings: bool,
}

/// The rule levels in force for one file.
pub(super) struct Levels<'a> {
    pub rules: &'a [(Selector, RuleLevel)],
    pub file_ignores: &'a [Selector],
    pub selection: &'a Selection,
}

impl Levels<'_> {
    /// The level a diagnostic of `code` found at `severity` is reported
    /// at, or `None` where it is not reported. Of the rules that match, a
    /// code's wins over an area's (each is named at most once).
    pub fn level(&self, code: &'static Code, severity: Severity) -> Option<Severity> {
        let selection = self.selection;
        if !selection.select.is_empty() && !selection.select.iter().any(|s| s.matches(code)) {
            return None;
        }
        if selection
            .ignore
            .iter()
            .chain(self.file_ignores)
            .any(|s| s.matches(code))
        {
            return None;
        }
        let rule = self
            .rules
            .iter()
            .filter(|(selector, _)| selector.matches(code))
            .max_by_key(|(selector, _)| selector.is_code())
            .map(|(_, level)| *level);
        let severity = match rule {
            Some(RuleLevel::Allow) => return None,
            Some(RuleLevel::Warn) => Severity::Warning,
            Some(RuleLevel::Deny) => Severity::Error,
            None => severity,
        };
        if selection.deny_warnings && severity == Severity::Warning {
            Some(Severity::Error)
        } else {
            Some(severity)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gcodec_source::codes;

    const CODE: &Code = codes::lower::NOT_LOWERED;

    fn level(rules: &[(Selector, RuleLevel)], selection: &Selection) -> Option<Severity> {
        Levels {
            rules,
            file_ignores: &[],
            selection,
        }
        .level(CODE, Severity::Warning)
    }

    #[test]
    fn a_code_rule_wins_over_an_area_rule_in_either_order() {
        let rules = [
            (Selector::Code(CODE), RuleLevel::Deny),
            (Selector::Area("lower"), RuleLevel::Allow),
        ];
        let none = Selection::default();
        assert_eq!(level(&rules, &none), Some(Severity::Error));
        let reversed = [rules[1], rules[0]];
        assert_eq!(level(&reversed, &none), Some(Severity::Error));
        assert_eq!(level(&rules[1..], &none), None);
    }

    #[test]
    fn select_ignore_and_deny_warnings_apply() {
        let only_parse = Selection {
            select: vec![Selector::Area("parse")],
            ..Selection::default()
        };
        assert_eq!(level(&[], &only_parse), None);
        let ignored = Selection {
            ignore: vec![Selector::Code(CODE)],
            ..Selection::default()
        };
        assert_eq!(level(&[], &ignored), None);
        let strict = Selection {
            deny_warnings: true,
            ..Selection::default()
        };
        assert_eq!(level(&[], &strict), Some(Severity::Error));
        let warned = [(Selector::Area("lower"), RuleLevel::Warn)];
        assert_eq!(
            level(&warned, &Selection::default()),
            Some(Severity::Warning)
        );
    }
}
