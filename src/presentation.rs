//! What a front-end shows of an [`Output`], made in one place: its text,
//! its Markdown, its pictures as PNG or APNG bytes (base64 for JSON text)
//! and the outputs of a cell as JSON data. The notebook kernel
//! (`crate::jupyter`) and the browser playground (`web/`) both show
//! outputs through these functions, so they show an output the same way,
//! and their pictures are the bytes the batch renderer writes.

use std::borrow::Cow;

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use image::RgbImage;
use serde::Serialize;
use serde_json::Value;

use crate::lang::SourceMap;
use crate::playback::Playback;
use crate::session::{LessonStep, LessonVerdict, Output, Picture, PixelExplanation, TextRole};

/// The width lessons' texts are wrapped to.
const TEXT_COLUMNS: usize = 76;

/// `output` as plain text: what a terminal writes of it, a notebook's
/// `text/plain` and the page's text. A diagnostic is drawn as the terminal
/// draws it, without colours, pointing into `sources`; a picture or an
/// animation is described in words.
pub fn plain_text(output: &Output, sources: &SourceMap) -> String {
    match output {
        Output::Text { text, .. } => text.clone(),
        Output::Diagnostic(diagnostic) => diagnostic.render(sources, false),
        Output::Picture(picture) => picture_caption(picture),
        Output::Frames { frames, fps } => format!("animation of {} frames at {fps} a second", frames.len()),
        Output::AnimationFile(path) => format!("animation {}", path.display()),
        Output::Explanation(explanation) => explanation.text.clone(),
        Output::LessonStep(step) => step_text(step),
        Output::LessonPictures(_) => "the goal (left) and your scene (right)".to_string(),
        Output::LessonVerdict(verdict) => verdict_text(verdict),
    }
}

/// `output` in Markdown, for the outputs that read better with emphasis
/// and code blocks than as plain text (a lesson's steps and verdicts);
/// `None` for the others.
pub fn markdown(output: &Output) -> Option<String> {
    match output {
        Output::LessonStep(step) => Some(step_markdown(step)),
        Output::LessonVerdict(verdict) => Some(verdict_markdown(verdict)),
        _ => None,
    }
}

/// The pictures of `output`, in the order [`outputs_json`] numbers them:
/// a picture's, the frames of an animation to play, a lesson's pair.
pub fn pictures(output: &Output) -> &[RgbImage] {
    match output {
        Output::Picture(picture) => std::slice::from_ref(&picture.image),
        Output::Frames { frames, .. } => frames,
        Output::LessonPictures(image) => std::slice::from_ref(image),
        _ => &[],
    }
}

/// The picture as a front-end that cannot draw over it shows it: with
/// the pixel `:pick` explains marked (`crate::session::mark_pixel`).
pub fn marked_image(picture: &Picture) -> Cow<'_, RgbImage> {
    match picture.marked {
        Some((x, y)) => Cow::Owned(crate::session::mark_pixel(&picture.image, x, y)),
        None => Cow::Borrowed(&picture.image),
    }
}

/// `image` as a PNG file, the bytes `rayrepl -o out.png` writes.
pub fn png(image: &RgbImage) -> image::ImageResult<Vec<u8>> {
    let mut bytes = Vec::new();
    crate::output::write_png(&mut bytes, image)?;
    Ok(bytes)
}

/// `frames` played at `fps` frames a second as an APNG file, the bytes
/// `rayrepl --anim N --fps FPS -o out.apng` writes.
pub fn apng(frames: &[RgbImage], fps: u32) -> Result<Vec<u8>, png::EncodingError> {
    crate::output::apng_bytes(frames, &Playback { fps: Some(f64::from(fps)), loops: None })
}

/// `bytes` in base64 (the standard alphabet, padded), as JSON text
/// carries a picture.
pub fn base64(bytes: &[u8]) -> String {
    STANDARD.encode(bytes)
}

/// `outputs` as a JSON list of objects, each with a `kind`: `text` (with
/// its `role`), `diagnostic` (`rendered` as [`plain_text`] draws it, and
/// `data`, as `--check --json` gives it), `picture` (the pixel `marked`),
/// `frames` (with their `fps`), `animation-file`, `explanation`,
/// `lesson-step`, `lesson-pictures` and `lesson-verdict` (`done` or not),
/// with their fields and their `text`. A picture is named by its number
/// among the pictures of all the outputs (see [`pictures`]) and its size:
/// `{ index, width, height }`; its pixels are not in the JSON.
pub fn outputs_json(outputs: &[Output], sources: &SourceMap) -> String {
    let mut first = 0;
    let mut data = Vec::with_capacity(outputs.len());
    for output in outputs {
        data.push(OutputData::of(output, sources, first));
        first += pictures(output).len();
    }
    serde_json::to_string(&data).expect("outputs as JSON are maps with text keys")
}

/// A picture in the JSON of outputs: its number among their pictures, and
/// its size.
#[derive(Debug, Serialize)]
struct PictureRef {
    index: usize,
    width: u32,
    height: u32,
}

impl PictureRef {
    /// `image`, numbered `index`.
    fn new(index: usize, image: &RgbImage) -> PictureRef {
        PictureRef { index, width: image.width(), height: image.height() }
    }
}

/// An output as JSON data (see [`outputs_json`]): its own fields, and the
/// forms that need the session's sources or its pictures' numbers.
#[derive(Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
enum OutputData<'a> {
    Text {
        role: TextRole,
        text: &'a str,
    },
    Diagnostic {
        rendered: String,
        data: Value,
    },
    Picture {
        marked: Option<(u32, u32)>,
        image: PictureRef,
    },
    Frames {
        fps: u32,
        frames: Vec<PictureRef>,
    },
    AnimationFile {
        path: String,
    },
    Explanation(&'a PixelExplanation),
    LessonStep {
        #[serde(flatten)]
        step: &'a LessonStep,
        text: String,
    },
    LessonPictures {
        image: PictureRef,
    },
    LessonVerdict {
        done: bool,
        #[serde(flatten)]
        verdict: &'a LessonVerdict,
        text: String,
    },
}

impl<'a> OutputData<'a> {
    /// `output` as data, its diagnostics pointing into `sources`, its
    /// pictures numbered from `first`.
    fn of(output: &'a Output, sources: &SourceMap, first: usize) -> OutputData<'a> {
        let text = || plain_text(output, sources);
        match output {
            Output::Text { role, text } => OutputData::Text { role: *role, text },
            Output::Diagnostic(diagnostic) => {
                OutputData::Diagnostic { rendered: text(), data: diagnostic.to_json(sources) }
            }
            Output::Picture(picture) => {
                OutputData::Picture { marked: picture.marked, image: PictureRef::new(first, &picture.image) }
            }
            Output::Frames { frames, fps } => OutputData::Frames {
                fps: *fps,
                frames: frames.iter().enumerate().map(|(k, frame)| PictureRef::new(first + k, frame)).collect(),
            },
            Output::AnimationFile(path) => OutputData::AnimationFile { path: path.display().to_string() },
            Output::Explanation(explanation) => OutputData::Explanation(explanation),
            Output::LessonStep(step) => OutputData::LessonStep { step, text: text() },
            Output::LessonPictures(image) => OutputData::LessonPictures { image: PictureRef::new(first, image) },
            Output::LessonVerdict(verdict) => {
                OutputData::LessonVerdict { done: matches!(verdict, LessonVerdict::Done { .. }), verdict, text: text() }
            }
        }
    }
}

/// A picture described in words: its size, the file it was saved to, the
/// pixel marked.
fn picture_caption(picture: &Picture) -> String {
    let mut caption = format!("picture {}×{}", picture.image.width(), picture.image.height());
    if let Some(path) = &picture.saved_to {
        caption.push_str(&format!(", saved to {}", path.display()));
    }
    if let Some((x, y)) = picture.marked {
        caption.push_str(&format!(", pixel ({x}, {y}) marked"));
    }
    caption
}

/// The step as the terminal shows it: the task wrapped under its number,
/// then the example, indented.
fn step_text(step: &LessonStep) -> String {
    let task = wrap(&step.task, &format!("step {} of {}: ", step.number, step.steps));
    match &step.example {
        Some(example) => format!("{task}\n{}", indent(example)),
        None => task,
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

/// What the scene still lacks, with the advice to take the last input
/// back when it made that.
fn shortfall(missing: &str, undo: bool) -> String {
    let undo = if undo { " (`:undo` takes your last input back)" } else { "" };
    format!("{missing}{undo}")
}

/// The verdict as the terminal shows it.
fn verdict_text(verdict: &LessonVerdict) -> String {
    match verdict {
        LessonVerdict::Done { number, already: false } => format!("✓ step {number} done"),
        LessonVerdict::Done { number, already: true } => format!("✓ step {number} done: your scene already does it"),
        LessonVerdict::NotYet { missing, undo, hint, example } => {
            let mut text = format!("{}\n{}", wrap(&shortfall(missing, *undo), "not yet: "), wrap(hint, "hint: "));
            if let Some(example) = example {
                text.push_str(&format!("\nfor example:\n{}", indent(example)));
            }
            text
        }
    }
}

/// A lesson's verdict in Markdown.
fn verdict_markdown(verdict: &LessonVerdict) -> String {
    match verdict {
        LessonVerdict::Done { .. } => verdict_text(verdict),
        LessonVerdict::NotYet { missing, undo, hint, example } => {
            let mut markdown = format!("**Not yet:** {}\n\n**Hint:** {hint}", shortfall(missing, *undo));
            if let Some(example) = example {
                markdown.push_str(&format!("\n\nFor example:\n\n```ray\n{example}\n```"));
            }
            markdown
        }
    }
}

/// `text` wrapped to [`TEXT_COLUMNS`], its first line after `first`, the
/// others indented by as much.
fn wrap(text: &str, first: &str) -> String {
    let rest = " ".repeat(first.chars().count());
    let options = textwrap::Options::new(TEXT_COLUMNS).initial_indent(first).subsequent_indent(&rest);
    textwrap::fill(text, options)
}

/// A program shown indented by four spaces.
fn indent(program: &str) -> String {
    program.lines().map(|line| format!("    {line}")).collect::<Vec<_>>().join("\n")
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use super::*;
    use crate::lang::{Diagnostic, Span};

    /// The JSON of `outputs`, pointing into no program text.
    fn json_of(outputs: &[Output]) -> String {
        outputs_json(outputs, &SourceMap::new())
    }

    fn image(width: u32, height: u32, shade: u8) -> RgbImage {
        RgbImage::from_pixel(width, height, image::Rgb([shade, 0, 0]))
    }

    #[test]
    fn text_serialises_with_its_role() {
        let printed = Output::Text { role: TextRole::PrintedNote, text: "3 lines left out".to_string() };
        let message = Output::Text { role: TextRole::Message, text: "defined r".to_string() };
        assert_eq!(
            json_of(&[printed, message]),
            r#"[{"kind":"text","role":"printed-note","text":"3 lines left out"},{"kind":"text","role":"message","text":"defined r"}]"#
        );
    }

    #[test]
    fn a_diagnostic_serialises_drawn_and_as_data() {
        let mut sources = SourceMap::new();
        let source = sources.add("<cell 1>", "put spehre end", 0);
        let diagnostic = Diagnostic::error(Span::new(source, 4, 10), "unknown shape `spehre`");
        let json = outputs_json(&[Output::Diagnostic(Box::new(diagnostic))], &sources);
        assert_eq!(
            json,
            concat!(
                r#"[{"kind":"diagnostic","rendered":"error: unknown shape `spehre`\n --> <cell 1>:1:5\n  |\n"#,
                r#"1 | put spehre end\n  |     ^^^^^^\n","data":{"severity":"error","code":"error","#,
                r#""message":"unknown shape `spehre`","place":{"source":"<cell 1>","line":1,"column":5,"#,
                r#""column_utf16":5,"end_line":1,"end_column":11,"end_column_utf16":11,"bytes":[4,10],"#,
                r#""label":null},"related":[],"notes":[],"help":[]}}]"#
            )
        );
    }

    #[test]
    fn pictures_serialise_numbered_across_the_outputs() {
        let outputs = [
            Output::Picture(Picture { image: image(3, 2, 1), marked: Some((1, 0)), saved_to: None }),
            Output::Frames { frames: vec![image(2, 2, 2), image(2, 2, 3)], fps: 12 },
            Output::LessonPictures(image(5, 1, 4)),
            Output::AnimationFile(PathBuf::from("out.gif")),
        ];
        assert_eq!(
            json_of(&outputs),
            concat!(
                r#"[{"kind":"picture","marked":[1,0],"image":{"index":0,"width":3,"height":2}},"#,
                r#"{"kind":"frames","fps":12,"frames":[{"index":1,"width":2,"height":2},{"index":2,"width":2,"height":2}]},"#,
                r#"{"kind":"lesson-pictures","image":{"index":3,"width":5,"height":1}},"#,
                r#"{"kind":"animation-file","path":"out.gif"}]"#
            )
        );
        let numbered: Vec<u8> = outputs.iter().flat_map(pictures).map(|picture| picture[(0, 0)][0]).collect();
        assert_eq!(numbered, [1, 2, 3, 4], "the pictures in the order the JSON numbers them");
    }

    #[test]
    fn an_explanation_serialises_as_text_and_data() {
        let explanation =
            PixelExplanation { text: "the sphere, lit".to_string(), json: serde_json::json!({ "pixel": [1, 2] }) };
        assert_eq!(
            json_of(&[Output::Explanation(Box::new(explanation))]),
            r#"[{"kind":"explanation","text":"the sphere, lit","data":{"pixel":[1,2]}}]"#
        );
    }

    #[test]
    fn lesson_steps_and_verdicts_serialise_with_their_text() {
        let step = LessonStep { number: 2, steps: 3, task: "Put a light.".to_string(), example: None };
        let done = LessonVerdict::Done { number: 2, already: true };
        let not_yet = LessonVerdict::NotYet {
            missing: "no light".to_string(),
            undo: true,
            hint: "`light`".to_string(),
            example: Some("light point 0, 5, 0 end".to_string()),
        };
        let outputs = [Output::LessonStep(step), Output::LessonVerdict(done), Output::LessonVerdict(not_yet)];
        assert_eq!(
            json_of(&outputs),
            concat!(
                r#"[{"kind":"lesson-step","number":2,"steps":3,"task":"Put a light.","example":null,"text":"step 2 of 3: Put a light."},"#,
                r#"{"kind":"lesson-verdict","done":true,"number":2,"already":true,"text":"✓ step 2 done: your scene already does it"},"#,
                r#"{"kind":"lesson-verdict","done":false,"missing":"no light","undo":true,"hint":"`light`","example":"light point 0, 5, 0 end","#,
                r#""text":"not yet: no light (`:undo` takes your last input back)\nhint: `light`\nfor example:\n    light point 0, 5, 0 end"}]"#
            )
        );
        assert_eq!(
            markdown(&outputs[2]).as_deref(),
            Some(
                "**Not yet:** no light (`:undo` takes your last input back)\n\n**Hint:** `light`\n\n\
                 For example:\n\n```ray\nlight point 0, 5, 0 end\n```"
            )
        );
        assert_eq!(markdown(&outputs[0]).as_deref(), Some("**Step 2 of 3.** Put a light."));
    }

    #[test]
    fn pictures_are_described_in_words() {
        let picture = Picture { image: image(4, 3, 0), marked: Some((1, 2)), saved_to: Some(PathBuf::from("a.png")) };
        assert_eq!(
            plain_text(&Output::Picture(picture), &SourceMap::new()),
            "picture 4×3, saved to a.png, pixel (1, 2) marked"
        );
    }

    #[test]
    fn a_picture_is_the_batch_renderers_png_file_and_its_base64() {
        let picture = image(2, 1, 200);
        let mut written = Vec::new();
        crate::output::write_png(&mut written, &picture).expect("a PNG is encoded in memory");
        let bytes = png(&picture).expect("a PNG is encoded in memory");
        assert_eq!(bytes, written);
        assert_eq!(STANDARD.decode(base64(&bytes)).expect("base64"), bytes);
        assert!(base64(b"ray").eq("cmF5"), "the standard alphabet");
    }

    #[test]
    fn text_is_wrapped_under_its_label() {
        let text = "one two three four five six seven eight nine ten eleven twelve thirteen fourteen fifteen";
        assert_eq!(
            wrap(text, "step 1 of 2: "),
            "step 1 of 2: one two three four five six seven eight nine ten eleven twelve\n             thirteen fourteen fifteen"
        );
        assert_eq!(indent("a\nb"), "    a\n    b");
    }
}
