//! Interrupt routines (ASUB, Job Planning "Interrupt routine"):
//! `SETINT(<input>) PRIO=<priority> <routine> [LIFTFAST] [BLSYNC]`
//! assigns a routine to one of the NCK's fast inputs; `ENABLE`, `DISABLE`
//! and `CLRINT` act on the assignment.

use std::ops::RangeInclusive;

/// The fast inputs a routine can be assigned to.
pub const INPUTS: RangeInclusive<u32> = 1..=8;

/// The priorities, 1 the highest.
pub const PRIORITIES: RangeInclusive<u32> = 1..=128;

/// The names `SETINT`'s block takes besides the routine's: the priority,
/// the fast retraction and the start at the end of the block in progress.
pub const PRIORITY: &str = "PRIO";
pub const LIFT_FAST: &str = "LIFTFAST";
pub const BLOCK_SYNC: &str = "BLSYNC";

/// `value` as an input or priority of `range`: a whole number in it.
pub fn in_range(value: f64, range: &RangeInclusive<u32>) -> Option<u32> {
    (value.fract() == 0.0 && value >= f64::from(*range.start()) && value <= f64::from(*range.end()))
        .then_some(value as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inputs_and_priorities_are_whole_numbers_in_their_range() {
        assert_eq!(in_range(3.0, &INPUTS), Some(3));
        assert_eq!(in_range(8.0, &INPUTS), Some(8));
        for not in [0.0, 9.0, 2.5, -1.0, f64::NAN] {
            assert_eq!(in_range(not, &INPUTS), None, "{not}");
        }
        assert_eq!(in_range(128.0, &PRIORITIES), Some(128));
        assert_eq!(in_range(129.0, &PRIORITIES), None);
    }
}
