//! The class of an M function on one machine: its profile's
//! `mcode_class_overrides` over the control's standard classes.

use gcodec_lang::MClass;
use gcodec_lang::mfunctions::standard_class;

use crate::Profile;

/// The class of the M function `value` on the machine `profile` describes: its
/// `mcode_class_overrides` first, then the predefined classes (the M-function
/// design); `None` for a value the machine does not know. For values computed
/// when a block runs (lowering classifies constants with the overrides read
/// once).
pub fn m_class(profile: &Profile, value: u32) -> Option<MClass> {
    profile
        .m_functions
        .mcode_class_overrides
        .iter()
        .find(|(k, _)| k.get_ref().parse::<u32>() == Ok(value))
        .map(|(_, class)| *class)
        .or_else(|| standard_class(value, *profile.tool_change.change_m_code.get_ref()))
}
