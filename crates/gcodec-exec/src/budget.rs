//! The budgets a run draws on besides its blocks: the work on array
//! elements and the memory of the variables (SPEC §11.3, §11.4).
//!
//! The step limit counts blocks, but one block can cost millions of
//! element operations (`DEF REAL A[1024,1024]` passed by a backward jump,
//! `A[0,0]=REP(1)` in a loop), and the variables alive at once can hold
//! gigabytes. [`WorkBudget`] counts the elements declarations initialise
//! and lists, fills and `VAR` copies write or read; [`MemoryBudget`] the
//! bytes of the variables alive. Both are checked before the work is done
//! or the memory taken, so a run stops with a diagnostic rather than
//! running for minutes or aborting on a failed allocation.

use std::mem::size_of;

use gcodec_lang::DataType;
use gcodec_source::codes;

use crate::value::{RtValue, RunError};

/// The work budget when nothing says otherwise (`--max-work`): element
/// operations, about a hundred per block at the default step limit.
pub const DEFAULT_MAX_WORK: u64 = 1_000_000_000;

/// The bytes one element of type `ty` counts: its value's storage, and
/// for a `STRING[n]` the n characters it may hold.
pub fn element_bytes(ty: DataType) -> u64 {
    let value = size_of::<RtValue>() as u64;
    match ty {
        DataType::String { length } => value + length.map_or(0, u64::from),
        _ => value,
    }
}

/// The element operations of a run, against their limit.
#[derive(Clone, Debug)]
pub struct WorkBudget {
    limit: u64,
    done: u64,
}

impl WorkBudget {
    pub fn new(limit: u64) -> Self {
        Self { limit, done: 0 }
    }

    /// The element operations done so far.
    pub fn done(&self) -> u64 {
        self.done
    }

    /// Counts `elements` operations about to be done; an error, and
    /// nothing counted, when they would pass the limit.
    pub fn spend(&mut self, elements: usize) -> Result<(), RunError> {
        let after = self.done.saturating_add(elements as u64);
        if after > self.limit {
            return Err(RunError::new(
                codes::run::WORK_LIMIT,
                format!(
                    "the run stopped before {elements} more element operations: with the {} done \
                     they pass the work budget of {} (--max-work)",
                    self.done, self.limit
                ),
            ));
        }
        self.done = after;
        Ok(())
    }
}

/// The bytes of the variables alive, against the memory for them.
#[derive(Clone, Debug)]
pub struct MemoryBudget {
    limit: u64,
    used: u64,
}

impl MemoryBudget {
    pub fn new(limit: u64) -> Self {
        Self { limit, used: 0 }
    }

    /// The bytes the variables alive hold.
    pub fn used(&self) -> u64 {
        self.used
    }

    /// Whether `bytes` for the variable `name` fit, the `freed` bytes of
    /// the one it replaces given back: an error when they do not.
    pub fn check(&self, name: &str, bytes: u64, freed: u64) -> Result<(), RunError> {
        let in_use = self.used.saturating_sub(freed);
        if in_use.saturating_add(bytes) <= self.limit {
            return Ok(());
        }
        Err(RunError::new(
            codes::run::VARIABLE_MEMORY,
            format!(
                "`{name}` needs {bytes} bytes, and {in_use} of the {} bytes for variables are in use \
                 (the profile's `[program] max_variable_memory`)",
                self.limit
            ),
        ))
    }

    /// Takes `bytes` that [`MemoryBudget::check`] found room for, giving
    /// back `freed`.
    pub fn take(&mut self, bytes: u64, freed: u64) {
        self.used = self.used.saturating_sub(freed).saturating_add(bytes);
    }

    /// Gives back the bytes of variables that are gone.
    pub fn release(&mut self, bytes: u64) {
        self.used = self.used.saturating_sub(bytes);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_past_the_limit_is_refused_and_not_counted() {
        let mut work = WorkBudget::new(1_000);
        assert!(work.spend(600).is_ok());
        let error = work.spend(401).expect_err("past the limit");
        assert_eq!(error.code, codes::run::WORK_LIMIT);
        assert_eq!(work.done(), 600);
        assert!(work.spend(400).is_ok());
        assert_eq!(work.done(), 1_000);
    }

    #[test]
    fn memory_is_taken_replaced_and_given_back() {
        let mut memory = MemoryBudget::new(100);
        assert!(memory.check("A", 60, 0).is_ok());
        memory.take(60, 0);
        // `A` declared again: its 60 bytes make room for the new 90.
        assert!(memory.check("A", 90, 60).is_ok());
        memory.take(90, 60);
        assert_eq!(memory.used(), 90);
        let error = memory.check("B", 11, 0).expect_err("does not fit");
        assert_eq!(error.code, codes::run::VARIABLE_MEMORY);
        memory.release(90);
        assert_eq!(memory.used(), 0);
    }

    #[test]
    fn a_string_element_counts_the_characters_it_may_hold() {
        let real = element_bytes(DataType::Real);
        assert_eq!(real, size_of::<RtValue>() as u64);
        assert_eq!(
            element_bytes(DataType::String { length: Some(200) }),
            real + 200
        );
    }
}
