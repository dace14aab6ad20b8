//! The shape of the modal state: one command per G group.

/// The number of G groups (reference §3.2).
pub const GROUP_COUNT: usize = 64;
