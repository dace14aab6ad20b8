//! Lines of a flood (`G1 X100.037 Y200.053 F1000`) judged plain sixteen
//! bytes at a time, for pass 1's skim: the byte-by-byte test
//! ([`crate::driver::is_plain`]) was half of the skim's work. A run of a
//! chunk's lines is judged in one pass that finds their line ends too,
//! rather than line by line after a search for each line's end.
//!
//! [`plain_at_a_glance`] (one line) and [`plain_lines`] (the lines of a
//! run of text) say yes only where the exact test would: every byte a
//! digit, a letter, a blank (`' '`, a tab, a carriage return), `.`, `-`,
//! `+` or `=`; no two letters touching (a name or keyword); no `M` (an M
//! function); every point touching a digit. Anything else — a comment,
//! `_`, a byte beyond ASCII, a name — is left to the exact test, which
//! decides.

/// Whether `line` (without its line end) is certainly plain; `false`
/// says nothing. The tests' measure of [`plain_lines`].
#[cfg(test)]
fn plain_at_a_glance(line: &[u8]) -> bool {
    let mut glance = Glance::default();
    let mut at = 0;
    while at < line.len() {
        let end = (at + LANES).min(line.len());
        // A line holds no line end.
        if glance.step::<LANES>(classify(&padded(&line[at..end]))) != Some(0) {
            return false;
        }
        at = end;
    }
    true
}

/// How many bytes at the start of `text` are whole lines that are each
/// certainly plain: the lines before the first that may not be, each with
/// its line end (`\n`; the last line of `text` may have none). The offset
/// of each of their line ends is pushed to `line_ends`. Pass 1 judges a
/// run of a chunk's lines at once this way, rather than finding each
/// line's end and glancing at it alone. Thirty-two bytes at a time where
/// the processor has AVX2.
pub(crate) fn plain_lines(text: &[u8], line_ends: &mut Vec<u32>) -> usize {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2, as just asked.
        return unsafe { wide::plain_lines(text, line_ends) };
    }
    plain_lines_by::<LANES>(text, line_ends, classify)
}

/// [`plain_lines`] by blocks of `N` bytes that `classify` reads.
#[inline(always)]
fn plain_lines_by<const N: usize>(
    text: &[u8],
    line_ends: &mut Vec<u32>,
    classify: impl Fn(&[u8; N]) -> Option<Classes>,
) -> usize {
    let mut glance = Glance::default();
    // Where the line holding the next block's first byte starts.
    let mut line_start = 0;
    let mut at = 0;
    while at < text.len() {
        let end = (at + N).min(text.len());
        let bytes = &text[at..end];
        let classes = match bytes.try_into() {
            Ok(full) => classify(full),
            Err(_) => classify(&padded(bytes)),
        };
        let Some(mut newlines) = glance.step::<N>(classes) else {
            // The lines that end in this block are left to the exact
            // test too: which byte failed is not known.
            return line_start;
        };
        while newlines != 0 {
            let newline = at + newlines.trailing_zeros() as usize;
            line_ends.push(newline as u32);
            line_start = newline + 1;
            newlines &= newlines - 1;
        }
        at = end;
    }
    text.len()
}

/// The bytes of a short last block, padded with blanks, which pass.
#[inline(always)]
fn padded<const N: usize>(bytes: &[u8]) -> [u8; N] {
    let mut block = [b' '; N];
    block[..bytes.len()].copy_from_slice(bytes);
    block
}

/// A glance along text, block by block.
#[derive(Default)]
struct Glance {
    /// Whether the byte before the next block is a letter.
    letter_before: bool,
    /// Whether the byte before the next block is a digit.
    digit_before: bool,
}

impl Glance {
    /// Takes in the next block of `N` bytes, classified (`None`: a byte
    /// no glance accepts): the bits of its line ends (`\n`), or `None` if
    /// it may not be plain.
    #[inline(always)]
    fn step<const N: usize>(&mut self, classes: Option<Classes>) -> Option<u32> {
        let Classes {
            letters,
            digits,
            points,
            newlines,
        } = classes?;
        let last = 1u32 << (N - 1);
        if letters & (letters >> 1) != 0 || (self.letter_before && letters & 1 != 0) {
            return None;
        }
        // Each point needs a digit before or after it; the byte after
        // the block's last is not known here: that point must have one
        // before.
        let before = (digits << 1) | u32::from(self.digit_before);
        let after = digits >> 1;
        if points & !(before | after) != 0 {
            return None;
        }
        self.letter_before = letters & last != 0;
        self.digit_before = digits & last != 0;
        Some(newlines)
    }
}

/// The bytes of a block everywhere.
const LANES: usize = 16;

/// One bit a byte of a block of at most 32, bit `i` for byte `i`.
struct Classes {
    letters: u32,
    digits: u32,
    points: u32,
    newlines: u32,
}

/// The classes of the bytes of the vector `$v` (of type `$vector`, its
/// lanes read with the intrinsics named after it): SSE2's sixteen and
/// AVX2's thirty-two lanes are classified alike.
#[cfg(target_arch = "x86_64")]
macro_rules! classify_vector {
    ($v:expr, $vector:ty, $set1:ident, $and:ident, $or:ident, $cmpeq:ident, $cmpgt:ident,
     $movemask:ident, $all:expr) => {{
        let v = $v;
        // Bytes beyond ASCII are negative as `i8`: none of the ranges
        // below holds them, so they fail `allowed`.
        let splat = |b: u8| $set1(b as i8);
        let within = |x: $vector, low: u8, high: u8| {
            $and($cmpgt(x, splat(low - 1)), $cmpgt(splat(high + 1), x))
        };
        let digit = within(v, b'0', b'9');
        // `b | 0x20` is a lower-case letter exactly for the letters.
        let folded = $or(v, splat(0x20));
        let letter = within(folded, b'a', b'z');
        let m = $cmpeq(folded, splat(b'm'));
        let point = $cmpeq(v, splat(b'.'));
        let newline = $cmpeq(v, splat(b'\n'));
        let other = [b' ', b'\t', b'\r', b'-', b'+', b'=']
            .into_iter()
            .fold($or(point, newline), |acc, b| $or(acc, $cmpeq(v, splat(b))));
        let allowed = $or($or(digit, letter), other);
        let bits = |x: $vector| $movemask(x) as u32;
        (bits(allowed) == $all && bits(m) == 0).then(|| Classes {
            letters: bits(letter),
            digits: bits(digit),
            points: bits(point),
            newlines: bits(newline),
        })
    }};
}

/// The classes of `block`'s bytes; `None` if a byte is none of those a
/// glance accepts (a line end among them), or an `M`.
#[cfg(target_arch = "x86_64")]
fn classify(block: &[u8; LANES]) -> Option<Classes> {
    use std::arch::x86_64::{
        __m128i, _mm_and_si128, _mm_cmpeq_epi8, _mm_cmpgt_epi8, _mm_loadu_si128, _mm_movemask_epi8,
        _mm_or_si128, _mm_set1_epi8,
    };
    // SAFETY: SSE2 is part of every x86_64 target; the load reads the
    // sixteen bytes of `block`, unaligned loads allowed.
    unsafe {
        let v = _mm_loadu_si128(block.as_ptr().cast::<__m128i>());
        classify_vector!(
            v,
            __m128i,
            _mm_set1_epi8,
            _mm_and_si128,
            _mm_or_si128,
            _mm_cmpeq_epi8,
            _mm_cmpgt_epi8,
            _mm_movemask_epi8,
            0xFFFF
        )
    }
}

/// The glance thirty-two bytes at a time, with AVX2.
#[cfg(target_arch = "x86_64")]
mod wide {
    use std::arch::x86_64::{
        __m256i, _mm256_and_si256, _mm256_cmpeq_epi8, _mm256_cmpgt_epi8, _mm256_loadu_si256,
        _mm256_movemask_epi8, _mm256_or_si256, _mm256_set1_epi8,
    };

    use super::{Classes, plain_lines_by};

    /// [`super::plain_lines`] with AVX2, which the caller has made sure
    /// of.
    #[target_feature(enable = "avx2")]
    pub(super) fn plain_lines(text: &[u8], line_ends: &mut Vec<u32>) -> usize {
        // The closure has this function's target feature.
        plain_lines_by::<32>(text, line_ends, |block| classify(block))
    }

    /// [`super::classify`] of thirty-two bytes.
    #[target_feature(enable = "avx2")]
    #[inline]
    fn classify(block: &[u8; 32]) -> Option<Classes> {
        // SAFETY: the load reads the thirty-two bytes of `block`,
        // unaligned loads allowed.
        let v = unsafe { _mm256_loadu_si256(block.as_ptr().cast::<__m256i>()) };
        classify_vector!(
            v,
            __m256i,
            _mm256_set1_epi8,
            _mm256_and_si256,
            _mm256_or_si256,
            _mm256_cmpeq_epi8,
            _mm256_cmpgt_epi8,
            _mm256_movemask_epi8,
            u32::MAX
        )
    }
}

/// [`classify`] a byte at a time, where SSE2 is not there.
#[cfg(not(target_arch = "x86_64"))]
fn classify(block: &[u8; LANES]) -> Option<Classes> {
    let mut classes = Classes {
        letters: 0,
        digits: 0,
        points: 0,
        newlines: 0,
    };
    for (i, &b) in block.iter().enumerate() {
        let bit = 1 << i;
        match b {
            b'0'..=b'9' => classes.digits |= bit,
            b'M' | b'm' => return None,
            b'A'..=b'Z' | b'a'..=b'z' => classes.letters |= bit,
            b'.' => classes.points |= bit,
            b'\n' => classes.newlines |= bit,
            b' ' | b'\t' | b'\r' | b'-' | b'+' | b'=' => {}
            _ => return None,
        }
    }
    Some(classes)
}

#[cfg(test)]
mod tests {
    use super::{LANES, classify, plain_at_a_glance, plain_lines, plain_lines_by};
    use crate::driver::is_plain;

    /// The bytes generated lines are made of: what a glance accepts, and
    /// what it must leave to the exact test.
    const BYTES: &[u8] = b"0123456789GXYZFNAIJKgxyzMm .-+=_;:\t\r\"$'(*/,\xC3\xA9ENDIF";

    /// A deterministic generator of numbers below `n`.
    fn numbers() -> impl FnMut(usize) -> usize {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        move |n: usize| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % n as u64) as usize
        }
    }

    /// A line of up to `max` bytes of [`BYTES`], mostly flood bytes.
    fn line(next: &mut impl FnMut(usize) -> usize, max: usize) -> Vec<u8> {
        let len = next(max + 1);
        // Most lines of few kinds of byte, so that runs of plain lines
        // are common.
        let kinds = if next(4) == 0 { BYTES.len() } else { 26 };
        (0..len).map(|_| BYTES[next(kinds)]).collect()
    }

    /// A glance never says yes where the exact test says no, over lines
    /// of every length up to three blocks, made of those bytes.
    #[test]
    fn a_glance_says_plain_only_where_the_exact_test_does() {
        let mut next = numbers();
        let mut glanced = 0;
        for _ in 0..200_000 {
            let line = line(&mut next, 48);
            if plain_at_a_glance(&line) {
                glanced += 1;
                assert!(is_plain(&line), "{:?}", String::from_utf8_lossy(&line));
            }
        }
        assert!(glanced > 10_000, "only {glanced} lines taken at a glance");
    }

    /// The plain lines of a text end at a line's start, and every line
    /// before it is plain by the exact test; a text of lines each plain at
    /// a glance is plain to its end.
    #[test]
    fn plain_lines_are_whole_lines_the_exact_test_takes() {
        let mut next = numbers();
        let (mut texts_to_the_end, mut lines_taken) = (0, 0);
        for _ in 0..20_000 {
            let lines: Vec<Vec<u8>> = (0..next(8)).map(|_| line(&mut next, 40)).collect();
            let mut text = lines.join(&b'\n');
            if next(2) == 0 {
                text.push(b'\n');
            }
            let mut wide_ends = Vec::new();
            let wide = plain_lines(&text, &mut wide_ends);
            // Sixteen bytes at a time too, where the processor takes
            // thirty-two.
            let mut narrow_ends = Vec::new();
            let narrow = plain_lines_by::<LANES>(&text, &mut narrow_ends, classify);
            for (plain, line_ends) in [(wide, wide_ends), (narrow, narrow_ends)] {
                assert!(plain <= text.len());
                assert!(plain == 0 || text[plain - 1] == b'\n' || plain == text.len());
                let newlines: Vec<u32> = (0..plain)
                    .filter(|&i| text[i] == b'\n')
                    .map(|i| i as u32)
                    .collect();
                assert_eq!(line_ends, newlines);
                for taken in text[..plain].split(|&b| b == b'\n') {
                    assert!(is_plain(taken), "{:?}", String::from_utf8_lossy(taken));
                    lines_taken += 1;
                }
                // A point may end a block, where whether a digit follows
                // is not seen: without points, lines each plain at a
                // glance are plain at a glance together.
                if lines
                    .iter()
                    .all(|line| plain_at_a_glance(line) && !line.contains(&b'.'))
                {
                    assert_eq!(plain, text.len(), "{:?}", String::from_utf8_lossy(&text));
                    texts_to_the_end += 1;
                }
            }
        }
        assert!(
            texts_to_the_end > 1_000,
            "only {texts_to_the_end} whole texts"
        );
        assert!(lines_taken > 20_000, "only {lines_taken} lines taken");
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
            "G1\tX1",
            "G1 X1\r",
        ] {
            assert!(plain_at_a_glance(line.as_bytes()), "{line:?}");
            assert!(is_plain(line.as_bytes()), "{line:?}");
        }
        for line in [
            "G1 X1 M3",
            "G1 X. Y1",
            "GOTOF END",
            "G1 X1 ; comment",
            "G1 X1\n",
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
