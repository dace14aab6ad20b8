//! What a rule level, `--select` or `--ignore` names: one diagnostic code
//! or a whole area of them.

use gcodec_source::{Code, codes};

/// One code (`gcodec::lower::unknown_m_function`, written in any form
/// [`codes::find`] takes) or an area (`gcodec::lower::*`, `lower::*`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Selector {
    Code(&'static Code),
    Area(&'static str),
}

impl Selector {
    /// Reads a selector; one that names nothing is a message saying so,
    /// with the code or area meant where one is close.
    pub fn parse(text: &str) -> Result<Self, String> {
        let trimmed = text.trim().to_ascii_lowercase();
        if let Some(written) = trimmed.strip_suffix("::*") {
            let parts: Vec<&str> = written.split("::").collect();
            let area = match parts[..] {
                [area] | ["gcodec", area] => area,
                _ => written,
            };
            let names = codes::areas().iter().map(|a| a.name);
            if let Some(found) = codes::areas().iter().find(|a| a.name == area) {
                return Ok(Self::Area(found.name));
            }
            let hint = gcodec_source::nearest(area, names)
                .map(|meant| format!("; did you mean `gcodec::{meant}::*`?"))
                .unwrap_or_default();
            return Err(format!("`{text}` names no area of diagnostic codes{hint}"));
        }
        if let Some(code) = codes::find(&trimmed) {
            return Ok(Self::Code(code));
        }
        let several: Vec<&str> = (codes::all().iter())
            .filter(|code| code.bare_name() == trimmed)
            .map(|code| code.name())
            .collect();
        if several.len() > 1 {
            return Err(format!(
                "`{text}` names a code of several areas; name one in full: `{}`",
                several.join("`, `")
            ));
        }
        let hint = codes::suggest(&trimmed)
            .map(|meant| format!("; did you mean `{meant}`?"))
            .unwrap_or_default();
        Err(format!(
            "`{text}` is not a diagnostic code (a whole area is written `gcodec::AREA::*`){hint}"
        ))
    }

    /// Whether diagnostics with `code` are selected.
    pub fn matches(self, code: &'static Code) -> bool {
        match self {
            Self::Code(selected) => selected == code,
            Self::Area(area) => code.area() == area,
        }
    }

    /// A code is more specific than an area: its rule level wins.
    pub(super) fn is_code(self) -> bool {
        matches!(self, Self::Code(_))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_code_in_any_form_and_an_area_parse() {
        let code = codes::lower::NOT_LOWERED;
        assert_eq!(
            Selector::parse("gcodec::lower::not_lowered"),
            Ok(Selector::Code(code))
        );
        assert_eq!(
            Selector::parse("lower::not_lowered"),
            Ok(Selector::Code(code))
        );
        assert_eq!(
            Selector::parse("gcodec::lower::*"),
            Ok(Selector::Area("lower"))
        );
        assert_eq!(Selector::parse("Lower::*"), Ok(Selector::Area("lower")));
        assert!(Selector::parse("x::lower::*").is_err());
        assert!(Selector::Area("lower").matches(code));
        assert!(!Selector::Area("parse").matches(code));
    }

    #[test]
    fn a_name_of_nothing_says_what_was_meant() {
        let error = Selector::parse("lower::not_lowerd").expect_err("no such code");
        assert!(
            error.contains("did you mean `gcodec::lower::not_lowered`"),
            "{error}"
        );
        let error = Selector::parse("unknown_m_function").expect_err("two areas have it");
        assert!(
            error
                .contains("`gcodec::lower::unknown_m_function`, `gcodec::run::unknown_m_function`"),
            "{error}"
        );
        let error = Selector::parse("gcodec::lowr::*").expect_err("no such area");
        assert!(error.contains("did you mean `gcodec::lower::*`"), "{error}");
    }
}
