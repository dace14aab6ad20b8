//! `gcodec explain`, and the examples of every explanation: the wrong one
//! makes gcodec report the code, the right one does not.

mod common;

use std::path::Path;

use common::{EXIT_CLEAN, EXIT_USAGE, code, gcodec, stderr, stdout};
use gcodec_source::codes::{self, Code};

#[test]
fn explain_prints_every_code() {
    for code_ in codes::all() {
        let out = gcodec(["explain", code_.name()]);
        assert_eq!(code(&out), EXIT_CLEAN, "{code_}: {}", stderr(&out));
        let text = stdout(&out);
        assert!(text.starts_with(code_.name()), "{code_}: {text}");
        assert!(text.contains(code_.level().name()), "{code_}: {text}");
        assert!(text.contains(code_.explanation()), "{code_}");
    }
}

#[test]
fn explain_takes_a_name_without_prefix_and_a_unique_last_part() {
    let full = stdout(&gcodec(["explain", "gcodec::parse::unclosed_structure"]));
    assert_eq!(
        stdout(&gcodec(["explain", "parse::unclosed_structure"])),
        full
    );
    assert_eq!(stdout(&gcodec(["explain", "unclosed_structure"])), full);
    let alarm = stdout(&gcodec(["explain", "run::jump_target_not_found"]));
    assert!(alarm.contains("alarm 14080"), "{alarm}");
}

#[test]
fn explain_list_lists_every_code_one_a_line() {
    let out = gcodec(["explain", "--list"]);
    assert_eq!(code(&out), EXIT_CLEAN);
    let text = stdout(&out);
    assert_eq!(text.lines().count(), codes::all().len());
    for (line, code_) in text.lines().zip(codes::all()) {
        assert!(line.starts_with(code_.name()), "{line}");
        assert!(line.contains(code_.summary()), "{line}");
    }
}

#[test]
fn an_unknown_code_is_a_usage_error_with_the_code_meant() {
    let meant = codes::parse::UNCLOSED_STRUCTURE;
    let out = gcodec(["explain", &format!("{meant}s")]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(
        stderr(&out).contains(&format!("did you mean `{meant}`?")),
        "{}",
        stderr(&out)
    );
    let out = gcodec(["explain", "qqqqqqqq"]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(!stderr(&out).contains("did you mean"), "{}", stderr(&out));
    // A bare name two areas share is not unique: no explanation, but help.
    let out = gcodec(["explain", "type_mismatch"]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(stderr(&out).contains("did you mean"), "{}", stderr(&out));
}

#[test]
fn explain_needs_a_code_or_list() {
    assert_eq!(code(&gcodec(["explain"])), EXIT_USAGE);
    assert_eq!(
        code(&gcodec(["explain", "--list", "invalid_word"])),
        EXIT_USAGE
    );
}

/// Runs every explanation's examples; fails on a malformed explanation.
#[test]
fn every_example_does_what_it_says() {
    let mut failures = Vec::new();
    for code_ in codes::all() {
        let examples = match examples(code_) {
            Ok(examples) => examples,
            Err(e) => {
                failures.push(format!("{code_}: malformed explanation: {e}"));
                continue;
            }
        };
        let Some(files) = examples else {
            continue;
        };
        for role in [Role::Wrong, Role::Right] {
            let output = run_example(code_, &files, role);
            let emitted = output.contains(code_.name());
            if emitted != (role == Role::Wrong) {
                failures.push(format!(
                    "{code_}: the {role:?} example {} the code:\n{output}",
                    if emitted { "emits" } else { "does not emit" }
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    Wrong,
    Right,
    Both,
}

/// One fenced block of an explanation's `## Example`.
#[derive(Debug)]
struct ExampleFile {
    lang: String,
    role: Role,
    /// The file name: `MAIN.MPF`, `PROFILE.TOML`, or the `file=` name.
    name: String,
    /// `command=` and `args=` (on the main program, or on the profile of
    /// a profile code).
    command: Option<String>,
    args: Vec<String>,
    text: String,
}

/// The example files of `code`: `None` for an explanation that says
/// `No example: …`; an error for anything else than the format of
/// `crates/gcodec-source/src/codes/` (`## Example`, then fenced blocks
/// `LANG ROLE [key=value]…`).
fn examples(code: &Code) -> Result<Option<Vec<ExampleFile>>, String> {
    let text = code.explanation();
    let no_example = text.lines().any(|l| l.starts_with("No example: "));
    let Some((_, body)) = text.split_once("\n## Example\n") else {
        return if no_example {
            Ok(None)
        } else {
            Err("neither `## Example` nor `No example: …`".into())
        };
    };
    if no_example {
        return Err("both `## Example` and `No example: …`".into());
    }
    let mut files = Vec::new();
    let mut lines = body.lines();
    while let Some(line) = lines.next() {
        if line.trim().is_empty() {
            continue;
        }
        let info = line
            .strip_prefix("```")
            .ok_or_else(|| format!("text outside a fenced block: `{line}`"))?;
        let mut text = String::new();
        loop {
            let line = lines.next().ok_or("a fenced block is not closed")?;
            if line == "```" {
                break;
            }
            text.push_str(line);
            text.push('\n');
        }
        files.push(example_file(info, text)?);
    }
    for role in [Role::Wrong, Role::Right] {
        if !files.iter().any(|f| f.role == role) {
            return Err(format!("no {role:?} example"));
        }
    }
    Ok(Some(files))
}

/// A fenced block from its info string, `LANG ROLE [key=value]…` (a value
/// may be quoted: `args="--max-steps 100"`).
fn example_file(info: &str, text: String) -> Result<ExampleFile, String> {
    let (lang, rest) = info.split_once(' ').ok_or("no role")?;
    let (role, mut rest) = rest.split_once(' ').unwrap_or((rest, ""));
    let role = match role {
        "wrong" => Role::Wrong,
        "right" => Role::Right,
        "both" => Role::Both,
        other => return Err(format!("unknown role `{other}`")),
    };
    let (mut file, mut command, mut args) = (None, None, Vec::new());
    while !rest.trim().is_empty() {
        let (key, after) = rest
            .trim_start()
            .split_once('=')
            .ok_or("a key without `=`")?;
        let (value, after) = match after.strip_prefix('"') {
            Some(quoted) => quoted.split_once('"').ok_or("an unclosed quote")?,
            None => after.split_once(' ').unwrap_or((after, "")),
        };
        match key {
            "file" => file = Some(value.to_owned()),
            "command" => command = Some(value.to_owned()),
            "args" => args = value.split_whitespace().map(str::to_owned).collect(),
            other => return Err(format!("unknown key `{other}`")),
        }
        rest = after;
    }
    let name = match (lang, file) {
        ("mpf", None) => "MAIN.MPF".to_owned(),
        ("toml", None) => "PROFILE.TOML".to_owned(),
        ("spf" | "def", Some(file)) => file,
        ("mpf" | "toml", Some(_)) => return Err(format!("`{lang}` takes no `file=`")),
        ("spf" | "def", None) => return Err(format!("`{lang}` needs `file=`")),
        (other, _) => return Err(format!("unknown language `{other}`")),
    };
    if lang != "mpf" && lang != "toml" && (command.is_some() || !args.is_empty()) {
        return Err(format!("`{lang}` takes no `command=` or `args=`"));
    }
    Ok(ExampleFile {
        lang: lang.to_owned(),
        role,
        name,
        command,
        args,
        text,
    })
}

/// The `gcodec.toml` that gives an example's main program its profile and
/// definition files.
fn check_config(files: &[&ExampleFile]) -> String {
    let mut section = String::from("[[files]]\nglob = \"*\"\n");
    if let Some(profile) = files.iter().find(|f| f.lang == "toml") {
        section.push_str(&format!("profile = \"{}\"\n", profile.name));
    }
    let definitions: Vec<String> = files
        .iter()
        .filter(|f| f.lang == "def")
        .map(|f| format!("\"{}\"", f.name))
        .collect();
    if !definitions.is_empty() {
        section.push_str(&format!("definitions = [{}]\n", definitions.join(", ")));
    }
    section
}

/// Writes the files of `role` (and those both use) to a folder of their
/// own, runs gcodec on them as the explanation says, and returns stdout
/// and stderr together.
fn run_example(code: &Code, files: &[ExampleFile], role: Role) -> String {
    let dir = std::env::temp_dir().join(format!(
        "gcodec-explain-{}-{role:?}-{}",
        code.short_name().replace("::", "-"),
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let files: Vec<_> = files
        .iter()
        .filter(|f| f.role == role || f.role == Role::Both)
        .collect();
    for file in &files {
        std::fs::write(dir.join(&file.name), &file.text).expect("write an example file");
    }
    let is_profile_code = code.area() == "profile";
    let driver = files
        .iter()
        .find(|f| f.lang == if is_profile_code { "toml" } else { "mpf" });
    let command = driver
        .and_then(|f| f.command.as_deref())
        .unwrap_or(match code.area() {
            "parse" => "parse",
            "run" => "run",
            "profile" => "profile-check",
            "lint" => "check",
            _ => "lower",
        });
    let path = |name: &str| dir.join(name).display().to_string();
    let mut args: Vec<String> = match command {
        "profile-check" => vec!["profile".into(), "check".into(), path("PROFILE.TOML")],
        other => vec![other.to_owned(), path("MAIN.MPF")],
    };
    if command == "check" {
        // `check` takes its machine from a configuration, as a repository
        // of programs would.
        let config = check_config(&files);
        std::fs::write(dir.join("gcodec.toml"), config).expect("write gcodec.toml");
    }
    if matches!(command, "parse" | "lower" | "run") {
        for file in &files {
            match file.lang.as_str() {
                "toml" if command != "parse" => {
                    args.extend(["--profile".to_owned(), path(&file.name)])
                }
                "def" => args.extend(["--definitions".to_owned(), path(&file.name)]),
                _ => {}
            }
        }
    }
    args.extend(driver.iter().flat_map(|f| f.args.iter().cloned()));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_gcodec"))
        .args(&args)
        .current_dir(Path::new(&dir))
        .output()
        .expect("gcodec runs");
    let _ = std::fs::remove_dir_all(&dir);
    format!("{}{}", stdout(&out), stderr(&out))
}
