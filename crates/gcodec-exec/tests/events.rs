//! Runtime events: the checked-in schema is current, every kind reads and
//! writes with the contract's field names (the tool-change, M-function and
//! work-offset designs), and the
//! sinks and the CSV writer write what SPEC §11.x says.

use std::borrow::Cow;
use std::sync::Arc;

use gcodec_exec::event::*;
use gcodec_lang::WorkOffsetCode;
use gcodec_source::{Severity, codes};
use serde_json::{Value as Json, json};

/// Fails when `docs/schema/events.schema.json` is stale.
#[test]
fn the_checked_in_schema_is_current() {
    gcodec_testkit::assert_schema_current(
        "events.schema.json",
        &events_json_schema(),
        "cargo test -p gcodec-exec --test events",
    );
}

fn source(line: u32, level: u32) -> EventSource {
    EventSource {
        file: Arc::from("part.mpf"),
        line,
        col: 1,
        level,
    }
}

fn event(line: u32, kind: EventKind) -> Event {
    Event {
        kind,
        source: source(line, 0),
    }
}

/// Serialises one event, checks it reads back equal, returns the JSON.
fn round_trip(event: &Event) -> Json {
    let value = serde_json::to_value(event).expect("serialises");
    let back: Event = serde_json::from_value(value.clone()).expect("reads back");
    assert_eq!(&back, event);
    let text = serde_json::to_string(event).expect("serialises");
    let back: Event = serde_json::from_str(&text).expect("reads back from text");
    assert_eq!(&back, event);
    value
}

fn linear_motion() -> MotionEvent {
    MotionEvent {
        motion: MotionKind::Linear,
        from: AxisMap::from([("X", 0.0), ("Y", 0.0), ("Z", 5.0)]),
        to: AxisMap::from([("X", 10.0), ("Y", 5.5), ("Z", 5.0)]),
        to_machine: AxisMap::from([("X", 110.0), ("Y", 55.5), ("Z", -195.0)]),
        centre: None,
        radius: None,
        turns: 0,
        feed: Some(200.0),
        feed_mode: Cow::Borrowed("G94"),
        plane: Plane::G17,
        work_offset: WorkOffsetContext::new(WorkOffsetCode::G54, None),
        inserted: None,
        tool: None,
    }
}

fn arc_motion() -> MotionEvent {
    MotionEvent {
        motion: MotionKind::ArcCw,
        from: AxisMap::from([("X", 10.0), ("Y", 5.5), ("Z", 5.0)]),
        to: AxisMap::from([("X", 20.0), ("Y", 15.5), ("Z", 5.0)]),
        to_machine: AxisMap::from([("X", 20.0), ("Y", 15.5), ("Z", 5.0)]),
        centre: Some(AxisMap::from([("X", 20.0), ("Y", 5.5)])),
        radius: Some(10.0),
        turns: 0,
        feed: Some(150.0 / 7.0),
        feed_mode: Cow::Borrowed("G94"),
        plane: Plane::G17,
        work_offset: WorkOffsetContext::new(WorkOffsetCode::G54, Some(Suppression::G53)),
        // A transition circle of compensation: the contour stays at the
        // corner, the tool centre goes round it.
        inserted: Some(InsertedElement::TransitionCircle),
        tool: Some(Box::new(ToolCentre {
            tool_to: AxisMap::from([("X", 24.0), ("Y", 15.5), ("Z", 5.0)]),
            tool_to_machine: AxisMap::from([("X", 24.0), ("Y", 15.5), ("Z", 5.0)]),
            tool_radius: 4.0,
            tool_arc: Some(ToolArc {
                motion: MotionKind::ArcCw,
                centre: AxisMap::from([("X", 20.0), ("Y", 15.5)]),
                radius: 4.0,
            }),
        })),
    }
}

/// One event of every kind, in the order a run might produce them.
fn every_kind() -> Vec<Event> {
    vec![
        event(
            3,
            EventKind::ModalChange(ModalChangeEvent {
                group: 8,
                code: "G54".into(),
                previous: Some("G500".into()),
            }),
        ),
        event(
            4,
            EventKind::ToolSelect(ToolSelectEvent {
                selector_kind: SelectorKind::Number,
                selector_value: "7".into(),
                selected_tool: Some("T7".into()),
                spindle_extension: None,
                timing: ToolTiming::DeferredUntilM6,
            }),
        ),
        event(
            5,
            EventKind::MFunction(MFunctionEvent {
                m_value: 6,
                address_extension: None,
                class: MClass::Tool,
                phase: MTiming::InBlock,
                action: MAction::ToolChange,
            }),
        ),
        event(
            5,
            EventKind::ToolChange(ToolChangeEvent {
                previous_tool: Some("T12".into()),
                new_tool: Some("T7".into()),
                selection_source: SelectionSource::PendingThenM6,
                substituted: false,
                trigger: ToolChangeTrigger::M6,
                committed: true,
                fault_reason: None,
            }),
        ),
        event(
            6,
            EventKind::Spindle(SpindleEvent {
                spindle: 1,
                state: SpindleState::Cw,
                speed: 1200.0,
                position: None,
            }),
        ),
        event(
            6,
            EventKind::HFunction(HFunctionEvent {
                h_value: 2.5,
                address_extension: Some(2),
                quick: false,
                phase: MTiming::InBlock,
            }),
        ),
        event(7, EventKind::Motion(linear_motion())),
        event(8, EventKind::Motion(arc_motion())),
        event(
            9,
            EventKind::Dwell(DwellEvent {
                seconds: Some(1.5),
                revolutions: None,
            }),
        ),
        event(
            10,
            EventKind::Message(MessageEvent {
                text: "roughing \"pass\" 1".into(),
            }),
        ),
        event(
            11,
            EventKind::Call(CallEvent {
                target: "L123".into(),
                call_kind: CallKind::Program,
                pass: 1,
                passes: 2,
                section: None,
                arguments: vec![
                    Some(ArgumentValue::Number(10.0)),
                    None,
                    Some(ArgumentValue::Text("X".into())),
                ],
            }),
        ),
        Event {
            kind: EventKind::Return(ReturnEvent {
                target: "L123".into(),
            }),
            source: EventSource {
                file: Arc::from("L123.SPF"),
                line: 4,
                col: 1,
                level: 1,
            },
        },
        event(
            12,
            EventKind::Stop(StopEvent {
                reason: StopReason::PreprocessingStop,
                detail: Some("STOPRE".into()),
            }),
        ),
        event(
            13,
            EventKind::Diagnostic(DiagnosticEvent {
                code: codes::run::JUMP_TARGET_NOT_FOUND,
                severity: Severity::Error,
                message: "jump target `END` not found".into(),
                alarm: Some(14080),
                help: None,
            }),
        ),
        event(
            14,
            EventKind::MFunction(MFunctionEvent {
                m_value: 30,
                address_extension: None,
                class: MClass::ProgramFlow,
                phase: MTiming::PostMotion,
                action: MAction::ProgramEnd,
            }),
        ),
        event(
            14,
            EventKind::ProgramEnd(ProgramEndEvent {
                reason: ProgramEndReason::M30,
                blocks: 14,
            }),
        ),
        event(
            3,
            EventKind::Interrupt(InterruptEvent {
                input: 3,
                change: InterruptChange::Assigned,
                routine: Some("LIFT_Z".into()),
                priority: Some(1),
                lift_fast: false,
                block_sync: false,
                enabled: true,
            }),
        ),
        // The newest kinds, last: the tests above pick the others by place.
        event(
            5,
            EventKind::Toolchanger(ToolchangerEvent {
                tool: Some("T7".into()),
                pocket: Some(7),
                ..ToolchangerEvent::new(
                    ToolchangerEdge::ChangeCommitted,
                    gcodec_exec::toolchanger::ChangerState::Idle,
                    12,
                )
            }),
        ),
        event(
            5,
            EventKind::Toolchanger(ToolchangerEvent {
                fault_reason: Some(-5),
                ..ToolchangerEvent::new(
                    ToolchangerEdge::FaultLatched,
                    gcodec_exec::toolchanger::ChangerState::Preparing,
                    13,
                )
            }),
        ),
        event(
            5,
            EventKind::Toolchanger(ToolchangerEvent {
                abort_reason: Some(gcodec_exec::toolchanger::AbortReason::MOTION_OR_IO_ERROR),
                ..ToolchangerEvent::new(
                    ToolchangerEdge::AbortRaised,
                    gcodec_exec::toolchanger::ChangerState::WaitingForAbortAck,
                    15,
                )
            }),
        ),
    ]
}

#[test]
fn every_kind_round_trips_and_names_itself() {
    let events = every_kind();
    let mut kinds: Vec<&str> = Vec::new();
    for event in &events {
        let value = round_trip(event);
        assert_eq!(value["event"], event.kind_name());
        assert_eq!(value["source"]["file"], *event.source.file);
        assert_eq!(value["source"]["line"], event.source.line);
        assert_eq!(value["source"]["col"], 1);
        assert_eq!(value["source"]["level"], event.source.level);
        if !kinds.contains(&event.kind_name()) {
            kinds.push(event.kind_name());
        }
    }
    // Every kind the schema knows is covered.
    kinds.sort_unstable();
    let mut all = EVENT_KINDS.to_vec();
    all.sort_unstable();
    assert_eq!(kinds, all);
}

#[test]
fn tool_change_has_the_tool_change_design_fields() {
    let value = round_trip(&every_kind()[3]);
    assert_eq!(
        value,
        json!({
            "event": "tool_change",
            "previous_tool": "T12",
            "new_tool": "T7",
            "selection_source": "pending_then_m6",
            "substituted": false,
            "trigger": "m6",
            "committed": true,
            "source": {"file": "part.mpf", "line": 5, "col": 1, "level": 0}
        })
    );
}

#[test]
fn toolchanger_has_the_edge_fields_and_leaves_out_what_does_not_apply() {
    let events = every_kind();
    let n = events.len();
    assert_eq!(
        round_trip(&events[n - 3]),
        json!({
            "event": "toolchanger",
            "edge": "change_committed",
            "state": "idle",
            "cycle": 12,
            "tool": "T7",
            "pocket": 7,
            "source": {"file": "part.mpf", "line": 5, "col": 1, "level": 0}
        })
    );
    let fault = round_trip(&events[n - 2]);
    assert_eq!(fault["fault_reason"], -5);
    assert_eq!(fault["state"], "preparing");
    assert!(fault.get("tool").is_none() && fault.get("abort_reason").is_none());
    let abort = round_trip(&events[n - 1]);
    assert_eq!(abort["abort_reason"], 3);
    assert_eq!(abort["state"], "waiting_for_abort_ack");
}

#[test]
fn the_text_trace_names_toolchanger_reasons_in_words() {
    let events = every_kind();
    let n = events.len();
    let line = |event: &Event| {
        let mut text = String::new();
        write_trace_line(&mut text, event).expect("writes");
        text
    };
    assert_eq!(
        line(&events[n - 2]),
        "5:1 [0] toolchanger: fault latched (reason -5, hard): the next change aborts [preparing, cycle 13]\n"
    );
    assert_eq!(
        line(&events[n - 1]),
        "5:1 [0] toolchanger: abort raised (reason 3: motion or toolchanger reported an error) [waiting_for_abort_ack, cycle 15]\n"
    );
}

#[test]
fn tool_select_has_the_seed_000_selector() {
    let value = round_trip(&every_kind()[1]);
    assert_eq!(value["event"], "tool_select");
    assert_eq!(value["selector_kind"], "number");
    assert_eq!(value["selector_value"], "7");
    assert_eq!(value["selected_tool"], "T7");
    assert_eq!(value["timing"], "deferred_until_m6");
    assert_eq!(value["spindle_extension"], Json::Null);
}

#[test]
fn m_function_has_the_seed_001_fields() {
    let value = round_trip(&every_kind()[14]);
    assert_eq!(
        value,
        json!({
            "event": "m_function",
            "m_value": 30,
            "address_extension": null,
            "class": "program_flow",
            "phase": "post_motion",
            "action": "program_end",
            "source": {"file": "part.mpf", "line": 14, "col": 1, "level": 0}
        })
    );
}

#[test]
fn motion_has_the_seed_003_work_offset_context() {
    let value = round_trip(&event(8, EventKind::Motion(arc_motion())));
    assert_eq!(value["event"], "motion");
    assert_eq!(value["motion"], "arc_cw");
    assert_eq!(value["effective_work_offset_selected"], "g54");
    assert_eq!(value["effective_work_offset_enabled"], false);
    assert_eq!(
        value["effective_suppression_mask"],
        "suppress_settable_and_programmable"
    );
    assert_eq!(value["centre"], json!({"X": 20.0, "Y": 5.5}));
    assert_eq!(value["radius"], 10.0);
    assert_eq!(value["plane"], "G17");
    assert_eq!(value["feed_mode"], "G94");
}

#[test]
fn a_linear_motion_is_compact_and_keeps_the_axis_order() {
    let motion = event(7, EventKind::Motion(linear_motion()));
    let value = round_trip(&motion);
    assert_eq!(
        value,
        json!({
            "event": "motion",
            "motion": "linear",
            "from": {"X": 0.0, "Y": 0.0, "Z": 5.0},
            "to": {"X": 10.0, "Y": 5.5, "Z": 5.0},
            "to_machine": {"X": 110.0, "Y": 55.5, "Z": -195.0},
            "feed": 200.0,
            "feed_mode": "G94",
            "plane": "G17",
            "effective_work_offset_selected": "g54",
            "effective_work_offset_enabled": true,
            "effective_suppression_mask": "none",
            "source": {"file": "part.mpf", "line": 7, "col": 1, "level": 0}
        })
    );
    // serde_json's map sorts keys; the text keeps the program's order.
    let mut reversed = linear_motion();
    reversed.to = AxisMap::from([("Z", 1.0), ("A", 2.0), ("X", 3.0)]);
    let text = serde_json::to_string(&event(7, EventKind::Motion(reversed))).expect("serialises");
    assert!(text.contains(r#""to":{"Z":1.0,"A":2.0,"X":3.0}"#), "{text}");
    let back: Event = serde_json::from_str(&text).expect("reads back");
    let EventKind::Motion(back) = back.kind else {
        panic!("not a motion")
    };
    let order: Vec<&str> = back.to.iter().map(|(axis, _)| axis).collect();
    assert_eq!(order, ["Z", "A", "X"]);
}

#[test]
fn work_offset_context_follows_seed_003() {
    let plain = WorkOffsetContext::new(WorkOffsetCode(505), None);
    assert!(plain.effective_work_offset_enabled);
    assert_eq!(plain.effective_suppression_mask, SuppressionMask::None);
    // G500 deactivates the settable offset; suppression keeps the
    // selection.
    assert!(!WorkOffsetContext::new(WorkOffsetCode::G500, None).effective_work_offset_enabled);
    let supa = WorkOffsetContext::new(WorkOffsetCode::G54, Some(Suppression::Supa));
    assert_eq!(supa.effective_work_offset_selected, WorkOffsetCode::G54);
    assert!(!supa.effective_work_offset_enabled);
    let names: Vec<Json> = [
        None,
        Some(Suppression::G53),
        Some(Suppression::G153),
        Some(Suppression::Supa),
    ]
    .into_iter()
    .map(|s| serde_json::to_value(SuppressionMask::from(s)).expect("serialises"))
    .collect();
    assert_eq!(
        names,
        [
            "none",
            "suppress_settable_and_programmable",
            "suppress_settable_programmable_and_basic",
            "suppress_settable_programmable_basic_and_external",
        ]
    );
    assert_eq!(WorkOffsetCode::parse("G505"), Some(WorkOffsetCode(505)));
    assert_eq!(WorkOffsetCode::parse("g54"), Some(WorkOffsetCode::G54));
    assert_eq!(WorkOffsetCode::parse("G"), None);
    assert_eq!(WorkOffsetCode::parse("G+5"), None);
    assert_eq!(WorkOffsetCode::parse("SUPA"), None);
    assert!(serde_json::from_value::<WorkOffsetCode>(json!("g5x")).is_err());
}

#[test]
fn optional_fields_are_left_out_when_absent() {
    let value = round_trip(&event(7, EventKind::Motion(linear_motion())));
    for field in [
        "centre",
        "radius",
        "turns",
        "inserted",
        "tool_to",
        "tool_to_machine",
        "tool_radius",
    ] {
        assert!(value.get(field).is_none(), "{field} present: {value}");
    }
    let rapid = MotionEvent {
        motion: MotionKind::Rapid,
        feed: None,
        ..linear_motion()
    };
    let value = round_trip(&event(7, EventKind::Motion(rapid)));
    assert_eq!(value["feed"], Json::Null);
    let value = round_trip(&every_kind()[13]);
    assert_eq!(value["alarm"], 14080);
    assert!(value.get("help").is_none());
}

#[test]
fn axis_maps_update_in_place() {
    let mut map = AxisMap::from([("X", 1.0), ("Y", 2.0)]);
    assert!(map.update("Y", 3.0));
    assert!(!map.update("Z", 4.0));
    map.insert(Cow::Owned("C1".to_owned()), 90.0);
    map.insert(Cow::Borrowed("X"), 5.0);
    assert_eq!(map.get("X"), Some(5.0));
    assert_eq!(map.get("Y"), Some(3.0));
    assert_eq!(map.get("C1"), Some(90.0));
    assert_eq!(map.len(), 3);
    let mut copy = AxisMap::from([("A", 0.0)]);
    copy.copy_from(&map);
    assert_eq!(copy, map);
    for value in copy.values_mut() {
        *value = 0.0;
    }
    assert_eq!(copy.get("C1"), Some(0.0));
    copy.clear();
    assert!(copy.is_empty());
}

#[test]
fn jsonl_writes_one_object_a_line() {
    let events = every_kind();
    let mut sink = JsonlSink::new(Vec::new());
    for event in &events {
        sink.event(event).expect("writes");
    }
    sink.finish().expect("flushes");
    let bytes = sink.into_inner().expect("flushes");
    let text = String::from_utf8(bytes).expect("UTF-8");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), events.len());
    assert!(text.ends_with('\n'));
    for (line, event) in lines.iter().zip(&events) {
        let back: Event = serde_json::from_str(line).expect("each line is an event");
        assert_eq!(&back, event);
    }
    insta::assert_snapshot!("jsonl", text);
}

#[test]
fn the_text_trace_is_stable() {
    let mut sink = TextSink::new(Vec::new());
    for event in &every_kind() {
        sink.event(event).expect("writes");
    }
    let text = String::from_utf8(sink.into_inner().expect("flushes")).expect("UTF-8");
    assert_eq!(text.lines().count(), every_kind().len());
    insta::assert_snapshot!("text_trace", text);
}

#[test]
fn the_text_trace_rounds_numbers_for_reading() {
    let mut motion = linear_motion();
    motion.to = AxisMap::from([("X", 1.0 / 3.0), ("Y", -0.00001), ("Z", -2.5)]);
    motion.feed = Some(1e20);
    let mut line = String::new();
    write_trace_line(&mut line, &event(7, EventKind::Motion(motion))).expect("writes");
    assert!(
        line.starts_with("7:1 [0] motion linear X0.3333 Y0 Z-2.5 F1e20 G94"),
        "{line}"
    );
}

#[test]
fn sinks_compose_and_count() {
    let events = every_kind();
    let mut counting = CountingSink::new();
    let mut kept = VecSink::new();
    {
        let mut sinks: Vec<Box<dyn EventSink>> = vec![Box::new(&mut counting), Box::new(&mut kept)];
        for event in &events {
            for sink in &mut sinks {
                sink.event(event).expect("counts");
            }
        }
        for sink in &mut sinks {
            sink.finish().expect("finishes");
        }
    }
    assert_eq!(counting.total(), events.len() as u64);
    assert_eq!(counting.count("motion"), 2);
    assert_eq!(counting.count("m_function"), 2);
    assert_eq!(counting.count("no_such_kind"), 0);
    assert_eq!(kept.events, events);
}

fn row() -> BlockRow {
    let mut row = BlockRow {
        block_number: Some(20),
        file: Arc::from("part.mpf"),
        line: 7,
        level: 0,
        blocks: 3,
        moved: true,
        positions: AxisMap::from([("X", 10.0), ("Y", 5.5), ("Z", 0.1)]),
        tool: Some("T7".into()),
        edge: 1,
        feed: 200.0,
        spindle_speed: 1200.0,
        spindle: SpindleState::Cw,
        ..BlockRow::default()
    };
    for (group, code) in [
        (1, "G1"),
        (6, "G17"),
        (7, "G40"),
        (8, "G54"),
        (10, "G64"),
        (13, "G71"),
        (14, "G90"),
        (15, "G94"),
    ] {
        assert!(row.set_modal(group, Cow::Borrowed(code)));
    }
    assert!(!row.set_modal(2, Cow::Borrowed("G4")));
    row
}

#[test]
fn csv_has_a_header_and_one_row_per_block() {
    let axes = ["X", "Y", "Z", "A"].map(Cow::Borrowed);
    let mut csv = CsvWriter::new(Vec::new(), axes).expect("header");
    csv.row(&row()).expect("row");
    let mut unnumbered = row();
    unnumbered.block_number = None;
    unnumbered.tool = Some("DRILL,10 \"long\"".into());
    unnumbered.edge = 0;
    unnumbered.spindle = SpindleState::Stopped;
    unnumbered.line = 8;
    unnumbered.blocks = 4;
    csv.row(&unnumbered).expect("row");
    csv.finish().expect("flushes");
    let text = String::from_utf8(csv.into_inner().expect("flushes")).expect("UTF-8");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines,
        [
            "block,file,line,level,blocks,X,Y,Z,A,tool,edge,feed,spindle_speed,spindle,\
             motion,plane,radius_compensation,work_offset,path_mode,units,dimensions,feed_mode",
            "20,part.mpf,7,0,3,10,5.5,0.1,,T7,1,200,1200,cw,G1,G17,G40,G54,G64,G71,G90,G94",
            ",part.mpf,8,0,4,10,5.5,0.1,,\"DRILL,10 \"\"long\"\"\",0,200,1200,stopped,\
             G1,G17,G40,G54,G64,G71,G90,G94",
        ]
    );
}

/// The rows of `blocks` as `CsvRows` selects them, by line number.
fn csv_lines_written(rows: CsvRows, blocks: &[BlockRow]) -> Vec<u32> {
    let mut csv = CsvWriter::new(Vec::new(), [Cow::Borrowed("X")])
        .expect("header")
        .with_rows(rows);
    for block in blocks {
        csv.row(block).expect("row");
    }
    let text = String::from_utf8(csv.into_inner().expect("flushes")).expect("UTF-8");
    text.lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .nth(2)
                .and_then(|n| n.parse().ok())
                .expect("line")
        })
        .collect()
}

#[test]
fn csv_rows_are_written_for_motions_changes_and_the_last_block() {
    // A loop's blocks: line 1 moves, 2 computes, 3 and 4 are its WHILE
    // and ENDWHILE, 5 starts the spindle, 6 computes, 7 computes and is
    // the last.
    let block = |line: u32, moved: bool| BlockRow {
        line,
        blocks: u64::from(line),
        moved,
        ..row()
    };
    let mut spindle_on = block(5, false);
    spindle_on.spindle = SpindleState::Ccw;
    let mut after = block(6, false);
    after.spindle = SpindleState::Ccw;
    let mut last = block(7, false);
    last.spindle = SpindleState::Ccw;
    let blocks = [
        block(1, true),
        block(2, false),
        block(3, false),
        block(4, false),
        spindle_on,
        after,
        last,
    ];
    assert_eq!(csv_lines_written(CsvRows::Changes, &blocks), [1, 5, 7]);
    assert_eq!(
        csv_lines_written(CsvRows::EveryBlock, &blocks),
        [1, 2, 3, 4, 5, 6, 7]
    );
    // The first block has no row before it; a run whose last block is
    // written writes it once.
    assert_eq!(
        csv_lines_written(CsvRows::Changes, &[block(1, false), block(2, true)]),
        [1, 2]
    );
    // A position written otherwise (`-0` against `0`) is a change.
    let mut negative_zero = block(2, false);
    negative_zero.positions = AxisMap::from([("X", -0.0)]);
    let mut zero = block(1, false);
    zero.positions = AxisMap::from([("X", 0.0)]);
    assert_eq!(
        csv_lines_written(CsvRows::Changes, &[zero, negative_zero, block(3, true)]),
        [1, 2, 3]
    );
}

/// The text of `blocks` as `CsvRows` selects them, header left out.
fn csv_rows(rows: CsvRows, blocks: &[BlockRow]) -> Vec<String> {
    let mut csv = CsvWriter::new(Vec::new(), [Cow::Borrowed("X"), Cow::Borrowed("Y")])
        .expect("header")
        .with_rows(rows);
    for block in blocks {
        csv.row(block).expect("row");
    }
    let text = String::from_utf8(csv.into_inner().expect("flushes")).expect("UTF-8");
    text.lines().skip(1).map(str::to_owned).collect()
}

/// A last block passed over is written at the end with its own number,
/// file, line, level and count, and the state columns of the last row
/// written, which were its own: the row the every-block trace has.
#[test]
fn a_passed_over_last_block_is_written_as_the_trace_writes_it() {
    let mut first = row();
    first.positions = AxisMap::from([("X", 1.5), ("Y", -0.0)]);
    let mut computes = first.clone();
    computes.moved = false;
    computes.block_number = None;
    computes.line = 8;
    computes.blocks = 4;
    let mut called = computes.clone();
    called.file = Arc::from("sub, with a comma.spf");
    called.block_number = Some(130);
    called.line = 2;
    called.level = 1;
    called.blocks = 5;
    let blocks = [first, computes, called];
    let changes = csv_rows(CsvRows::Changes, &blocks);
    let trace = csv_rows(CsvRows::EveryBlock, &blocks);
    assert_eq!(changes.len(), 2, "{changes:?}");
    assert_eq!(changes[0], trace[0]);
    assert_eq!(changes[1], trace[2]);
    assert!(
        changes[1].starts_with("130,\"sub, with a comma.spf\",2,1,5,1.5,-0,T7,"),
        "{}",
        changes[1]
    );
}

/// Each axis's cell follows its own value: an axis that did not move
/// keeps its text while another changes, and `-0` is written as such.
#[test]
fn csv_position_cells_follow_each_axis() {
    let at = |line: u32, x: f64, y: f64| BlockRow {
        line,
        blocks: u64::from(line),
        positions: AxisMap::from([("X", x), ("Y", y)]),
        ..row()
    };
    let cells: Vec<String> = csv_rows(
        CsvRows::Changes,
        &[
            at(1, 1.5, 2.0),
            at(2, 1.25, 2.0),
            at(3, 1.25, -0.0),
            at(4, 1.25, 0.0),
            at(5, 3.0, 0.0),
        ],
    )
    .iter()
    .map(|row| row.split(',').skip(5).take(2).collect::<Vec<_>>().join(" "))
    .collect();
    assert_eq!(cells, ["1.5 2", "1.25 2", "1.25 -0", "1.25 0", "3 0"]);
}

/// A modal command is compared by its text, whether the registry's or
/// owned: the same text is no change, another one is.
#[test]
fn csv_modal_columns_compare_static_and_owned_commands_by_text() {
    let block = |line: u32, motion: Cow<'static, str>| {
        let mut row = BlockRow {
            line,
            blocks: u64::from(line),
            moved: false,
            ..row()
        };
        row.set_modal(1, motion);
        row
    };
    let owned = |code: &str| Cow::Owned(code.to_owned());
    let blocks = [
        block(1, Cow::Borrowed("G1")),
        block(2, owned("G1")),
        block(3, owned("G0")),
        block(4, Cow::Borrowed("G0")),
        block(5, Cow::Borrowed("G2")),
        block(6, Cow::Borrowed("G2")),
    ];
    assert_eq!(csv_lines_written(CsvRows::Changes, &blocks), [1, 3, 5, 6]);
}

#[test]
fn a_diagnostic_is_written_with_its_code_s_name_level_and_alarm() {
    let diagnostic = DiagnosticEvent::new(codes::run::JUMP_TARGET_NOT_FOUND, "not found");
    assert_eq!(
        serde_json::to_value(&diagnostic).expect("serialises"),
        json!({
            "code": "gcodec::run::jump_target_not_found",
            "severity": "error",
            "message": "not found",
            "alarm": 14080,
        })
    );
    let warning = DiagnosticEvent::new(codes::run::NO_FEED, "no feed");
    assert_eq!(warning.severity, Severity::Warning);
    let json = serde_json::to_string(&warning).expect("serialises");
    let back: DiagnosticEvent = serde_json::from_str(&json).expect("reads back");
    assert_eq!(back, warning);
}

#[test]
fn a_motion_event_stays_small() {
    // Events are built on the stack for every block; the commonest must
    // not be boxed, and the rest must not make it bigger.
    assert!(
        std::mem::size_of::<Event>() <= 208,
        "{}",
        std::mem::size_of::<Event>()
    );
}

/// The values the hand-written motion JSON must write exactly as serde
/// does: whole, with few and many decimals, tiny, huge, negative, signed
/// zero, not finite, and a spread of pseudo-random ones.
fn awkward_numbers() -> Vec<f64> {
    let mut values = vec![
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.1,
        0.0001,
        0.00015,
        0.00001,
        1e-7,
        123.4567,
        -123.4567,
        999_999_999.999_9,
        1e9,
        1e9 + 0.5,
        123_456_789_012.5,
        1e15,
        1e16,
        1e17,
        1e300,
        5e-324,
        f64::MAX,
        1.0 / 3.0,
        2.0 / 3.0,
        0.3,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    for _ in 0..20_000 {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let digits = (state >> 33) as i64 % 2_000_000_000 - 1_000_000_000;
        let decimals = (state >> 20) % 7;
        values.push(digits as f64 / 10f64.powi(decimals as i32));
        values.push(f64::from_bits(state >> 2));
    }
    values
}

/// Writes `events` through a [`JsonlSink`] and checks every line against
/// serde's.
fn assert_written_as_serde_writes(events: &[Event]) {
    let mut sink = JsonlSink::new(Vec::new());
    let mut expected = String::new();
    for event in events {
        expected.push_str(&serde_json::to_string(event).expect("serialises"));
        expected.push('\n');
        sink.event(event).expect("writes");
    }
    let written = String::from_utf8(sink.into_inner().expect("flushes")).expect("UTF-8");
    for (line, (got, want)) in written.lines().zip(expected.lines()).enumerate() {
        assert_eq!(got, want, "line {line}");
    }
    assert_eq!(written, expected);
}

#[test]
fn hand_written_motion_json_is_what_serde_writes() {
    let mut events = Vec::new();
    let numbers = awkward_numbers();
    for (index, chunk) in numbers.chunks(3).enumerate() {
        let value = |i: usize| chunk.get(i).copied().unwrap_or(0.0);
        let mut motion = arc_motion();
        motion.to = AxisMap::from([("X", value(0)), ("Y", value(1)), ("Z", value(2))]);
        motion.radius = Some(value(1));
        motion.feed = (index % 2 == 0).then(|| value(2));
        motion.turns = (index % 3) as u32;
        motion.centre = (index % 4 != 0).then(|| AxisMap::from([("X", value(2))]));
        motion.from.insert(Cow::Owned("C\"1".into()), value(0));
        let source = EventSource {
            file: Arc::from(if index % 5 == 0 {
                "dir\\odd \"name\".mpf"
            } else {
                "part.mpf"
            }),
            line: index as u32,
            col: u32::MAX,
            level: 3,
        };
        let event = Event {
            kind: EventKind::Motion(motion),
            source,
        };
        events.push(event);
    }
    assert_written_as_serde_writes(&events);
}

/// The JSONL sink keeps the text of a motion's `from` and `to_machine`
/// apart from its `to` while a frame sets them apart: motions whose
/// `from` is the last `to`, a bit off it or another map, and whose
/// `to_machine` is their `to`, offset (values changing, staying, on other
/// axes), must still be written as serde writes each.
#[test]
fn machine_positions_apart_from_the_workpiece_are_written_as_serde_writes_them() {
    let numbers = awkward_numbers();
    let mut events = Vec::new();
    let mut last_to = AxisMap::from([("X", 0.0), ("Y", 0.0), ("Z", 5.0)]);
    for (index, chunk) in numbers.chunks(2).take(3_000).enumerate() {
        let (x, y) = (chunk[0], chunk.get(1).copied().unwrap_or(0.0));
        let mut motion = arc_motion();
        motion.centre = None;
        motion.radius = None;
        // The last `to`; the same with X a bit off (computed back from the
        // machine position under a frame); or a map of its own.
        motion.from = match index % 3 {
            0 => last_to.clone(),
            1 => {
                let mut off = AxisMap::from([("X", 0.0), ("Y", 0.0), ("Z", 5.0)]);
                for (axis, value) in last_to.iter() {
                    let value = if axis == "X" && value.is_finite() {
                        f64::from_bits(value.to_bits() ^ 1)
                    } else {
                        value
                    };
                    off.insert(Cow::Owned(axis.to_owned()), value);
                }
                off
            }
            _ => motion.from,
        };
        motion.to = AxisMap::from([("X", x), ("Y", y), ("Z", 5.0)]);
        last_to = motion.to.clone();
        motion.to_machine = match index % 4 {
            // No offset: the same map.
            0 => motion.to.clone(),
            // An offset on X and Y; Z stays.
            1 | 2 => AxisMap::from([("X", x - 412.5), ("Y", y - 20.0), ("Z", 5.0)]),
            // Another axis set.
            _ => AxisMap::from([("X", x - 412.5), ("Z", 0.0), ("B", y)]),
        };
        events.push(Event {
            kind: EventKind::Motion(motion),
            source: EventSource {
                file: Arc::from("part.mpf"),
                line: index as u32 + 1,
                col: 1,
                level: 0,
            },
        });
    }
    assert_written_as_serde_writes(&events);
}

/// The JSONL sink copies a motion's feed, plane and work-offset fields
/// from the last motion's text while they are the same: motions that now
/// keep them, now change one (the feed to `-0.0`, to none, the feed mode
/// to an owned text, the plane, the work offset) must still be written as
/// serde writes each.
#[test]
fn repeated_motion_settings_are_written_as_serde_writes_them() {
    let mut events = Vec::new();
    let settings: [(Option<f64>, Cow<'static, str>, Plane, WorkOffsetContext); 8] = [
        (
            Some(100.0),
            Cow::Borrowed("G94"),
            Plane::G17,
            WorkOffsetContext::new(WorkOffsetCode::G54, None),
        ),
        (
            Some(100.0),
            Cow::Borrowed("G94"),
            Plane::G17,
            WorkOffsetContext::new(WorkOffsetCode::G54, None),
        ),
        (
            Some(-0.0),
            Cow::Borrowed("G94"),
            Plane::G17,
            WorkOffsetContext::new(WorkOffsetCode::G54, None),
        ),
        (
            Some(0.0),
            Cow::Borrowed("G94"),
            Plane::G17,
            WorkOffsetContext::new(WorkOffsetCode::G54, None),
        ),
        (
            None,
            Cow::Borrowed("G94"),
            Plane::G17,
            WorkOffsetContext::new(WorkOffsetCode::G54, None),
        ),
        (
            None,
            Cow::Owned("G95".into()),
            Plane::G17,
            WorkOffsetContext::new(WorkOffsetCode::G54, None),
        ),
        (
            None,
            Cow::Owned("G95".into()),
            Plane::G18,
            WorkOffsetContext::new(WorkOffsetCode::G54, None),
        ),
        (
            None,
            Cow::Owned("G95".into()),
            Plane::G18,
            WorkOffsetContext::new(WorkOffsetCode::G54, Some(Suppression::G53)),
        ),
    ];
    for (index, (feed, feed_mode, plane, work_offset)) in settings.into_iter().enumerate() {
        let mut motion = arc_motion();
        motion.feed = feed;
        motion.feed_mode = feed_mode;
        motion.plane = plane;
        motion.work_offset = work_offset;
        let source = EventSource {
            file: Arc::from("part.mpf"),
            line: index as u32,
            col: 1,
            level: 0,
        };
        events.push(Event {
            kind: EventKind::Motion(motion),
            source,
        });
    }
    assert_written_as_serde_writes(&events);
}

/// The JSONL sink copies the text of a motion's `from` and `to_machine`
/// when they are the last `to`, of each axis of `to` whose value stays,
/// and of a file, column and level it just wrote: a run of motions whose
/// maps and sources are now the same, now not (another value, `-0.0` for
/// `0.0`, another axis, an owned or quoted name, another file, column or
/// level) must still be written exactly as serde writes each.
#[test]
fn repeated_maps_and_files_are_written_as_serde_writes_them() {
    let files = [
        Arc::<str>::from("part.mpf"),
        Arc::from("dir\\sub \"1\".spf"),
    ];
    let mut events = Vec::new();
    let mut to = AxisMap::from([("X", 0.0), ("Y", 1.5), ("Z", -2.0)]);
    let mut state: u64 = 7;
    for index in 0..2_000u32 {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let pick = |shift: u32, n: u64| (state >> shift) % n;
        let mut motion = arc_motion();
        motion.from = to.clone();
        if pick(10, 5) == 0 {
            motion.from.insert(Cow::Borrowed("Y"), 99.0);
        }
        let value = (state >> 20) as f64 / 1e4;
        let x = match pick(40, 4) {
            0 => 0.0,
            1 => -0.0,
            _ => value,
        };
        to = match pick(44, 7) {
            0 => AxisMap::from([("X", x), ("Y", 1.5)]),
            6 => AxisMap::from([("X", x), ("C\"1", 1.5), ("Z", -2.0)]),
            1 => {
                let mut map = AxisMap::from([("X", x), ("Y", 1.5)]);
                map.insert(Cow::Owned("Z".into()), -2.0);
                map
            }
            2 => AxisMap::from([("Y", 1.5), ("X", x), ("Z", -2.0)]),
            _ => AxisMap::from([("X", x), ("Y", 1.5), ("Z", -2.0)]),
        };
        motion.to = to.clone();
        motion.to_machine = to.clone();
        if pick(50, 3) == 0 {
            motion.to_machine.insert(Cow::Borrowed("X"), x + 100.0);
        }
        let event = Event {
            kind: EventKind::Motion(motion),
            source: EventSource {
                file: Arc::clone(&files[(pick(55, 7) == 0) as usize]),
                line: index,
                col: 1 + (pick(58, 5) == 0) as u32 * 10,
                level: (pick(61, 9) == 0) as u32,
            },
        };
        events.push(event);
    }
    assert_written_as_serde_writes(&events);
}

#[test]
fn hand_written_modal_change_json_is_what_serde_writes() {
    let mut events = Vec::new();
    let codes: [Cow<'static, str>; 4] = [
        Cow::Borrowed("G1"),
        Cow::Borrowed("DIAMON"),
        Cow::Owned("ODD \"CODE\"\\".into()),
        Cow::Owned("G\u{e4}\n".into()),
    ];
    for (index, code) in codes.iter().enumerate() {
        for previous in [None, Some(codes[(index + 1) % codes.len()].clone())] {
            let event = Event {
                kind: EventKind::ModalChange(ModalChangeEvent {
                    group: (index * 21) as u8,
                    code: code.clone(),
                    previous,
                }),
                source: EventSource {
                    file: Arc::from(if index % 2 == 0 {
                        "dir\\odd \"name\".mpf"
                    } else {
                        "part.mpf"
                    }),
                    line: u32::MAX - index as u32,
                    col: index as u32,
                    level: 2,
                },
            };
            events.push(event);
        }
    }
    assert_written_as_serde_writes(&events);
}

#[test]
fn csv_numbers_are_written_exactly() {
    let numbers = awkward_numbers();
    let mut csv = CsvWriter::new(Vec::new(), [Cow::Borrowed("X")]).expect("header");
    let mut row = row();
    for value in &numbers {
        row.positions = AxisMap::from([("X", *value)]);
        csv.row(&row).expect("row");
    }
    let text = String::from_utf8(csv.into_inner().expect("flushes")).expect("UTF-8");
    for (line, value) in text.lines().skip(1).zip(&numbers) {
        let cell = line.split(',').nth(5).unwrap_or("?");
        assert_eq!(cell, value.to_string(), "{line}");
        if value.is_finite() {
            assert_eq!(cell.parse::<f64>().ok(), Some(*value));
        }
    }
    assert_eq!(text.lines().count(), numbers.len() + 1);
}
