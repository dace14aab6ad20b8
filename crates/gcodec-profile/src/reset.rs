//! The modal G commands of a machine after a reset.

use gcodec_lang::ggroups;
use gcodec_lang::modal::GROUP_COUNT;

use crate::{Profile, group8_index};

/// The modal G commands after a reset, group `n` at `n - 1`: the registry's
/// defaults ([`ggroups::default_member`]), overridden by the profile's
/// `modal_defaults`; group 8 is the profile's `default_group8_offset` (the
/// selection lowering starts from for `work_offset`, per the work-offset
/// design) when that is a Group 8 code. `None` for non-modal and unassigned
/// groups.
pub fn reset_defaults(profile: &Profile) -> [Option<&'static str>; GROUP_COUNT] {
    let mut modal = [None; GROUP_COUNT];
    for (i, slot) in modal.iter_mut().enumerate() {
        *slot = ggroups::default_member(i as u8 + 1);
    }
    for (group, code) in &profile.modal_defaults {
        let lookup = ggroups::lookup(code.get_ref());
        if let (Ok(g), Some((found, index))) = (group.get_ref().parse::<u8>(), lookup) {
            // A profile `check_profile` rejects (a code of another group,
            // a non-modal group) changes nothing.
            if g == found && ggroups::is_modal(g) {
                modal[usize::from(g) - 1] = ggroups::member(g, index);
            }
        }
    }
    // Lowering tracks the Group 8 selection from this setting, so the
    // `group8_selected` of its `work_offset` instructions agree with it.
    let group8 = profile.work_offsets.default_group8_offset.get_ref();
    if let Some(uifr) = group8_index(group8) {
        modal[7] = ggroups::member(8, uifr + 1);
    }
    modal
}
