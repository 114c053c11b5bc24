//! Animations (`rayrepl::animation`): every frame must be byte-identical to
//! rendering that frame on its own, whatever the animation driver saves
//! (one render for a still scene, the static BVH kept, frame reuse).

use std::cell::RefCell;
use std::sync::atomic::AtomicBool;

use glam::{DMat3, DVec3};
use image::RgbImage;
use proptest::prelude::*;
use rayrepl::animation::{AnimationError, WINDOW_FRAMES, render_animation};
use rayrepl::lang::{Interpreter, Limits, SourceMap, parse_file};
use rayrepl::render::{RenderControl, RenderOptions, RenderStats, SceneGeometry, render};
use rayrepl::scene::{Primitive, Scene, Shape};

use crate::common::scenes::{cube, light, material, plane, scene, sphere};

/// A program's scene at `time`, keeping only the timed primitives with
/// `skip_static`.
fn evaluate(text: &str, time: u32, skip_static: bool) -> Result<Scene, String> {
    let mut sources = SourceMap::new();
    let id = sources.add("test.ray", text.to_string(), 0);
    let program = parse_file(id, text).map_err(|d| d.message)?;
    let mut interpreter = Interpreter::new(f64::from(time), Limits::default()).skip_static(skip_static);
    interpreter.run(&program).map_err(|d| d.message)?;
    Ok(interpreter.into_scene())
}

/// What [`animate`] gives: the frames handed over, and how it ended.
type Animated = (Vec<(u32, RgbImage)>, Result<RenderStats, AnimationError<String>>);

/// Renders frames `frames` with the animation driver; the images and the
/// total statistics.
fn animate(
    frames: std::ops::RangeInclusive<u32>,
    scene_at: impl FnMut(u32, bool) -> Result<Scene, String>,
    options: &RenderOptions,
) -> Animated {
    let mut images = Vec::new();
    let sink = |k: u32, image: RgbImage| {
        images.push((k, image));
        Ok(())
    };
    let result = render_animation(frames, scene_at, options, &RenderControl::default(), sink);
    (images, result)
}

/// Checks that each frame the driver renders equals rendering the full
/// scene of that frame alone; returns the driver's statistics.
fn assert_frames_exact(
    frames: std::ops::RangeInclusive<u32>,
    mut scene_at: impl FnMut(u32, bool) -> Result<Scene, String>,
    options: &RenderOptions,
    what: &str,
) -> RenderStats {
    let (images, result) = animate(frames.clone(), &mut scene_at, options);
    let stats = result.unwrap_or_else(|e| panic!("{what}: the animation failed: {e:?}"));
    assert_eq!(images.iter().map(|(k, _)| *k).collect::<Vec<_>>(), frames.clone().collect::<Vec<_>>(), "{what}");
    for (k, image) in images {
        let alone = scene_at(k, false).expect("the frame evaluates");
        let (expected, _) =
            render(&alone, &SceneGeometry::new(&alone), options, &RenderControl::default()).expect("no cancel");
        if image != expected {
            let differing = image.pixels().zip(expected.pixels()).filter(|(a, b)| a != b).count();
            panic!("{what}: frame {k} differs from its own render in {differing} pixels");
        }
    }
    stats
}

fn options(width: u32, height: u32) -> RenderOptions {
    RenderOptions { width, height, ..RenderOptions::default() }
}

fn file(path: &str) -> String {
    std::fs::read_to_string(format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))).expect("the file exists")
}

#[test]
fn animated_scenarios_are_exact_frame_by_frame() {
    for path in ["scenarios/solar.ray", "scenarios/spiral.ray", "benches/scenes/solar.ray"] {
        let text = file(path);
        assert_frames_exact(1..=12, |k, skip| evaluate(&text, k, skip), &options(96, 72), path);
    }
}

#[test]
fn frame_reuse_traces_few_pixels_of_the_solar_animation() {
    let text = file("benches/scenes/solar.ray");
    let frames = 30;
    let stats = assert_frames_exact(1..=frames, |k, skip| evaluate(&text, k, skip), &options(160, 120), "solar");
    let every_pixel = u64::from(frames) * 160 * 120;
    // Only the earth and moon move: most pixels are traced once.
    assert!(stats.rays.primary * 5 < every_pixel, "{} primary rays of {every_pixel}", stats.rays.primary);
}

/// A mirror room with a moving ball; `$MOVE` is replaced by what differs.
const ROOM: &str = "
camera distance 12 angle 1.0 end
ambient 0.2
light vector 0.6, 0, 0.5 intensity 0.7 end
light rotation 0.7, 0, -0.45 intensity 0.4 end
put plane rotation 0, 0, 0 shift -3 kd 0.4 ks 0.6 phong 50 color 90, 90, 140 end
put plane rotation pi / 2, pi / 4, 0 shift -8 kd 0.3 ks 0.7 phong 80 color 120, 200, 255 end
put box center 0, 0, 0 length 2, 1, 1 kd 0.7 ks 0.3 phong 30 color 200, 80, 40 end
put translate sphere center 0, 0, 0 radius 0.8 kd 0.8 ks 0.5 phong 40 color 40, 110, 255 end
  by 3 * cos(time / 2), 1, 3 * sin(time / 2) end
$MOVE
";

#[test]
fn frames_are_exact_whatever_depends_on_time() {
    // (what, the line of ROOM replaced, its replacement)
    let cases = [
        ("only a ball moves", "$MOVE", ""),
        ("the camera moves", "camera distance 12 angle 1.0 end", "camera distance 12 + time / 4 angle 1.0 end"),
        (
            "a light turns",
            "light vector 0.6, 0, 0.5 intensity 0.7 end",
            "light rotation 0.1 * time, 0, 0.3 intensity 0.7 end",
        ),
        ("the ambient light changes", "ambient 0.2", "ambient 0.1 + time / 100"),
        (
            "a plane moves",
            "$MOVE",
            "put plane rotation pi / 2, -pi / 4, 0 shift -8 - time / 3 kd 0.5 ks 0.5 phong 9 color 255, 160, 220 end",
        ),
        (
            "a box appears at time 4",
            "$MOVE",
            "if time > 3 then put box center 0, 0, 0 length 1, 1, 1 kd 0.9 ks 0 phong 1 color 0, 255, 0 end end",
        ),
        (
            "a ball leaves at time 4",
            "$MOVE",
            "if time < 4 then put sphere center 0, 2, 0 radius 0.5 kd 0.9 ks 0.2 phong 9 color 255, 0, 0 end end",
        ),
        (
            "a box spins in the ball's shadow",
            "$MOVE",
            "put rotate box center 0, 0, 0 length 3, 0.2, 3 kd 0.6 ks 0.4 phong 20 color 250, 250, 250 end by 0, time / 3, 0 end",
        ),
    ];
    for (what, line, change) in cases {
        let text = ROOM.replace(line, change).replace("$MOVE", "");
        assert_frames_exact(1..=7, |k, skip| evaluate(&text, k, skip), &options(48, 36), what);
    }
}

#[test]
fn frames_are_exact_with_anti_aliasing_and_without_skips() {
    let text = ROOM.replace("$MOVE", "");
    let with_samples = RenderOptions { samples: 4, ..options(40, 30) };
    assert_frames_exact(2..=6, |k, skip| evaluate(&text, k, skip), &with_samples, "4 samples");
    let adaptive = RenderOptions { samples: 4, adaptive: true, ..options(40, 30) };
    assert_frames_exact(2..=6, |k, skip| evaluate(&text, k, skip), &adaptive, "adaptive");
    let no_skips = RenderOptions { skips: rayrepl::render::Skips::none(), ..options(40, 30) };
    assert_frames_exact(1..=5, |k, skip| evaluate(&text, k, skip), &no_skips, "no skips");
    let deep = RenderOptions { depth: 12, ..options(40, 30) };
    assert_frames_exact(1..=5, |k, skip| evaluate(&text, k, skip), &deep, "depth 12");
}

#[test]
fn a_still_scene_is_rendered_once() {
    let text = file("scenarios/hello.ray");
    let stats = assert_frames_exact(1..=5, |k, skip| evaluate(&text, k, skip), &options(32, 24), "hello");
    assert_eq!(stats.rays.primary, 32 * 24);
}

#[test]
fn an_object_that_appears_later_is_not_missed() {
    // Frame 1 has nothing that depends on `time`; frame 4 has a sphere.
    let text = format!(
        "{}\nif time > 3 then put sphere center 1, 1, 1 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end end\n",
        file("scenarios/hello.ray")
    );
    assert_frames_exact(1..=5, |k, skip| evaluate(&text, k, skip), &options(32, 24), "appearing sphere");
}

#[test]
fn windows_of_frames_join_up() {
    // More frames than one window holds: each window starts afresh.
    let text = ROOM.replace("$MOVE", "");
    let last = WINDOW_FRAMES as u32 + 10;
    assert_frames_exact(1..=last, |k, skip| evaluate(&text, k, skip), &options(8, 6), "many frames");
}

#[test]
fn frames_before_a_failing_one_are_all_handed_over() {
    let text = ROOM.replace(
        "$MOVE",
        "if time > 5 then put sphere center 0, 0, 0 radius 1 - time / 5 kd 1 ks 0 phong 1 color 1, 1, 1 end end",
    );
    let (images, result) = animate(1..=9, |k, skip| evaluate(&text, k, skip), &options(16, 12));
    assert_eq!(images.iter().map(|(k, _)| *k).collect::<Vec<_>>(), vec![1, 2, 3, 4, 5]);
    match result {
        Err(AnimationError::Failed(message)) => assert!(message.contains("radius"), "{message}"),
        other => panic!("expected the frame-6 error, got {other:?}"),
    }
}

#[test]
fn a_sink_error_stops_the_animation() {
    let text = ROOM.replace("$MOVE", "");
    let handed = RefCell::new(0);
    let sink = |k: u32, _: RgbImage| {
        *handed.borrow_mut() += 1;
        if k == 3 { Err("disk full".to_string()) } else { Ok(()) }
    };
    let result =
        render_animation(1..=8, |k, skip| evaluate(&text, k, skip), &options(8, 6), &RenderControl::default(), sink);
    assert!(matches!(result, Err(AnimationError::Failed(ref m)) if m == "disk full"));
    assert_eq!(*handed.borrow(), 3);
}

#[test]
fn a_cancelled_animation_says_so() {
    let text = ROOM.replace("$MOVE", "");
    let cancel = AtomicBool::new(true);
    let control = RenderControl { progress: None, cancel: Some(&cancel) };
    let result = render_animation(1..=4, |k, skip| evaluate(&text, k, skip), &options(8, 6), &control, |_, _| Ok(()));
    assert!(matches!(result, Err(AnimationError::<String>::Cancelled)));
}

#[test]
fn progress_counts_every_pixel_of_every_frame() {
    let text = ROOM.replace("$MOVE", "");
    let counted = std::sync::atomic::AtomicU64::new(0);
    let tick = |n: u64| {
        counted.fetch_add(n, std::sync::atomic::Ordering::Relaxed);
    };
    let control = RenderControl { progress: Some(&tick), cancel: None };
    let done = render_animation(1..=6, |k, skip| evaluate(&text, k, skip), &options(20, 10), &control, |_, _| Ok(()));
    assert!(done.is_ok());
    assert_eq!(counted.into_inner(), 6 * 20 * 10);
}

// ------------------------------------------------ random moving scenes

/// A random scene: static spheres and boxes, mirror planes, and moving
/// spheres and boxes whose positions are linear in the frame number.
#[derive(Debug, Clone)]
struct Moving {
    fixed: Vec<Primitive>,
    /// Each with its velocity per frame.
    moving: Vec<(Primitive, DVec3)>,
}

impl Moving {
    fn at(&self, k: u32, skip_static: bool) -> Scene {
        let moved = self.moving.iter().map(|(p, v)| {
            let shift = *v * f64::from(k);
            let shape = match p.shape {
                Shape::Sphere { center, radius } => Shape::Sphere { center: center + shift, radius },
                Shape::Box { center, half, axes } => Shape::Box { center: center + shift, half, axes },
                plane => plane,
            };
            Primitive { shape, ..*p }
        });
        let lights = vec![light([0.5, 1.0, 0.6], 0.6), light([-0.7, 0.4, 0.9], 0.4)];
        let fixed = if skip_static { Vec::new() } else { self.fixed.clone() };
        let mut scene = scene(10.0, 1.0, 0.2, lights, fixed);
        scene.timed_primitives = moved.collect();
        scene
    }
}

fn arb_material() -> impl Strategy<Value = rayrepl::scene::Material> {
    (0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64, prop_oneof![Just(0.0), 0.0..1.0f64], 1.0..80.0f64)
        .prop_map(|(r, g, b, kd, ks, phong)| material([r, g, b], kd, ks, phong))
}

fn arb_bounded() -> impl Strategy<Value = Primitive> {
    let position = prop::array::uniform3(-4.0..4.0f64);
    prop_oneof![
        (position.clone(), 0.2..1.5f64, arb_material()).prop_map(|(c, r, m)| sphere(c, r, m)),
        (position, prop::array::uniform3(0.2..2.5f64), 0.0..3.0f64, arb_material())
            .prop_map(|(c, size, angle, m)| cube(c, size, DMat3::from_rotation_y(angle), m)),
    ]
}

fn arb_moving() -> impl Strategy<Value = Moving> {
    let planes = prop::collection::vec((prop::array::uniform3(-1.0..1.0f64), -6.0..-3.0f64, arb_material()), 0..3);
    (
        prop::collection::vec(arb_bounded(), 0..6),
        planes,
        prop::collection::vec((arb_bounded(), prop::array::uniform3(-0.6..0.6f64)), 1..9),
    )
        .prop_map(|(mut fixed, planes, moving)| {
            for (normal, shift, m) in planes {
                if DVec3::from(normal).length() > 0.2 {
                    fixed.push(plane(normal, shift, m));
                }
            }
            Moving { fixed, moving: moving.into_iter().map(|(p, v)| (p, DVec3::from(v))).collect() }
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Frame reuse on random scenes: every frame equals its own render.
    #[test]
    fn random_moving_scenes_are_exact_frame_by_frame(world in arb_moving()) {
        let stats = assert_frames_exact(1..=6, |k, skip| Ok(world.at(k, skip)), &options(24, 18), "random scene");
        prop_assert!(stats.rays.primary <= 6 * 24 * 18);
    }
}
