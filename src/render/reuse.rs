//! Frame reuse: rendering a run of animation frames in order, tracing in
//! each frame only the pixels that a moving object may have changed, and
//! copying the others from the previous frame, byte for byte.
//!
//! It applies when the camera, the ambient light, the lights and the planes
//! are the same in every frame, and only bounded objects (spheres, boxes)
//! depend on `time` ([`FrameReuse::applies`]). A traced pixel records the
//! last frame its bytes hold for ([`super::moving_bounds`] says why that is exact);
//! it is traced again in the frame after that.
//!
//! ```no_run
//! # use rayrepl::render::{FrameReuse, SceneGeometry, RenderControl, RenderOptions};
//! # fn demo(frames: &[(rayrepl::scene::Scene, SceneGeometry)], options: &RenderOptions) {
//! let bounds: Vec<_> = frames.iter().map(|(scene, prepared)| prepared.bounds_of(&scene.timed_primitives)).collect();
//! let mut reuse = FrameReuse::new(bounds.iter().map(Vec::as_slice), options);
//! for (scene, prepared) in frames {
//!     let (image, _) = reuse.render(scene, prepared, &RenderControl::default()).expect("not cancelled");
//! }
//! # }
//! ```

use image::RgbImage;

use super::geometry::{Blocker, SceneGeometry, SurfaceHit};
use super::intersect::{Aabb, Ray};
use super::moving_bounds::MovingBounds;
use super::options::{Cancelled, RenderControl, RenderOptions, RenderStats};
use super::pixels::Pass;
use super::shade::PathObserver;
use crate::clock::Stopwatch;
use crate::scene::{Scene, Shape};

/// The state carried from one frame of a run to the next.
#[derive(Debug)]
pub struct FrameReuse {
    moving_bounds: MovingBounds,
    options: RenderOptions,
    /// The frame [`FrameReuse::render`] renders next (0 for the first).
    next: u32,
    /// The previous frame's image.
    image: Option<RgbImage>,
    /// For each pixel, the last frame whose bytes it holds.
    valid_until: Vec<u32>,
    /// Whether frames are still traced with the bookkeeping (see
    /// [`GIVE_UP_SHARE`]); once off, each frame is rendered in full.
    watching: bool,
}

/// When a frame after the first has to trace more than this share of its
/// pixels again, the rest of the run is rendered frame by frame: the
/// bookkeeping (a query per ray) costs about as much as tracing, so it
/// only pays when most pixels are copied. Measured on
/// `scenarios/spiral.ray`, whose 250 spheres all move: about half the
/// pixels traced again per frame, and no time saved.
pub const GIVE_UP_SHARE: f64 = 0.5;

impl FrameReuse {
    /// Whether frame reuse can render the frames of an animation whose
    /// first frame is `scene` (prepared as `prepared`) with `options`:
    /// nothing but bounded objects depends on `time`, and no adaptive
    /// anti-aliasing (whose choice of pixels looks at their neighbours).
    /// Each later frame must also pass [`FrameReuse::holds_for`].
    pub fn applies(scene: &Scene, options: &RenderOptions) -> bool {
        !options.is_adaptive() && FrameReuse::holds_for(scene)
    }

    /// Whether one frame keeps the camera, ambient light, lights and planes
    /// fixed.
    pub fn holds_for(scene: &Scene) -> bool {
        let time_use = scene.time_use;
        let timed_plane = scene.timed_primitives.iter().any(|p| matches!(p.shape, Shape::Plane { .. }));
        !(time_use.camera || time_use.ambient || time_use.lights || timed_plane)
    }

    /// Frame reuse over frames given, in order, by the boxes of their
    /// moving objects ([`SceneGeometry::bounds_of`]), rendered with
    /// `options`.
    pub fn new<'a>(frames: impl IntoIterator<Item = &'a [Aabb]>, options: &RenderOptions) -> FrameReuse {
        FrameReuse {
            moving_bounds: MovingBounds::new(frames),
            options: *options,
            next: 0,
            image: None,
            valid_until: Vec::new(),
            watching: true,
        }
    }

    /// Renders the next frame of the run: `scene`, whose geometry is
    /// `prepared` (the frame given at that place to [`FrameReuse::new`]).
    /// The image is byte-identical to [`super::render`]'s.
    pub fn render(
        &mut self,
        scene: &Scene,
        prepared: &SceneGeometry,
        control: &RenderControl,
    ) -> Result<(RgbImage, RenderStats), Cancelled> {
        let frame = self.next;
        assert!(frame < self.moving_bounds.frames(), "more frames rendered than given to FrameReuse::new");
        self.next += 1;
        if !self.watching {
            return super::render(scene, prepared, &self.options, control);
        }
        let pixels = self.options.width as usize * self.options.height as usize;
        let mut image = match self.image.take() {
            Some(image) => image,
            None => {
                self.valid_until = vec![0; pixels];
                RgbImage::new(self.options.width, self.options.height)
            }
        };
        let stale: Vec<bool> =
            if frame == 0 { vec![true; pixels] } else { self.valid_until.iter().map(|&last| last < frame).collect() };
        let traced = stale.iter().filter(|&&s| s).count();
        if frame > 0 && traced as f64 > GIVE_UP_SHARE * pixels as f64 {
            self.watching = false;
            return super::render(scene, prepared, &self.options, control);
        }
        let start = Stopwatch::start();
        let last_frame = self.moving_bounds.frames() - 1;
        let watch = ValidityWatch { moving_bounds: &self.moving_bounds, frame, valid_until: last_frame };
        let mut watches = vec![watch; pixels];
        let pass = Pass::new(scene, prepared, &self.options, control, self.options.samples);
        let done = pass.run(&mut image, Some(&stale), &mut watches);
        // A cancelled frame leaves `image` half new: start again from scratch.
        if done.is_err() {
            self.next -= 1;
        }
        let mut stats = RenderStats { rays: done?, ..RenderStats::default() };
        for ((valid_until, watch), traced) in self.valid_until.iter_mut().zip(&watches).zip(&stale) {
            if *traced {
                *valid_until = watch.valid_until;
            }
        }
        stats.elapsed = start.elapsed();
        self.image = Some(image.clone());
        Ok((image, stats))
    }
}

/// Frame reuse's observer of one pixel's paths: works out the last frame
/// for which they give the same colours (see [`super::moving_bounds`]).
#[derive(Debug, Clone, Copy)]
struct ValidityWatch<'a> {
    /// The frames' moving objects.
    moving_bounds: &'a MovingBounds,
    /// The frame being traced.
    frame: u32,
    /// The last frame for which the paths seen so far hold.
    valid_until: u32,
}

impl ValidityWatch<'_> {
    /// Lowers [`ValidityWatch::valid_until`] to the frame before the first
    /// one whose moving objects could change what `ray` found in `[0, t]`.
    /// A hit on a moving object (`timed`) holds for this frame only.
    #[inline]
    fn watch(&mut self, ray: &Ray, t: f64, timed: bool) {
        if self.valid_until <= self.frame {
            return;
        }
        self.valid_until = if timed {
            self.frame
        } else {
            self.valid_until.min(self.moving_bounds.first_meeting(ray, t, self.frame) - 1)
        };
    }
}

impl PathObserver for ValidityWatch<'_> {
    const WANTS_BLOCKER: bool = true;

    #[inline(always)]
    fn hit(&mut self, ray: &Ray, hit: Option<&SurfaceHit>, _weight: f64) {
        self.watch(ray, hit.map_or(f64::INFINITY, |h| h.t), hit.is_some_and(|h| h.timed));
    }

    /// A shadow ray blocked by the static part stays blocked; one blocked
    /// only by a moving object holds for this frame only; an unblocked one
    /// until a moving object may cross it.
    #[inline(always)]
    fn shadow(&mut self, ray: &Ray, blocker: Blocker) {
        match blocker {
            Blocker::Static => {}
            Blocker::Timed => self.watch(ray, f64::INFINITY, true),
            Blocker::Nothing => self.watch(ray, f64::INFINITY, false),
        }
    }
}
