//! `builtin:NAME?key=value&key=value` parameters.

use crate::scene::SceneError;

/// The parameters given to one built-in scene, checked against the keys it declares.
pub(crate) struct Params<'a> {
    scene: &'a str,
    pairs: Vec<(&'a str, &'a str)>,
}

impl<'a> Params<'a> {
    /// Splits `query` (`key=value` pairs joined by `&`, possibly empty) and rejects keys not in
    /// `known`, naming the ones that are.
    pub fn parse(
        scene: &'a str,
        query: &'a str,
        known: &[(&str, &str)],
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
            .find(|(key, _)| !known.iter().any(|(k, _)| k == key))
        {
            let keys: Vec<&str> = known.iter().map(|(k, _)| *k).collect();
            return Err(error(format!(
                "unknown parameter `{key}`; this scene takes: {}",
                if keys.is_empty() {
                    "none".to_owned()
                } else {
                    keys.join(", ")
                }
            )));
        }
        Ok(Params { scene, pairs })
    }

    /// The last value given for `key` as an unsigned integer, or `default`.
    pub fn u32(&self, key: &str, default: u32) -> Result<u32, SceneError> {
        match self.pairs.iter().rev().find(|(k, _)| *k == key) {
            None => Ok(default),
            Some((_, value)) => value.parse().map_err(|_| SceneError::BuiltinParameter {
                scene: self.scene.to_owned(),
                reason: format!("`{key}={value}`: expected a non-negative integer"),
            }),
        }
    }
}
