//! The command line: clap definitions and the original course's spellings;
//! which flags go together is in [`flags`]. `job` turns what they parse into
//! the job to run.

pub mod flags;

use std::ffi::OsString;
use std::ops::RangeInclusive;
use std::path::PathBuf;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::compare::Tolerances;
use crate::lang::Limits;
use crate::lint::{Allowed, Check};
use crate::playback::{self, Loops, Timeline};
use crate::render::Screen;
use crate::settings::{self, DEFAULTS, DEPTH, FRAMES, HEIGHT, SAMPLES, THREADS, WIDTH};

/// rayrepl: an interpreter and ray tracer for the `.ray` scene language.
///
/// With a scene file, renders it (or checks it with --check). With no file
/// and a terminal, starts the interactive session; with no file and a piped
/// standard input, runs the script it carries.
#[derive(Debug, Clone, Parser)]
#[command(name = "rayrepl", version, after_help = AFTER_HELP, args_conflicts_with_subcommands = true)]
#[command(mut_args = flags::with_conflicts)]
pub struct Cli {
    /// A command other than rendering: `compare`, `fmt`, `lsp`, `jupyter`.
    #[command(subcommand)]
    pub command: Option<Command>,

    /// The scene to render or check; `-` reads it from standard input.
    pub scene: Option<PathBuf>,

    /// Where to write the image: .png, .ppm or (with --anim) .gif, .apng, .mp4, .webm; `-` writes PPM to stdout.
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,

    /// Parse and evaluate only, then print what the scene holds.
    #[arg(long)]
    pub check: bool,

    /// Load the scene into an interactive session instead of rendering it.
    #[arg(short, long)]
    pub interactive: bool,

    /// Do not say what was written.
    #[arg(short, long)]
    pub quiet: bool,

    /// The size and quality of the pictures.
    #[command(flatten)]
    pub picture: PictureFlags,

    /// The value of `time` for a single image [default: 0].
    #[arg(long, allow_negative_numbers = true, value_parser = settings::parse_time)]
    pub time: Option<f64>,

    /// With --samples N: render every pixel at its centre first, then give N samples only to pixels on edges (where
    /// the surfaces or lights seen change and the colour jumps by more than 2 levels), on sharp highlights, or on
    /// objects under 2 pixels wide.
    #[arg(long)]
    pub adaptive: bool,

    /// Ground-truth render for error measurements: 256 stratified samples per pixel, no shortcuts.
    #[arg(long)]
    pub reference: bool,

    /// Where the z axis meets the screen: its centre (default) or the middle of its bottom edge.
    #[arg(long, value_enum, default_value_t = ScreenArg::Centered)]
    pub screen: ScreenArg,

    /// Worker threads, 1 to 1024 (default: one per core).
    #[arg(long, value_parser = |text: &str| THREADS.parse(text))]
    pub threads: Option<u32>,

    /// Print ray counts, timings and millions of rays per second on stderr.
    #[arg(long)]
    pub stats: bool,

    /// Render an animation of N frames (1 to 1000000), frame k with `time = k` (see --time-start, --time-step).
    #[arg(long, value_name = "N", value_parser = |text: &str| FRAMES.parse(text))]
    pub anim: Option<u32>,

    /// With --anim, render only frames A to B (for spreading frames over machines).
    #[arg(long, value_name = "A..B", value_parser = parse_frames)]
    pub frames: Option<RangeInclusive<u32>>,

    /// The times of the frames.
    #[command(flatten)]
    pub timeline: TimelineFlags,

    /// With --anim, frames a second of a GIF, APNG or video, 0.01 to 100 [default: 25].
    #[arg(long, value_name = "F", value_parser = |text: &str| playback::parse_fps(text))]
    pub fps: Option<f64>,

    /// With --anim, how many times a GIF, APNG or video plays: a count, or `forever` [default: forever; 1 for a video].
    #[arg(long = "loop", value_name = "N|forever", value_parser = |text: &str| playback::parse_loops(text))]
    pub loops: Option<Loops>,

    /// With --anim, write one animated PNG to a .png name rather than numbered images.
    #[arg(long)]
    pub apng: bool,

    /// Write the scene evaluated at --time as a POV-Ray 3.7 scene file instead of rendering it (`-`: to stdout).
    #[arg(long, value_name = "OUT.pov")]
    pub export_pov: Option<PathBuf>,

    /// The evaluator's limits.
    #[command(flatten)]
    pub limits: LimitFlags,

    /// Render again each time the scene file is saved, until Ctrl-C: shown in the terminal, and written to -o FILE
    /// if given. A version with an error is reported and the last good picture stays.
    #[arg(long)]
    pub watch: bool,

    /// Interactive session (or --watch): no pictures in the terminal.
    #[arg(long)]
    pub no_preview: bool,

    /// Session (or script on stdin): start with a lesson, built in (its number) or written in a file.
    #[arg(long, value_name = "N|FILE")]
    pub lesson: Option<String>,

    /// Script on stdin: go on after an error (exit status 1 at the end).
    #[arg(long)]
    pub keep_going: bool,

    /// Explain the colour of pixel X,Y (from the left and from the top) instead of writing an image: what the
    /// camera ray met and which `put` and calls placed it, each light's part, the reflections, and the bytes.
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel)]
    pub explain: Option<(u32, u32)>,

    /// With --explain: print the explanation as one JSON object. With --check: print each diagnostic as one
    /// JSON object, one per line, on standard output.
    #[arg(long)]
    pub json: bool,

    /// Turn off warnings about the scene, by name, comma separated (`all`: every one).
    #[arg(long, value_name = "CHECKS", value_delimiter = ',', value_parser = allow_parser())]
    pub allow: Vec<Allowed>,
}

/// The commands of `rayrepl COMMAND ...`.
#[derive(Debug, Clone, Subcommand)]
pub enum Command {
    /// Grade submissions: compare each one's scene and pictures with a reference's.
    ///
    /// The objects are paired one to one whatever order or construction made them, and each difference is said
    /// in words with the submission's line; then the camera, the lights and the ambient light; then the pictures,
    /// rendered alike, pixel by pixel. A submission that does not run is a row with its diagnostic. Exit status 0
    /// when all match, 1 when one differs or does not run, 2 for a usage error (a reference that cannot be read
    /// or does not run too).
    #[command(after_help = COMPARE_AFTER_HELP)]
    Compare(Box<CompareArgs>),

    /// Format scene files in the style of the bundled scenarios, in place.
    ///
    /// Indents procedures, conditions, the camera, lights, shapes, transformations and groups written over several
    /// lines, spaces operators, commas and parentheses, and keeps every comment and the lines as written (blank
    /// lines one at a time). Only a file whose text changes is written, atomically. A file that does not parse gets
    /// its diagnostic and is left as it is; the others are still formatted. Exit status 0 when every file is
    /// formatted (with --check: none would change), 1 when one does not parse or cannot be written (with --check:
    /// or would change), 2 for a usage error.
    #[command(after_help = FMT_AFTER_HELP)]
    Fmt(FmtArgs),

    /// Serve the Language Server Protocol on standard input and output, for editors.
    ///
    /// Diagnostics while typing, quick fixes, hovers with the help of each word, definitions, references,
    /// renames and the outline of `.ray` files. An editor starts it; docs/guide/editors.md says how to set one up.
    #[cfg(feature = "lsp")]
    Lsp,

    /// Serve a Jupyter notebook kernel (Jupyter starts it), or install its kernelspec (`jupyter install`).
    ///
    /// Each cell holds items and `:` commands, run as a piped script runs them: definitions accumulate across
    /// cells, a cell stops at its first error, `:render` shows the picture in the notebook. docs/guide/notebook.md
    /// says how to start.
    #[cfg(feature = "jupyter")]
    #[command(after_help = JUPYTER_AFTER_HELP, args_conflicts_with_subcommands = true)]
    Jupyter(JupyterArgs),
}

/// `rayrepl jupyter [--connection-file FILE | install ...]`.
#[cfg(feature = "jupyter")]
#[derive(Debug, Clone, Args)]
pub struct JupyterArgs {
    /// What to do other than serving: `install`.
    #[command(subcommand)]
    pub action: Option<JupyterAction>,

    /// The connection file Jupyter writes for the kernel it starts (the kernelspec passes it).
    #[arg(long, value_name = "FILE")]
    pub connection_file: Option<PathBuf>,
}

/// What `rayrepl jupyter` does other than serving.
#[cfg(feature = "jupyter")]
#[derive(Debug, Clone, Subcommand)]
pub enum JupyterAction {
    /// Install the kernelspec `rayrepl` ("rayrepl (.ray)"), which starts this program; for the user by default.
    Install(JupyterInstallArgs),
}

/// `rayrepl jupyter install [--user | --sys-prefix | --prefix DIR]`.
#[cfg(feature = "jupyter")]
#[derive(Debug, Clone, Args)]
pub struct JupyterInstallArgs {
    /// For the user (the default): in JUPYTER_DATA_DIR, else ~/.local/share/jupyter on Linux.
    #[arg(long, conflicts_with_all = ["sys_prefix", "prefix"])]
    pub user: bool,

    /// In the Python environment Jupyter runs in (VIRTUAL_ENV, CONDA_PREFIX, else python3's sys.prefix).
    #[arg(long, conflicts_with = "prefix")]
    pub sys_prefix: bool,

    /// In DIR/share/jupyter/kernels.
    #[arg(long, value_name = "DIR")]
    pub prefix: Option<PathBuf>,

    /// How Jupyter interrupts a running cell: with a message on the control channel, or with SIGINT.
    #[arg(long, value_enum, default_value_t = InterruptMode::Message)]
    pub interrupt_mode: InterruptMode,
}

/// How Jupyter interrupts the kernel (the kernelspec's `interrupt_mode`).
#[cfg(feature = "jupyter")]
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum InterruptMode {
    /// An `interrupt_request` on the control channel.
    Message,
    /// SIGINT.
    Signal,
}

#[cfg(feature = "jupyter")]
const JUPYTER_AFTER_HELP: &str = "\
Examples:
  rayrepl jupyter install                              install the kernel for the user
  rayrepl jupyter install --sys-prefix                 install it in the active Python environment
  jupyter lab                                          then pick \"rayrepl (.ray)\" for a new notebook";

/// `rayrepl fmt [--check] FILE...`.
#[derive(Debug, Clone, Args)]
pub struct FmtArgs {
    /// The scene files; `-` alone formats standard input to standard output.
    #[arg(required = true, value_name = "FILE")]
    pub files: Vec<PathBuf>,

    /// Write nothing: say which files would change, from which line (exit status 1 if one would).
    #[arg(long)]
    pub check: bool,
}

const FMT_AFTER_HELP: &str = "\
Examples:
  rayrepl fmt scene.ray                                format scene.ray in place
  rayrepl fmt --check scenarios/*.ray                  say which files would change
  rayrepl fmt - < scene.ray > formatted.ray            standard input to standard output";

/// `rayrepl compare REFERENCE SUBMISSION...`.
#[derive(Debug, Clone, Args)]
pub struct CompareArgs {
    /// The reference scene.
    pub reference: PathBuf,

    /// The submissions: scene files, or folders (their `.ray` files, sorted by name, one row each).
    #[arg(required = true, value_name = "SUBMISSION")]
    pub submissions: Vec<PathBuf>,

    /// The size and quality of the pictures.
    #[command(flatten)]
    pub picture: PictureFlags,

    /// The value of `time` of the scenes compared [default: 0].
    #[arg(long, allow_negative_numbers = true, value_parser = settings::parse_time)]
    pub time: Option<f64>,

    /// Compare the N frames of an animation (1 to 1000000), frame k at `time = k` (see --time-start, --time-step).
    #[arg(long, value_name = "N", value_parser = |text: &str| FRAMES.parse(text))]
    pub anim: Option<u32>,

    /// The times of the frames.
    #[command(flatten)]
    pub timeline: TimelineFlags,

    /// Lengths (positions, sizes, the camera's distance) agree within this share of the reference scene's size.
    #[arg(long, value_name = "SHARE", default_value_t = Tolerances::DEFAULT.length, value_parser = parse_tolerance)]
    pub length_tolerance: f64,

    /// Colour components agree within this many levels of 255.
    #[arg(long, value_name = "LEVELS", default_value_t = Tolerances::DEFAULT.colour, value_parser = parse_tolerance)]
    pub colour_tolerance: f64,

    /// Other numbers (kd, ks, phong, intensities, directions, the camera's angle) agree within this, times the
    /// reference's value when it is above 1.
    #[arg(long, value_name = "E", default_value_t = Tolerances::DEFAULT.coefficient, value_parser = parse_tolerance)]
    pub coefficient_tolerance: f64,

    /// A pixel is off when one of its channels differs by more than this many levels (0 to 255).
    #[arg(long, value_name = "LEVELS", default_value_t = Tolerances::DEFAULT.pixel)]
    pub pixel_tolerance: u8,

    /// The pictures differ when more than this percentage of their pixels are off (0 to 100).
    #[arg(long, value_name = "PERCENT", default_value_t = Tolerances::DEFAULT.off_pixels * 100.0, value_parser = parse_percentage)]
    pub off_pixels: f64,

    /// Write a picture of the differences of each submission into this folder (made if missing):
    /// NAME.png, or NAME0001.png... for each frame of an animation.
    #[arg(long, value_name = "DIR")]
    pub diff: Option<PathBuf>,

    /// Print each submission's grade as one JSON object, one per line, instead of words.
    #[arg(long)]
    pub json: bool,

    /// Write the grades as CSV, one row per submission, to FILE (`-`: to standard output instead of words).
    #[arg(long, value_name = "FILE", conflicts_with = "json")]
    pub csv: Option<PathBuf>,

    /// The evaluator's limits.
    #[command(flatten)]
    pub limits: LimitFlags,

    /// Worker threads, 1 to 1024 (default: one per core).
    #[arg(long, value_parser = |text: &str| THREADS.parse(text))]
    pub threads: Option<u32>,
}

const COMPARE_AFTER_HELP: &str = "\
Examples:
  rayrepl compare reference.ray student.ray            one submission, in words
  rayrepl compare reference.ray submissions/ --csv grades.csv
                                                       a folder: one row each, and a CSV file
  rayrepl compare reference.ray a.ray b.ray --json     one JSON object per submission
  rayrepl compare reference.ray a.ray --anim 24 --diff diffs/
                                                       24 frames, a picture of the differences of each";

/// Parses a tolerance: a finite number, 0 or more.
fn parse_tolerance(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(value) if value.is_finite() && value >= 0.0 => Ok(value),
        _ => Err(format!("`{text}` is not a tolerance: give a number, 0 or more")),
    }
}

/// Parses a percentage, 0 to 100, into a share, 0 to 1.
fn parse_percentage(text: &str) -> Result<f64, String> {
    match parse_tolerance(text) {
        Ok(percent) if percent <= 100.0 => Ok(percent / 100.0),
        _ => Err(format!("`{text}` is not a percentage: give a number from 0 to 100")),
    }
}

/// The size and quality of the pictures, for rendering and for `compare`.
#[derive(Debug, Clone, Args)]
pub struct PictureFlags {
    /// Image width in pixels, 1 to 65535 (also `-hsize`); at most 8192×8192 pixels in all.
    #[arg(long, default_value_t = DEFAULTS.width, value_parser = |text: &str| WIDTH.parse(text))]
    pub width: u32,

    /// Image height in pixels, 1 to 65535 (also `-vsize`).
    #[arg(long, default_value_t = DEFAULTS.height, value_parser = |text: &str| HEIGHT.parse(text))]
    pub height: u32,

    /// Number of reflections followed (SPEC 6), 0 to 1000.
    #[arg(long, default_value_t = DEFAULTS.depth, value_parser = |text: &str| DEPTH.parse(text))]
    pub depth: u32,

    /// Samples per pixel, 1 to 4096 (deterministic stratified anti-aliasing; 1 = pixel centres).
    #[arg(long, default_value_t = DEFAULTS.samples, value_parser = |text: &str| SAMPLES.parse(text))]
    pub samples: u32,
}

/// The times of an animation's frames after the first.
#[derive(Debug, Clone, Args)]
pub struct TimelineFlags {
    /// With --anim, the time of frame 1 [default: 1].
    #[arg(long, value_name = "A", allow_negative_numbers = true, value_parser = |text: &str| playback::parse_time_number(text))]
    pub time_start: Option<f64>,

    /// With --anim, how much the time grows from a frame to the next: frame k has time = A + (k - 1) * S [default: 1].
    #[arg(long, value_name = "S", allow_negative_numbers = true, value_parser = |text: &str| playback::parse_time_number(text))]
    pub time_step: Option<f64>,
}

impl TimelineFlags {
    /// The timeline these flags give, the defaults where not given.
    pub fn timeline(&self) -> Timeline {
        Timeline {
            start: self.time_start.unwrap_or(Timeline::DEFAULT.start),
            step: self.time_step.unwrap_or(Timeline::DEFAULT.step),
        }
    }
}

/// The evaluator's limits.
#[derive(Debug, Clone, Args)]
pub struct LimitFlags {
    /// Deepest chain of procedure calls allowed.
    #[arg(long, default_value_t = Limits::DEFAULT.max_call_depth, value_name = "N")]
    pub max_calls: usize,

    /// Most primitives a scene may create.
    #[arg(long, default_value_t = Limits::DEFAULT.max_primitives, value_name = "N")]
    pub max_primitives: usize,
}

impl LimitFlags {
    /// The limits these flags give.
    pub fn limits(&self) -> Limits {
        Limits { max_call_depth: self.max_calls, max_primitives: self.max_primitives, ..Limits::DEFAULT }
    }
}

/// The two screen conventions of SPEC 5.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ScreenArg {
    /// The z axis goes through the centre of the screen.
    Centered,
    /// The z axis goes through the middle of the screen's bottom edge.
    Bottom,
}

impl ScreenArg {
    /// The renderer's name for this convention.
    pub fn screen(self) -> Screen {
        match self {
            ScreenArg::Centered => Screen::Centered,
            ScreenArg::Bottom => Screen::Bottom,
        }
    }
}

const AFTER_HELP: &str = "\
Examples:
  rayrepl scenarios/solar.ray -o solar.png             render one image
  rayrepl scenarios/solar.ray --anim 100 -o solar.gif  an animated GIF
  rayrepl scenarios/solar.ray --anim 100 --fps 30 --loop 1 -o solar.apng
                                                       an animated PNG at 30 fps, played once
  rayrepl scenarios/solar.ray --anim 400 --time-start 1 --time-step 0.25 -o solar.mp4
                                                       a video (with ffmpeg), time = 1, 1.25, ...
  rayrepl scenarios/solar.ray --anim 100 --frames 1..50 -o out.png
                                                       frames 1-50 as out0001.png...
  rayrepl --check scenarios/menger.ray                 parse and evaluate only
  rayrepl scenarios/solar.ray --time 10 --export-pov solar.pov
                                                       the scene for POV-Ray 3.7
  rayrepl scenarios/solar.ray --explain 400,300        why that pixel has its colour
  rayrepl scene.ray --watch -o scene.png               render again at every save
  rayrepl compare reference.ray submissions/          grade submissions against a reference
  rayrepl fmt scene.ray                                format a scene file in place
  rayrepl                                              the interactive session
  cat script.ray | rayrepl                             run a script

The original course's spellings -hsize, -vsize, -depth and -anim are accepted.";

/// The names `--allow` takes, with what each turns off (clap lists them in
/// `--help` and in the error for an unknown name).
fn allow_parser() -> impl TypedValueParser<Value = Allowed> {
    let checks = Check::ALL.map(|check| PossibleValue::new(check.name()).help(check.summary()));
    let every = PossibleValue::new(Allowed::EVERY_NAME).help("every warning about the scene");
    PossibleValuesParser::new(checks.into_iter().chain([every]))
        .map(|name| Allowed::named(&name).expect("clap accepts only the names listed"))
}

/// Parses a pixel `X,Y`.
fn parse_pixel(text: &str) -> Result<(u32, u32), String> {
    let wrong = || format!("`{text}` is not a pixel like 120,45 (X from the left, Y from the top, from 0)");
    let (x, y) = text.split_once(',').ok_or_else(wrong)?;
    let number = |s: &str| s.trim().parse::<u32>().map_err(|_| wrong());
    Ok((number(x)?, number(y)?))
}

/// Parses `A..B` (or `A-B`, or a single `A`) into a frame range.
fn parse_frames(text: &str) -> Result<RangeInclusive<u32>, String> {
    let (first, last) = match text.split_once("..").or_else(|| text.split_once('-')) {
        Some((a, b)) => (a, b),
        None => (text, text),
    };
    let number = |s: &str| s.trim().parse::<u32>().map_err(|_| format!("`{text}` is not a frame range like 1..50"));
    let (first, last) = (number(first)?, number(last)?);
    if first == 0 || first > last {
        return Err(format!("`{text}`: frames are numbered from 1 and the range must not be empty"));
    }
    Ok(first..=last)
}

/// Rewrites the original course's single-dash options (`-hsize 800`) into
/// this tool's (`--width 800`), leaving everything else as it is.
pub fn translate_legacy_args(args: impl IntoIterator<Item = OsString>) -> Vec<OsString> {
    args.into_iter()
        .map(|arg| match arg.to_str() {
            Some("-hsize") => "--width".into(),
            Some("-vsize") => "--height".into(),
            Some("-depth") => "--depth".into(),
            Some("-anim") => "--anim".into(),
            _ => arg,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_ranges_parse_and_reject_nonsense() {
        assert_eq!(parse_frames("1..50"), Ok(1..=50));
        assert_eq!(parse_frames("7"), Ok(7..=7));
        assert_eq!(parse_frames("3-4"), Ok(3..=4));
        assert!(parse_frames("0..3").is_err());
        assert!(parse_frames("5..2").is_err());
        assert!(parse_frames("a..b").is_err());
    }

    #[test]
    fn legacy_spellings_are_translated() {
        let args = ["rayrepl", "-hsize", "320", "-vsize", "200", "-depth", "2", "-anim", "3"];
        let cli = Cli::parse_from(translate_legacy_args(args.map(OsString::from)));
        let picture = &cli.picture;
        assert_eq!((picture.width, picture.height, picture.depth, cli.anim), (320, 200, 2, Some(3)));
    }

    #[test]
    fn reference_excludes_an_explicit_sample_count() {
        assert!(Cli::parse_from(["rayrepl", "--reference", "a.ray"]).reference);
        assert!(Cli::try_parse_from(["rayrepl", "--reference", "--samples", "4", "a.ray"]).is_err());
    }
}
