//! Addresses: the letters of DIN words and the named addresses
//! (reference §2.2, §2.6, §2.7, §3.3) with what each one is: a setting
//! the executor interprets (`SPOS`, `FA[X]`, `OVR`), part of the block's
//! motion (`AP`, `AX[X]`, `CHF`, `PW`) or the additive tool offset `DL`.
//! In JSON a named address is its name (`"SPOS"`).

use crate::names::serde_as_text;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::names::name_table;

/// An upper-case ASCII letter as a string (`?` for any other byte).
pub fn letter_str(letter: u8) -> &'static str {
    const LETTERS: &str = "ABCDEFGHIJKLMNOPQRSTUVWXYZ";
    match letter {
        b'A'..=b'Z' => {
            let i = usize::from(letter - b'A');
            &LETTERS[i..i + 1]
        }
        _ => "?",
    }
}

/// How long an address's value holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum AddressScope {
    /// Until programmed again (`FA`, `OVR`, `LIMS`, `RNDM`, `SD`).
    Modal,
    /// This block only (`FB`, `SPOS`, `POS`, `FP`).
    Block,
}

/// Which transition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TransitionKind {
    /// `CHF=`: chamfer, the value is the chamfer's length.
    Chamfer,
    /// `CHR=`: chamfer, the value is the leg length in the direction of
    /// motion.
    ChamferLeg,
    /// `RND=`: rounding with this radius.
    Rounding,
}

/// What a setting takes in brackets (or digits) besides its value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Operand {
    /// Nothing: `OVR=50`, `MEAS=1`.
    None,
    /// An axis: `FA[X]=400`, `OS[X]=1`.
    Axis,
    /// A spindle number: `SPOS[2]=`, `SPOS2=`.
    Spindle,
    /// Optionally a number: `TOFFL[1]=`, `IP[2]=`.
    Number,
    /// A number, then an axis: `FMA[2,X]=`.
    NumberAxis,
    /// The following axis, then the leading axis (generic coupling):
    /// `CPLNUM[X,Y]=`.
    AxisPair,
}

/// What a named address is and where its value goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AddressRole {
    /// A setting the executor interprets, with what it takes in
    /// brackets.
    Setting {
        scope: AddressScope,
        operand: Operand,
    },
    /// Part of the end point of the block's motion: `AP`, `RP`, `ANG`.
    Target,
    /// `AX[axis]=`: an axis target named in brackets.
    IndirectAxis,
    /// `CHF=`, `CHR=`, `RND=`: the transition at the end of the contour
    /// element.
    Transition(TransitionKind),
    /// `PW=`: the spline's point weight.
    Weight,
    /// `PL=`: the spline's parameter interval length.
    Interval,
    /// `DL=`: the additive tool offset, which acts with the cutting edge.
    AdditiveOffset,
}

const fn setting(scope: AddressScope, operand: Operand) -> AddressRole {
    AddressRole::Setting { scope, operand }
}

use AddressScope::{Block as B, Modal as M};
use Operand::{Axis, AxisPair, Number, NumberAxis, Spindle};

name_table! {
    /// A named address, by its place in [`NAMED_ADDRESSES`].
    enum NamedAddress;
    /// The named addresses with their names and roles, sorted by name:
    /// every address of the control's catalogue but the letters of DIN
    /// words (`F`, `I1`, `A2`, …), the circle data `CR`, `AR`, `TURN`, the
    /// frame instructions' `RPL`, the polynomial coefficients `PO` and
    /// `SETINT`'s `PRIO` (`tests/catalogue.rs` lists them with reasons).
    table NAMED_ADDRESSES: (AddressRole);
    Acc "ACC", setting(M, Axis);
    Acclima "ACCLIMA", setting(M, Axis);
    Adis "ADIS", setting(M, Operand::None);
    Adispos "ADISPOS", setting(M, Operand::None);
    Alf "ALF", setting(M, Operand::None);
    Ang "ANG", AddressRole::Target;
    Ap "AP", AddressRole::Target;
    Atol "ATOL", setting(M, Axis);
    Ax "AX", AddressRole::IndirectAxis;
    Chf "CHF", AddressRole::Transition(TransitionKind::Chamfer);
    Chr "CHR", AddressRole::Transition(TransitionKind::ChamferLeg);
    Coarsea "COARSEA", setting(M, Axis);
    Cpbc "CPBC", setting(M, Axis);
    Cpdef "CPDEF", setting(M, Operand::None);
    Cpdel "CPDEL", setting(M, Operand::None);
    Cpfmof "CPFMOF", setting(M, Axis);
    Cpfmon "CPFMON", setting(M, Axis);
    Cpfmson "CPFMSON", setting(M, Axis);
    Cpfpos "CPFPOS", setting(M, Axis);
    Cpfrs "CPFRS", setting(M, Axis);
    Cpla "CPLA", setting(M, Axis);
    Cplctid "CPLCTID", setting(M, AxisPair);
    Cpldef "CPLDEF", setting(M, Axis);
    Cpldel "CPLDEL", setting(M, Axis);
    Cplden "CPLDEN", setting(M, AxisPair);
    Cplinsc "CPLINSC", setting(M, AxisPair);
    Cplintr "CPLINTR", setting(M, AxisPair);
    Cplnum "CPLNUM", setting(M, AxisPair);
    Cplof "CPLOF", setting(M, Axis);
    Cplon "CPLON", setting(M, Axis);
    Cploutsc "CPLOUTSC", setting(M, AxisPair);
    Cplouttr "CPLOUTTR", setting(M, AxisPair);
    Cplpos "CPLPOS", setting(M, AxisPair);
    Cplsetval "CPLSETVAL", setting(M, AxisPair);
    Cpmalarm "CPMALARM", setting(M, Axis);
    Cpmbrake "CPMBRAKE", setting(M, Axis);
    Cpmprt "CPMPRT", setting(M, Axis);
    Cpmreset "CPMRESET", setting(M, Axis);
    Cpmstart "CPMSTART", setting(M, Axis);
    Cpmvdi "CPMVDI", setting(M, Axis);
    Cpof "CPOF", setting(M, Operand::None);
    Cpon "CPON", setting(M, Operand::None);
    Cpres "CPRES", setting(M, Operand::None);
    Cpsettype "CPSETTYPE", setting(M, Axis);
    Cpsyncop "CPSYNCOP", setting(M, Axis);
    Cpsyncop2 "CPSYNCOP2", setting(M, Axis);
    Cpsyncov "CPSYNCOV", setting(M, Axis);
    Cpsynfip "CPSYNFIP", setting(M, Axis);
    Cpsynfip2 "CPSYNFIP2", setting(M, Axis);
    Cpsynfiv "CPSYNFIV", setting(M, Axis);
    Ctol "CTOL", setting(M, Operand::None);
    Ctolg0 "CTOLG0", setting(M, Operand::None);
    Cutmod "CUTMOD", setting(M, Operand::None);
    Cutmodk "CUTMODK", setting(M, Operand::None);
    Diacycofa "DIACYCOFA", setting(M, Axis);
    Diam90a "DIAM90A", setting(M, Axis);
    Diamchan "DIAMCHAN", setting(M, Operand::None);
    Diamchana "DIAMCHANA", setting(M, Axis);
    Diamofa "DIAMOFA", setting(M, Axis);
    Diamona "DIAMONA", setting(M, Axis);
    Dilf "DILF", setting(M, Operand::None);
    Disc "DISC", setting(M, Operand::None);
    Discl "DISCL", setting(B, Operand::None);
    Dispr "DISPR", setting(B, Operand::None);
    Disr "DISR", setting(B, Operand::None);
    Disrp "DISRP", setting(B, Operand::None);
    Dite "DITE", setting(M, Operand::None);
    Dits "DITS", setting(M, Operand::None);
    Dl "DL", AddressRole::AdditiveOffset;
    Fa "FA", setting(M, Axis);
    Fad "FAD", setting(B, Operand::None);
    Fb "FB", setting(B, Operand::None);
    Fd "FD", setting(B, Operand::None);
    Fda "FDA", setting(B, Axis);
    Fgref "FGREF", setting(M, Axis);
    Finea "FINEA", setting(M, Axis);
    Fl "FL", setting(M, Axis);
    Flim "FLIM", setting(M, Operand::None);
    Fma "FMA", setting(B, NumberAxis);
    Foc "FOC", setting(B, Axis);
    Focof "FOCOF", setting(M, Axis);
    Focon "FOCON", setting(M, Axis);
    Fp "FP", setting(B, Operand::None);
    Frc "FRC", setting(B, Operand::None);
    Frcm "FRCM", setting(M, Operand::None);
    Fxs "FXS", setting(M, Axis);
    Fxst "FXST", setting(M, Axis);
    Fxsw "FXSW", setting(M, Axis);
    Fz "FZ", setting(M, Operand::None);
    Ip "IP", setting(B, Number);
    Ipoenda "IPOENDA", setting(M, Axis);
    Ir "IR", setting(B, Operand::None);
    Isd "ISD", setting(M, Operand::None);
    Jerklim "JERKLIM", setting(M, Axis);
    Jerklima "JERKLIMA", setting(M, Axis);
    Jr "JR", setting(B, Operand::None);
    Kr "KR", setting(B, Operand::None);
    Lead "LEAD", setting(M, Operand::None);
    Lims "LIMS", setting(M, Operand::None);
    Meac "MEAC", setting(B, Axis);
    Meas "MEAS", setting(B, Operand::None);
    Measa "MEASA", setting(B, Axis);
    Meaw "MEAW", setting(B, Operand::None);
    Meawa "MEAWA", setting(B, Axis);
    Mov "MOV", setting(M, Axis);
    Movt "MOVT", setting(B, Operand::None);
    Offn "OFFN", setting(M, Operand::None);
    Oma1 "OMA1", setting(M, Operand::None);
    Oma2 "OMA2", setting(M, Operand::None);
    Oma3 "OMA3", setting(M, Operand::None);
    Oma4 "OMA4", setting(M, Operand::None);
    Oma5 "OMA5", setting(M, Operand::None);
    Oris "ORIS", setting(M, Operand::None);
    Os "OS", setting(M, Axis);
    Osb "OSB", setting(M, Axis);
    Oscill "OSCILL", setting(M, Axis);
    Osctrl "OSCTRL", setting(M, Axis);
    Ose "OSE", setting(M, Axis);
    Osnsc "OSNSC", setting(M, Axis);
    Osp1 "OSP1", setting(M, Axis);
    Osp2 "OSP2", setting(M, Axis);
    Ost1 "OST1", setting(M, Axis);
    Ost2 "OST2", setting(M, Axis);
    Otol "OTOL", setting(M, Operand::None);
    Otolg0 "OTOLG0", setting(M, Operand::None);
    Ovr "OVR", setting(M, Operand::None);
    Ovra "OVRA", setting(M, Axis);
    Ovrrap "OVRRAP", setting(M, Operand::None);
    Pacclim "PACCLIM", setting(M, Operand::None);
    Pl "PL", AddressRole::Interval;
    Polf "POLF", setting(M, Axis);
    Pos "POS", setting(B, Axis);
    Posa "POSA", setting(B, Axis);
    Posp "POSP", setting(B, Axis);
    Pw "PW", AddressRole::Weight;
    Rnd "RND", AddressRole::Transition(TransitionKind::Rounding);
    Rndm "RNDM", setting(M, Operand::None);
    Rp "RP", AddressRole::Target;
    Scc "SCC", setting(M, Axis);
    Scpara "SCPARA", setting(M, Axis);
    Sd "SD", setting(M, Operand::None);
    Sf "SF", setting(M, Operand::None);
    Spn "SPN", setting(B, Operand::None);
    Spos "SPOS", setting(B, Spindle);
    Sposa "SPOSA", setting(B, Spindle);
    Spp "SPP", setting(B, Operand::None);
    Sr "SR", setting(M, Operand::None);
    Sra "SRA", setting(M, Axis);
    St "ST", setting(M, Operand::None);
    Sta "STA", setting(M, Axis);
    Stat "STAT", setting(B, Operand::None);
    Stolf "STOLF", setting(M, Operand::None);
    Svc "SVC", setting(M, Operand::None);
    Tcarr "TCARR", setting(M, Operand::None);
    Theta "THETA", setting(B, Operand::None);
    Tilt "TILT", setting(B, Operand::None);
    Toff "TOFF", setting(M, Axis);
    Toffl "TOFFL", setting(M, Number);
    Tofflr "TOFFLR", setting(M, Operand::None);
    Toffr "TOFFR", setting(M, Operand::None);
    Tu "TU", setting(B, Operand::None);
    Velolim "VELOLIM", setting(M, Axis);
    Velolima "VELOLIMA", setting(M, Axis);
}

impl NamedAddress {
    /// What the address is.
    pub fn role(self) -> AddressRole {
        NAMED_ADDRESSES[self as usize].2
    }
}

/// Whether the parser reads `name=value` as an address word rather than
/// an assignment: the named addresses of [`WRITTEN_AS_WORDS`], plus the
/// circle data `AR`, `CR`, `TURN`, the polynomial coefficients `PO` and
/// the frame instructions' `RPL`. Case is ignored. The other named
/// addresses (`FAD`, `MEAS`, `OS[X]`, `FMA[2,X]`) stay assignments in the
/// syntax tree, which keeps what a program may declare as a variable of
/// its own (`DEF REAL OSE`); lowering resolves them as addresses.
pub fn is_written_as_address(name: &str) -> bool {
    const OTHER_ADDRESS_WORDS: [&str; 5] = ["AR", "CR", "PO", "RPL", "TURN"];
    match NamedAddress::named(name) {
        Some(address) => WRITTEN_AS_WORDS.contains(&address),
        None => OTHER_ADDRESS_WORDS
            .iter()
            .any(|n| n.eq_ignore_ascii_case(name)),
    }
}

/// The named addresses the parser reads as words (`FA[X]=400`, `SPOS=90`).
pub const WRITTEN_AS_WORDS: [NamedAddress; 32] = {
    use NamedAddress::*;
    [
        Acc, Adis, Adispos, Ang, Ap, Ax, Chf, Chr, Disc, Dite, Dits, Dl, Fa, Fb, Fl, Fp, Fz, Lims,
        Offn, Ovr, Ovra, Pl, Pos, Posa, Pw, Rnd, Rndm, Rp, Sd, Sf, Spos, Sposa,
    ]
};

serde_as_text!(
    NamedAddress,
    |a| a.name(),
    NamedAddress::named,
    "a named address"
);

#[cfg(test)]
mod tests {

    #[test]
    fn the_words_written_as_addresses_are_the_parsers() {
        // The parser's list before the vocabulary held it: the tree must
        // not change.
        let parsers = [
            "ACC", "ADIS", "ADISPOS", "ANG", "AP", "AR", "AX", "CHF", "CHR", "CR", "DISC", "DITE",
            "DITS", "DL", "FA", "FB", "FL", "FP", "FZ", "LIMS", "OFFN", "OVR", "OVRA", "PL", "PO",
            "POS", "POSA", "PW", "RND", "RNDM", "RP", "RPL", "SD", "SF", "SPOS", "SPOSA", "TURN",
        ];
        for name in parsers {
            assert!(is_written_as_address(name), "{name}");
            assert!(is_written_as_address(&name.to_ascii_lowercase()), "{name}");
        }
        for name in [
            "DISCL", "DISR", "FAD", "MEAS", "OS", "FMA", "R1", "X", "DEPTH",
        ] {
            assert!(!is_written_as_address(name), "{name}");
        }
    }
    use super::*;

    #[test]
    fn letters_are_themselves() {
        for letter in b'A'..=b'Z' {
            assert_eq!(letter_str(letter), (letter as char).to_string());
        }
        assert_eq!(letter_str(b'a'), "?");
        assert_eq!(letter_str(b'1'), "?");
    }

    #[test]
    fn named_addresses_are_sorted_and_read_back() {
        for pair in NAMED_ADDRESSES.windows(2) {
            assert!(pair[0].1 < pair[1].1, "{} {}", pair[0].1, pair[1].1);
        }
        for (i, &(address, name, role)) in NAMED_ADDRESSES.iter().enumerate() {
            assert_eq!(address as usize, i, "{name}");
            assert_eq!(NamedAddress::named(name), Some(address));
            assert_eq!(
                NamedAddress::named(&name.to_ascii_lowercase()),
                Some(address)
            );
            assert_eq!(address.role(), role);
            let json = serde_json::to_string(&address).unwrap();
            assert_eq!(json, format!("\"{name}\""));
            assert_eq!(
                serde_json::from_str::<NamedAddress>(&json).unwrap(),
                address
            );
        }
        for not in ["CR", "RPL", "PO", "X", ""] {
            assert_eq!(NamedAddress::named(not), None, "{not}");
        }
        assert!(serde_json::from_str::<NamedAddress>("\"TURN\"").is_err());
    }
}
