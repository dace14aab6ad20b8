//! The codes of area `check`: what `gcodec check` reads besides the
//! programs' code: suppression comments in the programs
//! (`; gcodec: allow(CODE)`) and the baseline file (`--baseline`).

super::codes! {
    "check", "what `gcodec check` reads besides code: suppression comments and the baseline";
    BAD_SUPPRESSION = bad_suppression, Warning, "a `; gcodec: allow(…)` comment that is malformed or names no diagnostic code or area";
    UNUSED_SUPPRESSION = unused_suppression, Warning, "a code or area of a suppression comment that suppressed nothing";
    BAD_BASELINE = bad_baseline, Error, "a baseline file (`--baseline`) that cannot be read as one";
}
