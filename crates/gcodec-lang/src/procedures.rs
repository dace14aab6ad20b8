//! The predefined procedures of the control (reference §7.6
//! "Procedures"; the names are the catalogue's `procedures.txt`) that a
//! call may name: they are no subprograms and are never looked up on the
//! search path. Each has its [`Effect`] on the channel, which says how
//! the run treats it, and the [`Arity`] lowering checks. `MSG` and
//! `STOPRE` are not listed: lowering makes them a message and a stop of
//! their own; nor are `RET` (a return) and `L` (the address of a call by
//! number).

use crate::names::name_table;

/// What a predefined procedure changes on the control, by kind: the run
/// executes [`Effect::Alarm`], passes [`Effect::None`] in silence (the
/// simulation is exact without it) and gives the others as advice that
/// names the effect it leaves out ([`Effect::left_out`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Effect {
    /// Nothing a simulation shows: single-block suppression, the
    /// preprocessing buffer, stop delays, interpolation cycles.
    None,
    /// Raises an alarm (`SETAL`): the run ends.
    Alarm,
    Interrupts,
    SynchronizedActions,
    Couplings,
    Transformations,
    Channels,
    Waits,
    GeometryAxes,
    Dynamics,
    Feed,
    Spindles,
    ToolManagement,
    ToolOffsets,
    Files,
    SearchPath,
    ExternalProgram,
    ProtectionZones,
    Retraction,
    Drives,
    ActualValues,
    Motion,
    MachineData,
    AuxiliaryFunctions,
    Hmi,
    ContourTables,
    Execute,
    Return,
}

impl Effect {
    /// What the control does and the simulation leaves out, as the
    /// advice's words after the procedure's name; `None` for
    /// [`Effect::None`] and [`Effect::Alarm`], which the run models.
    pub fn left_out(self) -> Option<&'static str> {
        Some(match self {
            Effect::None | Effect::Alarm => return None,
            Effect::Interrupts => "acts on interrupt routines; the simulation's inputs never fire",
            Effect::SynchronizedActions => {
                "acts on synchronized actions or technology cycles, which the simulation does not run"
            }
            Effect::Couplings => {
                "couples axes or spindles (coupled motion, gears, master values, curve tables, tangential control); the simulation moves each axis as programmed"
            }
            Effect::Transformations => {
                "switches a kinematic transformation; the simulation moves the axes as programmed, untransformed"
            }
            Effect::Channels => {
                "coordinates channels or exchanges axes between them; the simulation runs one channel with all its axes"
            }
            Effect::Waits => {
                "waits for positioning axes, spindles or encoders; the simulation does not wait"
            }
            Effect::GeometryAxes => {
                "assigns other channel axes to the geometry axes; the simulation keeps the profile's geometry axes"
            }
            Effect::Dynamics => {
                "changes acceleration, jerk or interpolation settings; the path and the time estimate do not use them"
            }
            Effect::Feed => {
                "changes which axes the feed applies to and how; the simulation keeps the path feed of the geometry axes"
            }
            Effect::Spindles => {
                "changes the master spindle or how a spindle is controlled; the simulation keeps its spindles as they are"
            }
            Effect::ToolManagement => {
                "acts on tool management, magazines or tool monitoring; the simulation keeps the tool table and leaves result variables unchanged"
            }
            Effect::ToolOffsets => {
                "changes tool offsets online; the simulation keeps the tool table's offsets"
            }
            Effect::Files => {
                "reads or writes files of the control; the simulation leaves result variables unchanged"
            }
            Effect::SearchPath => {
                "changes the search path for subprograms; the simulation searches its own path"
            }
            Effect::ExternalProgram => {
                "runs a program from external memory; the simulation does not run it"
            }
            Effect::ProtectionZones => {
                "defines or switches protection zones; the simulation checks none"
            }
            Effect::Retraction => {
                "prepares a retraction or stop for an alarm or power failure; nothing triggers it in the simulation"
            }
            Effect::Drives => {
                "reads or writes drive or safety parameters; the simulation leaves result variables unchanged"
            }
            Effect::ActualValues => {
                "sets the actual values of axes; the simulation keeps its positions"
            }
            Effect::Motion => {
                "deletes the distance to go or overlaid motion; the simulation runs each motion as programmed"
            }
            Effect::MachineData => {
                "activates changed machine data; the simulation keeps the profile's"
            }
            Effect::AuxiliaryFunctions => {
                "changes how auxiliary functions are output; the simulation outputs them as programmed"
            }
            Effect::Hmi => {
                "acts on the operator panel (dialogs, the workpiece shown); nothing of it shows in the simulation"
            }
            Effect::ContourTables => {
                "prepares or runs a contour table; the simulation does not build it"
            }
            Effect::Execute => "runs a string as a block; the simulation does not run it",
            Effect::Return => "ends the subprogram; the simulation goes on with the next block",
        })
    }
}

/// How many arguments a predefined procedure takes, where the
/// catalogue's signatures settle it; [`Arity::ANY`] where they do not.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Arity {
    /// The fewest arguments.
    pub min: u8,
    /// The most; `None` for no limit.
    pub max: Option<u8>,
}

impl Arity {
    /// Not checked.
    pub const ANY: Self = Self { min: 0, max: None };
    /// No arguments (`SBLOF`).
    pub const NONE: Self = Self::exactly(0);

    pub const fn exactly(n: u8) -> Self {
        Self::between(n, n)
    }

    pub const fn between(min: u8, max: u8) -> Self {
        Self {
            min,
            max: Some(max),
        }
    }

    /// Whether a call with `count` arguments fits.
    pub fn accepts(self, count: usize) -> bool {
        count >= usize::from(self.min) && self.max.is_none_or(|max| count <= usize::from(max))
    }
}

name_table! {
    /// A predefined procedure, by its place in [`PROCEDURES`].
    enum Procedure;
    /// The predefined procedures with their names, effects and arities,
    /// sorted by name.
    table PROCEDURES: (Effect, Arity);
    Activate "ACTIVATE", Effect::MachineData, Arity::ANY;
    Adisposa "ADISPOSA", Effect::Dynamics, Arity::ANY;
    Afisof "AFISOF", Effect::Dynamics, Arity::NONE;
    Afison "AFISON", Effect::Dynamics, Arity::NONE;
    Auxfudel "AUXFUDEL", Effect::AuxiliaryFunctions, Arity::ANY;
    Auxfudelg "AUXFUDELG", Effect::AuxiliaryFunctions, Arity::exactly(1);
    Auxfumseq "AUXFUMSEQ", Effect::AuxiliaryFunctions, Arity::ANY;
    Auxfusync "AUXFUSYNC", Effect::AuxiliaryFunctions, Arity::ANY;
    Axctswe "AXCTSWE", Effect::Channels, Arity::ANY;
    Axctswec "AXCTSWEC", Effect::Channels, Arity::ANY;
    Axctswed "AXCTSWED", Effect::Channels, Arity::ANY;
    Axtochan "AXTOCHAN", Effect::Channels, Arity::ANY;
    Briska "BRISKA", Effect::Dynamics, Arity::ANY;
    Cadaptof "CADAPTOF", Effect::Couplings, Arity::ANY;
    Cadapton "CADAPTON", Effect::Couplings, Arity::ANY;
    Callpath "CALLPATH", Effect::SearchPath, Arity::between(0, 1);
    Cancel "CANCEL", Effect::SynchronizedActions, Arity::ANY;
    Cancelsub "CANCELSUB", Effect::Interrupts, Arity::NONE;
    Chandata "CHANDATA", Effect::Channels, Arity::exactly(1);
    Clearm "CLEARM", Effect::Channels, Arity::ANY;
    Clrint "CLRINT", Effect::Interrupts, Arity::ANY;
    Contdcon "CONTDCON", Effect::ContourTables, Arity::ANY;
    Contpron "CONTPRON", Effect::ContourTables, Arity::ANY;
    Corrof "CORROF", Effect::Motion, Arity::ANY;
    Coupdef "COUPDEF", Effect::Couplings, Arity::ANY;
    Coupdel "COUPDEL", Effect::Couplings, Arity::ANY;
    Coupof "COUPOF", Effect::Couplings, Arity::ANY;
    Coupofs "COUPOFS", Effect::Couplings, Arity::ANY;
    Coupon "COUPON", Effect::Couplings, Arity::ANY;
    Couponc "COUPONC", Effect::Couplings, Arity::ANY;
    Coupres "COUPRES", Effect::Couplings, Arity::ANY;
    Cprot "CPROT", Effect::ProtectionZones, Arity::ANY;
    Cprotdef "CPROTDEF", Effect::ProtectionZones, Arity::ANY;
    Ctabdef "CTABDEF", Effect::Couplings, Arity::ANY;
    Ctabdel "CTABDEL", Effect::Couplings, Arity::ANY;
    Ctabend "CTABEND", Effect::Couplings, Arity::ANY;
    Ctablock "CTABLOCK", Effect::Couplings, Arity::ANY;
    Ctabunlock "CTABUNLOCK", Effect::Couplings, Arity::ANY;
    Delayfstof "DELAYFSTOF", Effect::None, Arity::NONE;
    Delayfston "DELAYFSTON", Effect::None, Arity::NONE;
    Deldtg "DELDTG", Effect::Motion, Arity::ANY;
    Delete "DELETE", Effect::Files, Arity::ANY;
    Delmt "DELMT", Effect::ToolManagement, Arity::ANY;
    Delt "DELT", Effect::ToolManagement, Arity::ANY;
    Deltc "DELTC", Effect::ToolManagement, Arity::between(1, 2);
    Disable "DISABLE", Effect::Interrupts, Arity::ANY;
    Drivea "DRIVEA", Effect::Dynamics, Arity::ANY;
    Drvprd "DRVPRD", Effect::Drives, Arity::ANY;
    Drvpwr "DRVPWR", Effect::Drives, Arity::ANY;
    Dzero "DZERO", Effect::ToolManagement, Arity::ANY;
    Egdef "EGDEF", Effect::Couplings, Arity::ANY;
    Egdel "EGDEL", Effect::Couplings, Arity::ANY;
    Egofc "EGOFC", Effect::Couplings, Arity::ANY;
    Egofs "EGOFS", Effect::Couplings, Arity::ANY;
    Egon "EGON", Effect::Couplings, Arity::ANY;
    Egonsyn "EGONSYN", Effect::Couplings, Arity::ANY;
    Egonsyne "EGONSYNE", Effect::Couplings, Arity::ANY;
    Enable "ENABLE", Effect::Interrupts, Arity::ANY;
    Esrr "ESRR", Effect::Retraction, Arity::ANY;
    Esrs "ESRS", Effect::Retraction, Arity::ANY;
    Execstring "EXECSTRING", Effect::Execute, Arity::exactly(1);
    Exectab "EXECTAB", Effect::ContourTables, Arity::ANY;
    Execute "EXECUTE", Effect::ContourTables, Arity::ANY;
    Extcall "EXTCALL", Effect::ExternalProgram, Arity::ANY;
    Extclose "EXTCLOSE", Effect::Files, Arity::ANY;
    Extopen "EXTOPEN", Effect::Files, Arity::ANY;
    Fctdef "FCTDEF", Effect::SynchronizedActions, Arity::ANY;
    Fgref "FGREF", Effect::Feed, Arity::ANY;
    Fgroup "FGROUP", Effect::Feed, Arity::ANY;
    Filedate "FILEDATE", Effect::Files, Arity::ANY;
    Fileinfo "FILEINFO", Effect::Files, Arity::ANY;
    Filesize "FILESIZE", Effect::Files, Arity::ANY;
    Filestat "FILESTAT", Effect::Files, Arity::ANY;
    Filetime "FILETIME", Effect::Files, Arity::ANY;
    Fpo "FPO", Effect::Feed, Arity::ANY;
    Fpr "FPR", Effect::Feed, Arity::ANY;
    Fpraof "FPRAOF", Effect::Feed, Arity::ANY;
    Fpraon "FPRAON", Effect::Feed, Arity::ANY;
    Ftoc "FTOC", Effect::ToolOffsets, Arity::ANY;
    Geoax "GEOAX", Effect::GeometryAxes, Arity::between(0, 6);
    Get "GET", Effect::Channels, Arity::ANY;
    Getd "GETD", Effect::Channels, Arity::ANY;
    Getexet "GETEXET", Effect::ToolManagement, Arity::ANY;
    Getfreeloc "GETFREELOC", Effect::ToolManagement, Arity::ANY;
    Getselt "GETSELT", Effect::ToolManagement, Arity::ANY;
    Gwpsof "GWPSOF", Effect::Spindles, Arity::ANY;
    Gwpson "GWPSON", Effect::Spindles, Arity::ANY;
    Icycof "ICYCOF", Effect::None, Arity::NONE;
    Icycon "ICYCON", Effect::None, Arity::NONE;
    Init "INIT", Effect::Channels, Arity::ANY;
    Ipobrka "IPOBRKA", Effect::Dynamics, Arity::ANY;
    Iptrlock "IPTRLOCK", Effect::None, Arity::NONE;
    Iptrunlock "IPTRUNLOCK", Effect::None, Arity::NONE;
    Jerka "JERKA", Effect::Dynamics, Arity::ANY;
    Leadof "LEADOF", Effect::Couplings, Arity::ANY;
    Leadon "LEADON", Effect::Couplings, Arity::ANY;
    Lock "LOCK", Effect::SynchronizedActions, Arity::ANY;
    Masldef "MASLDEF", Effect::Couplings, Arity::ANY;
    Masldel "MASLDEL", Effect::Couplings, Arity::ANY;
    Maslof "MASLOF", Effect::Couplings, Arity::ANY;
    Maslofs "MASLOFS", Effect::Couplings, Arity::ANY;
    Maslon "MASLON", Effect::Couplings, Arity::ANY;
    Mmc "MMC", Effect::Hmi, Arity::between(1, 2);
    Mvtool "MVTOOL", Effect::ToolManagement, Arity::ANY;
    Newconf "NEWCONF", Effect::MachineData, Arity::NONE;
    Nprot "NPROT", Effect::ProtectionZones, Arity::ANY;
    Nprotdef "NPROTDEF", Effect::ProtectionZones, Arity::ANY;
    Orireset "ORIRESET", Effect::Transformations, Arity::ANY;
    Polfa "POLFA", Effect::Retraction, Arity::ANY;
    Polfmask "POLFMASK", Effect::Retraction, Arity::ANY;
    Polfmlin "POLFMLIN", Effect::Retraction, Arity::ANY;
    Polypath "POLYPATH", Effect::Dynamics, Arity::ANY;
    Posm "POSM", Effect::ToolManagement, Arity::ANY;
    Posmt "POSMT", Effect::ToolManagement, Arity::ANY;
    Preseton "PRESETON", Effect::ActualValues, Arity::ANY;
    Presetons "PRESETONS", Effect::ActualValues, Arity::ANY;
    Prota "PROTA", Effect::ProtectionZones, Arity::ANY;
    Protd "PROTD", Effect::ProtectionZones, Arity::ANY;
    Prots "PROTS", Effect::ProtectionZones, Arity::ANY;
    Punchacc "PUNCHACC", Effect::Dynamics, Arity::ANY;
    Putftoc "PUTFTOC", Effect::ToolOffsets, Arity::ANY;
    Putftocf "PUTFTOCF", Effect::ToolOffsets, Arity::ANY;
    Rdisable "RDISABLE", Effect::None, Arity::NONE;
    Read "READ", Effect::Files, Arity::ANY;
    Release "RELEASE", Effect::Channels, Arity::ANY;
    Reset "RESET", Effect::SynchronizedActions, Arity::ANY;
    Resetmon "RESETMON", Effect::ToolManagement, Arity::ANY;
    Retb "RETB", Effect::Return, Arity::NONE;
    Sblof "SBLOF", Effect::None, Arity::NONE;
    Sblon "SBLON", Effect::None, Arity::NONE;
    Setal "SETAL", Effect::Alarm, Arity::between(1, 2);
    Setint "SETINT", Effect::Interrupts, Arity::ANY;
    Setm "SETM", Effect::Channels, Arity::ANY;
    Setms "SETMS", Effect::Spindles, Arity::ANY;
    Setmth "SETMTH", Effect::ToolManagement, Arity::ANY;
    Setpiece "SETPIECE", Effect::ToolManagement, Arity::ANY;
    Setta "SETTA", Effect::ToolManagement, Arity::ANY;
    Settia "SETTIA", Effect::ToolManagement, Arity::ANY;
    Sirelin "SIRELIN", Effect::Drives, Arity::ANY;
    Sirelout "SIRELOUT", Effect::Drives, Arity::ANY;
    Sireltime "SIRELTIME", Effect::Drives, Arity::ANY;
    Softa "SOFTA", Effect::Dynamics, Arity::ANY;
    Spcof "SPCOF", Effect::Spindles, Arity::ANY;
    Spcon "SPCON", Effect::Spindles, Arity::ANY;
    Splinepath "SPLINEPATH", Effect::Dynamics, Arity::ANY;
    Start "START", Effect::Channels, Arity::ANY;
    Startfifo "STARTFIFO", Effect::None, Arity::NONE;
    Stopfifo "STOPFIFO", Effect::None, Arity::NONE;
    Stopreof "STOPREOF", Effect::None, Arity::NONE;
    Synfct "SYNFCT", Effect::SynchronizedActions, Arity::ANY;
    Tang "TANG", Effect::Couplings, Arity::ANY;
    Tangdel "TANGDEL", Effect::Couplings, Arity::ANY;
    Tangof "TANGOF", Effect::Couplings, Arity::ANY;
    Tangon "TANGON", Effect::Couplings, Arity::ANY;
    Tca "TCA", Effect::ToolManagement, Arity::ANY;
    Tci "TCI", Effect::ToolManagement, Arity::ANY;
    Tlift "TLIFT", Effect::Couplings, Arity::ANY;
    Tml "TML", Effect::ToolManagement, Arity::ANY;
    Tmof "TMOF", Effect::ToolManagement, Arity::ANY;
    Tmon "TMON", Effect::ToolManagement, Arity::ANY;
    Toffof "TOFFOF", Effect::ToolOffsets, Arity::ANY;
    Toffon "TOFFON", Effect::ToolOffsets, Arity::ANY;
    Traang "TRAANG", Effect::Transformations, Arity::ANY;
    Tracon "TRACON", Effect::Transformations, Arity::ANY;
    Tracyl "TRACYL", Effect::Transformations, Arity::ANY;
    Trafoof "TRAFOOF", Effect::Transformations, Arity::NONE;
    Trafoon "TRAFOON", Effect::Transformations, Arity::ANY;
    Trailof "TRAILOF", Effect::Couplings, Arity::ANY;
    Trailon "TRAILON", Effect::Couplings, Arity::ANY;
    Transmit "TRANSMIT", Effect::Transformations, Arity::ANY;
    Traori "TRAORI", Effect::Transformations, Arity::ANY;
    Unlock "UNLOCK", Effect::SynchronizedActions, Arity::ANY;
    Waitc "WAITC", Effect::Channels, Arity::ANY;
    Waite "WAITE", Effect::Channels, Arity::ANY;
    Waitenc "WAITENC", Effect::Waits, Arity::ANY;
    Waitm "WAITM", Effect::Channels, Arity::ANY;
    Waitmc "WAITMC", Effect::Channels, Arity::ANY;
    Waitp "WAITP", Effect::Waits, Arity::ANY;
    Waits "WAITS", Effect::Waits, Arity::ANY;
    Workpiece "WORKPIECE", Effect::Hmi, Arity::ANY;
    Write "WRITE", Effect::Files, Arity::ANY;
    Wrtpr "WRTPR", Effect::Files, Arity::ANY;
}

impl Procedure {
    /// What it changes on the control.
    pub fn effect(self) -> Effect {
        PROCEDURES[self as usize].2
    }

    /// How many arguments it takes.
    pub fn arity(self) -> Arity {
        PROCEDURES[self as usize].3
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn procedure_table_is_sorted() {
        for pair in PROCEDURES.windows(2) {
            assert!(pair[0].1 < pair[1].1, "{} {}", pair[0].1, pair[1].1);
        }
        for (i, &(procedure, name, ..)) in PROCEDURES.iter().enumerate() {
            assert_eq!(procedure as usize, i, "{name}");
            assert_eq!(Procedure::named(name), Some(procedure));
            assert_eq!(procedure.name(), name);
        }
        assert_eq!(Procedure::named("setal"), Some(Procedure::Setal));
        for not in ["MSG", "STOPRE", "RET", "L", "CYCLE81", ""] {
            assert_eq!(Procedure::named(not), None, "{not}");
        }
    }

    #[test]
    fn effects_and_arities() {
        assert_eq!(Procedure::Sblof.effect(), Effect::None);
        assert_eq!(Procedure::Setal.effect(), Effect::Alarm);
        assert_eq!(Procedure::Geoax.effect(), Effect::GeometryAxes);
        assert!(Effect::None.left_out().is_none() && Effect::Alarm.left_out().is_none());
        assert!(
            Effect::GeometryAxes
                .left_out()
                .unwrap()
                .contains("geometry axes")
        );
        assert!(Procedure::Sblof.arity().accepts(0) && !Procedure::Sblof.arity().accepts(1));
        assert!(Procedure::Chandata.arity().accepts(1) && !Procedure::Chandata.arity().accepts(0));
        assert!(Procedure::Setal.arity().accepts(2) && !Procedure::Setal.arity().accepts(3));
        assert!(Arity::ANY.accepts(0) && Arity::ANY.accepts(200));
    }
}
