//! The settable work offsets of Group 8 (`G500`, `G54`…`G57`,
//! `G505`…`G599`) by their number, and their index in `$P_UIFR`: the
//! control counts `G500` as 0, `G54`…`G57` as 1…4 and `G505`…`G599` as
//! 5…99. In JSON a code is its lower-case spelling of the work-offset
//! design (`"g54"`).

use std::borrow::Cow;
use std::fmt;

use crate::names::serde_as_text;
use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};

/// A Group 8 command by its number (`G54` is 54, `G505` is 505). Every member
/// of group 8 is `G` and a number, so the number is the whole identity; in JSON
/// it is the lower-case code of the work-offset design (`"g54"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct WorkOffsetCode(pub u16);

impl WorkOffsetCode {
    /// `G500`: no settable work offset.
    pub const G500: Self = Self(500);
    /// `G54`.
    pub const G54: Self = Self(54);

    /// Reads `G54`, `g54`, `G505`; `None` for anything else.
    pub fn parse(code: &str) -> Option<Self> {
        let digits = code.strip_prefix(['g', 'G'])?;
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        digits.parse().ok().map(Self)
    }

    /// The code of `$P_UIFR` index `index` (`0` → `G500`, `1` → `G54`,
    /// `5` → `G505`); `None` above 99.
    pub const fn of_index(index: u8) -> Option<Self> {
        match index {
            0 => Some(Self::G500),
            1..=4 => Some(Self(53 + index as u16)),
            5..=99 => Some(Self(500 + index as u16)),
            _ => None,
        }
    }

    /// The `$P_UIFR` index of the code (`G54` → 1); `None` where the number
    /// is no Group 8 command.
    pub const fn index(self) -> Option<u8> {
        match self.0 {
            500 => Some(0),
            n @ 54..=57 => Some((n - 53) as u8),
            n @ 505..=599 => Some((n - 500) as u8),
            _ => None,
        }
    }
}

impl fmt::Display for WorkOffsetCode {
    /// The work-offset design's spelling: `g54`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "g{}", self.0)
    }
}

serde_as_text!(
    WorkOffsetCode,
    |c| c,
    WorkOffsetCode::parse,
    "a Group 8 code like `g54`"
);

impl JsonSchema for WorkOffsetCode {
    fn schema_name() -> Cow<'static, str> {
        "WorkOffsetCode".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "A Group 8 command in lower case: `g500`, `g54`…`g57`, `g505`…`g599`.",
            "type": "string",
            "pattern": "^g[0-9]+$",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_follow_p_uifr() {
        assert_eq!(WorkOffsetCode::G500.index(), Some(0));
        assert_eq!(WorkOffsetCode::G54.index(), Some(1));
        assert_eq!(WorkOffsetCode(57).index(), Some(4));
        assert_eq!(WorkOffsetCode(505).index(), Some(5));
        assert_eq!(WorkOffsetCode(599).index(), Some(99));
        for not in [0, 53, 58, 504, 600] {
            assert_eq!(WorkOffsetCode(not).index(), None, "{not}");
        }
        for i in 0..100 {
            let code = WorkOffsetCode::of_index(i).unwrap();
            assert_eq!(code.index(), Some(i), "{code}");
        }
        assert_eq!(WorkOffsetCode::of_index(100), None);
    }

    #[test]
    fn the_text_is_lower_case() {
        let code = WorkOffsetCode(505);
        assert_eq!(serde_json::to_string(&code).unwrap(), "\"g505\"");
        assert_eq!(
            serde_json::from_str::<WorkOffsetCode>("\"G505\"").unwrap(),
            code
        );
        assert!(serde_json::from_str::<WorkOffsetCode>("\"g5x\"").is_err());
    }
}
