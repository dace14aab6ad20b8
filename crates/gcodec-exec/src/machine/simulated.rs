//! The machine `gcodec run` runs against.

use std::sync::Arc;

use gcodec_profile::Profile;

use super::Machine;

/// A machine that answers every call at once: M and H functions are
/// taken, waits take their time in the estimate only, a tool change is
/// made at once. Without a toolchanger in the profile, a run against it
/// is the run of a channel with no machine behind it.
pub struct SimulatedMachine {
    _profile: Arc<Profile>,
}

impl SimulatedMachine {
    pub fn new(profile: Arc<Profile>) -> Self {
        Self { _profile: profile }
    }
}

impl Machine for SimulatedMachine {}
