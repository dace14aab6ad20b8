//! The control's vocabulary at run time (issue 16): every predefined
//! procedure and function of the catalogue runs or is diagnosed as not
//! simulated, system variables the run cannot answer name the profile
//! key that supplies them, and tool data a program writes is the run's.

use std::sync::Arc;

use gcodec_ail::{Callee, Expr};
use gcodec_driver::{RunSetup, run_main};
use gcodec_exec::channel::MachineState;
use gcodec_exec::eval::{Env, eval};
use gcodec_exec::event::{EventKind, ProgramEndReason, VecSink};
use gcodec_exec::vars::Variables;
use gcodec_lang::functions::FUNCTIONS;
use gcodec_lang::procedures::{Effect, PROCEDURES};
use gcodec_profile::Profile;
use gcodec_source::{Severity, SourceFile, codes};

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
            EventKind::Diagnostic(d) => reported.push((
                d.code.name(),
                d.severity,
                d.message.to_string(),
                event.source.line,
            )),
            EventKind::ProgramEnd(e) => end = Some(e.reason),
            _ => {}
        }
    }
    (reported, end.expect("the program ends"))
}

/// A run that reports nothing and ends at `M30`.
fn runs_clean((reported, end): (Vec<Reported>, ProgramEndReason)) {
    assert_eq!(reported, []);
    assert_eq!(end, ProgramEndReason::M30);
}

fn run(program: &str) -> (Vec<Reported>, ProgramEndReason) {
    run_on(
        gcodec_profile::builtin().expect("the built-in profile"),
        program,
    )
}

#[test]
fn every_predefined_procedure_runs_or_is_advice() {
    for &(_, name, effect, arity) in PROCEDURES {
        if effect == Effect::Alarm {
            continue;
        }
        let args = vec!["1"; usize::from(arity.min)].join(",");
        let call = if args.is_empty() {
            name.to_owned()
        } else {
            format!("{name}({args})")
        };
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
    runs_clean(run("SBLOF\nG0 X1\nSBLON\nSTOPREOF\nG0 X2\nM30\n"));
}

#[test]
fn procedures_that_ended_the_run_are_advice_with_their_effect() {
    let (reported, end) =
        run("CHANDATA(1)\nMMC(\"CYCLE\",\"A\")\nGEOAX(1,X,2,Y)\nWAITENC\nG0 X1\nM30\n");
    assert_eq!(end, ProgramEndReason::M30);
    let lines: Vec<_> = reported.iter().map(|r| (r.0, r.3)).collect();
    assert_eq!(
        lines,
        [1, 2, 3, 4].map(|line| ("gcodec::run::not_simulated", line))
    );
    assert!(
        reported[2].2.contains("keeps the profile's geometry axes"),
        "{}",
        reported[2].2
    );
}

/// The built-in profile with a tool table of named tools: `DRILL_8` in
/// two sister tools (T7 duplo 2, T3 duplo 1), `MILL_10` as T12.
fn with_named_tools() -> Profile {
    let text = format!(
        "{}\n{}",
        include_str!("../../../profiles/default.toml"),
        r#"
[[tools]]
number = 7
name = "DRILL_8"
duplo = 2
edges = [{ d = 1, length = 80.0, radius = 4.0 }]

[[tools]]
number = 3
name = "DRILL_8"
edges = [{ d = 1, length = 81.0, radius = 4.0 }]

[[tools]]
number = 12
name = "MILL_10"
edges = [{ d = 1, length = 95.0, radius = 5.0 }]
"#
    );
    gcodec_profile::load(&text).expect("the profile with named tools")
}

/// The program's R parameters 1…n as `SETAL` would see them: the run
/// raises alarm `61000 + k` where `R<k>` is not `expected[k-1]`.
fn checks(expected: &[&str]) -> String {
    expected
        .iter()
        .enumerate()
        .map(|(k, value)| format!("IF R{}<>{value}\nSETAL({})\nENDIF\n", k + 1, 61001 + k))
        .collect()
}

#[test]
fn gett_gives_the_t_number_of_a_named_tool() {
    let program = format!(
        "R1=GETT(\"DRILL_8\")\nR2=GETT(\"drill_8\",2)\nR3=GETT(\"MILL_10\")\nR4=GETT(\"NONE\")\nR5=GETT(\"MILL_10\",2)\n{}M30\n",
        checks(&["3", "7", "12", "-1", "-1"])
    );
    runs_clean(run_on(with_named_tools(), &program));
}

#[test]
fn isaxis_and_isvar_ask_the_machine_and_the_program() {
    let program = format!(
        "DEF INT DEPTH=1\nR1=ISAXIS(1)\nR2=ISAXIS(3)\nR3=ISAXIS(4)\nR4=ISVAR(\"DEPTH\")\nR5=ISVAR(\"depht\")\nR6=ISVAR(\"$P_TOOLNO\")\nR7=ISVAR(\"$TC_DP3[1,1]\")\nR8=ISVAR(\"$P_NONE\")\nR9=ISVAR(\"R20\")\n{}M30\n",
        checks(&["1", "1", "0", "1", "0", "1", "1", "0", "1"])
    );
    runs_clean(run(&program));
}

#[test]
fn a_function_the_simulation_does_not_compute_is_an_error_naming_its_result() {
    let (reported, end) = run("G0 X1\nR1=GETACTT(1,\"DRILL\")\nG0 X2\nM30\n");
    assert_eq!(end, ProgramEndReason::Alarm);
    assert_eq!(
        reported,
        [(
            "gcodec::run::not_simulated",
            Severity::Error,
            "`GETACTT` is not simulated: on the control it returns the T number of the active tool of a tool group".to_owned(),
            2
        )]
    );
}

/// Every function of the vocabulary is computed (here, called without
/// arguments, at most an error about them) or not simulated: none is
/// unknown to the executor.
#[test]
fn no_predefined_function_is_unknown_to_the_executor() {
    let profile = Arc::new(gcodec_profile::builtin().expect("the built-in profile"));
    let state = MachineState::new(profile);
    let vars = Variables::default();
    for &(_, name, _) in FUNCTIONS {
        let call = Expr::Call {
            name: Callee::named(name),
            args: Vec::new(),
        };
        if let Err(error) = eval(&Env::new(&vars, &state), &call) {
            assert_ne!(error.code, codes::run::UNKNOWN_FUNCTION, "{name}: {error}");
        }
    }
}

/// The built-in profile with `table` as its `[system_variables]`.
fn with_system_variables(table: &str) -> Profile {
    let text = format!(
        "{}\n[system_variables]\n{table}",
        include_str!("../../../profiles/default.toml")
    );
    gcodec_profile::load(&text).expect("the profile with system variables")
}

#[test]
fn a_variable_the_run_cannot_know_names_the_profile_entry_that_gives_it() {
    let (reported, end) = run("G0 X1\nIF $P_ISTEST GOTOF END\nG0 X2\nEND: M30\n");
    assert_eq!(end, ProgramEndReason::Alarm);
    assert_eq!(
        reported,
        [(
            "gcodec::run::system_variable",
            Severity::Error,
            "the system variable `$P_ISTEST` has no value in the simulation; the machine profile gives it as `\"$P_ISTEST\" = …` in `[system_variables]`".to_owned(),
            2
        )]
    );
    let (reported, _) = run("R1=$A_IN[3]\nM30\n");
    assert!(
        reported[0].2.contains("`\"$A_IN[3]\" = …`"),
        "{}",
        reported[0].2
    );
}

#[test]
fn the_profile_gives_the_values_the_run_cannot_know() {
    let profile = with_system_variables(
        "\"$P_ISTEST\" = true\n\"$A_IN\" = false\n\"$A_IN[3]\" = true\n\"$AA_MM[X]\" = 12.5\n\"$P_TOOLNO\" = 9\n",
    );
    let program = format!(
        "R1=$P_ISTEST\nR2=$A_IN[3]\nR3=$A_IN[4]\nR4=$AA_MM[X]\nR5=$P_TOOLNO\n{}M30\n",
        // The run answers `$P_TOOLNO` itself: the profile's entry does not
        // override it.
        checks(&["1", "1", "0", "12.5", "0"])
    );
    runs_clean(run_on(profile, &program));
}

#[test]
fn tool_data_a_program_writes_reads_back() {
    let program = format!(
        "$TC_DP1[1,1]=120\n$TC_DP3[1,1]=50.5\n$TC_DP6[1,1]=4\n$TC_DP2[1,1]=3\n$TC_TPG5[7]=12.5\nR1=$TC_DP1[1,1]\nR2=$TC_DP3[1,1]\nR3=$TC_DP6[1,1]\nR4=$TC_DP2[1,1]\nR5=$TC_TPG5[7]\nR6=$TC_DP4[1,1]\n$TC_DP3[7,1]=70\nR7=$TC_DP3[7,1]\n{}M30\n",
        checks(&["120", "50.5", "4", "3", "12.5", "0", "70"])
    );
    runs_clean(run_on(with_named_tools(), &program));
}

#[test]
fn a_written_tool_length_takes_effect_at_the_next_d_selection() {
    // T7 D1 is 80 long in the profile; the program makes it 100.
    let program = format!(
        "T7 M6 D1\nG0 Z0\nR1=$AA_IM[Z]\n$TC_DP3[7,1]=100\nG0 Z1\nR2=$AA_IM[Z]\nD1\nG0 Z0\nR3=$AA_IM[Z]\n{}M30\n",
        checks(&["80", "81", "100"])
    );
    runs_clean(run_on(with_named_tools(), &program));
    // On a machine without a tool table the write makes the tool's edge.
    let program = format!(
        "$TC_DP3[9,1]=30\nT9 M6 D1\nG0 Z0\nR1=$AA_IM[Z]\n{}M30\n",
        checks(&["30"])
    );
    runs_clean(run(&program));
}

#[test]
fn tool_types_and_edge_positions_are_checked_when_written() {
    let (reported, end) = run("$TC_DP1[1,1]=42\nM30\n");
    assert_eq!(end, ProgramEndReason::Alarm);
    assert_eq!(reported[0].2, "`$TC_DP1[1,1]=42`: a tool type is 100…999");
    let (reported, _) = run("$TC_DP2[1,1]=12\nM30\n");
    assert_eq!(
        reported[0].2,
        "`$TC_DP2[1,1]=12`: a cutting edge position is 0…9"
    );
}

#[test]
fn tool_data_needs_tools_and_edges_numbered_from_one() {
    let (reported, end) = run("$TC_DP3[0,1]=5\nM30\n");
    assert_eq!(end, ProgramEndReason::Alarm);
    assert_eq!(reported[0].0, "gcodec::run::index_out_of_range");
    assert_eq!(
        reported[0].2,
        "`$TC_DP3[0,1]`: tools and cutting edges are numbered from 1"
    );
}

#[test]
fn isfile_asks_the_search_path() {
    let mut setup = RunSetup::new(gcodec_profile::builtin().expect("the built-in profile"));
    setup
        .search_dirs
        .push(concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/fixtures/run").into());
    let program = format!(
        "R1=ISFILE(\"DEEP\")\nR2=ISFILE(\"deep.spf\")\nR3=ISFILE(\"/_N_SPF_DIR/_N_DEEP_SPF\")\nR4=ISFILE(\"NO_SUCH_PROGRAM\")\n{}M30\n",
        checks(&["1", "1", "1", "0"])
    );
    let file = Arc::new(SourceFile::new("VOCAB.MPF", program));
    let mut sink = VecSink::new();
    let report = run_main(file, &setup, &mut sink, None);
    assert!(report.diagnostics.is_empty(), "{:?}", report.diagnostics);
    let ends: Vec<_> = sink
        .events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Diagnostic(d) => Some(d.message.to_string()),
            EventKind::ProgramEnd(end) => Some(format!("{:?}", end.reason)),
            _ => None,
        })
        .collect();
    assert_eq!(ends, ["M30"]);
}
