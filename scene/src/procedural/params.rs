//! `builtin:NAME?key=value&key=value` parameters.

use crate::SceneError;

/// One parameter a built-in scene takes: a whole number with a default and a documented
/// range, `min..=max`, checked before the scene allocates anything.
pub struct BuiltinParam {
    /// The `key` of `?key=value`.
    pub key: &'static str,
    /// What it means, for help and errors.
    pub meaning: &'static str,
    /// The value used when the spec leaves it out.
    pub default: u32,
    /// The smallest value accepted.
    pub min: u32,
    /// The largest value accepted.
    pub max: u32,
}

/// The parameters given to one built-in scene, checked against the keys it declares.
pub(crate) struct Params<'a> {
    scene: &'a str,
    known: &'static [BuiltinParam],
    pairs: Vec<(&'a str, &'a str)>,
}

impl<'a> Params<'a> {
    /// Splits `query` (`key=value` pairs joined by `&`, possibly empty) and rejects keys not in
    /// `known`, naming the ones that are.
    pub fn parse(
        scene: &'a str,
        query: &'a str,
        known: &'static [BuiltinParam],
    ) -> Result<Params<'a>, SceneError> {
        let error = |reason: String| SceneError::BuiltinParameter {
            scene: scene.to_owned(),
            reason,
        };
        let pairs = query
            .split('&')
            .filter(|pair| !pair.is_empty())
            .map(|pair| {
                pair.split_once('=')
                    .ok_or_else(|| error(format!("`{pair}` is not key=value")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        if let Some((key, _)) = pairs
            .iter()
            .find(|(key, _)| !known.iter().any(|p| p.key == *key))
        {
            let keys: Vec<&str> = known.iter().map(|p| p.key).collect();
            return Err(error(format!(
                "unknown parameter `{key}`; this scene takes: {}",
                if keys.is_empty() {
                    "none".to_owned()
                } else {
                    keys.join(", ")
                }
            )));
        }
        Ok(Params {
            scene,
            known,
            pairs,
        })
    }

    /// The last value given for `key` (one of the scene's declared parameters), or its
    /// default. Fails on anything but a whole number from the parameter's `min` to its `max`.
    pub fn u32(&self, key: &str) -> Result<u32, SceneError> {
        let spec = self
            .known
            .iter()
            .find(|p| p.key == key)
            .expect("scenes only ask for the parameters they declare");
        let Some((_, value)) = self.pairs.iter().rev().find(|(k, _)| *k == key) else {
            return Ok(spec.default);
        };
        let error = |reason: String| SceneError::BuiltinParameter {
            scene: self.scene.to_owned(),
            reason: format!("`{key}={value}`: {reason}"),
        };
        let range = format!("a whole number from {} to {}", spec.min, spec.max);
        // Parsed as u64 so a number just past u32 still gets the range, not "not a number".
        match value.parse::<u64>() {
            Ok(v) if (u64::from(spec.min)..=u64::from(spec.max)).contains(&v) => Ok(v as u32),
            Ok(_) => Err(error(format!("{range} ({})", spec.meaning))),
            Err(_) => Err(error(format!("expected {range}"))),
        }
    }
}
