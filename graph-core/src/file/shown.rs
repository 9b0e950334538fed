//! Text from a graph file quoted in a message.

use std::fmt;

/// A reference as messages show it: control characters (a NUL, a newline) escaped, so a
/// hostile file cannot write to the terminal through an error.
pub(crate) struct Shown<'a>(pub &'a str);

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "\"{}\"", self.0.escape_debug())
    }
}
