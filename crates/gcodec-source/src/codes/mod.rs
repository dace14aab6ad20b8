//! The registry of diagnostic codes: one definition per code, and every
//! diagnostic is built from one of them.
//!
//! A code is `gcodec::AREA::NAME`, with its default level, a one-line
//! summary, an explanation (the markdown file `codes/AREA/NAME.md`, with
//! a wrong and a right example where a short program can show it) and the
//! control's alarm number where there is one. Each area is one file of
//! this module that declares its codes with `codes!`, so a code cannot
//! be declared without being listed, and its name and explanation file
//! cannot drift apart. `gcodec explain` and `docs/diagnostics.md` are
//! made from it ([`explain`], [`list`], [`reference()`]).

mod text;

pub mod check;
pub mod config;
pub mod definitions;
pub mod io;
pub mod lint;
pub mod lower;
pub mod parse;
pub mod profile;
pub mod run;
pub mod scenario;

use std::fmt;
use std::sync::LazyLock;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::Severity;

pub use text::{explain, list, reference};

/// One diagnostic code and its documentation.
#[derive(PartialEq, Eq, Hash)]
pub struct Code {
    name: &'static str,
    level: Severity,
    summary: &'static str,
    explanation: &'static str,
    alarm: Option<u32>,
    scope: Option<Scope>,
}

/// What a code's check looks at: what `gcodec explain` says of a rule so
/// that a user knows which findings a check without `--run` can make.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scope {
    /// The text of the file, block by block and as a whole (parsing,
    /// lowering, a profile, a configuration).
    Text,
    /// Every path through the program, followed without running it
    /// (the `lint` rules of `gcodec check` that follow the program's
    /// jumps and structures).
    Paths,
    /// Only the path a run takes (`gcodec run`, `gcodec check --run`):
    /// values known when the block runs.
    Run,
}

impl Scope {
    /// How `gcodec explain` says it.
    pub const fn description(self) -> &'static str {
        match self {
            Scope::Text => "looks at the text of the file",
            Scope::Paths => "looks at every path through the program",
            Scope::Run => "looks only at the path a run takes (`gcodec run`, `gcodec check --run`)",
        }
    }
}

impl Code {
    /// The stable name, `gcodec::AREA::NAME`: tools and CI scripts may
    /// match on it.
    pub const fn name(&self) -> &'static str {
        self.name
    }

    /// The area, the middle part of the name (`parse`).
    pub fn area(&self) -> &'static str {
        self.short_name()
            .split_once("::")
            .map_or("", |(area, _)| area)
    }

    /// The name without its `gcodec::` prefix (`parse::unclosed_structure`).
    pub fn short_name(&self) -> &'static str {
        self.name.strip_prefix("gcodec::").unwrap_or(self.name)
    }

    /// The last part of the name (`unclosed_structure`).
    pub fn bare_name(&self) -> &'static str {
        self.name.rsplit("::").next().unwrap_or(self.name)
    }

    /// The level a diagnostic with this code has unless a profile policy
    /// decides otherwise.
    pub const fn level(&self) -> Severity {
        self.level
    }

    /// One line saying what the code reports.
    pub const fn summary(&self) -> &'static str {
        self.summary
    }

    /// The explanation, markdown: what the code means, why it is reported,
    /// how to fix it, and its examples.
    pub const fn explanation(&self) -> &'static str {
        self.explanation
    }

    /// The alarm number the control shows for this problem, where there
    /// is one.
    pub const fn alarm(&self) -> Option<u32> {
        self.alarm
    }

    /// What the check behind the code looks at: a code's own where it
    /// names one, else its area's (the run's codes look at the path a run
    /// takes, the others at the text).
    pub fn scope(&self) -> Scope {
        self.scope.unwrap_or(if self.area() == "run" {
            Scope::Run
        } else {
            Scope::Text
        })
    }
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name)
    }
}

/// Debug-printed as its name in quotes, as the string it replaces was, so
/// test output and debug dumps name codes the same way.
impl fmt::Debug for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.name, f)
    }
}

impl PartialEq<str> for Code {
    fn eq(&self, other: &str) -> bool {
        self.name == other
    }
}

impl PartialEq<&str> for Code {
    fn eq(&self, other: &&str) -> bool {
        self.name == *other
    }
}

/// A code is written as its name, so JSON output names codes as strings.
impl Serialize for Code {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name)
    }
}

/// A code is read from its full name; a name the registry lacks is an
/// error.
impl<'de> Deserialize<'de> for &'static Code {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = <std::borrow::Cow<'de, str>>::deserialize(deserializer)?;
        all()
            .iter()
            .copied()
            .find(|code| code.name == name)
            .ok_or_else(|| serde::de::Error::custom(format!("`{name}` is not a gcodec code")))
    }
}

/// The codes of one area, in the order they are declared.
#[derive(Debug)]
pub struct Area {
    /// `parse`, `lower`, …
    pub name: &'static str,
    /// What the area's codes are about, one line.
    pub title: &'static str,
    /// Its codes.
    pub codes: &'static [&'static Code],
}

/// Every area, in pipeline order.
pub fn areas() -> &'static [Area] {
    const AREAS: &[Area] = &[
        parse::AREA,
        definitions::AREA,
        profile::AREA,
        scenario::AREA,
        config::AREA,
        check::AREA,
        lower::AREA,
        lint::AREA,
        run::AREA,
        io::AREA,
    ];
    AREAS
}

/// Every code, area by area.
pub fn all() -> &'static [&'static Code] {
    static ALL: LazyLock<Vec<&'static Code>> = LazyLock::new(|| {
        areas()
            .iter()
            .flat_map(|area| area.codes.iter().copied())
            .collect()
    });
    &ALL
}

/// The code a user names: its full name (`gcodec::parse::invalid_word`),
/// its name without `gcodec::` (`parse::invalid_word`), or its last part
/// alone (`invalid_word`) where no other area has a code of that name.
/// Case and blanks around it do not matter.
pub fn find(name: &str) -> Option<&'static Code> {
    let name = name.trim().to_ascii_lowercase();
    let mut by_bare = all().iter().copied().filter(|c| c.bare_name() == name);
    if let Some(code) = all()
        .iter()
        .copied()
        .find(|c| c.name == name || c.short_name() == name)
    {
        return Some(code);
    }
    match (by_bare.next(), by_bare.next()) {
        (Some(code), None) => Some(code),
        _ => None,
    }
}

/// The code a misspelt name most likely means, compared in the form it is
/// written in (full, `area::name` or the last part alone); `None` when
/// nothing is close.
pub fn suggest(name: &str) -> Option<&'static Code> {
    let name = name.trim().to_ascii_lowercase();
    let form = |code: &'static Code| {
        if name.starts_with("gcodec::") {
            code.name
        } else if name.contains("::") {
            code.short_name()
        } else {
            code.bare_name()
        }
    };
    let nearest = crate::nearest(&name, all().iter().map(|code| form(code)))?;
    all().iter().copied().find(|code| form(code) == nearest)
}

/// Declares an area's codes: one `pub const UPPER_NAME: &Code` per code
/// and the area's list, `AREA`. A code's name is `gcodec::AREA::name`, its
/// explanation the file `AREA/name.md` beside this module.
///
/// ```text
/// codes! {
///     "parse", "the syntax of a part program";
///     UNCLOSED_STRUCTURE = unclosed_structure, Error, "…";
///     JUMP_TARGET_NOT_FOUND = jump_target_not_found, Error, alarm 14080, "…";
///     UNREACHABLE_CODE = unreachable_code, Warning, scope Paths, "…";
/// }
/// ```
macro_rules! codes {
    (
        $area:literal, $title:literal;
        $( $constant:ident = $name:ident, $level:ident $(, alarm $alarm:literal)? $(, scope $scope:ident)?, $summary:literal; )+
    ) => {
        use $crate::Severity;
        #[allow(unused_imports)]
        use super::{Area, Code, Scope};

        $(
            #[doc = $summary]
            pub const $constant: &Code = &Code {
                name: concat!("gcodec::", $area, "::", stringify!($name)),
                level: Severity::$level,
                summary: $summary,
                explanation: include_str!(concat!($area, "/", stringify!($name), ".md")),
                // The alarm if one is given, else `None`.
                alarm: [$(Some($alarm),)? None][0],
                scope: [$(Some(Scope::$scope),)? None][0],
            };
        )+

        /// This area and its codes.
        pub const AREA: Area = Area {
            name: $area,
            title: $title,
            codes: &[$($constant),+],
        };
    };
}
use codes;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_well_formed() {
        let mut seen = std::collections::HashSet::new();
        for code in all() {
            assert!(seen.insert(code.name()), "{code} is declared twice");
            let parts: Vec<_> = code.name().split("::").collect();
            assert_eq!(parts.len(), 3, "{code}");
            assert_eq!(parts[0], "gcodec");
            assert!(
                parts[2]
                    .bytes()
                    .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_'),
                "{code}"
            );
        }
    }

    #[test]
    fn summaries_are_one_line_and_explanations_have_no_heading_on_top() {
        for code in all() {
            assert!(
                !code.summary().is_empty() && !code.summary().contains('\n'),
                "{code}"
            );
            assert!(
                !code.summary().ends_with('.'),
                "{code}: a summary is no sentence"
            );
            let first = code.explanation().lines().next().unwrap_or("");
            assert!(!first.is_empty() && !first.starts_with('#'), "{code}");
        }
    }

    #[test]
    fn find_takes_the_full_the_short_and_a_unique_bare_name() {
        let code = parse::UNCLOSED_STRUCTURE;
        assert_eq!(find("gcodec::parse::unclosed_structure"), Some(code));
        assert_eq!(find("parse::unclosed_structure"), Some(code));
        assert_eq!(find(" Unclosed_Structure "), Some(code));
        // `type_mismatch` is a code of lowering and of the run.
        assert_eq!(find("type_mismatch"), None);
        assert_eq!(find("run::type_mismatch"), Some(run::TYPE_MISMATCH));
        assert_eq!(find("gcodec::parse::nothing"), None);
    }

    #[test]
    fn suggest_finds_a_misspelt_name_in_the_form_it_is_written() {
        assert_eq!(
            suggest("unclosed_structur"),
            Some(parse::UNCLOSED_STRUCTURE)
        );
        assert_eq!(
            suggest("gcodec::parse::unclosed_structures"),
            Some(parse::UNCLOSED_STRUCTURE)
        );
        assert_eq!(suggest("run::division_by_zer"), Some(run::DIVISION_BY_ZERO));
        assert_eq!(suggest("qqqqqqqq"), None);
    }

    #[test]
    fn a_code_serialises_as_its_name_and_reads_back() {
        let json = serde_json::to_string(parse::INVALID_WORD).expect("serialises");
        assert_eq!(json, "\"gcodec::parse::invalid_word\"");
        let back: &Code = serde_json::from_str(&json).expect("reads back");
        assert_eq!(back, parse::INVALID_WORD);
        assert!(serde_json::from_str::<&Code>("\"gcodec::parse::nothing\"").is_err());
    }
}
