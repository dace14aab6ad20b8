//! `lint::motion_without_feed`: a feed motion (`G1`, a circle, a spline)
//! in a main program on a path where no feed `F` has been set: the control
//! stops with alarm 10860 (`run::no_feed` when it runs). Reported once, at
//! the first such motion.

use gcodec_ail::Op;
use gcodec_lang::MotionKind;
use gcodec_source::{Diagnostic, codes};

use super::facts::Set;
use super::{Context, Findings};
use crate::ProgramKind;

/// A motion at the programmed feed `F`: not a rapid, not a thread or
/// tapping (which go by the lead), not one whose command is known only
/// when it runs.
pub(super) fn is_feed_motion(motion: MotionKind) -> bool {
    use MotionKind::*;
    matches!(
        motion,
        Linear
            | ArcCw
            | ArcCcw
            | ArcThroughPoint
            | ArcTangential
            | Aspline
            | Bspline
            | Cspline
            | Poly
            | InvoluteCw
            | InvoluteCcw
    )
}

/// The first feed motion some path reaches with `fact` holding.
pub(super) fn first_feed_motion_where(cx: &Context<'_>, fact: Set) -> Option<usize> {
    cx.document
        .instructions
        .iter()
        .enumerate()
        .position(|(at, i)| {
            matches!(&i.op, Op::Motion { motion, .. } if is_feed_motion(*motion))
                && cx.graph.is_reached(at)
                && cx.facts.may_hold(at, fact)
        })
}

pub(super) fn check(cx: &Context<'_>, out: &mut Findings) {
    if cx.kind != ProgramKind::Main {
        return;
    }
    if let Some(at) = first_feed_motion_where(cx, Set::FEED_UNSET) {
        out.push(
            Diagnostic::new(
                codes::lint::MOTION_WITHOUT_FEED,
                "a feed motion with no feed `F` set before it on some path",
            )
            .with_label(cx.span_of(at), "this motion has no feed")
            .with_help("program the feed with `F…` in this block or before it; the control stops with alarm 10860"),
        );
    }
}
