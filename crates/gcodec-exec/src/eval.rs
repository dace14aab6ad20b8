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

use std::f64::consts::PI;
use std::sync::Arc;

use gcodec_ail::{AssignList, Declare, Expr, Value, VarKind};
use gcodec_lang::{BinaryOp, UnaryOp};
use gcodec_profile::{Profile, ToolChangeMode};

use crate::value::{FrameAxis, FrameValue, RtValue, RunError, char_text, codes, real_to_int};
use crate::vars::{Init, Scope, Variables, undefined};

/// Expressions nested deeper than this are [`codes::TOO_DEEP`]. The
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

    /// Reads a system variable (`name` upper case with its `$`). The
    /// default is [`profile_system_variable`].
    fn system_variable(&self, name: &str, indices: &[RtValue]) -> Result<RtValue, RunError> {
        profile_system_variable(self.profile(), name, indices)
    }

    /// Writes a system variable. The default refuses
    /// ([`codes::READ_ONLY`]).
    fn set_system_variable(
        &mut self,
        name: &str,
        _indices: &[RtValue],
        _value: &RtValue,
    ) -> Result<(), RunError> {
        Err(RunError::new(
            codes::READ_ONLY,
            format!("the system variable `{name}` cannot be written here"),
        ))
    }

    /// A function that is not built into the evaluator (frame functions,
    /// tool management, user functions): `None` when the runtime does not
    /// know it either ([`codes::UNKNOWN_FUNCTION`]).
    fn function(
        &self,
        _name: &str,
        _args: &[Option<RtValue>],
    ) -> Option<Result<RtValue, RunError>> {
        None
    }

    /// The frame chaining operator `:`. The default: not available.
    fn chain_frames(&self, _lhs: &FrameValue, _rhs: &FrameValue) -> Result<FrameValue, RunError> {
        Err(RunError::new(
            codes::UNKNOWN_FUNCTION,
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
}

/// The plain context: a variable store and a runtime.
#[derive(Clone, Copy)]
pub struct Env<'a> {
    pub vars: &'a Variables,
    pub runtime: &'a dyn RuntimeInterface,
}

impl<'a> Env<'a> {
    pub fn new(vars: &'a Variables, runtime: &'a dyn RuntimeInterface) -> Self {
        Self { vars, runtime }
    }
}

impl EvalContext for Env<'_> {
    fn variables(&self) -> &Variables {
        self.vars
    }

    fn runtime(&self) -> &dyn RuntimeInterface {
        self.runtime
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
        Expr::Call { name, args } => call(ctx, name, args, depth),
        Expr::String { value } => Ok(RtValue::String(Arc::from(value.as_str()))),
        Expr::Bool { value } => Ok(RtValue::Bool(*value)),
    }
}

#[cold]
fn too_deep() -> RunError {
    RunError::new(
        codes::TOO_DEEP,
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
    name: &str,
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
        VarKind::Axis if indices.is_empty() => Ok(RtValue::axis(name)),
        kind => {
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

/// The one index of `R5`, when it is a whole constant.
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
            codes::INDEX_COUNT,
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
        } if indices.is_empty() && !ctx.variables().is_defined(name) => Ok(RtValue::axis(name)),
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
    name: &str,
    indices: &[Expr],
    depth: usize,
) -> Result<RtValue, RunError> {
    // The R parameters as system variables (`$R1`, `$R[5]`).
    if let Some(rest) = name.strip_prefix("$R") {
        if rest.is_empty() {
            let mut buf = [0i32; 4];
            let idx = int_indices(ctx, indices, depth, &mut buf)?;
            return ctx.variables().read(VarKind::RParameter, "R", idx);
        }
        if indices.is_empty()
            && let Ok(n) = rest.parse::<i32>()
        {
            return ctx.variables().read(VarKind::RParameter, "R", &[n]);
        }
    }
    if name == "$MC_MM_NUM_R_PARAM" && indices.is_empty() {
        return Ok(RtValue::Int(
            i32::try_from(ctx.variables().r_count()).unwrap_or(i32::MAX),
        ));
    }
    let idx = system_indices(ctx, indices, depth)?;
    ctx.runtime().system_variable(name, &idx)
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
        codes::TYPE_MISMATCH,
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
    RunError::new(codes::DIVISION_BY_ZERO, format!("`{op}` by zero"))
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
            (x, y) => RtValue::Real(match op {
                B::Add => x.real() + y.real(),
                B::Sub => x.real() - y.real(),
                _ => x.real() * y.real(),
            }),
        },
        B::Div => {
            let (x, y) = (num(sym, &a)?.real(), num(sym, &b)?.real());
            if y == 0.0 {
                return Err(division_by_zero(sym));
            }
            RtValue::Real(x / y)
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
                    RtValue::Real(q)
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
            text_bytes(a).cmp(text_bytes(b))
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
                codes::TYPE_MISMATCH,
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

/// The bytes of a STRING or CHAR, for comparisons.
fn text_bytes(v: &RtValue) -> &[u8] {
    match v {
        RtValue::String(s) => s.as_bytes(),
        RtValue::Char(c) => std::slice::from_ref(c),
        _ => &[],
    }
}

// ---------------------------------------------------------------------
// Built-in functions (reference §7.6)

/// Evaluates the arguments of a call lazily.
struct Args<'a, C: EvalContext + ?Sized> {
    ctx: &'a C,
    name: &'a str,
    args: &'a [Option<Expr>],
    depth: usize,
}

impl<C: EvalContext + ?Sized> Args<'_, C> {
    fn count(&self, min: usize, max: usize) -> Result<(), RunError> {
        let n = self.args.len();
        if n < min || n > max {
            let expected = if min == max {
                format!("{min}")
            } else {
                format!("{min} to {max}")
            };
            return Err(RunError::new(
                codes::ARGUMENT_COUNT,
                format!("`{}` takes {expected} arguments, not {n}", self.name),
            ));
        }
        Ok(())
    }

    fn present(&self, i: usize) -> bool {
        matches!(self.args.get(i), Some(Some(_)))
    }

    fn value(&self, i: usize) -> Result<RtValue, RunError> {
        match self.args.get(i) {
            Some(Some(e)) => eval_at(self.ctx, e, self.depth + 1),
            _ => Err(RunError::new(
                codes::ARGUMENT_COUNT,
                format!("`{}` needs its argument {}", self.name, i + 1),
            )),
        }
    }

    fn real(&self, i: usize) -> Result<f64, RunError> {
        let v = self.value(i)?;
        if !v.is_numeric() {
            return Err(self.wrong_type(i, &v, "a number"));
        }
        v.to_real()
    }

    fn int(&self, i: usize) -> Result<i32, RunError> {
        let v = self.value(i)?;
        if !v.is_numeric() {
            return Err(self.wrong_type(i, &v, "a number"));
        }
        v.to_int()
    }

    fn bool(&self, i: usize) -> Result<bool, RunError> {
        self.value(i)?.to_bool()
    }

    fn string(&self, i: usize) -> Result<Arc<str>, RunError> {
        match self.value(i)? {
            RtValue::String(s) => Ok(s),
            RtValue::Char(c) => Ok(Arc::from(char_text(c).as_str())),
            v => Err(self.wrong_type(i, &v, "a STRING")),
        }
    }

    fn char(&self, i: usize) -> Result<u8, RunError> {
        match self.value(i)? {
            v @ (RtValue::Char(_) | RtValue::String(_)) => v.to_char(),
            v => Err(self.wrong_type(i, &v, "a CHAR")),
        }
    }

    fn wrong_type(&self, i: usize, v: &RtValue, wanted: &str) -> RunError {
        RunError::new(
            codes::TYPE_MISMATCH,
            format!(
                "argument {} of `{}` must be {wanted}, not a {}",
                i + 1,
                self.name,
                v.type_name()
            ),
        )
    }
}

fn domain(name: &str, x: f64, why: &str) -> RunError {
    RunError::new(codes::DOMAIN, format!("`{name}({x})`: {why}"))
}

/// A result of degrees within 1e-12 of a whole number is that number
/// (`ASIN(0.5)` = 30, not 30.000000000000004).
fn snap_degrees(x: f64) -> f64 {
    let r = x.round();
    if (x - r).abs() < 1e-12 { r } else { x }
}

/// Sine of degrees, exact at multiples of 30 and 90 degrees.
fn sin_deg(x: f64) -> f64 {
    let r = x.rem_euclid(360.0);
    let quadrant = (r / 90.0).floor();
    let rem = r - 90.0 * quadrant;
    let (s, c) = (sin_first(rem), sin_first(90.0 - rem));
    match quadrant as i32 {
        0 => s,
        1 => c,
        2 => -s,
        _ => -c,
    }
}

/// Sine of 0…90 degrees.
fn sin_first(d: f64) -> f64 {
    if d == 0.0 {
        0.0
    } else if d == 30.0 {
        0.5
    } else if d == 90.0 {
        1.0
    } else {
        d.to_radians().sin()
    }
}

fn real(v: f64) -> Result<RtValue, RunError> {
    Ok(RtValue::Real(v))
}

#[inline(never)]
fn call<C: EvalContext + ?Sized>(
    ctx: &C,
    name: &str,
    args: &[Option<Expr>],
    depth: usize,
) -> Result<RtValue, RunError> {
    let a = Args {
        ctx,
        name,
        args,
        depth,
    };
    match name {
        // Arithmetic: REAL results.
        "ABS" | "SQRT" | "POT" | "TRUNC" | "ROUND" | "ROUNDUP" | "LN" | "EXP" | "SIN" | "COS"
        | "TAN" | "ASIN" | "ACOS" | "ITOR" | "BTOR" => {
            a.count(1, 1)?;
            let x = match name {
                "BTOR" => return real(if a.bool(0)? { 1.0 } else { 0.0 }),
                "ITOR" => return real(f64::from(a.int(0)?)),
                _ => a.real(0)?,
            };
            match name {
                "ABS" => real(x.abs()),
                "SQRT" if x < 0.0 => Err(domain(name, x, "the square root of a negative number")),
                "SQRT" => real(x.sqrt()),
                "POT" => real(x * x),
                "TRUNC" => real(x.trunc()),
                "ROUND" => real(x.round()),
                "ROUNDUP" => real(x.ceil()),
                "LN" if x <= 0.0 => Err(domain(name, x, "the logarithm needs a positive number")),
                "LN" => real(x.ln()),
                "EXP" => real(x.exp()),
                "SIN" => real(sin_deg(x)),
                "COS" => real(sin_deg(x + 90.0)),
                "TAN" => {
                    let c = sin_deg(x + 90.0);
                    if c == 0.0 {
                        Err(domain(name, x, "the tangent of ±90° is infinite"))
                    } else {
                        real(sin_deg(x) / c)
                    }
                }
                "ASIN" | "ACOS" if !(-1.0..=1.0).contains(&x) => {
                    Err(domain(name, x, "the argument must lie in −1…1"))
                }
                "ASIN" => real(snap_degrees(x.asin().to_degrees())),
                _ => real(snap_degrees(x.acos().to_degrees())),
            }
        }
        "ATAN2" => {
            a.count(2, 2)?;
            let (y, x) = (a.real(0)?, a.real(1)?);
            if y == 0.0 && x == 0.0 {
                return Err(RunError::new(
                    codes::DOMAIN,
                    "`ATAN2(0, 0)`: no angle without a direction",
                ));
            }
            real(snap_degrees(y.atan2(x).to_degrees()))
        }
        "MINVAL" | "MAXVAL" => {
            a.count(2, 2)?;
            let (x, y) = (a.real(0)?, a.real(1)?);
            real(if name == "MINVAL" { x.min(y) } else { x.max(y) })
        }
        "BOUND" => {
            a.count(3, 3)?;
            let (lo, hi, x) = (a.real(0)?, a.real(1)?, a.real(2)?);
            if lo > hi {
                return Err(RunError::new(
                    codes::DOMAIN,
                    format!("`BOUND({lo}, {hi}, …)`: the minimum is above the maximum"),
                ));
            }
            real(x.clamp(lo, hi))
        }
        // Conversions.
        "RTOI" => {
            a.count(1, 1)?;
            Ok(RtValue::Int(real_to_int(a.real(0)?)?))
        }
        "RTOB" => {
            a.count(1, 1)?;
            Ok(RtValue::Bool(a.real(0)? != 0.0))
        }
        "ITOB" => {
            a.count(1, 1)?;
            Ok(RtValue::Bool(a.int(0)? != 0))
        }
        "BTOI" => {
            a.count(1, 1)?;
            Ok(RtValue::Int(i32::from(a.bool(0)?)))
        }
        "NUMBER" | "ISNUMBER" => {
            a.count(1, 1)?;
            let s = a.string(0)?;
            let parsed = parse_number(&s);
            if name == "ISNUMBER" {
                return Ok(RtValue::Bool(parsed.is_some()));
            }
            parsed.map(RtValue::Real).ok_or_else(|| {
                RunError::new(
                    codes::INVALID_NUMBER,
                    format!("`NUMBER`: \"{s}\" is not a number"),
                )
            })
        }
        "AXNAME" => {
            a.count(1, 1)?;
            let s = a.string(0)?;
            let upper = s.trim().to_ascii_uppercase();
            if ctx.runtime().is_axis(&upper) {
                Ok(RtValue::Axis(Arc::from(upper.as_str())))
            } else {
                Err(RunError::new(
                    codes::UNKNOWN_AXIS,
                    format!("`AXNAME`: \"{s}\" is not an axis of the machine"),
                ))
            }
        }
        "AXSTRING" => {
            a.count(1, 1)?;
            match a.value(0)? {
                RtValue::Axis(n) => Ok(RtValue::String(n)),
                v => Err(a.wrong_type(0, &v, "an AXIS")),
            }
        }
        // Strings; positions count from 0, −1 is "not found".
        "STRLEN" => {
            a.count(1, 1)?;
            Ok(RtValue::Int(a.string(0)?.len() as i32))
        }
        "TOUPPER" | "TOLOWER" => {
            a.count(1, 1)?;
            let s = a.string(0)?;
            let t = if name == "TOUPPER" {
                s.to_ascii_uppercase()
            } else {
                s.to_ascii_lowercase()
            };
            Ok(RtValue::String(Arc::from(t.as_str())))
        }
        "INDEX" | "RINDEX" => {
            a.count(2, 2)?;
            let (s, c) = (a.string(0)?, a.char(1)?);
            let bytes = s.as_bytes();
            let at = if name == "INDEX" {
                bytes.iter().position(|&b| b == c)
            } else {
                bytes.iter().rposition(|&b| b == c)
            };
            Ok(position(at))
        }
        "MINDEX" => {
            a.count(2, 2)?;
            let (s, set) = (a.string(0)?, a.string(1)?);
            let at = s.bytes().position(|b| set.as_bytes().contains(&b));
            Ok(position(at))
        }
        "MATCH" => {
            a.count(2, 2)?;
            let (s, sub) = (a.string(0)?, a.string(1)?);
            Ok(position(s.find(&*sub)))
        }
        "SUBSTR" => {
            a.count(2, 3)?;
            let s = a.string(0)?;
            let start = a.int(1)?;
            let len = if a.present(2) { Some(a.int(2)?) } else { None };
            substr(&s, start, len)
        }
        "SPRINT" => {
            if args.is_empty() {
                a.count(1, usize::MAX)?;
            }
            let format = a.string(0)?;
            let mut values = Vec::with_capacity(args.len() - 1);
            for i in 1..args.len() {
                values.push(a.value(i)?);
            }
            sprint(&format, &values).map(|t| RtValue::String(Arc::from(t.as_str())))
        }
        _ => {
            let mut values = Vec::with_capacity(args.len());
            for arg in args {
                values.push(match arg {
                    Some(e) => Some(eval_at(ctx, e, depth + 1)?),
                    None => None,
                });
            }
            ctx.runtime().function(name, &values).unwrap_or_else(|| {
                Err(RunError::new(
                    codes::UNKNOWN_FUNCTION,
                    format!("`{name}` is not a function the executor knows"),
                ))
            })
        }
    }
}

fn position(at: Option<usize>) -> RtValue {
    RtValue::Int(at.map_or(-1, |i| i as i32))
}

/// `SUBSTR(s, start, len)`: the characters from `start` (0-based) on,
/// `len` of them or to the end; a part past the end is cut off (a start
/// at or past the end gives the empty string). A negative start or length
/// is [`codes::INDEX_OUT_OF_RANGE`].
fn substr(s: &str, start: i32, len: Option<i32>) -> Result<RtValue, RunError> {
    let bad = |what: &str, v: i32| {
        RunError::new(
            codes::INDEX_OUT_OF_RANGE,
            format!("`SUBSTR`: the {what} {v} is negative"),
        )
    };
    let start = usize::try_from(start).map_err(|_| bad("start", start))?;
    let bytes = s.as_bytes();
    let from = start.min(bytes.len());
    let to = match len {
        Some(n) => from.saturating_add(usize::try_from(n).map_err(|_| bad("length", n))?),
        None => bytes.len(),
    }
    .min(bytes.len());
    let text: String = bytes[from..to].iter().map(|&b| char::from(b)).collect();
    Ok(RtValue::String(Arc::from(text.as_str())))
}

/// A number as `NUMBER` reads it: blanks around, a sign, digits with an
/// optional point, an optional exponent `E`/`EX` with a sign (`1.5`,
/// `-3`, `.5`, `2EX3`, `1e-4`).
fn parse_number(text: &str) -> Option<f64> {
    let t = text.trim();
    let b = t.as_bytes();
    let mut i = 0;
    if matches!(b.first(), Some(b'+' | b'-')) {
        i += 1;
    }
    let mut digits = 0;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
        digits += 1;
    }
    if i < b.len() && b[i] == b'.' {
        i += 1;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
            digits += 1;
        }
    }
    if digits == 0 {
        return None;
    }
    let mantissa = &t[..i];
    let mut exponent = 0i32;
    if i < b.len() && b[i].eq_ignore_ascii_case(&b'E') {
        i += 1;
        if i < b.len() && b[i].eq_ignore_ascii_case(&b'X') {
            i += 1;
        }
        let sign_at = i;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        let exp_digits = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        if i == exp_digits {
            return None;
        }
        exponent = t[sign_at..i].parse().ok()?;
    }
    if i != b.len() {
        return None;
    }
    let value: f64 = format!("{mantissa}e{exponent}").parse().ok()?;
    value.is_finite().then_some(value)
}

/// `SPRINT(format, values…)`: the directives `%D` (INT), `%F` (REAL, 6
/// decimals), `%E`, `%G`, `%S` (the value as `<<` writes it), `%C`
/// (CHAR), `%B` (BOOL as `TRUE`/`FALSE`), `%X` (INT in hexadecimal) and
/// `%%`, each with an optional width (`%5D`, blanks on the left) and
/// precision (`%.3F`, `%10.3F`). Upper or lower case.
pub fn sprint(format: &str, values: &[RtValue]) -> Result<String, RunError> {
    use std::fmt::Write as _;
    let mut out = String::new();
    let mut next = values.iter();
    let mut chars = format.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
            continue;
        }
        if chars.peek() == Some(&'%') {
            chars.next();
            out.push('%');
            continue;
        }
        let mut width = String::new();
        while let Some(&d) = chars.peek().filter(|d| d.is_ascii_digit()) {
            width.push(d);
            chars.next();
        }
        let mut precision = None;
        if chars.peek() == Some(&'.') {
            chars.next();
            let mut p = String::new();
            while let Some(&d) = chars.peek().filter(|d| d.is_ascii_digit()) {
                p.push(d);
                chars.next();
            }
            precision = Some(p.parse::<usize>().unwrap_or(0).min(16));
        }
        let width: usize = width.parse::<usize>().unwrap_or(0).min(200);
        let Some(directive) = chars.next() else {
            return Err(RunError::new(
                codes::FORMAT,
                "`SPRINT`: the format ends in the middle of a directive",
            ));
        };
        let directive = directive.to_ascii_uppercase();
        if !"DFEGSCBX".contains(directive) {
            return Err(RunError::new(
                codes::FORMAT,
                format!("`SPRINT`: `%{directive}` is not a format directive"),
            ));
        }
        let Some(v) = next.next() else {
            return Err(RunError::new(
                codes::ARGUMENT_COUNT,
                format!("`SPRINT`: no value for the directive `%{directive}`"),
            ));
        };
        let field = match directive {
            'D' => v.to_int()?.to_string(),
            'X' => format!("{:X}", v.to_int()?),
            'F' => format!("{:.*}", precision.unwrap_or(6), v.to_real()?),
            'E' => c_exponent(v.to_real()?, precision.unwrap_or(6)),
            'G' => c_general(v.to_real()?, precision.unwrap_or(6)),
            'C' => char::from(v.to_char()?).to_string(),
            'B' => if v.to_bool()? { "TRUE" } else { "FALSE" }.to_owned(),
            _ => {
                let mut t = v.to_text()?;
                if let Some(p) = precision {
                    t.truncate(p.min(t.len()));
                }
                t
            }
        };
        let _ = write!(out, "{field:>width$}");
    }
    Ok(out)
}

/// C's `%.*e`: `1.500000e+02`.
fn c_exponent(x: f64, precision: usize) -> String {
    let text = format!("{x:.precision$e}");
    match text.split_once('e') {
        Some((m, e)) => {
            let (sign, digits) = match e.strip_prefix('-') {
                Some(d) => ('-', d),
                None => ('+', e),
            };
            format!("{m}e{sign}{digits:0>2}")
        }
        None => text,
    }
}

/// C's `%.*g`: `precision` significant digits, trailing zeros removed,
/// exponent form for very small or large numbers.
fn c_general(x: f64, precision: usize) -> String {
    let p = precision.max(1);
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 { "0".into() } else { format!("{x}") };
    }
    let exp = x.abs().log10().floor() as i32;
    let trim = |mut s: String| {
        if s.contains('.') {
            while s.ends_with('0') {
                s.pop();
            }
            if s.ends_with('.') {
                s.pop();
            }
        }
        s
    };
    if exp < -4 || exp >= p as i32 {
        let text = c_exponent(x, p - 1);
        match text.split_once('e') {
            Some((m, e)) => format!("{}e{e}", trim(m.to_owned())),
            None => text,
        }
    } else {
        let decimals = (p as i32 - 1 - exp).max(0) as usize;
        trim(format!("{x:.decimals$}"))
    }
}

// ---------------------------------------------------------------------
// System variables from the profile

/// The system variables a machine profile answers, the default of
/// [`RuntimeInterface::system_variable`]:
///
/// * `$PI` (also without a profile);
/// * `$P_TOOLNO`, `$P_TOOLP`, `$P_TOOL`: 0 — no tool and no edge active
///   at the start of a program (the channel answers with its own state);
/// * `$P_UIFR[n]` (a FRAME) and `$P_UIFR[n, axis, TR|FI|RT|SC|MI]` (a
///   REAL): the settable offset with the `$P_UIFR` index `n` as the
///   profile's `work_offsets.values` give it (translations; the other
///   components neutral); `n` must be an offset the machine has;
/// * `$TC_DP<k>[t, d]`: the tool table's edge `d` of tool `t`: `$TC_DP3`
///   its length, `$TC_DP6` its radius, the other parameters 2…25 0; the
///   tool type `$TC_DP1` is not in the profile (an error);
/// * `$P_AXN1`…`$P_AXN3`: the geometry axes in channel order;
/// * `$MC_TOOL_CHANGE_MODE`: 0 (`direct`) or 1 (`deferred_m6`).
///
/// Any other variable is [`codes::SYSTEM_VARIABLE`] naming it.
pub fn profile_system_variable(
    profile: Option<&Profile>,
    name: &str,
    indices: &[RtValue],
) -> Result<RtValue, RunError> {
    if name == "$PI" {
        no_indices(name, indices)?;
        return Ok(RtValue::Real(PI));
    }
    let Some(profile) = profile else {
        return Err(RunError::new(
            codes::SYSTEM_VARIABLE,
            format!("the system variable `{name}` has no value without a machine profile"),
        ));
    };
    match name {
        "$P_TOOLNO" | "$P_TOOLP" | "$P_TOOL" => {
            no_indices(name, indices)?;
            Ok(RtValue::Int(0))
        }
        "$MC_TOOL_CHANGE_MODE" => {
            no_indices(name, indices)?;
            Ok(RtValue::Int(match profile.tool_change.tool_change_mode {
                ToolChangeMode::Direct => 0,
                ToolChangeMode::DeferredM6 => 1,
            }))
        }
        "$P_AXN1" | "$P_AXN2" | "$P_AXN3" => {
            no_indices(name, indices)?;
            let n = usize::from(name.as_bytes()[6] - b'1');
            profile
                .axes
                .iter()
                .filter(|a| a.geometry)
                .nth(n)
                .map(|a| RtValue::axis(a.name.get_ref()))
                .ok_or_else(|| {
                    RunError::new(
                        codes::SYSTEM_VARIABLE,
                        format!("`{name}`: the machine has no geometry axis {}", n + 1),
                    )
                })
        }
        "$P_UIFR" => settable_frame(profile, name, indices),
        _ => {
            if let Some(k) = name.strip_prefix("$TC_DP")
                && let Ok(k) = k.parse::<u32>()
                && (1..=25).contains(&k)
            {
                return tool_parameter(profile, name, k, indices);
            }
            Err(RunError::new(
                codes::SYSTEM_VARIABLE,
                format!(
                    "the system variable `{name}` has no value here: the machine profile does not give it"
                ),
            ))
        }
    }
}

fn no_indices(name: &str, indices: &[RtValue]) -> Result<(), RunError> {
    if indices.is_empty() {
        Ok(())
    } else {
        Err(sys_index_count(name, "no", indices.len()))
    }
}

fn sys_index_count(name: &str, expected: &str, given: usize) -> RunError {
    RunError::new(
        codes::INDEX_COUNT,
        format!("`{name}` takes {expected} indices, not {given}"),
    )
}

fn settable_frame(profile: &Profile, name: &str, indices: &[RtValue]) -> Result<RtValue, RunError> {
    let (n, component) = match indices {
        [n] => (n, None),
        [n, axis, component] => (n, Some((axis, component))),
        _ => return Err(sys_index_count(name, "1 or 3", indices.len())),
    };
    let supported = profile.work_offsets.supported_group8();
    let index = settable_offset(n.to_int()?, |i| supported.get(i) == Some(&true))?;
    let frame = FrameValue {
        axes: profile_offsets(profile, index)
            .map(|(axis, v)| FrameAxis {
                translation: v,
                ..FrameAxis::neutral(&axis.to_ascii_uppercase())
            })
            .collect(),
    };
    let Some((axis, component)) = component else {
        return Ok(RtValue::Frame(Arc::new(frame)));
    };
    let axis = match axis {
        RtValue::Axis(a) | RtValue::String(a) => a,
        v => return Err(RunError::type_mismatch(v, "AXIS")),
    };
    frame.component_of(axis, component).map(RtValue::Real)
}

/// The settable offset `$P_UIFR[n]` addresses: `n` when `exists(n)`, else
/// the error that the machine has no settable offset `n`.
pub(crate) fn settable_offset(
    n: i32,
    exists: impl FnOnce(usize) -> bool,
) -> Result<usize, RunError> {
    usize::try_from(n)
        .ok()
        .filter(|&i| exists(i))
        .ok_or_else(|| {
            RunError::new(
                codes::INDEX_OUT_OF_RANGE,
                format!("`$P_UIFR[{n}]`: the machine has no settable offset {n}"),
            )
        })
}

/// The translations (axis name as the profile writes it, value) the
/// profile gives the settable offset with the Group 8 index `index`
/// (`[work_offsets.values.G54]`); none when it gives none.
pub(crate) fn profile_offsets(
    profile: &Profile,
    index: usize,
) -> impl Iterator<Item = (&str, f64)> {
    profile
        .work_offsets
        .values
        .iter()
        .find(|(code, _)| gcodec_profile::group8_index(code.get_ref()) == Some(index as u8))
        .into_iter()
        .flat_map(|(_, axes)| axes.iter().map(|(axis, &v)| (axis.get_ref().as_str(), v)))
}

fn tool_parameter(
    profile: &Profile,
    name: &str,
    k: u32,
    indices: &[RtValue],
) -> Result<RtValue, RunError> {
    let [t, d] = indices else {
        return Err(sys_index_count(name, "2", indices.len()));
    };
    let (t, d) = (t.to_int()?, d.to_int()?);
    let tool = u32::try_from(t)
        .ok()
        .and_then(|t| profile.tool(t))
        .ok_or_else(|| {
            RunError::new(
                codes::INDEX_OUT_OF_RANGE,
                format!("`{name}[{t},{d}]`: the tool table has no tool {t}"),
            )
        })?;
    let edge = u32::try_from(d)
        .ok()
        .and_then(|d| tool.edge(d))
        .ok_or_else(|| {
            RunError::new(
                codes::INDEX_OUT_OF_RANGE,
                format!("`{name}[{t},{d}]`: tool {t} has no cutting edge D{d}"),
            )
        })?;
    match k {
        1 => Err(RunError::new(
            codes::SYSTEM_VARIABLE,
            format!("`{name}[{t},{d}]`: the tool type is not in the machine profile"),
        )),
        3 => Ok(RtValue::Real(edge.length)),
        6 => Ok(RtValue::Real(edge.radius)),
        _ => Ok(RtValue::Real(0.0)),
    }
}

// ---------------------------------------------------------------------
// Instructions that write variables

fn target_parts(target: &Expr) -> Result<(VarKind, &str, &[Expr]), RunError> {
    match target {
        Expr::Var {
            var_kind,
            name,
            indices,
        } => Ok((*var_kind, name, indices)),
        _ => Err(RunError::new(
            codes::TYPE_MISMATCH,
            "only a variable can be assigned to",
        )),
    }
}

/// `assign`: `target = value`, the value converted to the target's type.
/// A system variable is written through the runtime (`$R…` are the R
/// parameters).
pub fn assign(
    vars: &mut Variables,
    rt: &mut dyn RuntimeInterface,
    target: &Expr,
    value: &Value,
) -> Result<(), RunError> {
    let (kind, name, indices) = target_parts(target)?;
    let env = Env::new(vars, &*rt);
    let v = eval_value(&env, value)?;
    if kind == VarKind::System && !(name.starts_with("$R") && is_r_system(name)) {
        let idx = system_indices(&env, indices, 0)?;
        return rt.set_system_variable(name, &idx, &v);
    }
    let mut buf = [0i32; 4];
    let (kind, name, idx) = resolve_target(&env, kind, name, indices, &mut buf)?;
    vars.write(kind, name, idx, &v)
}

/// `$R`, `$R5`: the R parameters.
fn is_r_system(name: &str) -> bool {
    let rest = &name[2..];
    rest.is_empty() || rest.bytes().all(|b| b.is_ascii_digit())
}

/// The kind, name and indices a write goes to (`$R5` → `R[5]`).
fn resolve_target<'n, 'b, C: EvalContext + ?Sized>(
    ctx: &C,
    kind: VarKind,
    name: &'n str,
    indices: &[Expr],
    buf: &'b mut [i32; 4],
) -> Result<(VarKind, &'n str, &'b [i32]), RunError> {
    if kind == VarKind::System {
        let rest = &name[2..];
        if !rest.is_empty() {
            buf[0] = rest.parse::<i32>().map_err(|_| undefined(name))?;
            return Ok((VarKind::RParameter, "R", &buf[..1]));
        }
        let idx = int_indices(ctx, indices, 0, buf)?;
        return Ok((VarKind::RParameter, "R", idx));
    }
    let idx = int_indices(ctx, indices, 0, buf)?;
    Ok((kind, name, idx))
}

/// `assign_list`: consecutive elements from the target on (`SET(…)`,
/// `(…)`, `REP(…)`).
pub fn assign_list(
    vars: &mut Variables,
    rt: &dyn RuntimeInterface,
    list: &AssignList,
) -> Result<(), RunError> {
    let (kind, name, indices) = target_parts(&list.target)?;
    if kind == VarKind::System && !(name.starts_with("$R") && is_r_system(name)) {
        return Err(RunError::new(
            codes::TYPE_MISMATCH,
            format!("a list of values cannot be assigned to `{name}`"),
        ));
    }
    let env = Env::new(vars, rt);
    let mut values = Vec::with_capacity(list.values.len());
    for v in &list.values {
        values.push(v.as_ref().map(|v| eval_value(&env, v)).transpose()?);
    }
    let repeat = repeat_values(&env, list.repeat.as_ref())?;
    let mut buf = [0i32; 4];
    let (kind, name, idx) = resolve_target(&env, kind, name, indices, &mut buf)?;
    if let Some((value, count)) = repeat {
        vars.fill(kind, name, idx, &value, count)?;
    }
    if !values.is_empty() {
        vars.write_list(kind, name, idx, &values)?;
    }
    Ok(())
}

fn repeat_values<C: EvalContext + ?Sized>(
    ctx: &C,
    repeat: Option<&gcodec_ail::Repeat>,
) -> Result<Option<(RtValue, Option<usize>)>, RunError> {
    let Some(repeat) = repeat else {
        return Ok(None);
    };
    let value = eval_value(ctx, &repeat.value)?;
    let count = match &repeat.count {
        None => None,
        Some(c) => {
            let n = eval_value(ctx, c)?.to_int()?;
            Some(usize::try_from(n).ok().filter(|&n| n >= 1).ok_or_else(|| {
                RunError::new(
                    codes::INDEX_OUT_OF_RANGE,
                    format!("`REP`: the count {n} is below 1"),
                )
            })?)
        }
    };
    Ok(Some((value, count)))
}

/// `declare`: a `DEF` in `scope`, with its dimensions and initial values
/// evaluated now.
pub fn declare(
    vars: &mut Variables,
    rt: &dyn RuntimeInterface,
    decl: &Declare,
    scope: Scope,
) -> Result<(), RunError> {
    let ty = decl.data_type;
    if !ty.is_declarable() {
        return Err(RunError::new(
            codes::INVALID_DECLARATION,
            format!("`{ty}` is not a type"),
        ));
    }
    let env = Env::new(vars, rt);
    let mut dims = Vec::with_capacity(decl.dims.len());
    for d in &decl.dims {
        let n = eval_value(&env, d)?.to_int()?;
        dims.push(usize::try_from(n).ok().filter(|&n| n >= 1).ok_or_else(|| {
            RunError::new(
                codes::INVALID_DECLARATION,
                format!("`{}`: the dimension {n} is below 1", decl.name),
            )
        })?);
    }
    let mut init = Vec::with_capacity(decl.init.len());
    for v in &decl.init {
        init.push(v.as_ref().map(|v| eval_value(&env, v)).transpose()?);
    }
    let repeat = repeat_values(&env, decl.init_repeat.as_ref())?;
    let init = match &repeat {
        Some((value, count)) => Init::Repeat(value, *count),
        None if init.is_empty() => Init::None,
        None => Init::List(&init),
    };
    vars.declare(scope, &decl.name, ty, &dims, init)
}
