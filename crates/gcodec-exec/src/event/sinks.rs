//! The sinks that write nothing: [`VecSink`] keeps the events (tests),
//! [`CountingSink`] counts them by kind (benchmarks), [`EventQueue`]
//! holds them for the application stepping a session.

use std::cell::RefCell;
use std::io;
use std::rc::Rc;

use super::{EVENT_KINDS, Event, EventSink};

/// Keeps every event, for tests.
#[derive(Clone, Debug, Default)]
pub struct VecSink {
    pub events: Vec<Event>,
}

impl VecSink {
    pub fn new() -> Self {
        Self::default()
    }
}

impl EventSink for VecSink {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        self.events.push(event.clone());
        Ok(())
    }
}

/// Counts events by kind and keeps nothing else, for benchmarks.
#[derive(Clone, Debug, Default)]
pub struct CountingSink {
    by_kind: [u64; EVENT_KINDS.len()],
}

impl CountingSink {
    pub fn new() -> Self {
        Self::default()
    }

    /// Events of the kind named `kind` (`motion`); 0 for an unknown name.
    pub fn count(&self, kind: &str) -> u64 {
        EVENT_KINDS
            .iter()
            .position(|name| *name == kind)
            .map_or(0, |index| self.by_kind[index])
    }

    /// All events.
    pub fn total(&self) -> u64 {
        self.by_kind.iter().sum()
    }
}

impl EventSink for CountingSink {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        self.by_kind[event.kind.index()] += 1;
        Ok(())
    }
}

/// The events of a stepped run, for the application to take between
/// steps: a clone shares the queue, so the application keeps one and
/// gives the channel another. A session hands over at the end of every
/// block after which the queue holds events.
#[derive(Clone, Debug, Default)]
pub struct EventQueue {
    events: Rc<RefCell<Vec<Event>>>,
}

impl EventQueue {
    pub fn new() -> Self {
        Self::default()
    }

    /// The events queued since last taken, in order.
    pub fn take(&self) -> Vec<Event> {
        std::mem::take(&mut *self.events.borrow_mut())
    }
}

impl EventSink for EventQueue {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        self.events.borrow_mut().push(event.clone());
        Ok(())
    }

    fn wants_yield(&self) -> bool {
        !self.events.borrow().is_empty()
    }

    fn may_yield(&self) -> bool {
        true
    }
}
