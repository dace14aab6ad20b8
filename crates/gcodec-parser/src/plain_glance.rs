//! A line of a flood (`G1 X100.037 Y200.053 F1000`) judged plain sixteen
//! bytes at a time, for pass 1's skim: the byte-by-byte test
//! ([`crate::driver::is_plain`]) was half of the skim's work.
//!
//! [`plain_at_a_glance`] says yes only where the exact test would: every
//! byte a digit, a letter, a blank (`' '`), `.`, `-`, `+` or `=`; no two
//! letters touching (a name or keyword); no `M` (an M function); every
//! point touching a digit. Anything else — a tab, a comment, `_`, a
//! byte beyond ASCII, a name — is left to the exact test, which decides.

/// Whether `line` is certainly plain; `false` says nothing.
pub(crate) fn plain_at_a_glance(line: &[u8]) -> bool {
    let mut at = 0;
    // Whether the byte before the block is a letter or a digit.
    let (mut letter_before, mut digit_before) = (false, false);
    while at < line.len() {
        let end = (at + LANES).min(line.len());
        // A short last block is padded with blanks, which pass.
        let mut block = [b' '; LANES];
        block[..end - at].copy_from_slice(&line[at..end]);
        let Some(classes) = classify(&block) else {
            return false;
        };
        let Classes {
            letters,
            digits,
            points,
        } = classes;
        if letters & (letters >> 1) != 0 || (letter_before && letters & 1 != 0) {
            return false;
        }
        // Each point needs a digit before or after it; the byte after
        // the block's last is not known here: that point must have one
        // before.
        let before = (digits << 1) | u32::from(digit_before);
        let after = digits >> 1;
        if points & !(before | after) != 0 {
            return false;
        }
        letter_before = letters & LAST != 0;
        digit_before = digits & LAST != 0;
        at = end;
    }
    true
}

const LANES: usize = 16;
const LAST: u32 = 1 << (LANES - 1);

/// One bit a byte of a block, bit `i` for byte `i`.
struct Classes {
    letters: u32,
    digits: u32,
    points: u32,
}

/// The classes of `block`'s bytes; `None` if a byte is none of those a
/// glance accepts, or an `M`.
#[cfg(target_arch = "x86_64")]
fn classify(block: &[u8; LANES]) -> Option<Classes> {
    use std::arch::x86_64::{
        __m128i, _mm_and_si128, _mm_cmpeq_epi8, _mm_cmpgt_epi8, _mm_cmplt_epi8, _mm_loadu_si128,
        _mm_movemask_epi8, _mm_or_si128, _mm_set1_epi8,
    };
    // SAFETY: SSE2 is part of every x86_64 target; the load reads the
    // sixteen bytes of `block`, unaligned loads allowed.
    unsafe {
        let v = _mm_loadu_si128(block.as_ptr().cast::<__m128i>());
        // Bytes beyond ASCII are negative as `i8`: none of the ranges
        // below holds them, so they fail `allowed`.
        let splat = |b: u8| _mm_set1_epi8(b as i8);
        let within = |x: __m128i, low: u8, high: u8| {
            _mm_and_si128(
                _mm_cmpgt_epi8(x, splat(low - 1)),
                _mm_cmplt_epi8(x, splat(high + 1)),
            )
        };
        let digit = within(v, b'0', b'9');
        // `b | 0x20` is a lower-case letter exactly for the letters.
        let folded = _mm_or_si128(v, splat(0x20));
        let letter = within(folded, b'a', b'z');
        let m = _mm_cmpeq_epi8(folded, splat(b'm'));
        let point = _mm_cmpeq_epi8(v, splat(b'.'));
        let other = [b' ', b'-', b'+', b'='].into_iter().fold(point, |acc, b| {
            _mm_or_si128(acc, _mm_cmpeq_epi8(v, splat(b)))
        });
        let allowed = _mm_or_si128(_mm_or_si128(digit, letter), other);
        let bits = |x: __m128i| _mm_movemask_epi8(x) as u32;
        (bits(allowed) == 0xFFFF && bits(m) == 0).then(|| Classes {
            letters: bits(letter),
            digits: bits(digit),
            points: bits(point),
        })
    }
}

/// [`classify`] a byte at a time, where SSE2 is not there.
#[cfg(not(target_arch = "x86_64"))]
fn classify(block: &[u8; LANES]) -> Option<Classes> {
    let mut classes = Classes {
        letters: 0,
        digits: 0,
        points: 0,
    };
    for (i, &b) in block.iter().enumerate() {
        let bit = 1 << i;
        match b {
            b'0'..=b'9' => classes.digits |= bit,
            b'M' | b'm' => return None,
            b'A'..=b'Z' | b'a'..=b'z' => classes.letters |= bit,
            b'.' => classes.points |= bit,
            b' ' | b'-' | b'+' | b'=' => {}
            _ => return None,
        }
    }
    Some(classes)
}

#[cfg(test)]
mod tests {
    use super::plain_at_a_glance;
    use crate::driver::is_plain;

    /// The bytes generated lines are made of: what a glance accepts, and
    /// what it must leave to the exact test.
    const BYTES: &[u8] = b"0123456789GXYZFNAIJKgxyzMm .-+=_;:\t\"$'(*/,\xC3\xA9ENDIF";

    /// A glance never says yes where the exact test says no, over lines
    /// of every length up to three blocks, made of those bytes.
    #[test]
    fn a_glance_says_plain_only_where_the_exact_test_does() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut next = |n: usize| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % n as u64) as usize
        };
        let mut glanced = 0;
        for _ in 0..200_000 {
            let len = next(49);
            let line: Vec<u8> = (0..len).map(|_| BYTES[next(BYTES.len())]).collect();
            if plain_at_a_glance(&line) {
                glanced += 1;
                assert!(is_plain(&line), "{:?}", String::from_utf8_lossy(&line));
            }
        }
        assert!(glanced > 1_000, "only {glanced} lines taken at a glance");
    }

    /// The lines of a flood are taken at a glance, points and signs at
    /// every place of a block included; near misses are not.
    #[test]
    fn flood_lines_are_plain_at_a_glance() {
        for line in [
            "G1 X100.037 Y200.053 F1000",
            "N10 G1 X100.000 Y200.000 Z10.000 F1000",
            "G0X-1.5Y+.5Z2.",
            "R1=2.5",
            "",
            "              5.",
            "123456789012345.6",
            "G1 X1 Y2 Z3 A4 B5 C6 U7 V8 W9 X10.5 Y11.5 Z12.5",
        ] {
            assert!(plain_at_a_glance(line.as_bytes()), "{line:?}");
            assert!(is_plain(line.as_bytes()), "{line:?}");
        }
        for line in [
            "G1 X1 M3",
            "G1 X. Y1",
            "GOTOF END",
            "G1 X1 ; comment",
            "G1\tX1",
            "G1 X1\r",
            "DEF REAL A",
            "               .X",
            "X1 Y_2",
        ] {
            assert!(!plain_at_a_glance(line.as_bytes()), "{line:?}");
        }
        // A point last in a block with its digit in the next: plain, but
        // the glance does not look ahead.
        let line = b"               .5";
        assert!(!plain_at_a_glance(line) && is_plain(line));
    }
}
