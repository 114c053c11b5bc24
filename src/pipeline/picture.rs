//! A scene's picture, or a rectangle of it, as every front-end makes a
//! still one: the memory it needs checked first, its geometry built, its
//! pixels rendered, stopped by the control's cancel flag.
//!
//! A front-end that splits one picture over workers (the browser page's
//! bands) or machines (tiles) asks for a [`Region`] of it: the pixels are
//! the whole picture's bytes there, at any number of samples and with
//! adaptive anti-aliasing ([`crate::render::render_region`]).

use std::time::Duration;

use image::RgbImage;

use crate::clock::Stopwatch;
use crate::render::{
    Cancelled, OutOfMemory, Region, RenderControl, RenderOptions, RenderStats, SceneGeometry, render_region,
    reserve_for,
};
use crate::scene::Scene;

/// A picture rendered, with what was counted and the geometry it was
/// rendered with (for the statistics and a pixel's explanation).
pub struct Rendered {
    /// The pixels of the region asked for.
    pub image: RgbImage,
    /// Rays traced, pixels refined, time taken.
    pub stats: RenderStats,
    /// The scene's geometry, as built for the render.
    pub geometry: SceneGeometry,
    /// The time building the geometry took.
    pub built: Duration,
}

/// Why a picture was not rendered.
#[derive(Debug, Clone, PartialEq)]
pub enum PictureError {
    /// The memory to build the geometry and hold the pixels cannot be had.
    OutOfMemory(OutOfMemory),
    /// The control's cancel flag was raised.
    Cancelled,
}

impl From<Cancelled> for PictureError {
    fn from(Cancelled: Cancelled) -> PictureError {
        PictureError::Cancelled
    }
}

impl std::fmt::Display for PictureError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PictureError::OutOfMemory(error) => error.fmt(f),
            PictureError::Cancelled => f.write_str("the render was stopped"),
        }
    }
}

impl std::error::Error for PictureError {}

/// Renders `region` of the picture of `scene` that `options` describe
/// (`Region::whole(options)` for all of it), once the memory it needs is
/// known to be there.
///
/// # Panics
///
/// If `region` does not lie within the picture ([`Region::fits`]).
pub fn render_picture(
    scene: &Scene,
    options: &RenderOptions,
    region: Region,
    control: &RenderControl,
) -> Result<Rendered, PictureError> {
    let held = RenderOptions { width: region.width(), height: region.height(), ..*options };
    reserve_for(scene, &held).map_err(PictureError::OutOfMemory)?;
    let start = Stopwatch::start();
    let geometry = SceneGeometry::new(scene);
    let built = start.elapsed();
    let (image, stats) = render_region(scene, &geometry, options, region, control)?;
    Ok(Rendered { image, stats, geometry, built })
}
