//! The checks of a lesson's steps: a small declarative vocabulary, one
//! check a line of a lesson file (`Check: a sphere, radius 2, center 0 0 0`),
//! each looking at the learner's evaluated scene, never at the text typed,
//! so that any program that builds the right scene passes.
//!
//! A check that does not hold says what in the learner's scene comes
//! closest and how it differs from the goal ([`Shortfall`]). The words are
//! documented in docs/lessons.md; [`parse`] is their one definition.

use glam::DVec3;

use crate::compare::{Side, Tolerances, differences};
use crate::lang::Span;
use crate::lang::degrees::in_radians_help;
use crate::lang::number::format_number;
use crate::scene::{Camera, Light, Primitive, Shape};

use super::super::session::Session;

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

// ---------------------------------------------------------------- reading a check

/// The check written `text` (what follows `Check:`), or what is wrong
/// with it.
pub(crate) fn parse(text: &str) -> Result<Check, String> {
    let text = text.trim();
    let words: Vec<&str> = text.split_whitespace().collect();
    match words.as_slice() {
        ["the", "scene", "depends", "on", "time"] => return Ok(Check::DependsOnTime),
        ["the", "scene", "matches", "the", "goal"] => return Ok(Check::MatchesGoal),
        ["procedure", ..] => return parse_procedure(text["procedure".len()..].trim()),
        _ => {}
    }
    let clauses: Vec<&str> = text.split(',').map(str::trim).collect();
    let (head, rest) = clauses.split_first().expect("split gives one part at least");
    let head_words: Vec<&str> = head.split_whitespace().collect();
    match head_words.as_slice() {
        ["camera", condition @ ..] => {
            let mut conditions = parse_conditions(rest)?;
            if !condition.is_empty() {
                conditions.insert(0, parse_condition(&condition.join(" "))?);
            }
            Ok(Check::Camera(conditions))
        }
        ["ambient", comparison @ ..] if rest.is_empty() => {
            Ok(Check::Ambient(parse_comparison(Quantity::Intensity, &comparison.join(" "))?))
        }
        ["number", name] if rest.is_empty() => Ok(Check::Number { name: name.to_string(), value: None }),
        ["number", name, comparison @ ..] if rest.is_empty() => {
            let value = parse_comparison(Quantity::X, &comparison.join(" "))?;
            Ok(Check::Number { name: name.to_string(), value: Some(value) })
        }
        ["object", name, "is", "a", kind] => {
            let (kind, _) = ShapeKind::read(kind).ok_or_else(|| format!("`{kind}` is not sphere, box or plane"))?;
            Ok(Check::Object { name: name.to_string(), kind, conditions: parse_conditions(rest)? })
        }
        [count, kind, more @ ..] => parse_parts(count, kind, &more.join(" "), rest),
        _ => Err(unknown_check()),
    }
}

fn unknown_check() -> String {
    "a check starts with `camera`, `ambient`, `a`, `an` or a count (`3 spheres`), `number`, `object`, \
     `procedure`, `the scene depends on time` or `the scene matches the goal`"
        .to_string()
}

/// `post(x)`: the procedure's name and its parameters.
fn parse_procedure(text: &str) -> Result<Check, String> {
    let usage = || "write a procedure as `procedure NAME(PARAMETER, ...)`".to_string();
    let (name, parameters) = text.strip_suffix(')').and_then(|t| t.split_once('(')).ok_or_else(usage)?;
    let name = name.trim();
    if name.is_empty() || name.contains(char::is_whitespace) {
        return Err(usage());
    }
    let parameters = parameters.split(',').filter(|p| !p.trim().is_empty()).count();
    Ok(Check::Procedure { name: name.to_string(), parameters })
}

/// `a light from above right`, `3 spheres like ball`, with the clauses after.
fn parse_parts(count: &str, kind: &str, first: &str, rest: &[&str]) -> Result<Check, String> {
    let count = match count {
        "a" | "an" | "one" => 1,
        number => number.parse::<usize>().ok().filter(|&n| n > 0).ok_or_else(unknown_check)?,
    };
    let clauses: Vec<&str> = std::iter::once(first).filter(|c| !c.is_empty()).chain(rest.iter().copied()).collect();
    if kind == "light" || kind == "lights" {
        let mut wanted = LightsWanted { count, from: Vec::new(), conditions: Vec::new(), weaker_than: None };
        for clause in clauses {
            if let Some(sides) = clause.strip_prefix("weaker than the light from ") {
                wanted.weaker_than = Some(parse_directions(sides)?);
            } else if let Some(sides) = clause.strip_prefix("from ") {
                wanted.from = parse_directions(sides)?;
            } else {
                wanted.conditions.push(parse_condition(clause)?);
            }
        }
        return Ok(Check::Lights(wanted));
    }
    let (kind, _) = ShapeKind::read(kind).ok_or_else(unknown_check)?;
    let mut wanted = ShapesWanted {
        count,
        kind,
        conditions: Vec::new(),
        like: None,
        moving: false,
        one_put: false,
        arrangement: Vec::new(),
    };
    for clause in clauses {
        if let Some(name) = clause.strip_prefix("like ") {
            wanted.like = Some(name.trim().to_string());
        } else if clause == "moving" {
            wanted.moving = true;
        } else if clause == "from one put" {
            wanted.one_put = true;
        } else if let Some((_, arrangement)) = ARRANGEMENTS.iter().find(|(name, _)| *name == clause) {
            wanted.arrangement.push(*arrangement);
        } else {
            wanted.conditions.push(parse_condition(clause)?);
        }
    }
    Ok(Check::Shapes(wanted))
}

fn parse_directions(text: &str) -> Result<Vec<Direction>, String> {
    let side = |word: &str| {
        DIRECTIONS
            .iter()
            .find(|(name, _)| *name == word)
            .map(|(_, d)| *d)
            .ok_or_else(|| format!("`{word}` is not a side: above, below, right, left, front or back"))
    };
    text.split_whitespace().filter(|w| *w != "and").map(side).collect()
}

fn parse_conditions(clauses: &[&str]) -> Result<Vec<Condition>, String> {
    clauses.iter().map(|clause| parse_condition(clause)).collect()
}

/// `radius 2`, `ks at least 0.3`, `color 255 120 40 within 60`.
fn parse_condition(clause: &str) -> Result<Condition, String> {
    let (name, comparison) = clause.trim().split_once(char::is_whitespace).unwrap_or((clause.trim(), ""));
    let Some(&(_, quantity, _)) = QUANTITIES.iter().find(|(known, _, _)| *known == name) else {
        let names: Vec<&str> = QUANTITIES.iter().map(|(name, _, _)| *name).collect();
        return Err(format!("`{name}` is not a property a check knows: {}", names.join(", ")));
    };
    Ok(Condition { quantity, comparison: parse_comparison(quantity, comparison)? })
}

/// `2`, `below 0.2`, `255 120 40 within 60`, for `quantity`.
fn parse_comparison(quantity: Quantity, text: &str) -> Result<Comparison, String> {
    let text = text.trim();
    let (relation, text) = RELATIONS
        .iter()
        .find_map(|(word, relation)| Some((*relation, text.strip_prefix(word)?.trim_start())))
        .unwrap_or((Relation::Equal, text));
    let (values, within) = match text.split_once(" within ") {
        Some((values, within)) => (values, Some(parse_number(within.trim())?)),
        None => (text, None),
    };
    let goal: Vec<f64> = values.split_whitespace().map(parse_number).collect::<Result<_, _>>()?;
    let name = quantity.name();
    match (goal.len(), quantity.arity()) {
        (1, 1) | (3, 3) => {}
        (_, 1) => return Err(format!("`{name}` takes one number")),
        _ => return Err(format!("`{name}` takes three numbers, with spaces between them")),
    }
    let within = within.unwrap_or_else(|| quantity.default_within(&goal));
    Ok(Comparison { relation, goal, within })
}

/// A number as a check writes it: `0.7`, `-3`, `pi/4`, `2*pi`, `-pi/2`.
fn parse_number(text: &str) -> Result<f64, String> {
    let (sign, body) = match text.strip_prefix('-') {
        Some(body) => (-1.0, body),
        None => (1.0, text),
    };
    let factor = |word: &str| match word {
        "pi" => Some(std::f64::consts::PI),
        number => number.parse::<f64>().ok().filter(|n| n.is_finite()),
    };
    let (first, divisor) = match body.split_once('/') {
        Some((first, divisor)) => (first, factor(divisor)),
        None => (body, Some(1.0)),
    };
    let product = first.split('*').map(factor).try_fold(1.0, |product, f| Some(product * f?));
    match (product, divisor) {
        (Some(product), Some(divisor)) if divisor != 0.0 => Ok(sign * product / divisor),
        _ => Err(format!("`{text}` is not a number (numbers are like 0.7, -3, pi/4, 2*pi)")),
    }
}

// ---------------------------------------------------------------- checking

/// `Ok` when `check` holds in the `learner`'s scene; `goal` is the step's
/// goal scene, for [`Check::MatchesGoal`] (`None` if it could not be built).
pub(crate) fn holds(check: &Check, learner: &Session, goal: Option<&Session>) -> Result<(), Shortfall> {
    match check {
        Check::Camera(conditions) => camera_holds(conditions, learner),
        Check::Ambient(comparison) => {
            let level = learner.scene().ambient;
            match learner.has_ambient() && comparison.miss(Quantity::Intensity, &[level]) == 0.0 {
                true => Ok(()),
                false if !learner.has_ambient() => Err(Shortfall::new(format!(
                    "there is no `ambient` yet (the default {} is used); the goal: {}",
                    format_number(level),
                    comparison.words(Quantity::Intensity)
                ))),
                false => Err(Shortfall {
                    text: format!(
                        "your ambient light is {}; the goal: {}",
                        format_number(level),
                        comparison.words(Quantity::Intensity)
                    ),
                    made_at: learner.origins().ambient,
                }),
            }
        }
        Check::Lights(wanted) => lights_hold(wanted, learner),
        Check::Shapes(wanted) => shapes_hold(wanted, learner),
        Check::Number { name, value } => number_holds(name, value.as_ref(), learner),
        Check::Object { name, kind, conditions } => object_holds(name, *kind, conditions, learner),
        Check::Procedure { name, parameters } => procedure_holds(name, *parameters, learner),
        Check::DependsOnTime => match learner.scene().timed_primitives.is_empty() {
            true => Err(Shortfall::new("nothing in your scene depends on `time`")),
            false => Ok(()),
        },
        Check::MatchesGoal => {
            let Some(goal) = goal else {
                return Err(Shortfall::new("the step's goal scene does not run"));
            };
            let found = differences(side(goal), side(learner), &Tolerances::DEFAULT);
            match found.first() {
                None => Ok(()),
                Some(first) => Err(Shortfall::new(first.words(learner.sources()).replace("reference", "goal"))),
            }
        }
    }
}

/// `Ok` unless an angle of the learner's program looks like degrees (a
/// lesson never asks for a turn of 45 radians): the check that comes
/// before every step's own, since such a turn may still pass them by chance.
pub(crate) fn no_degrees(learner: &Session) -> Result<(), Shortfall> {
    let Some(origin) = learner.origins().degrees.first() else {
        return Ok(());
    };
    let angle = format_number(origin.angle);
    Err(Shortfall {
        text: format!(
            "the angle {angle} {} looks like degrees, but angles are in radians: {}",
            place_words(learner, origin.span),
            in_radians_help(origin.angle, "")
        ),
        made_at: Some(origin.span),
    })
}

/// A session's scene as the grader compares it.
fn side(session: &Session) -> Side<'_> {
    Side { scene: session.scene(), origins: session.origins() }
}

/// What the conditions that `part` misses say: "radius 1 (the goal: 2) and
/// ...", or `None` if it meets them all.
fn misses(conditions: &[Condition], part: Part) -> Option<String> {
    let missed: Vec<String> = conditions.iter().filter(|c| c.miss(part) != Some(0.0)).map(|c| c.words(part)).collect();
    (!missed.is_empty()).then(|| missed.join(" and "))
}

/// How far `part` is from meeting `conditions`: how many it misses, then by
/// how much in all.
fn distance(conditions: &[Condition], part: Part) -> (usize, f64) {
    let gaps: Vec<f64> = conditions.iter().map(|c| c.miss(part).unwrap_or(f64::INFINITY)).collect();
    (gaps.iter().filter(|&&gap| gap > 0.0).count(), gaps.iter().sum())
}

/// Where `span` is, as the learner reads it: "at line 3" of a file or a
/// script; "in input [2]" (its line too, if it has several) of an input
/// typed in the session, which the prompt numbers.
fn place_words(learner: &Session, span: Span) -> String {
    let file = learner.sources().get(span.source);
    let (line, _) = file.line_col(span.start as usize);
    let typed = file.name.strip_prefix("<input ").and_then(|rest| rest.strip_suffix('>'));
    match typed {
        Some(number) if file.text.trim_end().contains('\n') => format!("at line {line} of input [{number}]"),
        Some(number) => format!("in input [{number}]"),
        None => format!("at line {line}"),
    }
}

fn camera_holds(conditions: &[Condition], learner: &Session) -> Result<(), Shortfall> {
    let camera = learner.scene().camera;
    let made_at = learner.origins().camera.as_ref().map(|origin| origin.item);
    let Some(made_at) = made_at.filter(|_| learner.has_camera()) else {
        return Err(Shortfall::new("there is no `camera` yet (the default one is used)"));
    };
    match misses(conditions, Part::Camera(&camera)) {
        None => Ok(()),
        Some(missed) => Err(Shortfall {
            text: format!("your camera, {}, has {missed}", place_words(learner, made_at)),
            made_at: Some(made_at),
        }),
    }
}

fn lights_hold(wanted: &LightsWanted, learner: &Session) -> Result<(), Shortfall> {
    let scene = learner.scene();
    let origins = learner.origins();
    let lights = || scene.lights.iter().zip(&origins.lights);
    if scene.lights.is_empty() {
        return Err(Shortfall::new("your scene has no light yet"));
    }
    let comes_from = |sides: &[Direction], light: &Light| sides.iter().all(|side| side.holds(light.direction));
    let brighter = match &wanted.weaker_than {
        None => None,
        Some(sides) => {
            let Some(other) = scene.lights.iter().find(|light| comes_from(sides, light)) else {
                return Err(Shortfall::new(format!("no light comes from {} yet", sides_words(sides))));
            };
            Some(other.intensity)
        }
    };
    let meets = |light: &Light| {
        comes_from(&wanted.from, light)
            && misses(&wanted.conditions, Part::Light(light)).is_none()
            && brighter.is_none_or(|brighter| light.intensity < brighter)
    };
    let good = scene.lights.iter().filter(|light| meets(light)).count();
    if good >= wanted.count {
        return Ok(());
    }
    // The closest light that misses: the one missing fewest of the sides and conditions.
    let score = |light: &Light| {
        let sides = wanted.from.iter().filter(|side| !side.holds(light.direction)).count();
        let weaker = usize::from(brighter.is_some_and(|brighter| light.intensity >= brighter));
        let (missed, by) = distance(&wanted.conditions, Part::Light(light));
        (sides + weaker + missed, by)
    };
    let closest =
        lights().filter(|(light, _)| !meets(light)).min_by(|a, b| score(a.0).partial_cmp(&score(b.0)).expect("no NaN"));
    let Some((light, origin)) = closest else {
        return Err(Shortfall::new(format!("your scene has {good} such lights; the goal: {}", wanted.count)));
    };
    let mut said = Vec::new();
    if !comes_from(&wanted.from, light) {
        let sides: Vec<Direction> =
            DIRECTIONS.iter().map(|(_, side)| *side).filter(|side| side.holds(light.direction)).collect();
        said.push(format!(
            "points towards {}, so it comes from {}; the goal: from {}",
            numbers_in_words(&light.direction.to_array()),
            if sides.is_empty() { "no side in particular".to_string() } else { sides_words(&sides) },
            sides_words(&wanted.from)
        ));
    }
    if let Some(brighter) = brighter.filter(|&brighter| light.intensity >= brighter) {
        said.push(format!(
            "has intensity {}, not weaker than the {}",
            format_number(light.intensity),
            format_number(brighter)
        ));
    }
    if let Some(missed) = misses(&wanted.conditions, Part::Light(light)) {
        said.push(format!("has {missed}"));
    }
    let short = if good > 0 {
        format!("{good} of the {} lights the goal asks are there; ", wanted.count)
    } else {
        String::new()
    };
    Err(Shortfall {
        text: format!("{short}your light {} {}", place_words(learner, origin.item), said.join("; and it ")),
        made_at: (good == 0).then_some(origin.item),
    })
}

/// "above, right and front".
fn sides_words(sides: &[Direction]) -> String {
    let names: Vec<&str> = sides.iter().map(|side| side.name()).collect();
    match names.split_last() {
        Some((last, [])) => last.to_string(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// The primitives of the scene, with the `put` that made each and whether it
/// depends on `time`.
fn placed(learner: &Session) -> Vec<(&Primitive, Option<Span>, bool)> {
    let (scene, origins) = (learner.scene(), learner.origins());
    let fixed = scene.primitives.iter().enumerate().map(|(i, p)| (p, origins.primitives.span_of(i), false));
    let timed = scene.timed_primitives.iter().enumerate().map(|(i, p)| (p, origins.timed_primitives.span_of(i), true));
    fixed.chain(timed).collect()
}

fn shapes_hold(wanted: &ShapesWanted, learner: &Session) -> Result<(), Shortfall> {
    let kind = wanted.kind;
    let all: Vec<_> = placed(learner).into_iter().filter(|(p, _, _)| ShapeKind::of(&p.shape) == kind).collect();
    if all.is_empty() {
        return Err(Shortfall::new(format!("your scene has no {} yet", kind.name())));
    }
    let like = match &wanted.like {
        None => None,
        Some(name) => match learner.global_object(name) {
            Some([first, ..]) => Some(*first),
            _ => return Err(Shortfall::new(format!("there is no object `{name}` to put"))),
        },
    };
    let is_like = |p: &Primitive| like.is_none_or(|model| same_but_place(&model, p));
    let meets = |(p, _, timed): &(&Primitive, Option<Span>, bool)| {
        misses(&wanted.conditions, Part::Primitive(p)).is_none() && is_like(p) && (*timed || !wanted.moving)
    };
    let good: Vec<_> = all.iter().filter(|part| meets(part)).collect();
    if good.is_empty() {
        let score = |(p, _, timed): &&(&Primitive, Option<Span>, bool)| {
            let (missed, by) = distance(&wanted.conditions, Part::Primitive(p));
            let others = usize::from(!is_like(p)) + usize::from(wanted.moving && !timed);
            (missed + others, by)
        };
        let (primitive, made_at, timed) =
            *all.iter().min_by(|a, b| score(a).partial_cmp(&score(b)).expect("no NaN")).expect("not empty");
        let mut said = Vec::new();
        if let Some(missed) = misses(&wanted.conditions, Part::Primitive(primitive)) {
            said.push(format!("has {missed}"));
        }
        if !is_like(primitive) {
            said.push(format!("is not like `{}` (another size or material)", wanted.like.as_deref().unwrap_or("")));
        }
        if wanted.moving && !timed {
            said.push("does not depend on `time`".to_string());
        }
        let at = made_at.map(|span| format!(", put {},", place_words(learner, span))).unwrap_or_default();
        return Err(Shortfall { text: format!("your {}{at} {}", kind.name(), said.join(", and ")), made_at });
    }
    // Those that meet the conditions, by the `put` that made them if they must share one.
    let mut groups: Vec<Vec<&Primitive>> = Vec::new();
    if wanted.one_put {
        let mut puts: Vec<Option<Span>> = Vec::new();
        for (p, span, _) in &good {
            match puts.iter().position(|s| s == span) {
                Some(at) => groups[at].push(p),
                None => {
                    puts.push(*span);
                    groups.push(vec![p]);
                }
            }
        }
    } else {
        groups.push(good.iter().map(|(p, _, _)| *p).collect());
    }
    let floors = floors(learner);
    let most = groups.iter().map(|group| arranged(group, &wanted.arrangement, &floors)).max().unwrap_or(0);
    if most >= wanted.count {
        return Ok(());
    }
    let mut how: Vec<String> = wanted.arrangement.iter().map(|a| a.name().to_string()).collect();
    if wanted.one_put {
        how.insert(0, "made by one `put`".to_string());
    }
    if let Some(name) = &wanted.like {
        how.insert(0, format!("like `{name}`"));
    }
    let how = if how.is_empty() { String::new() } else { format!(" ({})", how.join(", ")) };
    let plural = if wanted.count == 1 { kind.name() } else { kind.plural() };
    Err(Shortfall::new(format!("your scene has {most} of the {} {plural} the goal asks for{how}", wanted.count)))
}

/// Whether `a` and `b` have the same size, orientation and material,
/// wherever they are.
fn same_but_place(a: &Primitive, b: &Primitive) -> bool {
    let shape = match (a.shape, b.shape) {
        (Shape::Sphere { radius: r, .. }, Shape::Sphere { radius: s, .. }) => close(r, s),
        (Shape::Box { half: h, axes: a, .. }, Shape::Box { half: k, axes: b, .. }) => {
            h.abs_diff_eq(k, 1e-9) && a.abs_diff_eq(b, 1e-9)
        }
        (Shape::Plane { normal: n, .. }, Shape::Plane { normal: m, .. }) => n.abs_diff_eq(m, 1e-9),
        _ => false,
    };
    shape && a.material == b.material
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * (1.0 + a.abs().max(b.abs()))
}

/// The heights of the planes of the scene that face up.
fn floors(learner: &Session) -> Vec<f64> {
    let up = |normal: DVec3| normal.abs_diff_eq(DVec3::Y, 1e-9);
    let planes = learner.scene().all_primitives().filter_map(|p| match p.shape {
        Shape::Plane { normal, shift } if up(normal) => Some(shift),
        _ => None,
    });
    planes.collect()
}

/// The most primitives of `group` that stand as `arrangement` says, on
/// one of `floors` if it says so.
fn arranged(group: &[&Primitive], arrangement: &[Arrangement], floors: &[f64]) -> usize {
    if arrangement.is_empty() {
        return group.len();
    }
    let along_x = arrangement.contains(&Arrangement::SideBySide);
    let key = |p: &&Primitive| center_of(p).map_or(0.0, |c| if along_x { c.x } else { c.y });
    let mut sorted = group.to_vec();
    sorted.sort_by(|a, b| key(a).total_cmp(&key(b)));
    let follows = |below: &Primitive, next: &Primitive| arrangement.iter().all(|a| a.follows(below, next));
    let on_floor = |p: &Primitive| {
        let bottom = center_of(p).map(|c| c.y - extents(&p.shape).y);
        bottom.is_some_and(|bottom| floors.iter().any(|&floor| close(floor, bottom)))
    };
    let may_start = |p: &Primitive| !arrangement.contains(&Arrangement::OnTheFloor) || on_floor(p);
    (0..sorted.len().min(ARRANGEMENT_STARTS))
        .filter(|&start| may_start(sorted[start]))
        .map(|start| {
            let mut last = sorted[start];
            let mut count = 1;
            for next in &sorted[start + 1..] {
                if follows(last, next) {
                    last = next;
                    count += 1;
                }
            }
            count
        })
        .max()
        .unwrap_or(0)
}

fn center_of(p: &Primitive) -> Option<DVec3> {
    match p.shape {
        Shape::Sphere { center, .. } | Shape::Box { center, .. } => Some(center),
        Shape::Plane { .. } => None,
    }
}

impl Arrangement {
    /// Whether `next` (after `last` along x, or above it) stands as this
    /// arrangement says.
    fn follows(self, last: &Primitive, next: &Primitive) -> bool {
        let (Some(a), Some(b)) = (center_of(last), center_of(next)) else {
            return false;
        };
        let (ea, eb) = (extents(&last.shape), extents(&next.shape));
        match self {
            Arrangement::SideBySide => close(a.y, b.y) && close(a.z, b.z) && b.x - a.x >= ea.x + eb.x - 1e-6,
            Arrangement::Stacked => close(a.x, b.x) && close(a.z, b.z) && b.y > a.y && b.y - eb.y <= a.y + ea.y + 1e-6,
            Arrangement::Shrinking => eb.max_element() < ea.max_element() && !close(eb.max_element(), ea.max_element()),
            Arrangement::Rising => b.y > a.y && !close(a.y, b.y),
            Arrangement::OnTheFloor => true,
        }
    }
}

fn number_holds(name: &str, value: Option<&Comparison>, learner: &Session) -> Result<(), Shortfall> {
    let numbers = learner.numbers();
    let Some((_, found)) = numbers.iter().find(|(defined, _)| &**defined == name) else {
        let near = numbers.iter().find(|(defined, _)| defined.eq_ignore_ascii_case(name));
        return Err(Shortfall::new(match near {
            Some((other, _)) => format!("you named it `{other}`; names tell capitals apart: the goal is `{name}`"),
            None => format!("no number is named `{name}` yet"),
        }));
    };
    match value {
        Some(comparison) if comparison.miss(Quantity::X, &[*found]) > 0.0 => Err(Shortfall::new(format!(
            "your `{name}` is {}; the goal: {}",
            format_number(*found),
            comparison.words(Quantity::X)
        ))),
        _ => Ok(()),
    }
}

fn object_holds(name: &str, kind: ShapeKind, conditions: &[Condition], learner: &Session) -> Result<(), Shortfall> {
    let Some(primitives) = learner.global_object(name) else {
        let objects = learner.objects();
        let near = objects.iter().find(|(defined, _)| defined.eq_ignore_ascii_case(name));
        return Err(Shortfall::new(match near {
            Some((other, _)) => format!("you named it `{other}`; names tell capitals apart: the goal is `{name}`"),
            None => format!("no object is named `{name}` yet"),
        }));
    };
    let [primitive] = primitives else {
        return Err(Shortfall::new(format!(
            "your `{name}` is made of {} parts; the goal: one {}",
            primitives.len(),
            kind.name()
        )));
    };
    if ShapeKind::of(&primitive.shape) != kind {
        let is = ShapeKind::of(&primitive.shape).name();
        return Err(Shortfall::new(format!("your `{name}` is a {is}; the goal: a {}", kind.name())));
    }
    match misses(conditions, Part::Primitive(primitive)) {
        None => Ok(()),
        Some(missed) => Err(Shortfall::new(format!("your `{name}` has {missed}"))),
    }
}

fn procedure_holds(name: &str, parameters: usize, learner: &Session) -> Result<(), Shortfall> {
    let procedures = learner.procedures();
    let Some((_, params)) = procedures.iter().find(|(defined, _)| &**defined == name) else {
        let near = procedures.iter().find(|(defined, _)| defined.eq_ignore_ascii_case(name));
        return Err(Shortfall::new(match near {
            Some((other, _)) => format!("you named it `{other}`; names tell capitals apart: the goal is `{name}`"),
            None => format!("no procedure `{name}` is defined yet"),
        }));
    };
    match params.len() == parameters {
        true => Ok(()),
        false => {
            Err(Shortfall::new(format!("your `{name}` takes {} parameters; the goal: {parameters}", params.len())))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::Limits;
    use crate::repl::RenderSettings;

    fn session(program: &str) -> Session {
        let mut session = Session::new(RenderSettings::default(), Limits::default());
        session.submit("<test>", program, 0).expect("the program runs");
        session
    }

    fn check(check: &str, program: &str) -> Result<(), Shortfall> {
        let check = parse(check).expect("the check reads");
        holds(&check, &session(program), None)
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
        let goal = session("put sphere center 1, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end");
        let same =
            session("put translate sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end by 1, 0, 0 end");
        assert_eq!(holds(&Check::MatchesGoal, &same, Some(&goal)), Ok(()));
        let other = session("put sphere center 1, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 90 end");
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
