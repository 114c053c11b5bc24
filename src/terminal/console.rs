//! The session's outputs as text: messages to one stream, errors and
//! diagnostics to another, each with colours where anstream finds they
//! belong. Piped scripts show their outputs with it, and the terminal
//! session their text.

use std::fmt::Display;
use std::io::Write;

use annotate_snippets::renderer::{DEFAULT_EMPHASIS_STYLE, DEFAULT_ERROR_STYLE, DEFAULT_NOTE_STYLE};
use anstream::stream::RawStream;
use anstream::{AutoStream, ColorChoice};

use crate::lang::{Diagnostic, SourceMap};
use crate::presentation::plain_text;
use crate::process::failure::end_if_closed_pipe;
use crate::process::interruption::may_block;

use crate::process::cancel::CancelSwitch;
use crate::session::{FrontEnd, Output, TextRole};

/// The outputs written as text, and the switch Ctrl-C raises.
pub(crate) struct Console<'a> {
    /// The stream for messages, and whether it wants them styled.
    out: &'a mut (dyn Write + 'static),
    out_choice: ColorChoice,
    err: AutoStream<&'a mut (dyn Write + 'static)>,
    /// Ctrl-C stops what an entry does through this switch, when installed.
    pub cancel: Option<&'static CancelSwitch>,
    /// Why something could not be written (a full disk), the first time: a
    /// script then fails.
    pub unwritten: Option<String>,
}

impl<'a> Console<'a> {
    /// A console writing messages to `out` and errors to `err`, each styled
    /// only if it is a terminal that wants colours (`NO_COLOR`,
    /// `CLICOLOR_FORCE` and `CLICOLOR` are followed); no Ctrl-C handling.
    pub(crate) fn new<O: RawStream + 'static, E: RawStream + 'static>(out: &'a mut O, err: &'a mut E) -> Console<'a> {
        let (out_choice, err_choice) = (AutoStream::choice(&*out), AutoStream::choice(&*err));
        Console {
            out,
            out_choice,
            err: AutoStream::new(err as &mut dyn Write, err_choice),
            cancel: None,
            unwritten: None,
        }
    }

    /// Notes a write that failed: a closed pipe ends the program quietly
    /// (`crate::process::failure`), anything else is remembered in `unwritten`, and
    /// the session goes on.
    fn written(&mut self, result: std::io::Result<()>) {
        if let Err(error) = result {
            end_if_closed_pipe(&error);
            self.unwritten.get_or_insert_with(|| crate::output::io_reason(&error));
        }
    }

    /// Writes one line of information.
    pub(crate) fn say(&mut self, text: impl Display) {
        self.say_line(text.to_string());
    }

    /// Writes `line` (a message already formatted, without its newline) in
    /// one write, so that the stream sees whole lines.
    fn say_line(&mut self, mut line: String) {
        line.push('\n');
        let plain = line.bytes().all(|byte| (b' '..=b'~').contains(&byte) || byte == b'\n');
        let flushed = may_block(|| {
            let written = if plain {
                // Nothing to style or strip: most lines, such as confirmations.
                self.out.write_all(line.as_bytes())
            } else {
                AutoStream::new(&mut *self.out, self.out_choice).write_all(line.as_bytes())
            };
            written.and_then(|()| self.out.flush())
        });
        self.written(flushed);
    }

    /// Writes a one-line note that helps a learner along, styled as the
    /// notes of diagnostics.
    fn note(&mut self, text: impl Display) {
        self.say(format_args!("{DEFAULT_NOTE_STYLE}note:{DEFAULT_NOTE_STYLE:#} {text}"));
    }

    /// Writes an error message that is not about program text, styled as
    /// the first line of a diagnostic.
    pub(crate) fn error(&mut self, text: impl Display) {
        let (error, emphasis) = (DEFAULT_ERROR_STYLE, DEFAULT_EMPHASIS_STYLE);
        self.write_err(format!("{error}error{error:#}{emphasis}: {text}{emphasis:#}\n"));
    }

    /// Writes `text`, already formatted, on the error stream, noting a failure.
    fn write_err(&mut self, text: String) {
        let flushed = self.write_err_marked(&text);
        self.written(flushed);
    }

    /// Writes `text` on the error stream, marked as a write that may block
    /// (only the write: the text is formatted before, see `crate::process::interruption`).
    fn write_err_marked(&mut self, text: &str) -> std::io::Result<()> {
        may_block(|| self.err.write_all(text.as_bytes()).and_then(|()| self.err.flush()))
    }

    /// Writes a note about what the program printed, with the diagnostics.
    fn printed_note(&mut self, text: impl Display) {
        self.printed(format_args!("{DEFAULT_NOTE_STYLE}note:{DEFAULT_NOTE_STYLE:#} {text}"));
    }

    /// Writes a line the program printed (`print`), with the diagnostics.
    fn printed(&mut self, line: impl Display) {
        self.write_err(format!("{line}\n"));
    }

    /// Writes a diagnostic about program text.
    fn diagnostic(&mut self, diagnostic: &Diagnostic, sources: &SourceMap) {
        // Rendered first: finding lines in a long text is no blocked write.
        let text = diagnostic.render(sources, true);
        // As `emit` does, a diagnostic that cannot be written is not noted.
        let _ = self.write_err_marked(&text);
    }
}

impl FrontEnd for Console<'_> {
    /// Writes text and diagnostics; a picture, an animation or frames to
    /// play have no text of their own (their confirmation is a message).
    fn show(&mut self, output: Output, sources: &SourceMap) -> Result<(), String> {
        match output {
            Output::Text { role: TextRole::Message, text } => self.say_line(text),
            Output::Text { role: TextRole::Note, text } => self.note(text),
            Output::Text { role: TextRole::Error, text } => self.error(text),
            Output::Text { role: TextRole::Printed, text } => self.printed(text),
            Output::Text { role: TextRole::PrintedNote, text } => self.printed_note(text),
            Output::Diagnostic(diagnostic) => self.diagnostic(&diagnostic, sources),
            Output::Explanation(explanation) => self.say_line(explanation.text),
            Output::LessonStep(_) | Output::LessonVerdict(_) => self.say_line(plain_text(&output, sources)),
            Output::Picture(_) | Output::LessonPictures(_) | Output::Frames { .. } | Output::AnimationFile(_) => {}
        }
        Ok(())
    }

    fn cancel(&self) -> Option<&'static CancelSwitch> {
        self.cancel
    }
}
