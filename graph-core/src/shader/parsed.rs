//! Shaders parsed before, by their text: a graph load parses the WGSL of every pass it
//! sets up (the deferred passes compose theirs from parts), and most loads of a process
//! parse texts an earlier one did (a reload, the next render of a test, the next input
//! of a fuzzer, where naga's parsing was four fifths of the time).
//!
//! # Contract
//!
//! - **Owner.** The process: one table behind a lock (`wgsl.rs`'s static). Shaders are
//!   immutable and their clones share one parse, so a shader found here is the one
//!   parsing would give.
//! - **Key.** Everything a parse reads: the path messages name, the text (after a
//!   byte-order mark is stripped) and the features validation allows.
//! - **Invalidation.** None: a parse is a function of its key. Only successes are kept;
//!   a text that fails is parsed again each time, for its error. The table holds at most
//!   [`KEPT`] shaders and is emptied when full, which bounds what a process that parses
//!   ever new texts (an editor's live reload) holds.

use std::collections::HashMap;
use std::sync::{Mutex, PoisonError};

use wgpu_types::Features;

/// The most shaders kept: more than the shipped passes' variants that one process parses.
pub(super) const KEPT: usize = 4096;

#[derive(PartialEq, Eq, Hash)]
struct Key {
    path: String,
    source: String,
    features: Features,
}

/// Shaders (`S`, cheap to clone) by what they were parsed from.
pub(super) struct Parsed<S>(Mutex<Option<HashMap<Key, S>>>);

impl<S: Clone> Parsed<S> {
    pub(super) const fn new() -> Self {
        Parsed(Mutex::new(None))
    }

    /// The shader `parse` gives for `path`, `source` and `features`: one kept from an
    /// earlier call with the same three, or `parse`'s, kept when it succeeds. The table
    /// is not locked while `parse` runs, so threads parse in parallel (two parsing one
    /// text keep either).
    pub(super) fn get<E>(
        &self,
        path: String,
        source: String,
        features: Features,
        parse: impl FnOnce(String, String) -> Result<S, E>,
    ) -> Result<S, E> {
        let table = || self.0.lock().unwrap_or_else(PoisonError::into_inner);
        let key = Key {
            path,
            source,
            features,
        };
        if let Some(shader) = table().get_or_insert_default().get(&key) {
            return Ok(shader.clone());
        }
        let shader = parse(key.path.clone(), key.source.clone())?;
        let mut table = table();
        let kept = table.get_or_insert_default();
        if kept.len() == KEPT {
            kept.clear();
        }
        kept.insert(key, shader.clone());
        Ok(shader)
    }
}

#[cfg(test)]
mod tests {
    use wgpu_types::Features;

    use crate::shader::Shader;

    const WGSL: &str = "@compute @workgroup_size(1) fn main() {}";

    #[test]
    fn a_text_parsed_again_is_the_same_parse_and_another_path_or_text_is_not() {
        let first = Shader::parse("kept.wgsl", WGSL).expect("valid WGSL");
        let again = Shader::parse("kept.wgsl", WGSL).expect("valid WGSL");
        assert!(std::ptr::eq(first.module(), again.module()));
        let elsewhere = Shader::parse("other.wgsl", WGSL).expect("valid WGSL");
        assert!(!std::ptr::eq(first.module(), elsewhere.module()));
        assert_eq!(elsewhere.path(), "other.wgsl");
        let features = Shader::parse_for("kept.wgsl", WGSL, Features::SHADER_INT64);
        assert!(!std::ptr::eq(
            first.module(),
            features.expect("valid").module()
        ));
        let longer = format!("{WGSL}\n");
        let longer = Shader::parse("kept.wgsl", longer).expect("valid WGSL");
        assert!(!std::ptr::eq(first.module(), longer.module()));
    }

    #[test]
    fn a_text_that_fails_fails_every_time() {
        for _ in 0..2 {
            let error = Shader::parse("broken.wgsl", "fn main( {").expect_err("invalid WGSL");
            assert!(error.to_string().contains("broken.wgsl"), "{error}");
        }
    }
}
