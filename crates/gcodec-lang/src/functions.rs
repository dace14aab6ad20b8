//! The predefined functions of the NC language (reference §7.6; the
//! names are the catalogue's `functions.txt`) and the type of their
//! results. In AIL JSON a function is its name (`"SIN"`). The catalogue's
//! dimension modifiers (`IC`, `ACP`, …) are [`crate::DimensionMode`],
//! `QU` is read with the auxiliary function it modifies, and `SET` and
//! `REP` are keywords of array initialisation: none of them is listed.

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
    Addframe "ADDFRAME", DataType::Int;
    Asin "ASIN", DataType::Real;
    Atan2 "ATAN2", DataType::Real;
    Axname "AXNAME", DataType::Axis;
    Axstring "AXSTRING", DataType::String { length: None };
    Axtospi "AXTOSPI", DataType::Int;
    Bound "BOUND", DataType::Real;
    Btoi "BTOI", DataType::Int;
    Btor "BTOR", DataType::Real;
    Calcdat "CALCDAT", DataType::Bool;
    Calcposi "CALCPOSI", DataType::Int;
    Cfine "CFINE", DataType::Frame;
    Checksum "CHECKSUM", DataType::Int;
    Chkdm "CHKDM", DataType::Int;
    Chkdno "CHKDNO", DataType::Int;
    Cmirror "CMIRROR", DataType::Frame;
    Collpair "COLLPAIR", DataType::Int;
    Corrtc "CORRTC", DataType::Int;
    Corrtrafo "CORRTRAFO", DataType::Int;
    Cos "COS", DataType::Real;
    Crot "CROT", DataType::Frame;
    Crots "CROTS", DataType::Frame;
    Crpl "CRPL", DataType::Frame;
    Cscale "CSCALE", DataType::Frame;
    Ctab "CTAB", DataType::Real;
    Ctabexists "CTABEXISTS", DataType::Int;
    Ctabfno "CTABFNO", DataType::Int;
    Ctabfpol "CTABFPOL", DataType::Int;
    Ctabfseg "CTABFSEG", DataType::Int;
    Ctabid "CTABID", DataType::Int;
    Ctabinv "CTABINV", DataType::Real;
    Ctabislock "CTABISLOCK", DataType::Int;
    Ctabmemtyp "CTABMEMTYP", DataType::Int;
    Ctabmpol "CTABMPOL", DataType::Int;
    Ctabmseg "CTABMSEG", DataType::Int;
    Ctabno "CTABNO", DataType::Int;
    Ctabnomem "CTABNOMEM", DataType::Int;
    Ctabperiod "CTABPERIOD", DataType::Int;
    Ctabpol "CTABPOL", DataType::Int;
    Ctabpolid "CTABPOLID", DataType::Int;
    Ctabseg "CTABSEG", DataType::Int;
    Ctabsegid "CTABSEGID", DataType::Int;
    Ctabsev "CTABSEV", DataType::Real;
    Ctabssv "CTABSSV", DataType::Real;
    Ctabtep "CTABTEP", DataType::Real;
    Ctabtev "CTABTEV", DataType::Real;
    Ctabtmax "CTABTMAX", DataType::Real;
    Ctabtmin "CTABTMIN", DataType::Real;
    Ctabtsp "CTABTSP", DataType::Real;
    Ctabtsv "CTABTSV", DataType::Real;
    Ctrans "CTRANS", DataType::Frame;
    Deldl "DELDL", DataType::Int;
    Delmlowner "DELMLOWNER", DataType::Int;
    Delmlres "DELMLRES", DataType::Int;
    Delobj "DELOBJ", DataType::Int;
    Deltoolenv "DELTOOLENV", DataType::Int;
    Exp "EXP", DataType::Real;
    Getactt "GETACTT", DataType::Int;
    Getacttd "GETACTTD", DataType::Int;
    Getdno "GETDNO", DataType::Int;
    Gett "GETT", DataType::Int;
    Gettcor "GETTCOR", DataType::Int;
    Gettenv "GETTENV", DataType::Int;
    Getvarap "GETVARAP", DataType::Int;
    Getvardft "GETVARDFT", DataType::Int;
    Getvardim "GETVARDIM", DataType::Int;
    Getvarlim "GETVARLIM", DataType::Int;
    Getvarphu "GETVARPHU", DataType::Int;
    Getvartyp "GETVARTYP", DataType::Int;
    Gp "GP", DataType::Real;
    Index "INDEX", DataType::Int;
    Intersec "INTERSEC", DataType::Bool;
    Invframe "INVFRAME", DataType::Frame;
    Isaxis "ISAXIS", DataType::Bool;
    Isfile "ISFILE", DataType::Bool;
    Isnumber "ISNUMBER", DataType::Bool;
    Isvar "ISVAR", DataType::Bool;
    Itob "ITOB", DataType::Bool;
    Itor "ITOR", DataType::Real;
    Lentoax "LENTOAX", DataType::Int;
    Ln "LN", DataType::Real;
    Match "MATCH", DataType::Int;
    Maxval "MAXVAL", DataType::Real;
    Meaframe "MEAFRAME", DataType::Frame;
    Measure "MEASURE", DataType::Int;
    Mindex "MINDEX", DataType::Int;
    Minval "MINVAL", DataType::Real;
    Modaxval "MODAXVAL", DataType::Real;
    Nametoint "NAMETOINT", DataType::Int;
    Newmt "NEWMT", DataType::Int;
    Newt "NEWT", DataType::Int;
    Number "NUMBER", DataType::Real;
    Orisolh "ORISOLH", DataType::Int;
    Pm "PM", DataType::Real;
    Posrange "POSRANGE", DataType::Bool;
    Pot "POT", DataType::Real;
    Pr "PR", DataType::Real;
    Protd "PROTD", DataType::Int;
    Rindex "RINDEX", DataType::Int;
    Round "ROUND", DataType::Real;
    Roundup "ROUNDUP", DataType::Real;
    Rtob "RTOB", DataType::Bool;
    Rtoi "RTOI", DataType::Int;
    Setdno "SETDNO", DataType::Int;
    Settcor "SETTCOR", DataType::Int;
    Sin "SIN", DataType::Real;
    Sirelay "SIRELAY", DataType::Int;
    Spi "SPI", DataType::Axis;
    Sprint "SPRINT", DataType::String { length: None };
    Sqrt "SQRT", DataType::Real;
    Stringis "STRINGIS", DataType::Int;
    Strlen "STRLEN", DataType::Int;
    Substr "SUBSTR", DataType::String { length: None };
    Tan "TAN", DataType::Real;
    Tolower "TOLOWER", DataType::String { length: None };
    Toolenv "TOOLENV", DataType::Int;
    Toolgnt "TOOLGNT", DataType::Int;
    Toolgt "TOOLGT", DataType::Int;
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
