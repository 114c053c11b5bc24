//! The lessons themselves: what each step asks, an example answer, a hint,
//! and the check of the learner's evaluated scene.
//!
//! A check looks at what the session holds (the scene's camera, lights and
//! primitives, where each primitive was put, the names defined), never at
//! the text typed: any program that builds the right scene passes.

use std::collections::HashMap;

use glam::DVec3;

use crate::lang::Span;
use crate::scene::{Material, Primitive, Shape};

use super::super::session::Session;

/// One lesson: a title, the scene it starts from, and its steps.
#[derive(Debug)]
pub(crate) struct Lesson {
    /// What it teaches, in a few words.
    pub title: &'static str,
    /// Program text run when the lesson starts (a camera, a light, a floor),
    /// so that each lesson practises one thing.
    pub setup: &'static str,
    /// The steps, in order.
    pub steps: &'static [Step],
}

/// One step of a lesson.
#[derive(Debug)]
pub(crate) struct Step {
    /// What to do, in plain words.
    pub task: &'static str,
    /// A program that does it: shown with the task (`example_up_front`) or
    /// after a wrong try, run for the goal picture.
    pub example: &'static str,
    /// Whether the task shows the example at once (the first lessons) or
    /// only after a wrong try.
    pub example_up_front: bool,
    /// What to think of when the check fails.
    pub hint: &'static str,
    /// `Ok` when the session's scene does what the task asks, otherwise
    /// what is still missing.
    pub check: fn(&Session) -> Result<(), String>,
}

/// A camera, an ambient light, a light from above, right and front, and a
/// grey floor one unit below the origin: the stage of most lessons.
const STAGE: &str = "\
camera distance 12 angle 0.8 end
ambient 0.2
light vector 0.5, 0, -0.5 intensity 0.8 end
put plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0 phong 1 color 200, 200, 200 end";

/// Every lesson, from nothing to an animated recursive scene.
pub(crate) const LESSONS: &[Lesson] = &[
    Lesson {
        title: "a camera and a first sphere",
        setup: "",
        steps: &[
            Step {
                task: "Every scene looks through a camera. Place one: its eye 10 units from the \
                       origin, seeing 0.8 radians wide.",
                example: "camera distance 10 angle 0.8 end",
                example_up_front: true,
                hint: "`camera distance D angle A end`, with A in radians (between 0 and pi).",
                check: has_camera,
            },
            Step {
                task: "Put an orange ball of radius 2 at the origin, where the camera looks.",
                example: "put sphere center 0, 0, 0 radius 2 kd 0.8 ks 0.2 phong 20 color 255, 120, 40 end",
                example_up_front: true,
                hint: "`put sphere center X, Y, Z radius R kd KD ks KS phong N color R, G, B end`; \
                       the camera sees the origin.",
                check: sphere_in_view,
            },
            Step {
                task: "It looks flat: only the ambient light reaches it. Add a light shining from \
                       above, a little from the right and the front.",
                example: "light vector 0.5, 0, -0.5 intensity 0.8 end",
                example_up_front: true,
                hint: "`light vector RX, RY, RZ intensity I end` turns \"straight up\" by the three \
                       angles; I between 0 and 1.",
                check: has_bright_light,
            },
        ],
    },
    Lesson {
        title: "lights and shadows",
        setup: "\
camera distance 12 angle 0.8 end
put sphere center 0, 0, 0 radius 1 kd 0.8 ks 0.2 phong 20 color 255, 120, 40 end
put plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0 phong 1 color 200, 200, 200 end",
        steps: &[
            Step {
                task: "A ball on a floor, in the dark. Light it from the right, so that its shadow \
                       falls to the left: a light straight up turned about z by a negative angle \
                       leans to the right.",
                example: "light vector 0, 0, -0.9 intensity 0.8 end",
                example_up_front: true,
                hint: "turning \"straight up\" about z by -0.9 leans it to the right (+x); about x, \
                       it leans to the front or the back.",
                check: light_from_the_right,
            },
            Step {
                task: "Where no light reaches, only the ambient light shows. Make the shadows \
                       darker: an ambient light below the default 0.2.",
                example: "ambient 0.05",
                example_up_front: true,
                hint: "`ambient I` with I between 0 and 0.2: a new ambient replaces the old one.",
                check: dark_ambient,
            },
            Step {
                task: "Add a second, weaker light from the left: the ball now casts two shadows.",
                example: "light vector 0, 0, 0.9 intensity 0.4 end",
                example_up_front: false,
                hint: "a positive angle about z leans the light to the left (-x); each `light` adds one.",
                check: lights_from_both_sides,
            },
        ],
    },
    Lesson {
        title: "textures: kd, ks, phong and colours",
        setup: STAGE,
        steps: &[
            Step {
                task: "A matt red ball at x = -2: it spreads the light (kd) and does not shine \
                       at all (ks 0).",
                example: "put sphere center -2, 0, 0 radius 1 kd 0.9 ks 0 phong 1 color 220, 30, 30 end",
                example_up_front: true,
                hint: "red is `color 255, 0, 0` (red, green, blue, each 0 to 255); no shine is `ks 0`.",
                check: matt_red_sphere,
            },
            Step {
                task: "A shiny ball with a small, sharp highlight: ks at least 0.3 and phong at \
                       least 30 (the bigger phong, the smaller the highlight).",
                example: "put sphere center 0, 0, 0 radius 1 kd 0.6 ks 0.4 phong 60 color 40, 90, 220 end",
                example_up_front: false,
                hint: "ks is how shiny the surface is (0 to 1), phong how small the highlight is.",
                check: shiny_sphere,
            },
            Step {
                task: "A mirror ball at x = 2: with ks of 0.8 or more it reflects the other balls \
                       and the floor.",
                example: "put sphere center 2, 0, 0 radius 1 kd 0.1 ks 0.9 phong 200 color 255, 255, 255 end",
                example_up_front: false,
                hint: "the reflection is weighted by ks: near 1 it is a mirror; kd small keeps its own \
                       colour faint.",
                check: mirror_sphere,
            },
        ],
    },
    Lesson {
        title: "planes and boxes",
        setup: "\
camera distance 12 angle 0.8 end
ambient 0.2
light vector 0.5, 0, -0.5 intensity 0.8 end",
        steps: &[
            Step {
                task: "A floor one unit below the eye: a plane facing up. Unturned, a plane is \
                       horizontal and faces up; `shift` moves it along the way it faces.",
                example: "put plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0 phong 1 color 200, 200, 200 end",
                example_up_front: true,
                hint: "`put plane rotation 0, 0, 0 shift D ...`: D is its height; below the eye (0) \
                       it is seen from above.",
                check: floor_below_the_eye,
            },
            Step {
                task: "A back wall facing the camera, 5 units behind the origin: turn the plane \
                       a quarter turn (pi/2) about x.",
                example: "put plane rotation pi/2, 0, 0 shift -5 kd 0.8 ks 0 phong 1 color 120, 160, 220 end",
                example_up_front: false,
                hint: "turning \"up\" by pi/2 about x makes it face +z, towards the camera; its shift \
                       is then the distance along z.",
                check: wall_facing_the_camera,
            },
            Step {
                task: "A flat box, 3 wide, 0.6 high and 2 deep, lying on the floor (its bottom at \
                       y = -1), low enough to be seen from above.",
                example: "put box center 0, -0.7, 0 length 3, 0.6, 2 kd 0.7 ks 0.2 phong 10 color 250, 200, 40 end",
                example_up_front: false,
                hint: "`box center X, Y, Z length W, H, D`: its bottom is at Y - H/2.",
                check: box_on_the_floor,
            },
        ],
    },
    Lesson {
        title: "moving shapes: translate, rotate, scale, group",
        setup: STAGE,
        steps: &[
            Step {
                task: "A long box (3, 1, 1) turned an eighth of a turn (pi/4) about the z axis.",
                example: "\
put rotate box center 0, 0, 0 length 3, 1, 1 kd 0.7 ks 0.2 phong 10 color 40, 160, 90 end
  by 0, 0, pi/4 end",
                example_up_front: true,
                hint: "`put rotate OBJECT by RX, RY, RZ end` turns it about the origin (radians).",
                check: turned_box,
            },
            Step {
                task: "A ball of radius 1.5 centred at -3, 0.5, 0. Try it with `scale` (it multiplies \
                       sizes and positions) and `translate` (it moves).",
                example: "\
put translate scale sphere center 0, 0, 0 radius 1 kd 0.7 ks 0.3 phong 30 color 220, 60, 60 end
  by 1.5 end by -3, 0.5, 0 end",
                example_up_front: false,
                hint: "`scale OBJECT by K end` multiplies its radius by K; `translate OBJECT by X, Y, Z end` \
                       moves it. Any way to get that ball passes.",
                check: scaled_ball,
            },
            Step {
                task: "A snowman of two balls, one on the other, moved together to x = 3 with one \
                       `translate` of a `group`.",
                example: "\
put translate group
    sphere center 0, 0, 0 radius 0.8 kd 0.9 ks 0.1 phong 10 color 250, 250, 250 end
    sphere center 0, 1.2, 0 radius 0.5 kd 0.9 ks 0.1 phong 10 color 250, 250, 250 end
  end by 3, -0.2, 0 end",
                example_up_front: false,
                hint: "`group OBJECT OBJECT ... end` is one object made of several: one `translate` \
                       moves them all.",
                check: snowman,
            },
        ],
    },
    Lesson {
        title: "names: let and object",
        setup: STAGE,
        steps: &[
            Step {
                task: "Name a number: a radius r of 0.7 that later lines can use.",
                example: "let r = 0.7",
                example_up_front: true,
                hint: "`let NAME = EXPRESSION` names a number.",
                check: names_a_number,
            },
            Step {
                task: "Name an object without putting it: a yellow ball `ball` of radius r.",
                example: "object ball = sphere center 0, 0, 0 radius r kd 0.7 ks 0.3 phong 30 color 250, 200, 40 end",
                example_up_front: false,
                hint: "`object NAME = sphere ... end` names an object; nothing is put yet.",
                check: names_an_object,
            },
            Step {
                task: "Put your object three times, side by side.",
                example: "put translate ball by -2, 0, 0 end put ball put translate ball by 2, 0, 0 end",
                example_up_front: false,
                hint: "`put NAME` puts it where it is; `put translate NAME by X, Y, Z end` elsewhere.",
                check: same_ball_three_times,
            },
        ],
    },
    Lesson {
        title: "procedures",
        setup: STAGE,
        steps: &[
            Step {
                task: "Define a procedure `post(x)` that puts a post (a thin tall box) at x.",
                example: "\
proc post(x)
  put box center x, 0, 0 length 0.4, 2, 0.4 kd 0.7 ks 0.2 phong 10 color 150, 90, 40 end
end",
                example_up_front: true,
                hint: "`proc NAME(PARAMETER, ...) INSTRUCTIONS end`: nothing is put until it is called.",
                check: defines_post,
            },
            Step {
                task: "Call it to put three posts in a row: the same `put` runs three times.",
                example: "post(-2) post(0) post(2)",
                example_up_front: false,
                hint: "a call is `NAME(ARGUMENTS)`, for example `post(-2)`.",
                check: one_put_three_times,
            },
        ],
    },
    Lesson {
        title: "recursion and if",
        setup: STAGE,
        steps: &[
            Step {
                task: "A procedure `row(n)` that, while 0 < n, puts a ball at x = n - 4 and calls \
                       itself with n - 1.",
                example: "\
proc row(n)
  if 0 < n then
    put sphere center n - 4, -0.6, 1 radius 0.4 kd 0.7 ks 0.3 phong 30 color 40, 90, 220 end
    row(n - 1)
  end
end",
                example_up_front: true,
                hint: "inside, `if 0 < n then ... row(n - 1) end` stops when n reaches 0.",
                check: defines_row,
            },
            Step {
                task: "Call it once to put five balls: row(5).",
                example: "row(5)",
                example_up_front: false,
                hint: "one call `row(5)` runs the `put` five times, once for each n from 5 down to 1.",
                check: one_put_five_times,
            },
            Step {
                task: "A procedure `tower(n, r, y)` that puts a ball of radius r resting at height y, \
                       then calls itself with a smaller radius on top of it.",
                example: "\
proc tower(n, r, y)
  if 0 < n then
    put sphere center 3, y + r, 0 radius r kd 0.7 ks 0.3 phong 30 color 220, 60, 60 end
    tower(n - 1, r * 0.7, y + 2 * r)
  end
end",
                example_up_front: false,
                hint: "the next ball rests at y + 2 * r, and its radius is r times a number below 1.",
                check: defines_tower,
            },
            Step {
                task: "Build a tower of five shrinking balls on the floor (at y = -1).",
                example: "tower(5, 0.8, -1)",
                example_up_front: false,
                hint: "call it with n = 5, a first radius, and the floor's height -1.",
                check: shrinking_tower,
            },
        ],
    },
    Lesson {
        title: "time and animations",
        setup: STAGE,
        steps: &[
            Step {
                task: "`time` is 0 in a picture and k in frame k of an animation. Put a ball whose \
                       position depends on time.",
                example: "put sphere center 3 * sin(time / 2), 0, 0 radius 0.7 kd 0.7 ks 0.3 phong 30 color 250, 200, 40 end",
                example_up_front: true,
                hint: "use `time` in its center, for example `center 3 * sin(time / 2), 0, 0`; then \
                       `:time 3` moves it.",
                check: moves_with_time,
            },
            Step {
                task: "A procedure `spin(n)` that puts n small balls on a rising circle turning \
                       with time (ball n at angle n * pi / 4 + time / 4), by recursion.",
                example: "\
proc spin(n)
  if 0 < n then
    put sphere center 2.5 * cos(n * pi / 4 + time / 4), n * 0.3 - 0.7, 2.5 * sin(n * pi / 4 + time / 4) radius 0.3
      kd 0.7 ks 0.3 phong 30 color 40, 160, 90 end
    spin(n - 1)
  end
end",
                example_up_front: false,
                hint: "like `row(n)`, with cos and sin of an angle that grows with time.",
                check: defines_spin,
            },
            Step {
                task: "Call it with eight balls; then `:play 24` plays the animation here, and \
                       `:anim 24 spin.gif` writes it.",
                example: "spin(8)",
                example_up_front: false,
                hint: "one call `spin(8)` puts eight balls that move with time.",
                check: recursion_that_moves,
            },
        ],
    },
];

// ---------------------------------------------------------------- what a scene holds

/// The spheres of the scene: centre, radius and material.
fn spheres(session: &Session) -> impl Iterator<Item = (DVec3, f64, Material)> + '_ {
    session.scene().all_primitives().filter_map(|p| match p.shape {
        Shape::Sphere { center, radius } => Some((center, radius, p.material)),
        _ => None,
    })
}

/// The planes of the scene: unit normal and shift.
fn planes(session: &Session) -> impl Iterator<Item = (DVec3, f64)> + '_ {
    session.scene().all_primitives().filter_map(|p| match p.shape {
        Shape::Plane { normal, shift } => Some((normal, shift)),
        _ => None,
    })
}

/// The primitives of the scene grouped by the `put` that made them (one
/// `put` run again and again by a procedure makes several), among the
/// timed ones only if `timed`.
fn by_put(session: &Session, timed: bool) -> Vec<Vec<&Primitive>> {
    let (scene, origins) = (session.scene(), session.origins());
    let mut groups: HashMap<Span, Vec<&Primitive>> = HashMap::new();
    let timed_ones = scene.timed_primitives.iter().enumerate().map(|(i, p)| (origins.timed_primitives.span_of(i), p));
    let static_ones = scene.primitives.iter().enumerate().map(|(i, p)| (origins.primitives.span_of(i), p));
    let all: Box<dyn Iterator<Item = _>> =
        if timed { Box::new(timed_ones) } else { Box::new(static_ones.chain(timed_ones)) };
    for (span, primitive) in all {
        if let Some(span) = span {
            groups.entry(span).or_default().push(primitive);
        }
    }
    groups.into_values().collect()
}

/// Whether `a` and `b` are equal to within rounding.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * (1.0 + a.abs().max(b.abs()))
}

/// `Ok` if `holds`, otherwise `missing`.
fn require(holds: bool, missing: &str) -> Result<(), String> {
    if holds { Ok(()) } else { Err(missing.to_string()) }
}

/// How many different values `values` holds, to within rounding.
fn distinct(values: impl Iterator<Item = f64>) -> usize {
    let mut seen: Vec<f64> = Vec::new();
    for value in values {
        if !seen.iter().any(|&v| close(v, value)) {
            seen.push(value);
        }
    }
    seen.len()
}

// ---------------------------------------------------------------- the checks

fn has_camera(session: &Session) -> Result<(), String> {
    require(session.has_camera(), "there is no `camera` yet (the default one is used)")
}

fn sphere_in_view(session: &Session) -> Result<(), String> {
    let camera = session.scene().camera;
    let half_width = (camera.angle / 2.0).tan();
    // In view: in front of the eye, and within the field of view across.
    let seen = |center: DVec3, radius: f64| {
        let depth = camera.distance - center.z;
        depth > radius && center.x.hypot(center.y) - radius < depth * half_width
    };
    if spheres(session).next().is_none() {
        return Err("the scene has no sphere yet".to_string());
    }
    require(spheres(session).any(|(center, radius, _)| seen(center, radius)), "no sphere is in front of the camera")
}

fn has_bright_light(session: &Session) -> Result<(), String> {
    let lights = &session.scene().lights;
    require(!lights.is_empty(), "the scene has no light yet")?;
    require(lights.iter().any(|light| light.intensity > 0.0), "every light has intensity 0")
}

fn light_from_the_right(session: &Session) -> Result<(), String> {
    let lights = &session.scene().lights;
    require(!lights.is_empty(), "the scene has no light yet")?;
    require(lights.iter().any(|light| light.direction.x > 0.2), "no light comes from the right (+x)")
}

fn dark_ambient(session: &Session) -> Result<(), String> {
    require(session.has_ambient() && session.scene().ambient < 0.2, "the ambient light is not below 0.2")
}

fn lights_from_both_sides(session: &Session) -> Result<(), String> {
    let lights = &session.scene().lights;
    require(lights.len() >= 2, "the scene has fewer than two lights")?;
    require(lights.iter().any(|light| light.direction.x < -0.2), "no light comes from the left (-x)")
}

fn matt_red_sphere(session: &Session) -> Result<(), String> {
    let red = |c: DVec3| c.x > 0.5 && c.y < 0.5 * c.x && c.z < 0.5 * c.x;
    require(spheres(session).any(|(_, _, m)| red(m.color)), "no sphere is red")?;
    require(spheres(session).any(|(_, _, m)| red(m.color) && m.ks == 0.0), "the red sphere still shines (ks is not 0)")
}

fn shiny_sphere(session: &Session) -> Result<(), String> {
    let shiny = |m: Material| m.ks >= 0.3 && m.phong >= 30.0;
    require(spheres(session).any(|(_, _, m)| shiny(m)), "no sphere has ks of 0.3 or more and phong of 30 or more")
}

fn mirror_sphere(session: &Session) -> Result<(), String> {
    require(spheres(session).any(|(_, _, m)| m.ks >= 0.8), "no sphere has ks of 0.8 or more")
}

fn floor_below_the_eye(session: &Session) -> Result<(), String> {
    require(
        planes(session).any(|(normal, shift)| normal.y > 0.9 && shift < 0.0),
        "no plane faces up below the eye (rotation 0, 0, 0 and a negative shift)",
    )
}

fn wall_facing_the_camera(session: &Session) -> Result<(), String> {
    let distance = session.scene().camera.distance;
    require(
        planes(session).any(|(normal, shift)| normal.z > 0.9 && shift < distance),
        "no plane faces the camera (its normal towards +z)",
    )
}

fn box_on_the_floor(session: &Session) -> Result<(), String> {
    // The lowest point of a box: centre.y minus the y extent of its half sizes.
    let bottoms: Vec<f64> = session
        .scene()
        .all_primitives()
        .filter_map(|p| match p.shape {
            Shape::Box { center, half, axes } => Some(center.y - axes.row(1).abs().dot(half)),
            _ => None,
        })
        .collect();
    require(!bottoms.is_empty(), "the scene has no box yet")?;
    require(bottoms.iter().any(|&bottom| close(bottom, -1.0)), "no box has its bottom on the floor (y = -1)")
}

fn turned_box(session: &Session) -> Result<(), String> {
    let turned = |p: &Primitive| matches!(p.shape, Shape::Box { axes, .. } if axes.x_axis.x.abs() < 0.99);
    require(session.scene().all_primitives().any(turned), "no box is turned")
}

fn scaled_ball(session: &Session) -> Result<(), String> {
    let target = DVec3::new(-3.0, 0.5, 0.0);
    require(
        spheres(session).any(|(center, radius, _)| close(radius, 1.5) && center.distance(target) < 1e-6),
        "no sphere of radius 1.5 is centred at -3, 0.5, 0",
    )
}

fn snowman(session: &Session) -> Result<(), String> {
    let at_three: Vec<DVec3> =
        spheres(session).map(|(center, _, _)| center).filter(|center| close(center.x, 3.0)).collect();
    require(
        distinct(at_three.iter().map(|center| center.y)) >= 2,
        "there are not two spheres one above the other at x = 3",
    )
}

fn names_a_number(session: &Session) -> Result<(), String> {
    require(session.numbers().iter().any(|(name, _)| &**name != "time"), "no number has a name yet")
}

fn names_an_object(session: &Session) -> Result<(), String> {
    require(!session.objects().is_empty(), "no object has a name yet")
}

fn same_ball_three_times(session: &Session) -> Result<(), String> {
    let balls: Vec<(DVec3, f64, Material)> = spheres(session).collect();
    let copies = |(_, radius, material): &(DVec3, f64, Material)| {
        let same = balls.iter().filter(|(_, r, m)| close(*r, *radius) && m == material);
        distinct(same.map(|(center, _, _)| center.x + 1e3 * center.y + 1e6 * center.z))
    };
    require(balls.iter().any(|ball| copies(ball) >= 3), "there are not three copies of one ball at different places")
}

/// `Ok` when the procedure `name` is defined with `parameters` parameters.
fn defines(session: &Session, name: &str, parameters: usize) -> Result<(), String> {
    let procedures = session.procedures();
    let Some((_, params)) = procedures.iter().find(|(defined, _)| &**defined == name) else {
        return Err(format!("no procedure `{name}` is defined"));
    };
    require(params.len() == parameters, &format!("`{name}` does not take {parameters} parameters"))
}

fn defines_post(session: &Session) -> Result<(), String> {
    defines(session, "post", 1)
}

fn defines_row(session: &Session) -> Result<(), String> {
    defines(session, "row", 1)
}

fn defines_tower(session: &Session) -> Result<(), String> {
    defines(session, "tower", 3)
}

fn defines_spin(session: &Session) -> Result<(), String> {
    defines(session, "spin", 1)
}

/// `Ok` when one `put` made `count` primitives or more at different places
/// (among the timed ones only if `timed`).
fn one_put_made(session: &Session, count: usize, timed: bool) -> Result<(), String> {
    let places = |made: &Vec<&Primitive>| {
        distinct(made.iter().map(|p| match p.shape {
            Shape::Sphere { center, .. } | Shape::Box { center, .. } => center.x + 1e3 * center.y + 1e6 * center.z,
            Shape::Plane { shift, .. } => shift,
        }))
    };
    require(
        by_put(session, timed).iter().any(|made| places(made) >= count),
        &format!("no `put` ran {count} times at different places"),
    )
}

fn one_put_three_times(session: &Session) -> Result<(), String> {
    one_put_made(session, 3, false)
}

fn one_put_five_times(session: &Session) -> Result<(), String> {
    one_put_made(session, 5, false)
}

fn shrinking_tower(session: &Session) -> Result<(), String> {
    let sizes = |made: &Vec<&Primitive>| {
        distinct(made.iter().filter_map(|p| match p.shape {
            Shape::Sphere { radius, .. } => Some(radius),
            _ => None,
        }))
    };
    require(by_put(session, false).iter().any(|made| sizes(made) >= 5), "no `put` made five balls of different sizes")
}

fn moves_with_time(session: &Session) -> Result<(), String> {
    require(!session.scene().timed_primitives.is_empty(), "nothing in the scene depends on `time`")
}

fn recursion_that_moves(session: &Session) -> Result<(), String> {
    one_put_made(session, 8, true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::Limits;
    use crate::repl::RenderSettings;

    /// Every step fails before its example runs and passes after: the
    /// checks ask for something, and the examples do it.
    #[test]
    fn each_example_passes_its_step_and_only_its_example() {
        for (number, lesson) in LESSONS.iter().enumerate() {
            let mut session = Session::new(RenderSettings::default(), Limits::default());
            session.submit("<setup>", lesson.setup, 0).expect("the setup runs");
            for (index, step) in lesson.steps.iter().enumerate() {
                let place = format!("lesson {} step {}", number + 1, index + 1);
                assert!((step.check)(&session).is_err(), "{place} passes at once");
                session.submit("<example>", step.example, 0).unwrap_or_else(|e| panic!("{place}: {e:?}"));
                assert_eq!((step.check)(&session), Ok(()), "{place}");
            }
        }
    }

    #[test]
    fn a_tower_of_equal_balls_is_not_shrinking() {
        let mut session = Session::new(RenderSettings::default(), Limits::default());
        let lesson = &LESSONS[7];
        session.submit("<setup>", lesson.setup, 0).expect("runs");
        session.submit("<proc>", &lesson.steps[2].example.replace("r * 0.7", "r"), 0).expect("runs");
        session.submit("<call>", "tower(5, 0.8, -1)", 0).expect("runs");
        assert_eq!((lesson.steps[3].check)(&session), Err("no `put` made five balls of different sizes".to_string()));
    }
}
