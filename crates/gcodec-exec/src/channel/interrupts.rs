//! Interrupt assignments (`SETINT`, `ENABLE`, `DISABLE`, `CLRINT`): kept
//! per input as the channel's state and reported as `interrupt` events.
//! The simulation has no inputs, so a routine never starts (SPEC §11.7).

use std::ops::RangeInclusive;
use std::sync::Arc;

use gcodec_ail::{Instruction, InterruptAction, InterruptAssign, Value};
use gcodec_lang::interrupts::{self, INPUTS, PRIORITIES};
use gcodec_source::codes;

use super::Channel;
use crate::event::{EventKind, InterruptChange, InterruptEvent};
use crate::program::Program;
use crate::value::RunError;

/// The routine assigned to one input.
#[derive(Clone, Debug)]
pub(super) struct InterruptSlot {
    pub routine: Option<String>,
    pub priority: u32,
    pub lift_fast: bool,
    pub block_sync: bool,
    pub enabled: bool,
}

/// What is assigned to each input (index input − 1).
pub(super) type Interrupts = [Option<InterruptSlot>; *INPUTS.end() as usize];

impl Channel<'_> {
    /// `SETINT(n) PRIO=p NAME`: assigns (again) and enables.
    pub(super) fn interrupt_assign(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        assign: &InterruptAssign,
    ) -> Result<(), RunError> {
        let input = self.interrupt_number("the input", &assign.input, &INPUTS)?;
        let priority = self.interrupt_number("the priority", &assign.priority, &PRIORITIES)?;
        let slot = InterruptSlot {
            routine: assign.routine.clone(),
            priority,
            lift_fast: assign.lift_fast,
            block_sync: assign.block_sync,
            enabled: true,
        };
        self.interrupt_event(
            program,
            instruction,
            input,
            InterruptChange::Assigned,
            Some(&slot),
        );
        self.state.interrupts[input as usize - 1] = Some(slot);
        Ok(())
    }

    /// `ENABLE(n)` (an input without a routine is an alarm), `DISABLE(n)`,
    /// `CLRINT(n)` (an input without a routine stays so).
    pub(super) fn interrupt_control(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        action: InterruptAction,
        input: &Value,
    ) -> Result<(), RunError> {
        let input = self.interrupt_number("the input", input, &INPUTS)?;
        let slot = &mut self.state.interrupts[input as usize - 1];
        let change = match action {
            InterruptAction::Enable => {
                let Some(assigned) = slot else {
                    return Err(RunError::new(
                        codes::run::INTERRUPT,
                        format!("`ENABLE({input})`: input {input} has no interrupt routine"),
                    ));
                };
                assigned.enabled = true;
                InterruptChange::Enabled
            }
            InterruptAction::Disable => {
                if let Some(assigned) = slot {
                    assigned.enabled = false;
                }
                InterruptChange::Disabled
            }
            InterruptAction::Clear => {
                *slot = None;
                InterruptChange::Cleared
            }
        };
        let slot = self.state.interrupts[input as usize - 1].clone();
        self.interrupt_event(program, instruction, input, change, slot.as_ref());
        Ok(())
    }

    fn interrupt_number(
        &self,
        what: &str,
        value: &Value,
        range: &RangeInclusive<u32>,
    ) -> Result<u32, RunError> {
        let n = self.real_of(value)?;
        interrupts::in_range(n, range).ok_or_else(|| {
            RunError::new(
                codes::run::INTERRUPT,
                format!(
                    "{what} {n} is not a whole number {}…{}",
                    range.start(),
                    range.end()
                ),
            )
        })
    }

    fn interrupt_event(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        input: u32,
        change: InterruptChange,
        slot: Option<&InterruptSlot>,
    ) {
        let event = EventKind::Interrupt(InterruptEvent {
            input,
            change,
            routine: slot.and_then(|s| s.routine.clone()),
            priority: slot.map(|s| s.priority),
            lift_fast: slot.is_some_and(|s| s.lift_fast),
            block_sync: slot.is_some_and(|s| s.block_sync),
            enabled: slot.is_some_and(|s| s.enabled),
        });
        self.emit_at(program, instruction, event);
    }
}
