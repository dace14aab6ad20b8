//! The data types of the NC language (reference §7.1) and the conversions
//! between them. The one type lowering checks, the AIL carries and the
//! executor declares variables with; in AIL JSON it is its text
//! (`INT`, `STRING[12]`).

use std::fmt;

use crate::names::serde_as_text;

/// The longest string a `STRING` variable holds without a length (a
/// local `STRING[200]`, reference §7.1), and the longest length a
/// declaration may give.
pub const MAX_STRING_LEN: u16 = 200;

/// A declared data type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DataType {
    Int,
    Real,
    Bool,
    Char,
    /// `STRING[n]`; `length` is `None` where it is not a constant (or the
    /// type of a computed string).
    String {
        length: Option<u32>,
    },
    Axis,
    Frame,
}

impl DataType {
    /// The keyword (`STRING` without its length).
    pub const fn keyword(self) -> &'static str {
        match self {
            DataType::Int => "INT",
            DataType::Real => "REAL",
            DataType::Bool => "BOOL",
            DataType::Char => "CHAR",
            DataType::String { .. } => "STRING",
            DataType::Axis => "AXIS",
            DataType::Frame => "FRAME",
        }
    }

    /// The type as written in a message and in AIL (`STRING[12]`).
    pub fn describe(self) -> String {
        self.to_string()
    }

    /// A type as [`describe`](Self::describe) writes it, in any case:
    /// `INT`, `STRING`, `STRING[12]`; `None` for another text and for a
    /// length of 0.
    pub fn parse(text: &str) -> Option<Self> {
        let text = text.trim();
        let is = |k: &str| text.eq_ignore_ascii_case(k);
        Some(match text {
            _ if is("INT") => Self::Int,
            _ if is("REAL") => Self::Real,
            _ if is("BOOL") => Self::Bool,
            _ if is("CHAR") => Self::Char,
            _ if is("AXIS") => Self::Axis,
            _ if is("FRAME") => Self::Frame,
            _ if is("STRING") => Self::String { length: None },
            _ if text.len() > 6
                && text.is_char_boundary(6)
                && text[..6].eq_ignore_ascii_case("STRING") =>
            {
                let length = text[6..]
                    .trim()
                    .strip_prefix('[')?
                    .strip_suffix(']')?
                    .trim()
                    .parse::<u32>()
                    .ok()
                    .filter(|&n| n >= 1)?;
                Self::String {
                    length: Some(length),
                }
            }
            _ => return None,
        })
    }

    /// The characters a variable of this type holds when it is a
    /// `STRING`: its length, [`MAX_STRING_LEN`] where it has none; `None`
    /// for a length above [`MAX_STRING_LEN`], which the control cannot
    /// declare, and for the other types.
    pub fn string_capacity(self) -> Option<u16> {
        match self {
            DataType::String { length: None } => Some(MAX_STRING_LEN),
            DataType::String { length: Some(n) } => u16::try_from(n)
                .ok()
                .filter(|n| (1..=MAX_STRING_LEN).contains(n)),
            _ => None,
        }
    }

    /// Whether the control can declare a variable of this type: any but a
    /// `STRING` longer than [`MAX_STRING_LEN`].
    pub fn is_declarable(self) -> bool {
        !matches!(self, DataType::String { .. }) || self.string_capacity().is_some()
    }

    /// Whether a value of type `self` may be assigned to a variable of
    /// type `to`: the conversion table of the control (alarm 14096, "illegal
    /// type conversion", Siemens diagnostics manual; reference §7.1).
    ///
    /// REAL, INT, BOOL and CHAR convert into each other; CHAR and STRING
    /// into STRING; STRING into BOOL (empty is FALSE) and CHAR (one
    /// character, checked by the caller for constants); AXIS and FRAME only
    /// into themselves. Nothing numeric converts into STRING, AXIS or
    /// FRAME.
    pub fn converts_to(self, to: DataType) -> bool {
        use DataType::*;
        match (self, to) {
            (Axis, Axis) | (Frame, Frame) => true,
            (Axis | Frame, _) | (_, Axis | Frame) => false,
            (String { .. }, Int | Real) => false,
            (Int | Real | Bool, String { .. }) => false,
            _ => true,
        }
    }

    /// "a" or "an" before the keyword.
    pub const fn article(self) -> &'static str {
        match self {
            DataType::Int | DataType::Axis => "an",
            _ => "a",
        }
    }

    /// INT or REAL.
    pub const fn is_number(self) -> bool {
        matches!(self, DataType::Int | DataType::Real)
    }
}

impl fmt::Display for DataType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DataType::String { length: Some(n) } => write!(f, "STRING[{n}]"),
            other => f.write_str(other.keyword()),
        }
    }
}

serde_as_text!(DataType, |t| t, DataType::parse, "a data type");

#[cfg(test)]
mod tests {
    use super::*;
    use DataType::*;

    #[test]
    fn conversions_follow_the_control() {
        let s = String { length: None };
        assert!(Int.converts_to(Real) && Real.converts_to(Int) && Real.converts_to(Bool));
        assert!(Char.converts_to(s) && s.converts_to(Bool) && s.converts_to(Char));
        assert!(!s.converts_to(Real) && !Real.converts_to(s) && !Bool.converts_to(s));
        assert!(!Real.converts_to(Axis) && !Axis.converts_to(Real) && Axis.converts_to(Axis));
        assert!(!Frame.converts_to(Real) && Frame.converts_to(Frame) && !Int.converts_to(Frame));
    }

    #[test]
    fn the_text_reads_back() {
        for ty in [
            Int,
            Real,
            Bool,
            Char,
            Axis,
            Frame,
            String { length: None },
            String { length: Some(1) },
            String { length: Some(12) },
            String {
                length: Some(u32::MAX),
            },
        ] {
            assert_eq!(DataType::parse(&ty.describe()), Some(ty), "{ty:?}");
            let json = serde_json::to_string(&ty).unwrap();
            assert_eq!(json, format!("\"{}\"", ty.describe()));
            assert_eq!(serde_json::from_str::<DataType>(&json).unwrap(), ty);
        }
        assert_eq!(
            DataType::parse(" string [ 5 ] "),
            Some(String { length: Some(5) })
        );
        assert_eq!(DataType::parse("real"), Some(Real));
        for bad in [
            "STRING[0]",
            "STRING[-1]",
            "STRING[",
            "STRINGX",
            "DOUBLE",
            "",
            "STRINGÄ",
        ] {
            assert_eq!(DataType::parse(bad), None, "{bad}");
        }
        assert!(serde_json::from_str::<DataType>("\"DOUBLE\"").is_err());
    }

    #[test]
    fn string_capacity_is_the_length_the_control_allows() {
        assert_eq!(
            String { length: None }.string_capacity(),
            Some(MAX_STRING_LEN)
        );
        assert_eq!(String { length: Some(12) }.string_capacity(), Some(12));
        assert_eq!(String { length: Some(200) }.string_capacity(), Some(200));
        assert_eq!(String { length: Some(201) }.string_capacity(), None);
        assert_eq!(Int.string_capacity(), None);
        assert!(Int.is_declarable());
        assert!(String { length: Some(200) }.is_declarable());
        assert!(!String { length: Some(201) }.is_declarable());
    }
}
