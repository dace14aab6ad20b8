//! Program files in a legacy code page (SPEC §1): UTF-8 where a file is
//! valid UTF-8, else the profile's `[program] code_page`, unless
//! `--encoding` names one for every file; spans stay byte offsets into
//! the file as stored.

use std::path::Path;
use std::process::Output;

use serde_json::Value;

mod common;

use common::{EXIT_CLEAN, EXIT_USAGE, code, gcodec, stderr, stdout, temp_file};

/// `; Привет` and `MSG("При")` in Windows-1251, as a Russian machine
/// stores them.
const CYRILLIC: &[u8] = b"; \xcf\xf0\xe8\xe2\xe5\xf2\nMSG(\"\xcf\xf0\xe8\")\nM30\n";

fn cyrillic_program(test: &str) -> std::path::PathBuf {
    let path = temp_file(test, "CYR.MPF", "");
    std::fs::write(&path, CYRILLIC).expect("write");
    path
}

/// The built-in profile with `[program] code_page` set.
fn profile_with_code_page(test: &str, code_page: &str) -> std::path::PathBuf {
    let builtin = gcodec_profile::BUILTIN_TOML.replace(
        "[program]\n",
        &format!("[program]\ncode_page = \"{code_page}\"\n"),
    );
    assert!(
        builtin.contains("code_page"),
        "the built-in profile has a [program] table"
    );
    temp_file(test, "machine.toml", &builtin)
}

/// `gcodec run PROGRAM --profile PROFILE --format text`.
fn run_text(program: &Path, profile: &Path) -> Output {
    gcodec([
        "run".as_ref(),
        program.as_os_str(),
        "--profile".as_ref(),
        profile.as_os_str(),
        "--format".as_ref(),
        "text".as_ref(),
    ])
}

fn parse_json(args: &[&str]) -> Value {
    let out = gcodec(args);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    serde_json::from_str(&stdout(&out)).expect("JSON")
}

#[test]
fn encoding_names_the_code_page_and_spans_stay_byte_offsets() {
    let path = cyrillic_program("named");
    let path = path.to_str().expect("a UTF-8 path");
    let as_stored = parse_json(&["parse", path, "--format", "json"]);
    let comment = &as_stored["blocks"][0]["comment"];
    assert_eq!(comment["text"], " \u{cf}\u{f0}\u{e8}\u{e2}\u{e5}\u{f2}");
    let named = parse_json(&[
        "parse",
        path,
        "--format",
        "json",
        "--encoding",
        "windows-1251",
    ]);
    let comment = &named["blocks"][0]["comment"];
    assert_eq!(comment["text"], " Привет");
    // Eight bytes in the file, whatever they decode to.
    assert_eq!(comment["span"]["end"].as_u64(), Some(8), "{comment}");
}

#[test]
fn the_profiles_code_page_decodes_what_is_not_utf8() {
    let path = cyrillic_program("code_page");
    let profile = profile_with_code_page("code_page", "windows-1251");
    let out = run_text(&path, &profile);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    assert!(stdout(&out).contains("message \"При\""), "{}", stdout(&out));
    // A valid UTF-8 file stays UTF-8 on that machine.
    let utf8 = temp_file("code_page", "UTF8.MPF", "MSG(\"Grüße\")\nM30\n");
    let out = run_text(&utf8, &profile);
    assert!(
        stdout(&out).contains("message \"Grüße\""),
        "{}",
        stdout(&out)
    );
}

#[test]
fn an_unknown_encoding_is_a_usage_error_and_an_unknown_code_page_a_profile_error() {
    let path = cyrillic_program("unknown");
    let out = gcodec([
        "lower".as_ref(),
        path.as_os_str(),
        "--encoding".as_ref(),
        "utf-16".as_ref(),
    ]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(stderr(&out).contains("windows-1251"), "{}", stderr(&out));
    let profile = profile_with_code_page("unknown", "klingon");
    let out = gcodec(["profile".as_ref(), "check".as_ref(), profile.as_os_str()]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(
        stderr(&out).contains("gcodec::profile::out_of_range"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_called_program_is_decoded_as_the_profile_says() {
    let main = temp_file("called", "MAIN.MPF", "SUBCYR\nM30\n");
    let sub = main.with_file_name("SUBCYR.SPF");
    std::fs::write(&sub, b"MSG(\"\xcf\xf0\xe8\")\nM17\n").expect("write");
    let profile = profile_with_code_page("called", "windows-1251");
    let out = run_text(&main, &profile);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    assert!(stdout(&out).contains("message \"При\""), "{}", stdout(&out));
}
