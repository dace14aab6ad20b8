//! The profile and run options a golden fixture names on its
//! `; run:` line.

use std::path::Path;
use std::sync::Arc;

use gcodec_exec::channel::RunOptions;

/// The golden fixtures, relative to the repository root: the snapshots
/// show files and searched directories so.
pub const FIXTURES: &str = "tests/fixtures/run";

/// Makes the repository root the current directory, where [`FIXTURES`]
/// is. Every test of a binary that calls it wants the same directory, so
/// tests running in parallel agree.
pub fn at_repo_root() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    std::env::set_current_dir(root).expect("the repository root");
}

pub struct Setup {
    pub profile: Arc<gcodec_profile::Profile>,
    pub options: RunOptions,
}

pub fn setup(path: &Path, text: &str) -> Setup {
    let header = text
        .lines()
        .find_map(|l| l.strip_prefix("; run:"))
        .unwrap_or_else(|| panic!("{} has no `; run:` line", path.display()));
    let mut profile_file = None;
    let mut words = Vec::new();
    for word in header.split_whitespace() {
        match word.split_once('=') {
            Some(("profile", file)) => profile_file = Some(Path::new(FIXTURES).join(file)),
            _ => words.push(word.to_owned()),
        }
    }
    let profile = match profile_file {
        Some(file) => {
            let text = std::fs::read_to_string(&file).expect("profile");
            gcodec_profile::load(&text).expect("a valid profile")
        }
        None => gcodec_profile::builtin().expect("built-in profile"),
    };
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
            _ => panic!("unknown run option `{word}`"),
        }
    }
    Setup {
        profile: Arc::new(profile),
        options,
    }
}
