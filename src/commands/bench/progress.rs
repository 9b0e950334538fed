//! A progress bar over the (scene, pipeline) items on stderr; one plain line per item
//! when stderr is not a terminal, so logs keep the record without control characters.

use std::io::IsTerminal;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressStyle};

pub struct Progress {
    /// `None` when stderr is not a terminal.
    bar: Option<ProgressBar>,
    total: usize,
    done: usize,
}

impl Progress {
    pub fn new(total: usize) -> Self {
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = ProgressBar::new(total as u64);
            // The template is a constant: it parses, or this line never shipped.
            let style = ProgressStyle::with_template(
                "{bar:30} {pos}/{len} {elapsed:>4} eta {eta:>4} {wide_msg}",
            )
            .expect("valid progress template");
            bar.set_style(style);
            bar.enable_steady_tick(Duration::from_millis(200));
            bar
        });
        Progress {
            bar,
            total,
            done: 0,
        }
    }

    /// Starts the next item.
    pub fn item(&mut self, what: impl Into<String>) {
        let what = what.into();
        self.done += 1;
        match &self.bar {
            Some(bar) => {
                bar.set_position(self.done as u64 - 1);
                bar.set_message(what);
            }
            None => eprintln!("[{}/{}] {what}", self.done, self.total),
        }
    }

    /// `more` items found to do after the start (a scene measured in several groups).
    pub fn add(&mut self, more: usize) {
        self.total += more;
        if let Some(bar) = &self.bar {
            bar.set_length(self.total as u64);
        }
    }

    /// A line that stays, printed above the bar.
    pub fn note(&self, line: impl AsRef<str>) {
        match &self.bar {
            Some(bar) => bar.println(line),
            None => eprintln!("{}", line.as_ref()),
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
