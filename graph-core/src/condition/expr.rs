//! A condition: a conjunction of feature literals, and what it says about a feature set.

use std::fmt;

use serde::{Deserialize, Serialize};

use super::features::Features;

/// A feature that must be set, or (`negated`) must not be.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct Literal {
    /// The feature's name.
    pub feature: String,
    /// Written `!feature`: holds where the feature is not set.
    pub negated: bool,
}

impl Literal {
    /// Whether `features` satisfies the literal.
    pub fn holds(&self, features: &Features) -> bool {
        features.contains(&self.feature) != self.negated
    }
}

impl fmt::Display for Literal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let bang = if self.negated { "!" } else { "" };
        write!(f, "{bang}{}", self.feature)
    }
}

/// Literals that must all hold, in the order written: `spot_lights & !unlit_only`.
/// Parse one with [`Condition::parse`], or build it with [`Condition::feature`],
/// [`Condition::not`] and [`Condition::and`].
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(into = "String", try_from = "String")]
pub struct Condition {
    pub(super) literals: Vec<Literal>,
}

impl Condition {
    /// Holds when `feature` is set.
    pub fn feature(feature: impl Into<String>) -> Condition {
        Condition {
            literals: vec![Literal {
                feature: feature.into(),
                negated: false,
            }],
        }
    }

    /// Holds when `feature` is not set.
    pub fn not(feature: impl Into<String>) -> Condition {
        Condition {
            literals: vec![Literal {
                feature: feature.into(),
                negated: true,
            }],
        }
    }

    /// Holds when both hold.
    pub fn and(mut self, other: Condition) -> Condition {
        for literal in other.literals {
            if !self.literals.contains(&literal) {
                self.literals.push(literal);
            }
        }
        self
    }

    /// The literals, all of which must hold, in the order written (repeats dropped).
    pub fn literals(&self) -> &[Literal] {
        &self.literals
    }

    /// Whether `features` satisfies every literal.
    pub fn holds(&self, features: &Features) -> bool {
        self.literals.iter().all(|l| l.holds(features))
    }

    /// Why the condition is false for `features` (`None` when it holds), in the words
    /// plans use: `condition "spot_lights" is false`, naming the failing literals when
    /// there are several.
    pub fn why_false(&self, features: &Features) -> Option<String> {
        let failing: Vec<String> = self
            .literals
            .iter()
            .filter(|l| !l.holds(features))
            .map(|l| match l.negated {
                true => format!("\"{}\" is set", l.feature),
                false if super::is_device_condition(&l.feature) => format!(
                    "\"{}\" is not set for this device (rgraph explain --profile adapter \
                     shows a device's plan)",
                    l.feature
                ),
                false => format!("\"{}\" is not set", l.feature),
            })
            .collect();
        match (failing.is_empty(), self.literals.len()) {
            (true, _) => None,
            (false, 1) => Some(format!("condition \"{self}\" is false")),
            (false, _) => Some(format!(
                "condition \"{self}\" is false ({})",
                failing.join(", ")
            )),
        }
    }

    /// Whether no feature set satisfies both: one requires a feature the other forbids.
    /// Passes with exclusive conditions may write the same version, since at most one of
    /// them is ever in a compiled graph.
    pub fn excludes(&self, other: &Condition) -> bool {
        self.literals.iter().any(|l| {
            other
                .literals
                .iter()
                .any(|m| m.feature == l.feature && m.negated != l.negated)
        })
    }

    /// Whether every feature set satisfying this condition satisfies `other`: each of
    /// `other`'s literals is one of this one's.
    pub fn implies(&self, other: &Condition) -> bool {
        other.literals.iter().all(|m| self.literals.contains(m))
    }

    /// The features the condition names, as written.
    pub fn features(&self) -> impl Iterator<Item = &str> {
        self.literals.iter().map(|l| l.feature.as_str())
    }

    /// The smallest feature set that satisfies the condition: its positive literals.
    pub fn witness(&self) -> Features {
        self.literals
            .iter()
            .filter(|l| !l.negated)
            .map(|l| l.feature.clone())
            .collect()
    }
}

impl fmt::Display for Condition {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, literal) in self.literals.iter().enumerate() {
            if i > 0 {
                f.write_str(" & ")?;
            }
            write!(f, "{literal}")?;
        }
        Ok(())
    }
}

impl From<Condition> for String {
    fn from(condition: Condition) -> String {
        condition.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::{Condition, Features};

    #[test]
    fn a_conjunction_holds_when_every_literal_does() {
        let c = Condition::feature("spot_lights").and(Condition::not("unlit_only"));
        assert_eq!(c.to_string(), "spot_lights & !unlit_only");
        assert!(c.holds(&Features::from_iter(["spot_lights"])));
        assert!(!c.holds(&Features::from_iter(["spot_lights", "unlit_only"])));
        assert_eq!(
            c.why_false(&Features::from_iter(["unlit_only"])).unwrap(),
            "condition \"spot_lights & !unlit_only\" is false (\"spot_lights\" is not set, \
             \"unlit_only\" is set)"
        );
        assert_eq!(
            Condition::feature("spot_lights")
                .why_false(&Features::new())
                .unwrap(),
            "condition \"spot_lights\" is false"
        );
    }

    #[test]
    fn conditions_exclude_each_other_when_one_forbids_what_the_other_needs() {
        let lit = Condition::not("unlit_only");
        let unlit = Condition::feature("unlit_only").and(Condition::feature("emissive"));
        assert!(lit.excludes(&unlit) && unlit.excludes(&lit));
        assert!(!lit.excludes(&Condition::feature("emissive")));
        assert_eq!(
            unlit.witness(),
            Features::from_iter(["unlit_only", "emissive"])
        );
    }
}
