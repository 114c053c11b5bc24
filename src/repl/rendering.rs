//! Turning the session's scene into images: the one call into the renderer,
//! progress and cancellation around it, and writing image files.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use image::RgbImage;

use crate::output::{GIF_FRAME_DELAY_MS, write_gif};
use crate::render::{Cancelled, Prepared, RenderControl, RenderOptions, render};
use crate::scene::Scene;
pub use crate::settings::RenderSettings;

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
}

/// Renders `scene`, whose geometry is `prepared`, at `size` with the depth,
/// samples and screen of `settings`.
///
/// This is the only place that calls the renderer. It stops when `cancel`
/// is raised and reports finished pixels to `progress`, for the progress bar.
pub(crate) fn render_image(
    scene: &Scene,
    prepared: &Prepared,
    size: Size,
    settings: &RenderSettings,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<RgbImage, RenderError> {
    let options = render_options(size, settings);
    let control = RenderControl { progress: Some(progress), cancel: Some(cancel) };
    match render(scene, prepared, &options, &control) {
        Ok((image, _stats)) => Ok(image),
        Err(Cancelled) => Err(RenderError::Cancelled),
    }
}

/// The renderer's options for an image of `size` with the session's settings.
pub(crate) fn render_options(size: Size, settings: &RenderSettings) -> RenderOptions {
    RenderSettings { width: size.width, height: size.height, ..*settings }.render_options()
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
    let written = match ImageFormat::of(path) {
        Some(ImageFormat::Gif) => write_gif(path, std::slice::from_ref(image), GIF_FRAME_DELAY_MS),
        _ => crate::output::write_image(path, image),
    };
    written.map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicUsize, Ordering};

    use super::*;

    #[test]
    fn formats_follow_the_extension() {
        assert_eq!(ImageFormat::of(Path::new("a.PNG")), Some(ImageFormat::Png));
        assert_eq!(ImageFormat::of(Path::new("dir/a.ppm")), Some(ImageFormat::Ppm));
        assert_eq!(ImageFormat::of(Path::new("a.gif")), Some(ImageFormat::Gif));
        assert_eq!(ImageFormat::of(Path::new("a.jpg")), None);
        assert_eq!(ImageFormat::of(Path::new("a")), None);
    }

    fn empty_scene() -> Scene {
        crate::lang::Interpreter::new(0.0, crate::lang::Limits::default()).into_scene()
    }

    #[test]
    fn a_raised_cancel_flag_stops_the_render() {
        let scene = empty_scene();
        let size = Size { width: 64, height: 64 };
        let settings = RenderSettings::default();
        let cancel = AtomicBool::new(true);
        let result = render_image(&scene, &Prepared::new(&scene), size, &settings, &cancel, &|_| {});
        assert_eq!(result, Err(RenderError::Cancelled));
    }

    #[test]
    fn a_render_counts_every_pixel() {
        let scene = empty_scene();
        let size = Size { width: 40, height: 20 };
        let (cancel, pixels) = (AtomicBool::new(false), AtomicUsize::new(0));
        let count = |done: u64| {
            pixels.fetch_add(done as usize, Ordering::Relaxed);
        };
        let image = render_image(&scene, &Prepared::new(&scene), size, &RenderSettings::default(), &cancel, &count);
        assert_eq!(image.map(|i| i.dimensions()), Ok((40, 20)));
        assert_eq!(pixels.load(Ordering::Relaxed), 800);
    }
}
