//! The dimension modifiers of one value (reference §2.5): `AC(…)`,
//! `IC(…)`, the rotary, indexing and diameter forms.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A dimension modifier written on one value (`X=AC(10)`, `C=ACP(90)`),
/// as the control spells it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "UPPERCASE")]
pub enum DimensionMode {
    /// Absolute for this value.
    Ac,
    /// Incremental for this value.
    Ic,
    /// Rotary axis: absolute, the shorter way.
    Dc,
    /// Rotary axis: absolute, in the positive direction.
    Acp,
    /// Rotary axis: absolute, in the negative direction.
    Acn,
    /// Indexing positions: absolute, incremental, shorter way, positive,
    /// negative direction.
    Cac,
    Cic,
    Cdc,
    Cacp,
    Cacn,
    /// Diameter (`DAC`, `DIC`) or radius (`RAC`, `RIC`), absolute or
    /// incremental.
    Dac,
    Dic,
    Rac,
    Ric,
}

impl DimensionMode {
    /// Every modifier.
    pub const ALL: [DimensionMode; 14] = {
        use DimensionMode::*;
        [
            Ac, Ic, Dc, Acp, Acn, Cac, Cic, Cdc, Cacp, Cacn, Dac, Dic, Rac, Ric,
        ]
    };

    /// The modifier as the control spells it.
    pub const fn keyword(self) -> &'static str {
        use DimensionMode::*;
        match self {
            Ac => "AC",
            Ic => "IC",
            Dc => "DC",
            Acp => "ACP",
            Acn => "ACN",
            Cac => "CAC",
            Cic => "CIC",
            Cdc => "CDC",
            Cacp => "CACP",
            Cacn => "CACN",
            Dac => "DAC",
            Dic => "DIC",
            Rac => "RAC",
            Ric => "RIC",
        }
    }

    /// The modifier named `name` (case-insensitive).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|k| k.keyword().eq_ignore_ascii_case(name))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keywords_are_the_serde_names() {
        for mode in DimensionMode::ALL {
            let json = serde_json::to_string(&mode).unwrap();
            assert_eq!(json, format!("\"{}\"", mode.keyword()));
            assert_eq!(
                DimensionMode::from_name(&mode.keyword().to_ascii_lowercase()),
                Some(mode)
            );
        }
        assert_eq!(DimensionMode::from_name("ACC"), None);
    }
}
