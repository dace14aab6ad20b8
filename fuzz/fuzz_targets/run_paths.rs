//! The executor's two ways of running a straight motion must agree on
//! arbitrary bytes: the direct path for constant end points in a plain or
//! already traversed frame (`channel/motion.rs`, `direct_straight_motion`)
//! against the general path (`RunOptions::direct_motions` off), each in a
//! streamed run as `gcodec run` goes: the same JSONL, the same CSV rows and
//! events beside them, the same outcome, byte for byte. The check is the
//! tests' (`gcodec_testkit::agreement`, used by
//! `crates/gcodec-exec/tests/direct_motions.rs` on the fixtures, the corpus
//! and generated programs); here it meets inputs none of those has.

#![no_main]

use gcodec_testkit::agreement::assert_direct_motions_agree;
use libfuzzer_sys::fuzz_target;

#[allow(dead_code, reason = "this target shares the profiles only")]
mod running;
use running::run_profiles;

fuzz_target!(|data: &[u8]| {
    for profile in run_profiles() {
        assert_direct_motions_agree("fuzz.mpf", data, profile, 2_000);
    }
});
