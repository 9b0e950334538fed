//! Render stages on stderr: a spinner naming the current stage on a terminal, one plain
//! line per stage otherwise (logs and CI keep the record without control characters).

use std::io::IsTerminal;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressStyle};

pub struct Progress {
    /// `None` when stderr is not a terminal.
    spinner: Option<ProgressBar>,
    stages: usize,
    done: usize,
}

impl Progress {
    pub fn new(stages: usize) -> Self {
        let spinner = std::io::stderr().is_terminal().then(|| {
            let bar = ProgressBar::new_spinner();
            // `wide_msg` cuts long stage names (adapter names) to the terminal's width
            // instead of wrapping, which would leave stale lines behind. The template is
            // a constant: it parses, or this line never shipped.
            let style =
                ProgressStyle::with_template("{spinner} [{pos}/{len}] {elapsed:>3} {wide_msg}")
                    .expect("valid progress template");
            bar.set_style(style);
            bar.set_length(stages as u64);
            bar.enable_steady_tick(Duration::from_millis(100));
            bar
        });
        Self {
            spinner,
            stages,
            done: 0,
        }
    }

    /// Starts the next stage.
    pub fn stage(&mut self, what: impl Into<String>) {
        self.done += 1;
        let what = what.into();
        match &self.spinner {
            Some(bar) => {
                bar.set_position(self.done as u64);
                bar.set_message(what);
            }
            None => eprintln!("[{}/{}] {what}", self.done, self.stages),
        }
    }

    /// A line that stays, printed above the spinner.
    pub fn note(&self, line: impl AsRef<str>) {
        match &self.spinner {
            Some(bar) => bar.println(line),
            None => eprintln!("{}", line.as_ref()),
        }
    }
}

impl Drop for Progress {
    /// Errors and the summary print after the spinner, never through it.
    fn drop(&mut self) {
        if let Some(bar) = &self.spinner {
            bar.finish_and_clear();
        }
    }
}
