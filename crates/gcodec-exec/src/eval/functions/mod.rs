//! The built-in functions (reference §7.6). [`call`] dispatches by
//! function id to the family that computes it — arithmetic and rounding,
//! trigonometry, conversions, strings, `SPRINT` formatting, the
//! machine's inquiries (`GETT`, `ISAXIS`, `ISVAR`, `ISFILE`) — and hands any other
//! function to the runtime, which provides the frame functions. A
//! function neither computes is not simulated: an error naming what it
//! would return.

mod arithmetic;
mod conversions;
mod format;
mod inquiry;
mod not_simulated;
mod strings;
mod trigonometry;

use std::sync::Arc;

use gcodec_ail::{Callee, Expr};
use gcodec_lang::functions::Function;
use gcodec_source::codes;

use super::{EvalContext, eval_at};
use crate::value::{RtValue, RunError, char_text, finite_real};

pub use format::sprint;

/// Calls the function `callee`.
#[inline(never)]
pub(super) fn call<C: EvalContext + ?Sized>(
    ctx: &C,
    callee: &Callee,
    args: &[Option<Expr>],
    depth: usize,
) -> Result<RtValue, RunError> {
    let function = match callee {
        Callee::Predefined(function) => *function,
        // A user function or a name the vocabulary does not list: the
        // arguments are evaluated first, as for any call.
        Callee::Other(name) => {
            evaluate_all(ctx, args, depth)?;
            return Err(unknown_function(name));
        }
    };
    let a = Args {
        ctx,
        function,
        args,
        depth,
    };
    use Function as F;
    let result = match function {
        F::Abs | F::Sqrt | F::Pot | F::Trunc | F::Round | F::Roundup | F::Ln | F::Exp => {
            arithmetic::of_one_real(&a)
        }
        F::Minval | F::Maxval => arithmetic::min_max(&a),
        F::Bound => arithmetic::bound(&a),
        F::Sin | F::Cos | F::Tan | F::Asin | F::Acos => trigonometry::of_one_real(&a),
        F::Atan2 => trigonometry::atan2(&a),
        F::Itor | F::Btor | F::Rtoi | F::Rtob | F::Itob | F::Btoi => conversions::between_types(&a),
        F::Number | F::Isnumber => conversions::number(&a),
        F::Axname => conversions::axname(&a),
        F::Axstring => conversions::axstring(&a),
        F::Strlen => strings::strlen(&a),
        F::Toupper | F::Tolower => strings::change_case(&a),
        F::Index | F::Rindex => strings::index(&a),
        F::Mindex => strings::mindex(&a),
        F::Match => strings::find(&a),
        F::Substr => strings::substr(&a),
        F::Sprint => format::sprint_call(&a),
        F::Gett => inquiry::gett(&a),
        F::Isaxis => inquiry::isaxis(&a),
        F::Isvar => inquiry::isvar(&a),
        F::Isfile => inquiry::isfile(&a),
        _ => runtime_function(&a),
    };
    match result {
        Ok(RtValue::Real(r)) => {
            finite_real(r, || format!("the result of `{}`", a.name())).map(RtValue::Real)
        }
        other => other,
    }
}

/// A function the executor provides (frames), its arguments evaluated
/// in order, an omitted one as `None`; else one it does not simulate.
fn runtime_function<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    let values = evaluate_all(a.ctx, a.args, a.depth)?;
    a.ctx
        .runtime()
        .function(a.function, &values)
        .unwrap_or_else(|| {
            Err(not_simulated::not_simulated(a.function)
                .unwrap_or_else(|| unknown_function(a.name())))
        })
}

/// The arguments of a call evaluated in order, an omitted one as `None`.
fn evaluate_all<C: EvalContext + ?Sized>(
    ctx: &C,
    args: &[Option<Expr>],
    depth: usize,
) -> Result<Vec<Option<RtValue>>, RunError> {
    let mut values = Vec::with_capacity(args.len());
    for arg in args {
        values.push(match arg {
            Some(e) => Some(eval_at(ctx, e, depth + 1)?),
            None => None,
        });
    }
    Ok(values)
}

fn unknown_function(name: &str) -> RunError {
    RunError::new(
        codes::run::UNKNOWN_FUNCTION,
        format!("`{name}` is not a function the executor knows"),
    )
}

/// Evaluates the arguments of a call lazily.
struct Args<'a, C: EvalContext + ?Sized> {
    ctx: &'a C,
    function: Function,
    args: &'a [Option<Expr>],
    depth: usize,
}

impl<C: EvalContext + ?Sized> Args<'_, C> {
    fn name(&self) -> &'static str {
        self.function.name()
    }

    fn count(&self, min: usize, max: usize) -> Result<(), RunError> {
        let n = self.args.len();
        if n < min || n > max {
            let expected = if min == max {
                format!("{min}")
            } else {
                format!("{min} to {max}")
            };
            return Err(RunError::new(
                codes::run::ARGUMENT_COUNT,
                format!("`{}` takes {expected} arguments, not {n}", self.name()),
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
                codes::run::ARGUMENT_COUNT,
                format!("`{}` needs its argument {}", self.name(), i + 1),
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
            codes::run::TYPE_MISMATCH,
            format!(
                "argument {} of `{}` must be {wanted}, not a {}",
                i + 1,
                self.name(),
                v.type_name()
            ),
        )
    }
}

fn domain(name: &str, x: f64, why: &str) -> RunError {
    RunError::new(codes::run::DOMAIN, format!("`{name}({x})`: {why}"))
}

fn real(v: f64) -> Result<RtValue, RunError> {
    Ok(RtValue::Real(v))
}
