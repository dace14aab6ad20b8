//! `[system_variables]`: the keys' form (`$NAME` or `$NAME[i, …]`), their
//! check against the control's lists, and the value a run reads for a
//! variable and its indices ([`Profile::system_value`]).

use gcodec_lang::DataType;
use gcodec_lang::sysvars;
use gcodec_source::{Diagnostic, codes};

use crate::schema::{Profile, SystemValue};
use crate::span;

/// A key split into the variable's name and its indices, upper case and
/// without blanks (`$a_in[ 3 ]` → `$A_IN`, `["3"]`); `None` for a key of
/// another form.
pub fn split_key(key: &str) -> Option<(String, Vec<String>)> {
    let key: String = key
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_uppercase();
    let (name, indices) = match key.split_once('[') {
        None => (key.as_str(), Vec::new()),
        Some((name, rest)) => {
            let inner = rest.strip_suffix(']')?;
            let indices: Vec<String> = inner.split(',').map(str::to_owned).collect();
            if indices
                .iter()
                .any(|i| i.is_empty() || i.contains(['[', ']']))
            {
                return None;
            }
            (name, indices)
        }
    };
    let body = name.strip_prefix('$')?;
    let valid = !body.is_empty() && body.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_');
    valid.then(|| (name.to_owned(), indices))
}

impl Profile {
    /// The value `[system_variables]` gives the variable `name` (upper
    /// case, one `$`) with `indices` (as the run writes them: `1`, `X`):
    /// the entry with these indices, else the entry of the bare name,
    /// which stands for every index.
    pub fn system_value(&self, name: &str, indices: &[String]) -> Option<&SystemValue> {
        let mut bare = None;
        for (key, value) in &self.system_variables {
            let Some((key_name, key_indices)) = split_key(key.get_ref()) else {
                continue;
            };
            if key_name != name {
                continue;
            }
            if key_indices == indices {
                return Some(value);
            }
            if key_indices.is_empty() {
                bare = Some(value);
            }
        }
        bare
    }
}

/// Each key names a system variable of the control with no more indices
/// than it takes, once, and its value has the variable's type.
pub(crate) fn check(profile: &Profile, out: &mut Vec<Diagnostic>) {
    let mut seen = std::collections::BTreeSet::new();
    for (key, value) in &profile.system_variables {
        let at = span(key.span());
        let Some((name, indices)) = split_key(key.get_ref()) else {
            out.push(
                Diagnostic::new(
                    codes::profile::SCHEMA,
                    format!("`{}` is not a system variable's name", key.get_ref()),
                )
                .with_label(at, "here")
                .with_help("write the name with its `$` and, for one element, its indices: `\"$P_ISTEST\"`, `\"$A_IN[3]\"`"),
            );
            continue;
        };
        let Some(var) = sysvars::lookup(&name) else {
            let candidates = sysvars::all().map(|v| v.name);
            let help = match gcodec_source::nearest(&name, candidates) {
                Some(near) => {
                    format!("did you mean `{near}`? The names are those of the control's lists")
                }
                None => "the names are those of the control's lists of system variables".to_owned(),
            };
            out.push(
                Diagnostic::new(
                    codes::profile::UNKNOWN_SYSTEM_VARIABLE,
                    format!("`{name}` is not a system variable of the control"),
                )
                .with_label(at, "unknown")
                .with_help(help),
            );
            continue;
        };
        if !indices.is_empty() && !var.shape.accepts(indices.len()) {
            out.push(
                Diagnostic::new(
                    codes::profile::SCHEMA,
                    format!("`{name}` does not take {} indices", indices.len()),
                )
                .with_label(at, "here")
                .with_help("give the indices the variable takes, or none for every element"),
            );
        }
        if !seen.insert((name.clone(), indices.clone())) {
            out.push(
                Diagnostic::new(
                    codes::profile::DUPLICATE,
                    format!("`{name}` is given twice"),
                )
                .with_label(at, "again here"),
            );
        }
        let fits = match var.data_type(indices.len().max(dims_of(var.shape))) {
            Some(DataType::Bool) => matches!(value, SystemValue::Bool(_) | SystemValue::Int(_)),
            Some(DataType::Int | DataType::Real) => {
                matches!(
                    value,
                    SystemValue::Int(_) | SystemValue::Real(_) | SystemValue::Bool(_)
                )
            }
            Some(DataType::Char | DataType::String { .. } | DataType::Axis) => {
                matches!(value, SystemValue::Text(_))
            }
            Some(DataType::Frame) => false,
            None => true,
        };
        if !fits {
            out.push(
                Diagnostic::new(
                    codes::profile::SCHEMA,
                    format!("this value does not fit `{name}`, a {}", type_name(var.data_type(indices.len().max(dims_of(var.shape))))),
                )
                .with_label(at, "here")
                .with_help("a BOOL takes true or false, INT and REAL a number, STRING, CHAR and AXIS a string; frames cannot be given"),
            );
        }
    }
}

/// The indices an element of a variable of `shape` has.
fn dims_of(shape: sysvars::IndexShape) -> usize {
    use sysvars::IndexShape::*;
    match shape {
        None | Frame | FrameComponent | Any => 0,
        Axis | Number => 1,
        Numbers(n) | Dims(n) => usize::from(n),
    }
}

fn type_name(ty: Option<DataType>) -> String {
    ty.map_or_else(|| "value".to_owned(), |t| t.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn codes(table: &str) -> Vec<&'static str> {
        let text =
            format!("[machine]\nname = \"t\"\ncontrol = \"840d_sl\"\n[system_variables]\n{table}");
        match crate::load(&text) {
            Ok(_) => Vec::new(),
            Err(d) => d.iter().map(|d| d.code.name()).collect(),
        }
    }

    #[test]
    fn keys_are_names_with_optional_indices() {
        assert_eq!(split_key("$p_istest"), Some(("$P_ISTEST".into(), vec![])));
        assert_eq!(
            split_key("$A_IN[ 3 ]"),
            Some(("$A_IN".into(), vec!["3".into()]))
        );
        assert_eq!(
            split_key("$TC_MPP1[1,2]"),
            Some(("$TC_MPP1".into(), vec!["1".into(), "2".into()]))
        );
        for not in [
            "P_ISTEST",
            "$",
            "$A_IN[",
            "$A_IN[]",
            "$A_IN[1,]",
            "$A-IN",
            "$A_IN[1]X",
        ] {
            assert_eq!(split_key(not), None, "{not}");
        }
    }

    #[test]
    fn entries_are_checked_against_the_controls_lists() {
        let ok = "\"$P_ISTEST\" = true\n\"$A_IN[3]\" = false\n\"$AC_MEA\" = 1\n\"$P_PROG[0]\" = \"MAIN\"";
        assert_eq!(codes(ok), Vec::<&str>::new());
        assert_eq!(
            codes("\"$P_ISTST\" = true"),
            ["gcodec::profile::unknown_system_variable"]
        );
        assert_eq!(codes("\"P_ISTEST\" = true"), ["gcodec::profile::schema"]);
        assert_eq!(
            codes("\"$P_ISTEST\" = \"yes\""),
            ["gcodec::profile::schema"]
        );
        assert_eq!(codes("\"$P_UBFR\" = 1"), ["gcodec::profile::schema"]);
        assert_eq!(codes("\"$A_IN[1,2]\" = true"), ["gcodec::profile::schema"]);
        assert_eq!(
            codes("\"$A_IN[3]\" = true\n\"$a_in[ 3]\" = false"),
            ["gcodec::profile::duplicate"]
        );
    }

    #[test]
    fn an_element_entry_wins_over_the_bare_name() {
        let text = "[machine]\nname = \"t\"\ncontrol = \"840d_sl\"\n[system_variables]\n\"$A_IN\" = false\n\"$A_IN[3]\" = true\n";
        let profile = crate::load(text).unwrap();
        let at = |i: &str| profile.system_value("$A_IN", &[i.to_owned()]).cloned();
        assert_eq!(at("3"), Some(SystemValue::Bool(true)));
        assert_eq!(at("4"), Some(SystemValue::Bool(false)));
        assert_eq!(profile.system_value("$P_ISTEST", &[]), None);
    }
}
