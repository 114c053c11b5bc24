//! A progress bar with ETA on stderr, shown only when stderr is a terminal
//! and only once the work has taken more than half a second.

use std::io::IsTerminal;
use std::sync::OnceLock;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::clock::Stopwatch;

/// How long work runs silently before a bar appears.
const SHOW_AFTER: Duration = Duration::from_millis(500);

/// Progress of one piece of work measured in units (pixels), safe to advance
/// from worker threads.
#[derive(Debug)]
pub struct Progress {
    bar: ProgressBar,
    start: Stopwatch,
    shown: OnceLock<()>,
    enabled: bool,
}

impl Progress {
    /// Progress over `total` units, labelled `what` ("rendering").
    pub fn new(total: u64, what: &str) -> Progress {
        Progress::styled(total, &format!("{what} [{{bar:40}}] {{percent:>3}}% eta {{eta}}"))
    }

    /// Progress of a render in the interactive session, which Ctrl-C can
    /// cancel.
    pub fn in_session(total: u64, what: &str) -> Progress {
        Progress::styled(total, &format!("{what} [{{bar:30}}] {{percent}}% ({{elapsed}}, Ctrl-C cancels)"))
    }

    /// A bar drawn with the indicatif `template`, shown only when stderr is
    /// a terminal.
    fn styled(total: u64, template: &str) -> Progress {
        let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("=> "));
        }
        let enabled = std::io::stderr().is_terminal();
        Progress { bar, start: Stopwatch::start(), shown: OnceLock::new(), enabled }
    }

    /// Records `units` more done; shows the bar once the work is slow enough to need it.
    pub fn advance(&self, units: u64) {
        self.bar.inc(units);
        if self.enabled && self.start.elapsed() > SHOW_AFTER {
            self.shown.get_or_init(|| self.bar.set_draw_target(ProgressDrawTarget::stderr()));
        }
    }

    /// Removes the bar from the screen (also done when it is dropped).
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish();
    }
}
