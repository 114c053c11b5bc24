//! Warnings about an evaluated scene: the mistakes that make a valid program
//! render a black or wrong picture, such as a camera that looks away,
//! colours written from 0 to 1, an angle written in degrees, an object never
//! put, the camera inside an object, nothing in view, or no light at all.
//!
//! [`check_scene`] reads the scene, where its parts come from
//! ([`Origins`]) and how it is about to be rendered ([`Picture`]), and
//! returns at most one warning per cause, each pointing at the place to
//! change with the likely fix as its `help:`. It warns only when the picture
//! is certainly affected; for an animation, it leaves out what depends on
//! `time`, since other frames may differ. Each check can be turned off by
//! name (`--allow`, see [`Allowed`]).

use glam::DVec3;

use crate::lang::degrees::in_radians_help;
use crate::lang::eval::{Origins, Turned};
use crate::lang::number::format_number;
use crate::lang::{Diagnostic, Span};
use crate::render::{PrimaryRays, Screen};
use crate::scene::{Counts, Primitive, Scene, Shape};

/// One kind of mistake the checks look for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Check {
    /// A camera distance of 0 or less.
    CameraDistance,
    /// The eye strictly inside a sphere or a box.
    CameraInside,
    /// No object in the field of view.
    OutOfView,
    /// Every colour component at most 1 (of 255).
    Colours,
    /// One object's colour at most 1 (of 255) among brighter ones.
    DarkColour,
    /// An angle of a turn that looks like degrees.
    Degrees,
    /// No ambient light and no light that shines.
    NoLight,
    /// A light of intensity 0 or less.
    ZeroLight,
    /// An `object` defined and never used.
    UnusedObject,
}

impl Check {
    /// Every check, in the order its warnings are given.
    pub const ALL: [Check; 9] = [
        Check::CameraDistance,
        Check::CameraInside,
        Check::OutOfView,
        Check::Colours,
        Check::DarkColour,
        Check::Degrees,
        Check::NoLight,
        Check::ZeroLight,
        Check::UnusedObject,
    ];

    /// The name `--allow` takes.
    pub fn name(self) -> &'static str {
        match self {
            Check::CameraDistance => "camera-distance",
            Check::CameraInside => "camera-inside",
            Check::OutOfView => "out-of-view",
            Check::Colours => "colours",
            Check::DarkColour => "dark-colour",
            Check::Degrees => "degrees",
            Check::NoLight => "no-light",
            Check::ZeroLight => "zero-light",
            Check::UnusedObject => "unused-object",
        }
    }

    /// What it warns about, for `--help`.
    pub fn summary(self) -> &'static str {
        match self {
            Check::CameraDistance => "a camera distance of 0 or less",
            Check::CameraInside => "the camera inside a sphere or a box",
            Check::OutOfView => "no object in the camera's field of view",
            Check::Colours => "every colour at most 1 (colours go from 0 to 255)",
            Check::DarkColour => "an object's colour at most 1 among objects with colours up to 255",
            Check::Degrees => "an angle of a light, a plane or a `rotate` that looks like degrees",
            Check::NoLight => "no light and an ambient light of 0",
            Check::ZeroLight => "a light of intensity 0 or less",
            Check::UnusedObject => "an `object` defined and never put",
        }
    }
}

/// The checks turned off.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Allowed {
    /// Bit `i` stands for `Check::ALL[i]`.
    bits: u16,
}

impl Allowed {
    /// The name that turns every check off.
    pub const EVERY_NAME: &str = "all";

    /// Every check off.
    pub fn every() -> Allowed {
        Allowed { bits: (1 << Check::ALL.len()) - 1 }
    }

    /// `check` off (`all`: every check), by its name; `None` for an unknown name.
    pub fn named(name: &str) -> Option<Allowed> {
        if name == Allowed::EVERY_NAME {
            return Some(Allowed::every());
        }
        let index = Check::ALL.iter().position(|check| check.name() == name)?;
        Some(Allowed { bits: 1 << index })
    }

    /// The checks off in either.
    pub fn and(self, other: Allowed) -> Allowed {
        Allowed { bits: self.bits | other.bits }
    }

    /// Whether `check` is off.
    pub fn contains(self, check: Check) -> bool {
        let index = Check::ALL.iter().position(|c| *c == check).expect("every check is in the list");
        self.bits & (1 << index) != 0
    }
}

/// How the scene is about to be rendered: what the checks need to know.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Picture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Where the z axis meets the screen.
    pub screen: Screen,
    /// Whether the scene is the first frame of an animation, whose parts
    /// that depend on `time` are then left out of the checks.
    pub animation: bool,
}

/// One warning about the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    /// What it is about (`--allow` takes its name).
    pub check: Check,
    /// What is shown.
    pub diagnostic: Diagnostic,
}

/// The warnings about `scene`, evaluated with `origins`, rendered as
/// `picture`, for the checks not in `allowed`, in the order of
/// [`Check::ALL`]. The first warning of each check says how to turn it off.
pub fn check_scene(scene: &Scene, origins: &Origins, picture: &Picture, allowed: Allowed) -> Vec<Warning> {
    let subject = Subject { scene, origins, picture };
    let mut warnings = Vec::new();
    for check in Check::ALL.into_iter().filter(|check| !allowed.contains(*check)) {
        let diagnostics = match check {
            Check::CameraDistance => subject.camera_distance().into_iter().collect(),
            Check::CameraInside => subject.camera_inside().into_iter().collect(),
            Check::OutOfView => subject.out_of_view().into_iter().collect(),
            Check::Colours => subject.colours().into_iter().collect(),
            Check::DarkColour => subject.dark_colours(),
            Check::Degrees => subject.degrees(),
            Check::NoLight => subject.no_light().into_iter().collect(),
            Check::ZeroLight => subject.zero_lights(),
            Check::UnusedObject => subject.unused_objects(),
        };
        for (k, diagnostic) in diagnostics.into_iter().enumerate() {
            let diagnostic = diagnostic.with_code(check.name());
            let diagnostic = if k == 0 {
                diagnostic.with_note(format!("`--allow {}` turns this warning off", check.name()))
            } else {
                diagnostic
            };
            warnings.push(Warning { check, diagnostic });
        }
    }
    warnings
}

/// What the checks read.
struct Subject<'a> {
    scene: &'a Scene,
    origins: &'a Origins,
    picture: &'a Picture,
}

impl Subject<'_> {
    /// Whether the camera may differ in other frames.
    fn camera_moves(&self) -> bool {
        self.picture.animation && self.scene.time_use.camera
    }

    /// Whether anything may differ in other frames.
    fn scene_moves(&self) -> bool {
        self.picture.animation && self.scene.depends_on_time()
    }

    /// Whether the camera itself has a warning (its distance), which then
    /// explains whatever it does or does not see.
    fn camera_is_wrong(&self) -> bool {
        self.scene.camera.distance <= 0.0
    }

    /// Each primitive, numbered: the static ones, then (unless the picture
    /// is an animation) those that depend on `time`.
    fn primitives(&self) -> impl Iterator<Item = (usize, &Primitive)> {
        let timed: &[Primitive] = if self.picture.animation { &[] } else { &self.scene.timed_primitives };
        self.scene.primitives.iter().chain(timed).enumerate()
    }

    /// The `put` that made primitive `index` of [`Subject::primitives`].
    fn put_of(&self, index: usize) -> Option<Span> {
        self.origins.put_of(index, self.scene.primitives.len())
    }

    /// The eye (SPEC 5).
    fn eye(&self) -> DVec3 {
        DVec3::new(0.0, 0.0, self.scene.camera.distance)
    }

    /// A camera distance of 0 or less: the eye looks away from the origin.
    fn camera_distance(&self) -> Option<Diagnostic> {
        let origin = self.origins.camera?;
        let distance = self.scene.camera.distance;
        if distance > 0.0 || self.camera_moves() {
            return None;
        }
        let d = format_number(distance);
        Some(
            Diagnostic::warning(
                origin.distance,
                format!("the camera distance is {d}: the scene around the origin is not in front of the eye"),
            )
            .with_label(format!("puts the eye at (0, 0, {d})"))
            .with_help(
                "the eye is at (0, 0, distance) and looks towards -z, at the origin when the distance \
                     is positive: give a distance larger than the scene, such as `distance 10`",
            ),
        )
    }

    /// The eye inside a sphere or a box that holds nothing else: a room or
    /// a sky around the scene is fine, but then the picture is the inside
    /// of the object and nothing more.
    fn camera_inside(&self) -> Option<Diagnostic> {
        if self.camera_moves() {
            return None;
        }
        let eye = self.eye();
        let holds_nothing_else = |index: usize, container: &Shape| {
            let mut others = self.primitives().filter(|(other, _)| *other != index);
            others.all(|(_, primitive)| !may_show_inside(container, &primitive.shape))
        };
        let (index, primitive) = self
            .primitives()
            .filter(|(_, p)| p.shape.strictly_contains(eye))
            .find(|(index, p)| holds_nothing_else(*index, &p.shape))?;
        let kind = match primitive.shape {
            Shape::Sphere { .. } => "sphere",
            Shape::Box { .. } => "box",
            Shape::Plane { .. } => return None,
        };
        let eye = format!("(0, 0, {})", format_number(eye.z));
        Some(
            Diagnostic::warning(
                self.put_of(index)?,
                format!("the camera is inside a {kind}: the picture shows only its inside"),
            )
            .with_label(format!("the eye, at {eye}, is inside the {kind} this puts, and nothing else is"))
            .with_help(format!(
                "move the eye out of the {kind}, with a larger `camera distance`, or make the {kind} smaller or move it"
            )),
        )
    }

    /// No primitive in the view pyramid: every pixel is black. Left to the
    /// camera's own warnings when its angle or distance is wrong.
    fn out_of_view(&self) -> Option<Diagnostic> {
        if self.scene_moves() || self.camera_is_wrong() {
            return None;
        }
        let picture = self.picture;
        let rays = PrimaryRays::new(&self.scene.camera, picture.width, picture.height, picture.screen);
        let frustum = Frustum::new(self.eye(), rays.corner_directions(picture.height))?;
        if self.primitives().any(|(_, primitive)| frustum.may_see(&primitive.shape)) {
            return None;
        }
        let first = self.put_of(0)?;
        let counts = Counts::of(self.primitives().map(|(_, p)| p)).primitives_in_words();
        let message = format!("the camera sees none of the scene's {counts}: the picture is black");
        let help = "the eye is at (0, 0, distance) and looks towards -z, `angle` radians wide: \
                    put the objects in front of it (around the origin, for a positive distance), or move them into view";
        let diagnostic = match self.origins.camera {
            Some(camera) => Diagnostic::warning(camera.item, message)
                .with_label(format!(
                    "this camera looks from (0, 0, {}) towards -z",
                    format_number(self.scene.camera.distance)
                ))
                .with_related(first, "this object, for one, is out of view"),
            None => Diagnostic::warning(first, message).with_label("out of view of the default camera"),
        };
        Some(diagnostic.with_help(help))
    }

    /// Every colour component at most 1 (of 255), and not all black: colours
    /// written from 0 to 1, as other tools take them.
    fn colours(&self) -> Option<Diagnostic> {
        if self.scene_moves() {
            return None;
        }
        // A colour written c is stored as c / 255: c <= 1 exactly when c / 255 <= 1 / 255.
        let darkest = 1.0 / 255.0;
        if self.primitives().any(|(_, p)| p.material.color.max_element() > darkest) {
            return None;
        }
        let (index, primitive) = self.primitives().find(|(_, p)| p.material.color.max_element() > 0.0)?;
        let written = primitive.material.color * 255.0;
        let scaled = (written * 255.0).round();
        Some(
            Diagnostic::warning(
                self.put_of(index)?,
                "every colour in the scene is at most 1: the picture is nearly black",
            )
            .with_label(format!("this object's colour is {}", colour_as_written(written)))
            .with_help(format!(
                "colours go from 0 to 255, not from 0 to 1: for this one, write `color {}`",
                colour_as_written(scaled)
            )),
        )
    }

    /// Each object whose colour components are all at most 1 (of 255), and
    /// not all 0, in a scene where some colour is above 1: that one colour
    /// written from 0 to 1 (the case of every colour is [`Subject::colours`]).
    /// One warning per `put`.
    fn dark_colours(&self) -> Vec<Diagnostic> {
        let darkest = 1.0 / 255.0;
        if self.scene_moves() || !self.primitives().any(|(_, p)| p.material.color.max_element() > darkest) {
            return Vec::new();
        }
        let mut puts: Vec<Span> = Vec::new();
        let mut diagnostics = Vec::new();
        for (index, primitive) in self.primitives() {
            let color = primitive.material.color;
            if color.max_element() > darkest || color.max_element() <= 0.0 {
                continue;
            }
            let Some(put) = self.put_of(index) else { continue };
            if puts.contains(&put) {
                continue;
            }
            puts.push(put);
            let written = color * 255.0;
            let scaled = (written * 255.0).round();
            diagnostics.push(
                Diagnostic::warning(
                    put,
                    "this object's colour is at most 1, but the others go up to 255: it is nearly black",
                )
                .with_label(format!("this object's colour is {}", colour_as_written(written)))
                .with_help(format!(
                    "colours go from 0 to 255, not from 0 to 1: for this one, write `color {}`",
                    colour_as_written(scaled)
                )),
            );
            if puts.len() == MAX_DARK_COLOURS {
                break;
            }
        }
        diagnostics
    }

    /// Each angle of a turn (a light's or a plane's `rotation`, `rotate ...
    /// by`) that looks like degrees: valid, but most likely not the turn meant.
    fn degrees(&self) -> Vec<Diagnostic> {
        let degrees = self.origins.degrees.iter();
        degrees
            .map(|origin| {
                let a = format_number(origin.angle);
                let what = match origin.turned {
                    Turned::Light => "the light's angle",
                    Turned::Plane => "the plane's rotation",
                    Turned::Object => "the rotation",
                };
                let turns = format_number((origin.angle.abs() / std::f64::consts::TAU * 10.0).round() / 10.0);
                Diagnostic::warning(origin.span, format!("{what} {a} looks like degrees, but angles are in radians"))
                    .with_label(format!("read as {a} radians, about {turns} turns"))
                    .with_help(in_radians_help(origin.angle, ""))
            })
            .collect()
    }

    /// No light that shines and an ambient light of 0: every pixel is black.
    fn no_light(&self) -> Option<Diagnostic> {
        let time_use = self.scene.time_use;
        if self.picture.animation && (time_use.ambient || time_use.lights) {
            return None;
        }
        let shines = self.scene.lights.iter().any(|light| light.intensity > 0.0);
        if shines || self.scene.ambient > 0.0 || self.primitives().next().is_none() {
            return None;
        }
        let lights = if self.scene.lights.is_empty() { "there is no light" } else { "no light shines" };
        Some(
            Diagnostic::warning(self.origins.ambient?, format!("{lights} and the ambient light is 0: the picture is black"))
                .with_label("no ambient light")
                .with_help("add a light, such as `light vector 0.5, 0, 0.5 intensity 0.8 end`, or some ambient light (`ambient 0.2`)"),
        )
    }

    /// Each light of intensity 0 or less.
    fn zero_lights(&self) -> Vec<Diagnostic> {
        if self.picture.animation && self.scene.time_use.lights {
            return Vec::new();
        }
        let lights = self.scene.lights.iter().zip(&self.origins.lights);
        lights
            .filter(|(light, _)| light.intensity <= 0.0)
            .map(|(light, origin)| {
                let intensity = format_number(light.intensity);
                Diagnostic::warning(
                    origin.intensity,
                    format!("this light has intensity {intensity}: it lights nothing"),
                )
                .with_label("no light comes from it")
                .with_help("give it an intensity above 0, up to 1, such as `intensity 0.8`, or remove the light")
            })
            .collect()
    }

    /// Each `object` definition never used, unless an `if` on `time` may
    /// use it at another time.
    fn unused_objects(&self) -> Vec<Diagnostic> {
        if self.origins.branched_on_time {
            return Vec::new();
        }
        let unused = self.origins.objects.iter().filter(|definition| !definition.used);
        unused
            .map(|definition| {
                let name = &definition.name;
                Diagnostic::warning(definition.span, format!("the object `{name}` is defined but never put"))
                    .with_label("not in the scene")
                    .with_help(format!("`put {name}` adds it to the scene; or remove the definition"))
            })
            .collect()
    }
}

/// How many objects [`Subject::dark_colours`] names at most.
const MAX_DARK_COLOURS: usize = 8;

/// A colour as a program writes it: `0.8, 0.2, 0.1`.
fn colour_as_written(c: DVec3) -> String {
    format!("{}, {}, {}", format_number(c.x), format_number(c.y), format_number(c.z))
}

/// Whether the surface of `other` may pass inside `container` (a sphere or
/// a box around the eye), so that the eye may see it: `false` only when
/// certainly not. Solids are compared by their bounding spheres: apart, or
/// `other` a sphere enclosing the container, is certainly not.
fn may_show_inside(container: &Shape, other: &Shape) -> bool {
    let Some((center, radius)) = bounding_sphere(container) else { return true };
    let margin = MARGIN * (center.length() + radius);
    match (*other, bounding_sphere(other)) {
        (Shape::Plane { normal, shift }, _) => (normal.dot(center) - shift).abs() < radius + margin,
        (Shape::Sphere { .. }, Some((other_center, other_radius))) => {
            let apart = center.distance(other_center);
            let encloses = apart + radius < other_radius - margin;
            !encloses && apart < radius + other_radius + margin
        }
        (_, Some((other_center, other_radius))) => center.distance(other_center) < radius + other_radius + margin,
        (_, None) => true,
    }
}

/// The centre and radius of a sphere around a sphere or a box; `None` for a plane.
fn bounding_sphere(shape: &Shape) -> Option<(DVec3, f64)> {
    match *shape {
        Shape::Sphere { center, radius } => Some((center, radius)),
        Shape::Box { center, half, .. } => Some((center, half.length())),
        Shape::Plane { .. } => None,
    }
}

/// The region the primary rays sweep: an infinite pyramid with its apex at
/// the eye and its edges through the image's corners (SPEC 5).
struct Frustum {
    eye: DVec3,
    corners: [DVec3; 4],
    /// The unit normals of the four sides, pointing in.
    sides: [DVec3; 4],
}

/// How far outside a side an object must be to count as out of view,
/// relative to its distance from the eye: rounding never makes a visible
/// object look hidden.
const MARGIN: f64 = 1e-9;

impl Frustum {
    /// The pyramid of rays from `eye` between the corner directions, `None`
    /// when the camera gives no proper pyramid (an angle of 0: every ray
    /// goes straight ahead).
    fn new(eye: DVec3, corners: [DVec3; 4]) -> Option<Frustum> {
        let middle: DVec3 = corners.iter().sum();
        let mut sides = [DVec3::ZERO; 4];
        for (i, side) in sides.iter_mut().enumerate() {
            let normal = corners[i].cross(corners[(i + 1) % 4]).try_normalize()?;
            *side = if normal.dot(middle) >= 0.0 { normal } else { -normal };
        }
        corners.iter().all(|c| c.is_finite()).then_some(Frustum { eye, corners, sides })
    }

    /// Whether a primary ray may meet `shape`: `false` only when certainly not.
    ///
    /// A sphere or a box is out of view when it lies wholly outside one side
    /// (its centre's distance to the side is below minus its extent along the
    /// side's normal). A plane is seen from its front only (SPEC 4): it is
    /// out of view when the eye is behind it, or when no ray goes towards it
    /// (at every corner, the ray's direction has a non-negative component
    /// along the normal).
    fn may_see(&self, shape: &Shape) -> bool {
        match *shape {
            Shape::Sphere { center, radius } => self.may_contain(center, |_| radius),
            Shape::Box { center, half, axes } => {
                self.may_contain(center, |normal| (axes.transpose() * normal).abs().dot(half))
            }
            Shape::Plane { normal, shift } => {
                let margin = MARGIN * (shift.abs() + self.eye.length());
                normal.dot(self.eye) > shift - margin && self.corners.iter().any(|c| c.dot(normal) < 0.0)
            }
        }
    }

    /// Whether a solid around `center`, reaching `extent(normal)` along each
    /// side's normal, is not wholly outside a side.
    fn may_contain(&self, center: DVec3, extent: impl Fn(DVec3) -> f64) -> bool {
        let offset = center - self.eye;
        self.sides.iter().all(|&normal| {
            let reach = extent(normal);
            normal.dot(offset) >= -reach - MARGIN * (offset.length() + reach)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn allowed_checks_are_named_one_by_one_or_all() {
        let distance = Allowed::named("camera-distance").expect("a check");
        assert!(distance.contains(Check::CameraDistance) && !distance.contains(Check::Colours));
        let both = distance.and(Allowed::named("colours").expect("a check"));
        assert!(both.contains(Check::Colours));
        assert!(Check::ALL.iter().all(|check| Allowed::named("all").expect("all").contains(*check)));
        assert_eq!(Allowed::named("colour"), None);
        assert!(Check::ALL.iter().all(|check| Allowed::named(check.name()).is_some()));
    }

    fn view() -> Frustum {
        let rays = PrimaryRays::new(&crate::scene::Camera { distance: 10.0, angle: 1.0 }, 40, 30, Screen::Centered);
        Frustum::new(DVec3::new(0.0, 0.0, 10.0), rays.corner_directions(30)).expect("a proper pyramid")
    }

    #[test]
    fn the_view_sees_what_is_in_front_and_not_what_is_behind_or_aside() {
        let view = view();
        let sphere = |x: f64, z: f64, radius: f64| Shape::Sphere { center: DVec3::new(x, 0.0, z), radius };
        assert!(view.may_see(&sphere(0.0, 0.0, 1.0)));
        assert!(!view.may_see(&sphere(0.0, 20.0, 1.0)), "behind the eye");
        // At 10 units in front, the half width seen is 10 tan(0.5) = 5.46.
        assert!(view.may_see(&sphere(6.0, 0.0, 1.0)), "straddles the edge");
        assert!(!view.may_see(&sphere(7.0, 0.0, 1.0)), "just outside");
        let floor = |shift: f64| Shape::Plane { normal: DVec3::Y, shift };
        assert!(view.may_see(&floor(-1.0)), "a floor below the eye");
        assert!(!view.may_see(&floor(1.0)), "seen from below, its back");
        let wall = Shape::Plane { normal: DVec3::Z, shift: 20.0 };
        assert!(!view.may_see(&wall), "behind the eye, facing it");
    }

    #[test]
    fn a_room_or_a_sky_around_the_eye_may_show_what_is_inside_it() {
        let sky = Shape::Sphere { center: DVec3::ZERO, radius: 100.0 };
        let inside = Shape::Sphere { center: DVec3::ZERO, radius: 1.0 };
        let far = Shape::Sphere { center: DVec3::new(300.0, 0.0, 0.0), radius: 1.0 };
        let around = Shape::Sphere { center: DVec3::ZERO, radius: 500.0 };
        assert!(may_show_inside(&sky, &inside));
        assert!(!may_show_inside(&sky, &far));
        assert!(!may_show_inside(&sky, &around), "a larger sphere around it stays outside");
        let floor = Shape::Plane { normal: DVec3::Y, shift: -1.0 };
        assert!(may_show_inside(&sky, &floor));
        assert!(may_show_inside(&inside, &floor), "touching counts");
        let lower = Shape::Plane { normal: DVec3::Y, shift: -2.0 };
        assert!(!may_show_inside(&inside, &lower));
    }
}
