//! End-to-end tests of `gcodec run`: formats, options, the summary, exit
//! codes. What the channel does is tested in gcodec-exec; here the command
//! around it.

use std::path::PathBuf;

use serde_json::Value;

mod common;

use common::{
    EXIT_CLEAN, EXIT_DIAGNOSTICS, EXIT_USAGE, code, gcodec, gcodec_in, stderr, stdout, temp_file,
};

fn example(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

fn events(out: &std::process::Output) -> Vec<Value> {
    stdout(out)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect()
}

#[test]
fn jsonl_is_one_event_a_line_ending_with_program_end() {
    let out = gcodec(["run".as_ref(), example("pocket_mill.mpf").as_os_str()]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let events = events(&out);
    assert!(events.iter().all(|e| e["source"]["line"].is_u64()));
    let last = events.last().expect("events");
    assert_eq!(last["event"], "program_end");
    assert_eq!(last["reason"], "m30");
    // The subprogram next to the example is found and called.
    assert!(
        events
            .iter()
            .any(|e| e["event"] == "call" && e["target"] == "CHAMFER_EDGE")
    );
    // The summary goes to stderr in jsonl mode.
    assert!(
        stderr(&out).contains("blocks executed: 81"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn text_trace_ends_with_the_summary() {
    let out = gcodec([
        "run".as_ref(),
        example("pocket_mill.mpf").as_os_str(),
        "--format".as_ref(),
        "text".as_ref(),
    ]);
    assert_eq!(code(&out), EXIT_CLEAN);
    let text = stdout(&out);
    assert!(
        text.contains("tool_change T1 -> T2 pending_then_m6 m6"),
        "{text}"
    );
    assert!(text.contains("blocks executed: 81"));
    assert!(text.lines().any(|l| l.starts_with("T3 ")), "{text}");
}

#[test]
fn csv_has_a_row_per_change_or_per_block_on_request() {
    let csv = |rows: &str| {
        let out = gcodec([
            "run".as_ref(),
            example("pocket_mill.mpf").as_os_str(),
            "--format".as_ref(),
            "csv".as_ref(),
            "--csv-rows".as_ref(),
            rows.as_ref(),
        ]);
        assert_eq!(code(&out), EXIT_CLEAN);
        stdout(&out)
    };
    let column = |line: &str, index: usize| line.split(',').nth(index).unwrap_or("").to_owned();
    let changes = csv("changes");
    let mut lines = changes.lines();
    assert!(
        lines
            .next()
            .expect("header")
            .starts_with("block,file,line,level,blocks,X,Y,Z,tool")
    );
    let rows: Vec<&str> = lines.collect();
    // The pocket's WHILE loop, its R1 arithmetic and the DEFs change
    // nothing a column shows: no rows of theirs.
    for number in ["20", "100", "110", "200"] {
        let main_block = |r: &&str| column(r, 0) == number && column(r, 3) == "0";
        assert!(!rows.iter().any(main_block), "N{number}: {changes}");
    }
    // The last block (M30) has its row, and the count of every block.
    let last = rows.last().expect("rows");
    assert_eq!(column(last, 4), "81", "{last}");
    assert_eq!(rows.len(), 46);
    let every_block = csv("every-block");
    assert_eq!(every_block.lines().count(), 1 + 81);
    assert!(every_block.lines().any(|r| column(r, 0) == "200"));
}

/// The CSV `gcodec run` writes for `program`, as (line, X) of each row.
fn csv_lines_and_x(name: &str, program: &str) -> Vec<(String, String)> {
    let file = temp_file(name, "program.mpf", program);
    let out = gcodec(["run", file.to_str().expect("path"), "--format", "csv"]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    stdout(&out)
        .lines()
        .skip(1)
        .map(|r| {
            let cells: Vec<&str> = r.split(',').collect();
            (cells[2].to_owned(), cells[5].to_owned())
        })
        .collect()
}

/// (line, X) pairs as [`csv_lines_and_x`] gives them.
fn lines_and_x(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
    pairs
        .iter()
        .map(|(l, x)| ((*l).to_owned(), (*x).to_owned()))
        .collect()
}

/// A block without motion that moves the workpiece zero or changes the
/// units changes the CSV's positions: its row shows them anew.
#[test]
fn csv_positions_follow_frames_and_units_without_motion() {
    let program = "G0 X10 Y0 Z0\nR1=1\nTRANS X5\nG70\nR2=2\nTRANS\nG71\nM30\n";
    let expected = [
        ("1", "10"),
        ("3", "5"),
        ("4", "0.1968503937007874"),
        ("6", "0.3937007874015748"),
        ("7", "10"),
        ("8", "10"),
    ];
    assert_eq!(
        csv_lines_and_x("run-csv-frames", program),
        lines_and_x(&expected)
    );
}

/// A block that moves computes its row's positions without noting what
/// they came from; a block without motion after it must not take them
/// for those of an older row whose inputs it has again. Here the motion
/// (`G70 G1 X1`: one inch, where the machine already is) changes only
/// the units, and the `G71` after it brings back the machine position,
/// frame and units of the `G71` row before it.
#[test]
fn csv_positions_after_a_motion_are_not_taken_for_older_ones() {
    let program = "G71 G0 X25.4 Y0\nG71\nG70 G1 X1 F10\nG71\nM30\n";
    let expected = [("1", "25.4"), ("3", "1"), ("4", "25.4"), ("5", "25.4")];
    assert_eq!(
        csv_lines_and_x("run-csv-motion-units", program),
        lines_and_x(&expected)
    );
}

#[test]
fn skip_levels_and_max_steps_and_no_stop() {
    let program = "N10 G0 X0\n/1 N20 X10\nN30 M0\nN40 LOOP\nN50 R1=R1+1\nN60 ENDLOOP\n";
    let file = temp_file("run-options", "options.mpf", program);
    let run = |extra: &[&str]| {
        let mut args = vec!["run", file.to_str().expect("path"), "--format", "text"];
        args.extend_from_slice(extra);
        gcodec(args)
    };
    // M0 ends the run: exit 0.
    let out = run(&[]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    assert!(stdout(&out).contains("program_end stopped"));
    assert!(stdout(&out).contains("X10"), "level 1 is off by default");
    // Skip level 1 on: the block is skipped.
    let out = run(&["--skip-levels", "1"]);
    assert!(!stdout(&out).contains("X10"), "{}", stdout(&out));
    // --no-stop runs into the endless loop; --max-steps ends it: exit 1.
    let out = run(&["--no-stop", "--max-steps", "50"]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    assert!(
        stdout(&out).contains("program_end limit blocks 51"),
        "{}",
        stdout(&out)
    );
    assert!(
        stderr(&out).contains("gcodec::run::step_limit"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn max_work_stops_a_run_whose_blocks_cost_millions_of_operations() {
    // Each pass declares 2^20 elements; the budget admits three passes.
    let program = "LA: DEF REAL ARR[1024,1024]\nGOTOB LA\n";
    let file = temp_file("run-max-work", "work.mpf", program);
    let path = file.to_str().expect("path");
    let out = gcodec(["run", path, "--format", "text", "--max-work", "3500000"]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS, "{}", stderr(&out));
    // Two blocks a pass: the fourth `DEF` is block 7.
    assert!(
        stdout(&out).contains("program_end limit blocks 7"),
        "{}",
        stdout(&out)
    );
    assert!(
        stderr(&out).contains("gcodec::run::work_limit")
            && stderr(&out).contains("with the 3145728 done"),
        "{}",
        stderr(&out)
    );
    let out = gcodec(["run", path, "--max-work", "many"]);
    assert_eq!(code(&out), EXIT_USAGE, "{}", stderr(&out));
}

#[test]
fn a_global_variable_past_the_memory_for_variables_names_its_definition_file_and_line() {
    let definitions: String = (1..=20)
        .map(|n| format!("DEF REAL TAB{n}[1024,1024]\n"))
        .collect();
    let gud = temp_file("run-gud-memory", "MGUD.DEF", &definitions);
    let main = temp_file("run-gud-memory", "main.mpf", "N10 R1=1\nM30\n");
    let out = gcodec([
        "run",
        main.to_str().expect("path"),
        "--definitions",
        gud.to_str().expect("path"),
    ]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS, "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains("gcodec::run::variable_memory") && err.contains("MGUD.DEF:11:10"),
        "{err}"
    );
    assert!(err.contains("blocks executed: 0"), "{err}");
}

#[test]
fn a_missing_subprogram_is_an_alarm_naming_the_search_path() {
    let file = temp_file("run-missing", "missing.mpf", "N10 NOT_THERE\nN20 M30\n");
    let extra = file.parent().expect("dir").join("extra");
    let out = gcodec([
        "run".as_ref(),
        file.as_os_str(),
        "--subprogram-path".as_ref(),
        extra.as_os_str(),
    ]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    let err = stderr(&out);
    assert!(err.contains("gcodec::run::program_not_found"), "{err}");
    assert!(err.contains("NOT_THERE") && err.contains("extra"), "{err}");
    assert_eq!(events(&out).last().expect("end")["reason"], "alarm");
}

#[test]
fn a_missing_program_named_like_a_g_command_suggests_the_command() {
    // `GO` with the letter O is a call of a program `GO`.
    let file = temp_file("run-go", "rapid.mpf", "N10 GO X10\nN20 M30\n");
    let out = gcodec(["run".as_ref(), file.as_os_str()]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    let err = stderr(&out);
    assert!(err.contains("gcodec::run::program_not_found"), "{err}");
    assert!(err.contains("the G command `G0`?"), "{err}");
}

#[test]
fn a_run_time_error_in_a_called_program_is_labelled_in_its_file() {
    let main = temp_file(
        "run-called-error",
        "main.mpf",
        "N10 G1 X1 F100\nN20 SUB_DIV\nN30 M30\n",
    );
    let dir = main.parent().expect("dir");
    temp_file(
        "run-called-error",
        "SUB_DIV.SPF",
        "N10 R1=0\nN20 R2=5/R1\nN30 M17\n",
    );
    let out = gcodec_in(dir, ["run", "main.mpf"]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    // The subprogram's own lines, around the block the run stopped in.
    let labelled = "\
gcodec::run::division_by_zero

  × `/` by zero
   ╭─[./SUB_DIV.SPF:2:5]
 1 │ N10 R1=0
 2 │ N20 R2=5/R1
   ·     ───┬───
   ·        ╰── the run is here
 3 │ N30 M17
   ╰────
";
    let err = stderr(&out);
    assert!(err.starts_with(labelled), "{err}");
    assert_eq!(events(&out).last().expect("end")["reason"], "alarm");
}

#[test]
fn a_run_stops_with_an_alarm_at_the_first_block_with_errors_it_reaches() {
    let file = temp_file(
        "run-errors",
        "bad.mpf",
        "N10 G1 X1 F100\nN20 G1 X1 X2\nN30 G1 X3\nM30\n",
    );
    let out = gcodec(["run".as_ref(), file.as_os_str()]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    let err = stderr(&out);
    assert!(err.contains("gcodec::lower::repeated_axis"), "{err}");
    assert!(err.contains("gcodec::run::block_with_errors"), "{err}");
    assert!(err.contains("bad.mpf:2:"), "{err}");
    let events = events(&out);
    let last = events.last().expect("end");
    assert_eq!(last["event"], "program_end");
    assert_eq!(last["reason"], "alarm");
    // N10 ran, N20 and N30 did not.
    let motions: Vec<_> = events.iter().filter(|e| e["event"] == "motion").collect();
    assert_eq!(motions.len(), 1, "{events:?}");
    assert_eq!(motions[0]["source"]["line"], 1);
}

#[test]
fn a_jump_finds_the_number_of_a_block_with_a_syntax_error_and_stops_there() {
    // `N20 X=` cannot be read, but its number can: the jump goes there
    // (not to the later `N20`), and the run stops at the error.
    let file = temp_file(
        "run-errors-jump",
        "jump.mpf",
        "G1 X1 F100\nGOTOF N20\nN10 X2\nN20 X=\nN20 X3\nM30\n",
    );
    let out = gcodec(["run".as_ref(), file.as_os_str()]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    let err = stderr(&out);
    assert!(err.contains("gcodec::run::block_with_errors"), "{err}");
    assert!(err.contains("jump.mpf:4:"), "{err}");
    let events = events(&out);
    assert_eq!(events.last().expect("end")["reason"], "alarm");
    let motions: Vec<_> = events.iter().filter(|e| e["event"] == "motion").collect();
    assert_eq!(motions.len(), 1, "{events:?}");
}

#[test]
fn a_block_with_errors_the_run_does_not_reach_is_reported_not_run() {
    let file = temp_file(
        "run-errors-skipped",
        "skipped.mpf",
        "N10 G1 X1 F100\nIF 1 == 0\nN20 G1 X1 X2\nENDIF\nN30 G1 X3\nM30\n",
    );
    let out = gcodec(["run".as_ref(), file.as_os_str()]);
    // The program has an error, so exit code 1; the run goes round it.
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    let err = stderr(&out);
    assert!(err.contains("gcodec::lower::repeated_axis"), "{err}");
    assert!(!err.contains("block_with_errors"), "{err}");
    let events = events(&out);
    assert_eq!(events.last().expect("end")["reason"], "m30");
    assert_eq!(
        events.iter().filter(|e| e["event"] == "motion").count(),
        2,
        "{events:?}"
    );
}

#[test]
fn a_profile_that_does_not_stop_at_m0_is_followed_without_no_stop() {
    let default = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../profiles/default.toml"),
    )
    .expect("default profile");
    let profile = temp_file(
        "run-stop-profile",
        "no_stop.toml",
        &default.replace("[program]\n", "[program]\nstop_at_m0 = false\n"),
    );
    let file = temp_file("run-stop-profile", "m0.mpf", "G1 X1 F100\nM0\nG1 X2\nM30\n");
    let run = |profile: Option<&PathBuf>| {
        let mut args = vec!["run".as_ref(), file.as_os_str()];
        if let Some(p) = profile {
            args.extend(["--profile".as_ref(), p.as_os_str()]);
        }
        let out = gcodec(args);
        assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
        events(&out).last().expect("end")["reason"].clone()
    };
    // The built-in profile stops at M0; this one goes on to M30.
    assert_eq!(run(None), "stopped");
    assert_eq!(run(Some(&profile)), "m30");
}

#[test]
fn bad_options_are_usage_errors() {
    let file = temp_file("run-usage", "ok.mpf", "M30\n");
    for args in [
        vec!["run", file.to_str().expect("path"), "--skip-levels", "12"],
        vec!["run", file.to_str().expect("path"), "--format", "xml"],
        vec!["run", "/no/such/file.mpf"],
        vec![
            "run",
            file.to_str().expect("path"),
            "--profile",
            "/no/such.toml",
        ],
    ] {
        let out = gcodec(&args);
        assert_eq!(code(&out), EXIT_USAGE, "{args:?}: {}", stderr(&out));
        assert!(!stderr(&out).contains("panicked"));
    }
}

/// The profile an example's first comment names (after the archive
/// header `%_N_…` and `;$PATH=…`): `profiles/NAME.toml`, or `None` for
/// the built-in profile. An example that names neither fails.
fn profile_of_example(text: &str, name: &str) -> Option<PathBuf> {
    let comment = text
        .lines()
        .find(|l| l.starts_with(';') && !l.starts_with(";$PATH"))
        .unwrap_or_else(|| panic!("{name}: no comment"));
    if comment.starts_with("; For the built-in profile") {
        return None;
    }
    let profile = comment
        .split_whitespace()
        .find(|w| w.starts_with("profiles/"))
        .unwrap_or_else(|| panic!("{name}: the first comment names no profile: {comment}"));
    Some(
        example("../profiles").join(
            profile
                .trim_start_matches("profiles/")
                .trim_end_matches(['.', ',', ':']),
        ),
    )
}

/// Every example main program runs clean, as its first comment says: on
/// the built-in profile or the one it names (the README's examples are
/// run as written).
#[test]
fn every_example_runs_clean_on_the_profile_its_first_comment_names() {
    let mut ran = 0;
    for entry in std::fs::read_dir(example("")).expect("examples/") {
        let path = entry.expect("an entry").path();
        // Only main programs: `examples/` also holds folders (the
        // toolchanger's scenarios) and called programs.
        if path.extension().is_none_or(|e| e != "mpf") {
            continue;
        }
        let name = path.display().to_string();
        let text = std::fs::read_to_string(&path).expect("an example");
        let profile = profile_of_example(&text, &name);
        let mut args = vec!["run".into(), path.clone().into_os_string()];
        if let Some(profile) = &profile {
            args.extend(["--profile".into(), profile.clone().into_os_string()]);
        }
        let out = gcodec(args);
        assert_eq!(code(&out), EXIT_CLEAN, "{name}: {}", stderr(&out));
        ran += 1;
    }
    assert!(ran >= 2, "{ran} examples");
}

#[test]
fn toolchanger_scenario_faults_show_in_the_text_trace() {
    let out = gcodec([
        "run".as_ref(),
        example("toolchanger/tool_changes.mpf").as_os_str(),
        "--profile".as_ref(),
        example("toolchanger/profile/iov2.toml").as_os_str(),
        "--toolchanger".as_ref(),
        example("toolchanger/soft_fault.toml").as_os_str(),
        "--format".as_ref(),
        "text".as_ref(),
    ]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains("NOT MADE (toolchanger fault 7): the spindle stays empty"),
        "{text}"
    );
    assert!(text.contains("toolchanger: fault cleared"), "{text}");
    assert!(
        text.contains("tool changes"),
        "the summary counts the cycles: {text}"
    );
}

#[test]
fn a_bad_toolchanger_scenario_is_a_diagnostic_into_its_toml_and_exit_2() {
    let scenario = temp_file(
        "bad_scenario",
        "bad.toml",
        "ack_cycles = 0\n[[inject]]\nat = \"change\"\n",
    );
    let out = gcodec([
        "run".as_ref(),
        example("toolchanger/tool_changes.mpf").as_os_str(),
        "--profile".as_ref(),
        example("toolchanger/profile/iov2.toml").as_os_str(),
        "--toolchanger".as_ref(),
        scenario.as_os_str(),
    ]);
    assert_eq!(code(&out), EXIT_USAGE);
    let err = stderr(&out);
    assert!(err.contains("gcodec::scenario::"), "{err}");
    assert!(err.contains("bad.toml:2:1"), "{err}");
    assert!(stdout(&out).is_empty(), "no run: {}", stdout(&out));
}

/// Ctrl-C stops an endless run at the next block: the error
/// `gcodec::run::interrupted`, `program_end` with `limit`, exit code 1.
#[cfg(unix)]
#[test]
fn ctrl_c_stops_the_run_at_the_next_block() {
    use std::io::{BufRead, BufReader, Read};
    use std::process::Stdio;

    let program = temp_file(
        "ctrl_c",
        "endless.mpf",
        "WHILE 1\nG1 X=R1 F1000\nR1=R1+1\nENDWHILE\nM30\n",
    );
    let mut child = common::command([
        "run".as_ref(),
        "--max-steps".as_ref(),
        "18446744073709551615".as_ref(),
        program.as_os_str(),
    ])
    .stdout(Stdio::piped())
    .stderr(Stdio::piped())
    .spawn()
    .expect("gcodec starts");
    let mut stdout = BufReader::new(child.stdout.take().expect("stdout"));
    // The first event comes after the handler is installed.
    let mut first = String::new();
    stdout.read_line(&mut first).expect("an event");
    assert!(first.contains("\"event\""), "{first}");
    let kill = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(kill.success());
    let mut rest = String::new();
    stdout.read_to_string(&mut rest).expect("the events");
    let mut errors = String::new();
    child
        .stderr
        .take()
        .expect("stderr")
        .read_to_string(&mut errors)
        .expect("the diagnostics");
    let status = child.wait().expect("gcodec ends");
    assert_eq!(status.code(), Some(EXIT_DIAGNOSTICS), "{errors}");
    assert!(errors.contains("gcodec::run::interrupted"), "{errors}");
    let last: Value =
        serde_json::from_str(rest.lines().last().expect("program_end")).expect("json");
    assert_eq!(last["event"], "program_end");
    assert_eq!(last["reason"], "limit");
}
