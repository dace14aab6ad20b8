//! Axis names as events and CSV columns write them, and [`AxisMap`], the
//! ordered axis → value map of positions (a JSON object).

use std::borrow::Cow;
use std::fmt;

use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::de::{MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// An axis name in upper case (`X`, `C1`). Single letters are borrowed
/// statics, as in AIL, so that copying a name costs nothing.
pub type AxisName = Cow<'static, str>;

/// A profile's axis name as events and CSV columns write it: upper case,
/// a single letter borrowed.
pub fn axis_name(name: &str) -> AxisName {
    match name.as_bytes() {
        [b] if b.is_ascii_alphabetic() => {
            Cow::Borrowed(gcodec_lang::addresses::letter_str(b.to_ascii_uppercase()))
        }
        _ => Cow::Owned(name.to_ascii_uppercase()),
    }
}

/// The names of the channel axes of `profile`, in order.
pub fn axis_names(profile: &gcodec_profile::Profile) -> impl Iterator<Item = AxisName> + '_ {
    profile.axes.iter().map(|a| axis_name(a.name.get_ref()))
}

/// Axis → value, in the order the axes were put in (the profile's order
/// for positions). In JSON an object, `{"X": 10, "Y": 5}`, its keys in
/// that order.
///
/// A handful of axes per map makes a vector faster than any hash map, and
/// [`AxisMap::update`] and [`AxisMap::copy_from`] reuse it, so an executor
/// that refills one map per block allocates nothing.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AxisMap {
    /// Read by the JSONL writer, which remembers the last map it wrote.
    pub(super) entries: Vec<(AxisName, f64)>,
}

impl AxisMap {
    /// An empty map.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty map with room for `capacity` axes.
    pub fn with_capacity(capacity: usize) -> Self {
        Self {
            entries: Vec::with_capacity(capacity),
        }
    }

    /// The value of `axis`.
    pub fn get(&self, axis: &str) -> Option<f64> {
        self.entries
            .iter()
            .find(|(name, _)| name == axis)
            .map(|(_, value)| *value)
    }

    /// Sets `axis`, appending it when it is new.
    pub fn insert(&mut self, axis: AxisName, value: f64) {
        match self.entries.iter_mut().find(|(name, _)| *name == axis) {
            Some(entry) => entry.1 = value,
            None => self.entries.push((axis, value)),
        }
    }

    /// Sets `axis` if the map has it; false otherwise. Never allocates.
    pub fn update(&mut self, axis: &str, value: f64) -> bool {
        match self.entries.iter_mut().find(|(name, _)| name == axis) {
            Some(entry) => {
                entry.1 = value;
                true
            }
            None => false,
        }
    }

    /// Makes this map equal to `other`, reusing its storage (names that
    /// are already in place are not copied).
    pub fn copy_from(&mut self, other: &AxisMap) {
        self.entries.truncate(other.entries.len());
        for (index, (name, value)) in other.entries.iter().enumerate() {
            match self.entries.get_mut(index) {
                Some(entry) => {
                    if !same_name(&entry.0, name) {
                        entry.0.clone_from(name);
                    }
                    entry.1 = *value;
                }
                None => self.entries.push((name.clone(), *value)),
            }
        }
    }

    /// Removes every axis, keeping the storage.
    pub fn clear(&mut self) {
        self.entries.clear();
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The axes and values in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = (&str, f64)> + '_ {
        self.entries.iter().map(|(name, value)| (&**name, *value))
    }

    /// The values in order, to change them in place.
    pub fn values_mut(&mut self) -> impl ExactSizeIterator<Item = &mut f64> + '_ {
        self.entries.iter_mut().map(|(_, value)| value)
    }
}

impl FromIterator<(AxisName, f64)> for AxisMap {
    fn from_iter<I: IntoIterator<Item = (AxisName, f64)>>(iter: I) -> Self {
        let mut map = Self::new();
        for (axis, value) in iter {
            map.insert(axis, value);
        }
        map
    }
}

impl<const N: usize> From<[(&'static str, f64); N]> for AxisMap {
    fn from(entries: [(&'static str, f64); N]) -> Self {
        entries
            .into_iter()
            .map(|(axis, value)| (Cow::Borrowed(axis), value))
            .collect()
    }
}

impl Serialize for AxisMap {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.entries.len()))?;
        for (axis, value) in &self.entries {
            map.serialize_entry(&**axis, value)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for AxisMap {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct AxisMapVisitor;

        impl<'de> Visitor<'de> for AxisMapVisitor {
            type Value = AxisMap;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("an object of axis names and numbers")
            }

            fn visit_map<A: MapAccess<'de>>(self, mut access: A) -> Result<AxisMap, A::Error> {
                let mut map = AxisMap::with_capacity(access.size_hint().unwrap_or(0).min(64));
                while let Some((axis, value)) = access.next_entry::<String, f64>()? {
                    map.insert(Cow::Owned(axis), value);
                }
                Ok(map)
            }
        }

        deserializer.deserialize_map(AxisMapVisitor)
    }
}

impl JsonSchema for AxisMap {
    fn schema_name() -> Cow<'static, str> {
        "AxisMap".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "Axis name (upper case) → value, in the channel's axis order.",
            "type": "object",
            "additionalProperties": {"type": "number"},
        })
    }
}

/// Axis names and the feed mode are mostly the same static strings:
/// compare addresses first.
#[inline]
pub(super) fn same_name(a: &str, b: &str) -> bool {
    std::ptr::eq(a, b) || a == b
}
