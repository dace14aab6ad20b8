//! The predefined functions of the NC language (reference §7.6) and the
//! type of their results.

use crate::DataType;
use crate::names::compare_ignore_case;

/// Built-in functions and their result types, sorted by name for binary
/// search (a test keeps it so).
pub const FUNCTIONS: &[(&str, DataType)] = &[
    ("ABS", DataType::Real),
    ("ACOS", DataType::Real),
    ("ASIN", DataType::Real),
    ("ATAN2", DataType::Real),
    ("AXNAME", DataType::Axis),
    ("AXSTRING", DataType::String { length: None }),
    ("AXTOSPI", DataType::Int),
    ("BOUND", DataType::Real),
    ("BTOI", DataType::Int),
    ("BTOR", DataType::Real),
    ("CFINE", DataType::Frame),
    ("CMIRROR", DataType::Frame),
    ("COS", DataType::Real),
    ("CROT", DataType::Frame),
    ("CROTS", DataType::Frame),
    ("CRPL", DataType::Frame),
    ("CSCALE", DataType::Frame),
    ("CTRANS", DataType::Frame),
    ("EXP", DataType::Real),
    ("INDEX", DataType::Int),
    ("INVFRAME", DataType::Frame),
    ("ISAXIS", DataType::Bool),
    ("ISFILE", DataType::Bool),
    ("ISNUMBER", DataType::Bool),
    ("ISVAR", DataType::Bool),
    ("ITOB", DataType::Bool),
    ("ITOR", DataType::Real),
    ("LN", DataType::Real),
    ("MATCH", DataType::Int),
    ("MAXVAL", DataType::Real),
    ("MEAFRAME", DataType::Frame),
    ("MINDEX", DataType::Int),
    ("MINVAL", DataType::Real),
    ("NUMBER", DataType::Real),
    ("POT", DataType::Real),
    ("RINDEX", DataType::Int),
    ("ROUND", DataType::Real),
    ("ROUNDUP", DataType::Real),
    ("RTOB", DataType::Bool),
    ("RTOI", DataType::Int),
    ("SIN", DataType::Real),
    ("SPI", DataType::Axis),
    ("SPRINT", DataType::String { length: None }),
    ("SQRT", DataType::Real),
    ("STRLEN", DataType::Int),
    ("SUBSTR", DataType::String { length: None }),
    ("TAN", DataType::Real),
    ("TOLOWER", DataType::String { length: None }),
    ("TOUPPER", DataType::String { length: None }),
    ("TRUNC", DataType::Real),
];

/// The result type of a built-in function (reference §7.6), by name in
/// any case; `None` for functions whose type is not listed and for user
/// functions.
pub fn function_type(name: &str) -> Option<DataType> {
    FUNCTIONS
        .binary_search_by(|(entry, _)| compare_ignore_case(entry, name))
        .ok()
        .map(|i| FUNCTIONS[i].1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn function_table_is_sorted() {
        for pair in FUNCTIONS.windows(2) {
            assert!(pair[0].0 < pair[1].0, "{} {}", pair[0].0, pair[1].0);
        }
        assert_eq!(function_type("sin"), Some(DataType::Real));
        assert_eq!(function_type("CTrans"), Some(DataType::Frame));
        assert_eq!(function_type("TRUNC"), Some(DataType::Real));
        assert_eq!(function_type("ABS"), Some(DataType::Real));
        assert_eq!(function_type("MYFUNC"), None);
    }
}
