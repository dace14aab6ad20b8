//! End-to-end tests of the `gcodec` binary: exit codes, output formats and
//! diagnostics, run on the parse fixtures in `tests/fixtures/parse/`.

use std::path::PathBuf;
use std::process::Output;

use serde_json::Value;

mod common;

use common::{EXIT_CLEAN, EXIT_DIAGNOSTICS, EXIT_USAGE, code, gcodec, stderr, stdout, temp_file};

fn fixture(relative: &str) -> PathBuf {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/fixtures/parse")
        .join(relative);
    assert!(path.is_file(), "missing fixture {}", path.display());
    path
}

/// `gcodec parse --format json FILES...`.
fn parse_json(files: &[&PathBuf]) -> Output {
    let mut args: Vec<&std::ffi::OsStr> =
        vec!["parse".as_ref(), "--format".as_ref(), "json".as_ref()];
    args.extend(files.iter().map(|f| f.as_os_str()));
    gcodec(args)
}

/// A failure must be a message, not a crash.
fn assert_no_panic(out: &Output) {
    let err = stderr(out);
    assert!(!err.contains("panicked"), "gcodec panicked:\n{err}");
    assert!(
        !err.contains("stack backtrace"),
        "backtrace on stderr:\n{err}"
    );
    assert!(
        !err.contains("RUST_BACKTRACE"),
        "panic hint on stderr:\n{err}"
    );
}

fn json(out: &Output) -> Value {
    serde_json::from_str(&stdout(out)).expect("stdout is JSON")
}

fn assert_span(span: &Value) {
    for key in ["start", "end", "line", "col"] {
        assert!(span[key].is_u64(), "span without `{key}`: {span}");
    }
    assert!(
        span["line"].as_u64() >= Some(1),
        "lines are 1-based: {span}"
    );
    assert!(
        span["col"].as_u64() >= Some(1),
        "columns are 1-based: {span}"
    );
}

#[test]
fn clean_file_text_tree_exits_0() {
    let path = fixture("frames.mpf");
    let out = gcodec(["parse".as_ref(), path.as_os_str()]);
    assert_eq!(code(&out), EXIT_CLEAN, "stderr:\n{}", stderr(&out));
    assert_eq!(stderr(&out), "", "no diagnostics for a clean file");
    let text = stdout(&out);
    assert!(text.contains("TRANS X10 Y5"), "tree:\n{text}");
    assert!(text.contains("N120 M30"), "tree:\n{text}");
}

#[test]
fn clean_file_json_has_blocks_with_spans() {
    let path = fixture("words_and_addresses.mpf");
    let out = parse_json(&[&path]);
    assert_eq!(code(&out), EXIT_CLEAN, "stderr:\n{}", stderr(&out));
    assert_eq!(stderr(&out), "");
    let program = json(&out);
    assert!(program.is_object(), "one file gives one program object");
    assert!(
        program["file"]
            .as_str()
            .is_some_and(|f| f.ends_with("words_and_addresses.mpf")),
        "file name: {}",
        program["file"]
    );
    let blocks = program["blocks"].as_array().expect("`blocks` array");
    let source = std::fs::read_to_string(&path).expect("fixture");
    assert_eq!(blocks.len(), source.lines().count(), "one block per line");

    // Line 3: `N20 S1200 M3 F250 H2`.
    let block = &blocks[2];
    assert_span(&block["span"]);
    assert_eq!(block["span"]["line"], 3);
    assert_eq!(block["span"]["col"], 1);
    assert_eq!(block["number"]["value"], 20);
    let statements = block["statements"].as_array().expect("statements");
    assert_eq!(statements.len(), 4);
    let m3 = &statements[1];
    assert_eq!(m3["kind"], "word");
    assert_eq!(m3["address"], "M");
    assert_eq!(m3["value"]["value"], 3.0);
    assert_span(&m3["span"]);
    assert_eq!(m3["span"]["line"], 3);
    assert_eq!(m3["span"]["col"], 11);
}

#[test]
fn bad_file_exits_1_with_rendered_diagnostic() {
    let path = fixture("errors/word_blank_after_address.mpf");
    let out = gcodec(["parse".as_ref(), path.as_os_str()]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS, "stderr:\n{}", stderr(&out));
    assert_no_panic(&out);
    let err = stderr(&out);
    assert!(
        err.contains("gcodec::parse::invalid_word"),
        "stderr:\n{err}"
    );
    assert!(
        err.contains("blank between address `M` and its value"),
        "stderr:\n{err}"
    );
    // The report points into the file: name, line and column, source line.
    assert!(
        err.contains("word_blank_after_address.mpf:1:5"),
        "stderr:\n{err}"
    );
    assert!(err.contains("N10 M 5"), "stderr:\n{err}");
    // Not a terminal: no colour escapes.
    assert!(
        !err.contains('\u{1b}'),
        "ANSI escapes in piped stderr:\n{err}"
    );
}

#[test]
fn bad_file_json_still_prints_the_program() {
    let path = fixture("errors/several_errors.mpf");
    let out = parse_json(&[&path]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS, "stderr:\n{}", stderr(&out));
    assert_no_panic(&out);
    let err = stderr(&out);
    for code in [
        "gcodec::parse::invalid_word",
        "gcodec::parse::invalid_number",
        "gcodec::parse::invalid_character",
        "gcodec::parse::missing_jump_target",
        "gcodec::parse::unmatched_end",
    ] {
        assert!(err.contains(code), "`{code}` missing from stderr:\n{err}");
    }
    let program = json(&out);
    assert_eq!(program["blocks"].as_array().map(Vec::len), Some(10));
}

#[test]
fn unclosed_structure_exits_1() {
    let path = fixture("errors/unclosed_if.mpf");
    let out = gcodec(["parse".as_ref(), path.as_os_str()]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    assert!(stderr(&out).contains("gcodec::parse::unclosed_structure"));
}

/// 150 unclosed `IF`s and one warning for nesting past 16: the first 100
/// diagnostics are rendered, the other 51 counted; `--max-diagnostics 0`
/// renders all. The exit code counts them all.
#[test]
fn diagnostics_beyond_the_limit_are_counted_not_rendered() {
    let path = temp_file(
        "limit",
        "unclosed.mpf",
        &("IF R1==1\n".repeat(150) + "M30\n"),
    );
    let rendered = |out: &Output| stderr(out).matches("is never closed").count();

    let out = gcodec(["parse".as_ref(), path.as_os_str()]);
    assert_no_panic(&out);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    assert_eq!(rendered(&out), 99);
    assert!(stderr(&out).contains("gcodec::parse::deep_nesting"));
    assert!(
        stderr(&out).contains("… and 51 more diagnostics not shown (51 errors, 0 others)"),
        "{}",
        stderr(&out)
    );

    let out = gcodec([
        "parse".as_ref(),
        "--max-diagnostics".as_ref(),
        "0".as_ref(),
        path.as_os_str(),
    ]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    assert_eq!(rendered(&out), 150);
    assert!(!stderr(&out).contains("not shown"));
}

#[test]
fn missing_file_exits_2_with_a_message() {
    let path = fixture("frames.mpf").with_file_name("does_not_exist.mpf");
    let out = gcodec(["parse".as_ref(), path.as_os_str()]);
    assert_eq!(code(&out), EXIT_USAGE, "stderr:\n{}", stderr(&out));
    assert_no_panic(&out);
    let err = stderr(&out);
    assert!(err.contains("gcodec::io::read"), "stderr:\n{err}");
    assert!(err.contains("cannot read"), "stderr:\n{err}");
    assert!(err.contains("does_not_exist.mpf"), "stderr:\n{err}");
    assert_eq!(stdout(&out), "");
}

#[test]
fn missing_file_among_good_ones_exits_2_and_parses_the_rest() {
    let good = fixture("frames.mpf");
    let missing = good.with_file_name("does_not_exist.mpf");
    let out = gcodec(["parse".as_ref(), missing.as_os_str(), good.as_os_str()]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert_no_panic(&out);
    assert!(stdout(&out).contains("TRANS X10 Y5"));
}

#[test]
fn unknown_flag_is_a_usage_error() {
    let path = fixture("frames.mpf");
    let out = gcodec(["parse".as_ref(), "--bogus".as_ref(), path.as_os_str()]);
    assert_eq!(code(&out), EXIT_USAGE, "stderr:\n{}", stderr(&out));
    assert_no_panic(&out);
    let err = stderr(&out);
    assert!(err.contains("--bogus"), "stderr:\n{err}");
    assert!(err.contains("Usage:"), "stderr:\n{err}");
    assert_eq!(stdout(&out), "");
}

#[test]
fn unknown_format_is_a_usage_error() {
    let path = fixture("frames.mpf");
    let out = gcodec([
        "parse".as_ref(),
        "--format".as_ref(),
        "yaml".as_ref(),
        path.as_os_str(),
    ]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert_no_panic(&out);
    assert!(stderr(&out).contains("yaml"));
}

#[test]
fn missing_arguments_are_a_usage_error() {
    for args in [&[][..], &["parse"][..]] {
        let out = gcodec(args);
        assert_eq!(
            code(&out),
            EXIT_USAGE,
            "args {args:?}, stderr:\n{}",
            stderr(&out)
        );
        assert_no_panic(&out);
        assert!(stderr(&out).contains("Usage:"), "args {args:?}");
    }
}

#[test]
fn several_files_json_is_an_array() {
    let a = fixture("frames.mpf");
    let b = fixture("procs_and_calls.spf");
    let out = parse_json(&[&a, &b]);
    assert_eq!(code(&out), EXIT_CLEAN, "stderr:\n{}", stderr(&out));
    let programs = json(&out);
    let programs = programs.as_array().expect("several files give an array");
    assert_eq!(programs.len(), 2);
    assert!(
        programs[0]["file"]
            .as_str()
            .is_some_and(|f| f.ends_with("frames.mpf"))
    );
    assert!(
        programs[1]["file"]
            .as_str()
            .is_some_and(|f| f.ends_with("procs_and_calls.spf"))
    );
    assert_eq!(programs[1]["header"]["program"], "PROCS");
    for program in programs {
        assert!(program["blocks"].as_array().is_some_and(|b| !b.is_empty()));
    }
}

#[test]
fn several_files_text_trees_each_and_worst_exit_wins() {
    let good = fixture("frames.mpf");
    let bad = fixture("errors/unclosed_while.mpf");
    let out = gcodec(["parse".as_ref(), good.as_os_str(), bad.as_os_str()]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    let text = stdout(&out);
    assert!(text.contains("frames.mpf"), "stdout:\n{text}");
    assert!(text.contains("unclosed_while.mpf"), "stdout:\n{text}");
    assert!(stderr(&out).contains("unclosed_while.mpf"));
}

#[test]
fn latin1_file_is_read_and_decoded() {
    let path = fixture("messages.mpf");
    let out = parse_json(&[&path]);
    assert_eq!(code(&out), EXIT_CLEAN, "stderr:\n{}", stderr(&out));
    let program = json(&out);
    let comments: Vec<&str> = program["blocks"]
        .as_array()
        .expect("blocks")
        .iter()
        .filter_map(|b| b["comment"]["text"].as_str())
        .collect();
    assert!(
        comments.iter().any(|c| c.contains("Frühstück")),
        "comments: {comments:?}"
    );
}

#[test]
fn version_and_help_exit_0() {
    for flag in ["--version", "--help"] {
        let out = gcodec([flag]);
        assert_eq!(code(&out), EXIT_CLEAN, "{flag}");
        assert!(
            stdout(&out).contains("gcodec") || stdout(&out).contains("Usage"),
            "{flag}"
        );
    }
}

fn profile(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../profiles")
        .join(name)
}

#[test]
fn profile_check_accepts_every_shipped_profile() {
    for name in [
        "default.toml",
        "grinder_fb422.toml",
        "lathe_828d.toml",
        "mill_5axis.toml",
        "mill_g505_g599.toml",
        "mill_tool_management.toml",
    ] {
        let out = gcodec([
            "profile".as_ref(),
            "check".as_ref(),
            profile(name).as_os_str(),
        ]);
        assert_no_panic(&out);
        assert_eq!(code(&out), EXIT_CLEAN, "{name}: {}", stderr(&out));
        assert!(stderr(&out).is_empty(), "{}", stderr(&out));
    }
}

#[test]
fn profile_check_reports_a_bad_profile_with_exit_2() {
    let path = temp_file(
        "profile",
        "bad.toml",
        "[machine]\nname = \"m\"\ncontrol = \"840d_sl\"\n[work_offsets]\ndefault_group8_offset = \"G599\"\n",
    );
    let out = gcodec(["profile".as_ref(), "check".as_ref(), path.as_os_str()]);
    assert_no_panic(&out);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(
        stderr(&out).contains("gcodec::profile::unknown_reference"),
        "{}",
        stderr(&out)
    );
    assert!(stderr(&out).contains("bad.toml:5:25"), "{}", stderr(&out));
    let out = gcodec([
        "profile".as_ref(),
        "check".as_ref(),
        path.with_file_name("missing.toml").as_os_str(),
    ]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(
        stderr(&out).contains("gcodec::io::read"),
        "{}",
        stderr(&out)
    );
}

/// The checks against the G-group registry (`gcodec_driver::load_profile`)
/// run wherever a profile is loaded, rendered against the profile's text.
#[test]
fn profile_check_runs_the_g_group_checks() {
    let path = temp_file(
        "profile-g",
        "bad.toml",
        "[machine]\nname = \"m\"\ncontrol = \"840d_sl\"\n[modal_defaults]\n1 = \"G17\"\n[g_codes]\nunsupported = [\"G999\"]\n",
    );
    let out = gcodec(["profile".as_ref(), "check".as_ref(), path.as_os_str()]);
    assert_no_panic(&out);
    assert_eq!(code(&out), EXIT_USAGE);
    let err = stderr(&out);
    assert!(err.contains("gcodec::profile::not_in_group"), "{err}");
    assert!(err.contains("gcodec::profile::unknown_g_code"), "{err}");
    assert!(err.contains("bad.toml:5:5"), "{err}");
    assert!(err.contains("group 6"), "{err}");
    let out = gcodec(["profile".as_ref(), "show".as_ref(), path.as_os_str()]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(stdout(&out).is_empty(), "{}", stdout(&out));

    // `lower` rejects the profile before it reads the program.
    let program = temp_file("profile-g", "x.mpf", "G1 X1\n");
    let out = gcodec([
        "lower".as_ref(),
        program.as_os_str(),
        "--profile".as_ref(),
        path.as_os_str(),
    ]);
    assert_no_panic(&out);
    assert_eq!(code(&out), EXIT_USAGE);
    let err = stderr(&out);
    assert!(err.contains("gcodec::profile::not_in_group"), "{err}");
    assert!(err.contains("bad.toml"), "{err}");
    assert!(stdout(&out).is_empty(), "{}", stdout(&out));

    // A legacy alias that redefines a command of another group.
    let alias = temp_file(
        "profile-g",
        "alias.toml",
        "[machine]\nname = \"m\"\ncontrol = \"840d_sl\"\n[work_offsets]\nsupported_group8_offsets = [\"G500\", \"G54-G57\", \"G505-G599\"]\nlegacy_aliases = { G1 = \"G505\" }\n",
    );
    let out = gcodec(["profile".as_ref(), "check".as_ref(), alias.as_os_str()]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(
        stderr(&out).contains("gcodec::profile::alias_conflict"),
        "{}",
        stderr(&out)
    );
}

/// The built-in profile passes every check, `lower` without `--profile`
/// included.
#[test]
fn the_built_in_profile_passes_the_g_group_checks() {
    let out = gcodec(["profile", "show"]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    assert!(stderr(&out).is_empty(), "{}", stderr(&out));
    let file = gcodec_driver::builtin_profile_file();
    let (_, warnings) = gcodec_driver::load_profile(&file).expect("built-in profile");
    assert!(warnings.is_empty(), "{warnings:#?}");
}

/// `profile show` prints the effective built-in profile; its TOML loads
/// again, and its JSON names the control.
#[test]
fn profile_show_prints_the_effective_profile() {
    let out = gcodec(["profile", "show"]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let shown = stdout(&out);
    let again = gcodec_profile::load(&shown).unwrap_or_else(|d| panic!("{d:#?}\n{shown}"));
    assert_eq!(
        again.machine.control,
        gcodec_profile::Control::Sinumerik840dSl
    );
    // Defaults the file leaves out are shown filled in.
    assert!(shown.contains("unresolved"), "{shown}");

    let out = gcodec([
        "profile".as_ref(),
        "show".as_ref(),
        profile("lathe_828d.toml").as_os_str(),
        "--format".as_ref(),
        "json".as_ref(),
    ]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let json = json(&out);
    assert_eq!(json["machine"]["control"], "828d");
    assert_eq!(json["tool_change"]["tool_change_mode"], "direct");
}

fn example(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// `gcodec lower` with the built-in profile: a listing on stdout, the
/// warnings for what is not lowered yet on stderr, exit 0.
#[test]
fn lower_lists_instructions_with_their_lines() {
    let out = gcodec(["lower".as_ref(), example("pocket_mill.mpf").as_os_str()]);
    assert_no_panic(&out);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let listing = stdout(&out);
    assert!(listing.contains("tool_change trigger=\"m6\""), "{listing}");
    assert!(listing.lines().all(|l| {
        l.trim_start()
            .split(':')
            .next()
            .is_some_and(|n| n.parse::<u32>().is_ok())
    }));
    assert!(listing.trim_end().ends_with("end"), "{listing}");
}

/// JSON is the versioned AIL document; every instruction has its source.
#[test]
fn lower_json_is_the_ail_document() {
    let out = gcodec([
        "lower".as_ref(),
        "--format".as_ref(),
        "json".as_ref(),
        "--profile".as_ref(),
        profile("lathe_828d.toml").as_os_str(),
        example("lathe_shaft.mpf").as_os_str(),
    ]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let doc = json(&out);
    assert_eq!(doc["ail_version"], 1);
    let instructions = doc["instructions"].as_array().expect("instructions");
    assert!(instructions.len() > 10);
    for i in instructions {
        assert!(i["kind"].is_string(), "{i}");
        assert!(i["source"]["line"].as_u64().is_some_and(|l| l >= 1), "{i}");
        assert!(i["source"]["span"]["end"].is_u64(), "{i}");
    }
    // The lathe profile changes tools with T.
    assert!(
        instructions
            .iter()
            .any(|i| i["kind"] == "tool_change" && i["trigger"] == "t_word")
    );
}

/// A lowering error (a spindle the machine lacks) exits 1; a bad profile 2.
#[test]
fn lower_exit_codes() {
    let path = temp_file("lower", "spindle.mpf", "S4=1000\n");
    let out = gcodec(["lower".as_ref(), path.as_os_str()]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    assert!(
        stderr(&out).contains("gcodec::lower::unknown_spindle"),
        "{}",
        stderr(&out)
    );
    let bad = temp_file("lower", "bad.toml", "[machine]\nname = 1\n");
    let out = gcodec([
        "lower".as_ref(),
        "--profile".as_ref(),
        bad.as_os_str(),
        path.as_os_str(),
    ]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(
        stderr(&out).contains("gcodec::profile::schema"),
        "{}",
        stderr(&out)
    );
}
