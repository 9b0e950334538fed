//! A pass parameter that turns work on or off, written `true` or `false` in a graph file,
//! or as a graph parameter's value, 1 or 0 (`occlusion: Param(name: "occlusion", default:
//! 1)`, which `rgraph render --param occlusion=0` sets: parameters are numbers).

use serde::de::{self, Deserializer, Visitor};
use serde::Deserialize;

#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Switch {
    On,
    Off,
}

/// By hand: a boolean, or a number that is 1 or 0.
impl<'de> Deserialize<'de> for Switch {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct SwitchVisitor;

        impl Visitor<'_> for SwitchVisitor {
            type Value = Switch;

            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("true or false (or 1 or 0, a parameter's value)")
            }

            fn visit_bool<E: de::Error>(self, value: bool) -> Result<Switch, E> {
                Ok(if value { Switch::On } else { Switch::Off })
            }

            fn visit_u64<E: de::Error>(self, value: u64) -> Result<Switch, E> {
                match value {
                    0 | 1 => self.visit_bool(value == 1),
                    _ => Err(E::invalid_value(de::Unexpected::Unsigned(value), &self)),
                }
            }

            fn visit_i64<E: de::Error>(self, value: i64) -> Result<Switch, E> {
                match u64::try_from(value) {
                    Ok(value) => self.visit_u64(value),
                    Err(_) => Err(E::invalid_value(de::Unexpected::Signed(value), &self)),
                }
            }
        }

        deserializer.deserialize_any(SwitchVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::Switch;

    fn read(text: &str) -> Result<Switch, ron::error::SpannedError> {
        ron::from_str(text)
    }

    #[test]
    fn a_switch_reads_as_a_boolean_or_a_parameter_s_value() {
        assert_eq!(read("true").unwrap(), Switch::On);
        assert_eq!(read("false").unwrap(), Switch::Off);
        assert_eq!(read("1").unwrap(), Switch::On);
        assert_eq!(read("0").unwrap(), Switch::Off);
        for wrong in ["2", "-1", "on", "\"true\""] {
            let error = read(wrong).expect_err(wrong).to_string();
            assert!(
                error.contains("true or false (or 1 or 0"),
                "{wrong}: {error}"
            );
        }
    }
}
