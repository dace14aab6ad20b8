//! `lint::spindle_without_speed`: `M3` or `M4` in a main program on a
//! path where no speed `S` has been set for that spindle: the spindle
//! starts at speed 0 (or at whatever the last program left). Reported once
//! per spindle, at its first such start.

use gcodec_ail::Op;
use gcodec_lang::MClass;
use gcodec_source::{Diagnostic, codes};

use super::facts::Set;
use super::{Context, Findings};
use crate::ProgramKind;

pub(super) fn check(cx: &Context<'_>, out: &mut Findings) {
    if cx.kind != ProgramKind::Main {
        return;
    }
    let mut reported: Vec<u32> = Vec::new();
    for (at, instruction) in cx.document.instructions.iter().enumerate() {
        let Op::MFunction(m) = &instruction.op else {
            continue;
        };
        if m.class != MClass::Spindle
            || !matches!(m.m_value, Some(3 | 4))
            || m.address_extension_expr.is_some()
        {
            continue;
        }
        let spindle = cx.facts.spindle(m.address_extension);
        let Some(unset) = Set::speed_unset(spindle) else {
            continue;
        };
        if reported.contains(&spindle) || !cx.graph.is_reached(at) || !cx.facts.may_hold(at, unset)
        {
            continue;
        }
        reported.push(spindle);
        out.push(
            Diagnostic::new(
                codes::lint::SPINDLE_WITHOUT_SPEED,
                format!("spindle {spindle} is started with no speed `S` set before on some path"),
            )
            .with_label(cx.span_of(at), "started here")
            .with_help(if spindle == cx.facts.master_spindle {
                "set the speed with `S…` in this block or before it".to_owned()
            } else {
                format!("set the speed with `S{spindle}=…` in this block or before it")
            }),
        );
    }
}
