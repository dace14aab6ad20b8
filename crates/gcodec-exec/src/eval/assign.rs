//! The instructions that write variables: [`assign`] (`assign`),
//! [`assign_list`] (`assign_list`: `SET(…)`, `(…)`, `REP(…)`) and
//! [`declare`] (`declare`: a `DEF`).

use gcodec_ail::{AssignList, Declare, Expr, Value, VarKind, VarName};
use gcodec_lang::sysvars::SysVarId;
use gcodec_source::codes;

use super::{
    Env, EvalContext, RuntimeInterface, eval_value, int_indices, numbered_r, system_indices,
};
use crate::loader::ProgramLoader;
use crate::value::{RtValue, RunError};
use crate::vars::{Init, Scope, Variables, undefined};

fn target_parts(target: &Expr) -> Result<(VarKind, &VarName, &[Expr]), RunError> {
    match target {
        Expr::Var {
            var_kind,
            name,
            indices,
        } => Ok((*var_kind, name, indices)),
        _ => Err(RunError::new(
            codes::run::TYPE_MISMATCH,
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
    assign_in(vars, rt, None, target, value)
}

/// [`assign`], the value and indices evaluated with the programs a
/// loader finds for a call from the running program's file (`ISFILE`).
pub fn assign_in(
    vars: &mut Variables,
    rt: &mut dyn RuntimeInterface,
    programs: Option<(&dyn ProgramLoader, &str)>,
    target: &Expr,
    value: &Value,
) -> Result<(), RunError> {
    let (kind, name, indices) = target_parts(target)?;
    let env = Env::new(vars, &*rt);
    let env = match programs {
        Some((loader, caller_file)) => env.with_programs(loader, caller_file),
        None => env,
    };
    let v = eval_value(&env, value)?;
    if kind == VarKind::System && !is_r_system(name) {
        let idx = system_indices(&env, indices, 0)?;
        return rt.set_system_variable(name, &idx, &v);
    }
    let mut buf = [0i32; 4];
    let (kind, name, idx) = resolve_target(&env, kind, name, indices, &mut buf)?;
    vars.write(kind, name, idx, &v)
}

/// `$R`, `$R5`: the R parameters.
fn is_r_system(name: &VarName) -> bool {
    match name {
        VarName::System(id) => *id == SysVarId::R,
        VarName::Text(text) => text
            .strip_prefix("$R")
            .is_some_and(|rest| rest.bytes().all(|b| b.is_ascii_digit())),
    }
}

/// The kind, name and indices a write goes to (`$R5` → `R[5]`).
fn resolve_target<'n, 'b, C: EvalContext + ?Sized>(
    ctx: &C,
    kind: VarKind,
    name: &'n VarName,
    indices: &[Expr],
    buf: &'b mut [i32; 4],
) -> Result<(VarKind, &'n str, &'b [i32]), RunError> {
    if kind == VarKind::System {
        if let VarName::Text(text) = name
            && text.len() > 2
        {
            buf[0] = numbered_r(text).ok_or_else(|| undefined(text))?;
            return Ok((VarKind::RParameter, "R", &buf[..1]));
        }
        let idx = int_indices(ctx, indices, 0, buf)?;
        return Ok((VarKind::RParameter, "R", idx));
    }
    let idx = int_indices(ctx, indices, 0, buf)?;
    Ok((kind, name.as_str(), idx))
}

/// `assign_list`: consecutive elements from the target on (`SET(…)`,
/// `(…)`, `REP(…)`).
pub fn assign_list(
    vars: &mut Variables,
    rt: &dyn RuntimeInterface,
    list: &AssignList,
) -> Result<(), RunError> {
    let (kind, name, indices) = target_parts(&list.target)?;
    if kind == VarKind::System && !is_r_system(name) {
        return Err(RunError::new(
            codes::run::TYPE_MISMATCH,
            format!("a list of values cannot be assigned to `{}`", name.as_str()),
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
                    codes::run::INDEX_OUT_OF_RANGE,
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
            codes::run::INVALID_DECLARATION,
            format!("`{ty}` is not a type"),
        ));
    }
    let env = Env::new(vars, rt);
    let mut dims = Vec::with_capacity(decl.dims.len());
    for d in &decl.dims {
        let n = eval_value(&env, d)?.to_int()?;
        dims.push(usize::try_from(n).ok().filter(|&n| n >= 1).ok_or_else(|| {
            RunError::new(
                codes::run::INVALID_DECLARATION,
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
