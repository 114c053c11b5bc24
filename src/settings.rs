//! The render settings and their limits, one definition for the command
//! line, the session's commands and piped scripts: each value is checked by
//! the same function wherever it comes from, and a refusal names the limit
//! and the reason for it.

use std::fmt;

use crate::render::{self, RenderOptions, Screen};

/// How an image is rendered: size, reflections, anti-aliasing and time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Number of reflections followed (SPEC 6).
    pub depth: u32,
    /// Rays per pixel (1 samples each pixel at its centre).
    pub samples: u32,
    /// With `samples > 1`, give the samples only to the pixels that need them.
    pub adaptive: bool,
    /// The value of `time` for evaluation and renders (SPEC 3).
    pub time: f64,
    /// Where the z axis meets the screen (SPEC 5).
    pub screen: Screen,
}

/// The settings used where none are given: the renderer's defaults, at
/// time 0.
pub const DEFAULTS: RenderSettings = RenderSettings {
    width: RenderOptions::DEFAULT.width,
    height: RenderOptions::DEFAULT.height,
    depth: RenderOptions::DEFAULT.depth,
    samples: RenderOptions::DEFAULT.samples,
    adaptive: RenderOptions::DEFAULT.adaptive,
    time: 0.0,
    screen: RenderOptions::DEFAULT.screen,
};

impl Default for RenderSettings {
    fn default() -> RenderSettings {
        DEFAULTS
    }
}

impl RenderSettings {
    /// Checks every setting against its limit.
    pub fn validate(&self) -> Result<(), SettingError> {
        check_size(self.width, self.height)?;
        DEPTH.check(self.depth)?;
        SAMPLES.check(self.samples)?;
        check_time(self.time)
    }

    /// The renderer's options for these settings.
    pub fn render_options(&self) -> RenderOptions {
        RenderOptions {
            width: self.width,
            height: self.height,
            depth: self.depth,
            samples: self.samples,
            adaptive: self.adaptive,
            screen: self.screen,
            ..RenderOptions::default()
        }
    }
}

/// The range a whole-number setting may take, and why it stops there.
#[derive(Debug, PartialEq, Eq)]
pub struct Limit {
    /// What the value is, as a message names it ("the width").
    pub name: &'static str,
    /// The smallest value accepted.
    pub min: u32,
    /// The largest value accepted.
    pub max: u32,
    /// Why the range ends where it does.
    pub why: &'static str,
}

/// Image width in pixels.
pub const WIDTH: Limit = Limit { name: "the width", min: 1, max: MAX_SIDE, why: SIDE_WHY };
/// Image height in pixels.
pub const HEIGHT: Limit = Limit { name: "the height", min: 1, max: MAX_SIDE, why: SIDE_WHY };
/// Reflections followed: [`render::MAX_DEPTH`].
pub const DEPTH: Limit = Limit {
    name: "the depth",
    min: 0,
    max: render::MAX_DEPTH,
    why: "beyond it no scene changes by a visible level, and each reflection costs time",
};
/// Samples per pixel.
pub const SAMPLES: Limit = Limit {
    name: "the number of samples",
    min: 1,
    max: 4096,
    why: "a 64×64 grid in each pixel; more changes no 8-bit level",
};
/// Frames of an animation.
pub const FRAMES: Limit =
    Limit { name: "the number of frames", min: 1, max: 1_000_000, why: "over 11 hours at 25 frames a second" };
/// Worker threads.
pub const THREADS: Limit = Limit {
    name: "the number of threads",
    min: 1,
    max: 1024,
    why: "more threads than cores only share the same cores",
};

/// The largest width or height.
const MAX_SIDE: u32 = 65_535;
const SIDE_WHY: &str = "the largest side a GIF can have";

/// The most pixels an image may have: 8192×8192. The image takes 3 bytes a
/// pixel and the renderer's side buffers (adaptive sampling's records of
/// each pixel, frame reuse's validity) up to about 60 more, so an image at
/// the limit needs at most [`PIXEL_MEMORY`].
pub const MAX_PIXELS: u64 = 1 << 26;

/// What an image at [`MAX_PIXELS`] may take in memory, in words.
const PIXEL_MEMORY: &str = "4 GiB";

impl Limit {
    /// `value`, if it is within the limit.
    pub fn check(&'static self, value: u32) -> Result<u32, SettingError> {
        if (self.min..=self.max).contains(&value) {
            Ok(value)
        } else {
            Err(SettingError::OutOfRange { limit: self, given: value.to_string() })
        }
    }

    /// Parses `text` as a whole number within the limit.
    pub fn parse(&'static self, text: &str) -> Result<u32, SettingError> {
        let out_of_range = || SettingError::OutOfRange { limit: self, given: text.to_string() };
        self.check(text.trim().parse().map_err(|_| out_of_range())?).map_err(|_| out_of_range())
    }
}

/// Checks a width and a height, each and together.
pub fn check_size(width: u32, height: u32) -> Result<(), SettingError> {
    WIDTH.check(width)?;
    HEIGHT.check(height)?;
    if u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(SettingError::TooManyPixels { width, height });
    }
    Ok(())
}

/// Parses a value of `time`: any finite number.
pub fn parse_time(text: &str) -> Result<f64, SettingError> {
    let time = text.trim().parse::<f64>().map_err(|_| SettingError::NotANumber { given: text.to_string() })?;
    check_time(time)?;
    Ok(time)
}

fn check_time(time: f64) -> Result<(), SettingError> {
    if time.is_finite() { Ok(()) } else { Err(SettingError::NotANumber { given: time.to_string() }) }
}

/// A setting refused, with the limit it breaks.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SettingError {
    /// A whole number outside its [`Limit`], or not a whole number.
    OutOfRange {
        /// The limit broken.
        limit: &'static Limit,
        /// The value as given.
        given: String,
    },
    /// An image of more than [`MAX_PIXELS`] pixels.
    TooManyPixels {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
    },
    /// A time that is not a finite number.
    NotANumber {
        /// The value as given.
        given: String,
    },
}

impl fmt::Display for SettingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SettingError::OutOfRange { limit, given } => write!(
                f,
                "{} must be a whole number from {} to {} ({}), not `{given}`",
                limit.name, limit.min, limit.max, limit.why
            ),
            SettingError::TooManyPixels { width, height } => write!(
                f,
                "an image of {width}×{height} has {} pixels; the most is {MAX_PIXELS} (8192×8192), \
                 so that the image and the renderer's buffers fit in {PIXEL_MEMORY} of memory",
                u64::from(*width) * u64::from(*height)
            ),
            SettingError::NotANumber { given } => write!(f, "the time must be a finite number, not `{given}`"),
        }
    }
}

impl std::error::Error for SettingError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_accept_their_range_and_name_themselves_outside_it() {
        assert_eq!(DEPTH.parse("0"), Ok(0));
        assert_eq!(DEPTH.parse("1000"), Ok(1000));
        let refused = DEPTH.parse("4294967295").expect_err("past the maximum").to_string();
        assert!(refused.contains("the depth must be a whole number from 0 to 1000"), "{refused}");
        assert!(SAMPLES.parse("0").is_err());
        assert!(WIDTH.parse("-3").is_err());
        assert!(FRAMES.parse("x").is_err());
    }

    #[test]
    fn an_image_too_large_for_memory_is_refused_before_anything_is_allocated() {
        assert!(check_size(8192, 8192).is_ok());
        assert!(check_size(65_535, 1024).is_ok());
        let refused = check_size(65_535, 65_535).expect_err("4 billion pixels").to_string();
        assert!(refused.contains("4294836225 pixels") && refused.contains("4 GiB"), "{refused}");
        assert!(check_size(0, 10).is_err());
    }

    #[test]
    fn time_is_any_finite_number() {
        assert_eq!(parse_time("-2.5"), Ok(-2.5));
        assert!(parse_time("inf").is_err());
        assert!(parse_time("nan").is_err());
        assert!(RenderSettings { time: f64::NAN, ..DEFAULTS }.validate().is_err());
        assert!(DEFAULTS.validate().is_ok());
    }
}
