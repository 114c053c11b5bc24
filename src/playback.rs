//! How an animation plays: the value of `time` at each frame, the frame
//! rate and the looping. One definition and one set of parsers for the
//! command line (`--time-start`, `--fps`, ...) and the session's `:anim`.

use std::fmt;
use std::ops::RangeInclusive;

use crate::lang::number::format_number;

/// The value of `time` at each frame: frame k (from 1) is computed with
/// `time = start + (k - 1) * step`, so the defaults (1 and 1) give
/// `time = k` (SPEC 3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timeline {
    /// The time of frame 1.
    pub start: f64,
    /// How much the time grows from one frame to the next.
    pub step: f64,
}

impl Timeline {
    /// `time = k` at frame k.
    pub const DEFAULT: Timeline = Timeline { start: 1.0, step: 1.0 };

    /// The time of frame `k` (from 1).
    pub fn time_of(&self, k: u32) -> f64 {
        self.start + f64::from(k - 1) * self.step
    }

    /// Checks, before any work, that every frame of `frames` has a finite
    /// time: a start and a step that are each finite can still add up past
    /// the largest number (`1e308 + 1e308`), and no frame is then computed
    /// at a made-up time.
    pub fn check(&self, frames: RangeInclusive<u32>) -> Result<(), PlaybackError> {
        match frames.into_iter().find(|&k| !self.time_of(k).is_finite()) {
            None => Ok(()),
            Some(frame) => Err(PlaybackError::FrameTime {
                frame,
                time: format!("{} + {} * {}", format_number(self.start), frame - 1, format_number(self.step)),
            }),
        }
    }
}

impl Default for Timeline {
    fn default() -> Timeline {
        Timeline::DEFAULT
    }
}

/// How many times an animation plays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Loops {
    /// Again and again (a viewer's own choice ends it).
    Forever,
    /// This many times in all, from 1.
    Times(u32),
}

/// The speed and looping of an animation file, each `None` where not given
/// (every format then has its default: [`DEFAULT_FPS`], and looping forever
/// for GIF and APNG, playing once for a video).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Playback {
    /// Frames a second.
    pub fps: Option<f64>,
    /// How many times it plays.
    pub loops: Option<Loops>,
}

impl Playback {
    /// The frame rate, given or the default.
    pub fn fps(&self) -> f64 {
        self.fps.unwrap_or(DEFAULT_FPS)
    }

    /// Whether a speed or a looping was given.
    pub fn is_given(&self) -> bool {
        self.fps.is_some() || self.loops.is_some()
    }
}

/// The frame rate where none is given.
pub const DEFAULT_FPS: f64 = 25.0;

/// The slowest frame rate: one frame shown for 100 seconds.
const MIN_FPS: f64 = 0.01;

/// The fastest frame rate: a GIF's delays are counted in hundredths of a
/// second.
const MAX_FPS: f64 = 100.0;

/// The most plays of a looping count (a GIF stores at most 65535 repeats).
const MAX_LOOPS: u32 = 65_535;

/// A frame rate from 0.01 to 100 frames a second (`30`, `12.5`).
pub fn parse_fps(text: &str) -> Result<f64, PlaybackError> {
    let refused = || PlaybackError::Fps { given: text.to_string() };
    let fps = text.trim().parse::<f64>().map_err(|_| refused())?;
    if (MIN_FPS..=MAX_FPS).contains(&fps) { Ok(fps) } else { Err(refused()) }
}

/// A looping: `forever`, or how many times to play in all (1 to 65535).
pub fn parse_loops(text: &str) -> Result<Loops, PlaybackError> {
    let text = text.trim();
    if text.eq_ignore_ascii_case("forever") {
        return Ok(Loops::Forever);
    }
    match text.parse::<u32>() {
        Ok(times @ 1..=MAX_LOOPS) => Ok(Loops::Times(times)),
        _ => Err(PlaybackError::Loops { given: text.to_string() }),
    }
}

/// A time or a time step: any finite number.
pub fn parse_time_number(text: &str) -> Result<f64, PlaybackError> {
    match text.trim().parse::<f64>() {
        Ok(number) if number.is_finite() => Ok(number),
        _ => Err(PlaybackError::Time { given: text.to_string() }),
    }
}

/// What an animation is asked for besides its frames: their times and how
/// the file plays them.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct AnimationOptions {
    /// The time of each frame.
    pub timeline: Timeline,
    /// The speed and looping.
    pub playback: Playback,
    /// Whether a `.png` name is one animated PNG rather than numbered images.
    pub apng: bool,
}

/// The options `:anim` takes after its file name, with what each expects,
/// named as on the command line.
pub const SESSION_OPTIONS: &str = "--fps F, --loop N|forever, --time-start A, --time-step S, --apng";

impl AnimationOptions {
    /// Parses options written as on the command line (`--fps 30 --loop 2`),
    /// as `:anim` takes them.
    pub fn parse_words(words: &[String]) -> Result<AnimationOptions, PlaybackError> {
        let mut options = AnimationOptions::default();
        let mut words = words.iter();
        while let Some(name) = words.next() {
            if name == "--apng" {
                options.apng = true;
                continue;
            }
            let known = ["--fps", "--loop", "--time-start", "--time-step"];
            if !known.contains(&name.as_str()) {
                return Err(PlaybackError::UnknownOption { given: name.clone() });
            }
            let value = words.next().ok_or_else(|| PlaybackError::MissingValue { option: name.clone() })?;
            match name.as_str() {
                "--fps" => options.playback.fps = Some(parse_fps(value)?),
                "--loop" => options.playback.loops = Some(parse_loops(value)?),
                "--time-start" => options.timeline.start = parse_time_number(value)?,
                _ => options.timeline.step = parse_time_number(value)?,
            }
        }
        Ok(options)
    }
}

/// A frame rate, looping or time refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PlaybackError {
    /// A frame rate out of range or not a number.
    Fps {
        /// The value as given.
        given: String,
    },
    /// A looping that is neither `forever` nor a count in range.
    Loops {
        /// The value as given.
        given: String,
    },
    /// A time or time step that is not a finite number.
    Time {
        /// The value as given.
        given: String,
    },
    /// A frame whose time, start plus steps, is not a finite number.
    FrameTime {
        /// The frame, from 1.
        frame: u32,
        /// Its time as the sum that overflows: `1e308 + 1 * 1e308`.
        time: String,
    },
    /// An option `:anim` does not take.
    UnknownOption {
        /// The word given.
        given: String,
    },
    /// An option given without its value.
    MissingValue {
        /// The option.
        option: String,
    },
}

impl fmt::Display for PlaybackError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlaybackError::Fps { given } => write!(
                f,
                "the frame rate must be a number from {MIN_FPS} to {MAX_FPS} frames a second \
                 (a GIF counts its delays in hundredths of a second), not `{given}`"
            ),
            PlaybackError::Loops { given } => write!(
                f,
                "the looping must be `forever` or how many times to play, from 1 to {MAX_LOOPS}, not `{given}`"
            ),
            PlaybackError::Time { given } => write!(f, "a time or time step must be a finite number, not `{given}`"),
            PlaybackError::FrameTime { frame, time } => write!(
                f,
                "frame {frame} would have time = {time}, which is not a finite number: \
                 give a smaller --time-start or --time-step"
            ),
            PlaybackError::UnknownOption { given } => {
                write!(f, "`{given}` is not an option of :anim; it takes {SESSION_OPTIONS}")
            }
            PlaybackError::MissingValue { option } => write!(f, "{option} needs a value after it"),
        }
    }
}

impl std::error::Error for PlaybackError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_k_has_time_start_plus_k_minus_one_steps() {
        assert_eq!(Timeline::DEFAULT.time_of(1), 1.0);
        assert_eq!(Timeline::DEFAULT.time_of(7), 7.0);
        let smooth = Timeline { start: 0.0, step: 0.25 };
        assert_eq!((smooth.time_of(1), smooth.time_of(5)), (0.0, 1.0));
        assert_eq!(Timeline { start: 2.0, step: -0.5 }.time_of(3), 1.0);
    }

    #[test]
    fn a_frame_whose_time_is_not_finite_is_refused_naming_it() {
        let huge = Timeline { start: 1e308, step: 1e308 };
        assert_eq!(huge.check(1..=1), Ok(()));
        let refused = huge.check(1..=3).expect_err("frame 2 overflows").to_string();
        assert_eq!(
            refused,
            "frame 2 would have time = 1e308 + 1 * 1e308, which is not a finite number: \
             give a smaller --time-start or --time-step"
        );
        let falling = Timeline { start: -1e308, step: -0.5e308 };
        assert!(falling.check(2..=5).expect_err("overflows").to_string().starts_with("frame 3 "));
        assert_eq!(Timeline { start: 0.5, step: 0.25 }.check(1..=1_000_000), Ok(()));
    }

    #[test]
    fn frame_rates_and_loopings_parse_within_their_limits() {
        assert_eq!(parse_fps("30"), Ok(30.0));
        assert_eq!(parse_fps(" 12.5 "), Ok(12.5));
        for refused in ["0", "-1", "101", "nan", "inf", "x"] {
            assert!(parse_fps(refused).is_err(), "{refused}");
        }
        assert_eq!(parse_loops("forever"), Ok(Loops::Forever));
        assert_eq!(parse_loops("3"), Ok(Loops::Times(3)));
        for refused in ["0", "65536", "-2", "1.5", "always"] {
            assert!(parse_loops(refused).is_err(), "{refused}");
        }
        assert!(parse_time_number("inf").is_err());
        assert_eq!(parse_time_number("-0.5"), Ok(-0.5));
    }

    #[test]
    fn session_options_read_like_the_command_line() {
        let words = |text: &str| text.split_whitespace().map(String::from).collect::<Vec<_>>();
        let options = AnimationOptions::parse_words(&words("--fps 30 --loop 2 --time-start 0 --time-step 0.1 --apng"))
            .expect("all known");
        assert_eq!(options.playback, Playback { fps: Some(30.0), loops: Some(Loops::Times(2)) });
        assert_eq!(options.timeline, Timeline { start: 0.0, step: 0.1 });
        assert!(options.apng);
        assert_eq!(AnimationOptions::parse_words(&[]), Ok(AnimationOptions::default()));
        let unknown = AnimationOptions::parse_words(&words("--speed 3")).expect_err("unknown").to_string();
        assert!(unknown.contains("`--speed` is not an option of :anim"), "{unknown}");
        assert!(AnimationOptions::parse_words(&words("--fps")).is_err());
    }
}
