//! The checks of a lesson's steps: a small declarative vocabulary, one
//! check a line of a lesson file (`Check: a sphere, radius 2, center 0 0 0`),
//! each looking at the learner's evaluated scene, never at the text typed,
//! so that any program that builds the right scene passes.
//!
//! A check that does not hold says what in the learner's scene comes
//! closest and how it differs from the goal ([`Shortfall`]). The words are
//! documented in docs/lessons.md; [`parse`] is their one definition.

mod read;
mod verdict;

use glam::DVec3;

use crate::lang::Span;
use crate::lang::number::format_number;
use crate::scene::{Camera, Light, Primitive, Shape};

pub(crate) use read::parse;
pub(crate) use verdict::{holds, no_degrees};

/// One check of a step.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Check {
    /// The program places a camera with these properties.
    Camera(Vec<Condition>),
    /// The program sets an ambient light with this level.
    Ambient(Comparison),
    /// At least `count` lights of these properties.
    Lights(LightsWanted),
    /// At least `count` primitives of one kind, with these properties and
    /// arrangement.
    Shapes(ShapesWanted),
    /// A global number of this name (exactly: `r` is not `R`), with a value.
    Number { name: String, value: Option<Comparison> },
    /// A global object of this name, made of one primitive of this kind
    /// with these properties.
    Object { name: String, kind: ShapeKind, conditions: Vec<Condition> },
    /// A procedure of this name with this many parameters.
    Procedure { name: String, parameters: usize },
    /// Something in the scene depends on `time`.
    DependsOnTime,
    /// The scene is the step's goal (the lesson's setup and examples up to
    /// this step), compared as `rayrepl compare` does.
    MatchesGoal,
}

/// Lights a check asks for.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LightsWanted {
    pub count: usize,
    /// The sides every one of them comes from.
    pub from: Vec<Direction>,
    pub conditions: Vec<Condition>,
    /// A light, coming from these sides, that each must be weaker than.
    pub weaker_than: Option<Vec<Direction>>,
}

/// Primitives a check asks for.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ShapesWanted {
    pub count: usize,
    pub kind: ShapeKind,
    pub conditions: Vec<Condition>,
    /// Of the size and material of this global object's first primitive.
    pub like: Option<String>,
    /// Depending on `time`.
    pub moving: bool,
    /// All made by one `put` (run several times by a procedure, or of a group).
    pub one_put: bool,
    /// How they stand among themselves.
    pub arrangement: Vec<Arrangement>,
}

/// The kinds of primitives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ShapeKind {
    Sphere,
    Box,
    Plane,
}

/// How primitives stand among themselves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Arrangement {
    /// On a line along x, at the same height and depth, none overlapping.
    SideBySide,
    /// One on the other, upwards: same x and z, each touching or entering
    /// the one below.
    Stacked,
    /// Each higher one smaller.
    Shrinking,
    /// Each at its own height.
    Rising,
    /// The lowest resting on a plane that faces up.
    OnTheFloor,
}

/// A side a light comes from (the camera looks from the front, +z).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Direction {
    Above,
    Below,
    Right,
    Left,
    Front,
    Back,
}

/// A property of a part of the scene compared with a goal.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Condition {
    pub quantity: Quantity,
    pub comparison: Comparison,
}

/// How a value compares with the goal's.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Comparison {
    pub relation: Relation,
    /// One number, or three.
    pub goal: Vec<f64>,
    /// How far from the goal still counts as equal.
    pub within: f64,
}

/// How a value relates to the goal's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Relation {
    Equal,
    Below,
    Above,
    AtLeast,
    AtMost,
}

/// What a condition reads of a part of the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Quantity {
    Center,
    X,
    Y,
    Z,
    Radius,
    /// A box's extents along x, y and z.
    Size,
    /// The lowest point.
    Bottom,
    /// The highest point.
    Top,
    /// The direction of a box's longest side, either way along it.
    Axis,
    /// A box's side lengths, longest first.
    Sides,
    Normal,
    Shift,
    /// 0..255, as the program writes it.
    Color,
    Kd,
    Ks,
    Phong,
    Intensity,
    /// Towards the light.
    Direction,
    Distance,
    Angle,
}

/// Each quantity's name in a check, and how many numbers it has.
const QUANTITIES: &[(&str, Quantity, usize)] = &[
    ("center", Quantity::Center, 3),
    ("x", Quantity::X, 1),
    ("y", Quantity::Y, 1),
    ("z", Quantity::Z, 1),
    ("radius", Quantity::Radius, 1),
    ("size", Quantity::Size, 3),
    ("bottom", Quantity::Bottom, 1),
    ("top", Quantity::Top, 1),
    ("axis", Quantity::Axis, 3),
    ("sides", Quantity::Sides, 3),
    ("normal", Quantity::Normal, 3),
    ("shift", Quantity::Shift, 1),
    ("color", Quantity::Color, 3),
    ("kd", Quantity::Kd, 1),
    ("ks", Quantity::Ks, 1),
    ("phong", Quantity::Phong, 1),
    ("intensity", Quantity::Intensity, 1),
    ("direction", Quantity::Direction, 3),
    ("distance", Quantity::Distance, 1),
    ("angle", Quantity::Angle, 1),
];

/// The relation words, longest first.
const RELATIONS: &[(&str, Relation)] = &[
    ("at least", Relation::AtLeast),
    ("at most", Relation::AtMost),
    ("below", Relation::Below),
    ("above", Relation::Above),
];

const DIRECTIONS: &[(&str, Direction)] = &[
    ("above", Direction::Above),
    ("below", Direction::Below),
    ("right", Direction::Right),
    ("left", Direction::Left),
    ("front", Direction::Front),
    ("back", Direction::Back),
];

const ARRANGEMENTS: &[(&str, Arrangement)] = &[
    ("side by side", Arrangement::SideBySide),
    ("stacked", Arrangement::Stacked),
    ("shrinking", Arrangement::Shrinking),
    ("rising", Arrangement::Rising),
    ("on the floor", Arrangement::OnTheFloor),
];

/// The smallest part of a light's direction towards a side for it to come
/// from that side: 0.2 is about 12 degrees off the perpendicular.
const FROM_SIDE: f64 = 0.2;

/// The default tolerance of a colour: the same level out of 255.
const COLOR_WITHIN: f64 = 0.5;

/// The most primitives of one kind whose arrangements are searched from
/// each as a start: beyond, the first ones only (a lesson's scene has tens).
const ARRANGEMENT_STARTS: usize = 256;

/// Every word of the vocabulary of properties, relations, sides and
/// arrangements, for the test that docs/lessons.md documents them all.
#[cfg(test)]
pub(crate) fn vocabulary() -> Vec<&'static str> {
    let quantities = QUANTITIES.iter().map(|(name, _, _)| *name);
    let relations = RELATIONS.iter().map(|(name, _)| *name);
    let sides = DIRECTIONS.iter().map(|(name, _)| *name);
    quantities.chain(relations).chain(sides).chain(ARRANGEMENTS.iter().map(|(name, _)| *name)).collect()
}

/// Why a check does not hold: what the learner's scene has instead, in
/// words, and the input that made the part closest to the goal, if any.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Shortfall {
    pub text: String,
    pub made_at: Option<Span>,
}

impl Shortfall {
    fn new(text: impl Into<String>) -> Shortfall {
        Shortfall { text: text.into(), made_at: None }
    }
}

impl ShapeKind {
    fn name(self) -> &'static str {
        match self {
            ShapeKind::Sphere => "sphere",
            ShapeKind::Box => "box",
            ShapeKind::Plane => "plane",
        }
    }

    fn plural(self) -> &'static str {
        match self {
            ShapeKind::Sphere => "spheres",
            ShapeKind::Box => "boxes",
            ShapeKind::Plane => "planes",
        }
    }

    fn of(shape: &Shape) -> ShapeKind {
        match shape {
            Shape::Sphere { .. } => ShapeKind::Sphere,
            Shape::Box { .. } => ShapeKind::Box,
            Shape::Plane { .. } => ShapeKind::Plane,
        }
    }

    /// The kind a word of a check names, and whether it is plural.
    fn read(word: &str) -> Option<(ShapeKind, bool)> {
        [ShapeKind::Sphere, ShapeKind::Box, ShapeKind::Plane].into_iter().find_map(|kind| {
            (word == kind.name()).then_some((kind, false)).or((word == kind.plural()).then_some((kind, true)))
        })
    }
}

impl Direction {
    fn name(self) -> &'static str {
        DIRECTIONS.iter().find(|(_, d)| *d == self).map_or("", |(name, _)| name)
    }

    /// Whether a light towards `towards` comes from this side.
    fn holds(self, towards: DVec3) -> bool {
        match self {
            Direction::Above => towards.y > FROM_SIDE,
            Direction::Below => towards.y < -FROM_SIDE,
            Direction::Right => towards.x > FROM_SIDE,
            Direction::Left => towards.x < -FROM_SIDE,
            Direction::Front => towards.z > FROM_SIDE,
            Direction::Back => towards.z < -FROM_SIDE,
        }
    }
}

impl Arrangement {
    fn name(self) -> &'static str {
        ARRANGEMENTS.iter().find(|(_, a)| *a == self).map_or("", |(name, _)| name)
    }
}

impl Quantity {
    fn name(self) -> &'static str {
        QUANTITIES.iter().find(|(_, q, _)| *q == self).map_or("", |(name, _, _)| name)
    }

    fn arity(self) -> usize {
        QUANTITIES.iter().find(|(_, q, _)| *q == self).map_or(1, |(_, _, arity)| *arity)
    }

    /// Its value for `part`, if `part` has it.
    fn read(self, part: Part) -> Option<Vec<f64>> {
        let triple = |v: DVec3| Some(vec![v.x, v.y, v.z]);
        let one = |v: f64| Some(vec![v]);
        match (self, part) {
            (Quantity::Color, Part::Primitive(p)) => triple(p.material.color * 255.0),
            (Quantity::Kd, Part::Primitive(p)) => one(p.material.kd),
            (Quantity::Ks, Part::Primitive(p)) => one(p.material.ks),
            (Quantity::Phong, Part::Primitive(p)) => one(p.material.phong),
            (Quantity::Intensity, Part::Light(light)) => one(light.intensity),
            (Quantity::Direction, Part::Light(light)) => triple(light.direction),
            (Quantity::Distance, Part::Camera(camera)) => one(camera.distance),
            (Quantity::Angle, Part::Camera(camera)) => one(camera.angle),
            (_, Part::Primitive(p)) => self.read_shape(&p.shape),
            _ => None,
        }
    }

    fn read_shape(self, shape: &Shape) -> Option<Vec<f64>> {
        let extents = extents(shape);
        let (center, low, high) = match *shape {
            Shape::Sphere { center, .. } | Shape::Box { center, .. } => (center, center - extents, center + extents),
            Shape::Plane { .. } => (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO),
        };
        let solid = !matches!(shape, Shape::Plane { .. });
        let value = match (self, *shape) {
            (Quantity::Center, _) if solid => vec![center.x, center.y, center.z],
            (Quantity::X, _) if solid => vec![center.x],
            (Quantity::Y, _) if solid => vec![center.y],
            (Quantity::Z, _) if solid => vec![center.z],
            (Quantity::Bottom, _) if solid => vec![low.y],
            (Quantity::Top, _) if solid => vec![high.y],
            (Quantity::Radius, Shape::Sphere { radius, .. }) => vec![radius],
            (Quantity::Size, Shape::Box { .. }) => (2.0 * extents).to_array().to_vec(),
            (Quantity::Axis, Shape::Box { half, axes, .. }) => {
                let longest = if half.x >= half.y && half.x >= half.z {
                    axes.x_axis
                } else if half.y >= half.z {
                    axes.y_axis
                } else {
                    axes.z_axis
                };
                longest.to_array().to_vec()
            }
            (Quantity::Sides, Shape::Box { half, .. }) => {
                let mut sides = (2.0 * half).to_array();
                sides.sort_by(|a, b| b.total_cmp(a));
                sides.to_vec()
            }
            (Quantity::Normal, Shape::Plane { normal, .. }) => normal.to_array().to_vec(),
            (Quantity::Shift, Shape::Plane { shift, .. }) => vec![shift],
            _ => return None,
        };
        Some(value)
    }

    /// The default tolerance of a goal value.
    fn default_within(self, goal: &[f64]) -> f64 {
        match self {
            Quantity::Color => COLOR_WITHIN,
            _ => 1e-6 * (1.0 + goal.iter().fold(0.0_f64, |most, v| most.max(v.abs()))),
        }
    }
}

/// Half the extents of a solid along x, y and z.
fn extents(shape: &Shape) -> DVec3 {
    match *shape {
        Shape::Sphere { radius, .. } => DVec3::splat(radius),
        Shape::Box { half, axes, .. } => {
            DVec3::new(axes.row(0).abs().dot(half), axes.row(1).abs().dot(half), axes.row(2).abs().dot(half))
        }
        Shape::Plane { .. } => DVec3::ZERO,
    }
}

/// A part of the scene a condition reads.
#[derive(Debug, Clone, Copy)]
enum Part<'a> {
    Primitive(&'a Primitive),
    Light(&'a Light),
    Camera(&'a Camera),
}

impl Comparison {
    /// How far `value` is from holding, 0 when it holds.
    fn miss(&self, quantity: Quantity, value: &[f64]) -> f64 {
        let gap = |v: f64, goal: f64| match self.relation {
            Relation::Equal => ((v - goal).abs() - self.within).max(0.0),
            Relation::Below => (v - goal).max(0.0) + if v < goal { 0.0 } else { f64::MIN_POSITIVE },
            Relation::Above => (goal - v).max(0.0) + if v > goal { 0.0 } else { f64::MIN_POSITIVE },
            Relation::AtLeast => (goal - v).max(0.0),
            Relation::AtMost => (v - goal).max(0.0),
        };
        let apart = |sign: f64| value.iter().zip(&self.goal).map(|(v, g)| gap(sign * v, *g)).fold(0.0, f64::max);
        match quantity {
            Quantity::Axis => apart(1.0).min(apart(-1.0)),
            _ => apart(1.0),
        }
    }

    /// The goal in words: "2", "at least 0.3", "255, 120, 40 within 60".
    fn words(&self, quantity: Quantity) -> String {
        let relation = RELATIONS.iter().find(|(_, r)| *r == self.relation).map_or("", |(name, _)| name);
        let values = numbers_in_words(&self.goal);
        let within = if self.within > quantity.default_within(&self.goal) {
            format!(" within {}", format_number(self.within))
        } else {
            String::new()
        };
        let either_way = if quantity == Quantity::Axis { " (either way)" } else { "" };
        format!("{relation}{}{values}{within}{either_way}", if relation.is_empty() { "" } else { " " })
    }
}

fn numbers_in_words(values: &[f64]) -> String {
    values.iter().map(|&v| format_number(round_for_words(v))).collect::<Vec<_>>().join(", ")
}

/// `value` with the noise of rounding taken off, for words: 0.7071067811865476
/// stays, 2.9999999999999996 is 3.
fn round_for_words(value: f64) -> f64 {
    let rounded = (value * 1e9).round() / 1e9;
    // Adding 0 makes -0 a plain 0.
    if (rounded - value).abs() <= 1e-12 * (1.0 + value.abs()) { rounded + 0.0 } else { value }
}

impl Condition {
    fn miss(&self, part: Part) -> Option<f64> {
        self.quantity.read(part).map(|value| self.comparison.miss(self.quantity, &value))
    }

    /// What `part` has and what the goal is: "radius 1 (the goal: 2)".
    fn words(&self, part: Part) -> String {
        let value = self.quantity.read(part).map_or_else(|| "none".to_string(), |v| numbers_in_words(&v));
        format!("{} {value} (the goal: {})", self.quantity.name(), self.comparison.words(self.quantity))
    }
}

#[cfg(test)]
mod tests {
    use super::read::parse_number;
    use super::*;
    use crate::lessons::lesson_scene::LessonScene;
    use crate::settings::RenderSettings;

    fn learner(program: &str) -> LessonScene {
        let mut learner = LessonScene::new(RenderSettings::default().time);
        learner.run("<test>", program).expect("the program runs");
        learner
    }

    fn check(check: &str, program: &str) -> Result<(), Shortfall> {
        let check = parse(check).expect("the check reads");
        holds(&check, &learner(program), None)
    }

    #[test]
    fn checks_read_as_written() {
        let read = parse("a sphere, radius 2, color 255 120 40 within 60, ks at least 0.3").expect("reads");
        let Check::Shapes(wanted) = read else { panic!("{read:?}") };
        assert_eq!(wanted.kind, ShapeKind::Sphere);
        assert_eq!(
            wanted.conditions[1].comparison,
            Comparison { relation: Relation::Equal, goal: vec![255.0, 120.0, 40.0], within: 60.0 }
        );
        assert_eq!(wanted.conditions[2].comparison.relation, Relation::AtLeast);
        assert_eq!(parse("procedure tower(n, r, y)"), Ok(Check::Procedure { name: "tower".into(), parameters: 3 }));
        assert_eq!(parse_number("-pi/4"), Ok(-std::f64::consts::FRAC_PI_4));
        assert!(parse("a sphere, radius 2 3").unwrap_err().contains("one number"));
        assert!(parse("a sphere, colour 1 2 3").unwrap_err().contains("not a property"));
        assert!(parse("some spheres").is_err());
    }

    #[test]
    fn feedback_names_the_closest_part_and_how_it_differs() {
        let program = "put translate scale sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end \
                       by 1.5 end by -3, 0.5, 0 end\nput sphere center 0, 0, 0 radius 1.5 kd 1 ks 0 phong 1 color 9, 9, 9 end";
        assert_eq!(check("a sphere, radius 1.5, center -3 0.5 0", program), Ok(()));
        let program = "put scale translate sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end \
                       by -3, 0.5, 0 end by 1.5 end";
        let shortfall = check("a sphere, radius 1.5, center -3 0.5 0", program).unwrap_err();
        assert_eq!(shortfall.text, "your sphere, put at line 1, has center -4.5, 0.75, 0 (the goal: -3, 0.5, 0)");
        assert!(shortfall.made_at.is_some());
    }

    #[test]
    fn names_tell_capitals_apart_and_values_count() {
        assert_eq!(check("number r 0.7", "let r = 0.7"), Ok(()));
        assert!(check("number r 0.7", "let R = 0.7").unwrap_err().text.contains("you named it `R`"));
        assert!(check("number r 0.7", "let r = 7").unwrap_err().text.contains("your `r` is 7"));
    }

    #[test]
    fn lights_come_from_their_sides() {
        let right = "light vector 0, 0, -0.9 intensity 0.8 end";
        assert_eq!(check("a light from right above", right), Ok(()));
        assert!(
            check("a light from left", right)
                .unwrap_err()
                .text
                .contains("so it comes from above and right; the goal: from left")
        );
        let both = format!("{right}\nlight vector 0, 0, 0.9 intensity 0.8 end");
        let shortfall = check("a light from left, weaker than the light from right", &both).unwrap_err();
        assert!(shortfall.text.contains("not weaker"), "{}", shortfall.text);
    }

    #[test]
    fn arrangements_count_the_parts_standing_so() {
        let ball = |x: f64, y: f64, r: f64| {
            format!("put sphere center {x}, {y}, 0 radius {r} kd 1 ks 0 phong 1 color 9, 9, 9 end\n")
        };
        let row = [ball(-2.0, 0.0, 0.5), ball(0.0, 0.0, 0.5), ball(2.0, 0.0, 0.5)].concat();
        assert_eq!(check("3 spheres, side by side", &row), Ok(()));
        let overlapping = [ball(-0.5, 0.0, 0.5), ball(0.0, 0.0, 0.5), ball(0.5, 0.0, 0.5)].concat();
        assert!(check("3 spheres, side by side", &overlapping).is_err());
        let tower = [ball(0.0, 0.0, 1.0), ball(0.0, 1.8, 0.8), ball(0.0, 3.2, 0.6)].concat();
        assert_eq!(check("3 spheres, stacked, shrinking", &tower), Ok(()));
        let floating = [ball(0.0, 0.0, 1.0), ball(0.0, 3.0, 0.8), ball(0.0, 5.0, 0.6)].concat();
        assert!(check("3 spheres, stacked", &floating).is_err());
    }

    #[test]
    fn a_scene_matches_the_goal_however_it_is_built() {
        let goal = learner("put sphere center 1, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end");
        let same =
            learner("put translate sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end by 1, 0, 0 end");
        assert_eq!(holds(&Check::MatchesGoal, &same, Some(&goal)), Ok(()));
        let other = learner("put sphere center 1, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 90 end");
        let shortfall = holds(&Check::MatchesGoal, &other, Some(&goal)).unwrap_err();
        assert!(shortfall.text.contains("colour 9, 9, 90; the goal's has 9, 9, 9"), "{}", shortfall.text);
        assert_eq!(parse("the scene matches the goal"), Ok(Check::MatchesGoal));
    }

    #[test]
    fn a_turned_box_is_read_by_its_longest_side() {
        let turned = |angle: &str| {
            format!(
                "put rotate box center 0, 0, 0 length 3, 1, 1 kd 1 ks 0 phong 1 color 9, 9, 9 end by 0, 0, {angle} end"
            )
        };
        let wanted = "a box, axis 0.70710678 0.70710678 0 within 0.001";
        assert_eq!(check(wanted, &turned("pi/4")), Ok(()));
        assert_eq!(check(wanted, &turned("pi/4 + pi")), Ok(()));
        assert!(check(wanted, &turned("45")).is_err());
    }
}
