//! Functions that ask the machine about itself: `GETT` (the T number of
//! a named tool), `ISAXIS` (whether a geometry axis exists), `ISVAR`
//! (whether a name is a variable) and `ISFILE` (whether a program is on
//! the search path).

use gcodec_lang::sysvars;

use gcodec_lang::functions::Function;

use super::not_simulated::{ISFILE_RETURNS, returning};
use super::{Args, EvalContext};
use crate::value::{RtValue, RunError};

/// `GETT("NAME")`, `GETT("NAME", duplo)`: the T number of the tool of the
/// profile's tool table with that name (any case) and duplo number; with
/// no duplo number the lowest the name has; -1 when there is none.
pub(super) fn gett<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 2)?;
    let name = a.string(0)?;
    let duplo = if a.present(1) { Some(a.int(1)?) } else { None };
    let tools = a
        .ctx
        .runtime()
        .profile()
        .map_or(&[][..], |p| p.tools.as_slice());
    let number = tools
        .iter()
        .filter(|t| {
            t.name
                .as_ref()
                .is_some_and(|n| n.get_ref().eq_ignore_ascii_case(&name))
        })
        .filter(|t| duplo.is_none_or(|d| i64::from(t.duplo) == i64::from(d)))
        .min_by_key(|t| t.duplo)
        .map_or(-1.0, |t| f64::from(*t.number.get_ref()));
    Ok(crate::eval::number(number))
}

/// `ISAXIS(n)`: whether the machine has geometry axis `n` (1 abscissa, 2
/// ordinate, 3 applicate). An AXIS or STRING argument asks whether the
/// machine has that axis.
pub(super) fn isaxis<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    let runtime = a.ctx.runtime();
    match a.value(0)? {
        RtValue::Axis(name) | RtValue::String(name) => {
            Ok(RtValue::Bool(runtime.is_axis(&name.to_ascii_uppercase())))
        }
        _ => {
            let n = a.int(0)?;
            let geometry = runtime
                .profile()
                .map_or(0, |p| p.axes.iter().filter(|axis| axis.geometry).count());
            Ok(RtValue::Bool(
                usize::try_from(n).is_ok_and(|n| (1..=geometry.min(3)).contains(&n)),
            ))
        }
    }
}

/// `ISVAR("NAME")`: whether `NAME` (any case, with or without indices in
/// brackets, which are not checked) is a variable the running program
/// sees, an R parameter (`R5`) or a system variable or machine datum of
/// the control's lists.
pub(super) fn isvar<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    let text = a.string(0)?;
    let name = text
        .split('[')
        .next()
        .unwrap_or_default()
        .trim()
        .to_ascii_uppercase();
    let known = if name.starts_with('$') {
        sysvars::lookup(&name).is_some()
    } else {
        is_r_parameter(&name) || a.ctx.variables().is_defined(&name)
    };
    Ok(RtValue::Bool(known))
}

/// `R5`: an R parameter by number.
fn is_r_parameter(name: &str) -> bool {
    name.strip_prefix('R')
        .is_some_and(|digits| !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()))
}

/// `ISFILE("NAME")`: whether the program `NAME` (a name, `SUB.SPF`, or a
/// path, `/_N_SPF_DIR/_N_SUB_SPF`) is on the running program's search
/// path, as a call would find it. A name of no program (`DATA.INI`), or a
/// run without a search path, is not simulated.
pub(super) fn isfile<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    let name = a.string(0)?;
    match a.ctx.program_exists(&name) {
        Some(found) => Ok(RtValue::Bool(found)),
        None => Err(returning(Function::Isfile, ISFILE_RETURNS)),
    }
}
