//! The auxiliary and preparatory functions of a block: M and H functions,
//! spindles, dwell, named addresses and programmable frames.

use std::sync::Arc;

use gcodec_ail::{Address, Frame as FrameInstruction, HFunction, Instruction, MFunction, Value};
use gcodec_lang::addresses::NamedAddress;
use gcodec_lang::mfunctions::{MAX_M_VALUE, acts_after_motion};
use gcodec_lang::{FrameOp, MClass};
use gcodec_profile::Policy;
use gcodec_source::{Severity, codes};

use super::machine_calls::Continuation;
use super::{Channel, Flow};
use crate::eval;
use crate::event::{
    DwellEvent, EventKind, HFunctionEvent, MAction, MFunctionEvent, ProgramEndReason, SpindleEvent,
    SpindleState, StopEvent, StopReason,
};
use crate::frames;
use crate::machine::{AuxiliaryFunction, MachineAction, Wait};
use crate::program::Program;
use crate::value::{RtValue, RunError};

impl Channel<'_> {
    /// One M function per auxiliary-function group of the master spindle
    /// in a block (alarm 14760); constants were checked by lowering.
    fn check_auxiliary_group(
        &mut self,
        value: u32,
        extension: Option<u32>,
        raw: &str,
    ) -> Result<(), RunError> {
        let profile = &self.state.profile;
        let master = profile.machine.spindles.first().map(|s| *s.get_ref());
        let of_master = extension.is_none_or(|n| n == 0 || Some(n) == master);
        let group = profile
            .m_functions
            .auxiliary_group(value)
            .and_then(|g| g.parse::<u8>().ok())
            .filter(|g| of_master && (1..=64).contains(g));
        let Some(group) = group else {
            return Ok(());
        };
        let bit = 1u64 << (group - 1);
        if self.block.m_groups & bit != 0 {
            return Err(RunError::new(
                codes::run::M_GROUP_CONFLICT,
                format!(
                    "`{raw}` is M{value}, of auxiliary-function group {group} like another M function of this block"
                ),
            ));
        }
        self.block.m_groups |= bit;
        Ok(())
    }

    pub(super) fn m_function(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        m: &MFunction,
    ) -> Result<Flow, RunError> {
        let env = self.env();
        let value = match (&m.m_value, &m.m_expr) {
            (Some(v), _) => *v,
            (None, Some(expr)) => {
                let n = eval::eval(&env, expr)?.to_int()?;
                u32::try_from(n)
                    .ok()
                    .filter(|v| *v <= MAX_M_VALUE)
                    .ok_or_else(|| {
                        RunError::new(
                            codes::run::OVERFLOW,
                            format!("`M={n}`: M values are 0…{MAX_M_VALUE}"),
                        )
                    })?
            }
            (None, None) => 0,
        };
        let extension = self.extension(m.address_extension, m.address_extension_expr.as_ref())?;
        // The rules lowering checks on constants, for a computed value.
        if m.m_value.is_none() && extension.is_some() && acts_after_motion(value) {
            return Err(RunError::new(
                codes::run::M_EXTENSION_FORBIDDEN,
                format!("`{}` is M{value}, which takes no address extension", m.raw),
            ));
        }
        self.check_auxiliary_group(value, extension, &m.raw)?;
        // A computed value is classified now, as lowering classifies
        // constants.
        let computed_class = m
            .m_value
            .is_none()
            .then(|| gcodec_profile::m_class(&self.state.profile, value));
        let class = match computed_class {
            Some(known) => known.unwrap_or(MClass::Custom),
            None => m.class,
        };
        let change_m = *self.state.profile.tool_change.change_m_code.get_ref();
        let action = match (class, value) {
            (MClass::ProgramFlow, 0) => MAction::ProgramStop,
            (MClass::ProgramFlow, 1) => MAction::OptionalStop,
            (MClass::ProgramFlow, 2 | 30) => MAction::ProgramEnd,
            (MClass::ProgramFlow, 17) => MAction::SubprogramEnd,
            (MClass::Spindle, 3) => MAction::SpindleCw,
            (MClass::Spindle, 4) => MAction::SpindleCcw,
            (MClass::Spindle, 5) => MAction::SpindleStop,
            (MClass::Spindle, 19) => MAction::SpindlePosition,
            (MClass::Spindle, 70) => MAction::SpindleAxisMode,
            (MClass::Tool, v) if v == change_m => MAction::ToolChange,
            (MClass::Gearbox, 40) => MAction::GearStageAuto,
            (MClass::Gearbox, 41..=45) => MAction::GearStage,
            _ => MAction::Output,
        };
        if computed_class == Some(None) {
            match self.state.profile.m_functions.unknown_mcode_policy {
                Policy::Error => {
                    return Err(RunError::new(
                        codes::run::UNKNOWN_M_FUNCTION,
                        format!("`M{value}` is not an M function of this machine"),
                    ));
                }
                Policy::Warning => self.diagnostic_at(
                    program,
                    instruction,
                    codes::run::UNKNOWN_M_FUNCTION,
                    Severity::Warning,
                    format!(
                        "`M{value}` is not an M function of this machine; it is output to the PLC"
                    ),
                    Some("list it in the profile's `mcode_class_overrides` if the machine has it"),
                ),
                Policy::Ignore => {}
            }
        }
        let event = EventKind::MFunction(MFunctionEvent {
            m_value: value,
            address_extension: extension,
            class,
            phase: m.timing,
            action,
        });
        self.emit_at(program, instruction, event);
        // The change M is the machine's tool change (`tool_change`).
        if action != MAction::ToolChange {
            let function = AuxiliaryFunction::M { value, extension };
            let answer = self
                .machine
                .auxiliary_function(&function, &mut self.machine_events);
            let action_of = || MachineAction::AuxiliaryFunction(function);
            let continuation = Continuation::MAction {
                action,
                value,
                extension,
            };
            let ready =
                self.machine_answer(program, pc, instruction, answer, action_of, continuation)?;
            if ready.is_none() {
                return Ok(Flow::Pending);
            }
        }
        self.m_action(program, pc, instruction, action, value, extension)
    }

    /// What the channel itself does for an M function once the PLC has
    /// it: spindles, gear stages, stops, the end of the program.
    pub(super) fn m_action(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        action: MAction,
        value: u32,
        extension: Option<u32>,
    ) -> Result<Flow, RunError> {
        let spindle = |state| (extension, state);
        let change = match action {
            MAction::SpindleCw => Some(spindle(SpindleState::Cw)),
            MAction::SpindleCcw => Some(spindle(SpindleState::Ccw)),
            MAction::SpindleStop => Some(spindle(SpindleState::Stopped)),
            MAction::SpindlePosition => Some(spindle(SpindleState::Positioned)),
            MAction::SpindleAxisMode => Some(spindle(SpindleState::Axis)),
            _ => None,
        };
        if let Some((number, state)) = change {
            self.state.spindle(number)?.state = state;
            self.spindle_event(program, instruction, number)?;
        }
        match action {
            MAction::GearStageAuto => self.state.spindle(extension)?.gear = 0,
            MAction::GearStage => self.state.spindle(extension)?.gear = value - 40,
            MAction::ProgramStop | MAction::OptionalStop => {
                let stops = action == MAction::ProgramStop || self.options.optional_stop;
                if stops {
                    let reason = if action == MAction::ProgramStop {
                        StopReason::ProgramStop
                    } else {
                        StopReason::OptionalStop
                    };
                    let event = EventKind::Stop(StopEvent {
                        reason,
                        detail: None,
                    });
                    self.emit_at(program, instruction, event);
                    if self.options.stop_at_m0 {
                        return Ok(Flow::End(ProgramEndReason::Stopped));
                    }
                }
            }
            MAction::ProgramEnd | MAction::SubprogramEnd => {
                if self.program_level() == 0 && !self.in_call() {
                    return Ok(Flow::End(match value {
                        2 => ProgramEndReason::M2,
                        30 => ProgramEndReason::M30,
                        _ => ProgramEndReason::M17,
                    }));
                }
                // `M2`/`M30` in a subprogram end it like `M17`.
                return Ok(self.return_from_call(program, pc, false));
            }
            _ => {}
        }
        Ok(Flow::Next)
    }

    /// An address extension (a spindle number, `M2=`, `H[I]=`): written,
    /// or computed when the block runs. A computed one outside 0…99, the
    /// range lowering holds constant ones to (no spindle is numbered
    /// beyond it), is [`codes::run::OVERFLOW`] naming it, never a wrapped
    /// number or the master spindle.
    fn extension(
        &self,
        constant: Option<u32>,
        computed: Option<&gcodec_ail::Expr>,
    ) -> Result<Option<u32>, RunError> {
        match (constant, computed) {
            (Some(n), _) => Ok(Some(n)),
            (None, Some(expr)) => {
                let n = eval::eval(&self.env(), expr)?.to_int()?;
                match u32::try_from(n) {
                    Ok(extension) if extension <= 99 => Ok(Some(extension)),
                    _ => Err(RunError::new(
                        codes::run::OVERFLOW,
                        format!("the address extension {n} is outside 0…99"),
                    )),
                }
            }
            (None, None) => Ok(None),
        }
    }

    /// Whether a call level is on the stack (a section of the main program
    /// runs at level 0).
    fn in_call(&self) -> bool {
        self.stack
            .iter()
            .any(|l| matches!(l.kind, super::LevelKind::Call(_)))
    }

    fn spindle_event(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        number: Option<u32>,
    ) -> Result<(), RunError> {
        let s = self.state.spindle(number)?.clone();
        let event = EventKind::Spindle(SpindleEvent {
            spindle: s.number,
            state: s.state,
            speed: s.speed,
            position: s.position.filter(|_| s.state == SpindleState::Positioned),
        });
        self.emit_at(program, instruction, event);
        Ok(())
    }

    pub(super) fn spindle_speed(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        spindle: Option<u32>,
        speed: &Value,
        spindle_expr: Option<&gcodec_ail::Expr>,
    ) -> Result<(), RunError> {
        let env = self.env();
        let number = self.extension(spindle, spindle_expr)?;
        let speed = eval::eval_real(&env, speed)?;
        self.state.spindle(number)?.speed = speed;
        self.spindle_event(program, instruction, number)
    }

    pub(super) fn dwell(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        seconds: Option<&Value>,
        revolutions: Option<&Value>,
    ) -> Result<Flow, RunError> {
        let env = self.env();
        let seconds = seconds.map(|v| eval::eval_real(&env, v)).transpose()?;
        let revolutions = revolutions.map(|v| eval::eval_real(&env, v)).transpose()?;
        let speed = self.state.master_spindle().map_or(0.0, |s| s.speed);
        let time = seconds.unwrap_or(0.0)
            + revolutions.map_or(0.0, |r| if speed > 0.0 { r / speed * 60.0 } else { 0.0 });
        self.figures().feed_time += time.max(0.0);
        let event = EventKind::Dwell(DwellEvent {
            seconds,
            revolutions,
        });
        self.emit_at(program, instruction, event);
        let wait = Wait::Dwell {
            seconds: time.max(0.0),
        };
        let answer = self.machine.wait(&wait, &mut self.machine_events);
        let action = || MachineAction::Wait(wait);
        self.machine_done(program, pc, instruction, answer, action)
    }

    pub(super) fn h_function(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        h: &HFunction,
    ) -> Result<Flow, RunError> {
        let env = self.env();
        let value = match (&h.h_value, &h.h_expr) {
            (Some(v), _) => *v,
            (None, Some(expr)) => eval::eval(&env, expr)?.to_real()?,
            (None, None) => 0.0,
        };
        let extension = self.extension(h.address_extension, h.address_extension_expr.as_ref())?;
        let event = EventKind::HFunction(HFunctionEvent {
            h_value: value,
            address_extension: extension,
            quick: h.quick,
            phase: h.timing,
        });
        self.emit_at(program, instruction, event);
        let function = AuxiliaryFunction::H { value, extension };
        let answer = self
            .machine
            .auxiliary_function(&function, &mut self.machine_events);
        let action = || MachineAction::AuxiliaryFunction(function);
        self.machine_done(program, pc, instruction, answer, action)
    }

    /// `SPOS`/`SPOSA` position a spindle; the other named addresses do not
    /// change what the simulation shows and are reported once.
    pub(super) fn address(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        address: &Address,
    ) -> Result<(), RunError> {
        match address.address {
            NamedAddress::Spos | NamedAddress::Sposa => {
                let value = self.real_of(&address.value)?;
                let number = self.extension(address.extension, address.extension_expr.as_ref())?;
                let s = self.state.spindle(number)?;
                s.state = SpindleState::Positioned;
                s.position = Some(value);
                self.spindle_event(program, instruction, number)?;
            }
            NamedAddress::Offn | NamedAddress::Rndm | NamedAddress::Disc => {
                let value = self.real_of(&address.value)?;
                let length = self.state.length_in_mm(value);
                let contour = &mut self.state.contour;
                match address.address {
                    NamedAddress::Offn => contour.offn = length,
                    NamedAddress::Rndm => contour.rndm = length,
                    _ => contour.disc = value,
                }
            }
            other => {
                // Read, for its errors, though it has no effect: an axis
                // (`CPLA[X]=Y`) or a string (`CPSETTYPE[X]="CP"`) as well.
                if let Value::Expr(expr) = &address.value {
                    eval::eval(&self.env(), expr)?;
                }
                let other = other.name();
                let key = format!("address {other}");
                self.not_simulated(program, instruction, &key, || {
                    format!("`{other}=` has no effect in the simulation")
                });
            }
        }
        Ok(())
    }

    pub(super) fn frame(&mut self, frame: &FrameInstruction) -> Result<(), RunError> {
        let op = frame.op;
        if op.is_solid_angle() {
            return Err(frames::not_simulated(op));
        }
        // A translation of a linear axis is a length: in mm from inch.
        let inch = self.state.inch();
        let state = &self.state;
        let scaled = |axis: usize, value: f64| {
            let is_length =
                matches!(op, FrameOp::Trans | FrameOp::Atrans) && !state.axes[axis].rotary;
            (
                axis,
                if is_length && inch {
                    value * 25.4
                } else {
                    value
                },
            )
        };
        let mut values = Vec::with_capacity(frame.values.len());
        let mut rpl = None;
        let env = self.env();
        for v in &frame.values {
            let value = eval::eval_real(&env, &v.value)?;
            if v.axis == "RPL" {
                rpl = Some(value);
                continue;
            }
            values.push(scaled(self.axis(&v.axis)?, value));
        }
        for v in &frame.indirect_values {
            let name = match eval::eval(&env, &v.axis)? {
                RtValue::Axis(a) | RtValue::String(a) => a,
                other => return Err(RunError::type_mismatch(&other, "AXIS")),
            };
            let axis = self.axis(&name)?;
            values.push(scaled(axis, eval::eval_real(&env, &v.value)?));
        }
        let plane = self.state.plane();
        let state = &mut self.state;
        state
            .programmable
            .apply(&state.frame_axes, op, &values, rpl, plane)
    }
}
