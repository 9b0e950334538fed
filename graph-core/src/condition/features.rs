//! A set of feature names: what a caller's scene needs, or what a graph declares.

use std::collections::BTreeSet;
use std::fmt;

use serde::Serialize;

/// Feature names, sorted, so equal sets compare, hash and print equally (a plan cache
/// keys on them).
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct Features(BTreeSet<String>);

impl Features {
    /// No feature set: every `!feature` literal holds, no `feature` literal does.
    pub fn new() -> Features {
        Features::default()
    }

    /// Whether `feature` is set.
    pub fn contains(&self, feature: &str) -> bool {
        self.0.contains(feature)
    }

    /// Adds a feature; `false` when it was already set.
    pub fn insert(&mut self, feature: impl Into<String>) -> bool {
        self.0.insert(feature.into())
    }

    /// The features set in both.
    pub fn intersection(&self, other: &Features) -> Features {
        Features(self.0.intersection(&other.0).cloned().collect())
    }

    /// The features set, in alphabetical order.
    pub fn iter(&self) -> impl Iterator<Item = &str> {
        self.0.iter().map(String::as_str)
    }
}

impl<S: Into<String>> FromIterator<S> for Features {
    fn from_iter<I: IntoIterator<Item = S>>(iter: I) -> Features {
        Features(iter.into_iter().map(Into::into).collect())
    }
}

impl fmt::Display for Features {
    /// `a, b`, or `none` for the empty set.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            return f.write_str("none");
        }
        let names: Vec<&str> = self.iter().collect();
        f.write_str(&names.join(", "))
    }
}
