//! `G74` (reference point approach) and `G75 FP=n` (fixed point
//! approach): the named machine axes go at rapid to a position of the
//! machine data (the profile's `reference_point` and `fixed_points`),
//! outside every frame and offset (SPEC §11.5).

use std::sync::Arc;

use gcodec_ail::{ApproachPoint, Instruction};
use gcodec_lang::MotionKind;
use gcodec_source::codes;

use super::Channel;
use crate::program::Program;
use crate::value::RunError;

impl Channel<'_> {
    pub(super) fn approach_point(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        approach: &ApproachPoint,
    ) -> Result<(), RunError> {
        if approach.axes.is_empty() {
            // No axis named: nothing goes anywhere.
            return Ok(());
        }
        let fixed_point = match &approach.fixed_point {
            Some(value) => Some(self.fixed_point_number(value)?),
            None => None,
        };
        self.motion.workpiece_position(&self.state);
        self.motion.machine.copy_from_slice(&self.state.machine);
        let profile = Arc::clone(&self.state.profile);
        for name in &approach.axes {
            let axis = self.axis(name)?;
            let data = &profile.axes[axis];
            self.motion.machine[axis] = match fixed_point {
                None => *data.reference_point.get_ref(),
                Some(n) => match data.fixed_points.get(n - 1) {
                    Some(position) => *position.get_ref(),
                    None => {
                        return Err(RunError::new(
                            codes::run::FIXED_POINT,
                            format!(
                                "axis `{name}` has no fixed point {n}: the `fixed_points` of its `[[axes]]` entry in the profile list {}",
                                data.fixed_points.len()
                            ),
                        ));
                    }
                },
            };
        }
        {
            let frame = self.state.total_frame();
            let scratch = &mut self.motion;
            self.state
                .to_workpiece(&frame, &scratch.machine, &mut scratch.target);
        }
        let start = self.state.geometry_point(&self.motion.wcs);
        let end = self.state.geometry_point(&self.motion.target);
        self.state.note_traversed_frame();
        self.finish_motion(program, instruction, MotionKind::Rapid, start, end, None, 0)
    }

    /// `FP=`: 1…4 (MD30600 has four fixed points per axis).
    fn fixed_point_number(&self, value: &gcodec_ail::Value) -> Result<usize, RunError> {
        let n = self.real_of(value)?;
        if n.fract() == 0.0 && (1.0..=4.0).contains(&n) {
            return Ok(n as usize);
        }
        Err(RunError::new(
            codes::run::FIXED_POINT,
            format!("`FP={n}`: the fixed points are numbered 1…4"),
        ))
    }
}
