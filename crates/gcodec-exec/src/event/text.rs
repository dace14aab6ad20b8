//! `--format text`: [`TextSink`] and [`write_trace_line`], the readable
//! trace of one line an event.

use std::borrow::Cow;
use std::fmt;
use std::io::{self, BufWriter, Write};

use serde::Serialize;

use super::numbers::fraction_digits;
use super::{AxisMap, Event, EventKind, EventSink, ToolchangerEdge, ToolchangerEvent};
use crate::toolchanger::FaultReason;

/// `--format text`: a readable trace, one line an event:
/// `12:1 [0] motion linear X10 Y5 Z0 F200 G94 G17 g54 machine X110 …`.
///
/// Numbers are rounded to 4 decimals for reading; the exact values are in
/// `jsonl`.
pub struct TextSink<W: Write> {
    out: BufWriter<W>,
    /// The line being built, reused.
    line: String,
}

impl<W: Write> TextSink<W> {
    pub fn new(writer: W) -> Self {
        Self {
            out: BufWriter::with_capacity(1 << 16, writer),
            line: String::with_capacity(256),
        }
    }

    /// Flushes and gives the writer back.
    pub fn into_inner(self) -> io::Result<W> {
        self.out
            .into_inner()
            .map_err(io::IntoInnerError::into_error)
    }
}

impl<W: Write> EventSink for TextSink<W> {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        self.line.clear();
        // Formatting into a string fails only if a `Display` impl does,
        // and ours do not.
        write_trace_line(&mut self.line, event).map_err(io::Error::other)?;
        self.out.write_all(self.line.as_bytes())
    }

    fn finish(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

/// Writes one line of the text trace, newline included.
pub fn write_trace_line(out: &mut impl fmt::Write, event: &Event) -> fmt::Result {
    let source = &event.source;
    write!(
        out,
        "{}:{} [{}] {}",
        source.line,
        source.col,
        source.level,
        event.kind_name()
    )?;
    match &event.kind {
        EventKind::Motion(motion) => {
            write!(out, " {}", motion.motion.name())?;
            write_axes(out, &motion.to)?;
            if let Some(centre) = &motion.centre {
                write!(out, " centre")?;
                write_axes(out, centre)?;
            }
            if let Some(radius) = motion.radius {
                write!(out, " radius {}", Num(radius))?;
            }
            if motion.turns != 0 {
                write!(out, " turns {}", motion.turns)?;
            }
            match motion.feed {
                Some(feed) => write!(out, " F{} {}", Num(feed), motion.feed_mode)?,
                None => write!(out, " {}", motion.feed_mode)?,
            }
            let context = &motion.work_offset;
            write!(
                out,
                " {} {}",
                motion.plane.code(),
                context.effective_work_offset_selected
            )?;
            if let Some(command) = context.effective_suppression_mask.command() {
                write!(out, " {command}")?;
            } else if !context.effective_work_offset_enabled {
                write!(out, " off")?;
            }
            write!(out, " machine")?;
            write_axes(out, &motion.to_machine)?;
            if let Some(inserted) = motion.inserted {
                write!(out, " inserted {}", inserted.name())?;
            }
            if let Some(tool) = &motion.tool {
                write!(out, " tool")?;
                write_axes(out, &tool.tool_to)?;
                write!(out, " tool_radius {}", Num(tool.tool_radius))?;
                if let Some(arc) = &tool.tool_arc {
                    write!(out, " tool_arc {}", arc.motion.name())?;
                    write_axes(out, &arc.centre)?;
                    write!(out, " radius {}", Num(arc.radius))?;
                }
            }
        }
        EventKind::ModalChange(change) => {
            write!(out, " group {}", change.group)?;
            match &change.previous {
                Some(previous) => write!(out, " {previous} -> {}", change.code)?,
                None => write!(out, " {}", change.code)?,
            }
        }
        EventKind::MFunction(m) => {
            match m.address_extension {
                Some(extension) => write!(out, " M{extension}={}", m.m_value)?,
                None => write!(out, " M{}", m.m_value)?,
            }
            write!(
                out,
                " {} {} {}",
                snake_name(&m.class),
                snake_name(&m.phase),
                snake_name(&m.action)
            )?;
        }
        EventKind::HFunction(h) => {
            match h.address_extension {
                Some(extension) => write!(out, " H{extension}={}", Num(h.h_value))?,
                None => write!(out, " H{}", Num(h.h_value))?,
            }
            if h.quick {
                write!(out, " quick")?;
            }
            write!(out, " {}", snake_name(&h.phase))?;
        }
        EventKind::ToolSelect(select) => {
            write!(
                out,
                " {} {} {}",
                select.selected_tool.as_deref().unwrap_or("none"),
                snake_name(&select.selector_kind),
                snake_name(&select.timing)
            )?;
            if let Some(spindle) = select.spindle_extension {
                write!(out, " spindle {spindle}")?;
            }
        }
        EventKind::ToolChange(change) => {
            write!(
                out,
                " {} -> {} {} {}",
                change.previous_tool.as_deref().unwrap_or("none"),
                change.new_tool.as_deref().unwrap_or("none"),
                snake_name(&change.selection_source),
                snake_name(&change.trigger)
            )?;
            if change.substituted {
                write!(out, " substituted")?;
            }
            if !change.committed {
                write!(out, " NOT MADE")?;
                if let Some(reason) = change.fault_reason {
                    write!(out, " (toolchanger fault {reason})")?;
                }
                match change.previous_tool.as_deref() {
                    Some(tool) => write!(out, ": {tool} stays in the spindle")?,
                    None => write!(out, ": the spindle stays empty")?,
                }
            }
        }
        EventKind::Spindle(spindle) => {
            write!(
                out,
                " S{} {} {}",
                spindle.spindle,
                spindle.state.name(),
                Num(spindle.speed)
            )?;
            if let Some(position) = spindle.position {
                write!(out, " at {}", Num(position))?;
            }
        }
        EventKind::Dwell(dwell) => {
            if let Some(seconds) = dwell.seconds {
                write!(out, " {}s", Num(seconds))?;
            }
            if let Some(revolutions) = dwell.revolutions {
                write!(out, " {}rev", Num(revolutions))?;
            }
        }
        EventKind::Message(message) => write!(out, " {}", Quoted(&message.text))?,
        EventKind::Call(call) => {
            write!(
                out,
                " {} {} pass {}/{}",
                call.target,
                snake_name(&call.call_kind),
                call.pass,
                call.passes
            )?;
            if let Some(section) = &call.section {
                write!(out, " {}..{}", section.from, section.to)?;
            }
            if !call.arguments.is_empty() {
                out.write_str(" (")?;
                for (i, argument) in call.arguments.iter().enumerate() {
                    if i > 0 {
                        out.write_str(", ")?;
                    }
                    if let Some(argument) = argument {
                        write!(out, "{argument}")?;
                    }
                }
                out.write_char(')')?;
            }
        }
        EventKind::Return(ret) => write!(out, " {}", ret.target)?,
        EventKind::Interrupt(interrupt) => {
            write!(
                out,
                " input {} {}",
                interrupt.input,
                snake_name(&interrupt.change)
            )?;
            if let Some(routine) = &interrupt.routine {
                write!(out, " {routine}")?;
            }
            if let Some(priority) = interrupt.priority {
                write!(out, " prio {priority}")?;
            }
            if interrupt.lift_fast {
                write!(out, " liftfast")?;
            }
            if interrupt.block_sync {
                write!(out, " blsync")?;
            }
            if !interrupt.enabled {
                write!(out, " disabled")?;
            }
        }
        EventKind::Toolchanger(toolchanger) => write_toolchanger(out, toolchanger)?,
        EventKind::Stop(stop) => {
            write!(out, " {}", snake_name(&stop.reason))?;
            if let Some(detail) = &stop.detail {
                write!(out, " {detail}")?;
            }
        }
        EventKind::ProgramEnd(end) => {
            write!(out, " {} blocks {}", snake_name(&end.reason), end.blocks)?;
        }
        EventKind::Diagnostic(diagnostic) => {
            write!(out, " {} {}", diagnostic.severity.name(), diagnostic.code)?;
            if let Some(alarm) = diagnostic.alarm {
                write!(out, " alarm {alarm}")?;
            }
            write!(out, ": {}", diagnostic.message)?;
        }
    }
    out.write_char('\n')
}

/// `: fault latched (reason -5, hard): the next change aborts [idle, cycle 4]`.
fn write_toolchanger(out: &mut impl fmt::Write, event: &ToolchangerEvent) -> fmt::Result {
    write!(out, ": {}", event.edge.words())?;
    let unload = matches!(
        event.edge,
        ToolchangerEdge::PrepareRequested | ToolchangerEdge::ChangeCommitted
    );
    match &event.tool {
        Some(tool) => write!(out, " {tool}")?,
        None if unload => write!(out, " no tool")?,
        None => {}
    }
    if let Some(pocket) = event.pocket {
        write!(out, " pocket {pocket}")?;
    }
    if let Some(reason) = event.fault_reason {
        let reason = FaultReason(reason);
        write!(
            out,
            " (reason {}, {}): {}",
            reason.0,
            reason.severity(),
            reason.consequence()
        )?;
    }
    if let Some(reason) = event.abort_reason {
        write!(out, " (reason {reason})")?;
    }
    write!(out, " [{}, cycle {}]", event.state.name(), event.cycle)
}

fn write_axes(out: &mut impl fmt::Write, axes: &AxisMap) -> fmt::Result {
    for (axis, value) in axes.iter() {
        write!(out, " {axis}{}", Num(value))?;
    }
    Ok(())
}

/// The serde name of a unit-variant enum (`arc_cw`, `pending_then_m6`),
/// so that the trace uses the JSON's words.
fn snake_name<T: Serialize>(value: &T) -> Cow<'static, str> {
    match serde_json::to_value(value) {
        Ok(serde_json::Value::String(name)) => Cow::Owned(name),
        _ => Cow::Borrowed("?"),
    }
}

/// A number for reading: rounded to 4 decimals, trailing zeros dropped,
/// whole numbers without a point, no `-0`.
struct Num(f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let value = self.0;
        if !value.is_finite() {
            return write!(f, "{value}");
        }
        let scaled = (value * 1e4).round();
        if scaled == 0.0 {
            return f.write_str("0");
        }
        if scaled.abs() >= 1e18 {
            return write!(f, "{:e}", scaled / 1e4);
        }
        // Fixed point in integers: exact, and much cheaper than `{:.4}`.
        let magnitude = scaled.abs() as u64;
        if scaled < 0.0 {
            f.write_str("-")?;
        }
        f.write_str(itoa::Buffer::new().format(magnitude / 10_000))?;
        let mut fraction_buffer = [0; 4];
        let fraction = fraction_digits(magnitude % 10_000, &mut fraction_buffer);
        if !fraction.is_empty() {
            f.write_str(".")?;
            f.write_str(fraction)?;
        }
        Ok(())
    }
}

/// A string in double quotes, with `"`, `\` and line breaks escaped, so
/// that a message stays on its line.
struct Quoted<'a>(&'a str);

impl fmt::Display for Quoted<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("\"")?;
        for c in self.0.chars() {
            match c {
                '"' => f.write_str("\\\"")?,
                '\\' => f.write_str("\\\\")?,
                '\n' => f.write_str("\\n")?,
                '\r' => f.write_str("\\r")?,
                c => fmt::Write::write_char(f, c)?,
            }
        }
        f.write_str("\"")
    }
}
