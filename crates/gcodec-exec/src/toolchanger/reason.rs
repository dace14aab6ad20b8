//! Why the executor's side aborts ([`AbortReason`], LinuxCNC's numbers and
//! gcodec's own above 101) and what a changer's fault reason means
//! ([`FaultReason`]: above 0 soft, 0 and below hard).

use std::fmt;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The reason of an abort, as the changer reads it on `emc-reason`.
/// LinuxCNC's numbers (`EMC_IO_ABORT_REASON_ENUM`) where it has one;
/// gcodec's own above 101. The default, 0, is the `emc-reason` pin
/// before any abort.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(transparent)]
pub struct AbortReason(pub i32);

impl AbortReason {
    /// An execution error of the run (an alarm ended it).
    pub const TASK_EXEC_ERROR: Self = Self(1);
    /// External emergency stop.
    pub const AUX_ESTOP: Self = Self(2);
    /// Motion or the toolchanger reported an error: the hard fault caught
    /// at start-change.
    pub const MOTION_OR_IO_ERROR: Self = Self(3);
    /// The machine was switched off.
    pub const TASK_STATE_OFF: Self = Self(4);
    /// Emergency stop reset, which LinuxCNC sends at every start-up.
    pub const ESTOP_RESET: Self = Self(5);
    /// Emergency stop.
    pub const ESTOP: Self = Self(6);
    /// The machine is not on.
    pub const TASK_STATE_NOT_ON: Self = Self(7);
    /// The operator (or the application) aborted.
    pub const USER_ABORT: Self = Self(8);
    /// An interpreter error during read-ahead.
    pub const INTERPRETER_ERROR: Self = Self(9);
    /// An interpreter error in MDI.
    pub const INTERPRETER_ERROR_MDI: Self = Self(10);
    /// The first of the user-defined codes.
    pub const USER: Self = Self(100);
    /// A change met a latched toolchanger fault.
    pub const TOOLCHANGER_FAULT: Self = Self(101);
    /// gcodec's: the changer did not acknowledge within `timeout_cycles`.
    pub const ACK_TIMEOUT: Self = Self(102);

    /// What the reason means, in words.
    pub fn describe(self) -> &'static str {
        match self.0 {
            1 => "execution error",
            2 => "external emergency stop",
            3 => "motion or toolchanger reported an error",
            4 => "machine switched off",
            5 => "emergency stop reset",
            6 => "emergency stop",
            7 => "machine not on",
            8 => "aborted by the operator",
            9 => "interpreter error",
            10 => "interpreter error in MDI",
            100 => "user-defined abort",
            101 => "aborted by a toolchanger fault",
            102 => "no acknowledgement within the timeout",
            n if n > 100 => "user-defined abort",
            _ => "unknown reason",
        }
    }
}

impl fmt::Display for AbortReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.0, self.describe())
    }
}

/// A changer's fault reason (`toolchanger-reason`), latched with the
/// fault.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FaultReason(pub i32);

impl FaultReason {
    /// 0 and below: the next change aborts the program (below 0 with an
    /// operator message). Above 0 the fault is soft: the change is
    /// skipped and the program goes on.
    pub fn is_hard(self) -> bool {
        self.0 <= 0
    }

    /// `hard` or `soft`.
    pub fn severity(self) -> &'static str {
        if self.is_hard() { "hard" } else { "soft" }
    }

    /// What the next change does.
    pub fn consequence(self) -> &'static str {
        if self.is_hard() {
            "the next change aborts"
        } else {
            "the next change is skipped"
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reasons_are_linuxcnc_s_numbers_and_gcodec_s_above_101() {
        assert_eq!(AbortReason::MOTION_OR_IO_ERROR.0, 3);
        assert_eq!(AbortReason::ESTOP_RESET.0, 5);
        assert_eq!(AbortReason::USER_ABORT.0, 8);
        assert_eq!(AbortReason::INTERPRETER_ERROR_MDI.0, 10);
        assert_eq!(AbortReason::TOOLCHANGER_FAULT.0, 101);
        assert_eq!(AbortReason::ACK_TIMEOUT.0, 102);
        assert_eq!(
            AbortReason::TOOLCHANGER_FAULT.to_string(),
            "101: aborted by a toolchanger fault"
        );
        assert_eq!(AbortReason(0).describe(), "unknown reason");
        assert_eq!(AbortReason(140).describe(), "user-defined abort");
    }

    #[test]
    fn a_fault_reason_of_zero_or_below_is_hard() {
        assert!(FaultReason(0).is_hard());
        assert!(FaultReason(-5).is_hard());
        assert!(!FaultReason(7).is_hard());
        assert_eq!(FaultReason(7).consequence(), "the next change is skipped");
    }
}
