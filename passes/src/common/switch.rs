//! A pass parameter that turns work on or off, written `on` or `off` in a graph file, or
//! as a graph parameter's value, 1 or 0 (`occlusion: Param(name: "occlusion", default:
//! 1)`, which `rgraph render --param occlusion=0` sets: parameters are numbers).

use serde::de::{self, Deserializer, Visitor};
use serde::Deserialize;

#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Switch {
    On,
    Off,
}

/// By hand: `on` and `off` reach a visitor as an enum's unit variants or as identifiers,
/// a parameter's value as a number.
impl<'de> Deserialize<'de> for Switch {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct SwitchVisitor;

        impl<'de> Visitor<'de> for SwitchVisitor {
            type Value = Switch;

            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("on or off (or 1 or 0, a parameter's value)")
            }

            fn visit_u64<E: de::Error>(self, value: u64) -> Result<Switch, E> {
                match value {
                    1 => Ok(Switch::On),
                    0 => Ok(Switch::Off),
                    _ => Err(E::invalid_value(de::Unexpected::Unsigned(value), &self)),
                }
            }

            fn visit_i64<E: de::Error>(self, value: i64) -> Result<Switch, E> {
                match u64::try_from(value) {
                    Ok(value) => self.visit_u64(value),
                    Err(_) => Err(E::invalid_value(de::Unexpected::Signed(value), &self)),
                }
            }

            fn visit_str<E: de::Error>(self, value: &str) -> Result<Switch, E> {
                match value {
                    "on" => Ok(Switch::On),
                    "off" => Ok(Switch::Off),
                    _ => Err(E::invalid_value(de::Unexpected::Str(value), &self)),
                }
            }

            fn visit_enum<A: de::EnumAccess<'de>>(self, data: A) -> Result<Switch, A::Error> {
                use de::VariantAccess;
                let (name, variant): (String, _) = data.variant()?;
                variant.unit_variant()?;
                self.visit_str(&name)
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
    fn a_switch_reads_as_a_word_or_a_parameter_s_value() {
        assert_eq!(read("on").unwrap(), Switch::On);
        assert_eq!(read("off").unwrap(), Switch::Off);
        assert_eq!(read("1").unwrap(), Switch::On);
        assert_eq!(read("0").unwrap(), Switch::Off);
        for wrong in ["2", "-1", "yes"] {
            assert!(read(wrong).is_err(), "{wrong} read as a switch");
        }
    }
}
