//! Deterministic generator of large, realistic SINUMERIK part programs for
//! the parser benchmark and the `parse_file` example.
//!
//! The mix resembles CAM output with some hand-written logic around it:
//! linear moves with block numbers and comments, rapid moves, arcs with
//! `CR=`, R-parameter arithmetic, and `IF … ELSE … ENDIF` and
//! `WHILE … ENDWHILE` structures (nested up to three deep) with conditions.
//! Every generated program parses without diagnostics, and runs: arcs have
//! a radius larger than half of any chord in the coordinate range (so they
//! fit whatever path reached them) and are not written inside loops (a
//! second pass would start at their own end point); each `WHILE` counts
//! its own R parameter (`R41`…`R43`, which nothing else writes) up in its
//! first body line, so every loop ends.
//!
//! No `rand` dependency: a 64-bit LCG (Knuth's MMIX constants) drives all
//! choices, so the same `blocks` always gives the same bytes.

use std::fmt::Write as _;

/// A 64-bit linear congruential generator.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> u32 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 33) as u32
    }

    /// Uniform in `0..n`.
    fn below(&mut self, n: u32) -> u32 {
        self.next() % n
    }

    /// A coordinate with three decimals in `-range..range`.
    fn coord(&mut self, out: &mut String, range: u32) {
        let milli = self.below(range * 2000) as i64 - range as i64 * 1000;
        let sign = if milli < 0 { "-" } else { "" };
        let milli = milli.abs();
        let _ = write!(out, "{sign}{}.{:03}", milli / 1000, milli % 1000);
    }
}

const COMMENTS: &[&str] = &[
    "rough",
    "finish pass",
    "contour",
    "pocket",
    "retract",
    "approach",
    "chamfer",
    "face",
];

/// What kind of structure is open.
#[derive(Clone, Copy, PartialEq)]
enum Open {
    /// `IF`; `true` once its `ELSE` is written.
    If(bool),
    While,
}

/// Generates a program of exactly `blocks` lines, each ending in `\n`.
pub fn generate(blocks: usize) -> Vec<u8> {
    let mut rng = Lcg(0x5EED_CAFE_F00D_0001);
    let mut out = String::with_capacity(blocks * 40);
    // Open structures, each with the number of blocks in its current body.
    let mut stack: Vec<(Open, u32)> = Vec::new();
    let mut n = 0u32;
    // The counter a `WHILE` just opened increments in its first line.
    let mut pending_count = None;
    for line in 0..blocks {
        if let Some(counter) = pending_count.take() {
            let _ = writeln!(out, "R{counter}=R{counter}+1");
            if let Some(top) = stack.last_mut() {
                top.1 += 1;
            }
            continue;
        }
        let remaining = blocks - line;
        // Close everything before the end: each open structure needs a line.
        let must_close = remaining <= stack.len();
        let body_len = stack.last().map_or(0, |&(_, len)| len);
        let roll = rng.below(1000);
        if must_close || (!stack.is_empty() && body_len >= 2 && roll < 60) {
            let (open, _) = stack.pop().expect("a structure is open");
            // Sometimes an ELSE before the ENDIF.
            if open == Open::If(false) && !must_close && rng.below(3) == 0 {
                out.push_str("ELSE\n");
                stack.push((Open::If(true), 0));
                continue;
            }
            out.push_str(match open {
                Open::If(_) => "ENDIF\n",
                Open::While => "ENDWHILE\n",
            });
        } else if stack.len() < 3 && remaining > stack.len() + 4 && roll < 75 {
            let r = rng.below(20) + 1;
            if roll < 45 {
                let _ = match rng.below(3) {
                    0 => writeln!(out, "IF R{r}>{}", rng.below(50)),
                    1 => writeln!(out, "IF (R{r}<=R{}) AND (R{}<>0)", r + 1, r + 2),
                    _ => writeln!(out, "IF R{r}==1"),
                };
                stack.push((Open::If(false), 0));
            } else {
                let counter = 41 + stack.len();
                let _ = writeln!(out, "WHILE R{counter}<{}", rng.below(100) + 1);
                stack.push((Open::While, 0));
                pending_count = Some(counter);
            }
            if let Some(parent) = stack.iter_mut().rev().nth(1) {
                parent.1 += 1;
            }
            continue;
        } else {
            let in_loop = stack.iter().any(|(open, _)| *open == Open::While);
            statement_block(&mut rng, &mut out, &mut n, roll, in_loop);
        }
        if let Some(top) = stack.last_mut() {
            top.1 += 1;
        }
    }
    out.into_bytes()
}

/// One ordinary block: a move, an arc, a rapid or an R-parameter line.
fn statement_block(rng: &mut Lcg, out: &mut String, n: &mut u32, roll: u32, in_loop: bool) {
    let mut kind = rng.below(100);
    if in_loop && (65..=74).contains(&kind) {
        // No arcs in loops: a linear move instead.
        kind = 0;
    }
    // Most blocks carry a block number.
    if kind < 75 {
        *n = (*n + 10) % 100_000;
        let _ = write!(out, "N{} ", *n);
    }
    match kind {
        // Linear move, sometimes without Z or F.
        0..=54 => {
            out.push_str("G1 X");
            rng.coord(out, 200);
            out.push_str(" Y");
            rng.coord(out, 200);
            if !roll.is_multiple_of(3) {
                out.push_str(" Z");
                rng.coord(out, 20);
            }
            if rng.below(3) == 0 {
                let _ = write!(out, " F{}", 100 * (rng.below(30) + 1));
            }
        }
        // Rapid.
        55..=64 => {
            out.push_str("G0 X");
            rng.coord(out, 300);
            out.push_str(" Y");
            rng.coord(out, 300);
            out.push_str(" Z");
            rng.coord(out, 50);
        }
        // Arc by radius.
        65..=74 => {
            out.push_str(if roll.is_multiple_of(2) {
                "G2 X"
            } else {
                "G3 X"
            });
            rng.coord(out, 200);
            out.push_str(" Y");
            rng.coord(out, 200);
            // Coordinates lie within ±300, so no chord is longer than
            // 849 mm: a radius of at least 425 mm always fits.
            let _ = write!(out, " CR={}.{:03}0", 430 + rng.below(50), rng.below(1000));
        }
        // R-parameter arithmetic.
        75..=92 => {
            let r = rng.below(20) + 1;
            let _ = match rng.below(4) {
                0 => write!(out, "R{r}=R{r}+0.5"),
                1 => write!(out, "R{r}=R{}*2-1.25", rng.below(20) + 1),
                2 => write!(out, "R{r}=R{r}+1"),
                _ => write!(
                    out,
                    "R{r}=(R{}+R{})/2",
                    rng.below(20) + 1,
                    rng.below(20) + 1
                ),
            };
        }
        // Machine functions.
        _ => {
            let _ = match rng.below(3) {
                0 => write!(out, "M3 S{}", 1000 + rng.below(5000)),
                1 => write!(out, "M8"),
                _ => write!(out, "G90 G17 G54"),
            };
        }
    }
    if roll.is_multiple_of(2) {
        out.push_str(" ; ");
        out.push_str(COMMENTS[rng.below(COMMENTS.len() as u32) as usize]);
    }
    out.push('\n');
}
