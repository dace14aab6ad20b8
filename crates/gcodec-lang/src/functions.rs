//! The predefined functions of the NC language (reference §7.6) and the
//! type of their results. In AIL JSON a function is its name (`"SIN"`).

use crate::DataType;
use crate::names::name_table;

name_table! {
    /// A predefined function, by its place in [`FUNCTIONS`].
    enum Function;
    /// Built-in functions with their names and result types, sorted by
    /// name.
    table FUNCTIONS: (DataType);
    Abs "ABS", DataType::Real;
    Acos "ACOS", DataType::Real;
    Asin "ASIN", DataType::Real;
    Atan2 "ATAN2", DataType::Real;
    Axname "AXNAME", DataType::Axis;
    Axstring "AXSTRING", DataType::String { length: None };
    Axtospi "AXTOSPI", DataType::Int;
    Bound "BOUND", DataType::Real;
    Btoi "BTOI", DataType::Int;
    Btor "BTOR", DataType::Real;
    Cfine "CFINE", DataType::Frame;
    Cmirror "CMIRROR", DataType::Frame;
    Cos "COS", DataType::Real;
    Crot "CROT", DataType::Frame;
    Crots "CROTS", DataType::Frame;
    Crpl "CRPL", DataType::Frame;
    Cscale "CSCALE", DataType::Frame;
    Ctrans "CTRANS", DataType::Frame;
    Exp "EXP", DataType::Real;
    Index "INDEX", DataType::Int;
    Invframe "INVFRAME", DataType::Frame;
    Isaxis "ISAXIS", DataType::Bool;
    Isfile "ISFILE", DataType::Bool;
    Isnumber "ISNUMBER", DataType::Bool;
    Isvar "ISVAR", DataType::Bool;
    Itob "ITOB", DataType::Bool;
    Itor "ITOR", DataType::Real;
    Ln "LN", DataType::Real;
    Match "MATCH", DataType::Int;
    Maxval "MAXVAL", DataType::Real;
    Meaframe "MEAFRAME", DataType::Frame;
    Mindex "MINDEX", DataType::Int;
    Minval "MINVAL", DataType::Real;
    Number "NUMBER", DataType::Real;
    Pot "POT", DataType::Real;
    Rindex "RINDEX", DataType::Int;
    Round "ROUND", DataType::Real;
    Roundup "ROUNDUP", DataType::Real;
    Rtob "RTOB", DataType::Bool;
    Rtoi "RTOI", DataType::Int;
    Sin "SIN", DataType::Real;
    Spi "SPI", DataType::Axis;
    Sprint "SPRINT", DataType::String { length: None };
    Sqrt "SQRT", DataType::Real;
    Strlen "STRLEN", DataType::Int;
    Substr "SUBSTR", DataType::String { length: None };
    Tan "TAN", DataType::Real;
    Tolower "TOLOWER", DataType::String { length: None };
    Toupper "TOUPPER", DataType::String { length: None };
    Trunc "TRUNC", DataType::Real;
}

impl Function {
    /// The type of the result.
    pub fn result_type(self) -> DataType {
        FUNCTIONS[self as usize].2
    }
}

/// The result type of a built-in function (reference §7.6), by name in
/// any case; `None` for functions whose type is not listed and for user
/// functions.
pub fn function_type(name: &str) -> Option<DataType> {
    Function::named(name).map(Function::result_type)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn function_table_is_sorted() {
        for pair in FUNCTIONS.windows(2) {
            assert!(pair[0].1 < pair[1].1, "{} {}", pair[0].1, pair[1].1);
        }
        for (i, &(function, name, _)) in FUNCTIONS.iter().enumerate() {
            assert_eq!(function as usize, i, "{name}");
            assert_eq!(Function::named(name), Some(function));
            assert_eq!(function.name(), name);
        }
        assert_eq!(function_type("sin"), Some(DataType::Real));
        assert_eq!(function_type("CTrans"), Some(DataType::Frame));
        assert_eq!(function_type("TRUNC"), Some(DataType::Real));
        assert_eq!(function_type("ABS"), Some(DataType::Real));
        assert_eq!(function_type("MYFUNC"), None);
        assert_eq!(Function::named("atan2"), Some(Function::Atan2));
    }
}
