//! Rendering (SPEC 5 and 6): rays from the camera, intersections, shading,
//! and the parallel loop over the image.
//!
//! ```no_run
//! # use rayrepl::render::{render, Prepared, RenderControl, RenderOptions};
//! # fn demo(scene: &rayrepl::scene::Scene) {
//! let prepared = Prepared::new(scene);
//! let options = RenderOptions { width: 800, height: 600, ..RenderOptions::default() };
//! let (image, stats) = render(scene, &prepared, &options, &RenderControl::default()).expect("not cancelled");
//! # }
//! ```
//!
//! For an animation, build the static part once and only the timed part
//! per frame:
//!
//! ```no_run
//! # use rayrepl::render::{render, Prepared, RenderControl, RenderOptions};
//! # fn demo(frames: &[rayrepl::scene::Scene], options: &RenderOptions) {
//! let first = Prepared::new(&frames[0]);
//! for scene in frames {
//!     let prepared = Prepared::with_static(first.static_part().clone(), &scene.timed_primitives);
//!     let (image, _) = render(scene, &prepared, options, &RenderControl::default()).expect("not cancelled");
//! }
//! # }
//! ```
//!
//! The image is cut into bands of [`TILE`] rows (one row for a pass over
//! some pixels only), each band into tiles of [`TILE`] columns; rayon
//! spreads the bands over its threads.
//! Every pixel is computed on its own, so the bytes do not depend on the
//! number of threads.
//!
//! With [`RenderOptions::adaptive`], anti-aliasing is spent only where a
//! pixel's average may differ from its centre's colour: a first pass renders
//! every pixel at its centre, keeping a [`Glimpse`] of what each ray met;
//! [`refinement_mask`] flags edges (neighbours that met different surfaces
//! or lights and differ by more than [`ADAPTIVE_THRESHOLD`] levels), bends
//! of the colour and objects too small to be seen by the centres (see
//! [`adaptive`]), and a second pass renders just those with all `samples`
//! samples. A third pass gives the refined pixels whose
//! samples still disagree most ([`escalation_mask`]) four times as many
//! more ([`escalation_offsets`]), within a budget of rays
//! ([`escalation_budget`]). A refined pixel
//! gets exactly the bytes of the uniform `samples` render, an escalated one
//! those of the `5 * samples` pattern; any other keeps the bytes of the
//! 1-sample render.

pub mod adaptive;
pub mod bvh;
pub mod camera;
pub mod geometry;
pub mod intersect;
pub mod reuse;
pub mod shade;
pub mod sweep;

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use glam::{DVec2, DVec3};
use image::RgbImage;
use rayon::prelude::*;

pub use adaptive::{
    ADAPTIVE_THRESHOLD, CURVATURE_THRESHOLD, ESCALATION_BUDGET, ESCALATION_SPREAD, FINE_DETAIL, Glimpse, SampleSpread,
    escalation_budget, escalation_mask, refinement_mask,
};
pub use camera::{PrimaryRays, Screen, escalation_offsets, sample_offsets};
pub use geometry::{Geometry, Intersector, Prepared, PreparedF32, SurfaceHit};
use intersect::PlaneShape;
pub use intersect::Ray;
pub use reuse::FrameReuse;
pub use shade::RayCounts;
use shade::{Lighting, Tracer};
use sweep::Sweep;

use crate::scene::Scene;

/// The most reflections a render follows (`depth`), the same for every entry
/// point: a path's colour is computed level by level, so its cost in time
/// and stack grows with the depth, and past a few hundred reflections no
/// scene changes by a visible level (each level is weighted by a further
/// `ks`; two facing perfect mirrors are the exception, and they show the
/// same colour at every depth beyond this).
pub const MAX_DEPTH: u32 = 1000;

/// Side of a square tile, in pixels; also the height of a band.
pub const TILE: u32 = 16;

/// Work-saving shortcuts, each leaving the image byte-identical (each has a
/// test proving it). All are on by default; [`Skips::none`] turns them off
/// for measurement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Skips {
    /// No shadow ray towards a light with `N·L <= 0`: SPEC 6 sums only
    /// lights with `N·L > 0`, so the answer would be unused.
    pub back_facing_light: bool,
    /// With `ks = 0`: no specular computation and no reflection ray (both
    /// terms are exactly 0).
    pub zero_ks: bool,
    /// No reflection ray once the product of `ks` along the path is below
    /// half an 8-bit level; paths of pixels whose byte that could change are
    /// resumed (see [`shade`] for the proof).
    pub negligible_reflection: bool,
}

impl Skips {
    /// Every shortcut on (the default).
    pub const fn all() -> Skips {
        Skips { back_facing_light: true, zero_ks: true, negligible_reflection: true }
    }

    /// Every shortcut off: the formula of SPEC 6 followed literally.
    pub const fn none() -> Skips {
        Skips { back_facing_light: false, zero_ks: false, negligible_reflection: false }
    }
}

impl Default for Skips {
    fn default() -> Skips {
        Skips::all()
    }
}

/// The float type of the intersection tests (BVH traversal and the
/// sphere, box and plane tests).
///
/// Only the intersection tests change precision: the hit distance comes
/// back as f64 and the hit point, normal, shading and secondary rays are
/// f64 in both modes (see [`PreparedF32`] for why). The f32 data is built
/// at the start of each render that asks for it, so the default f64 path
/// neither stores nor builds anything for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Precision {
    /// f64 throughout (the default, and the reference).
    #[default]
    F64,
    /// Intersection tests in f32, rays rounded to f32.
    F32,
}

/// How to render an image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    /// Image width W in pixels.
    pub width: u32,
    /// Image height H in pixels.
    pub height: u32,
    /// Number of reflections followed (SPEC 6; default 5).
    pub depth: u32,
    /// Samples per pixel: 1 (default) is the pixel centre; more gives
    /// deterministic stratified anti-aliasing (see [`sample_offsets`]): the
    /// average of the clamped sample colours, then rounded. 0 is taken as 1.
    pub samples: u32,
    /// Where the z axis meets the screen (SPEC 5).
    pub screen: Screen,
    /// Work-saving shortcuts.
    pub skips: Skips,
    /// Adaptive anti-aliasing: with `samples > 1`, only the pixels flagged by
    /// [`refinement_mask`] on the 1-sample image get `samples` samples; the
    /// others keep their centre sample. Off by default.
    pub adaptive: bool,
    /// The float type of the intersection tests (default f64).
    pub precision: Precision,
}

/// Samples per pixel of [`RenderOptions::reference`]: a 16 x 16 stratified grid.
pub const REFERENCE_SAMPLES: u32 = 256;

impl RenderOptions {
    /// The ground truth for error measurements (`--reference`): 256
    /// stratified samples per pixel (a 16 x 16 grid, [`sample_offsets`]), no
    /// work-saving shortcut at all ([`Skips::none`]), and f64 arithmetic
    /// throughout ([`Precision::F64`]).
    ///
    /// Every field is spelt out rather than taken from the default, so that
    /// a new option (say, adaptive sampling) must be decided on here.
    pub const fn reference(width: u32, height: u32, depth: u32) -> RenderOptions {
        RenderOptions {
            width,
            height,
            depth,
            samples: REFERENCE_SAMPLES,
            screen: Screen::Centered,
            skips: Skips::none(),
            adaptive: false,
            precision: Precision::F64,
        }
    }
}

impl Default for RenderOptions {
    fn default() -> RenderOptions {
        RenderOptions {
            width: 800,
            height: 600,
            depth: 5,
            samples: 1,
            screen: Screen::Centered,
            skips: Skips::all(),
            adaptive: false,
            precision: Precision::F64,
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
    /// Paths paused by the reflection-weight cutoff and then followed to
    /// their end because the cutoff could have changed their pixel's byte.
    pub resumed_paths: u64,
    /// Adaptive anti-aliasing: pixels rendered again with all samples.
    pub refined_pixels: u64,
    /// Adaptive anti-aliasing: pixels rendered a third time with
    /// [`escalation_offsets`].
    pub escalated_pixels: u64,
    /// Wall-clock time of the render.
    pub elapsed: Duration,
}

impl std::ops::AddAssign for RenderStats {
    /// Sums two renders' counts and times (the frames of an animation).
    fn add_assign(&mut self, other: RenderStats) {
        self.rays += other.rays;
        self.resumed_paths += other.resumed_paths;
        self.refined_pixels += other.refined_pixels;
        self.escalated_pixels += other.escalated_pixels;
        self.elapsed += other.elapsed;
    }
}

impl RenderStats {
    /// All rays traced.
    pub fn total_rays(&self) -> u64 {
        self.rays.total()
    }
}

/// Renders `scene` (whose geometry is `prepared`) into an image of
/// `options.width` x `options.height` pixels (SPEC 5, 6).
///
/// Uses the current rayon thread pool. Returns [`Cancelled`] if
/// `control.cancel` was set during the render.
pub fn render(
    scene: &Scene,
    prepared: &Prepared,
    options: &RenderOptions,
    control: &RenderControl,
) -> Result<(RgbImage, RenderStats), Cancelled> {
    render_with(scene, prepared, options, control, None)
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
    prepared: &Prepared,
    options: &RenderOptions,
    refined: &[bool],
    control: &RenderControl,
) -> Result<(RgbImage, RenderStats), Cancelled> {
    assert_eq!(refined.len(), options.width as usize * options.height as usize, "one flag per pixel");
    render_with(scene, prepared, options, control, Some(refined))
}

/// [`render`], with the pixels adaptive anti-aliasing refines `given` or,
/// when `None`, detected by [`refinement_mask`].
fn render_with(
    scene: &Scene,
    prepared: &Prepared,
    options: &RenderOptions,
    control: &RenderControl,
    given: Option<&[bool]>,
) -> Result<(RgbImage, RenderStats), Cancelled> {
    let start = Instant::now();
    let mut image = RgbImage::new(options.width, options.height);
    let blocking_planes = blocking_planes(scene, prepared);
    let adaptive = options.adaptive && options.samples > 1;
    let first_samples = if adaptive { 1 } else { options.samples };
    let f32_geometry = (options.precision == Precision::F32).then(|| PreparedF32::new(prepared));
    let mut job = Job::new(scene, prepared, options, control, &blocking_planes, first_samples);
    job.f32_geometry = f32_geometry.as_ref();
    let mut stats = RenderStats::default();
    if !adaptive {
        job.run(&mut image, Selection::default(), &mut stats)?;
    } else {
        let glimpses = job.glimpse_pass(&mut image, &mut stats)?;
        let first_rays = stats.total_rays();
        let detected;
        let refined = match given {
            Some(flags) => flags,
            None => {
                detected = refinement_mask(&image, &glimpses);
                &detected
            }
        };
        let mut spread = vec![SampleSpread::default(); refined.len()];
        let refine = Job { offsets: sample_offsets(options.samples), report_all: false, ..job };
        let selection = Selection { flags: Some(refined), spread: Some(&mut spread), ..Selection::default() };
        refine.run(&mut image, selection, &mut stats)?;
        let budget = escalation_budget(options.samples, first_rays, stats.total_rays());
        let escalated = escalation_mask(refined, &spread, budget);
        let escalate = Job { offsets: escalation_offsets(options.samples), ..refine };
        escalate.run(&mut image, Selection { flags: Some(&escalated), ..Selection::default() }, &mut stats)?;
        stats.refined_pixels = refined.iter().filter(|&&f| f).count() as u64;
        stats.escalated_pixels = escalated.iter().filter(|&&f| f).count() as u64;
    }
    stats.elapsed = start.elapsed();
    Ok((image, stats))
}

/// Adaptive anti-aliasing's first pass alone: every pixel of `scene`
/// rendered at its centre, and the [`Glimpse`] of each pixel's ray (row
/// major). [`refinement_mask`] of the two gives the pixels the second pass
/// renders again.
pub fn glimpse_pass(scene: &Scene, prepared: &Prepared, options: &RenderOptions) -> (RgbImage, Vec<Glimpse>) {
    let blocking_planes = blocking_planes(scene, prepared);
    let control = RenderControl::default();
    let job = Job::new(scene, prepared, options, &control, &blocking_planes, 1);
    let mut image = RgbImage::new(options.width, options.height);
    let glimpses = job.glimpse_pass(&mut image, &mut RenderStats::default()).expect("no cancel flag: never cancelled");
    (image, glimpses)
}

/// For each light of `scene`, the planes that can block rays towards it
/// ([`Prepared::planes_blocking`]).
fn blocking_planes(scene: &Scene, prepared: &Prepared) -> Vec<Vec<PlaneShape>> {
    scene.lights.iter().map(|l| prepared.planes_blocking(l.direction)).collect()
}

/// Everything the pixel loop needs, shared by all threads.
struct Job<'a> {
    rays: PrimaryRays,
    offsets: Vec<DVec2>,
    lighting: Lighting<'a>,
    prepared: &'a Prepared,
    /// With [`Precision::F32`]: the geometry the intersection tests use.
    f32_geometry: Option<&'a PreparedF32<'a>>,
    width: u32,
    control: &'a RenderControl<'a>,
    /// Whether progress counts every pixel of a tile, or (a second pass
    /// over pixels already counted) none.
    report_all: bool,
    /// Frame reuse: the frames' moving objects and the frame being
    /// rendered (see [`sweep`]).
    watch: Option<(&'a Sweep, u32)>,
}

/// The pixels one pass renders, and what it records of them besides their
/// bytes.
#[derive(Default)]
struct Selection<'a> {
    /// One flag per pixel, row major: render it or keep its bytes (all
    /// pixels when `None`).
    flags: Option<&'a [bool]>,
    /// With frame reuse: for each pixel, the last frame its bytes hold for,
    /// updated for the pixels rendered.
    valid_until: Option<&'a mut [u32]>,
    /// With adaptive anti-aliasing: for each pixel, how much its samples
    /// disagree, written for the pixels rendered.
    spread: Option<&'a mut [SampleSpread]>,
    /// With adaptive anti-aliasing's first pass (one sample per pixel): for
    /// each pixel, the [`Glimpse`] of its ray.
    glimpse: Option<&'a mut [Glimpse]>,
}

impl<'a> Job<'a> {
    /// The pass over every pixel of `scene` with `samples` samples each.
    fn new(
        scene: &'a Scene,
        prepared: &'a Prepared,
        options: &RenderOptions,
        control: &'a RenderControl<'a>,
        blocking_planes: &'a [Vec<PlaneShape>],
        samples: u32,
    ) -> Job<'a> {
        let rays = PrimaryRays::new(&scene.camera, options.width, options.height, options.screen);
        Job {
            rays,
            offsets: sample_offsets(samples),
            lighting: Lighting {
                ambient: scene.ambient,
                lights: &scene.lights,
                blocking_planes,
                depth: options.depth,
                skips: options.skips,
                pixel_angle: rays.pixel_angle(),
            },
            prepared,
            f32_geometry: None,
            width: options.width,
            control,
            report_all: true,
            watch: None,
        }
    }

    /// Renders every pixel into `buffer`, as [`Job::run`] does, and returns
    /// the [`Glimpse`] of each pixel's last ray.
    fn glimpse_pass(&self, buffer: &mut [u8], stats: &mut RenderStats) -> Result<Vec<Glimpse>, Cancelled> {
        let mut glimpses = vec![Glimpse::start(0.0); buffer.len() / 3];
        self.run(buffer, Selection { glimpse: Some(&mut glimpses), ..Selection::default() }, stats)?;
        Ok(glimpses)
    }

    /// Renders into `buffer` (its RGB bytes, row major), in parallel bands,
    /// the pixels `selection` flags (all of them without flags), records
    /// what it asks for, and adds the bands' counts to `stats`.
    fn run(&self, buffer: &mut [u8], selection: Selection, stats: &mut RenderStats) -> Result<(), Cancelled> {
        // A pass over some pixels only (adaptive refinement, frame reuse)
        // finds them bunched in a few places, along edges or around what
        // moves: bands of one row keep both threads busy to the end.
        let band_rows = if selection.flags.is_some() { 1 } else { TILE };
        let band_pixels = band_rows as usize * self.width as usize;
        if band_pixels == 0 {
            return Ok(());
        }
        let band_count = buffer.len().div_ceil(band_pixels * 3);
        let Selection { flags, valid_until, spread, glimpse } = selection;
        let mut flags = flags.map(|v| v.chunks(band_pixels));
        let mut valid_until = valid_until.map(|v| v.chunks_mut(band_pixels));
        let mut spread = spread.map(|v| v.chunks_mut(band_pixels));
        let mut glimpse = glimpse.map(|v| v.chunks_mut(band_pixels));
        let selections: Vec<Selection> = (0..band_count)
            .map(|_| Selection {
                flags: flags.as_mut().and_then(Iterator::next),
                valid_until: valid_until.as_mut().and_then(Iterator::next),
                spread: spread.as_mut().and_then(Iterator::next),
                glimpse: glimpse.as_mut().and_then(Iterator::next),
            })
            .collect();
        let bands: Vec<RenderStats> = buffer
            .par_chunks_mut(band_pixels * 3)
            .zip(selections)
            .enumerate()
            .map(|(band, (pixels, selection))| {
                let top = band as u32 * band_rows;
                // Frame reuse, glimpses and each precision have their own
                // build of the tracer, so that a default still image pays
                // nothing for them. Frame reuse never asks for glimpses.
                let (watch, glimpse) = (self.watch.is_some(), selection.glimpse.is_some());
                match (watch, glimpse, self.f32_geometry) {
                    (false, false, None) => self.band::<false, false, _>(self.prepared, top, pixels, selection),
                    (false, true, None) => self.band::<false, true, _>(self.prepared, top, pixels, selection),
                    (true, _, None) => self.band::<true, false, _>(self.prepared, top, pixels, selection),
                    (false, false, Some(g)) => self.band::<false, false, _>(g, top, pixels, selection),
                    (false, true, Some(g)) => self.band::<false, true, _>(g, top, pixels, selection),
                    (true, _, Some(g)) => self.band::<true, false, _>(g, top, pixels, selection),
                }
            })
            .collect::<Result<_, Cancelled>>()?;
        for band in bands {
            *stats += band;
        }
        Ok(())
    }

    /// Renders the band of rows starting at `top` into `pixels` (its RGB
    /// bytes), tile by tile, intersecting rays with `geometry`: the pixels
    /// `selection` (the band's share of it) flags, recording what it asks.
    fn band<const WATCH: bool, const GLIMPSE: bool, G: Intersector>(
        &self,
        geometry: &G,
        top: u32,
        pixels: &mut [u8],
        mut selection: Selection,
    ) -> Result<RenderStats, Cancelled> {
        let rows = (pixels.len() / (self.width as usize * 3)) as u32;
        let mut tracer = Tracer::<WATCH, GLIMPSE, G>::new(geometry, self.lighting, self.offsets.len());
        if let Some((sweep, frame)) = self.watch {
            tracer = tracer.watching(sweep, frame);
        }
        let last_frame = self.watch.map_or(0, |(sweep, _)| sweep.frames() - 1);
        let mut left = 0;
        while left < self.width {
            if self.control.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                return Err(Cancelled);
            }
            let right = (left + TILE).min(self.width);
            for row in 0..rows {
                for i in left..right {
                    let index = row as usize * self.width as usize + i as usize;
                    if selection.flags.is_some_and(|f| !f[index]) {
                        continue;
                    }
                    tracer.valid_until = last_frame;
                    let rgb = match selection.spread.as_deref_mut() {
                        Some(spread) => {
                            let rays_before = tracer.counts.total();
                            let (rgb, levels) = self.pixel::<_, _, _, true>(&mut tracer, i, top + row);
                            spread[index] = SampleSpread { levels, rays: tracer.counts.total() - rays_before };
                            rgb
                        }
                        None => self.pixel::<_, _, _, false>(&mut tracer, i, top + row).0,
                    };
                    pixels[index * 3..index * 3 + 3].copy_from_slice(&rgb);
                    if let Some(valid_until) = selection.valid_until.as_deref_mut() {
                        valid_until[index] = tracer.valid_until;
                    }
                    if let (true, Some(glimpse)) = (GLIMPSE, selection.glimpse.as_deref_mut()) {
                        glimpse[index] = tracer.glimpse;
                    }
                }
            }
            if let (Some(progress), true) = (self.control.progress, self.report_all) {
                progress(u64::from((right - left) * rows));
            }
            left = right;
        }
        // A band's time is not measured: the render's whole time is.
        Ok(RenderStats { rays: tracer.counts, resumed_paths: tracer.resumed, ..RenderStats::default() })
    }

    /// The bytes of pixel `(i, j)`: `round(255 * c)` of the average of its
    /// samples (SPEC 6), and with `SPREAD` the [`SampleSpread::levels`] of
    /// those samples (of their lower bounds; 0 without). When the
    /// reflection-weight cutoff leaves the byte undecided, the paused paths
    /// are resumed (see [`shade`]).
    #[inline]
    fn pixel<const WATCH: bool, const GLIMPSE: bool, G: Intersector, const SPREAD: bool>(
        &self,
        tracer: &mut Tracer<WATCH, GLIMPSE, G>,
        i: u32,
        j: u32,
    ) -> ([u8; 3], f64) {
        let mut lo = DVec3::ZERO;
        let mut hi = DVec3::ZERO;
        let mut squares = DVec3::ZERO;
        let mut open = false;
        for (slot, &offset) in self.offsets.iter().enumerate() {
            let b = tracer.trace(slot, &self.rays.ray(i, j, offset));
            lo += b.lo;
            hi += b.hi;
            if SPREAD {
                squares += b.lo * b.lo;
            }
            open |= b.lo != b.hi;
        }
        let mean = self.average(lo);
        let levels =
            if SPREAD { 255.0 * (self.average(squares) - mean * mean).max_element().max(0.0).sqrt() } else { 0.0 };
        let bytes = to_bytes(mean);
        if !open || bytes == to_bytes(self.average(hi)) {
            return (bytes, levels);
        }
        // The same sum in the same order as without the cutoff.
        let exact = (0..self.offsets.len()).fold(DVec3::ZERO, |sum, slot| sum + tracer.resume(slot));
        (to_bytes(self.average(exact)), levels)
    }

    /// The average of a sum of sample colours.
    #[inline]
    fn average(&self, sum: DVec3) -> DVec3 {
        if self.offsets.len() == 1 { sum } else { sum / self.offsets.len() as f64 }
    }
}

/// SPEC 6: the stored byte is `round(255 * c)`, no gamma. NaN gives 0.
#[inline]
fn to_bytes(c: DVec3) -> [u8; 3] {
    [to_byte(c.x), to_byte(c.y), to_byte(c.z)]
}

/// `round(255 * c)` for one channel, saturating to 0..=255 (NaN gives 0).
#[inline]
fn to_byte(c: f64) -> u8 {
    // `as u8` saturates and maps NaN to 0.
    (255.0 * c).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_round_half_away_from_zero_and_saturate() {
        assert_eq!(to_byte(0.0), 0);
        assert_eq!(to_byte(1.0), 255);
        assert_eq!(to_byte(0.5), 128); // 127.5 rounds up
        assert_eq!(to_byte(f64::NAN), 0);
        assert_eq!(to_byte(-3.0), 0);
        assert_eq!(to_byte(7.0), 255);
    }

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

    /// Every pixel with the sample pattern `offsets`.
    fn render_pattern(scene: &Scene, options: &RenderOptions, offsets: Vec<DVec2>) -> RgbImage {
        let prepared = Prepared::new(scene);
        let planes = blocking_planes(scene, &prepared);
        let control = RenderControl::default();
        let job = Job { offsets, ..Job::new(scene, &prepared, options, &control, &planes, 1) };
        let mut image = RgbImage::new(options.width, options.height);
        job.run(&mut image, Selection::default(), &mut RenderStats::default()).expect("not cancelled");
        image
    }

    /// Each pixel of an adaptive render holds the bytes of the last pass
    /// that rendered it: the centre, the `samples` grid, or the escalation
    /// pattern, and the escalated pixels are the most spread refined ones.
    #[test]
    fn adaptive_pixels_hold_the_bytes_of_their_last_pass() {
        let s = scene();
        let options = RenderOptions { width: 80, height: 60, samples: 16, adaptive: true, ..RenderOptions::default() };
        let (one, glimpses) = glimpse_pass(&s, &Prepared::new(&s), &options);
        assert!(one == render_pattern(&s, &options, sample_offsets(1)));
        let uniform = render_pattern(&s, &options, sample_offsets(16));
        let escalated = render_pattern(&s, &options, escalation_offsets(16));
        let (adaptive, stats) = render(&s, &Prepared::new(&s), &options, &RenderControl::default()).expect("runs");
        let refined = refinement_mask(&one, &glimpses);
        let (mut from_uniform, mut from_escalation) = (0, 0);
        for (k, &refine) in refined.iter().enumerate() {
            let (x, y) = ((k % 80) as u32, (k / 80) as u32);
            let got = adaptive.get_pixel(x, y);
            if !refine {
                assert_eq!(got, one.get_pixel(x, y), "pixel ({x}, {y})");
            } else if got == uniform.get_pixel(x, y) {
                from_uniform += 1;
            } else {
                assert_eq!(got, escalated.get_pixel(x, y), "pixel ({x}, {y})");
                from_escalation += 1;
            }
        }
        assert_eq!(stats.refined_pixels, from_uniform + from_escalation);
        assert!(0 < from_escalation && from_escalation <= stats.escalated_pixels, "{stats:?}");
    }
}
