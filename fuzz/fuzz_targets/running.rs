//! What the running targets (`run`, `files`) share: the four shipped
//! machine profiles they run inputs on, loaded once per process, and the
//! check every run's event stream must pass at its end.

use std::sync::{Arc, OnceLock};

use gcodec_driver::event::{Event, EventKind};
use gcodec_profile::Profile;

/// `default`, `mill_tool_management`, `lathe_828d` and `mill_5axis`.
pub fn run_profiles() -> &'static [Arc<Profile>] {
    static PROFILES: OnceLock<Vec<Arc<Profile>>> = OnceLock::new();
    PROFILES.get_or_init(|| {
        let texts = [
            include_str!("../../profiles/default.toml"),
            include_str!("../../profiles/mill_tool_management.toml"),
            include_str!("../../profiles/lathe_828d.toml"),
            include_str!("../../profiles/mill_5axis.toml"),
        ];
        texts
            .iter()
            .map(|t| Arc::new(gcodec_profile::load(t).expect("shipped profiles load")))
            .collect()
    })
}

/// Exactly one `program_end`, and it is the last event.
pub fn assert_one_program_end_last(events: &[Event]) {
    let ends = events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::ProgramEnd(_)))
        .count();
    assert_eq!(ends, 1, "exactly one program_end");
    assert!(matches!(
        events.last().map(|e| &e.kind),
        Some(EventKind::ProgramEnd(_))
    ));
}
