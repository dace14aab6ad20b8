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

/// What a named address is and where its value goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AddressRole {
    /// A setting the executor interprets; `axis`: written `NAME[axis]=`;
    /// `spindle`: takes a spindle number (`SPOS[2]=`).
    Setting {
        scope: AddressScope,
        axis: bool,
        spindle: bool,
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

const fn setting(scope: AddressScope, axis: bool, spindle: bool) -> AddressRole {
    AddressRole::Setting {
        scope,
        axis,
        spindle,
    }
}

use AddressScope::{Block as B, Modal as M};

name_table! {
    /// A named address, by its place in [`NAMED_ADDRESSES`].
    enum NamedAddress;
    /// The named addresses with their names and roles, sorted by name.
    /// `CR`, `AR`, `TURN` are circle data and `RPL` belongs to the frame
    /// instructions; `PO[…]` is not listed.
    table NAMED_ADDRESSES: (AddressRole);
    Acc "ACC", setting(M, true, false);
    Adis "ADIS", setting(M, false, false);
    Adispos "ADISPOS", setting(M, false, false);
    Ang "ANG", AddressRole::Target;
    Ap "AP", AddressRole::Target;
    Ax "AX", AddressRole::IndirectAxis;
    Chf "CHF", AddressRole::Transition(TransitionKind::Chamfer);
    Chr "CHR", AddressRole::Transition(TransitionKind::ChamferLeg);
    Disc "DISC", setting(M, false, false);
    Discl "DISCL", setting(B, false, false);
    Disr "DISR", setting(B, false, false);
    Dite "DITE", setting(M, false, false);
    Dits "DITS", setting(M, false, false);
    Dl "DL", AddressRole::AdditiveOffset;
    Fa "FA", setting(M, true, false);
    Fad "FAD", setting(B, false, false);
    Fb "FB", setting(B, false, false);
    Fl "FL", setting(M, true, false);
    Fp "FP", setting(B, false, false);
    Fz "FZ", setting(M, false, false);
    Lims "LIMS", setting(M, false, false);
    Offn "OFFN", setting(M, false, false);
    Ovr "OVR", setting(M, false, false);
    Ovra "OVRA", setting(M, true, false);
    Pl "PL", AddressRole::Interval;
    Pos "POS", setting(B, true, false);
    Posa "POSA", setting(B, true, false);
    Pw "PW", AddressRole::Weight;
    Rnd "RND", AddressRole::Transition(TransitionKind::Rounding);
    Rndm "RNDM", setting(M, false, false);
    Rp "RP", AddressRole::Target;
    Sd "SD", setting(M, false, false);
    Sf "SF", setting(M, false, false);
    Spos "SPOS", setting(B, false, true);
    Sposa "SPOSA", setting(B, false, true);
}

impl NamedAddress {
    /// What the address is.
    pub fn role(self) -> AddressRole {
        NAMED_ADDRESSES[self as usize].2
    }
}

/// Whether the parser reads `name=value` as an address word rather than
/// an assignment: the named addresses but `DISCL`, `DISR` and `FAD`, which
/// the syntax tree keeps as assignments (lowering resolves them as
/// addresses), plus the circle data `AR`, `CR`, `TURN`, the polynomial
/// coefficients `PO` and the frame instructions' `RPL`. Case is ignored.
pub fn is_written_as_address(name: &str) -> bool {
    const READ_AS_ASSIGNMENTS: [NamedAddress; 3] =
        [NamedAddress::Discl, NamedAddress::Disr, NamedAddress::Fad];
    const OTHER_ADDRESS_WORDS: [&str; 5] = ["AR", "CR", "PO", "RPL", "TURN"];
    match NamedAddress::named(name) {
        Some(address) => !READ_AS_ASSIGNMENTS.contains(&address),
        None => OTHER_ADDRESS_WORDS
            .iter()
            .any(|n| n.eq_ignore_ascii_case(name)),
    }
}

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
        let others = NAMED_ADDRESSES
            .iter()
            .map(|e| e.1)
            .filter(|n| !parsers.contains(n));
        assert_eq!(others.collect::<Vec<_>>(), ["DISCL", "DISR", "FAD"]);
        for name in ["DISCL", "DISR", "FAD", "R1", "X", "DEPTH"] {
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
