//! The machine-dependent lines of `SYNTAX_CHECK.SPF` are valid syntax that
//! the control rejects for the machine: lowering with the default profile
//! rejects each of them, on its own.

mod common;

fn syntax_check_file() -> Option<String> {
    let path = common::corpus_dir()?.join("real/deathaxe+sublime-s840d/examples/SYNTAX_CHECK.SPF");
    match std::fs::read(&path) {
        Ok(bytes) => Some(String::from_utf8_lossy(&bytes).into_owned()),
        Err(_) => {
            eprintln!(
                "notice: {} is absent; the SYNTAX_CHECK lowering test is skipped",
                path.display()
            );
            None
        }
    }
}

#[test]
fn machine_dependent_lines_are_rejected_by_lowering() {
    let Some(text) = syntax_check_file() else {
        return;
    };
    let profile = gcodec_profile::builtin().expect("built-in profile");
    let expected = [
        ("M100", "gcodec::lower::unknown_spindle"),
        ("S4      =", "gcodec::lower::unknown_spindle"),
        ("T10     =", "gcodec::lower::unknown_spindle"),
        ("$MN_G53_TOLCORR", "gcodec::lower::unknown_system_variable"),
    ];
    for (start, code) in expected {
        let line = text
            .lines()
            .find(|l| l.starts_with(start))
            .unwrap_or_else(|| panic!("no line starting with `{start}`"));
        let parsed = gcodec_parser::parse_bytes("line", line.as_bytes());
        assert!(
            parsed.diagnostics.is_empty(),
            "`{line}` parses: {:#?}",
            parsed.diagnostics
        );
        let lowered = gcodec_sema::lower(&parsed.program, &profile);
        let errors: Vec<_> = lowered
            .diagnostics
            .iter()
            .filter(|d| d.is_error())
            .map(|d| d.code.name())
            .collect();
        assert_eq!(errors, [code], "`{line}`");
    }
}
