//! `gcodec lower` writes its instructions as they are made, and its
//! output is what lowering the whole program writes: the listing and the
//! JSON of every lowering fixture and example, and of a program long
//! enough for several chunks whose instructions are held from a join in
//! its middle on; the exit code follows the diagnostics.

mod common;

use std::path::Path;

use gcodec_driver::{Definitions, ProgramKind};

use common::*;

/// The listing and the JSON `compile` gives of `name` (its text `bytes`),
/// and whether it has errors.
fn whole(name: &str, bytes: &[u8]) -> (String, String, bool) {
    let profile = gcodec_profile::builtin().expect("built-in profile");
    let kind = ProgramKind::of_file(name);
    let compiled = gcodec_driver::compile_text(name, bytes, kind, &profile, &Definitions::new());
    let mut listing = String::new();
    gcodec_driver::write_listing(&compiled.document, &mut listing).expect("listing");
    let json = serde_json::to_string_pretty(&compiled.document).expect("json") + "\n";
    (listing, json, compiled.has_errors())
}

/// `gcodec lower` of `name` in `dir` writes what `compile` gives.
fn assert_lower_unchanged(dir: &Path, name: &str) {
    let bytes = std::fs::read(dir.join(name)).expect("readable");
    let (listing, json, has_errors) = whole(name, &bytes);
    let exit = if has_errors {
        EXIT_DIAGNOSTICS
    } else {
        EXIT_CLEAN
    };
    let text = gcodec_in(dir, ["lower", name]);
    assert_eq!(code(&text), exit, "{name}: {}", stderr(&text));
    assert!(stdout(&text) == listing, "{name}: the listing differs");
    let data = gcodec_in(dir, ["lower", "--format", "json", name]);
    assert_eq!(code(&data), exit, "{name}: {}", stderr(&data));
    assert!(stdout(&data) == json, "{name}: the JSON differs");
    assert_eq!(
        stderr(&text),
        stderr(&data),
        "{name}: the diagnostics differ"
    );
}

#[test]
fn lower_writes_what_the_whole_program_gives() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut seen = 0;
    for dir in [repo.join("tests/fixtures/lower"), repo.join("examples")] {
        let mut names: Vec<String> = std::fs::read_dir(&dir)
            .expect("fixtures")
            .filter_map(|entry| entry.ok()?.file_name().into_string().ok())
            .filter(|name| {
                let lower = name.to_ascii_lowercase();
                lower.ends_with(".mpf") || lower.ends_with(".spf")
            })
            .collect();
        names.sort();
        for name in names {
            assert_lower_unchanged(&dir, &name);
            seen += 1;
        }
    }
    assert!(seen >= 8, "only {seen} programs");
}

/// Several chunks of 1,024 lines: a straight run, then a label jumped
/// back to, whose motion only the whole program's dataflow completes, so
/// what follows it is held; a lowering error near the end.
#[test]
fn lower_of_a_long_program_with_a_join_is_unchanged() {
    let mut text = String::from("G1 X0 F100\n");
    for i in 0..1_500 {
        text.push_str(&format!("X{} Y{}\n", i % 97, i % 89));
    }
    text.push_str("LOOP:\nX1 Y1\nR1=R1+1\nIF R1<3 GOTOB LOOP\n");
    for i in 0..1_500 {
        text.push_str(&format!("G0 X{} Y{}\n", i % 83, i % 79));
    }
    text.push_str("S4=1000\nM30\n");
    let path = temp_file("lower-streamed", "LONG.MPF", &text);
    let dir = path.parent().expect("a folder");
    assert_lower_unchanged(dir, "LONG.MPF");
    let out = gcodec_in(dir, ["lower", "LONG.MPF"]);
    assert!(
        stderr(&out).contains("gcodec::lower::unknown_spindle"),
        "{}",
        stderr(&out)
    );
}
