//! A glob's alternatives (`{a,b}`) spelt out as globs of their own.
//!
//! globset matches a glob such as `**/tool.mpf` by its file name or
//! extension alone, but one with alternatives (`**/{tool,edge}.mpf`)
//! through a regular expression built when the configuration is read:
//! about 150,000 instructions, an eighth of a short program's whole run
//! (docs/performance.md, "Issue 20: the third measurement"). A set of the
//! alternatives' globs matches the same paths and builds none.

/// Globs at most a glob is spelt out into; one with more alternatives is
/// kept whole (its regular expression then costs less than the set).
const MAX_SPELT_OUT: usize = 16;

/// The globs `pattern`'s alternatives stand for, each group in turn:
/// `{a,b}/{c,d}` gives `a/c`, `a/d`, `b/c`, `b/d`. A pattern with a
/// character class or an escape (where a brace or comma may be a literal
/// one), with nested or unclosed braces or an empty alternative, or with
/// more than [`MAX_SPELT_OUT`] globs is given back whole, for globset to
/// match or reject as it is.
pub(crate) fn spelt_out(pattern: &str) -> Vec<String> {
    if pattern.contains(['[', '\\']) {
        return vec![pattern.to_owned()];
    }
    let mut globs = vec![String::new()];
    let mut rest = pattern;
    while let Some(open) = rest.find('{') {
        let Some(close) = rest[open..].find('}').map(|c| open + c) else {
            return vec![pattern.to_owned()];
        };
        let group = &rest[open + 1..close];
        if group.contains('{') {
            return vec![pattern.to_owned()];
        }
        let before = &rest[..open];
        let choices: Vec<&str> = group.split(',').collect();
        // globset's reading of an empty alternative is its own.
        if choices.contains(&"") || globs.len() * choices.len() > MAX_SPELT_OUT {
            return vec![pattern.to_owned()];
        }
        globs = globs
            .iter()
            .flat_map(|glob| {
                choices
                    .iter()
                    .map(move |choice| format!("{glob}{before}{choice}"))
            })
            .collect();
        rest = &rest[close + 1..];
    }
    if rest.contains('}') {
        return vec![pattern.to_owned()];
    }
    for glob in &mut globs {
        glob.push_str(rest);
    }
    globs
}

#[cfg(test)]
mod tests {
    use super::*;
    use globset::{GlobBuilder, GlobSet, GlobSetBuilder};

    fn whole(pattern: &str) -> GlobSet {
        let glob = GlobBuilder::new(pattern)
            .literal_separator(true)
            .build()
            .expect("glob");
        GlobSetBuilder::new().add(glob).build().expect("set")
    }

    fn spelt(pattern: &str) -> GlobSet {
        let mut set = GlobSetBuilder::new();
        for glob in spelt_out(pattern) {
            set.add(
                GlobBuilder::new(&glob)
                    .literal_separator(true)
                    .build()
                    .expect("glob"),
            );
        }
        set.build().expect("set")
    }

    #[test]
    fn alternatives_are_spelt_out_group_by_group() {
        assert_eq!(
            spelt_out("**/{edge_cases,for_loop,repeat}.mpf"),
            ["**/edge_cases.mpf", "**/for_loop.mpf", "**/repeat.mpf"]
        );
        assert_eq!(
            spelt_out("{a,b}/x{c,d}.spf"),
            ["a/xc.spf", "a/xd.spf", "b/xc.spf", "b/xd.spf"]
        );
        assert_eq!(spelt_out("**/tool.mpf"), ["**/tool.mpf"]);
    }

    #[test]
    fn what_is_not_plain_alternatives_is_kept_whole() {
        for pattern in [
            "**/{a,{b,c}}.mpf",
            "**/{a,b.mpf",
            "**/{}.mpf",
            "{a,b}/x{c,}.spf",
            "**/a,b}.mpf",
            "**/[{]x.mpf",
            "**/\\{a,b}.mpf",
            "{a,b}{c,d}{e,f}{g,h}{i,j}.mpf",
        ] {
            assert_eq!(spelt_out(pattern), [pattern], "{pattern}");
        }
    }

    /// The spelt-out globs match exactly the paths the glob does.
    #[test]
    fn spelt_out_globs_match_what_the_glob_matches() {
        let paths = [
            "edge_cases.mpf",
            "progs/for_loop.mpf",
            "progs/deep/repeat.mpf",
            "progs/repeat.spf",
            "progs/repeatx.mpf",
            "a/xc.spf",
            "a/xd.spf",
            "a/x.spf",
            "b/xc.spf",
            "c/xc.spf",
            "a/sub/xc.spf",
            "ab.mpf",
            "a.mpf",
            "b.mpf",
        ];
        for pattern in [
            "**/{edge_cases,for_loop,repeat}.mpf",
            "{a,b}/x{c,d}.spf",
            "{a,b}.mpf",
            "*/{x*,y}.spf",
        ] {
            let (whole, spelt) = (whole(pattern), spelt(pattern));
            for path in paths {
                assert_eq!(
                    whole.is_match(path),
                    spelt.is_match(path),
                    "{pattern} on {path}"
                );
            }
        }
    }
}
