//! Reading conditions as graph files and code write them: `a`, `!a`, `a & !b`.

use std::str::FromStr;

use thiserror::Error;

use super::expr::{Condition, Literal};

/// A condition that does not parse. `column` counts characters from the start of the
/// condition's text (0-based), so a graph file can point at the character at fault.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum ConditionError {
    /// The condition names no feature.
    #[error("a condition names at least one feature (`feature`, `!feature` or `a & !b`)")]
    Empty,

    /// Something other than a feature name where one belongs.
    #[error("expected a feature name, found {found}; conditions read `a & !b` (only `&` and `!`)")]
    Expected {
        /// Characters from the start of the condition to the fault.
        column: usize,
        /// What stands there, quoted, or "the end".
        found: String,
    },

    /// A feature both required and forbidden (`a & !a`): the condition could never hold.
    #[error("\"{feature}\" is both required and forbidden, so the condition never holds")]
    Contradiction {
        /// Characters from the start of the condition to the fault.
        column: usize,
        /// The feature.
        feature: String,
    },
}

impl ConditionError {
    /// Where the error is, in characters from the start of the condition.
    pub fn column(&self) -> usize {
        match self {
            ConditionError::Empty => 0,
            ConditionError::Expected { column, .. }
            | ConditionError::Contradiction { column, .. } => *column,
        }
    }
}

impl Condition {
    /// Parses `literal (& literal)*`, each literal a feature name (ASCII letters, digits
    /// and `_`, not starting with a digit) with an optional `!`. Spaces are ignored.
    pub fn parse(text: &str) -> Result<Condition, ConditionError> {
        let chars: Vec<char> = text.chars().collect();
        if chars.iter().all(|c| c.is_whitespace()) {
            return Err(ConditionError::Empty);
        }
        let mut at = 0;
        let mut literals: Vec<Literal> = Vec::new();
        loop {
            skip_spaces(&chars, &mut at);
            let negated = chars.get(at) == Some(&'!');
            if negated {
                at += 1;
                skip_spaces(&chars, &mut at);
            }
            let start = at;
            while chars
                .get(at)
                .is_some_and(|&c| c.is_ascii_alphanumeric() || c == '_')
            {
                at += 1;
            }
            if start == at || chars[start].is_ascii_digit() {
                return Err(expected(&chars, start));
            }
            let feature: String = chars[start..at].iter().collect();
            if literals
                .iter()
                .any(|l| l.feature == feature && l.negated != negated)
            {
                return Err(ConditionError::Contradiction {
                    column: start,
                    feature,
                });
            }
            let literal = Literal { feature, negated };
            if !literals.contains(&literal) {
                literals.push(literal);
            }
            skip_spaces(&chars, &mut at);
            match chars.get(at) {
                None => return Ok(Condition { literals }),
                Some('&') => at += 1,
                Some(_) => return Err(expected_and(&chars, at)),
            }
        }
    }
}

/// Parses, as [`Condition::parse`]: how serde reads a condition written as text.
impl TryFrom<String> for Condition {
    type Error = ConditionError;

    fn try_from(text: String) -> Result<Condition, Self::Error> {
        Condition::parse(&text)
    }
}

impl FromStr for Condition {
    type Err = ConditionError;

    fn from_str(text: &str) -> Result<Condition, ConditionError> {
        Condition::parse(text)
    }
}

fn skip_spaces(chars: &[char], at: &mut usize) {
    while chars.get(*at).is_some_and(|c| c.is_whitespace()) {
        *at += 1;
    }
}

fn expected(chars: &[char], column: usize) -> ConditionError {
    ConditionError::Expected {
        column,
        found: match chars.get(column) {
            Some(c) => format!("'{c}'"),
            None => "the end".into(),
        },
    }
}

/// After a literal only `&` or the end may follow.
fn expected_and(chars: &[char], column: usize) -> ConditionError {
    ConditionError::Expected {
        column,
        found: format!("'{}' after a feature", chars[column]),
    }
}

#[cfg(test)]
mod tests {
    use super::{Condition, ConditionError};

    #[test]
    fn literals_and_conjunctions_parse_as_written() {
        for (text, shown) in [
            ("spot_lights", "spot_lights"),
            ("!unlit_only", "!unlit_only"),
            (" spot_lights&! unlit_only ", "spot_lights & !unlit_only"),
            ("a & a", "a"),
        ] {
            assert_eq!(Condition::parse(text).unwrap().to_string(), shown);
        }
    }

    #[test]
    fn bad_conditions_say_where_and_what() {
        let error = Condition::parse("a | b").unwrap_err();
        assert_eq!(error.column(), 2);
        assert_eq!(
            error.to_string(),
            "expected a feature name, found '|' after a feature; conditions read `a & !b` \
             (only `&` and `!`)"
        );
        assert_eq!(Condition::parse("a & ").unwrap_err().column(), 4);
        assert_eq!(Condition::parse("!!a").unwrap_err().column(), 1);
        assert_eq!(Condition::parse("2d").unwrap_err().column(), 0);
        assert_eq!(Condition::parse("  ").unwrap_err(), ConditionError::Empty);
        let error = Condition::parse("a & !a").unwrap_err();
        assert_eq!(error.column(), 5);
        assert_eq!(
            error.to_string(),
            "\"a\" is both required and forbidden, so the condition never holds"
        );
    }
}
