//! The nearest of a set of names to a misspelt one: the did-you-mean
//! behind every diagnostic that can name what was probably meant (codes,
//! G commands, keywords, variables, system variables, axes).

/// Below this Jaro-Winkler similarity a name is not worth suggesting.
const THRESHOLD: f64 = 0.8;

/// The candidate most similar to `name`, compared without regard to case
/// (SINUMERIK names are case-insensitive); `None` when nothing is close.
/// Of equally close candidates the first wins, so a suggestion is
/// deterministic. A name that is a candidate is its own nearest: callers
/// ask for names they did not find, or found more than once.
pub fn nearest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let name = name.trim().to_ascii_uppercase();
    let mut best: Option<(f64, &'a str)> = None;
    for candidate in candidates {
        let similarity = strsim::jaro_winkler(&name, &candidate.to_ascii_uppercase());
        if similarity >= THRESHOLD && best.is_none_or(|(b, _)| similarity > b) {
            best = Some((similarity, candidate));
        }
    }
    best.map(|(_, candidate)| candidate)
}

#[cfg(test)]
mod tests {
    use super::nearest;

    #[test]
    fn a_near_name_is_suggested_whatever_its_case() {
        assert_eq!(nearest("depht", ["WIDTH", "DEPTH"]), Some("DEPTH"));
        assert_eq!(nearest("ENDIFF", ["ENDIF", "ENDFOR"]), Some("ENDIF"));
    }

    #[test]
    fn nothing_is_suggested_when_nothing_is_close() {
        assert_eq!(nearest("QQQQ", ["DEPTH", "WIDTH"]), None);
        assert_eq!(nearest("X", std::iter::empty()), None);
    }

    #[test]
    fn of_equally_close_names_the_first_wins() {
        assert_eq!(nearest("DEPTX", ["DEPTA", "DEPTB"]), Some("DEPTA"));
    }
}
