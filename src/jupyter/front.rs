//! A cell's outputs as Jupyter messages on the IOPub channel: text as
//! `stream`, pictures, animations, explanations and lessons as
//! `display_data`, errors as `error` (kept for the cell's reply).

use std::cell::RefCell;
use std::path::Path;

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use image::RgbImage;
use jupyter_protocol::{
    DisplayData, ErrorOutput, JupyterMessage, JupyterMessageContent, Media, MediaType, ReplyError, StreamContent,
};

use crate::lang::{Diagnostic, Severity, SourceMap};
use crate::playback::Playback;
use crate::process::interruption::Signal;
use crate::session::{
    CancelSwitch, FrontEnd, LessonStep, LessonVerdict, Output, Picture, Size, TextRole, Ticker, mark_pixel,
};

use super::sockets::Outgoing;

/// The most bytes one picture or animation may take in a notebook: past
/// it, the cell says where the file is instead (notebooks that hold many
/// large pictures become slow to open; Jupyter's own default limit on a
/// message is far larger).
pub(crate) const MOST_OUTPUT_BYTES: usize = 20 << 20;

/// The MIME type of a pixel's explanation as data (`--explain --json`).
pub(crate) const EXPLANATION_MIME: &str = "application/vnd.rayrepl.explanation+json";

/// Shows a cell's outputs in the notebook, as children of the cell's
/// request. Lines for standard output are gathered into one `stream`
/// message until something else is shown, a render starts or the cell
/// ends (as IPython's kernel buffers them): a cell that prints a thousand
/// lines sends a few messages, not a thousand.
pub(crate) struct KernelFront<'k> {
    /// Where messages go.
    pub outgoing: &'k Outgoing,
    /// The request whose outputs these are.
    pub parent: &'k JupyterMessage,
    /// Nothing is shown (`silent`): errors are still kept for the reply.
    pub silent: bool,
    /// The switch the kernel's interrupt raises.
    pub switch: &'static CancelSwitch,
    /// The cells run so far, as `:history` lists them.
    pub history: Vec<String>,
    /// The first error the cell showed, for its reply.
    pub first_error: Option<ReplyError>,
    /// Lines for standard output not yet sent.
    pub pending: RefCell<String>,
}

impl KernelFront<'_> {
    /// Publishes `content` as a child of the cell's request, after the
    /// lines of standard output before it.
    fn publish(&self, content: impl Into<JupyterMessageContent>) {
        self.flush();
        self.send(content.into());
    }

    fn send(&self, content: JupyterMessageContent) {
        if !self.silent {
            self.outgoing.iopub(JupyterMessage::new(content, Some(self.parent)));
        }
    }

    /// Sends the lines of standard output gathered so far.
    pub(crate) fn flush(&self) {
        let pending = std::mem::take(&mut *self.pending.borrow_mut());
        if !pending.is_empty() {
            self.send(StreamContent::stdout(&pending).into());
        }
    }

    fn stream(&self, text: &str, stderr: bool) {
        if stderr {
            self.publish(StreamContent::stderr(&format!("{text}\n")));
        } else {
            let mut pending = self.pending.borrow_mut();
            pending.push_str(text);
            pending.push('\n');
        }
    }

    /// Publishes an error, and keeps the first for the reply.
    fn error(&mut self, ename: &str, evalue: &str, traceback: String) {
        let error = ErrorOutput { ename: ename.to_string(), evalue: evalue.to_string(), traceback: vec![traceback] };
        self.first_error.get_or_insert_with(|| ReplyError {
            ename: error.ename.clone(),
            evalue: error.evalue.clone(),
            traceback: error.traceback.clone(),
        });
        self.publish(error);
    }

    fn display(&self, data: Vec<MediaType>) {
        self.publish(DisplayData::new(Media::new(data)));
    }

    /// Shows `bytes` of an image of `mime` (`image/png`, `image/gif`)
    /// described by `plain`, or says why not when it is too large.
    fn image(&self, bytes: &[u8], media: fn(String) -> MediaType, plain: String) {
        if bytes.len() > MOST_OUTPUT_BYTES {
            self.stream(
                &format!(
                    "{plain}: not shown, its {} MiB are more than the {} MiB a notebook output may take here \
                     (`:save` or `:anim` writes it to a file)",
                    bytes.len() >> 20,
                    MOST_OUTPUT_BYTES >> 20
                ),
                false,
            );
            return;
        }
        self.display(vec![media(STANDARD.encode(bytes)), MediaType::Plain(plain)]);
    }

    fn picture(&self, image: &RgbImage, plain: String) {
        let mut bytes = Vec::new();
        match crate::output::write_png(&mut bytes, image) {
            Ok(()) => self.image(&bytes, MediaType::Png, plain),
            Err(error) => self.stream(&format!("{plain}: the picture could not be encoded: {error}"), true),
        }
    }

    fn diagnostic(&mut self, diagnostic: &Diagnostic, sources: &SourceMap) {
        let rendered = diagnostic.render(sources, true);
        match diagnostic.severity {
            Severity::Error => {
                let ename = if diagnostic.code.is_empty() { "error" } else { diagnostic.code };
                self.error(ename, &diagnostic.message, rendered);
            }
            _ => self.stream(&rendered, true),
        }
    }

    fn animation_file(&self, path: &Path) {
        let media: Option<fn(String) -> MediaType> =
            match path.extension().and_then(|extension| extension.to_str()).map(str::to_ascii_lowercase).as_deref() {
                Some("png" | "apng") => Some(MediaType::Png),
                Some("gif") => Some(MediaType::Gif),
                _ => None,
            };
        match (media, std::fs::read(path)) {
            (Some(media), Ok(bytes)) => self.image(&bytes, media, format!("animation {}", path.display())),
            (Some(_), Err(error)) => self.stream(
                &format!("{} could not be read back to show it: {}", path.display(), crate::output::io_reason(&error)),
                true,
            ),
            // Videos: the notebook shows images only.
            (None, _) => {}
        }
    }
}

impl FrontEnd for KernelFront<'_> {
    fn show(&mut self, output: Output, sources: &SourceMap) -> Result<(), String> {
        match output {
            Output::Text { role: TextRole::Error, text } => self.error("error", &text, text.clone()),
            Output::Text { text, .. } => self.stream(&text, false),
            Output::Diagnostic(diagnostic) => self.diagnostic(&diagnostic, sources),
            Output::Picture(Picture { image, marked, saved_to }) => {
                let size = format!("{}×{}", image.width(), image.height());
                let plain = match &saved_to {
                    Some(path) => format!("picture {size}, saved to {}", path.display()),
                    None => format!("picture {size}"),
                };
                match marked {
                    Some((x, y)) => {
                        self.picture(&mark_pixel(&image, x, y), format!("{plain}, pixel ({x}, {y}) marked"))
                    }
                    None => self.picture(&image, plain),
                }
            }
            Output::Frames { frames, fps } => {
                let playback = Playback { fps: Some(f64::from(fps)), loops: None };
                let plain = format!("animation of {} frames at {fps} a second", frames.len());
                match crate::output::apng_bytes(&frames, &playback) {
                    Ok(bytes) => self.image(&bytes, MediaType::Png, plain),
                    Err(error) => self.stream(&format!("{plain}: it could not be encoded: {error}"), true),
                }
            }
            Output::AnimationFile(path) => self.animation_file(&path),
            Output::Explanation(explanation) => self.display(vec![
                MediaType::Plain(explanation.text),
                MediaType::Other((EXPLANATION_MIME.to_string(), explanation.json)),
            ]),
            Output::LessonStep(step) => {
                self.display(vec![MediaType::Markdown(step_markdown(&step)), MediaType::Plain(step.to_text())]);
            }
            Output::LessonPictures(image) => self.picture(&image, "the goal (left) and your scene (right)".to_string()),
            Output::LessonVerdict(verdict) => {
                self.display(vec![
                    MediaType::Markdown(verdict_markdown(&verdict)),
                    MediaType::Plain(verdict.to_text()),
                ]);
            }
        }
        Ok(())
    }

    fn picture_size(&self, shape: Size) -> Option<Size> {
        Some(shape)
    }

    fn cancel(&self) -> Option<&'static CancelSwitch> {
        Some(self.switch)
    }

    /// A notebook stops a cell with its interrupt (the ■ button, or
    /// `interrupt_request`), which reaches the kernel as SIGINT or as a
    /// message: not Ctrl-C.
    fn interrupt_name(&self, signal: Signal) -> String {
        match signal {
            Signal::Interrupt => "the kernel's interrupt".to_string(),
            other => other.to_string(),
        }
    }

    /// No progress is drawn; what was said before the work shows while it runs.
    fn progress(&self, _total: u64, _what: &str) -> Ticker<'_> {
        self.flush();
        Box::new(|_| {})
    }

    fn history(&self) -> Vec<String> {
        self.history.clone()
    }
}

/// A lesson's step in Markdown: its number, its task, and its example as
/// a `.ray` block.
fn step_markdown(step: &LessonStep) -> String {
    let mut markdown = format!("**Step {} of {}.** {}", step.number, step.steps, step.task);
    if let Some(example) = &step.example {
        markdown.push_str(&format!("\n\n```ray\n{example}\n```"));
    }
    markdown
}

/// A lesson's verdict in Markdown.
fn verdict_markdown(verdict: &LessonVerdict) -> String {
    match verdict {
        LessonVerdict::Done { .. } => verdict.to_text(),
        LessonVerdict::NotYet { hint, example, .. } => {
            let shortfall = verdict.shortfall().unwrap_or_default();
            let mut markdown = format!("**Not yet:** {shortfall}\n\n**Hint:** {hint}");
            if let Some(example) = example {
                markdown.push_str(&format!("\n\nFor example:\n\n```ray\n{example}\n```"));
            }
            markdown
        }
    }
}
