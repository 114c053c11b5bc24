//! `--precision f32` against the default f64: the scenario scenes stay
//! within the golden-image tolerance of the f64 render, every f32 hit is
//! finite, and a tiny object seen from far away shows where f32 breaks
//! down.

use std::path::PathBuf;

use glam::DVec2;
use image::RgbImage;
use rayrepl::lang::{Interpreter, Limits, SourceMap, parse_file};
use rayrepl::render::{
    Intersector, Precision, Prepared, PreparedF32, PrimaryRays, RenderControl, RenderOptions, Screen, render,
};
use rayrepl::scene::Scene;

mod common;
use common::scenes::{light, material, scene, sphere};

/// The golden-image tolerance: at most this share of pixels more than
/// [`LEVELS`] levels off in some channel.
const SHARE: f64 = 0.005;
const LEVELS: u8 = 2;

fn scenario(name: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenarios").join(format!("{name}.ray"));
    let text = std::fs::read_to_string(&path).expect("scene is readable");
    let mut sources = SourceMap::new();
    let id = sources.add(path.display().to_string(), text, 0);
    let program = parse_file(id, &sources.get(id).text).expect("scenario parses");
    let mut interpreter = Interpreter::new(0.0, Limits::default());
    interpreter.run(&program).expect("scenario evaluates");
    interpreter.into_scene()
}

fn render_in(scene: &Scene, width: u32, height: u32, precision: Precision) -> RgbImage {
    let options = RenderOptions { width, height, precision, ..RenderOptions::default() };
    render(scene, &Prepared::new(scene), &options, &RenderControl::default()).expect("not cancelled").0
}

/// Pixels of `a` more than [`LEVELS`] levels from `b` in some channel.
fn pixels_off(a: &RgbImage, b: &RgbImage) -> usize {
    a.pixels().zip(b.pixels()).filter(|(p, q)| p.0.iter().zip(q.0).any(|(x, y)| x.abs_diff(y) > LEVELS)).count()
}

const SCENARIOS: [&str; 11] = [
    "boxes",
    "conditions",
    "fractal_tree",
    "groups",
    "hello",
    "lights",
    "menger",
    "mirrors",
    "scoping",
    "solar",
    "spiral",
];

#[test]
fn f32_renders_the_scenarios_within_the_tolerance_of_f64() {
    let (width, height) = (96, 72);
    let mut failures = Vec::new();
    for name in SCENARIOS {
        let s = scenario(name);
        let off =
            pixels_off(&render_in(&s, width, height, Precision::F32), &render_in(&s, width, height, Precision::F64));
        let share = off as f64 / f64::from(width * height);
        if share > SHARE {
            failures.push(format!("{name}: {off} pixels ({:.2}%) more than {LEVELS} levels off", 100.0 * share));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn f32_hits_are_finite() {
    for name in SCENARIOS {
        let s = scenario(name);
        let prepared = Prepared::new(&s);
        let f32_geometry = PreparedF32::new(&prepared);
        let rays = PrimaryRays::new(&s.camera, 64, 48, Screen::Centered);
        for j in 0..48 {
            for i in 0..64 {
                let ray = rays.ray(i, j, DVec2::splat(0.5));
                if let Some(hit) = f32_geometry.closest_hit(&ray) {
                    let finite = hit.t.is_finite() && hit.point.is_finite() && hit.normal.is_finite();
                    assert!(finite && hit.t > 0.0, "{name}: pixel ({i}, {j}): {hit:?}");
                }
            }
        }
    }
}

/// A ball of radius 1e-3 seen from 50,000 units away through a field of
/// view of 1e-7 radians (it fills the middle of the image). In f64 the
/// render is the lit ball. In f32 the same pixels see the ball (the
/// silhouette depends on the ray's direction, whose small components keep
/// their relative precision), but the hit distance is computed from
/// numbers around 50,000, where one f32 ulp is 0.004: it is off by about
/// three radii, so the hit point, and the normal and shading with it, are
/// wrong on most of the ball.
#[test]
fn f32_breaks_down_on_a_tiny_ball_seen_from_far_away() {
    let ball = material([1.0, 1.0, 1.0], 0.8, 0.0, 1.0);
    let s = scene(50_000.0, 1e-7, 0.2, vec![light([0.3, 0.5, 1.0], 0.8)], vec![sphere([0.0, 0.0, 0.0], 1e-3, ball)]);
    let (width, height) = (64, 64);
    let lit = |image: &RgbImage| image.pixels().filter(|p| p.0 != [0, 0, 0]).count();
    let f64_image = render_in(&s, width, height, Precision::F64);
    let f32_image = render_in(&s, width, height, Precision::F32);
    // The ball's disc: radius 1e-3 over a view 50,000 * 1e-7 = 5e-3 wide,
    // so 0.2 of the image width: pi * (0.2 * 64)^2 = 515 pixels.
    let (lit64, lit32) = (lit(&f64_image), lit(&f32_image));
    assert!((lit64 as f64 - 515.0).abs() < 30.0, "f64: {lit64} lit pixels");
    assert_eq!(lit32, lit64, "f32 sees the ball in the same pixels");
    let off = pixels_off(&f32_image, &f64_image);
    assert!(off > lit64 * 3 / 4, "f32: only {off} of {lit64} pixels more than {LEVELS} levels off");
}
