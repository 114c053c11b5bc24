//! The command line: clap definitions and the original course's spellings.

use std::ffi::OsString;
use std::ops::RangeInclusive;
use std::path::PathBuf;

use clap::{Parser, ValueEnum};

use crate::render::Screen;

/// rayrepl: an interpreter and ray tracer for the `.ray` scene language.
///
/// With a scene file, renders it (or checks it with --check). With no file
/// and a terminal, starts the interactive session; with no file and a piped
/// standard input, runs the script it carries.
#[derive(Debug, Clone, Parser)]
#[command(name = "rayrepl", version, after_help = AFTER_HELP)]
pub struct Cli {
    /// The scene to render or check; `-` reads it from standard input.
    pub scene: Option<PathBuf>,

    /// Where to write the image: .png, .ppm or (with --anim) .gif; `-` writes PPM to stdout.
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,

    /// Parse and evaluate only, then print what the scene holds.
    #[arg(long)]
    pub check: bool,

    /// Load the scene into an interactive session instead of rendering it.
    #[arg(short, long)]
    pub interactive: bool,

    /// Image width in pixels (also `-hsize`).
    #[arg(long, default_value_t = 800, value_parser = clap::value_parser!(u32).range(1..=65_536))]
    pub width: u32,

    /// Image height in pixels (also `-vsize`).
    #[arg(long, default_value_t = 600, value_parser = clap::value_parser!(u32).range(1..=65_536))]
    pub height: u32,

    /// Number of reflections followed (SPEC 6).
    #[arg(long, default_value_t = 5)]
    pub depth: u32,

    /// The value of `time` for a single image.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, value_parser = parse_finite)]
    pub time: f64,

    /// Samples per pixel (deterministic stratified anti-aliasing; 1 = pixel centres).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub samples: u32,

    /// With --samples N: render every pixel at its centre first, then give N samples only to pixels on edges (where
    /// the surfaces or lights seen change and the colour jumps by more than 2 levels), on sharp highlights, or on
    /// objects under 2 pixels wide.
    #[arg(long)]
    pub adaptive: bool,

    /// Ground-truth render for error measurements: 256 stratified samples per pixel, no shortcuts.
    #[arg(long, conflicts_with_all = ["samples", "adaptive"])]
    pub reference: bool,

    /// Where the z axis meets the screen: its centre (default) or the middle of its bottom edge.
    #[arg(long, value_enum, default_value_t = ScreenArg::Centered)]
    pub screen: ScreenArg,

    /// Worker threads (default: one per core).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: Option<u32>,

    /// Print ray counts, timings and millions of rays per second on stderr.
    #[arg(long)]
    pub stats: bool,

    /// Render an animation of N frames, frame k with `time = k`.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub anim: Option<u32>,

    /// With --anim, render only frames A to B (for spreading frames over machines).
    #[arg(long, value_name = "A..B", value_parser = parse_frames)]
    pub frames: Option<RangeInclusive<u32>>,

    /// Deepest chain of procedure calls allowed.
    #[arg(long, default_value_t = 100_000, value_name = "N")]
    pub max_calls: usize,

    /// Most primitives a scene may create.
    #[arg(long, default_value_t = crate::lang::Limits::DEFAULT.max_primitives, value_name = "N")]
    pub max_primitives: usize,

    /// Interactive session: no pictures in the terminal.
    #[arg(long)]
    pub no_preview: bool,

    /// Script on stdin: go on after an error (exit status 1 at the end).
    #[arg(long)]
    pub keep_going: bool,
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
  rayrepl scenarios/solar.ray --anim 100 --frames 1..50 -o out.png
                                                       frames 1-50 as out0001.png...
  rayrepl --check scenarios/menger.ray                 parse and evaluate only
  rayrepl                                              the interactive session
  cat script.ray | rayrepl                             run a script

The original course's spellings -hsize, -vsize, -depth and -anim are accepted.";

/// Parses a finite number (`time` may not be NaN or infinite).
fn parse_finite(text: &str) -> Result<f64, String> {
    text.parse::<f64>().ok().filter(|t| t.is_finite()).ok_or_else(|| format!("`{text}` is not a finite number"))
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
        assert_eq!((cli.width, cli.height, cli.depth, cli.anim), (320, 200, 2, Some(3)));
    }

    #[test]
    fn reference_excludes_an_explicit_sample_count() {
        assert!(Cli::parse_from(["rayrepl", "--reference", "a.ray"]).reference);
        assert!(Cli::try_parse_from(["rayrepl", "--reference", "--samples", "4", "a.ray"]).is_err());
    }
}
