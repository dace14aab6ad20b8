//! `--format jsonl`: [`JsonlSink`], with the hand-written writer of
//! motions and modal changes (the hot path of a run's output).

use std::borrow::Cow;
use std::io::{self, Write};

use super::axis_map::same_name;
use super::line_buffer::LineBuffer;
use super::numbers::{CountText, write_u64};
use super::{
    AxisMap, AxisName, Event, EventKind, EventSink, EventSource, ModalChangeEvent, MotionEvent,
    WorkOffsetContext,
};
use crate::geometry::Plane;
use gcodec_ail::{FileJsonText, write_json_f64, write_json_string};
use gcodec_lang::MotionKind;

/// `--format jsonl`: one JSON object a line, buffered.
///
/// Motions and modal changes, most of the output, are written by hand
/// rather than through serde: the derived path (a flattened, internally
/// tagged enum) costs about 1 µs an event, several times the hand-written
/// one. The bytes are the same; tests compare them. Lines are built
/// straight into a [`LineBuffer`]; [`EventSink::finish`],
/// [`JsonlSink::into_inner`] or dropping the sink writes the rest.
pub struct JsonlSink<W: Write> {
    out: LineBuffer<W>,
    /// `{"event":"motion","motion":"…","from":` of the last motion's kind.
    last_head: KeptText<MotionKind>,
    /// The last motion's `to`, as written.
    last_to: AxisMapText,
    /// The last motion's `to_machine` where it was not its `to` (an
    /// offset or frame active, as `G54` mostly is), as written.
    last_to_machine: AxisMapText,
    /// The last motion's `from` where it was not the motion before's
    /// `to` (under a frame, the workpiece position computed back from the
    /// machine's can differ from it in the last bit), as written.
    last_from: AxisMapText,
    /// The last event's source, as written.
    last_source: SourceText,
    /// The last motion's feed, plane and work-offset fields, as written.
    last_settings: MotionSettingsText,
}

/// A text that depends on a key alone, written again only when the key
/// changes: a motion line's head on its kind, a source's tail on its
/// column and level.
struct KeptText<K> {
    key: Option<K>,
    text: Vec<u8>,
}

impl<K> Default for KeptText<K> {
    fn default() -> Self {
        Self {
            key: None,
            text: Vec::new(),
        }
    }
}

impl<K: PartialEq> KeptText<K> {
    /// Copies the text of `key` to `out`, made by `make` if the key
    /// changed.
    fn write(&mut self, out: &mut Vec<u8>, key: K, make: impl FnOnce(&mut Vec<u8>)) {
        if self.key.as_ref() != Some(&key) {
            self.text.clear();
            make(&mut self.text);
            self.key = Some(key);
        }
        out.extend_from_slice(&self.text);
    }
}

/// A motion's `feed` … `effective_suppression_mask` fields and their
/// text: the same from motion to motion but where the program changes
/// them, and about a third of a motion's line.
#[derive(Default)]
struct MotionSettingsText {
    /// The feed's bits, the plane and the work-offset context written.
    key: Option<(Option<u64>, Plane, WorkOffsetContext)>,
    feed_mode: Cow<'static, str>,
    text: Vec<u8>,
}

impl MotionSettingsText {
    fn write(&mut self, out: &mut Vec<u8>, motion: &MotionEvent) {
        let key = (
            motion.feed.map(f64::to_bits),
            motion.plane,
            motion.work_offset,
        );
        if self.key != Some(key) || !same_name(&self.feed_mode, &motion.feed_mode) {
            self.key = Some(key);
            self.feed_mode.clone_from(&motion.feed_mode);
            self.text.clear();
            write_motion_settings_json(&mut self.text, motion);
        }
        out.extend_from_slice(&self.text);
    }
}

/// `,"feed":…` to `"effective_suppression_mask":"…"`.
fn write_motion_settings_json(out: &mut Vec<u8>, motion: &MotionEvent) {
    out.extend_from_slice(b",\"feed\":");
    match motion.feed {
        Some(feed) => write_json_f64(out, feed),
        None => out.extend_from_slice(b"null"),
    }
    out.extend_from_slice(b",\"feed_mode\":");
    write_json_string(out, &motion.feed_mode);
    out.extend_from_slice(b",\"plane\":\"");
    out.extend_from_slice(motion.plane.code().as_bytes());
    let context = &motion.work_offset;
    out.extend_from_slice(b"\",\"effective_work_offset_selected\":\"g");
    write_u64(out, u64::from(context.effective_work_offset_selected.0));
    out.extend_from_slice(b"\",\"effective_work_offset_enabled\":");
    out.extend_from_slice(if context.effective_work_offset_enabled {
        b"true"
    } else {
        b"false"
    });
    out.extend_from_slice(b",\"effective_suppression_mask\":\"");
    out.extend_from_slice(context.effective_suppression_mask.name().as_bytes());
    out.push(b'"');
}

/// An axis map and its JSON text. A motion's `from` is the last motion's
/// `to`, and its `to_machine` is its `to` while no offset or frame is
/// active: their text is copied rather than written again (the numbers
/// were most of the time spent writing motions). Each axis's `"X":value`
/// is kept too: from one `to` to the next the names stay and some values
/// do (an axis the block does not move), and their text is copied.
#[derive(Default)]
struct AxisMapText {
    /// One per axis, in the map's order.
    cells: Vec<AxisCell>,
    text: Vec<u8>,
}

/// One axis of an [`AxisMapText`]: its name, the bits of its value and
/// `"name":value` as written (`-0.0` is not `0.0`: their text differs).
struct AxisCell {
    name: AxisName,
    bits: u64,
    /// The length of `"name":`, which stays while the value changes.
    key_len: usize,
    text: Vec<u8>,
}

impl AxisCell {
    fn new(name: &AxisName, value: f64) -> Self {
        let mut text = Vec::new();
        write_json_string(&mut text, name);
        text.push(b':');
        let key_len = text.len();
        write_json_f64(&mut text, value);
        Self {
            name: name.clone(),
            bits: value.to_bits(),
            key_len,
            text,
        }
    }

    /// Makes this the cell of `value` on the same axis.
    fn set_value(&mut self, value: f64) {
        if self.bits != value.to_bits() {
            self.bits = value.to_bits();
            self.text.truncate(self.key_len);
            write_json_f64(&mut self.text, value);
        }
    }
}

impl AxisMapText {
    /// Whether `map` holds the same axes and the same values, bit for bit.
    fn holds(&self, map: &AxisMap) -> bool {
        self.cells.len() == map.entries.len()
            && self
                .cells
                .iter()
                .zip(&map.entries)
                .all(|(cell, (name, value))| {
                    cell.bits == value.to_bits() && same_name(&cell.name, name)
                })
    }

    /// Writes `map` to `out` and remembers it.
    fn write(&mut self, out: &mut Vec<u8>, map: &AxisMap) {
        self.cells.truncate(map.entries.len());
        for (index, (name, value)) in map.entries.iter().enumerate() {
            match self.cells.get_mut(index) {
                Some(cell) if same_name(&cell.name, name) => cell.set_value(*value),
                Some(cell) => *cell = AxisCell::new(name, *value),
                None => self.cells.push(AxisCell::new(name, *value)),
            }
        }
        self.text.clear();
        self.text.push(b'{');
        for (index, cell) in self.cells.iter().enumerate() {
            if index > 0 {
                self.text.push(b',');
            }
            self.text.extend_from_slice(&cell.text);
        }
        self.text.push(b'}');
        out.extend_from_slice(&self.text);
    }

    /// Writes `map` to `out` as `kept`'s text if that is the same map, as
    /// this one's otherwise (and keeps it).
    #[inline]
    fn write_unless_kept(&mut self, out: &mut Vec<u8>, map: &AxisMap, kept: &AxisMapText) {
        if kept.holds(map) {
            out.extend_from_slice(&kept.text);
        } else {
            self.write(out, map);
        }
    }
}

impl<W: Write> JsonlSink<W> {
    pub fn new(writer: W) -> Self {
        Self {
            out: LineBuffer::new(writer),
            last_head: KeptText::default(),
            last_to: AxisMapText::default(),
            last_to_machine: AxisMapText::default(),
            last_from: AxisMapText::default(),
            last_source: SourceText::default(),
            last_settings: MotionSettingsText::default(),
        }
    }

    /// Flushes and gives the writer back.
    pub fn into_inner(self) -> io::Result<W> {
        self.out.into_inner()
    }
}

impl<W: Write> EventSink for JsonlSink<W> {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        let lines = &mut self.out.lines;
        match &event.kind {
            EventKind::Motion(motion) => {
                self.last_head.write(lines, motion.motion, |head| {
                    head.extend_from_slice(b"{\"event\":\"motion\",\"motion\":\"");
                    head.extend_from_slice(motion.motion.name().as_bytes());
                    head.extend_from_slice(b"\",\"from\":");
                });
                let maps = MotionMapsText {
                    from: &mut self.last_from,
                    to: &mut self.last_to,
                    to_machine: &mut self.last_to_machine,
                };
                write_motion_json(lines, motion, maps, &mut self.last_settings);
                self.last_source.write(lines, &event.source);
            }
            EventKind::ModalChange(change) => {
                write_modal_change_json(lines, change);
                self.last_source.write(lines, &event.source);
            }
            _ => serde_json::to_writer(&mut *lines, event)?,
        }
        lines.push(b'\n');
        self.out.line_done()
    }

    fn finish(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

/// The kept texts of a motion's maps: its `to` (its `from` is mostly the
/// last one's, its `to_machine` the same while no offset or frame is
/// active), and its `from` and `to_machine` where they differ.
struct MotionMapsText<'a> {
    from: &'a mut AxisMapText,
    to: &'a mut AxisMapText,
    to_machine: &'a mut AxisMapText,
}

/// A motion event as serde writes it: the same fields in the same order,
/// numbers in the same shortest form; from its `from` (after its head)
/// to before its source and closing brace.
fn write_motion_json(
    out: &mut Vec<u8>,
    motion: &MotionEvent,
    maps: MotionMapsText<'_>,
    last_settings: &mut MotionSettingsText,
) {
    let MotionMapsText {
        from,
        to,
        to_machine,
    } = maps;
    from.write_unless_kept(out, &motion.from, to);
    out.extend_from_slice(b",\"to\":");
    to.write(out, &motion.to);
    out.extend_from_slice(b",\"to_machine\":");
    to_machine.write_unless_kept(out, &motion.to_machine, to);
    if let Some(centre) = &motion.centre {
        out.extend_from_slice(b",\"centre\":");
        write_axis_map_json(out, centre);
    }
    if let Some(radius) = motion.radius {
        out.extend_from_slice(b",\"radius\":");
        write_json_f64(out, radius);
    }
    if motion.turns != 0 {
        out.extend_from_slice(b",\"turns\":");
        write_u64(out, u64::from(motion.turns));
    }
    last_settings.write(out, motion);
    if let Some(inserted) = motion.inserted {
        out.extend_from_slice(b",\"inserted\":\"");
        out.extend_from_slice(inserted.name().as_bytes());
        out.push(b'"');
    }
    if let Some(tool) = &motion.tool {
        out.extend_from_slice(b",\"tool_to\":");
        write_axis_map_json(out, &tool.tool_to);
        out.extend_from_slice(b",\"tool_to_machine\":");
        write_axis_map_json(out, &tool.tool_to_machine);
        out.extend_from_slice(b",\"tool_radius\":");
        write_json_f64(out, tool.tool_radius);
        if let Some(arc) = &tool.tool_arc {
            out.extend_from_slice(b",\"tool_arc\":{\"motion\":\"");
            out.extend_from_slice(arc.motion.name().as_bytes());
            out.extend_from_slice(b"\",\"centre\":");
            write_axis_map_json(out, &arc.centre);
            out.extend_from_slice(b",\"radius\":");
            write_json_f64(out, arc.radius);
            out.push(b'}');
        }
    }
}

/// A modal change as serde writes it (the second commonest event),
/// without its source and closing brace.
fn write_modal_change_json(out: &mut Vec<u8>, change: &ModalChangeEvent) {
    out.extend_from_slice(b"{\"event\":\"modal_change\",\"group\":");
    write_u64(out, u64::from(change.group));
    out.extend_from_slice(b",\"code\":");
    write_json_string(out, &change.code);
    out.extend_from_slice(b",\"previous\":");
    match &change.previous {
        Some(previous) => write_json_string(out, previous),
        None => out.extend_from_slice(b"null"),
    }
}

/// The text of the last event's source. The file, the column (a block's
/// first word) and the level mostly stay from event to event; the line
/// is the only part written anew.
struct SourceText {
    /// `,"source":{"file":…,"line":`.
    head: FileJsonText,
    /// The line: mostly the last event's or the next.
    line: CountText,
    /// `,"col":…,"level":…}}` of a column and level.
    tail: KeptText<(u32, u32)>,
}

impl Default for SourceText {
    fn default() -> Self {
        Self {
            head: FileJsonText::between(b",\"source\":{\"file\":", b",\"line\":"),
            line: CountText::default(),
            tail: KeptText::default(),
        }
    }
}

impl SourceText {
    /// `,"source":{…}}`: the event's source and the event's closing brace.
    fn write(&mut self, out: &mut Vec<u8>, source: &EventSource) {
        self.head.write(out, &source.file);
        self.line.write(out, u64::from(source.line));
        self.tail.write(out, (source.col, source.level), |tail| {
            tail.extend_from_slice(b",\"col\":");
            write_u64(tail, u64::from(source.col));
            tail.extend_from_slice(b",\"level\":");
            write_u64(tail, u64::from(source.level));
            tail.extend_from_slice(b"}}");
        });
    }
}

fn write_axis_map_json(out: &mut Vec<u8>, axes: &AxisMap) {
    out.push(b'{');
    for (index, (axis, value)) in axes.iter().enumerate() {
        if index > 0 {
            out.push(b',');
        }
        write_json_string(out, axis);
        out.push(b':');
        write_json_f64(out, value);
    }
    out.push(b'}');
}
