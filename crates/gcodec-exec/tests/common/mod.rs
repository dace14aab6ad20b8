//! Helpers shared by the executor's integration tests: the run set-up and
//! what a golden fixture names. Where the programs are, the shipped
//! profiles and the corpus's machines are `gcodec_testkit`'s.

#![allow(dead_code)]

pub mod golden;
pub mod runs;
pub mod setup;
pub mod tools;
