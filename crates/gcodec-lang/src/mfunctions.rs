//! M functions (the M-function design): the classes, and the class and timing
//! the control gives a predefined M function. A machine's own classes
//! (`mcode_class_overrides`) come from its profile (`gcodec_profile::m_class`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// M-function classes (the M-function design).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MClass {
    ProgramFlow,
    Spindle,
    Tool,
    Gearbox,
    Custom,
}

/// The built-in class of a predefined M function, `None` for the others;
/// `change_m` is the machine's tool-change M function (M6 by default).
pub fn standard_class(value: u32, change_m: u32) -> Option<MClass> {
    Some(match value {
        0 | 1 | 2 | 17 | 30 => MClass::ProgramFlow,
        3 | 4 | 5 | 19 | 70 => MClass::Spindle,
        40..=45 => MClass::Gearbox,
        v if v == change_m => MClass::Tool,
        _ => return None,
    })
}

/// The largest M value (reference §4.2: an INT at the interface).
pub const MAX_M_VALUE: u32 = 2_147_483_647;

/// `M0 M1 M2 M17 M30` act after the block's motion (the M-function design).
pub fn acts_after_motion(value: u32) -> bool {
    matches!(value, 0 | 1 | 2 | 17 | 30)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standard_classes() {
        assert_eq!(standard_class(30, 6), Some(MClass::ProgramFlow));
        assert_eq!(standard_class(70, 6), Some(MClass::Spindle));
        assert_eq!(standard_class(42, 6), Some(MClass::Gearbox));
        assert_eq!(standard_class(6, 6), Some(MClass::Tool));
        assert_eq!(standard_class(6, 66), None);
        assert_eq!(standard_class(66, 66), Some(MClass::Tool));
        assert_eq!(standard_class(8, 6), None);
    }

    #[test]
    fn the_program_flow_functions_act_after_motion() {
        let after: Vec<u32> = (0..100).filter(|&v| acts_after_motion(v)).collect();
        assert_eq!(after, [0, 1, 2, 17, 30]);
    }
}
