//! Helpers of the parser's integration tests: what every parse must
//! satisfy. Where the programs are is `gcodec_testkit`'s.

pub mod invariants;
