//! LinuxCNC's interpreter as a reference: what `rs274`, LinuxCNC's
//! standalone interpreter, prints for a program (its canonical motion
//! calls), read back as the end points of its moves, each with the block
//! it belongs to.
//!
//! rs274 prints one call a line: a counter, the `N` word of the block it
//! was reading when it made the call (`N.....` for a block without one)
//! and the call with its arguments, lengths in the program's unit with
//! four decimals:
//!
//! ```text
//!    21 N70    STRAIGHT_FEED(-3.0000, 50.0000, -1.0000, 0.0000, 0.0000, 0.0000)
//!    22 N70    ARC_FEED(0.0000, 53.0000, 0.0000, 50.0000, -1, -1.0000, 0.0000, 0.0000, 0.0000)
//! ```
//!
//! It names a block only by its `N` word, so the programs compared with
//! it number their blocks ([`block_numbers`]). With cutter compensation
//! on, LinuxCNC reads one block ahead before it moves (the corner decides
//! where the move ends), so the block a call is printed under is not
//! always the block it belongs to: [`attribute`] undoes that.

use std::collections::BTreeMap;
use std::fmt;

/// One call rs274 printed that the comparison needs.
#[derive(Clone, Debug, PartialEq)]
pub struct Call {
    /// The line of the recording (1-based), for messages.
    pub line: usize,
    /// The `N` word of the block rs274 was reading; `None` for `N.....`.
    pub reading: Option<u32>,
    pub what: CallKind,
}

/// What a [`Call`] is.
#[derive(Clone, Debug, PartialEq)]
pub enum CallKind {
    /// `STRAIGHT_TRAVERSE`, `STRAIGHT_FEED` or `ARC_FEED`.
    Move(Move),
    /// `COMMENT("interpreter: cutter radius compensation on left")` (or
    /// `right`): `G41`/`G42` took effect.
    CompensationOn(Side),
    /// `COMMENT("interpreter: cutter radius compensation off")`: `G40`.
    CompensationOff,
}

/// The side of the contour the tool is on: `G41` left, `G42` right.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    Left,
    Right,
}

/// A move of the tool (the tool centre, when compensating).
#[derive(Clone, Debug, PartialEq)]
pub struct Move {
    pub kind: MoveKind,
    /// X, Y and Z at the end.
    pub end: [f64; 3],
}

/// How a [`Move`] moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MoveKind {
    /// `STRAIGHT_TRAVERSE`: rapid.
    Traverse,
    /// `STRAIGHT_FEED`: a line at feed.
    Line,
    /// `ARC_FEED`: an arc or helix; `rotation` as LinuxCNC gives it,
    /// positive counter-clockwise, its magnitude one more than the number
    /// of full turns.
    Arc { rotation: i32 },
}

impl MoveKind {
    /// A short name for tables: `rapid`, `line`, `arc cw`, `arc ccw`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Traverse => "rapid",
            Self::Line => "line",
            Self::Arc { rotation } if rotation < 0 => "arc cw",
            Self::Arc { .. } => "arc ccw",
        }
    }
}

/// A line of the recording that could not be read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseError {
    /// 1-based.
    pub line: usize,
    pub message: String,
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "rs274 output line {}: {}", self.line, self.message)
    }
}

impl std::error::Error for ParseError {}

/// The plane of `ARC_FEED`'s arguments, as `SELECT_PLANE` last set it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Plane {
    Xy,
    Yz,
    Xz,
}

impl Plane {
    /// The axes (0 X, 1 Y, 2 Z) of ARC_FEED's `first_end`, `second_end`
    /// and `axis_end_point`: LinuxCNC's canonical order of each plane.
    fn arc_axes(self) -> [usize; 3] {
        match self {
            Self::Xy => [0, 1, 2],
            Self::Yz => [1, 2, 0],
            Self::Xz => [2, 0, 1],
        }
    }
}

/// Reads rs274's output: the moves and the compensation switches, in
/// the order printed. Other calls are skipped, except `SELECT_PLANE`,
/// which says how to read `ARC_FEED`; a line that is not a call (rs274
/// prints none, but a hand edit might) is an error.
pub fn parse(text: &str) -> Result<Vec<Call>, ParseError> {
    let mut plane = Plane::Xy;
    let mut calls = Vec::new();
    for (index, text) in text.lines().enumerate() {
        let line = index + 1;
        if text.trim().is_empty() {
            continue;
        }
        let error = |message: String| ParseError { line, message };
        let (reading, name, args) = split_call(text).ok_or_else(|| {
            error(format!(
                "not `COUNTER N… NAME(ARGUMENTS)`: {:?}",
                text.trim()
            ))
        })?;
        let what = match name {
            "SELECT_PLANE" => {
                plane = match args {
                    "CANON_PLANE_XY" => Plane::Xy,
                    "CANON_PLANE_YZ" => Plane::Yz,
                    "CANON_PLANE_XZ" => Plane::Xz,
                    other => return Err(error(format!("unknown plane {other:?}"))),
                };
                continue;
            }
            "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" => {
                let numbers = numbers(args, 3).map_err(&error)?;
                let kind = if name == "STRAIGHT_FEED" {
                    MoveKind::Line
                } else {
                    MoveKind::Traverse
                };
                CallKind::Move(Move {
                    kind,
                    end: [numbers[0], numbers[1], numbers[2]],
                })
            }
            "ARC_FEED" => {
                // first_end, second_end, first_axis, second_axis, rotation,
                // axis_end_point, then the other axes.
                let numbers = numbers(args, 6).map_err(&error)?;
                let rotation = numbers[4];
                if rotation.fract() != 0.0 || rotation == 0.0 {
                    return Err(error(format!("rotation {rotation} is not a turn count")));
                }
                let mut end = [0.0; 3];
                let [first, second, axis] = plane.arc_axes();
                end[first] = numbers[0];
                end[second] = numbers[1];
                end[axis] = numbers[5];
                CallKind::Move(Move {
                    kind: MoveKind::Arc {
                        rotation: rotation as i32,
                    },
                    end,
                })
            }
            "COMMENT" => match args {
                "\"interpreter: cutter radius compensation on left\"" => {
                    CallKind::CompensationOn(Side::Left)
                }
                "\"interpreter: cutter radius compensation on right\"" => {
                    CallKind::CompensationOn(Side::Right)
                }
                "\"interpreter: cutter radius compensation off\"" => CallKind::CompensationOff,
                _ => continue,
            },
            _ => continue,
        };
        calls.push(Call {
            line,
            reading,
            what,
        });
    }
    Ok(calls)
}

/// `   21 N70    NAME(ARGS)` as the block read (`None` for `N.....`), the
/// name and the arguments' text.
fn split_call(text: &str) -> Option<(Option<u32>, &str, &str)> {
    let mut words = text.trim_start().splitn(3, char::is_whitespace);
    words.next()?.parse::<u32>().ok()?;
    let block = words.next()?.strip_prefix('N')?;
    let reading = if block.bytes().all(|b| b == b'.') {
        None
    } else {
        Some(block.parse().ok()?)
    };
    let call = words.next()?.trim();
    let (name, args) = call.strip_suffix(')')?.split_once('(')?;
    Some((reading, name, args))
}

/// The comma-separated numbers of `args`, at least `at_least` of them.
fn numbers(args: &str, at_least: usize) -> Result<Vec<f64>, String> {
    let numbers = args
        .split(',')
        .map(|n| {
            n.trim()
                .parse::<f64>()
                .map_err(|_| format!("{:?} is not a number", n.trim()))
        })
        .collect::<Result<Vec<f64>, String>>()?;
    if numbers.len() < at_least {
        return Err(format!(
            "{} arguments, expected at least {at_least}",
            numbers.len()
        ));
    }
    Ok(numbers)
}

/// A move with the block it belongs to.
#[derive(Clone, Debug, PartialEq)]
pub struct BlockMove {
    /// The block's `N` word; `None` for a block without one.
    pub block: Option<u32>,
    pub motion: Move,
    /// The line of the recording, for messages.
    pub line: usize,
}

/// Every move of `calls` with the block it belongs to, in order.
///
/// Without compensation a move belongs to the block rs274 was reading.
/// With compensation on, LinuxCNC holds each move back until it has read
/// the next motion block, which says where the move ends (at the
/// intersection of an inside corner, perpendicular to its end before an
/// outside one): so the first move printed while reading a block is the
/// previous motion block's (the `G41`/`G42` block's, first), and the
/// moves printed after it in the same block are that block's own
/// elements before its programmed move, the arc round an outside corner.
/// SINUMERIK counts its transition circle (`G450`) to the next block the
/// same way. At the `G40` block the previous block's move comes first,
/// then compensation goes off and the `G40` block's own move follows.
/// The rule is what the recorded fixtures of
/// `tests/fixtures/compensation/linuxcnc` show rs274 doing.
pub fn attribute(calls: &[Call]) -> Vec<BlockMove> {
    let mut moves = Vec::new();
    let mut compensating = false;
    // The motion block whose move LinuxCNC still holds back.
    let mut held: Option<Option<u32>> = None;
    // The block of the last call, and whether a move was printed in it.
    let mut reading: Option<Option<u32>> = None;
    let mut moved_in_block = false;
    for call in calls {
        if reading != Some(call.reading) {
            reading = Some(call.reading);
            moved_in_block = false;
        }
        match &call.what {
            CallKind::CompensationOn(_) => {
                compensating = true;
                held = Some(call.reading);
            }
            CallKind::CompensationOff => compensating = false,
            CallKind::Move(motion) => {
                let block = match held {
                    Some(previous) if compensating && !moved_in_block => previous,
                    _ => call.reading,
                };
                if compensating {
                    held = Some(call.reading);
                }
                moved_in_block = true;
                moves.push(BlockMove {
                    block,
                    motion: motion.clone(),
                    line: call.line,
                });
            }
        }
    }
    moves
}

/// The `N` word at the start of each line of a program (either dialect),
/// by number: its line (1-based). A line without one is left out.
pub fn block_numbers(program: &str) -> BTreeMap<u32, u32> {
    let mut numbers = BTreeMap::new();
    for (index, line) in program.lines().enumerate() {
        if let Some(number) = n_word(line) {
            numbers.insert(number, index as u32 + 1);
        }
    }
    numbers
}

/// The number of the `N` word a line starts with (`N60 X0 Y50`: 60).
fn n_word(line: &str) -> Option<u32> {
    let rest = line.trim_start().strip_prefix(['N', 'n'])?;
    let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    rest[..digits].parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lines of `square_outside_g41.rs274.txt`: a square cut outside with
    /// G41, each outside corner an arc.
    const SQUARE_G41: &str = "\
   10 N10    SELECT_PLANE(CANON_PLANE_XY)
   16 N30    STRAIGHT_TRAVERSE(0.0000, -20.0000, 5.0000, 0.0000, 0.0000, 0.0000)
   17 N40    SET_FEED_RATE(200.0000)
   18 N40    STRAIGHT_FEED(0.0000, -20.0000, -1.0000, 0.0000, 0.0000, 0.0000)
   19 N50    COMMENT(\"interpreter: cutter radius compensation on left\")
   20 N60    STRAIGHT_FEED(-3.0000, 0.0000, -1.0000, 0.0000, 0.0000, 0.0000)
   21 N70    STRAIGHT_FEED(-3.0000, 50.0000, -1.0000, 0.0000, 0.0000, 0.0000)
   22 N70    ARC_FEED(0.0000, 53.0000, 0.0000, 50.0000, -1, -1.0000, 0.0000, 0.0000, 0.0000)
   23 N80    STRAIGHT_FEED(50.0000, 53.0000, -1.0000, 0.0000, 0.0000, 0.0000)
   24 N80    ARC_FEED(53.0000, 50.0000, 50.0000, 50.0000, -1, -1.0000, 0.0000, 0.0000, 0.0000)
   25 N90    STRAIGHT_FEED(53.0000, 0.0000, -1.0000, 0.0000, 0.0000, 0.0000)
   26 N90    ARC_FEED(50.0000, -3.0000, 50.0000, 0.0000, -1, -1.0000, 0.0000, 0.0000, 0.0000)
   27 N100   STRAIGHT_FEED(-0.0000, -3.0000, -1.0000, 0.0000, 0.0000, 0.0000)
   28 N100   COMMENT(\"interpreter: cutter radius compensation off\")
   29 N100   STRAIGHT_FEED(-20.0000, 0.0000, -1.0000, 0.0000, 0.0000, 0.0000)
   35 N.....   ON_RESET()
";

    fn line(end: [f64; 3]) -> Move {
        Move {
            kind: MoveKind::Line,
            end,
        }
    }

    #[test]
    fn reads_moves_and_switches_and_skips_the_other_calls() {
        let calls = parse(SQUARE_G41).expect("parses");
        let kinds: Vec<_> = calls.iter().map(|c| (c.line, c.reading, &c.what)).collect();
        assert_eq!(calls.len(), 13);
        assert_eq!(
            kinds[0],
            (
                2,
                Some(30),
                &CallKind::Move(Move {
                    kind: MoveKind::Traverse,
                    end: [0.0, -20.0, 5.0]
                })
            )
        );
        assert_eq!(
            kinds[2],
            (5, Some(50), &CallKind::CompensationOn(Side::Left))
        );
        assert_eq!(
            kinds[5],
            (
                8,
                Some(70),
                &CallKind::Move(Move {
                    kind: MoveKind::Arc { rotation: -1 },
                    end: [0.0, 53.0, -1.0]
                })
            )
        );
        assert_eq!(kinds[11], (14, Some(100), &CallKind::CompensationOff));
    }

    #[test]
    fn a_block_without_an_n_word_reads_as_none() {
        let calls =
            parse("    3 N.....   STRAIGHT_FEED(1.0, 2.0, 3.0, 0.0, 0.0, 0.0)\n").expect("parses");
        assert_eq!(calls[0].reading, None);
        assert_eq!(calls[0].what, CallKind::Move(line([1.0, 2.0, 3.0])));
    }

    #[test]
    fn arc_feed_reads_its_ends_in_the_plane_selected() {
        // G18 G2 X20 Z-10 I0 K-10 from X10 Z0, as rs274 printed it: in the
        // XZ plane the first axis is Z, the second X, the third Y.
        let text = "\
    7 N10    SELECT_PLANE(CANON_PLANE_XZ)
   11 N30    ARC_FEED(-10.0000, 20.0000, -10.0000, 10.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)
";
        let calls = parse(text).expect("parses");
        assert_eq!(
            calls,
            [Call {
                line: 2,
                reading: Some(30),
                what: CallKind::Move(Move {
                    kind: MoveKind::Arc { rotation: -1 },
                    end: [20.0, 0.0, -10.0]
                })
            }]
        );
    }

    #[test]
    fn a_line_that_is_no_call_is_an_error_naming_it() {
        let error = parse("   16 N30    STRAIGHT_FEED(1.0, 2.0, 3.0\n").expect_err("no ')'");
        assert_eq!(error.line, 1);
        let error = parse("   16 N30    STRAIGHT_FEED(1.0, x, 3.0)\n").expect_err("no number");
        assert_eq!(error.message, "\"x\" is not a number");
        let error = parse("   16 N30    ARC_FEED(1.0, 2.0, 3.0)\n").expect_err("too few");
        assert_eq!(error.message, "3 arguments, expected at least 6");
    }

    #[test]
    fn a_compensated_move_belongs_to_the_block_before_the_one_it_is_printed_in() {
        let moves = attribute(&parse(SQUARE_G41).expect("parses"));
        let blocks: Vec<_> = moves
            .iter()
            .map(|m| {
                (
                    m.block,
                    m.motion.kind.name(),
                    m.motion.end[0],
                    m.motion.end[1],
                )
            })
            .collect();
        assert_eq!(
            blocks,
            [
                (Some(30), "rapid", 0.0, -20.0),
                (Some(40), "line", 0.0, -20.0),
                // The G41 block's move, printed while N60 was read.
                (Some(50), "line", -3.0, 0.0),
                (Some(60), "line", -3.0, 50.0),
                // The corner arc before N70's line belongs to N70.
                (Some(70), "arc cw", 0.0, 53.0),
                (Some(70), "line", 50.0, 53.0),
                (Some(80), "arc cw", 53.0, 50.0),
                (Some(80), "line", 53.0, 0.0),
                (Some(90), "arc cw", 50.0, -3.0),
                // The last compensated move, printed while G40 was read.
                (Some(90), "line", -0.0, -3.0),
                // After G40 the block's own move.
                (Some(100), "line", -20.0, 0.0),
            ]
        );
    }

    #[test]
    fn without_compensation_a_move_belongs_to_the_block_it_is_printed_in() {
        let text = "\
   20 N60    STRAIGHT_FEED(20.0000, 0.0000, -1.0000, 0.0000, 0.0000, 0.0000)
   21 N70    ARC_FEED(40.0000, 20.0000, 20.0000, 20.0000, 1, -1.0000, 0.0000, 0.0000, 0.0000)
";
        let moves = attribute(&parse(text).expect("parses"));
        let blocks: Vec<_> = moves.iter().map(|m| (m.block, m.motion.end)).collect();
        assert_eq!(
            blocks,
            [
                (Some(60), [20.0, 0.0, -1.0]),
                (Some(70), [40.0, 20.0, -1.0])
            ]
        );
    }

    #[test]
    fn a_block_without_motion_holds_no_move_back() {
        // N65 sets the feed only: N60's move is still the one held back.
        let text = "\
   19 N50    COMMENT(\"interpreter: cutter radius compensation on right\")
   20 N60    STRAIGHT_FEED(0.0000, -3.0000, -1.0000, 0.0000, 0.0000, 0.0000)
   21 N65    SET_FEED_RATE(100.0000)
   22 N70    STRAIGHT_FEED(50.0000, -3.0000, -1.0000, 0.0000, 0.0000, 0.0000)
";
        let moves = attribute(&parse(text).expect("parses"));
        let blocks: Vec<_> = moves.iter().map(|m| m.block).collect();
        assert_eq!(blocks, [Some(50), Some(60)]);
    }

    #[test]
    fn block_numbers_are_the_leading_n_words_by_line() {
        let program = "; a comment\nN10 G17 G21\n  N20 T1 M6\nG0 X1\nN30X5 ; approach\n";
        let numbers = block_numbers(program);
        assert_eq!(
            numbers.into_iter().collect::<Vec<_>>(),
            [(10, 2), (20, 3), (30, 5)]
        );
    }
}
