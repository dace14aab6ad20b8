//! How names are compared: the control ignores case, and the tables hold
//! names in upper case.

use std::cmp::Ordering;

/// Compares an upper-case table name with `key` as if `key` were upper
/// case too, byte by byte (the order the tables are sorted in).
pub(crate) fn compare_ignore_case(upper: &str, key: &str) -> Ordering {
    upper
        .bytes()
        .cmp(key.bytes().map(|b| b.to_ascii_uppercase()))
}

/// Declares a closed set of names from one list: the enum (a variant's
/// discriminant is its place in the table), the table of each variant,
/// its name and the columns after it, sorted by name for binary search
/// (the module's tests keep it so), and `named` and `name`.
macro_rules! name_table {
    (
        $(#[$enum_doc:meta])* enum $Enum:ident;
        $(#[$table_doc:meta])* table $TABLE:ident: ($($column:ty),*);
        $($variant:ident $name:literal $(, $value:expr)*;)*
    ) => {
        $(#[$enum_doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum $Enum {
            $($variant,)*
        }

        $(#[$table_doc])*
        pub const $TABLE: &[($Enum, &str, $($column),*)] = &[
            $(($Enum::$variant, $name, $($value),*),)*
        ];

        impl $Enum {
            /// The one named `name` (any case); `None` for a name the
            /// table does not list.
            pub fn named(name: &str) -> Option<Self> {
                $TABLE
                    .binary_search_by(|entry| $crate::names::compare_ignore_case(entry.1, name))
                    .ok()
                    .map(|i| $TABLE[i].0)
            }

            /// The name in upper case.
            pub fn name(self) -> &'static str {
                $TABLE[self as usize].1
            }
        }
    };
}

pub(crate) use name_table;

/// Serialises a vocabulary type as its text (`|v| text`, a `Display` of
/// `v`) and reads it back with `parse`, an error naming the text and
/// `what` it is not: in JSON a vocabulary id is the control's word.
macro_rules! serde_as_text {
    ($ty:ty, |$v:ident| $text:expr, $parse:expr, $what:literal) => {
        impl serde::Serialize for $ty {
            fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                let $v = self;
                serializer.collect_str(&$text)
            }
        }

        impl<'de> serde::Deserialize<'de> for $ty {
            fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                let text =
                    <std::borrow::Cow<'de, str> as serde::Deserialize>::deserialize(deserializer)?;
                $parse(&text).ok_or_else(|| {
                    <D::Error as serde::de::Error>::custom(format_args!(
                        "`{}` is not {}",
                        text, $what
                    ))
                })
            }
        }
    };
}
pub(crate) use serde_as_text;
