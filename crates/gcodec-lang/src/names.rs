//! How names are compared: the control ignores case, and the tables hold
//! names in upper case.

use std::cmp::Ordering;

/// Compares an upper-case table name with `key` as if `key` were upper
/// case too, byte by byte (the order the tables are sorted in).
pub(crate) fn compare_ignore_case(upper: &str, key: &str) -> Ordering {
    upper
        .bytes()
        .cmp(key.bytes().map(|b| b.to_ascii_uppercase()))
}
