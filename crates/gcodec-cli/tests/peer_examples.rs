//! The example programs of the peer interpreter (issue 20) run as
//! `scripts/bench-peer/run.sh` runs them: `gcodec run --config
//! scripts/bench-peer/gcodec.toml --no-stop`. Each one gcodec rejects
//! ends with the first error and for the reason `gcodec_testkit::peer`
//! lists; every other one runs clean, so the script times it against the
//! peer.

mod common;

use common::{EXIT_CLEAN, EXIT_DIAGNOSTICS, command, stderr};
use gcodec_testkit::peer::{CONFIG, EXAMPLES, REJECTIONS};
use serde_json::Value as Json;

/// The first error of a run's diagnostics (a JSON array), the alarm that
/// stops a run at a block with errors aside, as `run.sh` reports it:
/// `(line, code, message)`.
fn first_error(diagnostics: &Json) -> Option<(u64, String, String)> {
    let records = diagnostics.as_array()?;
    records
        .iter()
        .filter(|r| r["level"] == "error" && r["code"] != "gcodec::run::block_with_errors")
        .map(|r| {
            (
                r["line"].as_u64().unwrap_or(0),
                r["code"].as_str().unwrap_or("").to_owned(),
                r["message"].as_str().unwrap_or("").to_owned(),
            )
        })
        .next()
}

#[test]
fn each_peer_example_runs_clean_or_is_rejected_for_its_listed_reason() {
    let Some(corpus) = gcodec_testkit::corpus_dir() else {
        return;
    };
    let config = gcodec_testkit::repo().join(CONFIG);
    let mut examples: Vec<_> = std::fs::read_dir(corpus.join(EXAMPLES))
        .expect("the peer's examples")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "mpf"))
        .collect();
    examples.sort();
    assert!(
        examples.len() >= 30,
        "found only {} examples",
        examples.len()
    );
    let mut failures = Vec::new();
    let mut clean = 0;
    for path in &examples {
        let name = path.file_name().and_then(|n| n.to_str()).expect("a name");
        let out = command(["run", "--no-stop", "--output-format", "json"])
            .arg("--config")
            .arg(&config)
            .arg(path)
            .output()
            .expect("gcodec runs");
        let status = out.status.code().unwrap_or(-1);
        let text = stderr(&out);
        let diagnostics: Json = match serde_json::from_str(&text) {
            Ok(d) => d,
            Err(e) => {
                failures.push(format!(
                    "{name}: exit {status}, no JSON on stderr ({e}): {text}"
                ));
                continue;
            }
        };
        let rejection = REJECTIONS.iter().find(|r| r.file == name);
        match (rejection, status, first_error(&diagnostics)) {
            (None, EXIT_CLEAN, None) => clean += 1,
            (Some(r), EXIT_DIAGNOSTICS, Some((line, code, _)))
                if line == u64::from(r.line) && code == r.code.name() => {}
            (Some(r), _, got) => failures.push(format!(
                "{name}: expected {}:{} ({}), got exit {status}, {got:?}",
                r.line,
                r.code.name(),
                r.reason
            )),
            (None, _, got) => {
                failures.push(format!(
                    "{name}: expected a clean run, got exit {status}, {got:?}"
                ));
            }
        }
    }
    for r in REJECTIONS {
        if !examples.iter().any(|p| p.ends_with(r.file)) {
            failures.push(format!("{}: listed, but not among the examples", r.file));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_eq!(
        clean + REJECTIONS.len(),
        examples.len(),
        "every example is clean or listed"
    );
}
