//! The differences between two evaluated scenes, part by part: the
//! primitives paired one to one whatever order or construction made them
//! ([`super::matching`]), then the camera, the lights and the ambient
//! light. Each difference keeps the places of its parts (spans, not
//! lines), and is put in words only when shown.

use glam::{DMat3, DVec3};
use serde_json::{Value, json};

use super::Tolerances;
use super::matching::assign;
use crate::lang::eval::Origins;
use crate::lang::number::format_number;
use crate::lang::{SourceMap, Span};
use crate::scene::{Light, Material, Primitive, Scene, Shape};

/// One side of a comparison: an evaluated scene and where its parts come from.
#[derive(Debug, Clone, Copy)]
pub struct Side<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// Where its parts come from in the program.
    pub origins: &'a Origins,
}

/// What kind of part of a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A sphere.
    Sphere,
    /// A plane.
    Plane,
    /// A box.
    Box,
    /// A light.
    Light,
    /// The camera.
    Camera,
    /// The ambient light.
    Ambient,
}

impl Kind {
    /// The kinds of primitive, in the order they are compared.
    const PRIMITIVES: [Kind; 3] = [Kind::Sphere, Kind::Plane, Kind::Box];

    /// Its name in words and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Sphere => "sphere",
            Kind::Plane => "plane",
            Kind::Box => "box",
            Kind::Light => "light",
            Kind::Camera => "camera",
            Kind::Ambient => "ambient light",
        }
    }

    /// "3 spheres", "1 box".
    fn counted(self, count: usize) -> String {
        let name = self.name();
        match count {
            1 => format!("1 {name}"),
            _ if self == Kind::Box => format!("{count} boxes"),
            _ => format!("{count} {name}s"),
        }
    }

    /// Whether a scene has one of these at most (no ordinal is said).
    fn is_single(self) -> bool {
        matches!(self, Kind::Camera | Kind::Ambient)
    }

    /// The kind of a primitive's shape.
    fn of(shape: &Shape) -> Kind {
        match shape {
            Shape::Sphere { .. } => Kind::Sphere,
            Shape::Plane { .. } => Kind::Plane,
            Shape::Box { .. } => Kind::Box,
        }
    }
}

/// One part of one scene: its kind, which one it is among its kind (from
/// 1, in the order the evaluation made them), and the instruction that
/// made it (`None` for the default camera or ambient light).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Part {
    /// What it is.
    pub kind: Kind,
    /// Which one among its kind, from 1.
    pub ordinal: usize,
    /// The `put`, `light`, `camera` or `ambient` that made it.
    pub place: Option<Span>,
}

impl Part {
    /// "the third sphere, put at line 12,"; for the reference's parts
    /// (`reference`), "the reference's second box, put at line 7 of
    /// ref.ray,"; "the default camera" where no instruction made it.
    fn words(&self, sources: &SourceMap, reference: bool) -> String {
        let whose = if reference { "the reference's" } else { "the" };
        let name = match self.kind.is_single() {
            true => self.kind.name().to_string(),
            false => format!("{} {}", ordinal(self.ordinal), self.kind.name()),
        };
        let verb = if Kind::PRIMITIVES.contains(&self.kind) { "put at" } else { "at" };
        match self.place {
            None => format!("{whose} default {name}"),
            Some(span) => {
                let file = sources.get(span.source);
                let (line, _) = file.line_col(span.start as usize);
                let of_file = if reference { format!(" of {}", file.name) } else { String::new() };
                format!("{whose} {name}, {verb} line {line}{of_file},")
            }
        }
    }

    /// The line of its place, if it has one.
    fn line(&self, sources: &SourceMap) -> Option<usize> {
        self.place.map(|span| sources.get(span.source).line_col(span.start as usize).0)
    }
}

/// A property of a part that two scenes may give different values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Property {
    /// The centre of a sphere or a box.
    Position,
    /// A sphere's radius.
    Radius,
    /// A box's lengths along its own axes.
    Lengths,
    /// How a box is turned: the farthest of its corners from the
    /// reference's (its one value).
    Orientation,
    /// The normal of a plane.
    Normal,
    /// A plane's distance from the origin along its normal.
    Shift,
    /// A surface's colour, 0 to 255.
    Colour,
    /// A surface's diffuse coefficient.
    Kd,
    /// A surface's specular coefficient.
    Ks,
    /// A surface's Phong exponent.
    Phong,
    /// The intensity of a light or of the ambient light.
    Intensity,
    /// The direction towards a light.
    Direction,
    /// The camera's distance from the origin.
    Distance,
    /// The camera's field of view.
    Angle,
}

impl Property {
    /// Its name in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Property::Position => "position",
            Property::Radius => "radius",
            Property::Lengths => "length",
            Property::Orientation => "orientation",
            Property::Normal => "normal",
            Property::Shift => "shift",
            Property::Colour => "colour",
            Property::Kd => "kd",
            Property::Ks => "ks",
            Property::Phong => "phong",
            Property::Intensity => "intensity",
            Property::Direction => "direction",
            Property::Distance => "distance",
            Property::Angle => "angle",
        }
    }

    /// What a part with `values` is, in words: "is at 1, 0, 0", "has
    /// colour 40, 40, 221"; `again` for the reference's, after the
    /// submission's ("has 40, 40, 220").
    fn phrase(self, values: &[f64], again: bool) -> String {
        let values = values.iter().map(|&value| format_number(value)).collect::<Vec<_>>().join(", ");
        match self {
            Property::Position => format!("is at {values}"),
            Property::Normal => format!("faces {values}"),
            Property::Direction => format!("points towards {values}"),
            _ if again => format!("has {values}"),
            _ => format!("has {} {values}", self.name()),
        }
    }
}

/// One way a submission's scene differs from the reference's.
#[derive(Debug, Clone, PartialEq)]
pub enum Difference {
    /// Two paired parts differ in one property.
    Differs {
        /// The submission's part.
        part: Part,
        /// The reference's part it is paired with.
        counterpart: Part,
        /// What differs.
        property: Property,
        /// The submission's values.
        submission: Vec<f64>,
        /// The reference's values.
        reference: Vec<f64>,
    },
    /// A part of the reference that the submission has no counterpart for.
    Missing {
        /// The reference's part.
        counterpart: Part,
        /// How many of its kind the submission has.
        submitted: usize,
        /// How many of its kind the reference has.
        expected: usize,
    },
    /// A part of the submission that the reference does not have.
    Extra {
        /// The submission's part.
        part: Part,
        /// How many of its kind the submission has.
        submitted: usize,
        /// How many of its kind the reference has.
        expected: usize,
    },
}

impl Difference {
    /// The difference in words, with the lines of its parts in `sources`:
    /// "the third sphere, put at line 12, has colour 40, 40, 221; the
    /// reference's has 40, 40, 220".
    pub fn words(&self, sources: &SourceMap) -> String {
        match self {
            Difference::Differs { part, property: Property::Orientation, submission, .. } => format!(
                "{} is turned otherwise: its corners are up to {} from the reference's",
                part.words(sources, false),
                format_number(submission[0])
            ),
            Difference::Differs { part, property, submission, reference, .. } => format!(
                "{} {}; the reference's {}",
                part.words(sources, false),
                property.phrase(submission, false),
                property.phrase(reference, true)
            ),
            Difference::Missing { counterpart, submitted, expected } => format!(
                "{} is missing (the submission has {}, the reference {})",
                counterpart.words(sources, true),
                counterpart.kind.counted(*submitted),
                expected
            ),
            Difference::Extra { part, submitted, expected } => format!(
                "{} is not in the reference (the submission has {}, the reference {})",
                part.words(sources, false),
                part.kind.counted(*submitted),
                expected
            ),
        }
    }

    /// The difference as one JSON object: `kind`, `ordinal`, `line` (the
    /// submission's part), `reference_ordinal`, `reference_line` (the
    /// reference's), `property` (or `"missing"`, `"extra"`), the values
    /// `submission` and `reference`, and `message`, the words.
    pub fn to_json(&self, sources: &SourceMap) -> Value {
        let (part, counterpart, property, submission, reference) = match self {
            Difference::Differs { part, counterpart, property, submission, reference } => {
                (Some(part), Some(counterpart), property.name(), json!(submission), json!(reference))
            }
            Difference::Missing { counterpart, .. } => (None, Some(counterpart), "missing", Value::Null, Value::Null),
            Difference::Extra { part, .. } => (Some(part), None, "extra", Value::Null, Value::Null),
        };
        let kind = part.or(counterpart).map(|part| part.kind.name());
        json!({
            "kind": kind,
            "ordinal": part.map(|part| part.ordinal),
            "line": part.and_then(|part| part.line(sources)),
            "reference_ordinal": counterpart.map(|part| part.ordinal),
            "reference_line": counterpart.and_then(|part| part.line(sources)),
            "property": property,
            "submission": submission,
            "reference": reference,
            "message": self.words(sources),
        })
    }
}

/// "first", ..., "tenth", then "11th", "21st", "102nd", "113th".
pub fn ordinal(n: usize) -> String {
    const WORDS: [&str; 10] =
        ["first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth", "tenth"];
    if let Some(word) = n.checked_sub(1).and_then(|index| WORDS.get(index)) {
        return word.to_string();
    }
    let suffix = match (n % 10, n % 100) {
        (_, 11..=13) => "th",
        (1, _) => "st",
        (2, _) => "nd",
        (3, _) => "rd",
        _ => "th",
    };
    format!("{n}{suffix}")
}

/// Every difference between the `submission`'s scene and the
/// `reference`'s, within `tolerances`: the primitives of each kind
/// (paired ones that differ, then missing ones, then extra ones), the
/// camera, the lights, the ambient light.
pub fn differences(reference: Side, submission: Side, tolerances: &Tolerances) -> Vec<Difference> {
    let units = Units::of(reference.scene, tolerances);
    let mut found = Vec::new();
    for kind in Kind::PRIMITIVES {
        let expected = primitives_of(reference, kind);
        let submitted = primitives_of(submission, kind);
        let pairs =
            assign(&expected, &submitted, |a, b| units.cost(&a.primitive, &b.primitive), |p| units.key(&p.primitive));
        let counts = (submitted.len(), expected.len());
        found.extend(paired_differences(&pairs, &expected, &submitted, counts, |a, b| units.compare(a, b)));
    }
    found.extend(camera_differences(reference, submission, &units));
    let expected = lights_of(reference);
    let submitted = lights_of(submission);
    let pairs = assign(&expected, &submitted, |a, b| units.light_cost(a, b), |light| units.light_key(light));
    let counts = (submitted.len(), expected.len());
    found.extend(paired_differences(&pairs, &expected, &submitted, counts, |a, b| units.compare_lights(a, b)));
    found.extend(ambient_differences(reference, submission, &units));
    found
}

/// A part of a scene with what it is made of.
#[derive(Debug, Clone, Copy)]
struct Placed<T> {
    part: Part,
    primitive: T,
}

/// The primitives of `kind` in `side`'s scene, in the order made.
fn primitives_of(side: Side, kind: Kind) -> Vec<Placed<Primitive>> {
    let static_count = side.scene.primitives.len();
    let of_kind = side.scene.all_primitives().enumerate().filter(|(_, p)| Kind::of(&p.shape) == kind);
    of_kind
        .enumerate()
        .map(|(n, (index, primitive))| Placed {
            part: Part { kind, ordinal: n + 1, place: side.origins.put_of(index, static_count) },
            primitive: *primitive,
        })
        .collect()
}

/// The lights of `side`'s scene, in the program's order.
fn lights_of(side: Side) -> Vec<Placed<Light>> {
    let lights = side.scene.lights.iter().enumerate();
    lights
        .map(|(index, light)| Placed {
            part: Part { kind: Kind::Light, ordinal: index + 1, place: side.origins.lights.get(index).map(|o| o.item) },
            primitive: *light,
        })
        .collect()
}

/// The differences of paired parts (`compare` gives each pair's differing
/// properties), in the submission's order, then the reference's parts
/// left without a pair, then the submission's; `counts` are how many
/// parts the submission and the reference have.
fn paired_differences<T>(
    pairs: &[(usize, usize)],
    expected: &[Placed<T>],
    submitted: &[Placed<T>],
    (submission_count, reference_count): (usize, usize),
    compare: impl Fn(&T, &T) -> Vec<(Property, Vec<f64>, Vec<f64>)>,
) -> Vec<Difference> {
    let mut by_submission: Vec<&(usize, usize)> = pairs.iter().collect();
    by_submission.sort_by_key(|&&(_, s)| s);
    let mut found = Vec::new();
    for &&(r, s) in &by_submission {
        for (property, submission, reference) in compare(&submitted[s].primitive, &expected[r].primitive) {
            let (part, counterpart) = (submitted[s].part, expected[r].part);
            found.push(Difference::Differs { part, counterpart, property, submission, reference });
        }
    }
    let mut reference_paired = vec![false; expected.len()];
    let mut submission_paired = vec![false; submitted.len()];
    for &(r, s) in pairs {
        (reference_paired[r], submission_paired[s]) = (true, true);
    }
    let (submitted_count, expected_count) = (submission_count, reference_count);
    for (counterpart, _) in
        expected.iter().map(|placed| placed.part).zip(reference_paired).filter(|(_, paired)| !paired)
    {
        found.push(Difference::Missing { counterpart, submitted: submitted_count, expected: expected_count });
    }
    for (part, _) in submitted.iter().map(|placed| placed.part).zip(submission_paired).filter(|(_, paired)| !paired) {
        found.push(Difference::Extra { part, submitted: submitted_count, expected: expected_count });
    }
    found
}

/// The camera's differences.
fn camera_differences(reference: Side, submission: Side, units: &Units) -> Vec<Difference> {
    let part = |side: Side| Part { kind: Kind::Camera, ordinal: 1, place: side.origins.camera.map(|o| o.item) };
    let (expected, submitted) = (reference.scene.camera, submission.scene.camera);
    let properties = [
        (Property::Distance, submitted.distance, expected.distance, units.length),
        (Property::Angle, submitted.angle, expected.angle, units.number(expected.angle)),
    ];
    single_differences(part(submission), part(reference), &properties)
}

/// The ambient light's differences.
fn ambient_differences(reference: Side, submission: Side, units: &Units) -> Vec<Difference> {
    let part = |side: Side| Part { kind: Kind::Ambient, ordinal: 1, place: side.origins.ambient };
    let (expected, submitted) = (reference.scene.ambient, submission.scene.ambient);
    single_differences(
        part(submission),
        part(reference),
        &[(Property::Intensity, submitted, expected, units.number(expected))],
    )
}

/// The differences of a part that each scene has one of: each property
/// `(property, submission, reference, tolerance)` whose values are further
/// apart than the tolerance.
fn single_differences(part: Part, counterpart: Part, properties: &[(Property, f64, f64, f64)]) -> Vec<Difference> {
    let differing =
        properties.iter().filter(|(_, submitted, expected, tolerance)| (submitted - expected).abs() > *tolerance);
    differing
        .map(|&(property, submitted, expected, _)| Difference::Differs {
            part,
            counterpart,
            property,
            submission: vec![submitted],
            reference: vec![expected],
        })
        .collect()
}

/// The tolerances in the units of the values compared: lengths in the
/// reference scene's own units.
struct Units {
    /// The largest difference of two lengths that agree.
    length: f64,
    /// The largest difference of two colour components (0 to 255) that agree.
    colour: f64,
    /// [`Tolerances::coefficient`].
    coefficient: f64,
}

/// The values of a property, the submission's and the reference's.
type Values = (Property, Vec<f64>, Vec<f64>);

impl Units {
    /// The units for comparing with `reference`.
    fn of(reference: &Scene, tolerances: &Tolerances) -> Units {
        Units {
            length: tolerances.length * scene_size(reference),
            colour: tolerances.colour,
            coefficient: tolerances.coefficient,
        }
    }

    /// The largest difference from `expected` of a number that agrees
    /// with it (coefficients, intensities, angles, directions).
    fn number(&self, expected: f64) -> f64 {
        self.coefficient * expected.abs().max(1.0)
    }

    /// How unlike two primitives of one kind are: the sum of their
    /// differences, each in its tolerance (1 is a difference just
    /// allowed), for the pairing.
    fn cost(&self, a: &Primitive, b: &Primitive) -> f64 {
        let geometry = match (a.shape, b.shape) {
            (Shape::Sphere { center: c, radius: r }, Shape::Sphere { center, radius }) => {
                c.distance(center) / self.length + (r - radius).abs() / self.length
            }
            (Shape::Plane { normal: n, shift: d }, Shape::Plane { normal, shift }) => {
                n.distance(normal) / self.coefficient + (d - shift).abs() / self.length
            }
            (Shape::Box { .. }, Shape::Box { .. }) => {
                let (box_a, box_b) = (BoxShape::of(&a.shape), BoxShape::of(&b.shape));
                let lengths = DVec3::from(box_a.sorted_lengths()) - DVec3::from(box_b.sorted_lengths());
                (box_a.center.distance(box_b.center) + lengths.abs().element_sum() + box_a.corner_distance(&box_b))
                    / self.length
            }
            _ => f64::INFINITY,
        };
        geometry + self.material_cost(&a.material, &b.material)
    }

    /// How unlike two materials are, as [`Units::cost`] counts.
    fn material_cost(&self, a: &Material, b: &Material) -> f64 {
        (a.color - b.color).abs().element_sum() * 255.0 / self.colour
            + ((a.kd - b.kd).abs() + (a.ks - b.ks).abs() + (a.phong - b.phong).abs() / a.phong.abs().max(1.0))
                / self.coefficient
    }

    /// The numbers that are equal for two primitives that agree (but for
    /// those on either side of a rounding), for pairing large scenes.
    fn key(&self, primitive: &Primitive) -> Vec<i64> {
        let mut numbers: Vec<f64> = match primitive.shape {
            Shape::Sphere { center, radius } => vec![center.x, center.y, center.z, radius],
            Shape::Plane { normal, shift } => vec![normal.x, normal.y, normal.z, shift],
            Shape::Box { .. } => {
                let shape = BoxShape::of(&primitive.shape);
                let [x, y, z] = shape.sorted_lengths();
                vec![shape.center.x, shape.center.y, shape.center.z, x, y, z]
            }
        };
        numbers.iter_mut().for_each(|number| *number /= self.length);
        let color = primitive.material.color * 255.0 / self.colour;
        numbers.extend([color.x, color.y, color.z]);
        numbers.iter().map(|number| number.round() as i64).collect()
    }

    /// Each property of the `submitted` primitive that differs from the
    /// `expected` one's.
    fn compare(&self, submitted: &Primitive, expected: &Primitive) -> Vec<Values> {
        let mut found = Vec::new();
        match (submitted.shape, expected.shape) {
            (Shape::Sphere { center: c, radius: r }, Shape::Sphere { center, radius }) => {
                found.extend(differing(Property::Position, c.to_array(), center.to_array(), self.length));
                found.extend(differing(Property::Radius, [r], [radius], self.length));
            }
            (Shape::Plane { normal: n, shift: d }, Shape::Plane { normal, shift }) => {
                found.extend(differing(Property::Normal, n.to_array(), normal.to_array(), self.coefficient));
                found.extend(differing(Property::Shift, [d], [shift], self.length));
            }
            (Shape::Box { .. }, Shape::Box { .. }) => {
                let (a, b) = (BoxShape::of(&submitted.shape), BoxShape::of(&expected.shape));
                found.extend(differing(Property::Position, a.center.to_array(), b.center.to_array(), self.length));
                let sized = differing(Property::Lengths, a.sorted_lengths(), b.sorted_lengths(), self.length);
                let turned = a.corner_distance(&b);
                if sized.is_some() {
                    // Said in each box's own order, as the program writes it.
                    found.push((Property::Lengths, a.lengths().to_vec(), b.lengths().to_vec()));
                } else if found.is_empty() && turned > self.length {
                    found.push((Property::Orientation, vec![turned], Vec::new()));
                }
            }
            _ => {}
        }
        found.extend(self.compare_materials(&submitted.material, &expected.material));
        found
    }

    /// Each property of the `submitted` material that differs from the
    /// `expected` one's (colours from 0 to 255, as the program writes them).
    fn compare_materials(&self, submitted: &Material, expected: &Material) -> Vec<Values> {
        let as_written = |color: DVec3| (color * 255.0).to_array();
        let colour = differing(Property::Colour, as_written(submitted.color), as_written(expected.color), self.colour);
        let coefficients = [
            (Property::Kd, submitted.kd, expected.kd),
            (Property::Ks, submitted.ks, expected.ks),
            (Property::Phong, submitted.phong, expected.phong),
        ];
        let coefficients =
            coefficients.into_iter().filter_map(|(property, a, b)| differing(property, [a], [b], self.number(b)));
        colour.into_iter().chain(coefficients).collect()
    }

    /// How unlike two lights are, as [`Units::cost`] counts.
    fn light_cost(&self, a: &Placed<Light>, b: &Placed<Light>) -> f64 {
        let (a, b) = (a.primitive, b.primitive);
        (a.direction.distance(b.direction) + (a.intensity - b.intensity).abs()) / self.coefficient
    }

    /// The numbers that are equal for two lights that agree, as [`Units::key`].
    fn light_key(&self, light: &Placed<Light>) -> Vec<i64> {
        let light = light.primitive;
        let numbers = [light.direction.x, light.direction.y, light.direction.z, light.intensity];
        numbers.iter().map(|number| (number / self.coefficient).round() as i64).collect()
    }

    /// Each property of the `submitted` light that differs from the `expected` one's.
    fn compare_lights(&self, submitted: &Light, expected: &Light) -> Vec<Values> {
        let (a, b) = (submitted.direction.to_array(), expected.direction.to_array());
        let direction = differing(Property::Direction, a, b, self.coefficient);
        let intensity = [submitted.intensity];
        let intensity =
            differing(Property::Intensity, intensity, [expected.intensity], self.number(expected.intensity));
        direction.into_iter().chain(intensity).collect()
    }
}

/// `property` with the values `submitted` and `expected`, if some
/// component of one is further than `tolerance` from the other's. A value
/// a thousandth of the tolerance from 0 is said as 0 (a turn by `pi / 2`
/// leaves 1e-16 where 0 was meant).
fn differing<const N: usize>(
    property: Property,
    submitted: [f64; N],
    expected: [f64; N],
    tolerance: f64,
) -> Option<Values> {
    let apart = submitted.iter().zip(&expected).any(|(a, b)| (a - b).abs() > tolerance);
    let said =
        |values: [f64; N]| values.map(|value| if value.abs() < tolerance / 1000.0 { 0.0 } else { value }).to_vec();
    apart.then(|| (property, said(submitted), said(expected)))
}

/// The size of a scene, for tolerances on lengths: how far from the origin
/// its bounded primitives reach, its planes lie and its camera stands
/// (1 for an empty scene at the origin).
fn scene_size(scene: &Scene) -> f64 {
    let reach = scene.all_primitives().map(|primitive| match primitive.shape {
        Shape::Sphere { center, radius } => center.length() + radius,
        Shape::Plane { shift, .. } => shift.abs(),
        Shape::Box { center, half, .. } => center.length() + half.length(),
    });
    let size = reach.fold(scene.camera.distance.abs(), f64::max);
    if size > 0.0 && size.is_finite() { size } else { 1.0 }
}

/// A box's geometry, compared whatever its axes' order and signs: the same
/// box is made by `length 2, 1, 1` and by `length 1, 2, 1` turned a quarter
/// about z.
struct BoxShape {
    center: DVec3,
    half: DVec3,
    axes: DMat3,
}

impl BoxShape {
    /// The geometry of a box shape.
    fn of(shape: &Shape) -> BoxShape {
        match *shape {
            Shape::Box { center, half, axes } => BoxShape { center, half, axes },
            _ => unreachable!("only boxes are compared as boxes"),
        }
    }

    /// Its lengths along its own axes.
    fn lengths(&self) -> [f64; 3] {
        (self.half * 2.0).to_array()
    }

    /// Its lengths, longest first.
    fn sorted_lengths(&self) -> [f64; 3] {
        let mut lengths = self.lengths();
        lengths.sort_by(|a, b| b.total_cmp(a));
        lengths
    }

    /// Its eight corners.
    fn corners(&self) -> [DVec3; 8] {
        std::array::from_fn(|k| {
            let sign = |bit: usize| if k >> bit & 1 == 1 { 1.0 } else { -1.0 };
            let own = DVec3::new(sign(0) * self.half.x, sign(1) * self.half.y, sign(2) * self.half.z);
            self.center + self.axes * own
        })
    }

    /// How far the farthest of its corners is from the nearest corner of
    /// `other`: 0 for the same box, however its axes are numbered.
    fn corner_distance(&self, other: &BoxShape) -> f64 {
        let theirs = other.corners();
        let nearest = |corner: DVec3| theirs.iter().map(|c| c.distance(corner)).fold(f64::INFINITY, f64::min);
        self.corners().into_iter().map(nearest).fold(0.0, f64::max)
    }
}
