//! The profile and run options a golden fixture names on its `; run:`
//! line (`; run: profile=mill.toml no-stop skip=1 max-steps=20`).

use gcodec_exec::channel::RunOptions;
use gcodec_testkit::{Fixture, Header};

/// Makes the repository root the current directory: the golden streams
/// show the fixtures' files and the directories searched for their calls
/// relative to it (`tests/fixtures/run/…`). Every test of a binary that
/// calls it wants the same directory, so tests running in parallel agree.
pub fn at_repo_root() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    std::env::set_current_dir(root).expect("the repository root");
}

/// The golden run fixtures, `tests/fixtures/run/*.mpf`, in name order.
pub fn run_fixtures() -> Vec<std::path::PathBuf> {
    let mut fixtures: Vec<std::path::PathBuf> =
        std::fs::read_dir(gcodec_testkit::fixtures::root("run"))
            .expect("fixtures")
            .map(|e| e.expect("entry").path())
            .filter(|p| p.extension().is_some_and(|e| e == "mpf"))
            .collect();
    fixtures.sort();
    fixtures
}

pub struct Setup {
    pub profile: std::sync::Arc<gcodec_profile::Profile>,
    pub options: RunOptions,
}

pub fn setup(fixture: &Fixture) -> Setup {
    let Header {
        profile,
        options: words,
    } = fixture.header();
    let mut options = RunOptions::for_profile(&profile);
    // A fixture that loops by mistake must not write a huge snapshot.
    options.max_steps = 10_000;
    for word in words {
        match word.split_once('=') {
            None if word == "no-stop" => options.stop_at_m0 = false,
            None if word == "optional-stop" => options.optional_stop = true,
            Some(("skip", levels)) => {
                for level in levels.split(',') {
                    options.skip_levels[level.parse::<usize>().expect("level")] = true;
                }
            }
            Some(("max-steps", n)) => options.max_steps = n.parse().expect("number"),
            _ => panic!("{}: unknown run option `{word}`", fixture.relative),
        }
    }
    Setup {
        profile: std::sync::Arc::new(profile),
        options,
    }
}
