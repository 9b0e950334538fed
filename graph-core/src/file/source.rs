//! A graph file's text and path: turns names and raw values that borrow from the text,
//! and `ron`'s spans, into positioned errors.

use std::path::Path;

use ron::value::RawValue;

use super::error::{ErrorKind, FileError, Location};
use super::line_index::LineIndex;
use super::ron_message;
use super::schema::{offset_in, Name};
use crate::position::Position;

pub(crate) struct Source<'a> {
    path: &'a Path,
    text: &'a str,
    /// Built once: every name of the file is placed through it.
    lines: LineIndex<'a>,
}

impl<'a> Source<'a> {
    pub fn new(path: &'a Path, text: &'a str) -> Self {
        Source {
            path,
            text,
            lines: LineIndex::new(text),
        }
    }

    /// The directory relative paths in the file are resolved against.
    pub fn dir(&self) -> &'a Path {
        self.path.parent().unwrap_or(Path::new(""))
    }

    pub fn location(&self, at: Position) -> Location {
        Location {
            path: self.path.display().to_string(),
            at,
        }
    }

    /// Where a name is written: its opening quote. A name with escapes (a copy, not a
    /// slice of the text) is placed at the start of the file.
    pub fn position(&self, name: &Name<'_>) -> Position {
        name.offset(self.text).map_or(Position::START, |offset| {
            let quote = offset
                .checked_sub(1)
                .filter(|&q| self.text.as_bytes()[q] == b'"');
            self.lines.position(quote.unwrap_or(offset))
        })
    }

    /// Where the character `column` (counted from 0) of `name`'s text is, when the name
    /// borrows from the file; else where the name is.
    pub fn position_in(&self, name: &Name<'_>, column: usize) -> Position {
        let within = name
            .as_str()
            .char_indices()
            .nth(column)
            .map_or(name.as_str().len(), |(i, _)| i);
        name.offset(self.text)
            .map_or(self.position(name), |offset| {
                self.lines.position(offset + within)
            })
    }

    /// An error pointing at `name`.
    pub fn error(&self, name: &Name<'_>, kind: ErrorKind) -> FileError {
        FileError {
            location: self.location(self.position(name)),
            kind,
        }
    }

    /// Where a raw value starts.
    pub fn raw_position(&self, raw: &RawValue) -> Position {
        offset_in(self.text, raw.get_ron())
            .map_or(Position::START, |offset| self.lines.position(offset))
    }

    /// A `ron` error in the whole file.
    pub fn syntax(&self, error: &ron::error::SpannedError) -> FileError {
        FileError {
            location: self.location(Position::from(error.span.start).skip_whitespace(self.text)),
            kind: ErrorKind::Syntax {
                message: ron_message::describe(&error.code),
            },
        }
    }
}
