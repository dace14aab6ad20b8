//! Evaluation of AIL expressions ([`gcodec_ail::Expr`], [`gcodec_ail::Value`])
//! with the control's semantics (reference §7.5, §7.6; SPEC §11.x).
//!
//! [`eval`] reads variables from a [`Variables`] store and system
//! variables through a [`RuntimeInterface`], both reached through an
//! [`EvalContext`]. Errors are [`RunError`] values with stable codes,
//! never panics. Evaluating a numeric expression allocates nothing:
//! numbers are inline values, names are looked up without copying, index
//! lists and the arguments of the built-in functions are evaluated into
//! fixed buffers.
//!
//! [`assign`], [`assign_list`] and [`declare`] run the instructions that
//! write variables (`assign`, `assign_list`, `declare`).
//!
//! This file holds the evaluator: values, variables, operators and
//! comparisons. The built-in functions are in `functions/`, one file a
//! family; the system variables a machine profile answers in
//! `profile_variables.rs`; the instructions that write variables in
//! `assign.rs`.

mod assign;
mod functions;
pub(crate) mod profile_variables;

use std::sync::Arc;

use gcodec_ail::{Expr, Value, VarKind, VarName};
use gcodec_lang::functions::Function;
use gcodec_lang::sysvars::SysVarId;
use gcodec_lang::{BinaryOp, UnaryOp};
use gcodec_profile::Profile;
use gcodec_source::{codes, cp1252_byte};

use crate::loader::{LoadRequest, ProgramLoader};
use crate::value::{FrameValue, RtValue, RunError, finite_real, format_real, real_to_int};
use crate::vars::{Variables, undefined};

pub use assign::{assign, assign_in, assign_list, declare};
pub use functions::sprint;
pub use profile_variables::profile_system_variable;
pub(crate) use profile_variables::{profile_offsets, settable_offset};

/// Expressions nested deeper than this are [`codes::run::EXPRESSION_TOO_DEEP`]. The
/// parser's limits (64 brackets, 1000 operators a block) keep every
/// lowered expression well below it; the bound protects the stack from
/// hand-made AIL.
pub const MAX_DEPTH: usize = 1500;

/// Relative tolerance of REAL comparisons (reference §7.5: the control
/// compares REALs for relative equality, about 1e-12).
pub const REAL_TOLERANCE: f64 = 1e-12;

/// What a running machine (or the channel) knows beyond the variable
/// store: system variables, functions the executor provides (frames, tool
/// management), the axes. Every method has a default; the defaults read
/// the machine profile ([`RuntimeInterface::profile`]).
pub trait RuntimeInterface {
    /// The machine profile, if there is one.
    fn profile(&self) -> Option<&Profile> {
        None
    }

    /// Reads a system variable (a listed one by its id, another by its
    /// name, upper case with its `$`). The default is
    /// [`profile_system_variable`].
    fn system_variable(&self, name: &VarName, indices: &[RtValue]) -> Result<RtValue, RunError> {
        profile_system_variable(self.profile(), name, indices)
    }

    /// Writes a system variable. The default refuses
    /// ([`codes::run::READ_ONLY`]).
    fn set_system_variable(
        &mut self,
        name: &VarName,
        _indices: &[RtValue],
        _value: &RtValue,
    ) -> Result<(), RunError> {
        Err(RunError::new(
            codes::run::READ_ONLY,
            format!(
                "the system variable `{}` cannot be written here",
                name.as_str()
            ),
        ))
    }

    /// A function that is not built into the evaluator (frame functions,
    /// tool management, user functions): `None` when the runtime does not
    /// know it either ([`codes::run::UNKNOWN_FUNCTION`]).
    fn function(
        &self,
        _function: Function,
        _args: &[Option<RtValue>],
    ) -> Option<Result<RtValue, RunError>> {
        None
    }

    /// The frame chaining operator `:`. The default: not available.
    fn chain_frames(&self, _lhs: &FrameValue, _rhs: &FrameValue) -> Result<FrameValue, RunError> {
        Err(RunError::new(
            codes::run::UNKNOWN_FUNCTION,
            "frame chaining (`:`) is not available here",
        ))
    }

    /// Whether `name` (upper case) is an axis of the machine: a channel
    /// axis of the profile or a machine axis `AX1`, `AX2`, … (MD10000).
    fn is_axis(&self, name: &str) -> bool {
        let Some(profile) = self.profile() else {
            return false;
        };
        profile
            .axes
            .iter()
            .any(|a| a.name.get_ref().eq_ignore_ascii_case(name))
            || machine_axis_number(name, profile.axes.len()).is_some()
    }
}

/// `AX1`, `AX2`, … (any case): the index of machine axis `n` of `count`
/// axes (MD10000); `None` for another name or a number outside
/// `1 … count`.
pub(crate) fn machine_axis_number(name: &str, count: usize) -> Option<usize> {
    let bytes = name.as_bytes();
    if bytes.len() > 2 && bytes[..2].eq_ignore_ascii_case(b"AX") {
        let n: usize = name[2..].parse().ok()?;
        return (1..=count).contains(&n).then(|| n - 1);
    }
    None
}

/// A machine profile is a runtime that knows what the profile says.
impl RuntimeInterface for Profile {
    fn profile(&self) -> Option<&Profile> {
        Some(self)
    }
}

/// A runtime without a machine: `$PI` and nothing else.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoMachine;

impl RuntimeInterface for NoMachine {}

/// What an expression is evaluated against.
pub trait EvalContext {
    fn variables(&self) -> &Variables;
    fn runtime(&self) -> &dyn RuntimeInterface;

    /// Whether the program `name` (a name or path) is on the running
    /// program's search path (`ISFILE`); `None` where the context has no
    /// search path or `name` names no program.
    fn program_exists(&self, _name: &str) -> Option<bool> {
        None
    }
}

/// The plain context: a variable store and a runtime, and the programs
/// the running one can call.
#[derive(Clone, Copy)]
pub struct Env<'a> {
    pub vars: &'a Variables,
    pub runtime: &'a dyn RuntimeInterface,
    /// The loader and the running program's file.
    programs: Option<(&'a dyn ProgramLoader, &'a str)>,
}

impl<'a> Env<'a> {
    pub fn new(vars: &'a Variables, runtime: &'a dyn RuntimeInterface) -> Self {
        Self {
            vars,
            runtime,
            programs: None,
        }
    }

    /// With the programs `loader` finds for a call from `caller_file`.
    pub fn with_programs(mut self, loader: &'a dyn ProgramLoader, caller_file: &'a str) -> Self {
        self.programs = Some((loader, caller_file));
        self
    }
}

impl EvalContext for Env<'_> {
    fn variables(&self) -> &Variables {
        self.vars
    }

    fn runtime(&self) -> &dyn RuntimeInterface {
        self.runtime
    }

    fn program_exists(&self, name: &str) -> Option<bool> {
        let (loader, caller_file) = self.programs?;
        let name = name.trim().to_ascii_uppercase();
        loader.exists(&LoadRequest {
            name: &name,
            by_path: name.contains('/'),
            external: false,
            caller_file,
        })
    }
}

/// Evaluates an expression.
pub fn eval<C: EvalContext + ?Sized>(ctx: &C, expr: &Expr) -> Result<RtValue, RunError> {
    eval_at(ctx, expr, 0)
}

/// Evaluates a value: a constant as a number (INT when whole, see
/// [`number`]), an expression by [`eval`].
pub fn eval_value<C: EvalContext + ?Sized>(ctx: &C, value: &Value) -> Result<RtValue, RunError> {
    match value {
        Value::Const(n) => Ok(number(*n)),
        Value::Expr(e) => eval_at(ctx, e, 0),
    }
}

/// Evaluates to a REAL.
pub fn eval_real<C: EvalContext + ?Sized>(ctx: &C, value: &Value) -> Result<f64, RunError> {
    match value {
        Value::Const(n) => Ok(*n),
        Value::Expr(e) => eval_at(ctx, e, 0)?.to_real(),
    }
}

/// Evaluates to a BOOL (a condition).
pub fn eval_bool<C: EvalContext + ?Sized>(ctx: &C, expr: &Expr) -> Result<bool, RunError> {
    eval_at(ctx, expr, 0)?.to_bool()
}

/// A numeric constant: INT when it is a whole number in the INT range
/// (AIL does not keep whether it was written with a point), else REAL.
pub fn number(n: f64) -> RtValue {
    if n.fract() == 0.0 && n >= f64::from(i32::MIN) && n <= f64::from(i32::MAX) {
        RtValue::Int(n as i32)
    } else {
        RtValue::Real(n)
    }
}

fn eval_at<C: EvalContext + ?Sized>(
    ctx: &C,
    expr: &Expr,
    depth: usize,
) -> Result<RtValue, RunError> {
    // A thin dispatcher: the recursion goes through this frame and one of
    // the small ones below, so that deep expressions need little stack
    // also in unoptimised builds (which inline nothing); optimised builds
    // inline them.
    if depth > MAX_DEPTH {
        return Err(too_deep());
    }
    match expr {
        Expr::Number { value } => Ok(number(*value)),
        Expr::Binary { operator, lhs, rhs } => eval_binary(ctx, *operator, lhs, rhs, depth),
        Expr::Var {
            var_kind,
            name,
            indices,
        } => eval_var(ctx, *var_kind, name, indices, depth),
        Expr::Unary { operator, operand } => eval_unary(ctx, *operator, operand, depth),
        Expr::Call { name, args } => functions::call(ctx, name, args, depth),
        Expr::String { value } => Ok(RtValue::String(Arc::from(value.as_str()))),
        Expr::Bool { value } => Ok(RtValue::Bool(*value)),
    }
}

#[cold]
fn too_deep() -> RunError {
    RunError::new(
        codes::run::EXPRESSION_TOO_DEEP,
        format!("the expression is nested deeper than {MAX_DEPTH} levels"),
    )
}

fn eval_binary<C: EvalContext + ?Sized>(
    ctx: &C,
    op: BinaryOp,
    lhs: &Expr,
    rhs: &Expr,
    depth: usize,
) -> Result<RtValue, RunError> {
    let a = eval_at(ctx, lhs, depth + 1)?;
    let b = eval_at(ctx, rhs, depth + 1)?;
    binary(ctx.runtime(), op, a, b)
}

fn eval_unary<C: EvalContext + ?Sized>(
    ctx: &C,
    op: UnaryOp,
    operand: &Expr,
    depth: usize,
) -> Result<RtValue, RunError> {
    let v = eval_at(ctx, operand, depth + 1)?;
    unary(op, v)
}

fn eval_var<C: EvalContext + ?Sized>(
    ctx: &C,
    kind: VarKind,
    name: &VarName,
    indices: &[Expr],
    depth: usize,
) -> Result<RtValue, RunError> {
    // `R5`, the commonest variable of all: straight to the store.
    if kind == VarKind::RParameter
        && let Some(index) = constant_index(indices)
    {
        return ctx.variables().r(index).map(RtValue::Real);
    }
    match kind {
        VarKind::System => system_var(ctx, name, indices, depth),
        VarKind::Axis if indices.is_empty() => Ok(RtValue::axis(name.as_str())),
        kind => {
            let name = name.as_str();
            let mut buf = [0i32; 4];
            let idx = int_indices(ctx, indices, depth, &mut buf)?;
            if kind == VarKind::RParameter {
                return ctx.variables().read(kind, name, idx);
            }
            match ctx.variables().get(name) {
                Some(var) => var.read(name, idx),
                None if idx.is_empty() && ctx.runtime().is_axis(name) => Ok(RtValue::axis(name)),
                None => Err(undefined(name)),
            }
        }
    }
}

/// The one index of `R5`, when it is a whole constant. (`as` saturates,
/// NaN to 0, so the value comes back unchanged only from an INT.)
#[inline]
fn constant_index(indices: &[Expr]) -> Option<i32> {
    match indices {
        [Expr::Number { value }] if *value == f64::from(*value as i32) => Some(*value as i32),
        _ => None,
    }
}

/// The indices of an R parameter or user variable, as INTs (a REAL index
/// rounded), into `buf`.
fn int_indices<'b, C: EvalContext + ?Sized>(
    ctx: &C,
    indices: &[Expr],
    depth: usize,
    buf: &'b mut [i32; 4],
) -> Result<&'b [i32], RunError> {
    if indices.len() > buf.len() {
        return Err(RunError::new(
            codes::run::INDEX_COUNT,
            format!("{} indices: no variable has that many", indices.len()),
        ));
    }
    for (slot, e) in buf.iter_mut().zip(indices) {
        *slot = match e {
            // A constant index is nearly always whole: no rounding then.
            Expr::Number { value } if *value == f64::from(*value as i32) => *value as i32,
            Expr::Number { value } => real_to_int(*value)?,
            e => eval_at(ctx, e, depth + 1)?.to_int()?,
        };
    }
    Ok(&buf[..indices.len()])
}

/// The indices of a system variable: a name that is no variable (an
/// axis, or a frame component `TR FI RT SC MI`) is passed as an AXIS
/// value carrying the name.
fn system_indices<C: EvalContext + ?Sized>(
    ctx: &C,
    indices: &[Expr],
    depth: usize,
) -> Result<SystemIndices, RunError> {
    let index = |e: &Expr| match e {
        Expr::Var {
            var_kind: VarKind::User | VarKind::Axis,
            name,
            indices,
        } if indices.is_empty() && !ctx.variables().is_defined(name.as_str()) => {
            Ok(RtValue::axis(name.as_str()))
        }
        e => eval_at(ctx, e, depth + 1),
    };
    if indices.len() > INLINE_INDICES {
        return indices
            .iter()
            .map(index)
            .collect::<Result<_, _>>()
            .map(SystemIndices::Heap);
    }
    let mut values = [const { RtValue::Int(0) }; INLINE_INDICES];
    for (slot, e) in values.iter_mut().zip(indices) {
        *slot = index(e)?;
    }
    Ok(SystemIndices::Inline(values, indices.len()))
}

/// System-variable indices held without allocating up to this many.
const INLINE_INDICES: usize = 4;

/// The evaluated indices of a system variable: inline when there are at
/// most [`INLINE_INDICES`], so that reading `$P_UIFR[1, X, TR]` allocates
/// no list.
enum SystemIndices {
    /// The values and how many of them are used.
    Inline([RtValue; INLINE_INDICES], usize),
    Heap(Vec<RtValue>),
}

impl std::ops::Deref for SystemIndices {
    type Target = [RtValue];

    fn deref(&self) -> &[RtValue] {
        match self {
            Self::Inline(values, len) => &values[..*len],
            Self::Heap(values) => values,
        }
    }
}

#[inline(never)]
fn system_var<C: EvalContext + ?Sized>(
    ctx: &C,
    name: &VarName,
    indices: &[Expr],
    depth: usize,
) -> Result<RtValue, RunError> {
    match name {
        // The R parameters as system variables (`$R[5]`, `$R1`).
        VarName::System(SysVarId::R) => {
            let mut buf = [0i32; 4];
            let idx = int_indices(ctx, indices, depth, &mut buf)?;
            return ctx.variables().read(VarKind::RParameter, "R", idx);
        }
        VarName::Text(text) => {
            if indices.is_empty()
                && let Some(n) = numbered_r(text)
            {
                return ctx.variables().read(VarKind::RParameter, "R", &[n]);
            }
        }
        VarName::System(SysVarId::MC_MM_NUM_R_PARAM) if indices.is_empty() => {
            return Ok(RtValue::Int(
                i32::try_from(ctx.variables().r_count()).unwrap_or(i32::MAX),
            ));
        }
        VarName::System(_) => {}
    }
    let idx = system_indices(ctx, indices, depth)?;
    ctx.runtime().system_variable(name, &idx)
}

/// The number of `$R<n>`, an R parameter named by number (the form
/// synchronized actions use), which the AIL carries as its text.
pub(crate) fn numbered_r(name: &str) -> Option<i32> {
    name.strip_prefix("$R")?.parse().ok()
}

fn unary(op: UnaryOp, v: RtValue) -> Result<RtValue, RunError> {
    Ok(match op {
        UnaryOp::Neg => match v {
            RtValue::Real(r) => RtValue::Real(-r),
            RtValue::Int(i) => i
                .checked_neg()
                .map_or(RtValue::Real(-f64::from(i)), RtValue::Int),
            RtValue::Bool(_) | RtValue::Char(_) => RtValue::Int(-v.to_int()?),
            _ => return Err(operand_error("-", &v)),
        },
        UnaryOp::Plus => match v {
            RtValue::Real(_) | RtValue::Int(_) => v,
            RtValue::Bool(_) | RtValue::Char(_) => RtValue::Int(v.to_int()?),
            _ => return Err(operand_error("+", &v)),
        },
        UnaryOp::Not => RtValue::Bool(!v.to_bool()?),
        UnaryOp::BNot => RtValue::Int(!bit_operand("B_NOT", &v)?),
        UnaryOp::ToString => RtValue::String(Arc::from(v.to_text()?.as_str())),
    })
}

/// A number operand: integer (INT, BOOL, CHAR) or REAL.
#[derive(Clone, Copy)]
enum Num {
    I(i64),
    R(f64),
}

fn num(op: &str, v: &RtValue) -> Result<Num, RunError> {
    Ok(match *v {
        RtValue::Int(i) => Num::I(i64::from(i)),
        RtValue::Real(r) => Num::R(r),
        RtValue::Bool(b) => Num::I(i64::from(b)),
        RtValue::Char(c) => Num::I(i64::from(c)),
        _ => return Err(operand_error(op, v)),
    })
}

impl Num {
    fn real(self) -> f64 {
        match self {
            Num::I(i) => i as f64,
            Num::R(r) => r,
        }
    }
}

/// An integer result: INT when it fits, else REAL (the control computes
/// in REAL internally; an INT overflow is no alarm before assignment).
fn int_result(i: i64) -> RtValue {
    i32::try_from(i).map_or(RtValue::Real(i as f64), RtValue::Int)
}

fn operand_error(op: &str, v: &RtValue) -> RunError {
    RunError::new(
        codes::run::TYPE_MISMATCH,
        format!("`{op}` does not take a {} operand", v.type_name()),
    )
}

fn bit_operand(op: &str, v: &RtValue) -> Result<i32, RunError> {
    if !v.is_numeric() {
        return Err(operand_error(op, v));
    }
    v.to_int()
}

fn division_by_zero(op: &str) -> RunError {
    RunError::new(codes::run::DIVISION_BY_ZERO, format!("`{op}` by zero"))
}

/// REAL equality within [`REAL_TOLERANCE`], relative.
pub fn real_eq(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= REAL_TOLERANCE * a.abs().max(b.abs())
}

fn binary(
    rt: &dyn RuntimeInterface,
    op: BinaryOp,
    a: RtValue,
    b: RtValue,
) -> Result<RtValue, RunError> {
    use BinaryOp as B;
    let sym = op_symbol(op);
    Ok(match op {
        B::Add | B::Sub | B::Mul => match (num(sym, &a)?, num(sym, &b)?) {
            (Num::I(x), Num::I(y)) => int_result(match op {
                B::Add => x + y,
                B::Sub => x - y,
                _ => x * y,
            }),
            (x, y) => {
                let r = match op {
                    B::Add => x.real() + y.real(),
                    B::Sub => x.real() - y.real(),
                    _ => x.real() * y.real(),
                };
                RtValue::Real(finite_real(r, || written(sym, x.real(), y.real()))?)
            }
        },
        B::Div => {
            let (x, y) = (num(sym, &a)?.real(), num(sym, &b)?.real());
            if y == 0.0 {
                return Err(division_by_zero(sym));
            }
            RtValue::Real(finite_real(x / y, || written(sym, x, y))?)
        }
        B::IntDiv => match (num(sym, &a)?, num(sym, &b)?) {
            (_, Num::I(0)) => return Err(division_by_zero(sym)),
            (Num::I(x), Num::I(y)) => int_result(x / y),
            (x, y) => {
                if y.real() == 0.0 {
                    return Err(division_by_zero(sym));
                }
                let q = (x.real() / y.real()).trunc();
                if q >= f64::from(i32::MIN) && q <= f64::from(i32::MAX) {
                    RtValue::Int(q as i32)
                } else {
                    RtValue::Real(finite_real(q, || written(sym, x.real(), y.real()))?)
                }
            }
        },
        B::Mod => match (num(sym, &a)?, num(sym, &b)?) {
            (_, Num::I(0)) => return Err(division_by_zero(sym)),
            (Num::I(x), Num::I(y)) => int_result(x % y),
            (x, y) => {
                if y.real() == 0.0 {
                    return Err(division_by_zero(sym));
                }
                RtValue::Real(x.real() % y.real())
            }
        },
        B::BAnd => RtValue::Int(bit_operand(sym, &a)? & bit_operand(sym, &b)?),
        B::BOr => RtValue::Int(bit_operand(sym, &a)? | bit_operand(sym, &b)?),
        B::BXor => RtValue::Int(bit_operand(sym, &a)? ^ bit_operand(sym, &b)?),
        B::And => RtValue::Bool(a.to_bool()? & b.to_bool()?),
        B::Or => RtValue::Bool(a.to_bool()? | b.to_bool()?),
        B::Xor => RtValue::Bool(a.to_bool()? ^ b.to_bool()?),
        B::Concat => {
            let mut text = a.to_text()?;
            b.write_text(&mut text)?;
            RtValue::String(Arc::from(text.as_str()))
        }
        B::Eq | B::Ne | B::Lt | B::Gt | B::Le | B::Ge => RtValue::Bool(compare(op, &a, &b)?),
        B::Chain => match (&a, &b) {
            (RtValue::Frame(x), RtValue::Frame(y)) => {
                RtValue::Frame(Arc::new(rt.chain_frames(x, y)?))
            }
            (RtValue::Frame(_), other) | (other, _) => return Err(operand_error(sym, other)),
        },
    })
}

/// `x op y` as the program would write it, for a message.
fn written(op: &str, x: f64, y: f64) -> String {
    let mut text = String::from("`");
    format_real(x, &mut text);
    text.push(' ');
    text.push_str(op);
    text.push(' ');
    format_real(y, &mut text);
    text.push('`');
    text
}

fn op_symbol(op: BinaryOp) -> &'static str {
    use BinaryOp as B;
    match op {
        B::Mul => "*",
        B::Div => "/",
        B::IntDiv => "DIV",
        B::Mod => "MOD",
        B::Add => "+",
        B::Sub => "-",
        B::BAnd => "B_AND",
        B::BXor => "B_XOR",
        B::BOr => "B_OR",
        B::And => "AND",
        B::Xor => "XOR",
        B::Or => "OR",
        B::Concat => "<<",
        B::Eq => "==",
        B::Ne => "<>",
        B::Lt => "<",
        B::Gt => ">",
        B::Le => "<=",
        B::Ge => ">=",
        B::Chain => ":",
    }
}

fn compare(op: BinaryOp, a: &RtValue, b: &RtValue) -> Result<bool, RunError> {
    use BinaryOp as B;
    use std::cmp::Ordering;
    let sym = op_symbol(op);
    let ordering = match (a, b) {
        (x, y) if x.is_numeric() && y.is_numeric() => match (num(sym, x)?, num(sym, y)?) {
            (Num::I(i), Num::I(j)) => i.cmp(&j),
            (x, y) => {
                let (x, y) = (x.real(), y.real());
                if real_eq(x, y) {
                    Ordering::Equal
                } else if x < y {
                    Ordering::Less
                } else if x > y {
                    Ordering::Greater
                } else {
                    // NaN: equal to nothing, and neither less nor greater.
                    return Ok(op == B::Ne);
                }
            }
        },
        (RtValue::String(_) | RtValue::Char(_), RtValue::String(_) | RtValue::Char(_)) => {
            code_page_keys(a).cmp(code_page_keys(b))
        }
        (RtValue::Axis(x), RtValue::Axis(y) | RtValue::String(y))
        | (RtValue::String(x), RtValue::Axis(y))
            if matches!(op, B::Eq | B::Ne) =>
        {
            return Ok(x.eq_ignore_ascii_case(y) == (op == B::Eq));
        }
        (RtValue::Frame(x), RtValue::Frame(y)) if matches!(op, B::Eq | B::Ne) => {
            return Ok((x == y) == (op == B::Eq));
        }
        _ => {
            return Err(RunError::new(
                codes::run::TYPE_MISMATCH,
                format!(
                    "`{sym}` cannot compare a {} with a {}",
                    a.type_name(),
                    b.type_name()
                ),
            ));
        }
    };
    Ok(match op {
        B::Eq => ordering.is_eq(),
        B::Ne => ordering.is_ne(),
        B::Lt => ordering.is_lt(),
        B::Gt => ordering.is_gt(),
        B::Le => ordering.is_le(),
        _ => ordering.is_ge(),
    })
}

/// The characters of a STRING or CHAR as the control orders them, for
/// comparisons: by their byte in the code page (so that `"ä"` equals the
/// CHAR 228 and sorts after `"z"`), a character the code page lacks after
/// every byte, by its code point.
fn code_page_keys(v: &RtValue) -> impl Iterator<Item = u32> + '_ {
    let (text, code) = match v {
        RtValue::String(s) => (&**s, None),
        RtValue::Char(c) => ("", Some(u32::from(*c))),
        _ => ("", None),
    };
    let key = |c: char| cp1252_byte(c).map_or(0x100 + u32::from(c), u32::from);
    code.into_iter().chain(text.chars().map(key))
}
