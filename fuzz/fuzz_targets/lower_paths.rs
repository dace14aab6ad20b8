//! The three ways a program is lowered must agree on arbitrary bytes:
//! the direct path for blocks of constant words (`G1 X… Y… F…`) against
//! the general path, and a streamed run's lowering (outlined chunk by
//! chunk, then lowered chunk by chunk, lines of constant words read
//! without their block, filled in from the dataflow) against lowering the
//! whole program. The checks are the tests' (`gcodec_testkit::agreement`,
//! used by `crates/gcodec-sema/tests/constant_words.rs` and `stream.rs` on
//! the fixtures, the corpus and generated programs); here they meet
//! inputs none of those has.

#![no_main]

use gcodec_testkit::agreement::{assert_direct_lowering_agrees, assert_streamed_lowering_agrees};
use libfuzzer_sys::fuzz_target;

mod shipped;
use shipped::shipped_profiles;

fuzz_target!(|data: &[u8]| {
    for profile in shipped_profiles() {
        assert_direct_lowering_agrees("fuzz.mpf", data, profile);
        // Every line its own chunk, and chunks of three on this thread and
        // on two workers taking turns.
        assert_streamed_lowering_agrees("fuzz.mpf", data, profile, &[1], &[1]);
        assert_streamed_lowering_agrees("fuzz.mpf", data, profile, &[3], &[1, 2]);
    }
});
