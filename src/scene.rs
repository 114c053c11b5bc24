//! The evaluated scene: camera, lights, ambient light and flat primitives.
//!
//! Everything here is in f64 and in world coordinates: the evaluator bakes
//! every transformation into the primitives (SPEC 4), so the renderer only
//! ever sees spheres, one-sided planes and oriented boxes.

pub mod transform;

use glam::{DMat3, DVec3};

/// The camera of SPEC 5: eye at (0, 0, distance), looking towards -z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Distance of the eye from the origin along +z.
    pub distance: f64,
    /// Horizontal field of view in radians.
    pub angle: f64,
}

/// A directional light (SPEC 6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Unit vector pointing towards the light: R(rotation) * (0, 1, 0).
    pub direction: DVec3,
    /// Intensity, 0..1.
    pub intensity: f64,
}

/// A surface's texture, converted for rendering (colour components 0..1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Colour, each component in 0..1 (the language's 0..255 divided by 255).
    pub color: DVec3,
    /// Diffuse coefficient, 0..1.
    pub kd: f64,
    /// Specular and reflection coefficient, 0..1.
    pub ks: f64,
    /// Phong exponent, > 0.
    pub phong: f64,
}

/// The geometry of one primitive, in world coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius, > 0.
        radius: f64,
    },
    /// The plane `{p : normal·p = shift}`, seen from the side `normal` points to;
    /// it bounds the solid half-space `normal·p <= shift`.
    Plane {
        /// Unit normal.
        normal: DVec3,
        /// Signed distance from the origin.
        shift: f64,
    },
    /// An oriented box.
    Box {
        /// Centre.
        center: DVec3,
        /// Half sizes along the box's own axes, all > 0.
        half: DVec3,
        /// Columns are the box's own x, y, z axes in world space (a rotation matrix).
        axes: DMat3,
    },
}

impl Shape {
    /// Whether `point` is strictly inside the solid: inside a sphere or a box,
    /// not on its surface. A plane's half-space counts as no solid here: an
    /// eye below a floor sees nothing of it, but nothing wrong either.
    pub fn strictly_contains(&self, point: DVec3) -> bool {
        match *self {
            Shape::Sphere { center, radius } => point.distance_squared(center) < radius * radius,
            // In the box's own axes: |(p - c)·axis_k| < half_k for every k.
            Shape::Box { center, half, axes } => (axes.transpose() * (point - center)).abs().cmplt(half).all(),
            Shape::Plane { .. } => false,
        }
    }
}

/// One sphere, plane or box with its material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Primitive {
    /// Where it is.
    pub shape: Shape,
    /// What it looks like.
    pub material: Material,
}

/// Which parts of a scene depend on `time` (so an animation rebuilds only those).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TimeUse {
    /// The camera's distance or angle depends on `time`.
    pub camera: bool,
    /// The ambient intensity depends on `time`.
    pub ambient: bool,
    /// Some light depends on `time`.
    pub lights: bool,
    /// Evaluation read `time` somewhere, even if nothing above nor any
    /// primitive came out depending on it: at another time the program may
    /// put other primitives (`if time > 5 then put ...`) or fail.
    pub read: bool,
}

/// How many objects of each kind a scene holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counts {
    /// Spheres.
    pub spheres: usize,
    /// Planes.
    pub planes: usize,
    /// Boxes.
    pub boxes: usize,
    /// Directional lights.
    pub lights: usize,
}

/// A scene ready to render.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The camera.
    pub camera: Camera,
    /// Ambient intensity Ia, 0..1.
    pub ambient: f64,
    /// Directional lights.
    pub lights: Vec<Light>,
    /// Primitives whose existence and shape do not depend on `time`: the same
    /// for every frame of an animation.
    pub primitives: Vec<Primitive>,
    /// Primitives that depend on `time` (directly, or because a condition or a
    /// procedure argument that led to their `put` did).
    pub timed_primitives: Vec<Primitive>,
    /// Which of camera, ambient and lights depend on `time`.
    pub time_use: TimeUse,
}

impl Counts {
    /// How many primitives of each kind `primitives` holds (no lights).
    pub fn of<'a>(primitives: impl IntoIterator<Item = &'a Primitive>) -> Counts {
        let mut counts = Counts::default();
        for primitive in primitives {
            match primitive.shape {
                Shape::Sphere { .. } => counts.spheres += 1,
                Shape::Plane { .. } => counts.planes += 1,
                Shape::Box { .. } => counts.boxes += 1,
            }
        }
        counts
    }

    /// The primitives counted, in words: "nothing", "1 sphere", "2 spheres,
    /// 1 plane and 3 boxes" (kinds with none are left out; lights too).
    pub fn primitives_in_words(&self) -> String {
        use std::fmt::Write as _;
        let kinds =
            [(self.spheres, "sphere", "spheres"), (self.planes, "plane", "planes"), (self.boxes, "box", "boxes")];
        let present = kinds.iter().filter(|(count, _, _)| *count > 0).count();
        if present == 0 {
            return "nothing".to_string();
        }
        // Written into one string: a confirmation of every `put` says this.
        let mut words = String::new();
        for (index, (count, one, many)) in kinds.into_iter().filter(|(count, _, _)| *count > 0).enumerate() {
            let separator = match present - index {
                _ if index == 0 => "",
                1 => " and ",
                _ => ", ",
            };
            let _ = write!(words, "{separator}{count} {}", if count == 1 { one } else { many });
        }
        words
    }
}

impl Scene {
    /// All primitives, static ones first.
    pub fn all_primitives(&self) -> impl Iterator<Item = &Primitive> {
        self.primitives.iter().chain(&self.timed_primitives)
    }

    /// How many primitives of each kind, and lights, the scene holds (static
    /// and timed primitives together): the `--check` summary.
    pub fn counts(&self) -> Counts {
        self.counts_after(0, 0)
    }

    /// Like [`Scene::counts`], but of the primitives after the first
    /// `primitives` static and `timed` timed ones (what one input added),
    /// with every light.
    pub fn counts_after(&self, primitives: usize, timed: usize) -> Counts {
        let added = self.primitives.get(primitives..).unwrap_or_default();
        let primitives = added.iter().chain(self.timed_primitives.get(timed..).unwrap_or_default());
        Counts { lights: self.lights.len(), ..Counts::of(primitives) }
    }

    /// Whether the scene may be different at another `time`.
    pub fn depends_on_time(&self) -> bool {
        let time_use = self.time_use;
        time_use.read || time_use.camera || time_use.ambient || time_use.lights || !self.timed_primitives.is_empty()
    }
}
