//! The programmable frame instructions (reference §9.2): `TRANS X10`,
//! `AROT RPL=45`, `MIRROR X0`. The syntax tree, the AIL and the executor
//! share this one set; in JSON an instruction is its keyword (`"ATRANS"`).

use crate::names::serde_as_text;

/// A programmable frame instruction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FrameOp {
    Trans,
    Atrans,
    Rot,
    Arot,
    Rots,
    Arots,
    Crots,
    Scale,
    Ascale,
    Mirror,
    Amirror,
}

impl FrameOp {
    /// Every frame instruction.
    pub const ALL: [FrameOp; 11] = [
        FrameOp::Trans,
        FrameOp::Atrans,
        FrameOp::Rot,
        FrameOp::Arot,
        FrameOp::Rots,
        FrameOp::Arots,
        FrameOp::Crots,
        FrameOp::Scale,
        FrameOp::Ascale,
        FrameOp::Mirror,
        FrameOp::Amirror,
    ];

    /// The instruction as the control spells it.
    pub const fn keyword(self) -> &'static str {
        match self {
            FrameOp::Trans => "TRANS",
            FrameOp::Atrans => "ATRANS",
            FrameOp::Rot => "ROT",
            FrameOp::Arot => "AROT",
            FrameOp::Rots => "ROTS",
            FrameOp::Arots => "AROTS",
            FrameOp::Crots => "CROTS",
            FrameOp::Scale => "SCALE",
            FrameOp::Ascale => "ASCALE",
            FrameOp::Mirror => "MIRROR",
            FrameOp::Amirror => "AMIRROR",
        }
    }

    /// The frame instruction named `name` (case-insensitive).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|op| op.keyword().eq_ignore_ascii_case(name))
    }

    /// `ATRANS`, `AROT`, `AROTS`, `ASCALE`, `AMIRROR`: act on the current
    /// frame; the others replace it.
    pub const fn is_additive(self) -> bool {
        matches!(
            self,
            FrameOp::Atrans | FrameOp::Arot | FrameOp::Arots | FrameOp::Ascale | FrameOp::Amirror
        )
    }

    /// `ROT`, `AROT`: the ones that take `RPL=`.
    pub const fn is_rotation(self) -> bool {
        matches!(self, FrameOp::Rot | FrameOp::Arot)
    }

    /// `ROTS`, `AROTS`, `CROTS`: rotations given by solid angles.
    pub const fn is_solid_angle(self) -> bool {
        matches!(self, FrameOp::Rots | FrameOp::Arots | FrameOp::Crots)
    }
}

serde_as_text!(
    FrameOp,
    |op| op.keyword(),
    FrameOp::from_name,
    "a frame instruction"
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keywords_read_back_in_any_case() {
        for op in FrameOp::ALL {
            assert_eq!(FrameOp::from_name(op.keyword()), Some(op));
            assert_eq!(
                FrameOp::from_name(&op.keyword().to_ascii_lowercase()),
                Some(op)
            );
            let json = serde_json::to_string(&op).unwrap();
            assert_eq!(json, format!("\"{}\"", op.keyword()));
            assert_eq!(serde_json::from_str::<FrameOp>(&json).unwrap(), op);
        }
        for not in ["G58", "G59", "", "TRANSX"] {
            assert_eq!(FrameOp::from_name(not), None, "{not}");
        }
        assert!(serde_json::from_str::<FrameOp>("\"G58\"").is_err());
        assert!(FrameOp::Atrans.is_additive() && !FrameOp::Trans.is_additive());
        assert!(FrameOp::Arot.is_rotation() && !FrameOp::Rots.is_rotation());
        assert!(FrameOp::Crots.is_solid_angle() && !FrameOp::Rot.is_solid_angle());
    }
}
