//! Every shipped machine profile, loaded once per process: what the
//! lowering targets (`lower`, `lower_paths`) lower each input for.

use std::sync::OnceLock;

use gcodec_profile::Profile;

/// The profiles of `profiles/`.
pub fn shipped_profiles() -> &'static [Profile] {
    static PROFILES: OnceLock<Vec<Profile>> = OnceLock::new();
    PROFILES.get_or_init(|| {
        let texts = [
            include_str!("../../profiles/default.toml"),
            include_str!("../../profiles/mill_tool_management.toml"),
            include_str!("../../profiles/lathe_828d.toml"),
            include_str!("../../profiles/mill_g505_g599.toml"),
            include_str!("../../profiles/mill_5axis.toml"),
            include_str!("../../profiles/grinder_fb422.toml"),
        ];
        texts
            .iter()
            .map(|t| gcodec_profile::load(t).expect("shipped profiles load"))
            .collect()
    })
}
