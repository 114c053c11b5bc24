//! Why a pixel has its colour: the paths traced for it, recorded by an
//! observer of the tracer while it renders that pixel the way a render
//! does. The recorded colours are the ones the tracer computed, so the
//! explained bytes are the rendered bytes.
//!
//! [`Explainer`] prepares a scene once (and, for adaptive anti-aliasing,
//! finds which pixels get all the samples); [`Explainer::explain`] then
//! traces one pixel with a [`PathRecorder`] watching.

use glam::DVec3;

use super::adaptive::{glimpse_pass, refinement_mask};
use super::geometry::{SceneGeometry, SurfaceHit};
use super::intersect::Ray;
use super::options::{RenderControl, RenderOptions};
use super::pixels::Pass;
use super::shade::{LightTerm, PathObserver};
use crate::scene::{Material, Scene};

/// Everything traced for one pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct PixelPaths {
    /// The pixel, from the left and from the top.
    pub pixel: (u32, u32),
    /// The bytes written to the image: `round(255 * c)` of the average
    /// of the samples' colours (SPEC 6).
    pub rgb: [u8; 3],
    /// Each sample's path, in the order traced.
    pub samples: Vec<SamplePath>,
}

/// The path of one camera ray, down its mirror reflections.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SamplePath {
    /// What each ray met, the camera ray first.
    pub levels: Vec<Level>,
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
        let mut recorder = PathRecorder { geometry: &self.geometry, samples: Vec::new(), done: true };
        let rgb = pass.one_pixel(x, y, &mut recorder);
        PixelPaths { pixel: (x, y), rgb, samples: recorder.samples }
    }
}

/// Records the paths the tracer follows for one pixel: each ray's hit, the
/// terms of SPEC 6 there and each level's colour.
struct PathRecorder<'g> {
    /// To find what blocks a shadow ray.
    geometry: &'g SceneGeometry,
    samples: Vec<SamplePath>,
    /// Whether the last path is complete: the next hit starts a new one.
    done: bool,
}

impl PathRecorder<'_> {
    /// The level being traced.
    fn level(&mut self) -> &mut Level {
        self.samples.last_mut().and_then(|path| path.levels.last_mut()).expect("a hit comes first")
    }
}

impl PathObserver for PathRecorder<'_> {
    fn hit(&mut self, _ray: &Ray, hit: Option<&SurfaceHit>, weight: f64) {
        if self.done {
            self.samples.push(SamplePath::default());
            self.done = false;
        }
        let surface = hit.map(|hit| Surface {
            primitive: self.geometry.primitive_index(hit),
            // The geometry works in its own unit (an exact power of two).
            point: hit.point / self.geometry.scale(),
            normal: hit.normal,
            material: hit.material,
        });
        let path = self.samples.last_mut().expect("just pushed");
        // A camera ray that meets nothing ends its path, with no colour to fold.
        self.done = surface.is_none() && path.levels.is_empty();
        path.levels.push(Level { weight, surface, ambient: DVec3::ZERO, lights: Vec::new(), colour: DVec3::ZERO });
    }

    fn ambient(&mut self, part: DVec3) {
        self.level().ambient = part;
    }

    fn light(&mut self, term: LightTerm) {
        let part = match term {
            LightTerm::FacingAway => LightPart::FacingAway,
            LightTerm::Shadowed(ray) => {
                LightPart::Shadowed(self.geometry.closest_hit(&ray).map(|hit| self.geometry.primitive_index(&hit)))
            }
            LightTerm::Lit { diffuse, specular } => LightPart::Lit { diffuse, specular },
        };
        self.level().lights.push(part);
    }

    fn level_colour(&mut self, level: usize, colour: DVec3) {
        let path = self.samples.last_mut().expect("a hit comes first");
        path.levels[level].colour = colour;
        self.done = level == 0;
    }
}
