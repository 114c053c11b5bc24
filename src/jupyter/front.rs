//! A cell's outputs as Jupyter messages on the IOPub channel: text as
//! `stream`, pictures, animations, explanations and lessons as
//! `display_data`, errors as `error` (kept for the cell's reply).

use std::fmt::Display;
use std::path::Path;

use jupyter_protocol::{
    DisplayData, ErrorOutput, JupyterMessage, JupyterMessageContent, Media, MediaType, ReplyError, StreamContent,
};

use crate::lang::{Diagnostic, Severity, SourceMap};
use crate::presentation::{apng, base64, markdown, marked_image, plain_text, png};
use crate::process::interruption::Signal;
use crate::session::{CancelSwitch, FrontEnd, Output, Size, TextRole};

use super::sockets::Outgoing;

/// The most bytes one picture or animation may take in a notebook: past
/// it, the cell says where the file is instead (notebooks that hold many
/// large pictures become slow to open; Jupyter's own default limit on a
/// message is far larger).
pub(crate) const MOST_OUTPUT_BYTES: usize = 20 << 20;

/// The MIME type of a pixel's explanation as data (`--explain --json`).
pub(crate) const EXPLANATION_MIME: &str = "application/vnd.rayrepl.explanation+json";

/// Shows a cell's outputs in the notebook, as children of the cell's
/// request, in the forms `crate::presentation` makes of them. Lines for
/// standard output are gathered into one `stream` message until something
/// else is shown, a render starts (the session flushes the front-end) or
/// the cell ends (as IPython's kernel buffers them): a cell that prints a
/// thousand lines sends a few messages, not a thousand.
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
    pub pending: String,
}

impl KernelFront<'_> {
    /// Publishes `content` as a child of the cell's request, after the
    /// lines of standard output before it.
    fn publish(&mut self, content: impl Into<JupyterMessageContent>) {
        self.flush();
        self.send(content.into());
    }

    fn send(&self, content: JupyterMessageContent) {
        if !self.silent {
            self.outgoing.iopub(JupyterMessage::new(content, Some(self.parent)));
        }
    }

    fn stream(&mut self, text: &str, stderr: bool) {
        if stderr {
            self.publish(StreamContent::stderr(&format!("{text}\n")));
        } else {
            self.pending.push_str(text);
            self.pending.push('\n');
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

    fn display(&mut self, data: Vec<MediaType>) {
        self.publish(DisplayData::new(Media::new(data)));
    }

    /// Shows the image file `encoded` as `media` (`MediaType::Png`,
    /// `MediaType::Gif`) described by `plain`, or says why not when it
    /// could not be encoded.
    fn encoded(&mut self, encoded: Result<Vec<u8>, impl Display>, media: fn(String) -> MediaType, plain: String) {
        match encoded {
            Ok(bytes) => self.image(&bytes, media, plain),
            Err(error) => self.stream(&format!("{plain}: it could not be encoded: {error}"), true),
        }
    }

    /// Shows the image file `bytes` as `media` described by `plain`, or
    /// says why not when it is too large.
    fn image(&mut self, bytes: &[u8], media: fn(String) -> MediaType, plain: String) {
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
        self.display(vec![media(base64(bytes)), MediaType::Plain(plain)]);
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

    fn animation_file(&mut self, path: &Path, plain: String) {
        let media: Option<fn(String) -> MediaType> =
            match path.extension().and_then(|extension| extension.to_str()).map(str::to_ascii_lowercase).as_deref() {
                Some("png" | "apng") => Some(MediaType::Png),
                Some("gif") => Some(MediaType::Gif),
                _ => None,
            };
        match (media, std::fs::read(path)) {
            (Some(media), Ok(bytes)) => self.image(&bytes, media, plain),
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
        let plain = || plain_text(&output, sources);
        match &output {
            Output::Text { role: TextRole::Error, text } => self.error("error", text, plain()),
            Output::Text { .. } => self.stream(&plain(), false),
            Output::Diagnostic(diagnostic) => self.diagnostic(diagnostic, sources),
            Output::Picture(picture) => self.encoded(png(&marked_image(picture)), MediaType::Png, plain()),
            Output::LessonPictures(image) => self.encoded(png(image), MediaType::Png, plain()),
            Output::Frames { frames, fps } => self.encoded(apng(frames, *fps), MediaType::Png, plain()),
            Output::AnimationFile(path) => self.animation_file(path, plain()),
            Output::Explanation(explanation) => self.display(vec![
                MediaType::Plain(plain()),
                MediaType::Other((EXPLANATION_MIME.to_string(), explanation.json.clone())),
            ]),
            Output::LessonStep(_) | Output::LessonVerdict(_) => {
                let markdown = markdown(&output).expect("a lesson's steps and verdicts have Markdown");
                self.display(vec![MediaType::Markdown(markdown), MediaType::Plain(plain())]);
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

    /// Sends the lines of standard output gathered so far.
    fn flush(&mut self) {
        let pending = std::mem::take(&mut self.pending);
        if !pending.is_empty() {
            self.send(StreamContent::stdout(&pending).into());
        }
    }

    fn history(&self) -> Vec<String> {
        self.history.clone()
    }
}

#[cfg(test)]
mod tests {
    use jupyter_protocol::ExecuteRequest;
    use serde_json::Value;

    use super::*;
    use crate::presentation::{outputs_json, pictures};
    use crate::session::{CellSession, Collected, RenderSettings, SessionOptions};

    const CELL: &str = "light vector 0.5, 0, -0.5 intensity 0.8 end\n\
        put sphere center 0, 0, 0 radius 2 kd 0.7 ks 0.3 phong 20 color 255, 80, 40 end\n\
        :render\n\
        :lesson 1";

    /// A session rendering small pictures.
    fn session() -> CellSession {
        let settings = RenderSettings { width: 16, height: 12, ..RenderSettings::default() };
        CellSession::new(&SessionOptions { settings, ..SessionOptions::default() })
    }

    /// The messages the kernel publishes for [`CELL`], as (type, content).
    fn kernel_messages() -> Vec<(String, Value)> {
        let (outgoing, mut published) = Outgoing::kept();
        let parent = JupyterMessage::new(ExecuteRequest::new(CELL.to_string()), None);
        let mut front = KernelFront {
            outgoing: &outgoing,
            parent: &parent,
            silent: false,
            switch: Box::leak(Box::default()),
            history: Vec::new(),
            first_error: None,
            pending: String::new(),
        };
        assert_eq!(session().run("<cell 1>", CELL, &mut front), crate::session::CellEnd::Done);
        front.flush();
        let mut messages = Vec::new();
        while let Ok(message) = published.try_recv() {
            let content = serde_json::to_value(&message.content).expect("a message is JSON");
            messages.push((message.header.msg_type, content));
        }
        messages
    }

    #[test]
    fn the_kernel_shows_what_the_page_shows() {
        let messages = kernel_messages();
        let kinds: Vec<&str> = messages.iter().map(|(kind, _)| kind.as_str()).collect();
        // The lines said before the render go out when it starts, before its picture.
        assert_eq!(kinds[..3], ["stream", "display_data", "stream"], "{messages:?}");
        assert!(kinds[3..].iter().all(|kind| *kind == "display_data" || *kind == "stream"), "{kinds:?}");
        assert!(messages[0].1["text"].as_str().is_some_and(|text| text.starts_with("1 light added")), "{messages:?}");

        let mut page = session();
        let mut collected = Collected::default();
        page.run("<cell 1>", CELL, &mut collected);
        let json: Value = serde_json::from_str(&outputs_json(&collected.outputs, page.sources())).expect("JSON");
        let page_pngs: Vec<String> =
            collected.outputs.iter().flat_map(pictures).map(|image| base64(&png(image).expect("a PNG"))).collect();
        let kernel_pngs: Vec<&str> =
            messages.iter().filter_map(|(_, content)| content["data"]["image/png"].as_str()).collect();
        assert_eq!(kernel_pngs, page_pngs, "the picture, then the lesson's pair");

        let step = json.as_array().expect("a list").iter().find(|output| output["kind"] == "lesson-step");
        let step = step.expect("`:lesson 1` shows its first step");
        let shown = messages.iter().find(|(_, content)| content["data"]["text/markdown"].is_string());
        let (_, shown) = shown.expect("the kernel shows the step in Markdown");
        assert_eq!(shown["data"]["text/plain"], step["text"]);
        let Some(Output::LessonStep(first)) = collected.outputs.iter().find(|o| matches!(o, Output::LessonStep(_)))
        else {
            panic!("a step")
        };
        assert_eq!(shown["data"]["text/markdown"].as_str(), markdown(&Output::LessonStep(first.clone())).as_deref());
    }
}
