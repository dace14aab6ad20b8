//! The path stage: between the blocks the channel interprets and the
//! motions that go out, the elements the control inserts or changes with
//! a look-ahead (SPEC §11.12):
//!
//! - contour definitions at a corner (`CHF=`, `CHR=`, `RND=`, `RNDM=`),
//!   which trim the element into the corner and the one out of it
//!   (`transition.rs`);
//! - tool radius compensation (`G41`/`G42`), which moves the tool centre
//!   onto the equidistant of the contour and joins equidistants at the
//!   corners (`compensation.rs`).
//!
//! Both need the next element in the plane before an element is final,
//! so the stage holds the elements and every output of the channel that
//! comes after them (events, CSV rows) until they are, and releases them
//! in the order they came: events stay in block order. While neither is
//! in force the stage is empty and the channel bypasses it, so a program
//! without them pays nothing. What the stage holds is bounded: by the
//! blocks without motion in the plane that compensation allows between
//! two elements (MD20250 `CUTCOM_MAXNUM_DUMMY_BLOCKS`), and by the next
//! element ending every pending corner.
//!
//! The geometry is in the working plane (`planar.rs`); the other axes
//! move as the block programs them. The stage is generic over what the
//! channel keeps of a motion (`M`) and of other output (`O`), so that it
//! knows nothing of events.

pub mod compensation;
pub mod planar;
pub mod transition;

use std::collections::VecDeque;

use gcodec_source::Code;

pub use compensation::{CornerMode, Side};
use planar::{P2, Segment};
pub use transition::CornerElement;

use crate::event::InsertedElement;

/// The compensation in force for an element.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Compensation {
    /// `None` under `G40`.
    pub side: Option<Side>,
    /// The cutting edge's radius plus `OFFN`, mm.
    pub radius: f64,
    pub corner: CornerMode,
    /// `CDON`.
    pub collision_detection: bool,
    /// How compensation starts and ends (group 17).
    pub approach: Approach,
    /// From the centre of the cutting edge's radius to the point the
    /// machine positions (a turning tool's theoretical tip), in the plane;
    /// zero for a milling tool.
    pub tip: P2,
}

impl Compensation {
    pub const OFF: Compensation = Compensation {
        side: None,
        radius: 0.0,
        corner: CornerMode::Circle { disc: 0 },
        collision_detection: false,
        approach: Approach::Normal,
        tip: [0.0, 0.0],
    };

    /// Where the tool's reference point lies from the centre of its
    /// cutting edge while compensation is on (`tip`); zero under `G40`,
    /// where the reference point is on the programmed point.
    pub fn tip_in_force(&self) -> P2 {
        if self.side.is_some() {
            self.tip
        } else {
            [0.0, 0.0]
        }
    }

    /// The signed offset: positive to the left of the contour.
    pub fn offset(&self) -> f64 {
        match self.side {
            Some(Side::Left) => self.radius,
            Some(Side::Right) => -self.radius,
            None => 0.0,
        }
    }
}

/// How compensation starts and ends (group 17).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Approach {
    /// `NORM`: straight, perpendicular to the contour at its end point.
    Normal,
    /// `KONT`: round the contour's end point when the tool is behind it.
    AroundEnds,
    /// `KONTT` (and `KONTC`): on a circle tangent to the equidistant.
    Tangent,
}

/// A motion as the stage holds it: what the channel keeps of it, its
/// contour in the plane (`None`: it does not move in the plane), and what
/// the stage works out.
#[derive(Clone, Debug)]
pub struct Element<M> {
    pub motion: M,
    pub contour: Option<Segment>,
    pub compensation: Compensation,
    /// A corner element due at its end (the block's `CHF=`…, or `RNDM`).
    pub corner: Option<CornerElement>,
    /// Set for a chamfer or rounding the stage inserted.
    pub inserted: Option<InsertedElement>,
    /// The contour was trimmed at its start or end by a corner element.
    pub trimmed: bool,
    /// Where the tool centre goes while compensation is on.
    pub tool: Option<ToolTrack>,
    /// The first block of a contour definition (`ANG=` alone): its end
    /// point comes with the next block ([`PathStage::complete_pending`]).
    pub pending: bool,
}

/// The tool centre's path for one element.
#[derive(Clone, Debug, Default)]
pub struct ToolTrack {
    pub start: Option<P2>,
    pub end: Option<P2>,
    /// Pieces of the tool-centre path only, traversed before the element
    /// (a transition circle, corner lines), each with its contour corner.
    pub before: Vec<Piece>,
    /// The block that selects compensation: its tool path is a straight
    /// line from the start to the compensated start of the next element.
    pub approach: bool,
    /// Left out by collision detection (`CDON`): the tool stands still.
    pub left_out: bool,
    /// The tool-centre path of an approach or retraction that is not a
    /// straight line (`KONTT`).
    pub curve: Option<Segment>,
}

/// A piece of the tool-centre path at a corner, where the contour stands
/// still.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    pub kind: InsertedElement,
    pub path: Segment,
    /// The contour corner it goes round.
    pub corner: P2,
}

impl<M> Element<M> {
    fn is_final(&self) -> bool {
        !self.pending && self.corner.is_none() && self.tool.as_ref().is_none_or(|t| t.end.is_some())
    }
}

/// What the stage holds, in the order the channel produced it.
#[derive(Debug)]
// Not boxed: what is held is a few elements at a time, moved in and out
// of one queue, and a box would allocate for each.
#[allow(clippy::large_enum_variant)]
pub enum Held<M, O> {
    Element(Element<M>),
    Output(O),
}

/// What the stage reports: an alarm it stops with (the compensation
/// cannot follow the contour) or a warning of what it left out or
/// changed; the code's level says which.
#[derive(Clone, Debug, PartialEq)]
pub struct PathDiagnostic {
    pub code: &'static Code,
    pub message: String,
}

/// The look-ahead buffer.
#[derive(Debug)]
pub struct PathStage<M, O> {
    held: VecDeque<Held<M, O>>,
    /// Blocks ended since the last element in the plane while
    /// compensation was on.
    dummy_blocks: u32,
    max_dummy_blocks: u32,
    /// MD20240 `CUTCOM_MAXNUM_CHECK_BLOCKS`: how many elements collision
    /// detection looks back over, and holds.
    pub(crate) max_check_blocks: u32,
    /// Warnings to report, taken by the channel.
    pub warnings: Vec<PathDiagnostic>,
}

impl<M: Clone, O> PathStage<M, O> {
    pub fn new(max_dummy_blocks: u32, max_check_blocks: u32) -> Self {
        Self {
            held: VecDeque::new(),
            dummy_blocks: 0,
            max_dummy_blocks,
            max_check_blocks,
            warnings: Vec::new(),
        }
    }

    /// Nothing held: outputs go straight out.
    pub fn is_idle(&self) -> bool {
        self.held.is_empty()
    }

    pub fn hold_output(&mut self, output: O) {
        self.held.push_back(Held::Output(output));
    }

    /// Where the tool centre stands after the last motion taken, in the
    /// plane, while compensation is on: the end of its equidistant where
    /// it is final, else perpendicular to its element's end (where a
    /// stop of the look-ahead would leave it); `None` without
    /// compensation.
    pub fn tool_centre_now(&self) -> Option<P2> {
        let last = self.held.iter().rev().find_map(|h| match h {
            Held::Element(e) => Some(e),
            Held::Output(_) => None,
        })?;
        last.compensation.side?;
        let tool = last.tool.as_ref()?;
        if let Some(end) = tool.end {
            return Some(end);
        }
        match last.contour {
            Some(contour) => Some(compensation::normal_end(
                &contour,
                last.compensation.offset(),
            )),
            None => tool.start,
        }
    }

    /// Holds the first block of a contour definition, whose end point is
    /// not known yet: everything after it waits.
    pub fn hold_pending(&mut self, mut element: Element<M>) {
        element.pending = true;
        self.held.push_back(Held::Element(element));
    }

    /// The second block of a contour definition came: `patch` gives the
    /// waiting element its end point, and it is taken as if it came now,
    /// before the outputs made after it.
    pub fn complete_pending(
        &mut self,
        patch: impl FnOnce(&mut Element<M>),
    ) -> Result<(), PathDiagnostic> {
        let Some(at) = self
            .held
            .iter()
            .rposition(|h| matches!(h, Held::Element(e) if e.pending))
        else {
            return Ok(());
        };
        let after = self.held.split_off(at + 1);
        let Some(Held::Element(mut element)) = self.held.pop_back() else {
            self.held.extend(after);
            return Ok(());
        };
        element.pending = false;
        patch(&mut element);
        let pushed = self.push(element);
        self.held.extend(after);
        pushed
    }

    /// The contour definition waiting will not be completed (the run
    /// stops at the block that should have ended it): it goes out as it
    /// stands, without a second complaint.
    pub fn abandon_pending(&mut self) {
        for held in &mut self.held {
            if let Held::Element(e) = held {
                e.pending = false;
            }
        }
    }

    /// Takes the next motion of the program.
    pub fn push(&mut self, mut element: Element<M>) -> Result<(), PathDiagnostic> {
        let Some(contour) = element.contour else {
            return self.push_without_plane_motion(element);
        };
        self.dummy_blocks = 0;
        if contour.is_point() {
            return self.push_without_plane_motion(Element {
                contour: None,
                ..element
            });
        }
        let previous = self.last_plane_element();
        // The corner element of the previous block, between it and this:
        // an element of the contour like the others, traversed right
        // after the previous one.
        if let Some(p) = previous
            && let Held::Element(lead) = &mut self.held[p]
            && let Some(corner) = lead.corner.take()
            && let Some(mut inserted) = self.corner_between(p, &mut element, corner)
        {
            let compensated = match &self.held[p] {
                Held::Element(e) => e.compensation.side.is_some(),
                Held::Output(_) => false,
            };
            self.compensate(compensated.then_some(p), &mut inserted)?;
            self.held.insert(p + 1, Held::Element(inserted));
        }
        let previous = self.compensating();
        self.compensate(previous, &mut element)?;
        self.held.push_back(Held::Element(element));
        Ok(())
    }

    /// Compensation for `element` after the compensated element in the
    /// plane held at `previous`, or after none.
    fn compensate(
        &mut self,
        previous: Option<usize>,
        element: &mut Element<M>,
    ) -> Result<(), PathDiagnostic> {
        match previous {
            Some(p) => compensation::join(self, p, element),
            None => compensation::start(element),
        }
    }

    /// The held element in the plane that compensation continues from:
    /// the last one, if it is compensated and no motion since ended
    /// compensation.
    fn compensating(&self) -> Option<usize> {
        let last = self.held.iter().rev().find_map(|h| match h {
            Held::Element(e) => Some(e),
            Held::Output(_) => None,
        })?;
        last.compensation.side?;
        let p = self.last_plane_element()?;
        match &self.held[p] {
            Held::Element(e) if e.compensation.side.is_some() => Some(p),
            _ => None,
        }
    }

    /// A motion with no extent in the plane: while compensation is on it
    /// keeps the tool where the last element ends; a corner element
    /// waiting for it is left out.
    fn push_without_plane_motion(&mut self, mut element: Element<M>) -> Result<(), PathDiagnostic> {
        element.corner = None;
        if let Some(p) = self.last_plane_element()
            && let Held::Element(lead) = &mut self.held[p]
            && lead.corner.take().is_some()
        {
            self.warnings.push(PathDiagnostic {
                code: gcodec_source::codes::run::CORNER_ELEMENT_LEFT_OUT,
                message: "the chamfer or rounding is left out: the next motion does not move in the plane".into(),
            });
        }
        if let Some(p) = self.compensating()
            && let Held::Element(lead) = &mut self.held[p]
        {
            if element.compensation.side.is_none() {
                // `G40` and a motion off the plane (an infeed, a retract
                // along the tool axis): compensation ends with it, from
                // the point perpendicular to the last element's end.
                let corner = lead.contour.map(|c| c.end());
                match &mut lead.tool {
                    Some(tool) if tool.approach => lead.tool = None,
                    Some(tool) => {
                        let end = lead
                            .contour
                            .map(|c| compensation::normal_end(&c, lead.compensation.offset()));
                        tool.end = end;
                        element.tool = Some(ToolTrack {
                            start: end,
                            end: corner,
                            ..ToolTrack::default()
                        });
                    }
                    None => {}
                }
            } else {
                element.tool = Some(ToolTrack {
                    start: lead.tool.as_ref().and_then(|t| t.end),
                    end: lead.tool.as_ref().and_then(|t| t.end),
                    ..ToolTrack::default()
                });
            }
        }
        self.held.push_back(Held::Element(element));
        Ok(())
    }

    /// The chamfer or rounding at the corner between the element at
    /// `lead` and `leave`, both trimmed to it; `None` where the corner
    /// takes none.
    fn corner_between(
        &mut self,
        lead: usize,
        leave: &mut Element<M>,
        corner: CornerElement,
    ) -> Option<Element<M>> {
        let Held::Element(lead_element) = &mut self.held[lead] else {
            return None;
        };
        let (a, b) = (lead_element.contour?, leave.contour?);
        let resolved = transition::resolve(&a, &b, corner)?;
        if resolved.reduced {
            self.warnings.push(PathDiagnostic {
                code: gcodec_source::codes::run::CORNER_ELEMENT_REDUCED,
                message: "the chamfer or rounding is reduced: an element at the corner is too short for it".into(),
            });
        }
        lead_element.contour = Some(a.with_ends(a.start(), resolved.lead_end));
        lead_element.trimmed = true;
        leave.contour = Some(b.with_ends(resolved.leave_start, b.end()));
        leave.trimmed = true;
        Some(Element {
            motion: lead_element.motion.clone(),
            contour: Some(resolved.inserted),
            compensation: lead_element.compensation,
            corner: None,
            inserted: Some(match corner {
                CornerElement::Rounding(_) => InsertedElement::Rounding,
                _ => InsertedElement::Chamfer,
            }),
            trimmed: false,
            tool: None,
            pending: false,
        })
    }

    /// The index of the last held element that moves in the plane.
    fn last_plane_element(&self) -> Option<usize> {
        self.held.iter().rposition(|h| match h {
            Held::Element(e) => e.contour.is_some(),
            Held::Output(_) => false,
        })
    }

    /// The end of a block: counts the blocks without motion in the plane
    /// while compensation waits for the next element.
    pub fn block_ended(&mut self, moved_in_plane: bool) -> Result<(), PathDiagnostic> {
        if moved_in_plane {
            return Ok(());
        }
        if self.compensating().is_none() {
            return Ok(());
        }
        self.dummy_blocks += 1;
        if self.dummy_blocks > self.max_dummy_blocks {
            self.dummy_blocks = 0;
            return Err(PathDiagnostic {
                code: gcodec_source::codes::run::COMPENSATION_DUMMY_BLOCKS,
                message: format!(
                    "more than {} blocks without motion in the plane while tool radius compensation is on (MD20250 CUTCOM_MAXNUM_DUMMY_BLOCKS)",
                    self.max_dummy_blocks
                ),
            });
        }
        Ok(())
    }

    /// Under collision detection an element may still be left out until
    /// `max_check_blocks` elements follow it, or compensation ends.
    fn may_still_be_left_out(&self, index: usize) -> bool {
        let Some(Held::Element(e)) = self.held.get(index) else {
            return false;
        };
        if !e.compensation.collision_detection || e.tool.is_none() || e.contour.is_none() {
            return false;
        }
        let mut after = 0;
        for held in self.held.range(index + 1..) {
            if let Held::Element(later) = held {
                if later.compensation.side.is_none() {
                    return false;
                }
                if later.contour.is_some() {
                    after += 1;
                }
            }
        }
        after < self.max_check_blocks
    }

    /// Takes what is final from the front, in order.
    pub fn release(&mut self, out: &mut Vec<Held<M, O>>) {
        while let Some(front) = self.held.front() {
            if let Held::Element(e) = front
                && (!e.is_final() || self.may_still_be_left_out(0))
            {
                break;
            }
            if let Some(item) = self.held.pop_front() {
                out.push(item);
            }
        }
    }

    /// The program ends (or the run stops): no next element comes. A
    /// corner element still due is left out; compensation ends each
    /// element perpendicular to its end. Everything is released.
    pub fn finish(&mut self, out: &mut Vec<Held<M, O>>) {
        let mut end: Option<P2> = None;
        for held in &mut self.held {
            let Held::Element(e) = held else { continue };
            if std::mem::take(&mut e.pending) {
                self.warnings.push(PathDiagnostic {
                    code: gcodec_source::codes::run::CONTOUR_ANGLE,
                    message: "the contour definition begun by `ANG=` without an end point has no block that ends it (`X… Y… ANG=…`)".into(),
                });
            }
            if e.corner.take().is_some() {
                self.warnings.push(PathDiagnostic {
                    code: gcodec_source::codes::run::CORNER_ELEMENT_LEFT_OUT,
                    message: "the chamfer or rounding is left out: no motion in the plane follows"
                        .into(),
                });
            }
            if let Some(tool) = &mut e.tool {
                if tool.end.is_none() {
                    tool.end = Some(match e.contour {
                        Some(contour) => {
                            compensation::normal_end(&contour, e.compensation.offset())
                        }
                        None => end.or(tool.start).unwrap_or_default(),
                    });
                }
                if tool.start.is_none() {
                    tool.start = end.or(tool.end);
                }
                end = tool.end;
            }
        }
        out.extend(self.held.drain(..));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(motion: u32, start: P2, end: P2) -> Element<u32> {
        Element {
            motion,
            contour: Some(Segment::Line { start, end }),
            compensation: Compensation::OFF,
            corner: None,
            inserted: None,
            trimmed: false,
            tool: None,
            pending: false,
        }
    }

    /// What the stage releases, as (motion or output, inserted?).
    fn released(stage: &mut PathStage<u32, &'static str>) -> Vec<String> {
        let mut out = Vec::new();
        stage.release(&mut out);
        out.iter()
            .map(|h| match h {
                Held::Element(e) => match e.inserted {
                    Some(kind) => format!("{} {}", e.motion, kind.name()),
                    None => e.motion.to_string(),
                },
                Held::Output(o) => (*o).to_owned(),
            })
            .collect()
    }

    #[test]
    fn a_corner_element_holds_what_follows_until_the_next_element() {
        let mut stage = PathStage::new(3, 4);
        let mut first = line(1, [0.0, 0.0], [0.0, 10.0]);
        first.corner = Some(CornerElement::Rounding(2.0));
        stage.push(first).unwrap();
        stage.hold_output("M8 of block 2");
        assert!(released(&mut stage).is_empty(), "the corner is not known");
        stage.push(line(2, [0.0, 10.0], [10.0, 10.0])).unwrap();
        // The rounding goes right after the element it ends, before the
        // next block's own output; the next element is final at once.
        assert_eq!(
            released(&mut stage),
            ["1", "1 rounding", "M8 of block 2", "2"]
        );
        assert!(stage.is_idle());
    }

    #[test]
    fn compensation_holds_an_element_until_its_corner_is_known() {
        let mut stage = PathStage::new(3, 4);
        let left = Compensation {
            side: Some(Side::Left),
            radius: 1.0,
            ..Compensation::OFF
        };
        let mut approach = line(1, [-5.0, 0.0], [0.0, 0.0]);
        approach.compensation = left;
        stage.push(approach).unwrap();
        let mut wall = line(2, [0.0, 0.0], [10.0, 0.0]);
        wall.compensation = left;
        stage.push(wall).unwrap();
        assert_eq!(
            released(&mut stage),
            ["1"],
            "the approach ends where the wall starts"
        );
        assert!(!stage.is_idle(), "the wall waits for its corner");
        for _ in 0..3 {
            stage.block_ended(false).unwrap();
        }
        let error = stage.block_ended(false).unwrap_err();
        assert_eq!(
            error.code,
            gcodec_source::codes::run::COMPENSATION_DUMMY_BLOCKS
        );
        let mut out = Vec::new();
        stage.finish(&mut out);
        let Some(Held::Element(wall)) = out.first() else {
            panic!("{out:?}")
        };
        assert_eq!(wall.tool.as_ref().and_then(|t| t.end), Some([10.0, 1.0]));
    }
}
