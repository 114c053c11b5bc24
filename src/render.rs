//! Rendering (SPEC 5 and 6): rays from the camera, intersections, shading,
//! and the parallel loop over the image.
//!
//! ```no_run
//! # use rayrepl::render::{render, SceneGeometry, RenderControl, RenderOptions};
//! # fn demo(scene: &rayrepl::scene::Scene) {
//! let prepared = SceneGeometry::new(scene);
//! let options = RenderOptions { width: 800, height: 600, ..RenderOptions::default() };
//! let (image, stats) = render(scene, &prepared, &options, &RenderControl::default()).expect("not cancelled");
//! # }
//! ```
//!
//! For an animation, build the static part once and only the timed part
//! per frame:
//!
//! ```no_run
//! # use rayrepl::render::{render, SceneGeometry, RenderControl, RenderOptions};
//! # fn demo(frames: &[rayrepl::scene::Scene], options: &RenderOptions) {
//! let first = SceneGeometry::new(&frames[0]);
//! for scene in frames {
//!     let prepared = SceneGeometry::with_static(first.static_part().clone(), &scene.timed_primitives);
//!     let (image, _) = render(scene, &prepared, options, &RenderControl::default()).expect("not cancelled");
//! }
//! # }
//! ```
//!
//! The modules follow a ray: [`camera`] makes the primary rays, [`geometry`]
//! (over [`bvh`] and [`intersect`]) finds what they meet, [`shade`] computes
//! a path's colour by SPEC 6, and `pixels` turns the samples into the bytes
//! of the image, in parallel. [`adaptive`] (anti-aliasing only where it
//! shows) and [`reuse`] (animation frames that copy what did not change)
//! watch the paths through [`shade`]'s observer, and so does [`pixel_paths`],
//! which records why a pixel has its colour.

pub mod adaptive;
pub mod bvh;
pub mod camera;
pub mod geometry;
pub mod intersect;
pub mod isa;
pub mod memory;
pub mod moving_bounds;
mod options;
pub mod pixel_paths;
mod pixels;
pub mod reuse;
pub mod shade;

use image::RgbImage;

pub use adaptive::{ADAPTIVE_THRESHOLD, CURVATURE_THRESHOLD, FINE_DETAIL, Glimpse, glimpse_pass, refinement_mask};
pub use camera::{PrimaryRays, Screen, sample_offsets};
pub use geometry::{Geometry, SceneGeometry, SurfaceHit};
pub use intersect::Ray;
pub use memory::{OutOfMemory, reserve_for};
pub use options::{
    Cancelled, MAX_DEPTH, REFERENCE_SAMPLES, RayCounts, Region, RenderControl, RenderOptions, RenderStats, Skips,
};
pub use pixel_paths::{Explainer, PixelPaths};
pub use pixels::TILE;
pub use reuse::FrameReuse;

use crate::clock::Stopwatch;
use crate::scene::Scene;

/// Renders `scene` (whose geometry is `prepared`) into an image of
/// `options.width` x `options.height` pixels (SPEC 5, 6).
///
/// Uses the current rayon thread pool. Returns [`Cancelled`] if
/// `control.cancel` was set during the render.
pub fn render(
    scene: &Scene,
    prepared: &SceneGeometry,
    options: &RenderOptions,
    control: &RenderControl,
) -> Result<(RgbImage, RenderStats), Cancelled> {
    render_with(scene, prepared, options, Region::whole(options), control, None)
}

/// The pixels of `region` of the image [`render`] makes with `options`,
/// the same bytes, at any number of samples and with adaptive
/// anti-aliasing too (whose choice of a pixel looks at its neighbours: the
/// region's first pass reaches one pixel beyond its edges). Every pixel is
/// computed on its own (`pixels`), so regions put together are the whole
/// image's bytes: for a front-end that splits one image over workers of
/// its own (the browser page's bands) or over machines (tiles).
///
/// # Panics
///
/// If `region` does not lie within the image ([`Region::fits`]).
pub fn render_region(
    scene: &Scene,
    prepared: &SceneGeometry,
    options: &RenderOptions,
    region: Region,
    control: &RenderControl,
) -> Result<(RgbImage, RenderStats), Cancelled> {
    assert!(region.fits(options), "{region:?} lies outside the {}x{} image", options.width, options.height);
    render_with(scene, prepared, options, region, control, None)
}

/// [`render`] with adaptive anti-aliasing (`options.adaptive`, more than one
/// sample) told which pixels to refine: `refined` (one flag per pixel, row
/// major) replaces [`refinement_mask`]; the passes and their costs are
/// otherwise the same. Benchmarks give it the pixels that an ideal
/// detector, one that knew the reference image, would pick, to see how far
/// a better detector alone could go.
///
/// # Panics
///
/// If `refined` does not hold one flag per pixel.
pub fn render_refining(
    scene: &Scene,
    prepared: &SceneGeometry,
    options: &RenderOptions,
    refined: &[bool],
    control: &RenderControl,
) -> Result<(RgbImage, RenderStats), Cancelled> {
    assert_eq!(refined.len(), options.width as usize * options.height as usize, "one flag per pixel");
    render_with(scene, prepared, options, Region::whole(options), control, Some(refined))
}

/// [`render_region`], with the pixels adaptive anti-aliasing refines
/// `given` (one flag per pixel of `region`) or, when `None`, detected by
/// [`refinement_mask`].
fn render_with(
    scene: &Scene,
    prepared: &SceneGeometry,
    options: &RenderOptions,
    region: Region,
    control: &RenderControl,
    given: Option<&[bool]>,
) -> Result<(RgbImage, RenderStats), Cancelled> {
    let start = Stopwatch::start();
    let mut image = RgbImage::new(region.width(), region.height());
    let mut stats = if options.is_adaptive() {
        adaptive::render_two_passes(scene, prepared, options, region, control, given, &mut image)?
    } else {
        let pass = pixels::Pass::new(scene, prepared, options, control, options.samples).over(region);
        RenderStats { rays: pass.run_plain(&mut image, None)?, ..RenderStats::default() }
    };
    stats.elapsed = start.elapsed();
    Ok((image, stats))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small scene in the language: spheres against a black sky, a floor.
    fn scene() -> Scene {
        let text = "camera distance 10 angle 0.9 end\n\
                    ambient 0.2\n\
                    light vector 0.5, 1, 0.6 intensity 0.8 end\n\
                    put sphere center 0, 0, 0 radius 2 kd 0.8 ks 0.3 phong 20 color 250, 200, 40 end\n\
                    put sphere center 2.5, 1, 1 radius 0.6 kd 0.8 ks 0 phong 1 color 40, 90, 250 end\n\
                    put plane rotation 0, 0, 0 shift -2 kd 0.6 ks 0.4 phong 10 color 150, 150, 150 end\n";
        let mut sources = crate::lang::source::SourceMap::new();
        let id = sources.add("test.ray".to_owned(), text.to_owned(), 0);
        let program = crate::lang::parse_file(id, text).expect("parses");
        let mut interpreter = crate::lang::Interpreter::new(0.0, crate::lang::Limits::default());
        interpreter.run(&program).expect("runs");
        interpreter.into_scene()
    }

    /// Bands of rows put together are the bytes of the whole image,
    /// wherever their edges fall; rows past the bottom are left out.
    #[test]
    fn bands_put_together_are_the_whole_image() {
        let s = scene();
        let prepared = SceneGeometry::new(&s);
        let options = RenderOptions { width: 40, height: 30, samples: 4, ..RenderOptions::default() };
        let control = RenderControl::default();
        let (whole, _) = render(&s, &prepared, &options, &control).expect("runs");
        let mut bands = Vec::new();
        for rows in [0..7, 7..23, 23..40] {
            let band = Region::rows(&options, rows);
            bands.extend_from_slice(&render_region(&s, &prepared, &options, band, &control).expect("runs").0);
        }
        assert!(bands == whole.into_raw());
    }

    /// Every region of the image holds the whole image's bytes there, with
    /// one sample, many, and adaptive anti-aliasing (whose refined pixels
    /// depend on their neighbours beyond the region's edges), and counts the
    /// refined pixels inside it only.
    #[test]
    fn a_region_holds_the_whole_images_bytes_in_every_sampling_mode() {
        let s = scene();
        let prepared = SceneGeometry::new(&s);
        let control = RenderControl::default();
        let one = RenderOptions { width: 48, height: 36, ..RenderOptions::default() };
        let modes = [one, RenderOptions { samples: 9, ..one }, RenderOptions { samples: 9, adaptive: true, ..one }];
        for options in modes {
            let (whole, whole_stats) = render(&s, &prepared, &options, &control).expect("runs");
            let mut refined = 0;
            // Four tiles of unequal sizes that cover the image, then a
            // pixel, an empty region and a column at the right edge.
            let tiles = [(0, 0, 17, 20), (17, 0, 48, 20), (0, 20, 30, 36), (30, 20, 48, 36)];
            for (left, top, right, bottom) in tiles.into_iter().chain([(5, 7, 6, 8), (9, 9, 9, 9), (47, 0, 48, 36)]) {
                let region = Region { left, top, right, bottom };
                let (tile, stats) = render_region(&s, &prepared, &options, region, &control).expect("runs");
                assert_eq!((tile.width(), tile.height()), (right - left, bottom - top));
                for (x, y, pixel) in tile.enumerate_pixels() {
                    assert_eq!(pixel, whole.get_pixel(left + x, top + y), "{options:?} {region:?} ({x}, {y})");
                }
                if tiles.contains(&(left, top, right, bottom)) {
                    refined += stats.refined_pixels;
                }
            }
            assert_eq!(refined, whole_stats.refined_pixels, "{options:?}");
        }
    }

    /// Each pixel of an adaptive render holds the bytes of the pass that
    /// last rendered it: the centre, or the uniform `samples` grid.
    #[test]
    fn adaptive_pixels_hold_the_bytes_of_their_last_pass() {
        let s = scene();
        let prepared = SceneGeometry::new(&s);
        let adaptive = RenderOptions { width: 80, height: 60, samples: 16, adaptive: true, ..RenderOptions::default() };
        let uniform = RenderOptions { adaptive: false, ..adaptive };
        let control = RenderControl::default();
        let (one, glimpses) = glimpse_pass(&s, &prepared, &adaptive);
        let (one_sample, _) = render(&s, &prepared, &RenderOptions { samples: 1, ..uniform }, &control).expect("runs");
        assert!(one == one_sample);
        let (sixteen, _) = render(&s, &prepared, &uniform, &control).expect("runs");
        let (image, stats) = render(&s, &prepared, &adaptive, &control).expect("runs");
        let refined = refinement_mask(&one, &glimpses);
        for (k, &refine) in refined.iter().enumerate() {
            let (x, y) = ((k % 80) as u32, (k / 80) as u32);
            let expected = if refine { sixteen.get_pixel(x, y) } else { one.get_pixel(x, y) };
            assert_eq!(image.get_pixel(x, y), expected, "pixel ({x}, {y})");
        }
        assert_eq!(stats.refined_pixels, refined.iter().filter(|&&f| f).count() as u64);
        assert!(0 < stats.refined_pixels && stats.refined_pixels < 80 * 60, "{stats:?}");
    }
}
