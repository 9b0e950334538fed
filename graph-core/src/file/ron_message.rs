//! `ron`'s error messages in a graph file's terms: a few of them give advice to the
//! programmer calling `ron` (raise `ron::Options::recursion_limit`, use `serde_stacker`, a
//! raw identifier `r#...`), which means nothing to someone writing a graph file.

/// How deep `ron` lets values nest by default ([`ron::Options`]'s recursion limit).
const NESTING_LIMIT: usize = 128;

/// The message for `error`, for the author of a graph file.
pub(crate) fn describe(error: &ron::Error) -> String {
    match error {
        ron::Error::ExceededRecursionLimit => {
            format!("values are nested more than {NESTING_LIMIT} levels deep")
        }
        ron::Error::SuggestRawIdentifier(identifier) => {
            format!("`{identifier}` is not a valid field or variant name")
        }
        ron::Error::ExpectedRawValue => "expected a value".to_owned(),
        ron::Error::UnclosedLineComment => {
            "a line comment at the end of the parameters must end with a newline".to_owned()
        }
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::describe;

    #[test]
    fn no_message_mentions_ron_s_api() {
        for error in [
            ron::Error::ExceededRecursionLimit,
            ron::Error::SuggestRawIdentifier("3".to_owned()),
            ron::Error::ExpectedRawValue,
            ron::Error::UnclosedLineComment,
        ] {
            let message = describe(&error);
            for internal in ["ron::", "serde", "r#", "RawValue"] {
                assert!(!message.contains(internal), "{message}");
            }
        }
        assert_eq!(
            describe(&ron::Error::ExceededRecursionLimit),
            "values are nested more than 128 levels deep"
        );
    }
}
