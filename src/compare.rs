//! Grading: a submission's scene compared with a reference's, frame by
//! frame. The scenes are evaluated as the batch renderer evaluates them,
//! their parts paired one to one whatever order or construction made them
//! (`matching`) and every difference said in words with the submission's
//! line (`differences`), then both are rendered with the same options and
//! their pictures compared pixel by pixel (`pictures`).
//!
//! Nothing here reads a file, a stream or the terminal: the front-end
//! gives the texts and shows the [`Grade`]s, as words, JSON or CSV rows.

mod differences;
mod matching;
mod pictures;

use image::RgbImage;
use serde_json::{Value, json};

pub use differences::{Difference, Kind, Part, Property, Side, differences, ordinal};
pub use matching::{EXACT_LIMIT, assign};
pub use pictures::{PictureDifference, compare_pictures, difference_picture};

use crate::lang::number::format_number;
use crate::lang::{Diagnostic, Interpreter, Limits, SourceId, SourceMap, parse_file};
use crate::pipeline::{Evaluation, render_picture};
use crate::playback::Timeline;
use crate::render::{Region, RenderControl, RenderOptions};

/// How close a submission must come to the reference to match it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances {
    /// Lengths (positions, radii, box lengths, plane shifts, the camera's
    /// distance) agree within this share of the reference scene's size
    /// (how far from the origin it reaches): scenes in any units compare
    /// alike.
    pub length: f64,
    /// Colour components agree within this many levels, of 255.
    pub colour: f64,
    /// Every other number (`kd`, `ks`, `phong`, intensities, the camera's
    /// angle, the components of directions and normals) agrees within this
    /// times the reference's value, or this itself for values below 1.
    pub coefficient: f64,
    /// A pixel is off when a channel differs by more than this many levels.
    pub pixel: u8,
    /// The pictures differ when more than this share (0 to 1) of the
    /// pixels are off: an edge may move by a pixel between two scenes
    /// that agree within the other tolerances.
    pub off_pixels: f64,
}

impl Tolerances {
    /// What `compare` uses unless told: a thousandth of a scene 10 across,
    /// half a colour level (a different whole number differs), numbers to
    /// 1e-4, pixels within 2 levels (as adaptive sampling counts a visible
    /// change), and one pixel in a thousand off.
    pub const DEFAULT: Tolerances =
        Tolerances { length: 1e-4, colour: 0.5, coefficient: 1e-4, pixel: 2, off_pixels: 1e-3 };
}

impl Default for Tolerances {
    fn default() -> Tolerances {
        Tolerances::DEFAULT
    }
}

/// The frames compared: one scene at a time, or the frames of an animation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Frames {
    /// One picture, with `time` this value (`--time`).
    Still(f64),
    /// Frames 1 to `count` of an animation, at the times `timeline` gives
    /// them (as `--anim` renders them).
    Animation {
        /// How many frames.
        count: u32,
        /// The time of each.
        timeline: Timeline,
    },
}

impl Frames {
    /// Each frame compared.
    fn each(&self) -> Vec<Frame> {
        match *self {
            Frames::Still(time) => vec![Frame { number: None, time }],
            Frames::Animation { count, timeline } => {
                (1..=count).map(|k| Frame { number: Some(k), time: timeline.time_of(k) }).collect()
            }
        }
    }
}

/// One frame compared: its number in an animation, and its time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Its number, from 1, in an animation; `None` for a single picture.
    pub number: Option<u32>,
    /// The value of `time`.
    pub time: f64,
}

impl Frame {
    /// "frame 3 (time 3)", or "time 0" for a single picture.
    fn words(&self) -> String {
        match self.number {
            Some(k) => format!("frame {k} (time {})", format_number(self.time)),
            None => format!("time {}", format_number(self.time)),
        }
    }

    /// `{"frame", "time"}`, `frame` `null` for a single picture.
    fn to_json(self) -> Value {
        json!({"frame": self.number, "time": self.time})
    }
}

/// How submissions are graded.
#[derive(Debug, Clone, PartialEq)]
pub struct Grading {
    /// How both pictures are rendered.
    pub options: RenderOptions,
    /// The frames compared.
    pub frames: Frames,
    /// How close is a match.
    pub tolerances: Tolerances,
    /// The evaluator's limits, for both programs.
    pub limits: Limits,
    /// Whether to keep a picture of the differences of each frame.
    pub difference_pictures: bool,
}

/// Why a reference cannot be graded against.
#[derive(Debug)]
pub enum ReferenceError {
    /// It does not parse, or fails at some frame.
    Scene(Box<Diagnostic>),
    /// It cannot be rendered (the memory cannot be had).
    Render(String),
}

/// The reference: its text, and each frame's evaluated scene and picture,
/// computed once for all the submissions.
pub struct Reference {
    sources: SourceMap,
    frames: Vec<Evaluated>,
}

/// One frame of one program: the interpreter that evaluated it (its scene
/// and where the parts come from), and its picture.
struct Evaluated {
    frame: Frame,
    interpreter: Interpreter,
    picture: RgbImage,
}

impl Evaluated {
    /// The side of a comparison it is.
    fn side(&self) -> Side<'_> {
        Side { scene: self.interpreter.scene(), origins: self.interpreter.origins() }
    }
}

/// Why a program gave no frame: its diagnostic, or a failure to render.
enum Failure {
    Scene(Box<Diagnostic>),
    Render(String),
}

/// Parses the file `id` of `sources` as the batch renderer does, then
/// evaluates and renders it at every frame of `grading`.
fn evaluate_all(sources: &SourceMap, id: SourceId, grading: &Grading) -> Result<Vec<Evaluated>, (Frame, Failure)> {
    let frames = grading.frames.each();
    let program = parse_file(id, &sources.get(id).text).map_err(|e| (frames[0], Failure::Scene(Box::new(e))))?;
    frames
        .into_iter()
        .map(|frame| {
            let evaluated = Evaluation::at(frame.time, grading.limits).run(&program);
            evaluated.result.map_err(|e| (frame, Failure::Scene(Box::new(e))))?;
            let interpreter = evaluated.interpreter;
            let options = &grading.options;
            let whole = Region::whole(options);
            let picture = match render_picture(interpreter.scene(), options, whole, &RenderControl::default()) {
                Ok(rendered) => rendered.image,
                Err(error) => return Err((frame, Failure::Render(error.to_string()))),
            };
            Ok(Evaluated { frame, interpreter, picture })
        })
        .collect()
}

impl Reference {
    /// The reference, the file `id` of `sources`, evaluated and rendered at
    /// every frame of `grading`; or why it cannot be graded against.
    pub fn prepare(
        sources: SourceMap,
        id: SourceId,
        grading: &Grading,
    ) -> Result<Reference, (SourceMap, ReferenceError)> {
        match evaluate_all(&sources, id, grading) {
            Ok(frames) => Ok(Reference { sources, frames }),
            Err((_, Failure::Scene(diagnostic))) => Err((sources, ReferenceError::Scene(diagnostic))),
            Err((_, Failure::Render(message))) => Err((sources, ReferenceError::Render(message))),
        }
    }

    /// The texts of the reference: a submission is added to a copy, so
    /// that the differences can name the places of both.
    pub fn sources(&self) -> &SourceMap {
        &self.sources
    }

    /// Grades the submission, the file `id` of `sources` (a copy of
    /// [`Reference::sources`] with the submission added), named `name`.
    pub fn grade(&self, name: String, sources: SourceMap, id: SourceId, grading: &Grading) -> Grade {
        let outcome = match evaluate_all(&sources, id, grading) {
            Err((frame, Failure::Scene(diagnostic))) => Outcome::Broken { frame, diagnostic },
            Err((frame, Failure::Render(message))) => Outcome::Failed(format!("at {}: {message}", frame.words())),
            Ok(submitted) => Outcome::Compared(
                self.frames
                    .iter()
                    .zip(&submitted)
                    .map(|(expected, submitted)| compare_frame(expected, submitted, grading))
                    .collect(),
            ),
        };
        Grade { name, sources, outcome }
    }
}

/// Compares one frame of a submission with the reference's.
fn compare_frame(expected: &Evaluated, submitted: &Evaluated, grading: &Grading) -> FrameGrade {
    let tolerances = &grading.tolerances;
    let (reference, submission) = (&expected.picture, &submitted.picture);
    FrameGrade {
        frame: expected.frame,
        differences: differences(expected.side(), submitted.side(), tolerances),
        pictures: compare_pictures(reference, submission, tolerances.pixel),
        difference_picture: grading
            .difference_pictures
            .then(|| difference_picture(reference, submission, tolerances.pixel)),
    }
}

/// One submission graded.
pub struct Grade {
    /// The submission's name, as given.
    pub name: String,
    /// The texts of the reference and of the submission.
    pub sources: SourceMap,
    /// What the grading found.
    pub outcome: Outcome,
}

/// What grading a submission found.
pub enum Outcome {
    /// Every frame compared.
    Compared(Vec<FrameGrade>),
    /// The submission does not parse, or fails at `frame`.
    Broken {
        /// The first frame it failed at.
        frame: Frame,
        /// Why.
        diagnostic: Box<Diagnostic>,
    },
    /// The submission could not be read or rendered, in words.
    Failed(String),
}

/// One frame of a submission compared with the reference's.
pub struct FrameGrade {
    /// Which frame.
    pub frame: Frame,
    /// How the scenes differ.
    pub differences: Vec<Difference>,
    /// How the pictures differ.
    pub pictures: PictureDifference,
    /// The picture of the differences, when asked for.
    pub difference_picture: Option<RgbImage>,
}

impl FrameGrade {
    /// Whether the frame matches: no difference in the scenes, and the
    /// pictures within the tolerances.
    pub fn matches(&self, tolerances: &Tolerances) -> bool {
        self.differences.is_empty() && !self.pictures.differs(tolerances.off_pixels)
    }
}

/// The verdict of a grade.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Every frame matches.
    Matches,
    /// Some frame differs.
    Differs,
    /// The submission does not run (or could not be read or rendered).
    Broken,
}

impl Verdict {
    /// Its name in JSON and CSV.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Matches => "match",
            Verdict::Differs => "differ",
            Verdict::Broken => "broken",
        }
    }
}

/// The header of [`Grade::csv_row`]'s rows.
pub const CSV_HEADER: &str = "submission,result,frames_differing,differences,pixels_off,largest_difference,details";

impl Grade {
    /// A submission that could not be read, `why` in words.
    pub fn unreadable(name: String, why: String) -> Grade {
        Grade { name, sources: SourceMap::new(), outcome: Outcome::Failed(why) }
    }

    /// Whether it matches, differs or does not run.
    pub fn verdict(&self, tolerances: &Tolerances) -> Verdict {
        match &self.outcome {
            Outcome::Compared(frames) if frames.iter().all(|frame| frame.matches(tolerances)) => Verdict::Matches,
            Outcome::Compared(_) => Verdict::Differs,
            Outcome::Broken { .. } | Outcome::Failed(_) => Verdict::Broken,
        }
    }

    /// The frames that differ.
    fn differing<'g>(&'g self, tolerances: &'g Tolerances) -> impl Iterator<Item = &'g FrameGrade> + 'g {
        let frames = match &self.outcome {
            Outcome::Compared(frames) => frames.as_slice(),
            _ => &[],
        };
        frames.iter().filter(move |frame| !frame.matches(tolerances))
    }

    /// The grade in words, one line for the verdict and one for each
    /// difference of the first frame that differs, with the numbers of the
    /// other frames that differ; a broken submission's diagnostic as the
    /// batch renderer draws it (with ANSI styles if `color`).
    pub fn words(&self, tolerances: &Tolerances, color: bool) -> String {
        let mut text = match &self.outcome {
            Outcome::Broken { frame, diagnostic } => {
                let at = if frame.number.is_some() { format!(" at {}", frame.words()) } else { String::new() };
                return format!("{}: does not run{at}\n{}", self.name, diagnostic.render(&self.sources, color));
            }
            Outcome::Failed(why) => return format!("{}: cannot be graded: {why}\n", self.name),
            Outcome::Compared(frames) => {
                let differing: Vec<&FrameGrade> = self.differing(tolerances).collect();
                match (differing.first(), frames.len()) {
                    (None, 1) => return format!("{}: matches\n", self.name),
                    (None, count) => return format!("{}: matches, all {count} frames\n", self.name),
                    (Some(_), 1) => format!("{}: differs\n", self.name),
                    (Some(first), count) => {
                        let numbers: Vec<String> =
                            differing.iter().filter_map(|frame| frame.frame.number).map(|k| k.to_string()).collect();
                        let more = first.frame.words();
                        format!(
                            "{}: differs in {} of {count} frames ({}); at {more}:\n",
                            self.name,
                            differing.len(),
                            numbers.join(", ")
                        )
                    }
                }
            }
        };
        let first = self.differing(tolerances).next().expect("a frame differs");
        for difference in &first.differences {
            text.push_str(&format!("  {}\n", difference.words(&self.sources)));
        }
        if first.pictures.differs(tolerances.off_pixels) {
            text.push_str(&format!("  the pictures differ: {}\n", first.pictures.words(tolerances.pixel)));
        }
        text
    }

    /// The grade as one JSON object: `submission`, `result` (`match`,
    /// `differ` or `broken`), and `frames` (each compared frame's `frame`,
    /// `time`, `match`, `differences` and `pictures`), or for a broken
    /// submission `diagnostic` (as `--check --json` gives it, with its
    /// `frame` and `time`) or `error` (in words).
    pub fn to_json(&self, tolerances: &Tolerances) -> Value {
        let mut object = json!({"submission": self.name, "result": self.verdict(tolerances).name()});
        match &self.outcome {
            Outcome::Compared(frames) => {
                let frames = frames.iter().map(|grade| {
                    let mut frame = grade.frame.to_json();
                    frame["match"] = json!(grade.matches(tolerances));
                    let differences = grade.differences.iter().map(|difference| difference.to_json(&self.sources));
                    frame["differences"] = Value::Array(differences.collect());
                    frame["pictures"] = grade.pictures.to_json();
                    frame
                });
                object["frames"] = Value::Array(frames.collect());
            }
            Outcome::Broken { frame, diagnostic } => {
                let mut failed = frame.to_json();
                failed["diagnostic"] = diagnostic.to_json(&self.sources);
                object["failed"] = failed;
            }
            Outcome::Failed(why) => object["error"] = json!(why),
        }
        object
    }

    /// The grade as a row under [`CSV_HEADER`]: the submission, the
    /// verdict, how many frames differ, and of the first that differs (or
    /// the first frame) how many differences the scenes have, the pixels
    /// off and the largest difference; `details` holds every difference
    /// in words, separated by `; ` (a broken submission's diagnostic
    /// message, or why it could not be graded).
    pub fn csv_row(&self, tolerances: &Tolerances) -> String {
        let verdict = self.verdict(tolerances).name();
        let fields: Vec<String> = match &self.outcome {
            Outcome::Compared(frames) => {
                let shown = self.differing(tolerances).next().or(frames.first()).expect("a frame is compared");
                let mut details: Vec<String> =
                    shown.differences.iter().map(|difference| difference.words(&self.sources)).collect();
                if shown.pictures.differs(tolerances.off_pixels) {
                    details.push(format!("the pictures differ: {}", shown.pictures.words(tolerances.pixel)));
                }
                vec![
                    self.differing(tolerances).count().to_string(),
                    shown.differences.len().to_string(),
                    shown.pictures.off.to_string(),
                    shown.pictures.largest.to_string(),
                    details.join("; "),
                ]
            }
            Outcome::Broken { diagnostic, .. } => {
                vec![String::new(), String::new(), String::new(), String::new(), diagnostic.message.clone()]
            }
            Outcome::Failed(why) => vec![String::new(), String::new(), String::new(), String::new(), why.clone()],
        };
        let row = [self.name.clone(), verdict.to_string()].into_iter().chain(fields);
        row.map(|field| csv_field(&field)).collect::<Vec<_>>().join(",")
    }
}

/// `field` as CSV writes it (RFC 4180): in quotes, its quotes doubled,
/// when it holds a comma, a quote or a line break.
fn csv_field(field: &str) -> String {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_string()
    }
}

/// "3 submissions: 1 matches, 1 differs, 1 does not run".
pub fn summary(verdicts: &[Verdict]) -> String {
    let count = |verdict: Verdict| verdicts.iter().filter(|&&v| v == verdict).count();
    let submissions =
        if verdicts.len() == 1 { "1 submission".to_string() } else { format!("{} submissions", verdicts.len()) };
    format!(
        "{submissions}: {} {}, {} {}, {} {}",
        count(Verdict::Matches),
        if count(Verdict::Matches) == 1 { "matches" } else { "match" },
        count(Verdict::Differs),
        if count(Verdict::Differs) == 1 { "differs" } else { "differ" },
        count(Verdict::Broken),
        if count(Verdict::Broken) == 1 { "does not run" } else { "do not run" },
    )
}
