//! Scale invariance (SPEC 6): a scene with every length multiplied by
//! `10^k` renders the same pixels as the original, for every k from -150 to
//! 150, and the same bytes exactly for a power of two; translating the
//! whole scene, camera included, by a small amount changes nothing either.
//!
//! Property tests over random scenes: spheres, boxes and planes in groups
//! moved by random similarities (the language's `rotate`, `scale` and
//! `translate`), random materials and lights.

use glam::DVec3;
use image::RgbImage;
use proptest::prelude::*;
use rayrepl::render::{RenderControl, RenderOptions, SceneGeometry, render};
use rayrepl::scene::transform::rotation_matrix;
use rayrepl::scene::{Light, Material, Primitive, Scene, Shape};

use crate::common::scenes::{light, material, scene};

/// `scene` with every length multiplied by `factor`.
fn scaled(scene: &Scene, factor: f64) -> Scene {
    let mut scene = scene.clone();
    scene.camera.distance *= factor;
    for primitive in &mut scene.primitives {
        primitive.scale(factor);
    }
    scene
}

/// `scene` moved by `shift` along z, its camera with it.
fn moved_along_z(scene: &Scene, shift: f64) -> Scene {
    let mut scene = scene.clone();
    scene.camera.distance += shift;
    for primitive in &mut scene.primitives {
        primitive.translate(DVec3::new(0.0, 0.0, shift));
    }
    scene
}

fn image(scene: &Scene) -> RgbImage {
    let options = RenderOptions { width: 48, height: 36, depth: 3, ..RenderOptions::default() };
    let prepared = SceneGeometry::new(scene);
    render(scene, &prepared, &options, &RenderControl::default()).expect("no cancel flag").0
}

/// How many pixels differ by more than 2 levels in some channel.
fn pixels_off(a: &RgbImage, b: &RgbImage) -> usize {
    a.pixels().zip(b.pixels()).filter(|(p, q)| p.0.iter().zip(q.0).any(|(&x, y)| x.abs_diff(y) > 2)).count()
}

fn triple(range: std::ops::Range<f64>) -> impl Strategy<Value = DVec3> {
    (range.clone(), range.clone(), range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn material_strategy() -> impl Strategy<Value = Material> {
    (triple(0.0..1.0), 0.0..1.0f64, 0.0..0.8f64, 1.0..100.0f64)
        .prop_map(|(c, kd, ks, phong)| material(c.into(), kd, ks, phong))
}

fn shape_strategy() -> impl Strategy<Value = Shape> {
    prop_oneof![
        4 => (triple(-3.0..3.0), 0.2..2.0f64).prop_map(|(center, radius)| Shape::Sphere { center, radius }),
        4 => (triple(-3.0..3.0), triple(0.1..1.5), triple(0.0..6.3)).prop_map(|(center, half, r)| Shape::Box {
            center,
            half,
            axes: rotation_matrix(r.x, r.y, r.z),
        }),
        1 => (triple(-0.6..0.6), -6.0..-1.0f64).prop_map(|(r, shift)| Shape::Plane {
            normal: rotation_matrix(r.x, r.y, r.z).y_axis,
            shift,
        }),
    ]
}

/// A group of primitives under one similarity: rotated, scaled (maybe by a
/// negative ratio) and moved, as `rotate`, `scale` and `translate` do.
fn group_strategy() -> impl Strategy<Value = Vec<Primitive>> {
    let members = prop::collection::vec((shape_strategy(), material_strategy()), 1..5);
    let ratio = prop_oneof![0.4..2.5f64, -2.5..-0.4f64];
    (members, triple(0.0..6.3), ratio, triple(-2.0..2.0)).prop_map(|(members, r, k, v)| {
        let rotation = rotation_matrix(r.x, r.y, r.z);
        members
            .into_iter()
            .map(|(shape, material)| {
                let mut primitive = Primitive { shape, material };
                primitive.rotate(&rotation);
                primitive.scale(k);
                primitive.translate(v);
                primitive
            })
            .collect()
    })
}

fn light_strategy() -> impl Strategy<Value = Light> {
    (triple(-1.0..1.0).prop_filter("a direction", |d| d.length() > 0.1), 0.2..1.0f64)
        .prop_map(|(d, intensity)| light(d.into(), intensity))
}

fn scene_strategy() -> impl Strategy<Value = Scene> {
    let groups = prop::collection::vec(group_strategy(), 1..4);
    let lights = prop::collection::vec(light_strategy(), 1..3);
    (8.0..30.0f64, 0.5..1.5f64, 0.0..0.4f64, lights, groups).prop_map(|(distance, angle, ambient, lights, groups)| {
        scene(distance, angle, ambient, lights, groups.into_iter().flatten().collect())
    })
}

/// Powers of ten from the ends of the range and in between.
fn power_of_ten() -> impl Strategy<Value = i32> {
    prop_oneof![Just(-150), Just(150), -150..=150i32]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Multiplying by a power of two is exact, and the renderer's formulas
    /// are homogeneous in the lengths: the same bytes, at any scale f64
    /// holds.
    #[test]
    fn a_scene_scaled_by_a_power_of_two_gives_the_same_bytes(s in scene_strategy(), k in -1000..=1000i32) {
        let original = image(&s);
        prop_assert!(original == image(&scaled(&s, 2f64.powi(k))), "scaled by 2^{}", k);
    }

    /// By `10^k` each length is rounded once more: a pixel may change
    /// only where a ray grazes an edge.
    #[test]
    fn a_scene_scaled_by_a_power_of_ten_gives_the_same_pixels(s in scene_strategy(), k in power_of_ten()) {
        let original = image(&s);
        let factor: f64 = format!("1e{k}").parse().expect("a number");
        let off = pixels_off(&original, &image(&scaled(&s, factor)));
        prop_assert!(off == 0, "scaled by 1e{}: {} pixels off", k, off);
    }

    /// The whole scene, camera included, moved along the camera's axis by up
    /// to a thousandth of the camera distance.
    #[test]
    fn a_scene_moved_with_its_camera_gives_the_same_pixels(s in scene_strategy(), fraction in -1e-3..1e-3f64) {
        let original = image(&s);
        let off = pixels_off(&original, &image(&moved_along_z(&s, fraction * s.camera.distance)));
        prop_assert!(off == 0, "moved by {} of the distance: {} pixels off", fraction, off);
    }
}

/// Two boxes whose front faces coincide, turned (so that their distances
/// are computed along different roundings): at every scale, the same box
/// is seen where they overlap, the one put first.
#[test]
fn coinciding_faces_show_the_object_put_first_at_every_scale() {
    let turned = |center: [f64; 3], length: [f64; 3], color: [f64; 3]| {
        let mut primitive = Primitive {
            shape: Shape::Box { center: center.into(), half: DVec3::from(length) / 2.0, axes: glam::DMat3::IDENTITY },
            material: material(color, 0.8, 0.3, 40.0),
        };
        primitive.rotate(&rotation_matrix(0.3, 0.2, 0.0));
        primitive
    };
    let red = turned([0.0, 0.0, 0.0], [0.6, 4.0, 0.6], [0.9, 0.2, 0.2]);
    let blue = turned([0.7, 0.2, 0.0], [1.4, 0.6, 0.6], [0.2, 0.3, 0.9]);
    let lights = vec![light([0.5, 1.0, 0.8], 0.7)];
    let s = scene(8.0, 0.8, 0.2, lights, vec![red, blue]);
    let original = image(&s);
    for k in (-150..=150).step_by(5) {
        let factor: f64 = format!("1e{k}").parse().expect("a number");
        assert_eq!(pixels_off(&original, &image(&scaled(&s, factor))), 0, "scaled by 1e{k}");
    }
}
