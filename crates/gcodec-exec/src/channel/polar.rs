//! End points a block computes rather than writes (SPEC §11.5): polar
//! coordinates (`AP=` angle, `RP=` radius about the pole) and the
//! one-block contour angle (`G1 X20 ANG=45`).

use gcodec_ail::{AxisValue, Value};
use gcodec_lang::DimensionMode;
use gcodec_source::codes;

use super::Channel;
use crate::eval;
use crate::geometry::{Plane, Point3};
use crate::value::RunError;

/// The `AP=`, `RP=` and `ANG=` words of a block.
#[derive(Default)]
pub(super) struct PolarWords<'a> {
    angle: Option<(&'a Value, Option<DimensionMode>)>,
    radius: Option<(&'a Value, Option<DimensionMode>)>,
    contour_angle: Option<&'a Value>,
}

impl<'a> PolarWords<'a> {
    /// Takes `value` if it is one of the three; `false` for an axis.
    pub fn take(&mut self, value: &'a AxisValue) -> bool {
        match value.axis.as_ref() {
            "AP" => self.angle = Some((&value.value, value.mode)),
            "RP" => self.radius = Some((&value.value, value.mode)),
            "ANG" => self.contour_angle = Some(&value.value),
            _ => return false,
        }
        true
    }

    /// The block gives its end point in polar coordinates.
    pub fn is_polar(&self) -> bool {
        self.angle.is_some() || self.radius.is_some()
    }

    /// `ANG=` is written.
    pub fn has_contour_angle(&self) -> bool {
        self.contour_angle.is_some()
    }
}

/// Which coordinates of the working plane a block writes (abscissa,
/// ordinate).
pub(super) type PlaneWritten = (bool, bool);

/// What `ANG=` makes of a block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum ContourAngle {
    /// No `ANG=`, or one that gave the missing coordinate.
    None,
    /// `ANG=` with no end point in the plane: the first block of a
    /// contour definition of two blocks, at this angle.
    Begins(f64),
    /// `ANG=` with both coordinates: the second block of one, arriving at
    /// its end point at this angle.
    Ends(f64),
}

impl Channel<'_> {
    /// `AP` and `RP` as programmed (degrees; mm, inches under `G70`), from
    /// `angle` and `radius` where incremental (`IC(…)`, `G91`) or not
    /// written.
    pub(super) fn polar_values(
        &self,
        words: &PolarWords,
        angle: f64,
        radius: f64,
    ) -> Result<(f64, f64), RunError> {
        let env = self.env();
        let incremental = |mode: Option<DimensionMode>| match mode {
            Some(DimensionMode::Ic) => true,
            Some(_) => false,
            None => self.state.incremental(),
        };
        let angle = match words.angle {
            Some((value, mode)) => {
                let v = eval::eval_real(&env, value)?;
                if incremental(mode) { angle + v } else { v }
            }
            None => angle,
        };
        let radius = match words.radius {
            Some((value, mode)) => {
                let mut v = eval::eval_real(&env, value)?;
                if self.state.inch() {
                    v *= 25.4;
                }
                if incremental(mode) { radius + v } else { v }
            }
            None => radius,
        };
        if !(radius >= 0.0 && radius.is_finite() && angle.is_finite()) {
            return Err(RunError::new(
                codes::run::POLAR_END_POINT,
                format!("the polar radius is {radius}: `RP` is a finite length of 0 or more"),
            ));
        }
        Ok((angle, radius))
    }

    /// Sets the plane's end point of a motion from its polar words (which
    /// become the stored ones) and returns the pole, the centre of a
    /// polar arc.
    pub(super) fn polar_end_point(
        &mut self,
        words: &PolarWords,
        plane: Plane,
        written: PlaneWritten,
    ) -> Result<Point3, RunError> {
        if words.has_contour_angle() {
            return Err(RunError::new(
                codes::run::CONTOUR_ANGLE,
                "`ANG=` and a polar end point (`AP=`, `RP=`) in one block give the end point twice",
            ));
        }
        if written.0 || written.1 {
            return Err(RunError::new(
                codes::run::POLAR_END_POINT,
                format!(
                    "the block gives its end point in polar coordinates and a coordinate of the working plane ({}) too",
                    plane.code()
                ),
            ));
        }
        let stored = &self.state.polar;
        let (angle, radius) = self.polar_values(words, stored.angle, stored.radius)?;
        let pole = stored.pole;
        let (h, v, _) = plane.axes();
        let (sin, cos) = angle.to_radians().sin_cos();
        self.set_plane_coordinate(plane, h, pole[h] + radius * cos)?;
        self.set_plane_coordinate(plane, v, pole[v] + radius * sin)?;
        self.state.polar.angle = angle;
        self.state.polar.radius = radius;
        Ok(pole)
    }

    /// `G1 X20 ANG=45`: the coordinate of the working plane not written,
    /// from the one written and the angle of the line to the abscissa.
    /// Without exactly one written it is a contour of several blocks,
    /// which is not simulated.
    pub(super) fn contour_angle_end_point(
        &mut self,
        words: &PolarWords,
        plane: Plane,
        written: PlaneWritten,
        start: Point3,
    ) -> Result<ContourAngle, RunError> {
        let Some(value) = words.contour_angle else {
            return Ok(ContourAngle::None);
        };
        let angle = self.real_of(value)?;
        if written == (false, false) {
            // The first block of a contour of two blocks: its end point
            // is where the next block's line meets it.
            return Ok(ContourAngle::Begins(angle));
        }
        if written == (true, true) {
            return Ok(ContourAngle::Ends(angle));
        }
        let (sin, cos) = angle.to_radians().sin_cos();
        let (h, v, _) = plane.axes();
        let end = self.state.geometry_point(&self.motion.target);
        // A line that cannot reach the coordinate written: the angle is
        // within rounding of perpendicular to its axis.
        const PARALLEL: f64 = 1e-12;
        let (slot, coordinate) = match written {
            (true, false) if cos.abs() > PARALLEL => {
                (v, start[v] + (end[h] - start[h]) * sin / cos)
            }
            (false, true) if sin.abs() > PARALLEL => {
                (h, start[h] + (end[v] - start[v]) * cos / sin)
            }
            (true, false) | (false, true) => {
                return Err(RunError::new(
                    codes::run::CONTOUR_ANGLE,
                    format!(
                        "a line at ANG={angle} never reaches the coordinate written on the {}",
                        if written.0 { "abscissa" } else { "ordinate" }
                    ),
                ));
            }
            _ => return Ok(ContourAngle::None),
        };
        self.set_plane_coordinate(plane, slot, coordinate)?;
        Ok(ContourAngle::None)
    }

    /// Sets the end point's coordinate of geometry slot `slot`.
    fn set_plane_coordinate(
        &mut self,
        plane: Plane,
        slot: usize,
        value: f64,
    ) -> Result<(), RunError> {
        let Some(axis) = self.state.frame_axes.geometry_axis(slot) else {
            return Err(RunError::new(
                codes::run::POLAR_END_POINT,
                format!(
                    "the working plane {} has an axis this machine lacks",
                    plane.code()
                ),
            ));
        };
        self.motion.target[axis] = crate::value::finite_real(value, || {
            format!("the position on `{}`", self.state.axes[axis].name)
        })?;
        Ok(())
    }
}
