//! `lint::tool_without_edge`: a feed motion after a tool change with no
//! cutting edge `D` selected since, on a machine whose MD20270
//! (`cutting_edge_default`) gives a changed-in tool no edge: the tool cuts
//! with no length or radius offset. Reported once, at the first such
//! motion.

use gcodec_source::{Diagnostic, codes};

use super::facts::Set;
use super::motion_without_feed::first_feed_motion_where;
use super::{Context, Findings};

pub(super) fn check(cx: &Context<'_>, out: &mut Findings) {
    if let Some(at) = first_feed_motion_where(cx, Set::NO_EDGE) {
        out.push(
            Diagnostic::new(
                codes::lint::TOOL_WITHOUT_EDGE,
                "a feed motion with the changed tool and no cutting edge selected",
            )
            .with_label(cx.span_of(at), "this motion has no tool offset")
            .with_help(
                "select the cutting edge with `D1` (or the edge meant) after the change; \
                 this machine's `cutting_edge_default` (MD20270) is 0",
            ),
        );
    }
}
