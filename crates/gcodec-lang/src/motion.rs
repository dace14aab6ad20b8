//! How a block traverses: the motion of each group 1 command.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// How a block traverses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MotionKind {
    /// The motion command of group 1 active when the block runs: not
    /// known before the program runs, because the block is reached from
    /// places with different commands (after a jump target, a call, at the
    /// start of a subprogram) and programs none of its own.
    Modal,
    Rapid,
    Linear,
    ArcCw,
    ArcCcw,
    /// `CIP`: a circle through an intermediate point.
    ArcThroughPoint,
    /// `CT`: a circle tangential to the previous path.
    ArcTangential,
    /// `ASPLINE`: Akima spline through the programmed points.
    Aspline,
    /// `BSPLINE`: B spline with the points as control points.
    Bspline,
    /// `CSPLINE`: cubic spline through the programmed points.
    Cspline,
    /// `POLY`: polynomial interpolation.
    Poly,
    /// `G33`: thread with constant lead.
    Thread,
    /// `G34`: thread with increasing lead.
    ThreadIncreasingLead,
    /// `G35`: thread with decreasing lead.
    ThreadDecreasingLead,
    /// `G331`: rigid tapping.
    Tapping,
    /// `G332`: retraction of rigid tapping.
    TappingRetract,
    /// `G335`: convex thread, clockwise.
    ThreadConvexCw,
    /// `G336`: convex thread, counter-clockwise.
    ThreadConvexCcw,
    /// `INVCW`: involute, clockwise.
    InvoluteCw,
    /// `INVCCW`: involute, counter-clockwise.
    InvoluteCcw,
}

impl MotionKind {
    /// The name serde gives the kind (`linear`, `arc_cw`), without the
    /// allocation of going through serde: the JSON writers of motions and
    /// instructions write it for most of what they write.
    pub const fn name(self) -> &'static str {
        match self {
            MotionKind::Modal => "modal",
            MotionKind::Rapid => "rapid",
            MotionKind::Linear => "linear",
            MotionKind::ArcCw => "arc_cw",
            MotionKind::ArcCcw => "arc_ccw",
            MotionKind::ArcThroughPoint => "arc_through_point",
            MotionKind::ArcTangential => "arc_tangential",
            MotionKind::Aspline => "aspline",
            MotionKind::Bspline => "bspline",
            MotionKind::Cspline => "cspline",
            MotionKind::Poly => "poly",
            MotionKind::Thread => "thread",
            MotionKind::ThreadIncreasingLead => "thread_increasing_lead",
            MotionKind::ThreadDecreasingLead => "thread_decreasing_lead",
            MotionKind::Tapping => "tapping",
            MotionKind::TappingRetract => "tapping_retract",
            MotionKind::ThreadConvexCw => "thread_convex_cw",
            MotionKind::ThreadConvexCcw => "thread_convex_ccw",
            MotionKind::InvoluteCw => "involute_cw",
            MotionKind::InvoluteCcw => "involute_ccw",
        }
    }

    /// The motion of the G command at `group` and 1-based `index` (as
    /// [`crate::ggroups::lookup`] gives them); `None` for a command of another
    /// group and for group 1's `OEMIPO1`/`OEMIPO2`, which make no motion
    /// gcodec knows.
    pub fn of_command(group: u8, index: u8) -> Option<Self> {
        if group != MOTION_GROUP {
            return None;
        }
        Some(match index {
            1 => Self::Rapid,
            2 => Self::Linear,
            3 => Self::ArcCw,
            4 => Self::ArcCcw,
            5 => Self::ArcThroughPoint,
            6 => Self::Aspline,
            7 => Self::Bspline,
            8 => Self::Cspline,
            9 => Self::Poly,
            10 => Self::Thread,
            11 => Self::Tapping,
            12 => Self::TappingRetract,
            15 => Self::ArcTangential,
            16 => Self::ThreadIncreasingLead,
            17 => Self::ThreadDecreasingLead,
            18 => Self::InvoluteCw,
            19 => Self::InvoluteCcw,
            20 => Self::ThreadConvexCw,
            21 => Self::ThreadConvexCcw,
            _ => return None,
        })
    }
}

/// The group of the motion commands.
pub const MOTION_GROUP: u8 = 1;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ggroups;

    #[test]
    fn each_motion_command_has_its_motion() {
        let expected = [
            ("G0", Some(MotionKind::Rapid)),
            ("G1", Some(MotionKind::Linear)),
            ("G2", Some(MotionKind::ArcCw)),
            ("G3", Some(MotionKind::ArcCcw)),
            ("CIP", Some(MotionKind::ArcThroughPoint)),
            ("ASPLINE", Some(MotionKind::Aspline)),
            ("BSPLINE", Some(MotionKind::Bspline)),
            ("CSPLINE", Some(MotionKind::Cspline)),
            ("POLY", Some(MotionKind::Poly)),
            ("G33", Some(MotionKind::Thread)),
            ("G331", Some(MotionKind::Tapping)),
            ("G332", Some(MotionKind::TappingRetract)),
            ("OEMIPO1", None),
            ("OEMIPO2", None),
            ("CT", Some(MotionKind::ArcTangential)),
            ("G34", Some(MotionKind::ThreadIncreasingLead)),
            ("G35", Some(MotionKind::ThreadDecreasingLead)),
            ("INVCW", Some(MotionKind::InvoluteCw)),
            ("INVCCW", Some(MotionKind::InvoluteCcw)),
            ("G335", Some(MotionKind::ThreadConvexCw)),
            ("G336", Some(MotionKind::ThreadConvexCcw)),
        ];
        for (name, motion) in expected {
            let (group, index) = ggroups::lookup(name).unwrap();
            assert_eq!(MotionKind::of_command(group, index), motion, "{name}");
        }
        assert_eq!(
            ggroups::group(MOTION_GROUP).unwrap().members.len(),
            expected.len()
        );
        let (group, index) = ggroups::lookup("G17").unwrap();
        assert_eq!(MotionKind::of_command(group, index), None);
        assert_eq!(MotionKind::of_command(1, 0), None);
        assert_eq!(MotionKind::of_command(1, 22), None);
    }

    /// `name` is what serde writes, for every kind.
    #[test]
    fn each_name_is_the_serde_name() {
        for kind in [
            MotionKind::Modal,
            MotionKind::Rapid,
            MotionKind::Linear,
            MotionKind::ArcCw,
            MotionKind::ArcCcw,
            MotionKind::ArcThroughPoint,
            MotionKind::ArcTangential,
            MotionKind::Aspline,
            MotionKind::Bspline,
            MotionKind::Cspline,
            MotionKind::Poly,
            MotionKind::Thread,
            MotionKind::ThreadIncreasingLead,
            MotionKind::ThreadDecreasingLead,
            MotionKind::Tapping,
            MotionKind::TappingRetract,
            MotionKind::ThreadConvexCw,
            MotionKind::ThreadConvexCcw,
            MotionKind::InvoluteCw,
            MotionKind::InvoluteCcw,
        ] {
            let serde = serde_json::to_string(&kind).expect("serialises");
            assert_eq!(serde, format!("\"{}\"", kind.name()));
        }
    }
}
