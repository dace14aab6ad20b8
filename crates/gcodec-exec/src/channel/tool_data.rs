//! The run's tool data: a copy of the profile's tool table, which a
//! program's writes of `$TC_DP<k>[t,d]` change (creating the tool and
//! edge as the control does), so that a written length `$TC_DP3` takes
//! effect at the next `D` selection and reads back; and the other tool
//! data a program writes (`$TC_TPG5[t]`, `$TC_TP1[t]`, …), kept to be
//! read back.

use gcodec_lang::sysvars::SysVarId;
use gcodec_profile::{Edge, Profile, Tool};
use gcodec_source::codes;
use rustc_hash::FxHashMap;

use crate::eval::profile_variables::tool_parameter;
use crate::value::{RtValue, RunError};

/// How many values of tool data a run may write besides lengths and
/// radii: a loop writing a new index each pass must not grow the run
/// without bound.
const MAX_WRITTEN: usize = 1 << 20;

pub struct ToolData {
    tools: Vec<Tool>,
    /// Values written, by variable and indices (0 for an index not given).
    written: FxHashMap<(SysVarId, [i32; 2]), RtValue>,
}

impl ToolData {
    pub fn new(profile: &Profile) -> Self {
        Self {
            tools: profile.tools.clone(),
            written: FxHashMap::default(),
        }
    }

    /// The run's tool table.
    pub fn tools(&self) -> &[Tool] {
        &self.tools
    }

    /// The tool numbered `number` in the run's tool table.
    pub fn tool(&self, number: u32) -> Option<&Tool> {
        self.tools.iter().find(|t| *t.number.get_ref() == number)
    }

    /// `var` with `indices` read from the run's tool data; `None` for a
    /// variable that is no tool datum or that no one wrote.
    pub fn read(&self, id: SysVarId, indices: &[RtValue]) -> Option<Result<RtValue, RunError>> {
        if !is_tool_datum(id) {
            return None;
        }
        let key = match key(id, indices) {
            Ok(key) => key,
            Err(e) => return Some(Err(e)),
        };
        if let Some(value) = self.written.get(&key) {
            return Some(Ok(value.clone()));
        }
        let k = SysVarId::TC_DP.iter().position(|&dp| dp == id)?;
        Some(tool_parameter(&self.tools, id.name(), k + 1, indices))
    }

    /// Writes `value` to `var` with `indices`; `None` for a variable that
    /// is no tool datum.
    pub fn write(
        &mut self,
        id: SysVarId,
        indices: &[RtValue],
        value: &RtValue,
    ) -> Option<Result<(), RunError>> {
        if !is_tool_datum(id) {
            return None;
        }
        Some(self.write_datum(id, indices, value))
    }

    fn write_datum(
        &mut self,
        id: SysVarId,
        indices: &[RtValue],
        value: &RtValue,
    ) -> Result<(), RunError> {
        let key = key(id, indices)?;
        let Some(k) = SysVarId::TC_DP.iter().position(|&dp| dp == id) else {
            return self.keep(key, value.clone());
        };
        let name = id.name();
        let [t, d] = key.1;
        let (Some(t), Some(d)) = (positive(t), positive(d)) else {
            return Err(RunError::new(
                codes::run::INDEX_OUT_OF_RANGE,
                format!("`{name}[{t},{d}]`: tools and cutting edges are numbered from 1"),
            ));
        };
        let edge = self.edge_mut(t, d);
        match k + 1 {
            1 => {
                let tool_type = value.to_real()?;
                if !(tool_type.fract() == 0.0 && (100.0..=999.0).contains(&tool_type)) {
                    return Err(RunError::new(
                        codes::run::INDEX_OUT_OF_RANGE,
                        format!("`{name}[{t},{d}]={tool_type}`: a tool type is 100…999"),
                    ));
                }
                edge.set_tool_type(tool_type as u32);
            }
            2 => {
                let position = value.to_real()?;
                *edge.position.get_mut() = match position {
                    p if p.fract() == 0.0 && (0.0..=9.0).contains(&p) => p as u8,
                    _ => {
                        return Err(RunError::new(
                            codes::run::INDEX_OUT_OF_RANGE,
                            format!("`{name}[{t},{d}]={position}`: a cutting edge position is 0…9"),
                        ));
                    }
                };
            }
            3 => edge.length = value.to_real()?,
            6 => edge.radius = value.to_real()?,
            _ => return self.keep(key, value.clone()),
        }
        Ok(())
    }

    fn keep(&mut self, key: (SysVarId, [i32; 2]), value: RtValue) -> Result<(), RunError> {
        if self.written.len() >= MAX_WRITTEN && !self.written.contains_key(&key) {
            return Err(RunError::new(
                codes::run::VARIABLE_MEMORY,
                format!("the run's tool data holds at most {MAX_WRITTEN} written values"),
            ));
        }
        self.written.insert(key, value);
        Ok(())
    }

    /// Edge `d` of tool `t`, both made if the table lacks them.
    fn edge_mut(&mut self, t: u32, d: u32) -> &mut Edge {
        let at = match self
            .tools
            .iter()
            .position(|tool| *tool.number.get_ref() == t)
        {
            Some(at) => at,
            None => {
                self.tools.push(Tool::unnamed(t));
                self.tools.len() - 1
            }
        };
        self.tools[at].edge_or_new(d)
    }
}

/// Tool data: the `$TC_…` variables.
fn is_tool_datum(id: SysVarId) -> bool {
    id.name().starts_with("$TC_")
}

/// The key of a value of `id`: its indices as numbers (at most two).
fn key(id: SysVarId, indices: &[RtValue]) -> Result<(SysVarId, [i32; 2]), RunError> {
    let mut key = [0; 2];
    if indices.len() > 2 {
        return Err(RunError::new(
            codes::run::INDEX_COUNT,
            format!(
                "`{}` takes at most 2 indices, not {}",
                id.name(),
                indices.len()
            ),
        ));
    }
    for (slot, index) in key.iter_mut().zip(indices) {
        *slot = index.to_int()?;
    }
    Ok((id, key))
}

fn positive(n: i32) -> Option<u32> {
    u32::try_from(n).ok().filter(|&n| n > 0)
}
