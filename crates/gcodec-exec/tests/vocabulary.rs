//! The control's vocabulary at run time (issue 16): every predefined
//! procedure and function of the catalogue runs or is diagnosed as not
//! simulated, system variables the run cannot answer name the profile
//! key that supplies them, and tool data a program writes is the run's.

use std::sync::Arc;

use gcodec_driver::{RunSetup, run_main};
use gcodec_exec::event::{EventKind, ProgramEndReason, VecSink};
use gcodec_lang::procedures::{Effect, PROCEDURES};
use gcodec_profile::Profile;
use gcodec_source::{Severity, SourceFile};

/// One diagnostic of a run: code, severity, message, line.
type Reported = (&'static str, Severity, String, u32);

/// Runs `program` on `profile` and returns the lowering and run
/// diagnostics and how the run ended.
fn run_on(profile: Profile, program: &str) -> (Vec<Reported>, ProgramEndReason) {
    let setup = RunSetup::new(profile);
    let file = Arc::new(SourceFile::new("VOCAB.MPF", program));
    let mut sink = VecSink::new();
    let report = run_main(file, &setup, &mut sink, None);
    let mut reported: Vec<Reported> = report
        .diagnostics
        .iter()
        .map(|d| (d.code.name(), d.severity, d.message.to_string(), 0))
        .collect();
    let mut end = None;
    for event in &sink.events {
        match &event.kind {
            EventKind::Diagnostic(d) => {
                reported.push((d.code.name(), d.severity, d.message.to_string(), event.source.line))
            }
            EventKind::ProgramEnd(e) => end = Some(e.reason),
            _ => {}
        }
    }
    (reported, end.expect("the program ends"))
}

fn run(program: &str) -> (Vec<Reported>, ProgramEndReason) {
    run_on(gcodec_profile::builtin().expect("the built-in profile"), program)
}

#[test]
fn every_predefined_procedure_runs_or_is_advice() {
    for &(_, name, effect, arity) in PROCEDURES {
        if effect == Effect::Alarm {
            continue;
        }
        let args = vec!["1"; usize::from(arity.min)].join(",");
        let call = if args.is_empty() { name.to_owned() } else { format!("{name}({args})") };
        let (reported, end) = run(&format!("G0 X1\n{call}\nM30\n"));
        assert_eq!(end, ProgramEndReason::M30, "{name}: {reported:?}");
        match effect.left_out() {
            None => assert_eq!(reported, [], "{name}"),
            Some(left_out) => assert_eq!(
                reported,
                [(
                    "gcodec::run::not_simulated",
                    Severity::Advice,
                    format!("the predefined procedure `{name}` {left_out}"),
                    2
                )],
                "{name}"
            ),
        }
    }
}

#[test]
fn single_block_and_preprocessing_switches_pass_in_silence() {
    let (reported, end) = run("SBLOF\nG0 X1\nSBLON\nSTOPREOF\nG0 X2\nM30\n");
    assert_eq!(reported, []);
    assert_eq!(end, ProgramEndReason::M30);
}

#[test]
fn procedures_that_ended_the_run_are_advice_with_their_effect() {
    let (reported, end) = run(
        "CHANDATA(1)\nMMC(\"CYCLE\",\"A\")\nGEOAX(1,X,2,Y)\nWAITENC\nCLRINT(3)\nG0 X1\nM30\n",
    );
    assert_eq!(end, ProgramEndReason::M30);
    let lines: Vec<_> = reported.iter().map(|r| (r.0, r.3)).collect();
    assert_eq!(
        lines,
        [1, 2, 3, 4, 5].map(|line| ("gcodec::run::not_simulated", line))
    );
    assert!(reported[2].2.contains("keeps the profile's geometry axes"), "{}", reported[2].2);
}
