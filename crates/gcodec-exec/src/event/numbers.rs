//! The number texts the executor's writers share besides
//! `gcodec_ail::write_fixed_point`: the 4-decimal fraction of the text
//! trace, and unsigned integers.

/// `fraction` (0…9999) as 4 decimals without trailing zeros; empty for
/// 0.
pub(super) fn fraction_digits(fraction: u64, buffer: &mut [u8; 4]) -> &str {
    let fraction = fraction % 10_000;
    *buffer = [
        b'0' + (fraction / 1000) as u8,
        b'0' + (fraction / 100 % 10) as u8,
        b'0' + (fraction / 10 % 10) as u8,
        b'0' + (fraction % 10) as u8,
    ];
    let used = 4 - buffer.iter().rev().take_while(|d| **d == b'0').count();
    std::str::from_utf8(&buffer[..used]).unwrap_or("")
}

pub(super) fn write_u64(out: &mut Vec<u8>, value: u64) {
    out.extend_from_slice(itoa::Buffer::new().format(value).as_bytes());
}
