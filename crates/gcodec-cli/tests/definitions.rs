//! `gcodec lower --definitions FILE.DEF`: global user data and macros
//! for the program, read from definition files; IO errors and bad files
//! are exit code 2. `parse` and `run` take the flag too, and see the
//! macros expanded.

mod common;

use common::{EXIT_CLEAN, EXIT_DIAGNOSTICS, EXIT_USAGE, code, gcodec, stderr, temp_file};

const PROGRAM: &str = "GR_TOOL=\"WHEEL\"\nR1=GR_STEPS[5]*GR_FEED\nM30\n";

#[test]
fn definitions_make_global_names_known() {
    let program = temp_file("known", "main.mpf", PROGRAM);
    // Without the definition file the names are undefined.
    let out = gcodec(["lower".as_ref(), program.as_os_str()]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS, "{}", stderr(&out));
    assert!(stderr(&out).contains("gcodec::lower::undefined_variable"));
    // Two files, the flag repeated.
    let mgud = temp_file(
        "known",
        "MGUD.DEF",
        "DEF CHAN STRING[32] GR_TOOL\nDEF CHAN REAL GR_STEPS[6]=REP(0.1)\nM30\n",
    );
    let ugud = temp_file("known", "UGUD.DEF", "DEF NCK REAL GR_FEED\n");
    let out = gcodec([
        "lower".as_ref(),
        program.as_os_str(),
        "--definitions".as_ref(),
        mgud.as_os_str(),
        "--definitions".as_ref(),
        ugud.as_os_str(),
    ]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let listing = String::from_utf8_lossy(&out.stdout);
    assert!(listing.contains("assign"), "{listing}");
}

#[test]
fn types_from_definitions_are_checked() {
    let program = temp_file("types", "main.mpf", "GR_TOOL=5\n");
    let mgud = temp_file("types", "MGUD.DEF", "DEF CHAN STRING[32] GR_TOOL\n");
    let out = gcodec([
        "lower".as_ref(),
        program.as_os_str(),
        "--definitions".as_ref(),
        mgud.as_os_str(),
    ]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    assert!(stderr(&out).contains("gcodec::lower::type_mismatch"));
}

#[test]
fn an_unreadable_definition_file_is_exit_code_2() {
    let program = temp_file("io", "main.mpf", PROGRAM);
    let out = gcodec([
        "lower",
        program.to_str().expect("utf-8 path"),
        "--definitions",
        "/nonexistent/MGUD.DEF",
    ]);
    assert_eq!(code(&out), EXIT_USAGE);
    let err = stderr(&out);
    assert!(err.contains("gcodec::io::read"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(out.stdout.is_empty());
}

#[test]
fn a_bad_definition_file_is_exit_code_2_with_its_diagnostics() {
    let program = temp_file("bad", "main.mpf", PROGRAM);
    let bad = temp_file("bad", "BAD.DEF", "DEF INT AA\nG1 X10\nDEF REAL AA\n");
    let out = gcodec([
        "lower".as_ref(),
        program.as_os_str(),
        "--definitions".as_ref(),
        bad.as_os_str(),
    ]);
    assert_eq!(code(&out), EXIT_USAGE);
    let err = stderr(&out);
    assert!(
        err.contains("gcodec::definitions::not_a_definition"),
        "{err}"
    );
    assert!(err.contains("gcodec::definitions::duplicate"), "{err}");
    assert!(err.contains("BAD.DEF"), "{err}");
    assert!(out.stdout.is_empty());
}

/// A `SMAC.DEF` and a `MMAC.DEF` as a machine maker ships them: a
/// constant, an M code and a keyword.
fn macro_files(test: &str) -> [std::path::PathBuf; 2] {
    [
        temp_file(
            test,
            "SMAC.DEF",
            "DEFINE MAXN AS 100\nDEFINE LIFT_ON AS M17\nM17\n",
        ),
        temp_file(
            test,
            "MMAC.DEF",
            "DEFINE WHEN_LOW AS IF R1<50\nDEFINE DONE AS ENDIF\n",
        ),
    ]
}

const MACRO_PROGRAM: &str = "R1=MAXN\nWHEN_LOW\nG1 X10 F100\nDONE\nLIFT_ON\n";

#[test]
fn macros_of_definition_files_are_expanded_for_parse_lower_and_run() {
    let program = temp_file("macros", "main.mpf", MACRO_PROGRAM);
    let [smac, mmac] = macro_files("macros");
    let with_definitions = |command: &str| {
        gcodec([
            command.as_ref(),
            program.as_os_str(),
            "--definitions".as_ref(),
            smac.as_os_str(),
            "--definitions".as_ref(),
            mmac.as_os_str(),
        ])
    };
    let out = with_definitions("parse");
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let tree = String::from_utf8_lossy(&out.stdout);
    assert!(
        tree.contains("R[1] = 100") && tree.contains("M17"),
        "{tree}"
    );
    let out = with_definitions("lower");
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let listing = String::from_utf8_lossy(&out.stdout);
    assert!(!listing.contains("call"), "{listing}");
    let out = with_definitions("run");
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let events = String::from_utf8_lossy(&out.stdout);
    assert!(events.contains("\"m_value\":17"), "{events}");
    // Without them `MAXN` is not defined and `LIFT_ON` is a call.
    let out = gcodec(["lower".as_ref(), program.as_os_str()]);
    assert!(stderr(&out).contains("gcodec::lower::undefined_variable"));
}

/// A lowering or run diagnostic inside a macro's expansion names the
/// macro, as the parser's do: the program shows only the use.
#[test]
fn a_diagnostic_inside_an_expansion_names_the_macro() {
    let program = temp_file("expansion_note", "main.mpf", "R1=MAXN\nM30\n");
    let umac = temp_file(
        "expansion_note",
        "UMAC.DEF",
        "DEFINE MAXN AS NOT_DEFINED_ANYWHERE\n",
    );
    for command in ["lower", "run"] {
        let out = gcodec([
            command.as_ref(),
            program.as_os_str(),
            "--definitions".as_ref(),
            umac.as_os_str(),
        ]);
        let err = stderr(&out);
        assert!(
            err.contains("gcodec::lower::undefined_variable"),
            "{command}: {err}"
        );
        assert!(
            err.contains("in the expansion of the macro `MAXN`"),
            "{command}: {err}"
        );
    }
}
