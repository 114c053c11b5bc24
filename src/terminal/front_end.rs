//! The terminal session's front-end: text through the console, pictures
//! previewed in the terminal, animations played there, progress bars,
//! Ctrl-C and file watches.

use std::path::Path;
use std::time::Duration;

use rustyline::history::{FileHistory, History};

use super::console::Console;
use crate::lang::SourceMap;
use crate::session::{CancelSwitch, FrontEnd, Output, Picture, PreviewSize, SaveWatcher, Size, Ticker, mark_pixel};

use super::history::history_path;
use super::play::play_until_key;
use super::preview::Preview;
use super::progress::Progress;
use super::watch::FileWatcher;

/// The terminal session's front-end.
pub(crate) struct TerminalFrontEnd<'a> {
    /// Where the text goes, and the Ctrl-C switch.
    pub console: Console<'a>,
    /// Where pictures are shown; `None` when previews are off.
    pub preview: Option<Preview>,
}

impl TerminalFrontEnd<'_> {
    /// The previewer, unless previews are off.
    fn shown(&self) -> Option<Preview> {
        self.preview.filter(|preview| preview.size != PreviewSize::Off)
    }
}

impl FrontEnd for TerminalFrontEnd<'_> {
    /// Previews pictures (not those written to a file, which their message
    /// confirms) and plays frames; the rest is text.
    fn show(&mut self, output: Output, sources: &SourceMap) -> Result<(), String> {
        match output {
            Output::Picture(Picture { image, marked, saved_to: None }) => {
                let Some(preview) = self.shown() else { return Ok(()) };
                match marked {
                    Some((x, y)) => preview.show(&mark_pixel(&image, x, y)).map(drop),
                    None => preview.show(&image).map(drop),
                }
            }
            Output::LessonPictures(image) => {
                let Some(preview) = self.shown() else { return Ok(()) };
                preview.show_lesson(&image).map(drop)
            }
            Output::Frames { frames, fps } => {
                let (Some(preview), Some(first)) = (self.shown(), frames.first()) else { return Ok(()) };
                let size = Size { width: first.width(), height: first.height() };
                let count = frames.len();
                self.console.say(format!("playing {count} frames of {size} at {fps} a second; any key stops"));
                let played = play_until_key(&preview, &frames, Duration::from_secs(1) / fps)?;
                self.console.say(format!("stopped after {played} frames"));
                Ok(())
            }
            output => self.console.show(output, sources),
        }
    }

    fn picture_size(&self, shape: Size) -> Option<Size> {
        self.shown().map(|preview| preview.render_size(shape))
    }

    fn lesson_picture_size(&self, shape: Size) -> Option<Size> {
        self.shown().map(|preview| preview.lesson_render_size(shape))
    }

    fn preview_size(&mut self) -> Option<&mut PreviewSize> {
        self.preview.as_mut().map(|preview| &mut preview.size)
    }

    fn progress(&self, total: u64, what: &str) -> Ticker<'_> {
        let bar = Progress::in_session(total, what);
        Box::new(move |units| bar.advance(units))
    }

    fn cancel(&self) -> Option<&'static CancelSwitch> {
        self.console.cancel
    }

    /// The history file, as the line editor keeps it; none if it cannot be read.
    fn history(&self) -> Vec<String> {
        let mut history = FileHistory::new();
        if let Some(path) = history_path() {
            // No file yet is an empty history.
            let _ = history.load(&path);
        }
        history.iter().cloned().collect()
    }

    fn watch(&self, path: &Path) -> Result<Box<dyn SaveWatcher>, String> {
        Ok(Box::new(FileWatcher::new(path).map_err(|error| error.to_string())?))
    }
}
