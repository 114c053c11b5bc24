//! What inputs and commands show, as values, and what a front-end offers
//! while they run.
//!
//! Nothing in the session core writes to a stream: it hands each
//! [`Output`] to the [`FrontEnd`] driving it, at the moment it has it (a
//! long render's confirmation comes after its picture, as on a terminal).
//! The terminal session and piped scripts write them as text and preview
//! pictures; [`Collected`] keeps them in a list, for a front-end that shows
//! them its own way (a notebook, a browser) and for tests. The forms those
//! front-ends show of an output (JSON, PNG bytes, Markdown) are
//! `crate::presentation`'s; the image and animation files the commands
//! write are `crate::output`'s.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use image::RgbImage;
use serde::Serialize;
use serde_json::Value;

use crate::lang::{Diagnostic, SourceMap};

use super::rendering::Size;
use crate::process::cancel::CancelSwitch;
use crate::process::interruption::Signal;

/// One thing an input or a command shows.
#[derive(Debug, Clone, PartialEq)]
pub enum Output {
    /// A line (or lines) of text, with what it is.
    Text {
        /// What the text is, which decides where and how it is shown.
        role: TextRole,
        /// The text, without a final newline; it may hold style escapes.
        text: String,
    },
    /// An error or a warning about program text, pointing into the
    /// session's sources.
    Diagnostic(Box<Diagnostic>),
    /// A rendered picture.
    Picture(Picture),
    /// The frames of an animation to play (`:play`), in order.
    Frames {
        /// The frames, all of one size.
        frames: Vec<RgbImage>,
        /// Frames a second.
        fps: u32,
    },
    /// An animation written to a file (`:anim`): its confirmation is a
    /// [`TextRole::Message`] of its own.
    AnimationFile(PathBuf),
    /// Why a pixel has its colour (`:pick`).
    Explanation(Box<PixelExplanation>),
    /// What a step of a lesson asks (`:lesson`).
    LessonStep(LessonStep),
    /// A lesson's goal (left) and the learner's picture (right), side by side.
    LessonPictures(RgbImage),
    /// Whether the learner's scene does what the step asks.
    LessonVerdict(LessonVerdict),
}

/// What a text output is; it serialises as its name in kebab-case
/// (`message`, `printed-note`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TextRole {
    /// What a command or an input did (`defined r`, `saved out.png`), and
    /// what was asked for (help, listings).
    Message,
    /// A note that helps a learner along.
    Note,
    /// Why a command failed, when it is not about program text.
    Error,
    /// A line the program printed (`print`).
    Printed,
    /// A note about what the program printed (lines left out).
    PrintedNote,
}

/// A rendered picture, and what it is for.
#[derive(Debug, Clone, PartialEq)]
pub struct Picture {
    /// The pixels, as the batch renderer writes them for the same scene and size.
    pub image: RgbImage,
    /// The pixel `:pick` explains, to mark on the picture.
    pub marked: Option<(u32, u32)>,
    /// The file the picture was also written to (`:save`).
    pub saved_to: Option<PathBuf>,
}

/// Why one pixel has its colour: the text `:pick` says, and the same as
/// `--explain --json` gives it; it serialises as `{ text, data }`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PixelExplanation {
    /// The explanation in words.
    pub text: String,
    /// The explanation as data.
    #[serde(rename = "data")]
    pub json: Value,
}

/// What a step of a lesson asks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LessonStep {
    /// The step's number, from 1.
    pub number: usize,
    /// How many steps the lesson has.
    pub steps: usize,
    /// What to build, in one paragraph.
    pub task: String,
    /// A program that does it, shown with the task when the step gives it
    /// up front.
    pub example: Option<String>,
}

/// Whether the learner's scene does what a lesson's step asks. It
/// serialises as the fields of its variant alone: the presentation says
/// beside them which it is (`done`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum LessonVerdict {
    /// It does: the step is done.
    Done {
        /// The step's number, from 1.
        number: usize,
        /// The scene did it before the learner typed anything for it.
        already: bool,
    },
    /// Not yet.
    NotYet {
        /// What the scene still lacks: what in it comes closest to the
        /// goal, and how it differs.
        missing: String,
        /// Whether the learner's last input made what comes closest, so
        /// that taking it back may help (not after a right part of the step).
        undo: bool,
        /// The step's hint, in one paragraph.
        hint: String,
        /// A program that does it, after a few wrong tries.
        example: Option<String>,
    },
}

/// How a wait for a save of a watched file ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Waited {
    /// The file was written (or replaced).
    Saved,
    /// The cancel flag was raised.
    Cancelled,
}

/// Follows one file through its saves (`:watch`).
pub trait SaveWatcher {
    /// Waits for the next save of the file, or until `cancel` is raised.
    fn wait(&self, cancel: &AtomicBool) -> Result<Waited, String>;
}

/// How far along a long piece of work is, in units (pixels); advanced from
/// the render's threads.
pub type Ticker<'a> = Box<dyn Fn(u64) + Sync + 'a>;

/// What drives the session: it shows the outputs, and says what it can do
/// while a command runs. Only [`FrontEnd::show`] must be written; the rest
/// describe a front-end that shows no pictures, draws no progress, cannot
/// be interrupted, keeps no history of typed lines and watches no files.
pub trait FrontEnd {
    /// Shows `output` now. `sources` are the texts a diagnostic points
    /// into. Fails with the reason when a picture cannot be shown here.
    fn show(&mut self, output: Output, sources: &SourceMap) -> Result<(), String>;

    /// The size to render a picture shaped like `shape` at, to be shown
    /// here, or `None` when this front-end shows no pictures.
    fn picture_size(&self, _shape: Size) -> Option<Size> {
        None
    }

    /// The size to render a lesson's goal and the learner's picture at,
    /// side by side and together shaped like `shape`; `None` when this
    /// front-end shows no pictures. Lessons may show them larger than a
    /// preview, to show a highlight and a shadow.
    fn lesson_picture_size(&self, shape: Size) -> Option<Size> {
        self.picture_size(shape)
    }

    /// How large pictures are shown (`:preview`), where that can be chosen.
    fn preview_size(&mut self) -> Option<&mut PreviewSize> {
        None
    }

    /// Shows at once what this front-end has gathered to show together
    /// (lines of text sent as one message): called before work that takes
    /// a while (a render), so that what was said before it is seen while it
    /// runs. A front-end that shows each output when it gets it has nothing
    /// to do.
    fn flush(&mut self) {}

    /// Progress of work of `total` units labelled `what` ("rendering"),
    /// shown while it runs and gone when the ticker drops.
    fn progress(&self, _total: u64, _what: &str) -> Ticker<'_> {
        Box::new(|_| {})
    }

    /// The switch that stops a running command (Ctrl-C), if there is one.
    fn cancel(&self) -> Option<&'static CancelSwitch> {
        None
    }

    /// How this front-end's messages name `signal` when it stopped a run
    /// ("stopped by SIGTERM"): Ctrl-C for SIGINT at a terminal.
    fn interrupt_name(&self, signal: Signal) -> String {
        signal.to_string()
    }

    /// The lines typed in this front-end, oldest first, as `:history`
    /// lists them (none where nothing is typed).
    fn history(&self) -> Vec<String> {
        Vec::new()
    }

    /// Starts following the file at `path` through its saves, or says why
    /// this front-end cannot.
    fn watch(&self, _path: &Path) -> Result<Box<dyn SaveWatcher>, String> {
        Err("only the interactive session can stop a watch (with Ctrl-C): here, run `rayrepl FILE.ray --watch`"
            .to_string())
    }
}

/// How much of the terminal a preview takes (`:preview`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PreviewSize {
    /// The whole terminal.
    Fit,
    /// A third of its rows and half its columns, so that what was just typed
    /// stays on screen above it.
    Small,
    /// No preview.
    Off,
}

impl PreviewSize {
    /// The setting named `name` (`fit`, `small`, `off`).
    pub(crate) fn parse(name: &str) -> Option<PreviewSize> {
        match name {
            "fit" => Some(PreviewSize::Fit),
            "small" => Some(PreviewSize::Small),
            "off" => Some(PreviewSize::Off),
            _ => None,
        }
    }

    /// Its name, as `:preview` takes it.
    pub(crate) fn name(self) -> &'static str {
        match self {
            PreviewSize::Fit => "fit",
            PreviewSize::Small => "small",
            PreviewSize::Off => "off",
        }
    }
}

/// `left` and `right` side by side on a black background, `gap` pixels
/// apart, their tops aligned.
pub(crate) fn side_by_side(left: &RgbImage, right: &RgbImage, gap: u32) -> RgbImage {
    let width = left.width() + gap + right.width();
    let mut both = RgbImage::new(width, left.height().max(right.height()));
    image::imageops::replace(&mut both, left, 0, 0);
    image::imageops::replace(&mut both, right, i64::from(left.width() + gap), 0);
    both
}

/// `image` with pixel `(x, y)` marked by a cross around it, in the colour
/// opposite to the pixel's, its arms long enough to see once the image is
/// fitted to the terminal; the pixel itself keeps its colour.
pub fn mark_pixel(image: &RgbImage, x: u32, y: u32) -> RgbImage {
    let mut marked = image.clone();
    let [r, g, b] = image.get_pixel(x, y).0;
    let opposite = image::Rgb([255 - r, 255 - g, 255 - b]);
    // A cell of a fitted preview covers about 1/80 of the width.
    let step = (image.width().max(image.height()) / 80).max(1) as i64;
    let (x, y) = (i64::from(x), i64::from(y));
    for distance in step..=4 * step {
        for (dx, dy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
            let (px, py) = (x + dx * distance, y + dy * distance);
            if (0..i64::from(image.width())).contains(&px) && (0..i64::from(image.height())).contains(&py) {
                marked.put_pixel(px as u32, py as u32, opposite);
            }
        }
    }
    marked
}

/// The texts of no program, for outputs that point into none.
static NO_SOURCES: SourceMap = SourceMap::new();

impl dyn FrontEnd + '_ {
    /// Shows a text output of `role`.
    pub(crate) fn text(&mut self, role: TextRole, text: impl std::fmt::Display) {
        let _ = self.show(Output::Text { role, text: text.to_string() }, &NO_SOURCES);
    }

    /// Shows what a command or an input did.
    pub(crate) fn say(&mut self, text: impl std::fmt::Display) {
        self.text(TextRole::Message, text);
    }

    /// Shows a note that helps a learner along.
    pub(crate) fn note(&mut self, text: impl std::fmt::Display) {
        self.text(TextRole::Note, text);
    }

    /// Shows why a command failed, when it is not about program text.
    pub(crate) fn error(&mut self, text: impl std::fmt::Display) {
        self.text(TextRole::Error, text);
    }

    /// Shows a line the program printed (`print`).
    pub(crate) fn printed(&mut self, line: impl std::fmt::Display) {
        self.text(TextRole::Printed, line);
    }

    /// Shows a note about what the program printed.
    pub(crate) fn printed_note(&mut self, text: impl std::fmt::Display) {
        self.text(TextRole::PrintedNote, text);
    }

    /// Shows a diagnostic pointing into `sources`; one that says a run was
    /// stopped names the signal that stopped it, as this front-end names it.
    pub(crate) fn diagnostic(&mut self, diagnostic: &Diagnostic, sources: &SourceMap) {
        let signal = self.cancel().and_then(CancelSwitch::last_signal);
        let shown = match signal {
            Some(signal) => diagnostic.clone().stopped_by(&self.interrupt_name(signal)),
            None => diagnostic.clone(),
        };
        let _ = self.show(Output::Diagnostic(Box::new(shown)), sources);
    }

    /// Shows an output that points into no program text; fails with the
    /// reason when it is a picture that cannot be shown here.
    pub(crate) fn present(&mut self, output: Output) -> Result<(), String> {
        self.show(output, &NO_SOURCES)
    }
}

/// A front-end that keeps the outputs in order, to show them later (a
/// diagnostic with the session's sources, which only grow). Pictures are
/// rendered at the session's size.
#[derive(Debug, Default)]
pub struct Collected {
    /// The outputs, in the order they were shown.
    pub outputs: Vec<Output>,
}

impl FrontEnd for Collected {
    fn show(&mut self, output: Output, _sources: &SourceMap) -> Result<(), String> {
        self.outputs.push(output);
        Ok(())
    }

    fn picture_size(&self, shape: Size) -> Option<Size> {
        Some(shape)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::Limits;
    use crate::render::{RenderControl, SceneGeometry, render};
    use crate::session::commands::execute;
    use crate::session::inputs::report_input;
    use crate::session::shell::Shell;
    use crate::session::{RenderSettings, Session};

    /// Submits `text` as the input `name` and reports it, as the terminal does.
    fn submit(shell: &mut Shell, front: &mut dyn FrontEnd, name: &str, text: &str) -> Result<(), ()> {
        let result = shell.session.submit(name, text, 0);
        report_input(shell, front, text, result)
    }

    const SCENE: &str = "light vector 0.5, 0, -0.5 intensity 0.8 end\n\
        put sphere center 0, 0, 0 radius 2 kd 0.7 ks 0.3 phong 20 color 255, 80, 40 end";
    const SMALL: RenderSettings = RenderSettings { width: 24, height: 18, ..crate::settings::DEFAULTS };

    /// A shell holding [`SCENE`], and what its input showed.
    fn shell_with_scene() -> (Shell, Collected) {
        let mut shell = Shell::new(Session::new(SMALL, Limits::default()));
        let mut front = Collected::default();
        submit(&mut shell, &mut front, "<input 1>", SCENE).expect("the scene is accepted");
        (shell, front)
    }

    fn messages(outputs: &[Output]) -> Vec<&str> {
        let texts = outputs.iter().filter_map(|output| match output {
            Output::Text { role: TextRole::Message, text } => Some(text.as_str()),
            _ => None,
        });
        texts.collect()
    }

    #[test]
    fn a_render_hands_the_front_end_the_batch_renderers_pixels() {
        let (mut shell, mut front) = shell_with_scene();
        assert_eq!(
            messages(&front.outputs),
            ["1 light added (1 light in the scene)", "put 1 sphere (1 object in the scene)"]
        );
        front.outputs.clear();
        execute(&mut shell, ":render", &mut front).expect("it renders");
        let scene = shell.session.scene();
        let (batch, _) = render(scene, &SceneGeometry::new(scene), &SMALL.render_options(), &RenderControl::default())
            .expect("not cancelled");
        let pictures: Vec<&Picture> = front
            .outputs
            .iter()
            .filter_map(|output| match output {
                Output::Picture(picture) => Some(picture),
                _ => None,
            })
            .collect();
        assert_eq!(pictures, [&Picture { image: batch, marked: None, saved_to: None }]);
        assert!(messages(&front.outputs).last().is_some_and(|text| text.starts_with("24×18 in ")));
    }

    #[test]
    fn a_pick_hands_the_explanation_as_text_and_data() {
        let (mut shell, mut front) = shell_with_scene();
        execute(&mut shell, ":render", &mut front).expect("it renders");
        front.outputs.clear();
        execute(&mut shell, ":pick 12 9", &mut front).expect("it explains");
        let [Output::Picture(picture), Output::Explanation(explanation)] = front.outputs.as_slice() else {
            panic!("a marked picture, then the explanation: {:?}", front.outputs);
        };
        assert_eq!(picture.marked, Some((12, 9)));
        assert!(explanation.text.contains("sphere"), "{}", explanation.text);
        assert_eq!(explanation.json["pixel"], serde_json::json!([12, 9]));
    }

    #[test]
    fn a_failed_input_hands_its_diagnostic() {
        let (mut shell, mut front) = shell_with_scene();
        front.outputs.clear();
        assert!(submit(&mut shell, &mut front, "<input 2>", "put sphere radius end").is_err());
        assert!(matches!(front.outputs.as_slice(), [Output::Diagnostic(_)]), "{:?}", front.outputs);
    }

    #[test]
    fn pictures_side_by_side_keep_their_pixels() {
        let left = RgbImage::from_pixel(2, 3, image::Rgb([255, 0, 0]));
        let right = RgbImage::from_pixel(3, 2, image::Rgb([0, 0, 255]));
        let both = side_by_side(&left, &right, 1);
        assert_eq!(both.dimensions(), (6, 3));
        assert_eq!(
            (both[(1, 2)], both[(2, 0)], both[(3, 1)], both[(3, 2)]),
            (image::Rgb([255, 0, 0]), image::Rgb([0, 0, 0]), image::Rgb([0, 0, 255]), image::Rgb([0, 0, 0]))
        );
    }

    #[test]
    fn a_marked_pixel_keeps_its_colour_inside_a_cross() {
        let image = RgbImage::from_pixel(20, 10, image::Rgb([10, 200, 30]));
        let marked = mark_pixel(&image, 2, 5);
        let opposite = image::Rgb([245, 55, 225]);
        assert_eq!(*marked.get_pixel(2, 5), image::Rgb([10, 200, 30]));
        for (x, y) in [(3, 5), (6, 5), (0, 5), (2, 9), (2, 1)] {
            assert_eq!(*marked.get_pixel(x, y), opposite, "({x}, {y})");
        }
        assert_eq!(*marked.get_pixel(7, 5), image::Rgb([10, 200, 30]), "the arms end");
        assert_eq!(*marked.get_pixel(3, 6), image::Rgb([10, 200, 30]), "the diagonals stay");
    }
}
