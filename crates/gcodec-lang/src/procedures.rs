//! The predefined procedures of the control (reference §7.6
//! "Procedures") that a call may name: they are no subprograms and are
//! never looked up on the search path. `MSG` and `STOPRE` are not
//! listed: lowering makes them a message and a stop of their own.

use crate::names::name_table;

name_table! {
    /// A predefined procedure, by its place in [`PROCEDURES`].
    enum Procedure;
    /// The predefined procedures with their names, sorted by name.
    table PROCEDURES: ();
    Activate "ACTIVATE";
    Cancel "CANCEL";
    Clearm "CLEARM";
    Contdcon "CONTDCON";
    Contpron "CONTPRON";
    Corrof "CORROF";
    Coupdel "COUPDEL";
    Coupof "COUPOF";
    Coupon "COUPON";
    Cprot "CPROT";
    Cprotdef "CPROTDEF";
    Ctabdef "CTABDEF";
    Ctabend "CTABEND";
    Deldtg "DELDTG";
    Delete "DELETE";
    Egofc "EGOFC";
    Egofs "EGOFS";
    Egon "EGON";
    Execstring "EXECSTRING";
    Exectab "EXECTAB";
    Fgref "FGREF";
    Fgroup "FGROUP";
    Get "GET";
    Getd "GETD";
    Leadof "LEADOF";
    Leadon "LEADON";
    Newconf "NEWCONF";
    Nprot "NPROT";
    Nprotdef "NPROTDEF";
    Preseton "PRESETON";
    Presetons "PRESETONS";
    Prota "PROTA";
    Protd "PROTD";
    Putftoc "PUTFTOC";
    Putftocf "PUTFTOCF";
    Read "READ";
    Release "RELEASE";
    Setal "SETAL";
    Setm "SETM";
    Setms "SETMS";
    Setpiece "SETPIECE";
    Spcof "SPCOF";
    Spcon "SPCON";
    Startfifo "STARTFIFO";
    Stopfifo "STOPFIFO";
    Tangof "TANGOF";
    Tangon "TANGON";
    Toffof "TOFFOF";
    Toffon "TOFFON";
    Traang "TRAANG";
    Tracyl "TRACYL";
    Trafoof "TRAFOOF";
    Transmit "TRANSMIT";
    Traori "TRAORI";
    Waitc "WAITC";
    Waite "WAITE";
    Waitm "WAITM";
    Waitmc "WAITMC";
    Waitp "WAITP";
    Waits "WAITS";
    Write "WRITE";
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn procedure_table_is_sorted() {
        for pair in PROCEDURES.windows(2) {
            assert!(pair[0].1 < pair[1].1, "{} {}", pair[0].1, pair[1].1);
        }
        for (i, &(procedure, name)) in PROCEDURES.iter().enumerate() {
            assert_eq!(procedure as usize, i, "{name}");
            assert_eq!(Procedure::named(name), Some(procedure));
            assert_eq!(procedure.name(), name);
        }
        assert_eq!(Procedure::named("setal"), Some(Procedure::Setal));
        for not in ["MSG", "STOPRE", "CYCLE81", ""] {
            assert_eq!(Procedure::named(not), None, "{not}");
        }
    }
}
