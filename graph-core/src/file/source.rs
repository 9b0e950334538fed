//! A graph file's text and path: turns names and raw values that borrow from the text,
//! and `ron`'s spans, into positioned errors.

use std::path::Path;

use super::error::{ErrorKind, FileError, Location};
use super::line_index::LineIndex;
use super::ron_message;
use super::schema::{offset_in, Name};
use crate::position::Position;

pub(crate) struct Source<'a> {
    /// The file the user named: file-level errors point here.
    main: Text<'a>,
    /// The other files the graph is read from: a preset's base (see `load::apply_preset`)
    /// and the parts it uses (see `compose`). Names and values borrowed from one of them
    /// are placed in it.
    others: Vec<Text<'a>>,
    /// Whether the main file is a preset, whose graph is in `others[0]`.
    preset: bool,
}

/// One file's path and text.
struct Text<'a> {
    path: &'a Path,
    text: &'a str,
    /// Built once: every name of the file is placed through it.
    lines: LineIndex<'a>,
}

impl<'a> Text<'a> {
    fn new(path: &'a Path, text: &'a str) -> Self {
        Text {
            path,
            text,
            lines: LineIndex::new(text),
        }
    }

    fn location(&self, at: Position) -> Location {
        Location {
            path: self.path.display().to_string(),
            at,
        }
    }
}

impl<'a> Source<'a> {
    pub fn new(path: &'a Path, text: &'a str) -> Self {
        Source {
            main: Text::new(path, text),
            others: Vec::new(),
            preset: false,
        }
    }

    /// A preset at `path` over the graph file `base` (its path and text): the graph is the
    /// base's, with parts borrowed from the preset's text.
    pub fn with_base(path: &'a Path, text: &'a str, base: (&'a Path, &'a str)) -> Self {
        Source {
            main: Text::new(path, text),
            others: vec![Text::new(base.0, base.1)],
            preset: true,
        }
    }

    /// Adds a file the graph reads names from: a part it uses.
    pub fn add(&mut self, path: &'a Path, text: &'a str) {
        self.others.push(Text::new(path, text));
    }

    /// The file whose text holds `part`: one of the others', or the main file's (also for
    /// text that is in none, such as a copied name).
    fn text_of(&self, part: &str) -> &Text<'a> {
        self.others
            .iter()
            .find(|other| offset_in(other.text, part).is_some())
            .unwrap_or(&self.main)
    }

    /// Whether `part` is text of a preset over a base (a change the preset makes), not
    /// the base's.
    pub fn in_preset(&self, part: &str) -> bool {
        self.preset && offset_in(self.main.text, part).is_some()
    }

    /// The directory relative paths in the graph are resolved against: the graph's file
    /// (a preset's base), where its passes are written.
    pub fn dir(&self) -> &'a Path {
        let graph = match self.preset {
            true => &self.others[0],
            false => &self.main,
        };
        graph.path.parent().unwrap_or(Path::new(""))
    }

    /// The directory relative paths written beside `name` resolve against: that of the
    /// file `name` is written in (a part's, for its passes' shaders).
    pub fn dir_of(&self, name: &Name<'_>) -> &'a Path {
        let file = self.text_of(name.written_text());
        file.path.parent().unwrap_or(Path::new(""))
    }

    /// A position in the file the user named.
    pub fn location(&self, at: Position) -> Location {
        self.main.location(at)
    }

    /// Where a name is written: its opening quote, in the file it is written in. A name
    /// with escapes (a copy, not a slice of the text) is placed at the start of the file.
    pub fn locate(&self, name: &Name<'_>) -> Location {
        let file = self.text_of(name.written_text());
        let at = name.offset(file.text).map_or(Position::START, |offset| {
            let quote = offset
                .checked_sub(1)
                .filter(|&q| file.text.as_bytes()[q] == b'"');
            file.lines.position(quote.unwrap_or(offset))
        });
        file.location(at)
    }

    /// Where the character `column` (counted from 0) of `name`'s text is, when the name
    /// borrows from a file; else where the name is.
    pub fn locate_in(&self, name: &Name<'_>, column: usize) -> Location {
        let file = self.text_of(name.written_text());
        let Some(column) = name.written_column(column) else {
            return self.locate(name);
        };
        let within = name
            .written_text()
            .char_indices()
            .nth(column)
            .map_or(name.written_text().len(), |(i, _)| i);
        match name.offset(file.text) {
            Some(offset) => file.location(file.lines.position(offset + within)),
            None => self.locate(name),
        }
    }

    /// An error pointing at `name`.
    pub fn error(&self, name: &Name<'_>, kind: ErrorKind) -> FileError {
        FileError {
            location: self.locate(name),
            kind,
        }
    }

    /// Where a raw value (its text) starts.
    pub fn locate_raw(&self, raw: &str) -> Location {
        self.locate_raw_at(raw, 0)
    }

    /// Where byte `within` of a raw value's text is.
    pub fn locate_raw_at(&self, raw: &str, within: usize) -> Location {
        let file = self.text_of(raw);
        let at = offset_in(file.text, raw).map_or(Position::START, |offset| {
            file.lines.position(offset + within)
        });
        file.location(at)
    }

    /// A `ron` error in the whole file.
    pub fn syntax(&self, error: &ron::error::SpannedError) -> FileError {
        let at = Position::from(error.span.start).skip_whitespace(self.main.text);
        FileError {
            location: self.location(at),
            kind: ErrorKind::Syntax {
                message: ron_message::describe(&error.code),
            },
        }
    }
}
