//! Turning the session's scene into images: the one call into the renderer,
//! progress and cancellation around it, and writing image files.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::thread;
use std::time::{Duration, Instant};

use image::RgbImage;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::scene::Scene;

/// How the session renders: image size, reflections, antialiasing and time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderSettings {
    /// Image width in pixels for `:save` and `:anim`.
    pub width: u32,
    /// Image height in pixels for `:save` and `:anim`.
    pub height: u32,
    /// Number of reflections followed (SPEC 6).
    pub depth: u32,
    /// Rays per pixel (1 samples each pixel at its centre).
    pub samples: u32,
    /// The value of `time` for evaluation and renders (SPEC 3).
    pub time: f64,
}

impl Default for RenderSettings {
    fn default() -> RenderSettings {
        RenderSettings {
            width: 640,
            height: 480,
            depth: 5,
            samples: 1,
            time: 0.0,
        }
    }
}

/// Width and height of an image in pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Size {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl std::fmt::Display for Size {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}×{}", self.width, self.height)
    }
}

/// Why a render gave no image.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum RenderError {
    /// Ctrl-C was pressed.
    Cancelled,
    /// The renderer failed, for the reason given.
    #[allow(dead_code)] // TEMPORARY(lead): constructed once the renderer is wired in.
    Failed(String),
}

/// Renders `scene` at `size` with the depth and samples of `settings`.
///
/// This is the only place that calls the renderer. It polls `cancel` and
/// counts finished rows in `rows_done`, which drive cancellation and the
/// progress bar.
pub(crate) fn render_image(
    scene: &Scene,
    size: Size,
    settings: &RenderSettings,
    cancel: &AtomicBool,
    rows_done: &AtomicUsize,
) -> Result<RgbImage, RenderError> {
    // TEMPORARY(lead): the render branch is not merged yet. Replace this body
    // with the call to `crate::render::render(scene, ...)`, mapping
    // `settings.depth` and `settings.samples` to its options, `cancel` to its
    // cancellation flag and `rows_done` to its progress counter.
    let _ = (scene, settings);
    let image = RgbImage::new(size.width, size.height);
    for _row in 0..size.height {
        if cancel.load(Ordering::Relaxed) {
            return Err(RenderError::Cancelled);
        }
        rows_done.fetch_add(1, Ordering::Relaxed);
    }
    Ok(image)
}

/// Progress reporting for a long job: after half a second a bar appears on
/// standard error, fed from a counter the job increments.
pub(crate) struct Progress<'a> {
    /// Whether to show a bar at all (interactive sessions only).
    pub visible: bool,
    /// What the bar says ("rendering", "animating").
    pub label: &'a str,
    /// The count at which the job is done.
    pub total: usize,
}

/// How long a job runs before its progress bar appears.
const PROGRESS_DELAY: Duration = Duration::from_millis(500);
/// How often the bar is refreshed.
const PROGRESS_TICK: Duration = Duration::from_millis(50);

impl Progress<'_> {
    /// Runs `job`, which counts its progress in the counter it is given, and
    /// shows a bar if it lasts longer than half a second.
    pub(crate) fn run<R: Send>(&self, job: impl FnOnce(&AtomicUsize) -> R + Send) -> R {
        let counter = AtomicUsize::new(0);
        let finished = AtomicBool::new(false);
        thread::scope(|scope| {
            if self.visible {
                scope.spawn(|| self.watch(&counter, &finished));
            }
            let result = job(&counter);
            finished.store(true, Ordering::SeqCst);
            result
        })
    }

    fn watch(&self, counter: &AtomicUsize, finished: &AtomicBool) {
        let started = Instant::now();
        let mut bar: Option<ProgressBar> = None;
        while !finished.load(Ordering::SeqCst) {
            thread::sleep(PROGRESS_TICK);
            if bar.is_none() && started.elapsed() >= PROGRESS_DELAY {
                bar = Some(self.new_bar());
            }
            if let Some(bar) = &bar {
                bar.set_position(counter.load(Ordering::Relaxed) as u64);
            }
        }
        if let Some(bar) = bar {
            bar.finish_and_clear();
        }
    }

    fn new_bar(&self) -> ProgressBar {
        let bar =
            ProgressBar::with_draw_target(Some(self.total as u64), ProgressDrawTarget::stderr());
        if let Ok(style) =
            ProgressStyle::with_template("{msg} [{bar:30}] {percent}% ({elapsed}, Ctrl-C cancels)")
        {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(self.label.to_string());
        bar
    }
}

/// The image formats the session writes, chosen by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ImageFormat {
    /// `.png`
    Png,
    /// `.ppm` (binary P6)
    Ppm,
    /// `.gif`
    Gif,
}

impl ImageFormat {
    /// The format named by `path`'s extension, if it is one the session writes.
    pub(crate) fn of(path: &Path) -> Option<ImageFormat> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "png" => Some(ImageFormat::Png),
            "ppm" => Some(ImageFormat::Ppm),
            "gif" => Some(ImageFormat::Gif),
            _ => None,
        }
    }
}

/// Writes one image to `path`, in the format its extension names.
pub(crate) fn write_image(path: &Path, image: &RgbImage) -> Result<(), String> {
    // TEMPORARY(lead): switch to `crate::output::write_image` once the render
    // branch, which owns output.rs, is merged.
    let format = match ImageFormat::of(path) {
        Some(ImageFormat::Png) => image::ImageFormat::Png,
        Some(ImageFormat::Ppm) => image::ImageFormat::Pnm,
        Some(ImageFormat::Gif) => image::ImageFormat::Gif,
        None => {
            return Err(format!(
                "cannot tell the image format of {}",
                path.display()
            ));
        }
    };
    image
        .save_with_format(path, format)
        .map_err(|e| e.to_string())
}

/// Writes the frames of an animation: one animated GIF if `path` ends in
/// `.gif`, otherwise one numbered file per frame (`spin_01.png` ...).
/// Returns the files written.
pub(crate) fn write_animation(path: &Path, frames: &[RgbImage]) -> Result<Vec<PathBuf>, String> {
    if ImageFormat::of(path) == Some(ImageFormat::Gif) {
        write_gif(path, frames)?;
        return Ok(vec![path.to_path_buf()]);
    }
    let mut written = Vec::with_capacity(frames.len());
    for (index, frame) in frames.iter().enumerate() {
        let frame_path = frame_path(path, index + 1, frames.len());
        write_image(&frame_path, frame)?;
        written.push(frame_path);
    }
    Ok(written)
}

/// Delay between the frames of an animated GIF: ten frames a second.
const GIF_FRAME_DELAY_MS: u32 = 100;

fn write_gif(path: &Path, frames: &[RgbImage]) -> Result<(), String> {
    // TEMPORARY(lead): switch to `crate::output::write_gif` once the render
    // branch is merged.
    use image::codecs::gif::{GifEncoder, Repeat};
    use image::{Delay, DynamicImage, Frame};
    let file = std::fs::File::create(path).map_err(|e| e.to_string())?;
    let mut encoder = GifEncoder::new_with_speed(std::io::BufWriter::new(file), 10);
    encoder
        .set_repeat(Repeat::Infinite)
        .map_err(|e| e.to_string())?;
    let delay = Delay::from_numer_denom_ms(GIF_FRAME_DELAY_MS, 1);
    let frames = frames.iter().map(|frame| {
        Frame::from_parts(
            DynamicImage::ImageRgb8(frame.clone()).into_rgba8(),
            0,
            0,
            delay,
        )
    });
    encoder.encode_frames(frames).map_err(|e| e.to_string())
}

/// The name of frame `k` of `n` of an animation saved as `path`: the frame
/// number, zero-padded to the width of `n`, goes before the extension.
pub(crate) fn frame_path(path: &Path, k: usize, n: usize) -> PathBuf {
    let width = n.to_string().len();
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = match path.extension() {
        Some(extension) => format!("{stem}_{k:0width$}.{}", extension.to_string_lossy()),
        None => format!("{stem}_{k:0width$}"),
    };
    path.with_file_name(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_follow_the_extension() {
        assert_eq!(ImageFormat::of(Path::new("a.PNG")), Some(ImageFormat::Png));
        assert_eq!(
            ImageFormat::of(Path::new("dir/a.ppm")),
            Some(ImageFormat::Ppm)
        );
        assert_eq!(ImageFormat::of(Path::new("a.gif")), Some(ImageFormat::Gif));
        assert_eq!(ImageFormat::of(Path::new("a.jpg")), None);
        assert_eq!(ImageFormat::of(Path::new("a")), None);
    }

    #[test]
    fn frames_are_numbered_to_the_width_of_the_count() {
        assert_eq!(
            frame_path(Path::new("out/spin.png"), 3, 12),
            PathBuf::from("out/spin_03.png")
        );
        assert_eq!(
            frame_path(Path::new("spin.ppm"), 7, 9),
            PathBuf::from("spin_7.ppm")
        );
    }

    #[test]
    fn progress_runs_the_job_and_returns_its_result() {
        let progress = Progress {
            visible: false,
            label: "test",
            total: 1,
        };
        assert_eq!(
            progress.run(|counter| counter.fetch_add(1, Ordering::Relaxed) + 41),
            41
        );
    }
}
