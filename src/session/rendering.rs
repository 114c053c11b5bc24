//! Turning the session's scene into images with the session's settings:
//! the render options they give, and a render with progress and
//! cancellation around it, on the pipeline's one road to a picture.

use std::sync::atomic::AtomicBool;

use image::RgbImage;

use crate::pipeline::{PictureError, render_picture};
use crate::render::{Region, RenderControl, RenderOptions};
use crate::scene::Scene;
pub use crate::settings::RenderSettings;

/// Width and height of an image in pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Size {
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

/// Renders `scene` at `size` with the depth, samples and screen of
/// `settings`, on the one road every front-end takes
/// ([`render_picture`]). It stops when `cancel` is raised and reports
/// finished pixels to `progress`, for the progress bar.
pub(crate) fn render_image(
    scene: &Scene,
    size: Size,
    settings: &RenderSettings,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<RgbImage, PictureError> {
    let options = render_options(size, settings);
    let control = RenderControl { progress: Some(progress), cancel: Some(cancel) };
    render_picture(scene, &options, Region::whole(&options), &control).map(|rendered| rendered.image)
}

/// The renderer's options for an image of `size` with the session's settings.
pub(crate) fn render_options(size: Size, settings: &RenderSettings) -> RenderOptions {
    RenderSettings { width: size.width, height: size.height, ..*settings }.render_options()
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicUsize, Ordering};

    use super::*;

    fn empty_scene() -> Scene {
        crate::lang::Interpreter::new(0.0, crate::lang::Limits::default()).into_scene()
    }

    #[test]
    fn a_raised_cancel_flag_stops_the_render() {
        let scene = empty_scene();
        let size = Size { width: 64, height: 64 };
        let settings = RenderSettings::default();
        let cancel = AtomicBool::new(true);
        let result = render_image(&scene, size, &settings, &cancel, &|_| {});
        assert!(matches!(result, Err(PictureError::Cancelled)));
    }

    #[test]
    fn a_render_counts_every_pixel() {
        let scene = empty_scene();
        let size = Size { width: 40, height: 20 };
        let (cancel, pixels) = (AtomicBool::new(false), AtomicUsize::new(0));
        let count = |done: u64| {
            pixels.fetch_add(done as usize, Ordering::Relaxed);
        };
        let image = render_image(&scene, size, &RenderSettings::default(), &cancel, &count);
        assert_eq!(image.map(|i| i.dimensions()), Ok((40, 20)));
        assert_eq!(pixels.load(Ordering::Relaxed), 800);
    }
}
