//! Whether a check holds in a learner's scene, and if not, what in the
//! scene comes closest to the goal and how it differs, in words.

use glam::DVec3;

use crate::compare::{Side, Tolerances, differences};
use crate::lang::Span;
use crate::lang::degrees::in_radians_help;
use crate::lang::number::format_number;
use crate::scene::{Light, Primitive, Shape};

use super::super::learner::Learner;
use super::{
    ARRANGEMENT_STARTS, Arrangement, Check, Comparison, Condition, DIRECTIONS, Direction, LightsWanted, Part, Quantity,
    ShapeKind, ShapesWanted, Shortfall, extents, numbers_in_words,
};

/// `Ok` when `check` holds in the `learner`'s scene; `goal` is the step's
/// goal scene, for [`Check::MatchesGoal`] (`None` if it could not be built).
pub(crate) fn holds(check: &Check, learner: &dyn Learner, goal: Option<&dyn Learner>) -> Result<(), Shortfall> {
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
pub(crate) fn no_degrees(learner: &dyn Learner) -> Result<(), Shortfall> {
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

/// A learner's scene as the grader compares it.
fn side(learner: &dyn Learner) -> Side<'_> {
    Side { scene: learner.scene(), origins: learner.origins() }
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
fn place_words(learner: &dyn Learner, span: Span) -> String {
    let file = learner.sources().get(span.source);
    let (line, _) = file.line_col(span.start as usize);
    let typed = file.name.strip_prefix("<input ").and_then(|rest| rest.strip_suffix('>'));
    match typed {
        Some(number) if file.text.trim_end().contains('\n') => format!("at line {line} of input [{number}]"),
        Some(number) => format!("in input [{number}]"),
        None => format!("at line {line}"),
    }
}

fn camera_holds(conditions: &[Condition], learner: &dyn Learner) -> Result<(), Shortfall> {
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

fn lights_hold(wanted: &LightsWanted, learner: &dyn Learner) -> Result<(), Shortfall> {
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
fn placed(learner: &dyn Learner) -> Vec<(&Primitive, Option<Span>, bool)> {
    let (scene, origins) = (learner.scene(), learner.origins());
    let fixed = scene.primitives.iter().enumerate().map(|(i, p)| (p, origins.primitives.span_of(i), false));
    let timed = scene.timed_primitives.iter().enumerate().map(|(i, p)| (p, origins.timed_primitives.span_of(i), true));
    fixed.chain(timed).collect()
}

fn shapes_hold(wanted: &ShapesWanted, learner: &dyn Learner) -> Result<(), Shortfall> {
    let kind = wanted.kind;
    let all: Vec<_> = placed(learner).into_iter().filter(|(p, _, _)| ShapeKind::of(&p.shape) == kind).collect();
    if all.is_empty() {
        return Err(Shortfall::new(format!("your scene has no {} yet", kind.name())));
    }
    let like = match &wanted.like {
        None => None,
        Some(name) => match learner.object(name) {
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
fn floors(learner: &dyn Learner) -> Vec<f64> {
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

/// Why `name` is not among the names `defined`: the one that differs from
/// it only by capitals, if there is one (`R` for `r`), or `none` and the name.
fn missing_name<'a>(name: &str, mut defined: impl Iterator<Item = &'a str>, none: &str) -> Shortfall {
    Shortfall::new(match defined.find(|defined| defined.eq_ignore_ascii_case(name)) {
        Some(other) => format!("you named it `{other}`; names tell capitals apart: the goal is `{name}`"),
        None => format!("{none} `{name}` yet"),
    })
}

fn number_holds(name: &str, value: Option<&Comparison>, learner: &dyn Learner) -> Result<(), Shortfall> {
    let numbers = learner.numbers();
    let Some((_, found)) = numbers.iter().find(|(defined, _)| &**defined == name) else {
        return Err(missing_name(name, numbers.iter().map(|(defined, _)| &**defined), "no number is named"));
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

fn object_holds(name: &str, kind: ShapeKind, conditions: &[Condition], learner: &dyn Learner) -> Result<(), Shortfall> {
    let Some(primitives) = learner.object(name) else {
        let objects = learner.object_names();
        return Err(missing_name(name, objects.iter().map(|defined| &**defined), "no object is named"));
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

fn procedure_holds(name: &str, parameters: usize, learner: &dyn Learner) -> Result<(), Shortfall> {
    let procedures = learner.procedures();
    let Some((_, takes)) = procedures.iter().find(|(defined, _)| &**defined == name) else {
        return Err(missing_name(name, procedures.iter().map(|(defined, _)| &**defined), "no procedure is named"));
    };
    match *takes == parameters {
        true => Ok(()),
        false => Err(Shortfall::new(format!("your `{name}` takes {takes} parameters; the goal: {parameters}"))),
    }
}
