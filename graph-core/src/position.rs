//! Line and column positions in source text, as editors and compilers count them.

use std::fmt;

/// A 1-based line and column. Columns count characters, not bytes, as `ron` does, so a
/// position from a `ron` error and one computed here agree.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Position {
    /// Line, from 1.
    pub line: usize,
    /// Column in characters, from 1.
    pub column: usize,
}

impl Position {
    /// The start of a file.
    pub const START: Position = Position { line: 1, column: 1 };

    /// The position of byte `offset` in `text`. An offset past the end, or one that is not
    /// a character boundary, is counted as the end of the text.
    pub fn of_offset(text: &str, offset: usize) -> Position {
        let before = text.get(..offset).unwrap_or(text);
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        Position {
            line: 1 + before.matches('\n').count(),
            column: 1 + before[line_start..].chars().count(),
        }
    }

    /// The next position in `text` that is not whitespace: `ron` places some errors at
    /// the whitespace before the token at fault.
    pub fn skip_whitespace(self, text: &str) -> Position {
        let line_start: usize = text
            .split_inclusive('\n')
            .take(self.line.saturating_sub(1))
            .map(str::len)
            .sum();
        let offset = text[line_start..]
            .char_indices()
            .nth(self.column.saturating_sub(1))
            .map(|(i, _)| line_start + i);
        let token = offset.and_then(|o| {
            text[o..]
                .char_indices()
                .find(|(_, c)| !c.is_whitespace())
                .map(|(i, _)| o + i)
        });
        token.map_or(self, |t| Position::of_offset(text, t))
    }

    /// This position seen from a text that embeds the text it was counted in at `base`:
    /// the first line shifts by the base column, later lines only by the base line.
    pub fn within(self, base: Position) -> Position {
        if self.line == 1 {
            Position {
                line: base.line,
                column: base.column + self.column - 1,
            }
        } else {
            Position {
                line: base.line + self.line - 1,
                column: self.column,
            }
        }
    }
}

impl From<ron::error::Position> for Position {
    fn from(p: ron::error::Position) -> Self {
        Position {
            line: p.line,
            column: p.col,
        }
    }
}

impl fmt::Display for Position {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

#[cfg(test)]
mod tests {
    use super::Position;

    #[test]
    fn offsets_count_lines_and_characters() {
        let text = "ab\né x\n";
        assert_eq!(Position::of_offset(text, 0), Position::START);
        assert_eq!(
            Position::of_offset(text, 3),
            Position { line: 2, column: 1 }
        );
        // 'é' is two bytes but one column.
        assert_eq!(
            Position::of_offset(text, 6),
            Position { line: 2, column: 3 }
        );
    }

    #[test]
    fn whitespace_is_skipped_up_to_the_next_token() {
        let text = "(a: \n   b)";
        let after_colon = Position { line: 1, column: 4 };
        assert_eq!(
            after_colon.skip_whitespace(text),
            Position { line: 2, column: 4 }
        );
        assert_eq!(Position::START.skip_whitespace(text), Position::START);
        let past_end = Position { line: 9, column: 1 };
        assert_eq!(past_end.skip_whitespace(text), past_end);
    }

    #[test]
    fn embedded_positions_shift_by_the_base() {
        let base = Position {
            line: 4,
            column: 10,
        };
        let first = Position { line: 1, column: 3 };
        let later = Position { line: 2, column: 3 };
        assert_eq!(
            first.within(base),
            Position {
                line: 4,
                column: 12
            }
        );
        assert_eq!(later.within(base), Position { line: 5, column: 3 });
    }
}
