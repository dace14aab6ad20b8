//! The four shipped machine profiles the running targets (`run`, `files`)
//! run every input on, loaded once per process.

use std::sync::{Arc, OnceLock};

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
