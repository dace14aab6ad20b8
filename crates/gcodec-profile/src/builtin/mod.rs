//! The built-in profile, precompiled: `profiles/default.toml` as
//! [`crate::load`] reads it, spans into its text included, written out as
//! the Rust code that builds it (`generated.rs`), so that a start of
//! gcodec does not parse TOML. A test regenerates the code from the TOML
//! and fails when the checked-in code differs; another compares the
//! profile the code builds with the loaded one, spans and all.
//!
//! Why Rust code and not a serialized form: the profile's values carry
//! `toml::Spanned` spans (diagnostics point into the built-in profile's
//! text), which serde serializes as the bare value, so any serialized form
//! would lose them.

#[rustfmt::skip]
mod generated;
#[cfg(test)]
mod rust_literal;

pub(crate) use generated::profile;

#[cfg(test)]
mod tests {
    use super::rust_literal::Writer;
    use crate::{BUILTIN_TOML, Profile, load};

    const GENERATED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/src/builtin/generated.rs");

    /// Set to rewrite `generated.rs` from `profiles/default.toml`.
    const UPDATE: &str = "GCODEC_UPDATE_BUILTIN_PROFILE";

    const HEADER: &str = "\
// @generated from profiles/default.toml by the tests of
// crates/gcodec-profile/src/builtin/mod.rs. Do not edit: regenerate with
//   GCODEC_UPDATE_BUILTIN_PROFILE=1 cargo test -p gcodec-profile --lib builtin
#![allow(unused_imports)]

use std::collections::BTreeMap;
use std::ops::Range;

use gcodec_lang::MClass;
use toml::Spanned;

use crate::schema::*;

fn s<T>(span: Range<usize>, value: T) -> Spanned<T> {
    Spanned::new(span, value)
}

/// `profiles/default.toml` as `crate::load` reads it.
";

    fn loaded() -> Profile {
        load(BUILTIN_TOML).expect("the built-in profile loads")
    }

    fn render(profile: &Profile) -> String {
        let mut out = Writer::new();
        out.push(HEADER);
        out.open("pub(crate) fn profile() -> Profile {");
        out.tail(profile);
        out.close("}");
        out.push("\n");
        out.into_text()
    }

    #[test]
    fn generated_code_is_current() {
        let expected = render(&loaded());
        if std::env::var_os(UPDATE).is_some() {
            std::fs::write(GENERATED, &expected).expect("write generated.rs");
            return;
        }
        let actual = std::fs::read_to_string(GENERATED).expect("read generated.rs");
        assert!(
            actual == expected,
            "crates/gcodec-profile/src/builtin/generated.rs is not what \
             profiles/default.toml gives; regenerate with \
             {UPDATE}=1 cargo test -p gcodec-profile --lib builtin"
        );
    }

    /// `Spanned`'s `==` compares values only; its `Debug` shows the span,
    /// and `f64`'s `Debug` every bit of the value.
    #[test]
    fn precompiled_profile_equals_the_loaded_one() {
        assert_eq!(
            format!("{:#?}", super::profile()),
            format!("{:#?}", loaded())
        );
    }

    #[test]
    fn precompiled_profile_has_spans_into_the_text() {
        let profile = super::profile();
        let name = &profile.axes[0].name;
        assert_eq!(&BUILTIN_TOML[name.span()], "\"X\"");
    }
}
