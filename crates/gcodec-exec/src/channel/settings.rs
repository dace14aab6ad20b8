//! The group 3 commands whose axis words set a value instead of moving
//! (SPEC §11.6): working-area limits (`G25`/`G26`, with `S` the
//! spindle-speed limits), the pole (`G110`/`G111`/`G112`) and the axial
//! programmable offsets (`G58`/`G59`).

use gcodec_ail::{AxisSetting, AxisValue};
use gcodec_source::codes;

use super::Channel;
use super::polar::PolarWords;
use crate::frames::TranslationPart;
use crate::geometry::Point3;
use crate::value::RunError;

/// Where a pole is programmed from.
#[derive(Clone, Copy)]
enum PoleReference {
    /// `G110`: the last programmed position.
    LastPosition,
    /// `G111`: the workpiece zero of the current frame.
    WorkpieceZero,
    /// `G112`: the last valid pole.
    LastPole,
}

impl Channel<'_> {
    pub(super) fn axis_setting(&mut self, setting: &AxisSetting) -> Result<(), RunError> {
        match setting.command.name() {
            name @ ("G25" | "G26") => self.working_area(name == "G26", setting),
            "G110" => self.pole(PoleReference::LastPosition, &setting.values),
            "G111" => self.pole(PoleReference::WorkpieceZero, &setting.values),
            "G112" => self.pole(PoleReference::LastPole, &setting.values),
            "G58" => self.axial_offset(TranslationPart::Coarse, &setting.values),
            "G59" => self.axial_offset(TranslationPart::Fine, &setting.values),
            other => Err(RunError::new(
                codes::run::NOT_SIMULATED,
                format!("`{other}` sets nothing the simulation knows"),
            )),
        }
    }

    /// An axis value in mm (degrees for a rotary axis): lengths are
    /// inches under `G70`/`G700`.
    fn length_of(&self, value: &AxisValue) -> Result<(usize, f64), RunError> {
        let axis = self.axis(&value.axis)?;
        let v = self.real_of(&value.value)?;
        let inch = self.state.inch() && !self.state.axes[axis].rotary;
        Ok((axis, if inch { v * 25.4 } else { v }))
    }

    fn working_area(&mut self, upper: bool, setting: &AxisSetting) -> Result<(), RunError> {
        let n = self.state.axes.len();
        for value in &setting.values {
            let (axis, v) = self.length_of(value)?;
            let limits = &mut self.state.working_area;
            let side = if upper {
                &mut limits.upper
            } else {
                &mut limits.lower
            };
            side.resize(n, None);
            side[axis] = Some(v);
        }
        for limit in &setting.spindle_limits {
            let speed = self.real_of(&limit.speed)?;
            let spindle = self.state.spindle(limit.spindle)?;
            spindle.speed_limits[usize::from(upper)] = Some(speed);
        }
        Ok(())
    }

    /// The pole in the working plane: the plane's coordinates written
    /// (Cartesian, or polar by `AP=`/`RP=`) from the reference point; a
    /// coordinate not written is the reference point's.
    fn pole(&mut self, reference: PoleReference, values: &[AxisValue]) -> Result<(), RunError> {
        let plane = self.state.plane();
        let (h, v, _) = plane.axes();
        let origin: Point3 = match reference {
            PoleReference::LastPosition => {
                self.motion.workpiece_position(&self.state);
                self.state.geometry_point(&self.motion.wcs)
            }
            PoleReference::WorkpieceZero => [0.0; 3],
            PoleReference::LastPole => self.state.polar.pole,
        };
        let mut pole = origin;
        let mut polar = PolarWords::default();
        for value in values {
            if polar.take(value) {
                if polar.has_contour_angle() {
                    return Err(RunError::new(
                        codes::run::POLAR_END_POINT,
                        "`ANG=` sets no pole: give it in the plane's axes or by `AP=`/`RP=`",
                    ));
                }
                continue;
            }
            let (axis, mut length) = self.length_of(value)?;
            // The diameter axis: `G111` is absolute, `G110`/`G112`
            // relative (DIAMON, DIAM90; SPEC §11.5).
            let (absolute_diameter, incremental_diameter) = self.state.diameter_mode();
            let diameter = match reference {
                PoleReference::WorkpieceZero => absolute_diameter,
                _ => incremental_diameter,
            };
            if self.state.axes[axis].diameter && diameter {
                length /= 2.0;
            }
            match self.state.axes[axis].geometry {
                Some(g) if g == h || g == v => pole[g] = origin[g] + length,
                _ => {
                    return Err(RunError::new(
                        codes::run::POLAR_END_POINT,
                        format!(
                            "the pole lies in the working plane ({}); `{}` is not one of its axes",
                            plane.code(),
                            value.axis
                        ),
                    ));
                }
            }
        }
        if polar.is_polar() {
            let (angle, radius) = self.polar_values(&polar, 0.0, 0.0)?;
            let (sin, cos) = angle.to_radians().sin_cos();
            pole[h] = origin[h] + radius * cos;
            pole[v] = origin[v] + radius * sin;
        }
        // A new pole starts the polar angle anew (reference §2.7).
        self.state.polar.pole = pole;
        self.state.polar.angle = 0.0;
        Ok(())
    }

    fn axial_offset(
        &mut self,
        part: TranslationPart,
        values: &[AxisValue],
    ) -> Result<(), RunError> {
        let mut offsets = Vec::with_capacity(values.len());
        for value in values {
            offsets.push(self.length_of(value)?);
        }
        let state = &mut self.state;
        state
            .programmable
            .replace_translation(&state.frame_axes, part, &offsets)
    }
}
