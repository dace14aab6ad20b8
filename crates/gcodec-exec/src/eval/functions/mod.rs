//! The built-in functions (reference §7.6). [`call`] dispatches by name
//! to the family that computes it — arithmetic and rounding,
//! trigonometry, conversions, strings, `SPRINT` formatting — and hands
//! any other name to the runtime, which provides the frame functions and
//! those of tool management.

mod arithmetic;
mod conversions;
mod format;
mod strings;
mod trigonometry;

use std::sync::Arc;

use gcodec_ail::Expr;
use gcodec_source::codes;

use super::{EvalContext, eval_at};
use crate::value::{RtValue, RunError, char_text};

pub use format::sprint;

/// Calls the built-in function `name`.
#[inline(never)]
pub(super) fn call<C: EvalContext + ?Sized>(
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
        "ABS" | "SQRT" | "POT" | "TRUNC" | "ROUND" | "ROUNDUP" | "LN" | "EXP" => {
            arithmetic::of_one_real(&a)
        }
        "MINVAL" | "MAXVAL" => arithmetic::min_max(&a),
        "BOUND" => arithmetic::bound(&a),
        "SIN" | "COS" | "TAN" | "ASIN" | "ACOS" => trigonometry::of_one_real(&a),
        "ATAN2" => trigonometry::atan2(&a),
        "ITOR" | "BTOR" | "RTOI" | "RTOB" | "ITOB" | "BTOI" => conversions::between_types(&a),
        "NUMBER" | "ISNUMBER" => conversions::number(&a),
        "AXNAME" => conversions::axname(&a),
        "AXSTRING" => conversions::axstring(&a),
        "STRLEN" => strings::strlen(&a),
        "TOUPPER" | "TOLOWER" => strings::change_case(&a),
        "INDEX" | "RINDEX" => strings::index(&a),
        "MINDEX" => strings::mindex(&a),
        "MATCH" => strings::find(&a),
        "SUBSTR" => strings::substr(&a),
        "SPRINT" => format::sprint_call(&a),
        _ => runtime_function(&a),
    }
}

/// A function the executor provides (frames, tool management), its
/// arguments evaluated in order, an omitted one as `None`.
fn runtime_function<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    let mut values = Vec::with_capacity(a.args.len());
    for arg in a.args {
        values.push(match arg {
            Some(e) => Some(eval_at(a.ctx, e, a.depth + 1)?),
            None => None,
        });
    }
    a.ctx
        .runtime()
        .function(a.name, &values)
        .unwrap_or_else(|| {
            Err(RunError::new(
                codes::run::UNKNOWN_FUNCTION,
                format!("`{}` is not a function the executor knows", a.name),
            ))
        })
}

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
                codes::run::ARGUMENT_COUNT,
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
                codes::run::ARGUMENT_COUNT,
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
            codes::run::TYPE_MISMATCH,
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
    RunError::new(codes::run::DOMAIN, format!("`{name}({x})`: {why}"))
}

fn real(v: f64) -> Result<RtValue, RunError> {
    Ok(RtValue::Real(v))
}
