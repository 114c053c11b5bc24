//! Extreme but valid scenes (issue 35, point 3): sizes from 1e-300 to 1e300
//! render without a panic on the command line, in `--explain` and in a
//! session, and keep the promise of the same picture at every scale.
//!
//! Property tests over random scenes whose spheres, boxes and planes are
//! each of a size and at a distance anywhere from 1e-300 to 1e300, seen by
//! a camera at a distance of that range too.

use std::io::Write;

use assert_cmd::Command;
use glam::DVec3;
use image::RgbImage;
use proptest::prelude::*;
use rayrepl::render::{RenderControl, RenderOptions, SceneGeometry, render};
use rayrepl::scene::transform::rotation_matrix;
use rayrepl::scene::{Primitive, Scene, Shape};
use rayrepl::session::{RenderSettings, SessionOptions};
use rayrepl::terminal::run_script;

use crate::common::scenes::{light, material, scene};

/// A mirror sphere of radius 1e40 around four ordinary spheres: the
/// reflections start past the range of f32, where the tree's walk once met
/// the unused slots of its nodes and looped back to the root until its
/// stack overflowed.
const HUGE_MIRROR: &str = "camera distance 8 angle 1 end
ambient 0.2
light vector 0.5, 0, 0.5 intensity 0.8 end
put sphere center 0, 0, 0 radius 1e40 kd 0.1 ks 0.9 phong 50 color 200, 200, 200 end
put sphere center 1, 0, 0 radius 0.5 kd 0.8 ks 0.3 phong 50 color 220, 40, 40 end
put sphere center -1, 0, 0 radius 0.5 kd 0.8 ks 0.3 phong 50 color 40, 220, 40 end
put sphere center 0, 1, 0 radius 0.5 kd 0.8 ks 0.3 phong 50 color 40, 40, 220 end
put sphere center 0, -1, 0 radius 0.5 kd 0.8 ks 0.3 phong 50 color 220, 220, 40 end
";

fn rayrepl() -> Command {
    Command::cargo_bin("rayrepl").expect("the binary is built")
}

/// A temporary scene file holding `text`.
fn scene_file(text: &str) -> tempfile::NamedTempFile {
    let mut file = tempfile::Builder::new().suffix(".ray").tempfile().expect("a temporary file");
    file.write_all(text.as_bytes()).expect("scene written");
    file
}

#[test]
fn a_huge_mirror_around_small_spheres_renders_on_the_command_line() {
    let (file, dir) = (scene_file(HUGE_MIRROR), tempfile::tempdir().expect("a temporary folder"));
    let out = dir.path().join("out.png");
    rayrepl().arg(file.path()).args(["--width", "40", "--height", "30", "-o"]).arg(&out).assert().success();
    let image = image::open(&out).expect("a readable image").to_rgb8();
    assert_eq!(image.dimensions(), (40, 30));
}

#[test]
fn a_huge_mirror_around_small_spheres_is_explained_at_every_pixel() {
    let file = scene_file(HUGE_MIRROR);
    for y in 0..6 {
        for x in 0..8 {
            let pixel = format!("{x},{y}");
            rayrepl().arg(file.path()).args(["--width", "8", "--height", "6", "--explain", &pixel]).assert().success();
        }
    }
}

#[test]
fn a_huge_mirror_around_small_spheres_renders_and_is_picked_in_a_session() {
    let options = SessionOptions {
        settings: RenderSettings { width: 16, height: 12, ..RenderSettings::default() },
        ..SessionOptions::default()
    };
    let picks: String = (0..12).flat_map(|y| (0..16).map(move |x| format!(":pick {x} {y}\n"))).collect();
    let script = format!("{HUGE_MIRROR}:render\n{picks}");
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let code = run_script(script.as_bytes(), &mut out, &mut err, &options);
    let err = String::from_utf8_lossy(&err);
    assert_eq!(code, 0, "{err}");
    assert!(String::from_utf8_lossy(&out).contains("rendered 16×12 in "), "{err}");
}

/// `10^e`, for `e` from -300 to 300.
fn power_of_ten(e: i32) -> f64 {
    format!("1e{e}").parse().expect("a number")
}

/// A size from 1e-300 to 1e300: often an ordinary one, the ends of the
/// range, or any power of ten between, times a factor near 1.
fn any_size() -> BoxedStrategy<f64> {
    let exponent = prop_oneof![2 => Just(0), 1 => Just(-300), 1 => Just(300), 1 => Just(40), 4 => -300..=300i32];
    (exponent, 0.2..2.0f64).prop_map(|(e, factor)| power_of_ten(e) * factor).boxed()
}

/// A size near `10^e`.
fn size_near(e: i32) -> BoxedStrategy<f64> {
    (0.2..2.0f64).prop_map(move |factor| power_of_ten(e) * factor).boxed()
}

fn triple(range: std::ops::Range<f64>) -> impl Strategy<Value = DVec3> {
    (range.clone(), range.clone(), range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// A sphere, a turned box or a plane, of a size and at a distance each
/// drawn from `size`.
fn shape_strategy(size: BoxedStrategy<f64>) -> impl Strategy<Value = Shape> {
    let sphere = (triple(-3.0..3.0), size.clone(), size.clone())
        .prop_map(|(at, reach, radius)| Shape::Sphere { center: at * reach, radius });
    let cube = (triple(-3.0..3.0), size.clone(), triple(0.1..1.5), size.clone(), triple(0.0..6.3)).prop_map(
        |(at, reach, half, length, r)| Shape::Box {
            center: at * reach,
            half: half * length,
            axes: rotation_matrix(r.x, r.y, r.z),
        },
    );
    let plane = (triple(-3.2..3.2), 1.0..6.0f64, size).prop_map(|(r, shift, length)| Shape::Plane {
        normal: rotation_matrix(r.x, r.y, r.z).y_axis,
        shift: -shift * length,
    });
    prop_oneof![3 => sphere, 3 => cube, 1 => plane]
}

/// Up to a dozen objects (more than four: they get a tree), mirrors among
/// them, with sizes, distances and the camera's distance drawn from `size`.
fn scene_of(size: BoxedStrategy<f64>) -> impl Strategy<Value = Scene> {
    let texture = (triple(0.0..1.0), 0.0..1.0f64, 0.0..0.95f64, 1.0..100.0f64)
        .prop_map(|(c, kd, ks, phong)| material(c.into(), kd, ks, phong));
    let objects = prop::collection::vec((shape_strategy(size.clone()), texture), 1..13);
    let lights = prop::collection::vec(triple(-1.0..1.0).prop_filter("a direction", |d| d.length() > 0.1), 1..3);
    (size, 0.3..1.5f64, 0.0..0.4f64, lights, objects).prop_map(|(distance, angle, ambient, lights, objects)| {
        let lights = lights.into_iter().map(|d| light(d.into(), 0.7)).collect();
        let primitives = objects.into_iter().map(|(shape, material)| Primitive { shape, material }).collect();
        scene(8.0 * distance, angle, ambient, lights, primitives)
    })
}

/// Every object of its own size, from 1e-300 to 1e300.
fn hostile_scene() -> impl Strategy<Value = Scene> {
    scene_of(any_size())
}

/// Every object of about one size, anywhere from 1e-290 to 1e290.
fn scene_at_any_scale() -> impl Strategy<Value = Scene> {
    prop_oneof![Just(-290), Just(290), -290..=290i32].prop_flat_map(|e| scene_of(size_near(e)))
}

/// `scene` with every length times `factor` (the camera distance too).
fn times(scene: &Scene, factor: f64) -> Scene {
    let primitives =
        scene.primitives.iter().map(|p| Primitive { shape: p.shape.scaled(factor), material: p.material }).collect();
    Scene {
        primitives,
        camera: rayrepl::scene::Camera { distance: scene.camera.distance * factor, ..scene.camera },
        ..scene.clone()
    }
}

/// A small picture of `scene`, with reflections.
fn picture(scene: &Scene) -> RgbImage {
    let options = RenderOptions { width: 24, height: 18, depth: 4, ..RenderOptions::default() };
    render(scene, &SceneGeometry::new(scene), &options, &RenderControl::default()).expect("no cancel flag").0
}

/// How many pixels differ by more than 2 levels in some channel.
fn pixels_off(a: &RgbImage, b: &RgbImage) -> usize {
    a.pixels().zip(b.pixels()).filter(|(p, q)| p.0.iter().zip(q.0).any(|(&x, y)| x.abs_diff(y) > 2)).count()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// No panic, and the same bytes once every length is multiplied by a
    /// power of two that keeps them all in f64's normal range (exact).
    #[test]
    fn hostile_scenes_render_and_give_the_same_bytes_at_a_power_of_two(s in hostile_scene(), k in -20..=20i32) {
        let original = picture(&s);
        prop_assert!(original == picture(&times(&s, 2f64.powi(k))), "scaled by 2^{}", k);
    }

    /// By a power of ten each length is rounded once more: a pixel may
    /// change only where a ray grazes an edge. Not so in a scene whose
    /// sizes span the range: a box 0.04 wide 4e39 away is far below the
    /// rounding of its own position, and whether a ray meets it is decided
    /// by that rounding; the scenes here keep their objects within a few
    /// powers of ten of each other, at any scale.
    #[test]
    fn scenes_at_any_scale_give_the_same_pixels_at_a_power_of_ten(s in scene_at_any_scale(), k in -8..=8i32) {
        let off = pixels_off(&picture(&s), &picture(&times(&s, power_of_ten(k))));
        prop_assert!(off == 0, "scaled by 1e{}: {} pixels off", k, off);
    }
}
