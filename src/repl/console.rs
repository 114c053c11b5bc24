//! Where the session writes: messages to one stream, errors and diagnostics
//! to another, with colours only for terminals.

use std::fmt::Display;
use std::io::Write;

use crate::lang::{Diagnostic, SourceMap};

use super::cancel::CancelSwitch;
use super::preview::Preview;

/// The session's output and what it may do on the terminal.
pub(crate) struct Console<'a> {
    out: &'a mut dyn Write,
    err: &'a mut dyn Write,
    /// ANSI colours in messages and diagnostics.
    pub color: bool,
    /// Where renders are shown; `None` when previews are off.
    pub preview: Option<Preview>,
    /// Progress bars on standard error for long renders.
    pub progress: bool,
    /// Ctrl-C cancels renders through this switch, when installed.
    pub cancel: Option<&'static CancelSwitch>,
}

impl<'a> Console<'a> {
    /// A plain console: no colours, previews, progress bars or Ctrl-C handling.
    pub(crate) fn plain(out: &'a mut dyn Write, err: &'a mut dyn Write) -> Console<'a> {
        Console { out, err, color: false, preview: None, progress: false, cancel: None }
    }

    /// Writes one line of information. Output errors (a closed pipe) are
    /// ignored: the session goes on and the exit status tells what happened.
    pub(crate) fn say(&mut self, text: impl Display) {
        let _ = writeln!(self.out, "{text}");
        let _ = self.out.flush();
    }

    /// Writes a one-line note that helps a learner along.
    pub(crate) fn note(&mut self, text: impl Display) {
        let label = self.paint("note:", "36");
        self.say(format_args!("{label} {text}"));
    }

    /// Writes an error message that is not about program text.
    pub(crate) fn error(&mut self, text: impl Display) {
        let label = self.paint("error:", "1;31");
        let _ = writeln!(self.err, "{label} {text}");
        let _ = self.err.flush();
    }

    /// Writes a line the program printed (`print`), with the diagnostics.
    pub(crate) fn printed(&mut self, line: impl Display) {
        let _ = writeln!(self.err, "{line}");
        let _ = self.err.flush();
    }

    /// Writes a diagnostic about program text.
    pub(crate) fn diagnostic(&mut self, diagnostic: &Diagnostic, sources: &SourceMap) {
        let text = diagnostic.render(sources, self.color);
        let _ = write!(self.err, "{text}");
        if !text.ends_with('\n') {
            let _ = writeln!(self.err);
        }
        let _ = self.err.flush();
    }

    /// `text` in the ANSI style `code` when colours are on.
    pub(crate) fn paint(&self, text: &str, code: &str) -> String {
        if self.color { format!("\x1b[{code}m{text}\x1b[0m") } else { text.to_string() }
    }
}
