//! Byte offsets to line and column in constant time per lookup (after one pass over the
//! text), so placing every name of a large graph file stays linear in its size.

use crate::position::Position;

/// How far apart (in bytes) the character counts are recorded: a lookup counts at most
/// this many bytes' characters, whatever the length of the line.
const STRIDE: usize = 256;

/// Where each line starts, and how many characters precede every `STRIDE`-th byte.
pub(crate) struct LineIndex<'a> {
    text: &'a str,
    /// Byte offset of the start of each line; the first is 0.
    line_starts: Vec<usize>,
    /// `(byte offset, characters before it)` at the first character boundary at or after
    /// each multiple of `STRIDE`.
    checkpoints: Vec<(usize, usize)>,
}

impl<'a> LineIndex<'a> {
    pub fn new(text: &'a str) -> Self {
        let mut line_starts = vec![0];
        let mut checkpoints = vec![(0, 0)];
        for (chars, (offset, c)) in text.char_indices().enumerate() {
            if offset >= checkpoints.last().map_or(0, |(o, _)| *o) + STRIDE {
                checkpoints.push((offset, chars));
            }
            if c == '\n' {
                line_starts.push(offset + 1);
            }
        }
        LineIndex {
            text,
            line_starts,
            checkpoints,
        }
    }

    /// The same as [`Position::of_offset`]: an offset past the end, or one that is not a
    /// character boundary, is counted as the end of the text.
    pub fn position(&self, offset: usize) -> Position {
        let offset = match self.text.is_char_boundary(offset) {
            true => offset,
            false => self.text.len(),
        };
        let line = self.line_starts.partition_point(|&start| start <= offset);
        let line_start = self.line_starts[line - 1];
        Position {
            line,
            column: 1 + self.chars_before(offset) - self.chars_before(line_start),
        }
    }

    /// How many characters precede byte `offset` (a character boundary).
    fn chars_before(&self, offset: usize) -> usize {
        let at = self.checkpoints.partition_point(|&(o, _)| o <= offset) - 1;
        let (from, chars) = self.checkpoints[at];
        chars + self.text[from..offset].chars().count()
    }
}

#[cfg(test)]
mod tests {
    use super::LineIndex;
    use crate::position::Position;

    #[test]
    fn agrees_with_scanning_at_every_offset() {
        let line = "ab é x\n".repeat(40) + &"ü".repeat(300) + "\n\nend";
        let texts = ["", "\n", "a", "é\n", line.as_str()];
        for text in texts {
            let index = LineIndex::new(text);
            for offset in 0..=text.len() + 2 {
                assert_eq!(
                    index.position(offset),
                    Position::of_offset(text, offset),
                    "offset {offset} of {text:?}"
                );
            }
        }
    }
}
