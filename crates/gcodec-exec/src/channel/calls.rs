//! Calls: subprograms and cycles with their parameters, pass counts,
//! program sections, `MCALL`, `REPEAT` sections, and the returns.
//!
//! `VAR` parameters are passed by copy-in/copy-out: the called program
//! works on a local copy that is written back to the caller's variable when
//! it returns. This is the control's reference semantics except where the
//! subprogram reaches the same variable by another name too (an R
//! parameter or GUD passed by `VAR` and also used directly) — SPEC §11.

use std::sync::Arc;

use gcodec_ail::{Call, Declare, Expr, Instruction, Op, Parameter, RepeatSection, Value, VarKind};
use gcodec_lang::procedures::{Effect, Procedure};
use gcodec_source::{Severity, codes};

use super::{Channel, Flow, Level, LevelKind};
use crate::eval;
use crate::event::{
    ArgumentValue, CallEvent, CallKind, Event, EventKind, EventSource, ProgramEndReason,
    ReturnEvent, SectionEvent,
};
use crate::loader::LoadRequest;
use crate::program::{Program, written_label};
use crate::tool_resolution::CallerSelection;
use crate::value::{RtValue, RunError};
use crate::vars::Scope;

/// A call in progress.
pub(super) struct ActiveCall {
    pub target: String,
    pub kind: CallKind,
    pub pass: u32,
    pub passes: u32,
    /// The arguments, ready to bind again for the next pass.
    bindings: Vec<Binding>,
    /// Where each pass starts.
    start: usize,
    /// `CALL … BLOCK … TO …`: the last line of the section.
    pub section_end_line: Option<u32>,
    section: Option<SectionEvent>,
    /// The arguments as the `call` events show them.
    arguments: Vec<Option<ArgumentValue>>,
    /// Whether the call opened a program level (a section of the calling
    /// program itself does not).
    own_level: bool,
    /// Where the call is written: every pass's `call` event points there.
    origin: EventSource,
    /// The caller's pending tool selection, put aside while the call runs
    /// (`pending_selection_scope = "program_level"`).
    caller_pending: Option<CallerSelection>,
}

impl ActiveCall {
    /// The `call` event of the current pass.
    fn event(&self) -> EventKind {
        EventKind::Call(CallEvent {
            target: self.target.clone(),
            call_kind: self.kind,
            pass: self.pass,
            passes: self.passes,
            section: self.section.clone(),
            arguments: self.arguments.clone(),
        })
    }
}

/// The `call` event of a pass of a `REPEAT` section (the end is a label
/// lowering made; the target names the section).
fn repeat_event(target: &str, pass: u32, passes: u32) -> EventKind {
    EventKind::Call(CallEvent {
        target: target.to_owned(),
        call_kind: CallKind::Repeat,
        pass,
        passes,
        section: None,
        arguments: Vec::new(),
    })
}

/// One parameter's argument.
#[derive(Clone)]
enum Binding {
    /// By value, or the default, or the type's initial value (`None`).
    Value {
        param: Parameter,
        value: Option<RtValue>,
    },
    /// `VAR`: the caller's variable, copied in and written back.
    Reference { param: Parameter, target: VarRef },
}

/// A caller's variable, its indices evaluated at the call.
#[derive(Clone)]
pub(super) struct VarRef {
    kind: VarKind,
    name: String,
    indices: Vec<i32>,
}

/// `MCALL NAME(…)`: called after every traversing block.
#[derive(Clone)]
pub(super) struct ModalCall {
    target: String,
    /// `None`: a cycle not on the search path (reported, not run).
    program: Option<Arc<Program>>,
    bindings: Vec<Binding>,
    arguments: Vec<Option<ArgumentValue>>,
}

/// Names of Siemens standard cycles and ShopMill/ShopTurn steps: when one
/// is not on the search path, the call is reported and the run goes on.
pub fn is_standard_cycle(name: &str) -> bool {
    let upper = name.to_ascii_uppercase();
    [
        "CYCLE", "POCKET", "SLOT", "LONGHOLE", "HOLES", "E_", "F_", "CUST_", "PROBE",
    ]
    .iter()
    .any(|prefix| upper.starts_with(prefix))
}

/// A value as a `call` event shows it.
fn argument_value(value: &RtValue) -> ArgumentValue {
    match value {
        RtValue::Int(n) => ArgumentValue::Number(f64::from(*n)),
        RtValue::Real(r) => ArgumentValue::Number(*r),
        RtValue::Bool(b) => ArgumentValue::Bool(*b),
        RtValue::Char(c) => ArgumentValue::Text(char::from(*c).to_string()),
        RtValue::String(s) | RtValue::Axis(s) => ArgumentValue::Text(s.to_string()),
        RtValue::Frame(_) => ArgumentValue::Text("FRAME".to_owned()),
    }
}

impl Channel<'_> {
    /// `SETAL(n)` raises alarm `n` (the run ends); a predefined procedure
    /// without effect on what the simulation shows passes in silence; the
    /// others are advice once, naming the effect left out. `None` when
    /// `target` is none.
    fn predefined(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        target: &str,
        call: &Call,
    ) -> Option<Result<Flow, RunError>> {
        let procedure = Procedure::named(target)?;
        if procedure.effect() == Effect::Alarm {
            let env = self.env();
            let number = call
                .args
                .first()
                .and_then(Option::as_ref)
                .map(|a| eval::eval_value(&env, a));
            let number = match number
                .transpose()
                .and_then(|n| n.map(|n| n.to_int()).transpose())
            {
                Ok(n) => n.unwrap_or(0),
                Err(e) => return Some(Err(e)),
            };
            self.count(Severity::Error);
            let event = EventKind::Diagnostic(crate::event::DiagnosticEvent {
                code: codes::run::CYCLE_ALARM,
                severity: Severity::Error,
                message: format!("the program raised alarm {number} (`SETAL`)").into(),
                alarm: u32::try_from(number).ok(),
                help: None,
            });
            self.emit_at(program, instruction, event);
            return Some(Ok(Flow::End(ProgramEndReason::Alarm)));
        }
        if let Some(left_out) = procedure.effect().left_out() {
            self.not_simulated(program, instruction, target, || {
                format!("the predefined procedure `{target}` {left_out}")
            });
        }
        Some(Ok(Flow::Next))
    }

    pub(super) fn call(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        call: &Call,
    ) -> Result<Flow, RunError> {
        let target = match &call.target_expr {
            Some(expr) => eval::eval(&self.env(), expr)?
                .to_text()?
                .trim()
                .to_ascii_uppercase(),
            None => call.target.clone(),
        };
        if !call.modal
            && call.section.is_none()
            && let Some(result) = self.predefined(program, instruction, &target, call)
        {
            return result;
        }
        if call.modal {
            let modal = self.prepare_modal_call(program, instruction, &target, call)?;
            self.state.modal_call = Some(modal);
            return Ok(Flow::Next);
        }
        let arguments = self.argument_values(call)?;
        let passes = match &call.passes {
            None => 1,
            Some(p) => {
                let n = eval::eval_value(&self.env(), p)?.to_int()?;
                u32::try_from(n).ok().filter(|&n| n >= 1).ok_or_else(|| {
                    RunError::new(
                        codes::run::INDEX_OUT_OF_RANGE,
                        format!("`P{n}`: a call runs at least once"),
                    )
                })?
            }
        };
        // `CALL BLOCK A TO B` without a program: a section of this one.
        let (callee, own_level) = if target.is_empty() && call.section.is_some() {
            (Arc::clone(program), false)
        } else {
            match self.load(program, instruction, &target, (call.by_path, call.external))? {
                Some(callee) => (callee, true),
                None => {
                    self.not_simulated_call(
                        program,
                        instruction,
                        &target,
                        CallKind::Program,
                        passes,
                        arguments,
                    );
                    return Ok(Flow::Next);
                }
            }
        };
        let (start, section_end_line, section) = match &call.section {
            None => (0, None, None),
            Some(section) => {
                let from = eval::eval_value(&self.env(), &section.from)?.to_text()?;
                let to = eval::eval_value(&self.env(), &section.to)?.to_text()?;
                let (start, end_line) = callee.section(&from, &to).map_err(|label| {
                    RunError::new(
                        codes::run::JUMP_TARGET_NOT_FOUND,
                        format!("the section label `{label}` is not in `{}`", callee.name),
                    )
                })?;
                (start, Some(end_line), Some(SectionEvent { from, to }))
            }
        };
        let bindings = if own_level {
            self.bindings(&callee, call)?
        } else {
            Vec::new()
        };
        let active = ActiveCall {
            target: if target.is_empty() {
                callee.name.clone()
            } else {
                target
            },
            kind: CallKind::Program,
            pass: 1,
            passes,
            bindings,
            start,
            section_end_line,
            section,
            arguments,
            own_level,
            origin: self.source(program, instruction),
            caller_pending: None,
        };
        self.enter(pc + 1, callee, active)
    }

    /// Loads `target` (by path for `PCALL`, from external storage first
    /// for `EXTCALL`); `None` for a standard cycle that is not on the
    /// search path (reported as a warning).
    fn load(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        target: &str,
        (by_path, external): (bool, bool),
    ) -> Result<Option<Arc<Program>>, RunError> {
        let request = LoadRequest {
            name: target,
            by_path,
            external,
            caller_file: &program.file,
        };
        match self.loader.load(&request) {
            Ok(loaded) => {
                let level = self.program_level() + 1;
                for mut event in loaded.diagnostics {
                    event.source.level = level;
                    if let EventKind::Diagnostic(d) = &event.kind {
                        self.count(d.severity);
                    }
                    self.emit(&event);
                }
                if loaded.has_errors {
                    return Err(RunError::new(
                        codes::run::PROGRAM_HAS_ERRORS,
                        format!(
                            "`{target}` ({}) has errors: the control does not run it",
                            loaded.program.file
                        ),
                    ));
                }
                Ok(Some(loaded.program))
            }
            Err(error) if is_standard_cycle(target) => {
                let message = format!("{}; the call is reported, not simulated", error.message);
                self.diagnostic_at(
                    program,
                    instruction,
                    codes::run::CYCLE_NOT_SIMULATED,
                    Severity::Warning,
                    message,
                    Some("pass the directory holding the cycle's source with --subprogram-path to simulate it"),
                );
                Ok(None)
            }
            Err(error) => {
                let mut message = error.message;
                if let Some(help) = error.help {
                    message.push_str("; ");
                    message.push_str(&help);
                }
                // Its own code: not found, unreadable, a link outside the
                // search path, a FIFO, too large.
                Err(RunError::new(error.code, message))
            }
        }
    }

    /// A call that is reported but not run: `call` and `return` events.
    fn not_simulated_call(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        target: &str,
        kind: CallKind,
        passes: u32,
        arguments: Vec<Option<ArgumentValue>>,
    ) {
        let call = EventKind::Call(CallEvent {
            target: target.to_owned(),
            call_kind: kind,
            pass: 1,
            passes,
            section: None,
            arguments,
        });
        self.emit_at(program, instruction, call);
        let ret = EventKind::Return(ReturnEvent {
            target: target.to_owned(),
        });
        self.emit_at(program, instruction, ret);
    }

    /// The arguments of `call`, evaluated in the caller's context, as the
    /// `call` event shows them.
    fn argument_values(&self, call: &Call) -> Result<Vec<Option<ArgumentValue>>, RunError> {
        let env = self.env();
        call.args
            .iter()
            .map(|arg| {
                arg.as_ref()
                    .map(|value| match self.whole_array(value) {
                        Some(shown) => Ok(ArgumentValue::Text(shown)),
                        None => eval::eval_value(&env, value).map(|v| argument_value(&v)),
                    })
                    .transpose()
            })
            .collect()
    }

    /// An argument that names a whole array (`FILL(ARR)` for a `VAR REAL
    /// A[3]`), as the `call` event shows it: its name and dimensions,
    /// `ARR[3]`. Its elements are passed by the binding, not as a value.
    fn whole_array(&self, value: &Value) -> Option<String> {
        let Value::Expr(expr) = value else {
            return None;
        };
        let Expr::Var {
            var_kind: VarKind::User,
            name,
            indices,
        } = &**expr
        else {
            return None;
        };
        let dims = self.vars.get(name.as_str())?.dims();
        if !indices.is_empty() || dims.is_empty() {
            return None;
        }
        let dims: Vec<String> = dims.iter().map(usize::to_string).collect();
        Some(format!("{}[{}]", name.as_str(), dims.join(",")))
    }

    fn prepare_modal_call(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        target: &str,
        call: &Call,
    ) -> Result<ModalCall, RunError> {
        let callee = self.load(program, instruction, target, (call.by_path, call.external))?;
        let bindings = match &callee {
            Some(callee) => self.bindings(callee, call)?,
            None => Vec::new(),
        };
        Ok(ModalCall {
            target: target.to_owned(),
            program: callee,
            bindings,
            arguments: self.argument_values(call)?,
        })
    }

    /// The modal call after a traversing block; the caller goes on at `pc`.
    pub(super) fn run_modal_call(&mut self, program: &Arc<Program>, pc: usize) -> Flow {
        let Some(modal) = self.state.modal_call.clone() else {
            return Flow::Next;
        };
        let instruction = match program
            .instruction(pc.saturating_sub(1))
            .or_else(|| program.instruction(pc))
        {
            Some(i) => i,
            None => return Flow::Next,
        };
        let Some(callee) = modal.program else {
            self.not_simulated_call(
                program,
                &instruction,
                &modal.target,
                CallKind::Modal,
                1,
                modal.arguments,
            );
            return Flow::Next;
        };
        let active = ActiveCall {
            target: modal.target,
            kind: CallKind::Modal,
            pass: 1,
            passes: 1,
            bindings: modal.bindings,
            start: 0,
            section_end_line: None,
            section: None,
            arguments: modal.arguments,
            own_level: true,
            origin: self.source(program, &instruction),
            caller_pending: None,
        };
        match self.enter(pc, callee, active) {
            Ok(flow) => flow,
            Err(error) => Flow::End(self.alarm(program, &instruction, error)),
        }
    }

    /// Pushes the level of a call and binds its parameters.
    fn enter(
        &mut self,
        resume: usize,
        callee: Arc<Program>,
        mut active: ActiveCall,
    ) -> Result<Flow, RunError> {
        let what = if active.own_level {
            format!("calling `{}`", active.target)
        } else {
            format!("the section `{}`", active.target)
        };
        self.check_depth(what)?;
        if let Some(top) = self.stack.last_mut() {
            top.pc = resume;
        }
        self.emit(&Event {
            kind: active.event(),
            source: active.origin.clone(),
        });
        let program_level = self.program_level() + u32::from(active.own_level);
        if active.own_level {
            self.vars.push_level();
            self.bind(&active.bindings)?;
            active.caller_pending = self.enter_pending_scope();
        }
        self.stack.push(Level {
            program: callee,
            pc: active.start,
            program_level,
            kind: LevelKind::Call(Box::new(active)),
        });
        Ok(Flow::Switch)
    }

    /// Whether one more level fits the control's program levels. Each
    /// call takes one until it returns, and so does each section that
    /// runs (`REPEAT`, `CALL BLOCK` of the program's own blocks) until its
    /// last pass ends, though its events keep its program's level: a
    /// section containing the `REPEAT` that runs it nests itself on every
    /// pass, and the stack must not grow with the run. `what` names the
    /// new level in the message.
    fn check_depth(&self, what: String) -> Result<(), RunError> {
        let level = self.stack.len();
        if level < self.options.max_levels {
            return Ok(());
        }
        Err(RunError::new(
            codes::run::CALL_DEPTH,
            format!(
                "{what} would open program level {level}: the control has {} (the main program is level 0)",
                self.options.max_levels
            ),
        ))
    }

    /// The main program's `PROC` parameters, when it has any: declared
    /// with their defaults (nobody passes arguments to a main program).
    pub(super) fn bind_main(&mut self, main: &Program) -> Result<(), RunError> {
        let call = Call {
            target: main.name.clone(),
            target_expr: None,
            section: None,
            by_path: false,
            external: false,
            args: Vec::new(),
            passes: None,
            modal: false,
        };
        let bindings = self.bindings(main, &call)?;
        self.bind(&bindings)
    }

    /// Evaluates the arguments of `call` in the caller's context against
    /// the callee's `PROC` parameters.
    fn bindings(&self, callee: &Program, call: &Call) -> Result<Vec<Binding>, RunError> {
        let first = callee.first_statement();
        let params: &[Parameter] = match first.as_deref().map(|i| &i.op) {
            Some(Op::Procedure(p)) => &p.params,
            _ => &[],
        };
        if call.args.len() > params.len()
            && call.args.iter().skip(params.len()).any(Option::is_some)
        {
            return Err(RunError::new(
                codes::run::ARGUMENT_COUNT,
                format!(
                    "`{}` takes {} parameters, the call passes {}",
                    callee.name,
                    params.len(),
                    call.args.len()
                ),
            ));
        }
        let env = self.env();
        let mut bindings = Vec::with_capacity(params.len());
        for (i, param) in params.iter().enumerate() {
            let arg = call.args.get(i).and_then(Option::as_ref);
            let binding = match (param.by_reference, arg) {
                (true, Some(Value::Expr(expr))) if matches!(**expr, Expr::Var { .. }) => {
                    let Expr::Var {
                        var_kind,
                        name,
                        indices,
                    } = &**expr
                    else {
                        unreachable!("matched above")
                    };
                    let mut evaluated = Vec::with_capacity(indices.len());
                    for index in indices {
                        evaluated.push(eval::eval(&env, index)?.to_int()?);
                    }
                    Binding::Reference {
                        param: param.clone(),
                        target: VarRef {
                            kind: *var_kind,
                            name: name.as_str().to_owned(),
                            indices: evaluated,
                        },
                    }
                }
                (true, Some(_)) => {
                    return Err(RunError::new(
                        codes::run::TYPE_MISMATCH,
                        format!(
                            "the `VAR` parameter `{}` needs a variable, not a value",
                            param.name
                        ),
                    ));
                }
                (_, Some(value)) => Binding::Value {
                    param: param.clone(),
                    value: Some(eval::eval_value(&env, value)?),
                },
                (_, None) => Binding::Value {
                    param: param.clone(),
                    value: None,
                },
            };
            bindings.push(binding);
        }
        Ok(bindings)
    }

    /// Declares the parameters in the new level and gives them their
    /// values (`VAR`: a copy of the caller's variable, read from the level
    /// below).
    fn bind(&mut self, bindings: &[Binding]) -> Result<(), RunError> {
        for binding in bindings {
            let param = match binding {
                Binding::Value { param, .. } | Binding::Reference { param, .. } => param,
            };
            let declare = Declare {
                name: param.name.clone(),
                data_type: param.data_type,
                dims: param.dims.clone(),
                init: Vec::new(),
                init_repeat: None,
            };
            match binding {
                Binding::Value { value, .. } => {
                    eval::declare(&mut self.vars, &self.state, &declare, Scope::Local)?;
                    let value = match (value, &param.default) {
                        (Some(v), _) => Some(v.clone()),
                        (None, Some(default)) => Some(eval::eval_value(&self.env(), default)?),
                        (None, None) => None,
                    };
                    if let Some(value) = value {
                        self.vars.write(VarKind::User, &param.name, &[], &value)?;
                    }
                }
                Binding::Reference { target, .. } => {
                    let values = self.read_caller(target)?;
                    let mut declare = declare;
                    if declare.dims.is_empty() && values.len() > 1 {
                        // `VAR REAL A[]`: the caller's array decides.
                        declare.dims = vec![Value::Const(values.len() as f64)];
                    }
                    eval::declare(&mut self.vars, &self.state, &declare, Scope::Local)?;
                    if values.len() == 1 {
                        self.vars
                            .write(VarKind::User, &param.name, &[], &values[0])?;
                    } else {
                        let list: Vec<Option<RtValue>> = values.into_iter().map(Some).collect();
                        self.vars
                            .write_list(VarKind::User, &param.name, &[], &list)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// The value of a caller's variable (all elements of an array named
    /// without indices), read from the level below the current one.
    fn read_caller(&mut self, target: &VarRef) -> Result<Vec<RtValue>, RunError> {
        self.vars.with_caller_level(|vars| {
            if target.indices.is_empty()
                && target.kind == VarKind::User
                && let Some(var) = vars.get(&target.name)
                && !var.dims().is_empty()
            {
                return Ok(var.elements().to_vec());
            }
            Ok(vec![vars.read(
                target.kind,
                &target.name,
                &target.indices,
            )?])
        })
    }

    /// Writes the `VAR` parameters back to the caller's variables; the
    /// current level is the called program's.
    fn write_back(&mut self, bindings: &[Binding]) -> Result<(), RunError> {
        for binding in bindings {
            let Binding::Reference { param, target } = binding else {
                continue;
            };
            let Some(local) = self.vars.get(&param.name) else {
                continue;
            };
            let values: Vec<Option<RtValue>> = local.elements().iter().cloned().map(Some).collect();
            self.vars.with_caller_level(|vars| {
                if values.len() == 1 {
                    vars.write(
                        target.kind,
                        &target.name,
                        &target.indices,
                        values[0].as_ref().expect("some"),
                    )
                } else {
                    vars.write_list(target.kind, &target.name, &target.indices, &values)
                }
            })?;
        }
        Ok(())
    }

    /// `REPEAT`: runs the section, then goes on after the instruction.
    pub(super) fn repeat_section(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        section: &RepeatSection,
    ) -> Result<Flow, RunError> {
        let missing = |label: &str| {
            RunError::new(
                codes::run::JUMP_TARGET_NOT_FOUND,
                format!(
                    "the section label `{}` is not in the program",
                    written_label(label)
                ),
            )
        };
        let start = program
            .label(&section.start)
            .ok_or_else(|| missing(&section.start))?;
        let end = program
            .label(&section.end)
            .ok_or_else(|| missing(&section.end))?;
        let passes = eval::eval_value(&self.env(), &section.passes)?.to_int()?;
        let passes = u32::try_from(passes)
            .ok()
            .filter(|&p| p >= 1)
            .ok_or_else(|| {
                RunError::new(
                    codes::run::INDEX_OUT_OF_RANGE,
                    format!("`P={passes}`: a section runs at least once"),
                )
            })?;
        let target = written_label(&section.start).to_owned();
        self.check_depth(format!("the section `{target}`"))?;
        if let Some(top) = self.stack.last_mut() {
            top.pc = pc + 1;
        }
        let origin = self.source(program, instruction);
        self.emit(&Event {
            kind: repeat_event(&target, 1, passes),
            source: origin.clone(),
        });
        let program_level = self.program_level();
        self.stack.push(Level {
            program: Arc::clone(program),
            pc: start,
            program_level,
            kind: LevelKind::Repeat {
                target,
                start,
                end,
                pass: 1,
                passes,
                origin,
            },
        });
        Ok(Flow::Switch)
    }

    /// The end label of the top `REPEAT` section is reached: the next pass,
    /// or back after the `REPEAT`.
    pub(super) fn repeat_pass_done(&mut self) -> Option<ProgramEndReason> {
        let top = self.stack.last_mut()?;
        let program = Arc::clone(&top.program);
        let LevelKind::Repeat {
            target,
            start,
            end,
            pass,
            passes,
            origin,
        } = &mut top.kind
        else {
            return None;
        };
        if *pass < *passes {
            *pass += 1;
            top.pc = *start;
            let event = Event {
                kind: repeat_event(target, *pass, *passes),
                source: origin.clone(),
            };
            self.emit(&event);
            return None;
        }
        let instruction = program
            .instruction(*end)
            .or_else(|| program.last_instruction())?;
        let event = EventKind::Return(ReturnEvent {
            target: target.clone(),
        });
        self.stack.pop();
        self.emit_at(&program, &instruction, event);
        None
    }

    /// `RET`, `M17` (`M2`, `M30` in a subprogram), the end of a section or
    /// of the text: back to the caller, or the next pass. In the main
    /// program the program ends.
    pub(super) fn return_from_call(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        section_end: bool,
    ) -> Flow {
        let Some(instruction) = program
            .instruction(pc)
            .or_else(|| program.last_instruction())
        else {
            return Flow::End(ProgramEndReason::EndOfText);
        };
        // A return inside a `REPEAT` section leaves the section too.
        while matches!(
            self.stack.last().map(|l| &l.kind),
            Some(LevelKind::Repeat { .. })
        ) {
            self.stack.pop();
        }
        let (bindings, own_level, target) = match self.stack.last_mut().map(|l| &mut l.kind) {
            Some(LevelKind::Call(call)) => (
                std::mem::take(&mut call.bindings),
                call.own_level,
                call.target.clone(),
            ),
            _ => {
                let reason = if section_end || matches!(instruction.op, Op::End) {
                    ProgramEndReason::EndOfText
                } else {
                    ProgramEndReason::M17
                };
                return Flow::End(reason);
            }
        };
        if own_level {
            let written = self.write_back(&bindings);
            self.vars.pop_level();
            if let Err(error) = written {
                return Flow::End(self.alarm(program, &instruction, error));
            }
            if let Some(LevelKind::Call(call)) = self.stack.last_mut().map(|l| &mut l.kind) {
                let caller = call.caller_pending.take();
                self.leave_pending_scope(caller);
            }
        }
        self.emit_at(
            program,
            &instruction,
            EventKind::Return(ReturnEvent { target }),
        );
        let Some(mut level) = self.stack.pop() else {
            return Flow::End(ProgramEndReason::EndOfText);
        };
        let LevelKind::Call(call) = &mut level.kind else {
            return Flow::End(ProgramEndReason::EndOfText);
        };
        if call.pass >= call.passes {
            return Flow::Switch;
        }
        // The next pass, reported where the call is written.
        call.pass += 1;
        level.pc = call.start;
        let event = Event {
            kind: call.event(),
            source: call.origin.clone(),
        };
        call.bindings = bindings.clone();
        if own_level {
            call.caller_pending = self.enter_pending_scope();
        }
        self.emit(&event);
        self.stack.push(level);
        if own_level {
            self.vars.push_level();
            if let Err(error) = self.bind(&bindings) {
                return Flow::End(self.alarm(program, &instruction, error));
            }
        }
        Flow::Switch
    }
}
