//! Work and memory that would grow faster than the program (issue 14):
//! computed spindles the machine lacks, a new tool in every pass, blocks
//! that each cost millions of element operations, sections that nest
//! themselves and variables beyond the memory for them. Each test counts
//! what the run did — blocks, element operations, bytes, table entries —
//! and checks the run stops at the documented limit; none measures time.

use std::sync::Arc;

use gcodec_driver::{Definitions, RunOptions, RunSetup, run_main};
use gcodec_exec::event::{DiagnosticEvent, Event, EventKind, ProgramEndReason, VecSink};
use gcodec_exec::vars::{Init, Scope, Variables};
use gcodec_lang::DataType;
use gcodec_profile::{DEFAULT_MAX_VARIABLE_MEMORY, Profile};
use gcodec_source::{Code, SourceFile, codes};

static BUILTIN: std::sync::LazyLock<Profile> =
    std::sync::LazyLock::new(|| gcodec_profile::builtin().expect("the built-in profile"));

/// The bytes of a `DEF REAL ARR[1024,1024]`: 2^20 elements of 24 bytes.
const BIG_ARRAY_BYTES: u64 = (1 << 20) * 24;

struct Ran {
    events: Vec<Event>,
    reason: ProgramEndReason,
    blocks: u64,
    tools: Vec<Option<String>>,
}

impl Ran {
    /// The only error diagnostic of the run, with where it was reported.
    fn alarm(&self) -> (&DiagnosticEvent, &Event) {
        let mut errors = self.events.iter().filter_map(|e| match &e.kind {
            EventKind::Diagnostic(d) if d.severity == gcodec_source::Severity::Error => {
                Some((d, e))
            }
            _ => None,
        });
        let first = errors.next().expect("an alarm");
        assert!(errors.next().is_none(), "one alarm");
        first
    }

    fn assert_alarm(&self, code: &'static Code, line: u32) -> &str {
        let (diagnostic, event) = self.alarm();
        assert_eq!(diagnostic.code, code, "{}", diagnostic.message);
        assert_eq!(event.source.line, line, "{}", diagnostic.message);
        &diagnostic.message
    }
}

fn run_with(program: &str, definitions: Definitions, options: impl FnOnce(&mut RunOptions)) -> Ran {
    let mut setup = RunSetup::new(Profile::clone(&BUILTIN));
    setup.definitions = Arc::new(definitions);
    options(&mut setup.options);
    let file = Arc::new(SourceFile::new("BUDGET.MPF", program));
    let mut sink = VecSink::new();
    let report = run_main(file, &setup, &mut sink, None);
    assert!(
        !report.diagnostics.iter().any(|d| d.is_error()),
        "{:#?}",
        report.diagnostics
    );
    let outcome = report.outcome.expect("events go to memory");
    Ran {
        reason: outcome.reason,
        blocks: outcome.summary.blocks,
        tools: outcome
            .summary
            .tools()
            .iter()
            .map(|t| t.tool.clone())
            .collect(),
        events: sink.events,
    }
}

fn run(program: &str) -> Ran {
    run_with(program, Definitions::new(), |_| {})
}

#[test]
fn a_computed_spindle_the_machine_lacks_stops_the_run_at_its_first_use() {
    // The built-in machine has spindle 1 only: the second pass names 2.
    for (word, line) in [("S[CNT]=100", 3), ("M[CNT]=3", 3), ("SPOS[CNT]=90", 3)] {
        let program =
            format!("DEF INT CNT\nN10 FOR CNT=1 TO 1000000\nN20 {word}\nN30 ENDFOR\nN40 M30\n");
        let ran = run(&program);
        let message = ran.assert_alarm(codes::run::UNKNOWN_SPINDLE, line);
        assert_eq!(message, "this machine has no spindle 2");
        assert_eq!(ran.reason, ProgramEndReason::Alarm);
        // DEF, FOR, the word, ENDFOR, the FOR's test, the word again.
        assert_eq!(ran.blocks, 6, "{word}");
    }
}

#[test]
fn extension_zero_is_the_master_spindle() {
    let ran = run("DEF INT CNT=0\nN10 S[CNT]=500 M[CNT]=3\nN20 M30\n");
    let spindles: Vec<u32> = ran
        .events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Spindle(s) => Some(s.spindle),
            _ => None,
        })
        .collect();
    assert_eq!(spindles, [1, 1]);
    assert_eq!(ran.reason, ProgramEndReason::M30);
}

#[test]
fn a_new_tool_in_every_pass_keeps_the_summary_in_the_order_first_used() {
    let program = "DEF INT CNT\nN10 FOR CNT=1 TO 3000\nN20 T=CNT\nN30 M6\nN40 ENDFOR\nN50 M30\n";
    let ran = run(program);
    assert_eq!(ran.reason, ProgramEndReason::M30);
    // No tool for the first blocks, then each of the 3000 once.
    assert_eq!(ran.tools.len(), 3001);
    assert_eq!(ran.tools[0], None);
    assert_eq!(ran.tools[1].as_deref(), Some("T1"));
    assert_eq!(ran.tools[3000].as_deref(), Some("T3000"));
}

#[test]
fn a_declaration_passed_again_and_again_draws_on_the_work_budget() {
    // Ten declarations of 2^20 elements fit a budget of ten and a half.
    let max_work = 10 * (1 << 20) + (1 << 19);
    let program = "LA: DEF REAL ARR[1024,1024]\nGOTOB LA\n";
    let ran = run_with(program, Definitions::new(), |o| o.max_work = max_work);
    let message = ran.assert_alarm(codes::run::WORK_LIMIT, 1);
    assert_eq!(
        message,
        "the run stopped before 1048576 more element operations: with the 10485760 done \
         they pass the work budget of 11010048 (--max-work)"
    );
    assert_eq!(ran.reason, ProgramEndReason::Limit);
    // Two blocks a pass; the eleventh `DEF` is block 21.
    assert_eq!(ran.blocks, 21);
}

#[test]
fn a_fill_of_a_whole_array_in_a_loop_draws_on_the_work_budget() {
    let program = "DEF REAL ARR[1024,1024]\nN10 LOOP\nN20 ARR[0,0]=REP(1)\nN30 ENDLOOP\n";
    // The declaration's 2^20 and five fills of 2^20.
    let ran = run_with(program, Definitions::new(), |o| o.max_work = 6 << 20);
    let message = ran.assert_alarm(codes::run::WORK_LIMIT, 3);
    assert!(message.contains("with the 6291456 done"), "{message}");
    // DEF, LOOP, then fill, ENDLOOP and LOOP five times, the sixth fill.
    assert_eq!(ran.blocks, 18);
    // The default budget leaves the step limit to end the same loop.
    let ran = run_with(program, Definitions::new(), |o| o.max_steps = 100);
    assert_eq!(ran.reason, ProgramEndReason::Limit);
    ran.assert_alarm(codes::run::STEP_LIMIT, 2);
}

#[test]
fn a_section_that_nests_itself_stops_at_the_programs_levels() {
    // `REPEAT LA LB` in the block labelled LB: each pass runs the REPEAT
    // again. Levels 1…15 open, the sixteenth is the alarm.
    let ran = run("LA: R1=R1+1\nLB: REPEAT LA LB P=3\nM30\n");
    let message = ran.assert_alarm(codes::run::CALL_DEPTH, 2);
    assert_eq!(
        message,
        "the section `LA` would open program level 16: the control has 16 \
         (the main program is level 0)"
    );
    assert_eq!(ran.blocks, 32);
    let ran = run("LA: R1=R1+1\nLB: CALL BLOCK LA TO LB\nM30\n");
    let message = ran.assert_alarm(codes::run::CALL_DEPTH, 2);
    assert!(message.starts_with("the section `BUDGET`"), "{message}");
    assert_eq!(ran.blocks, 32);
}

/// `DEF REAL AA1[1024,1024]` … `AA<count>`, one a line.
fn big_declarations(count: usize) -> String {
    (1..=count)
        .map(|n| format!("DEF REAL AA{n}[1024,1024]\n"))
        .collect()
}

#[test]
fn declarations_past_the_memory_for_variables_stop_at_the_one_that_does_not_fit() {
    // 256 MiB hold ten arrays of 24 MiB: the eleventh does not fit.
    assert_eq!(DEFAULT_MAX_VARIABLE_MEMORY, 256 << 20);
    let ran = run(&format!("{}M30\n", big_declarations(400)));
    let message = ran.assert_alarm(codes::run::VARIABLE_MEMORY, 11);
    assert_eq!(
        message,
        format!(
            "`AA11` needs {BIG_ARRAY_BYTES} bytes, and {} of the {DEFAULT_MAX_VARIABLE_MEMORY} \
             bytes for variables are in use (the profile's `[program] max_variable_memory`)",
            10 * BIG_ARRAY_BYTES
        )
    );
    assert_eq!(ran.reason, ProgramEndReason::Alarm);
    assert_eq!(ran.blocks, 11);
}

#[test]
fn global_data_past_the_memory_for_variables_is_reported_at_its_definition() {
    let (definitions, diagnostics) =
        Definitions::from_source("MGUD.DEF", &format!("{}M30\n", big_declarations(400)));
    assert!(diagnostics.is_empty(), "{diagnostics:#?}");
    let ran = run_with("N10 R1=1\nM30\n", definitions, |_| {});
    let (diagnostic, event) = ran.alarm();
    assert_eq!(diagnostic.code, codes::run::VARIABLE_MEMORY);
    assert!(
        diagnostic.message.starts_with("`AA11` needs"),
        "{}",
        diagnostic.message
    );
    assert_eq!(&*event.source.file, "MGUD.DEF");
    assert_eq!((event.source.line, event.source.col), (11, 10));
    // The run does not start.
    assert_eq!(ran.blocks, 0);
    assert_eq!(ran.reason, ProgramEndReason::Alarm);
}

#[test]
fn the_variables_of_a_level_give_their_memory_back() {
    let mut vars = Variables::default();
    let declare = |vars: &mut Variables, name: &str| {
        vars.declare(
            Scope::Local,
            name,
            DataType::Real,
            &[1024, 1024],
            Init::None,
        )
    };
    for _ in 0..100 {
        vars.push_level();
        declare(&mut vars, "A").expect("fits");
        assert_eq!(vars.memory_used(), BIG_ARRAY_BYTES);
        vars.pop_level();
        assert_eq!(vars.memory_used(), 0);
    }
    // A declaration again of the same name replaces the variable.
    for _ in 0..100 {
        declare(&mut vars, "A").expect("fits");
    }
    assert_eq!(vars.memory_used(), BIG_ARRAY_BYTES);
    assert_eq!(vars.work_done(), 200 << 20);
    // A STRING[n] element counts its n characters too.
    vars.declare(
        Scope::Local,
        "S",
        DataType::String { length: Some(100) },
        &[10],
        Init::None,
    )
    .expect("fits");
    assert_eq!(vars.memory_used(), BIG_ARRAY_BYTES + 10 * (24 + 100));
}

#[test]
fn memory_is_checked_before_it_is_taken() {
    let mut vars = Variables::default().with_budgets(u64::MAX, 1000);
    let error = vars
        .declare(Scope::Local, "A", DataType::Real, &[1024, 1024], Init::None)
        .expect_err("too large");
    assert_eq!(error.code, codes::run::VARIABLE_MEMORY);
    assert_eq!(vars.memory_used(), 0);
    assert!(!vars.is_defined("A"));
}
