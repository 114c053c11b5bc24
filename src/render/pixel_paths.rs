//! Why a pixel has its colour: the paths traced for it, recorded by an
//! observer of the tracer while it renders that pixel the way a render
//! does. The recorded colours are the ones the tracer computed, so the
//! explained bytes are the rendered bytes.
//!
//! [`Explainer`] prepares a scene once (and, for adaptive anti-aliasing,
//! finds which pixels get all the samples); [`Explainer::explain`] then
//! traces one pixel with a [`PathRecorder`] watching.
//!
//! What is kept is bounded, whatever the samples and the depth: the paths
//! of the first [`SAMPLES_RECORDED`] samples, each down to its first
//! [`LEVELS_RECORDED`] rays. Every sample is still traced in full and
//! counts in the colour; of the others only their colours' sum is kept,
//! and of the deeper rays only their number. (4096 samples between two
//! mirrors 1000 reflections deep would otherwise be four million levels,
//! gigabytes, and more than anyone reads.)

use glam::DVec3;

use super::adaptive::{glimpse_pass, refinement_mask};
use super::geometry::{SceneGeometry, SurfaceHit};
use super::intersect::Ray;
use super::options::{RenderControl, RenderOptions};
use super::pixels::Pass;
use super::shade::{LightTerm, PathObserver};
use crate::scene::{Material, Scene};

/// The paths of at most this many samples of a pixel are recorded, the
/// first ones traced; the others count in its colour, unrecorded.
pub const SAMPLES_RECORDED: usize = 8;

/// At most this many rays of a path are recorded, the camera ray and the
/// first reflections; the deeper ones are traced and counted, unrecorded.
pub const LEVELS_RECORDED: usize = 16;

/// Everything traced for one pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct PixelPaths {
    /// The pixel, from the left and from the top.
    pub pixel: (u32, u32),
    /// The bytes written to the image: `round(255 * c)` of the average
    /// of the samples' colours (SPEC 6).
    pub rgb: [u8; 3],
    /// The path of each of the first [`SAMPLES_RECORDED`] samples, in the
    /// order traced.
    pub samples: Vec<SamplePath>,
    /// How many samples were traced, recorded or not.
    pub traced: usize,
    /// The average of every sample's colour, which `rgb` rounds: summed in
    /// the order traced, as the render sums them.
    pub colour: DVec3,
    /// The average colour of the samples whose paths were not recorded
    /// (black when all were).
    pub unrecorded_colour: DVec3,
}

impl PixelPaths {
    /// How many samples were traced but not recorded.
    pub fn unrecorded(&self) -> usize {
        self.traced - self.samples.len()
    }
}

/// The path of one camera ray, down its mirror reflections.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SamplePath {
    /// What each of the first [`LEVELS_RECORDED`] rays met, the camera ray
    /// first.
    pub levels: Vec<Level>,
    /// How many rays were traced below the recorded ones (reflections
    /// followed but not recorded).
    pub unrecorded_levels: usize,
}

impl SamplePath {
    /// The sample's colour, each component in [0, 1]: its first level's,
    /// black if the camera ray met nothing.
    pub fn colour(&self) -> DVec3 {
        self.levels.first().map_or(DVec3::ZERO, |level| level.colour)
    }
}

/// One ray of a path and what it met.
#[derive(Debug, Clone, PartialEq)]
pub struct Level {
    /// The product of the `ks` above this ray: its weight in the pixel.
    pub weight: f64,
    /// The surface met; `None` when the ray met nothing (black).
    pub surface: Option<Surface>,
    /// The ambient part `kd*Ia*C`.
    pub ambient: DVec3,
    /// What each light adds, in the scene's order.
    pub lights: Vec<LightPart>,
    /// The colour of this level, clamped: the local parts plus `ks` times
    /// the colour of the next level.
    pub colour: DVec3,
}

/// A surface point met by a ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    /// The primitive's place in [`Scene::all_primitives`].
    pub primitive: usize,
    /// The point hit, in the scene's coordinates.
    pub point: DVec3,
    /// The unit normal there, facing the ray.
    pub normal: DVec3,
    /// The primitive's texture.
    pub material: Material,
}

/// What one light adds at a surface point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightPart {
    /// The light is behind the surface (`N·L <= 0`).
    FacingAway,
    /// Something blocks the way to the light: the nearest primitive on the
    /// shadow ray (its place in [`Scene::all_primitives`]).
    Shadowed(Option<usize>),
    /// The light adds its diffuse and specular parts.
    Lit {
        /// `kd*(N·L)*I*C`.
        diffuse: DVec3,
        /// `ks*max(0, N·H)^n*I*C`.
        specular: DVec3,
    },
}

/// A scene prepared for explaining any of its pixels, rendered with `options`.
pub struct Explainer<'a> {
    scene: &'a Scene,
    geometry: SceneGeometry,
    options: RenderOptions,
    /// With adaptive anti-aliasing, the pixels that get all the samples.
    refined: Option<Vec<bool>>,
}

impl<'a> Explainer<'a> {
    /// Prepares `scene` to be rendered with `options`. With adaptive
    /// anti-aliasing this renders the 1-sample image once, to find the
    /// pixels that get all the samples, as a render does.
    pub fn new(scene: &'a Scene, options: &RenderOptions) -> Explainer<'a> {
        let geometry = SceneGeometry::new(scene);
        let refined = options.is_adaptive().then(|| {
            let (image, glimpses) = glimpse_pass(scene, &geometry, options);
            refinement_mask(&image, &glimpses)
        });
        Explainer { scene, geometry, options: *options, refined }
    }

    /// The paths traced for pixel `(x, y)` (from the left and from the top).
    ///
    /// # Panics
    ///
    /// If the pixel is outside the image.
    pub fn explain(&self, x: u32, y: u32) -> PixelPaths {
        let index = y as usize * self.options.width as usize + x as usize;
        let samples = match &self.refined {
            Some(refined) if !refined[index] => 1,
            _ => self.options.samples,
        };
        let control = RenderControl::default();
        let pass = Pass::new(self.scene, &self.geometry, &self.options, &control, samples);
        let mut recorder = PathRecorder {
            geometry: &self.geometry,
            samples: Vec::new(),
            traced: 0,
            depth: 0,
            done: true,
            sum: DVec3::ZERO,
            unrecorded_sum: DVec3::ZERO,
        };
        let rgb = pass.one_pixel(x, y, &mut recorder);
        let average = |sum: DVec3, count: usize| if count == 1 { sum } else { sum / count as f64 };
        let unrecorded = recorder.traced - recorder.samples.len();
        PixelPaths {
            pixel: (x, y),
            rgb,
            colour: average(recorder.sum, recorder.traced),
            unrecorded_colour: if unrecorded == 0 { DVec3::ZERO } else { average(recorder.unrecorded_sum, unrecorded) },
            samples: recorder.samples,
            traced: recorder.traced,
        }
    }
}

/// Records the paths the tracer follows for one pixel: each ray's hit, the
/// terms of SPEC 6 there and each level's colour, for the first
/// [`SAMPLES_RECORDED`] samples down to [`LEVELS_RECORDED`] rays; and the
/// sum of every sample's colour.
struct PathRecorder<'g> {
    /// To find what blocks a shadow ray.
    geometry: &'g SceneGeometry,
    samples: Vec<SamplePath>,
    /// How many samples were begun.
    traced: usize,
    /// The level of the ray being traced in the current path (0: the
    /// camera ray).
    depth: usize,
    /// Whether the last path is complete: the next hit starts a new one.
    done: bool,
    /// The sum of the colours of the samples traced, in order.
    sum: DVec3,
    /// The same sum over the samples not recorded.
    unrecorded_sum: DVec3,
}

impl PathRecorder<'_> {
    /// The level being traced, if it is recorded.
    fn level(&mut self) -> Option<&mut Level> {
        if !self.recording() {
            return None;
        }
        self.samples.last_mut().and_then(|path| path.levels.last_mut())
    }

    /// Whether the ray being traced is recorded.
    fn recording(&self) -> bool {
        self.traced <= SAMPLES_RECORDED && self.depth < LEVELS_RECORDED
    }

    /// A sample's path ended with colour `colour`.
    fn sample_done(&mut self, colour: DVec3) {
        self.done = true;
        self.sum += colour;
        if self.traced > SAMPLES_RECORDED {
            self.unrecorded_sum += colour;
        }
    }
}

impl PathObserver for PathRecorder<'_> {
    fn hit(&mut self, _ray: &Ray, hit: Option<&SurfaceHit>, weight: f64) {
        if self.done {
            self.traced += 1;
            self.depth = 0;
            self.done = false;
            if self.traced <= SAMPLES_RECORDED {
                self.samples.push(SamplePath::default());
            }
        } else {
            self.depth += 1;
        }
        if !self.recording() {
            if let (true, Some(path)) = (self.traced <= SAMPLES_RECORDED, self.samples.last_mut()) {
                path.unrecorded_levels += 1;
            }
        } else {
            let surface = hit.map(|hit| Surface {
                primitive: self.geometry.primitive_index(hit),
                // The geometry works in its own unit (an exact power of two).
                point: hit.point / self.geometry.scale(),
                normal: hit.normal,
                material: hit.material,
            });
            let level = Level { weight, surface, ambient: DVec3::ZERO, lights: Vec::new(), colour: DVec3::ZERO };
            self.samples.last_mut().expect("just pushed").levels.push(level);
        }
        // A camera ray that meets nothing ends its path, with no colour to
        // fold: the tracer gives it black.
        if hit.is_none() && self.depth == 0 {
            self.sample_done(DVec3::ZERO);
        }
    }

    fn ambient(&mut self, part: DVec3) {
        if let Some(level) = self.level() {
            level.ambient = part;
        }
    }

    fn light(&mut self, term: LightTerm) {
        if !self.recording() {
            return;
        }
        let part = match term {
            LightTerm::FacingAway => LightPart::FacingAway,
            LightTerm::Shadowed(ray) => {
                LightPart::Shadowed(self.geometry.closest_hit(&ray).map(|hit| self.geometry.primitive_index(&hit)))
            }
            LightTerm::Lit { diffuse, specular } => LightPart::Lit { diffuse, specular },
        };
        if let Some(level) = self.level() {
            level.lights.push(part);
        }
    }

    fn level_colour(&mut self, level: usize, colour: DVec3) {
        if self.traced <= SAMPLES_RECORDED
            && let Some(recorded) = self.samples.last_mut().and_then(|path| path.levels.get_mut(level))
        {
            recorded.colour = colour;
        }
        if level == 0 {
            self.sample_done(colour);
        }
    }
}
