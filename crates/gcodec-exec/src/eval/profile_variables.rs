//! The system variables a machine profile answers
//! ([`profile_system_variable`]), and the settable work offsets the
//! profile gives, which the channel reads too.

use std::f64::consts::PI;
use std::sync::Arc;

use gcodec_ail::VarName;
use gcodec_lang::sysvars::SysVarId;
use gcodec_profile::{Profile, SystemValue, Tool, ToolChangeMode};
use gcodec_source::codes;

use crate::value::{FrameAxis, FrameValue, RtValue, RunError};

/// The system variables a machine profile answers, the default of
/// [`super::RuntimeInterface::system_variable`]:
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
/// * `$MC_TOOL_CHANGE_MODE`: 0 (`direct`) or 1 (`deferred_m6`);
/// * any other: the value the profile's `[system_variables]` gives it
///   ([`Profile::system_value`]).
///
/// A variable none of these answers is [`codes::run::SYSTEM_VARIABLE`],
/// naming it and the profile entry that would give its value.
pub fn profile_system_variable(
    profile: Option<&Profile>,
    var: &VarName,
    indices: &[RtValue],
) -> Result<RtValue, RunError> {
    let name = var.as_str();
    let id = var.system();
    if id == Some(SysVarId::PI) {
        no_indices(name, indices)?;
        return Ok(RtValue::Real(PI));
    }
    let Some(profile) = profile else {
        return Err(RunError::new(
            codes::run::SYSTEM_VARIABLE,
            format!("the system variable `{name}` has no value without a machine profile"),
        ));
    };
    let Some(id) = id else {
        return profile_value(profile, name, indices);
    };
    match id {
        SysVarId::P_TOOLNO | SysVarId::P_TOOLP | SysVarId::P_TOOL => {
            no_indices(name, indices)?;
            Ok(RtValue::Int(0))
        }
        SysVarId::MC_TOOL_CHANGE_MODE => {
            no_indices(name, indices)?;
            Ok(RtValue::Int(match profile.tool_change.tool_change_mode {
                ToolChangeMode::Direct => 0,
                ToolChangeMode::DeferredM6 => 1,
            }))
        }
        SysVarId::P_AXN1 | SysVarId::P_AXN2 | SysVarId::P_AXN3 => {
            no_indices(name, indices)?;
            let n = match id {
                SysVarId::P_AXN1 => 0,
                SysVarId::P_AXN2 => 1,
                _ => 2,
            };
            profile
                .axes
                .iter()
                .filter(|a| a.geometry)
                .nth(n)
                .map(|a| RtValue::axis(a.name.get_ref()))
                .ok_or_else(|| {
                    RunError::new(
                        codes::run::SYSTEM_VARIABLE,
                        format!("`{name}`: the machine has no geometry axis {}", n + 1),
                    )
                })
        }
        SysVarId::P_UIFR => settable_frame(profile, name, indices),
        _ => match SysVarId::TC_DP.iter().position(|&dp| dp == id) {
            Some(k) => tool_parameter(&profile.tools, name, k + 1, indices),
            None => profile_value(profile, name, indices),
        },
    }
}

/// The value `[system_variables]` gives `name` with `indices`, else the
/// error naming the entry that would.
fn profile_value(profile: &Profile, name: &str, indices: &[RtValue]) -> Result<RtValue, RunError> {
    let name = format!("${}", name.trim_start_matches('$').to_ascii_uppercase());
    let written: Vec<String> = indices.iter().map(index_text).collect();
    if let Some(value) = profile.system_value(&name, &written) {
        return Ok(match value {
            SystemValue::Bool(b) => RtValue::Bool(*b),
            SystemValue::Int(n) => i32::try_from(*n).map_or(RtValue::Real(*n as f64), RtValue::Int),
            SystemValue::Real(r) => RtValue::Real(*r),
            SystemValue::Text(t) => RtValue::String(Arc::from(t.as_str())),
        });
    }
    let key = if written.is_empty() {
        name.clone()
    } else {
        format!("{name}[{}]", written.join(","))
    };
    Err(RunError::new(
        codes::run::SYSTEM_VARIABLE,
        format!(
            "the system variable `{key}` has no value in the simulation; the machine profile gives it as `\"{key}\" = …` in `[system_variables]`"
        ),
    ))
}

/// An index as a `[system_variables]` key writes it: a whole number in
/// digits, an axis by its name.
fn index_text(index: &RtValue) -> String {
    match index {
        RtValue::Int(n) => n.to_string(),
        RtValue::Real(r) if r.fract() == 0.0 && r.abs() < 1e15 => format!("{r:.0}"),
        RtValue::Axis(a) | RtValue::String(a) => a.to_ascii_uppercase(),
        other => other
            .to_text()
            .map_or_else(|_| String::new(), |t| t.to_string()),
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
        codes::run::INDEX_COUNT,
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
                codes::run::INDEX_OUT_OF_RANGE,
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

/// `$TC_DP<k>[t, d]` (`name`) of the tool table `tools`.
pub(crate) fn tool_parameter(
    tools: &[Tool],
    name: &str,
    k: usize,
    indices: &[RtValue],
) -> Result<RtValue, RunError> {
    let [t, d] = indices else {
        return Err(sys_index_count(name, "2", indices.len()));
    };
    let (t, d) = (t.to_int()?, d.to_int()?);
    let tool = u32::try_from(t)
        .ok()
        .and_then(|t| tools.iter().find(|tool| *tool.number.get_ref() == t))
        .ok_or_else(|| {
            RunError::new(
                codes::run::INDEX_OUT_OF_RANGE,
                format!("`{name}[{t},{d}]`: the tool table has no tool {t}"),
            )
        })?;
    let edge = u32::try_from(d)
        .ok()
        .and_then(|d| tool.edge(d))
        .ok_or_else(|| {
            RunError::new(
                codes::run::INDEX_OUT_OF_RANGE,
                format!("`{name}[{t},{d}]`: tool {t} has no cutting edge D{d}"),
            )
        })?;
    match k {
        1 => match &edge.tool_type {
            Some(tool_type) => Ok(RtValue::Real(f64::from(*tool_type.get_ref()))),
            None => Err(RunError::new(
                codes::run::SYSTEM_VARIABLE,
                format!(
                    "`{name}[{t},{d}]`: the tool type is not in the machine profile (its edge's `type`)"
                ),
            )),
        },
        2 => Ok(RtValue::Real(f64::from(*edge.position.get_ref()))),
        3 => Ok(RtValue::Real(edge.length)),
        6 => Ok(RtValue::Real(edge.radius)),
        _ => Ok(RtValue::Real(0.0)),
    }
}
