//! What a render is asked to do, how it can be watched and stopped, and
//! what it reports.

use std::sync::atomic::AtomicBool;
use std::time::Duration;

use super::camera::Screen;

/// The most reflections a render follows (`depth`), the same for every entry
/// point: a path's colour is computed level by level, so its cost in time
/// and stack grows with the depth, and past a few hundred reflections no
/// scene changes by a visible level (each level is weighted by a further
/// `ks`; two facing perfect mirrors are the exception, and they show the
/// same colour at every depth beyond this).
pub const MAX_DEPTH: u32 = 1000;

/// Samples per pixel of [`RenderOptions::reference`]: a 16 x 16 stratified grid.
pub const REFERENCE_SAMPLES: u32 = 256;

/// Rays traced, counted per band and summed (no atomics per ray).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RayCounts {
    /// Camera rays.
    pub primary: u64,
    /// Rays towards lights.
    pub shadow: u64,
    /// Mirror rays.
    pub reflection: u64,
}

impl RayCounts {
    /// All rays, of every kind.
    pub fn total(&self) -> u64 {
        self.primary + self.shadow + self.reflection
    }
}

impl std::ops::AddAssign for RayCounts {
    fn add_assign(&mut self, other: RayCounts) {
        self.primary += other.primary;
        self.shadow += other.shadow;
        self.reflection += other.reflection;
    }
}

/// Work-saving shortcuts, each leaving the image byte-identical (each has a
/// test proving it). Both are on by default; [`Skips::none`] turns them off
/// for measurement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Skips {
    /// No shadow ray towards a light with `N·L <= 0`: SPEC 6 sums only
    /// lights with `N·L > 0`, so the answer would be unused.
    pub back_facing_light: bool,
    /// With `ks = 0`: no specular computation and no reflection ray (both
    /// terms are exactly 0).
    pub zero_ks: bool,
}

impl Skips {
    /// Every shortcut on (the default).
    pub const fn all() -> Skips {
        Skips { back_facing_light: true, zero_ks: true }
    }

    /// Every shortcut off: the formula of SPEC 6 followed literally.
    pub const fn none() -> Skips {
        Skips { back_facing_light: false, zero_ks: false }
    }
}

impl Default for Skips {
    fn default() -> Skips {
        Skips::all()
    }
}

/// How to render an image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    /// Image width W in pixels.
    pub width: u32,
    /// Image height H in pixels.
    pub height: u32,
    /// Number of reflections followed (SPEC 6; default 5), at most
    /// [`MAX_DEPTH`]: a larger value is taken as that.
    pub depth: u32,
    /// Samples per pixel: 1 (default) is the pixel centre; more gives
    /// deterministic stratified anti-aliasing (see
    /// [`super::sample_offsets`]): the average of the clamped sample
    /// colours, then rounded. 0 is taken as 1.
    pub samples: u32,
    /// Where the z axis meets the screen (SPEC 5).
    pub screen: Screen,
    /// Work-saving shortcuts.
    pub skips: Skips,
    /// Adaptive anti-aliasing: with `samples > 1`, only the pixels flagged by
    /// [`super::refinement_mask`] on the 1-sample image get `samples`
    /// samples; the others keep their centre sample. Off by default.
    pub adaptive: bool,
}

impl RenderOptions {
    /// The ground truth for error measurements (`--reference`): 256
    /// stratified samples per pixel (a 16 x 16 grid), and no work-saving
    /// shortcut at all ([`Skips::none`]).
    ///
    /// Every field is spelt out rather than taken from the default, so that
    /// a new option must be decided on here.
    pub const fn reference(width: u32, height: u32, depth: u32) -> RenderOptions {
        RenderOptions {
            width,
            height,
            depth,
            samples: REFERENCE_SAMPLES,
            screen: Screen::Centered,
            skips: Skips::none(),
            adaptive: false,
        }
    }

    /// Whether adaptive anti-aliasing is on and has samples to spend.
    pub(crate) fn is_adaptive(&self) -> bool {
        self.adaptive && self.samples > 1
    }
}

impl RenderOptions {
    /// The options used where none are given: 800x600, 5 reflections, one
    /// ray a pixel, every shortcut on. The command line's and the session's
    /// defaults are these.
    pub const DEFAULT: RenderOptions = RenderOptions {
        width: 800,
        height: 600,
        depth: 5,
        samples: 1,
        screen: Screen::Centered,
        skips: Skips::all(),
        adaptive: false,
    };
}

impl Default for RenderOptions {
    fn default() -> RenderOptions {
        RenderOptions::DEFAULT
    }
}

/// A rectangle of an image's pixels: columns `left..right` and rows
/// `top..bottom`, the ends excluded (as pbrt's crop window).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Region {
    /// The first column.
    pub left: u32,
    /// The first row.
    pub top: u32,
    /// The column after the last.
    pub right: u32,
    /// The row after the last.
    pub bottom: u32,
}

impl Region {
    /// Every pixel of the image `options` describe.
    pub fn whole(options: &RenderOptions) -> Region {
        Region { left: 0, top: 0, right: options.width, bottom: options.height }
    }

    /// The rows `rows` of the image `options` describe, across its width;
    /// rows past its bottom are left out.
    pub fn rows(options: &RenderOptions, rows: std::ops::Range<u32>) -> Region {
        let bottom = rows.end.min(options.height);
        Region { left: 0, top: rows.start.min(bottom), right: options.width, bottom }
    }

    /// Its width in pixels.
    pub fn width(&self) -> u32 {
        self.right - self.left
    }

    /// Its height in pixels.
    pub fn height(&self) -> u32 {
        self.bottom - self.top
    }

    /// Whether it lies within the image `options` describe, its ends in order.
    pub fn fits(&self, options: &RenderOptions) -> bool {
        self.left <= self.right
            && self.top <= self.bottom
            && self.right <= options.width
            && self.bottom <= options.height
    }

    /// It and the pixels around it, `by` on each side, within the image
    /// `options` describe.
    pub(crate) fn grown(&self, by: u32, options: &RenderOptions) -> Region {
        Region {
            left: self.left.saturating_sub(by),
            top: self.top.saturating_sub(by),
            right: (self.right + by).min(options.width),
            bottom: (self.bottom + by).min(options.height),
        }
    }
}

/// Progress reporting and cancellation for one render.
#[derive(Clone, Copy, Default)]
pub struct RenderControl<'a> {
    /// Called from worker threads with the number of pixels just finished
    /// (a delta, once per tile).
    pub progress: Option<&'a (dyn Fn(u64) + Sync)>,
    /// When set, the render stops at the next tile and returns [`Cancelled`].
    pub cancel: Option<&'a AtomicBool>,
}

impl std::fmt::Debug for RenderControl<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RenderControl")
            .field("progress", &self.progress.is_some())
            .field("cancel", &self.cancel)
            .finish()
    }
}

/// The render was stopped through [`RenderControl::cancel`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cancelled;

impl std::fmt::Display for Cancelled {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("rendering cancelled")
    }
}

impl std::error::Error for Cancelled {}

/// What a render did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RenderStats {
    /// Rays traced, by kind.
    pub rays: RayCounts,
    /// Adaptive anti-aliasing: pixels rendered again with all samples.
    pub refined_pixels: u64,
    /// Wall-clock time of the render.
    pub elapsed: Duration,
}

impl std::ops::AddAssign for RenderStats {
    /// Sums two renders' counts and times (the frames of an animation).
    fn add_assign(&mut self, other: RenderStats) {
        self.rays += other.rays;
        self.refined_pixels += other.refined_pixels;
        self.elapsed += other.elapsed;
    }
}

impl RenderStats {
    /// All rays traced.
    pub fn total_rays(&self) -> u64 {
        self.rays.total()
    }
}
