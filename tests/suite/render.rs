//! Whole-scene rendering tests: pixel values computed by hand from SPEC 5-6,
//! self-intersection ("acne") at large coordinates, BVH against brute force,
//! the skips' byte-identity, determinism across thread counts.

use std::f64::consts::{FRAC_PI_4, FRAC_PI_6, FRAC_PI_8};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use glam::{DMat3, DVec3};
use image::RgbImage;
use proptest::prelude::*;
use rayrepl::render::bvh::Bvh;
use rayrepl::render::intersect::{Bounded, BoxShape, SphereShape};
use rayrepl::render::{
    Cancelled, MAX_DEPTH, Ray, RenderControl, RenderOptions, RenderStats, SceneGeometry, Screen, Skips, glimpse_pass,
    refinement_mask, render, render_refining,
};
use rayrepl::scene::{Light, Material, Primitive, Scene, Shape};

use crate::common::scenes::{cube, light, material, plane, scene, sphere};

// ---------------------------------------------------------------- helpers

fn options(width: u32, height: u32) -> RenderOptions {
    RenderOptions { width, height, ..RenderOptions::default() }
}

fn render_with(scene: &Scene, options: &RenderOptions) -> (RgbImage, RenderStats) {
    let prepared = SceneGeometry::new(scene);
    render(scene, &prepared, options, &RenderControl::default()).expect("no cancel flag")
}

/// The single pixel of a 1x1 image: its ray is the camera's axis, (0,0,-1).
fn centre_pixel(scene: &Scene, depth: u32) -> [u8; 3] {
    let (image, _) = render_with(scene, &RenderOptions { depth, ..options(1, 1) });
    image.get_pixel(0, 0).0
}

// ------------------------------------------------- hand-computed pixels

/// Sphere of radius 2 at the origin seen from (0,0,10) along -z: P = (0,0,2),
/// N = (0,0,1), V = (0,0,-1). Light L = (0, √2/2, √2/2) (rotation π/4 about
/// x), I = 0.9; Ia = 0.2; C = (1, 0.5, 0.25), kd 0.8, ks 0.3, n 10.
///
/// N·L = √2/2 = 0.70710678; H = normalize(L - V) = normalize(0, .7071, 1.7071)
/// = (0, sin π/8, cos π/8), N·H = cos π/8 = 0.92387953, (N·H)^10 = 0.45305764.
/// kd*Ia + kd*(N·L)*I + ks*(N·H)^10*I = 0.16 + 0.50911688 + 0.12232556
/// = 0.79144245; times C and 255: (201.818, 100.909, 50.454) -> (202, 101, 50).
/// The reflected ray (0,0,1) hits nothing: + 0.3 * black.
fn one_light_scene(object: Primitive) -> Scene {
    scene(10.0, 1.0, 0.2, vec![light([0.0, FRAC_PI_4.cos(), FRAC_PI_4.sin()], 0.9)], vec![object])
}

fn one_light_material() -> Material {
    material([1.0, 0.5, 0.25], 0.8, 0.3, 10.0)
}

#[test]
fn sphere_centre_under_one_light_matches_the_formula() {
    let s = one_light_scene(sphere([0.0, 0.0, 0.0], 2.0, one_light_material()));
    assert!((FRAC_PI_8.cos().powi(10) - 0.45305764).abs() < 1e-8);
    assert_eq!(centre_pixel(&s, 5), [202, 101, 50]);
}

/// The front face of a 2x2x2 box at the origin has the same P-independent
/// data as the sphere's front point (N = (0,0,1), same V and L), so the same
/// bytes: (202, 101, 50).
#[test]
fn box_face_matches_the_formula() {
    let s = one_light_scene(cube([0.0, 0.0, 0.0], [2.0, 2.0, 2.0], DMat3::IDENTITY, one_light_material()));
    assert_eq!(centre_pixel(&s, 5), [202, 101, 50]);
}

/// Ambient only (no light): kd*Ia*C = 0.5 * 0.4 * (1, 0.6, 0.2) = (0.2, 0.12,
/// 0.04) -> (51, 30.6, 10.2) -> (51, 31, 10).
#[test]
fn ambient_only() {
    let s = scene(10.0, 1.0, 0.4, vec![], vec![sphere([0.0, 0.0, 0.0], 1.0, material([1.0, 0.6, 0.2], 0.5, 0.0, 1.0))]);
    assert_eq!(centre_pixel(&s, 5), [51, 31, 10]);
}

/// The plane z = 0 facing the camera, lit along L = (0, √2/2, √2/2): N·L =
/// 0.7071. A sphere at (0, 3, 3) of radius 1 sits on the shadow ray from
/// P = (0,0,0) but off the camera's ray (distance 3 from the z axis).
/// Shadowed: kd*Ia*C = 0.5*0.3*1 = 0.15 -> 38.25 -> 38. Lit (no blocker):
/// 0.15 + 0.5*0.7071*1 = 0.50355 -> 128.41 -> 128 (ks = 0: no specular).
#[test]
fn shadowed_point_gets_ambient_only() {
    let wall = plane([0.0, 0.0, 1.0], 0.0, material([1.0, 1.0, 1.0], 0.5, 0.0, 1.0));
    let blocker = sphere([0.0, 3.0, 3.0], 1.0, material([0.0, 1.0, 0.0], 1.0, 0.0, 1.0));
    let lights = vec![light([0.0, 1.0, 1.0], 1.0)];
    let shadowed = scene(10.0, 1.0, 0.3, lights.clone(), vec![wall, blocker]);
    assert_eq!(centre_pixel(&shadowed, 5), [38, 38, 38]);
    let lit = scene(10.0, 1.0, 0.3, lights, vec![wall]);
    assert_eq!(centre_pixel(&lit, 5), [128, 128, 128]);
}

/// A mirror plane z = 0 (kd 0, ks 0.5) reflects the camera's ray back to a
/// sphere behind the camera (centre (0,0,20), radius 1, hit at z = 19).
/// Sphere: kd*Ia*C = 1 * 0.5 * (1, 0.6, 0.2) = (0.5, 0.3, 0.1); mirror: 0 +
/// 0.5 * that = (0.25, 0.15, 0.05) -> (63.75, 38.25, 12.75) -> (64, 38, 13).
#[test]
fn one_reflection() {
    let mirror = plane([0.0, 0.0, 1.0], 0.0, material([1.0, 1.0, 1.0], 0.0, 0.5, 1.0));
    let ball = sphere([0.0, 0.0, 20.0], 1.0, material([1.0, 0.6, 0.2], 1.0, 0.0, 1.0));
    let s = scene(10.0, 1.0, 0.5, vec![], vec![mirror, ball]);
    assert_eq!(centre_pixel(&s, 5), [64, 38, 13]);
    // depth 0: no reflection term, the mirror alone is black.
    assert_eq!(centre_pixel(&s, 0), [0, 0, 0]);
}

/// Two mirror planes facing each other, z = 0 (A, red) and z = 20 (B), the
/// camera between them at z = 10. Ia = 0.3, kd = ks = 0.5.
/// local A = 0.5*0.3*(1,0,0) = (0.15,0,0); local B = 0.15*(0,0.8,1) =
/// (0,0.12,0.15). depth 2: A, B, A: c2 = (0.15,0,0); c1 = local B + 0.5 c2 =
/// (0.075,0.12,0.15); c0 = local A + 0.5 c1 = (0.1875,0.06,0.075) ->
/// (47.81,15.3,19.13) -> (48,15,19). depth 1: c1 = local B, c0 =
/// (0.15,0.06,0.075) -> (38,15,19).
#[test]
fn two_reflections_between_facing_mirrors() {
    let a = plane([0.0, 0.0, 1.0], 0.0, material([1.0, 0.0, 0.0], 0.5, 0.5, 1.0));
    let b = plane([0.0, 0.0, -1.0], -20.0, material([0.0, 0.8, 1.0], 0.5, 0.5, 1.0));
    let s = scene(10.0, 1.0, 0.3, vec![], vec![a, b]);
    assert_eq!(centre_pixel(&s, 2), [48, 15, 19]);
    assert_eq!(centre_pixel(&s, 1), [38, 15, 19]);
}

/// Clamping at every level: a mirror box face (kd 0.5, ks 0.5, C 0.5, Ia 1:
/// local 0.25, lights behind it) reflects a white sphere lit by Ia = 1 and two
/// lights of intensity 1 at N·L = 2/√5 = 0.894 each: its local colour is 1 +
/// 2*0.894 = 2.79, clamped to 1 at its own level. Pixel: 0.25 + 0.5*1 = 0.75
/// -> 191.25 -> 191 (clamping only at the end would give 0.25 + 0.5*2.79 ->
/// 255).
#[test]
fn clamping_happens_at_every_level() {
    let mirror = cube([0.0, 0.0, -0.5], [2.0, 2.0, 1.0], DMat3::IDENTITY, material([0.5, 0.5, 0.5], 0.5, 0.5, 1.0));
    let ball = sphere([0.0, 0.0, 20.0], 1.0, material([1.0, 1.0, 1.0], 1.0, 0.0, 1.0));
    let lights = vec![light([0.5, 0.0, -1.0], 1.0), light([-0.5, 0.0, -1.0], 1.0)];
    let s = scene(10.0, 1.0, 1.0, lights, vec![mirror, ball]);
    assert_eq!(centre_pixel(&s, 5), [191, 191, 191]);
}

/// SPEC 5 option: with `Screen::Bottom` the ray of a 1x1 image is
/// normalize(0, H - 0.5, -f) = normalize(0, 0.5, -1) for angle 2 atan(1/2)
/// (f = W / (2 tan(A/2)) = 1). From (0,0,10) it meets z = 0 at y = 5, where
/// a sphere sits: ambient 0.5 * kd 1 * C (1,1,1) -> 127.5 -> 128. The centred
/// ray (0,0,-1) misses it.
#[test]
fn bottom_screen_convention() {
    let s = scene(
        10.0,
        2.0 * 0.5f64.atan(),
        0.5,
        vec![],
        vec![sphere([0.0, 5.0, 0.0], 1.0, material([1.0, 1.0, 1.0], 1.0, 0.0, 1.0))],
    );
    let bottom = RenderOptions { screen: Screen::Bottom, ..options(1, 1) };
    assert_eq!(render_with(&s, &bottom).0.get_pixel(0, 0).0, [128, 128, 128]);
    assert_eq!(centre_pixel(&s, 5), [0, 0, 0]);
}

/// SPEC 4: a plane is seen only from the side its normal points to. The
/// plane z = 0 with normal (0,0,-1) has the camera on its solid side: black.
/// Flipped, it shows kd*Ia*C = 1 * 0.6 * 1 -> 153.
#[test]
fn one_sided_plane_from_behind_is_black() {
    let m = material([1.0, 1.0, 1.0], 1.0, 0.0, 1.0);
    let behind = scene(10.0, 1.0, 0.6, vec![light([0.0, 0.0, -1.0], 1.0)], vec![plane([0.0, 0.0, -1.0], 0.0, m)]);
    assert_eq!(centre_pixel(&behind, 5), [0, 0, 0]);
    let front = scene(10.0, 1.0, 0.6, vec![], vec![plane([0.0, 0.0, 1.0], 0.0, m)]);
    assert_eq!(centre_pixel(&front, 5), [153, 153, 153]);
}

/// A unit cube (half sizes 1) rotated by π/6 about y: the face hit by the
/// camera's ray has N = (sin π/6, 0, cos π/6), so N·V = -cos π/6. Light L =
/// (0,0,1), I = 0.8: N·L = cos π/6 = 0.8660254; H = normalize(L - V) =
/// (0,0,1), N·H = 0.8660254, (N·H)^2 = 0.75. Ia 0.1, kd 0.6, ks 0.3, C white:
/// 0.06 + 0.6*0.8660254*0.8 + 0.3*0.75*0.8 = 0.06 + 0.41569219 + 0.18 =
/// 0.65569219 -> 167.20 -> 167.
#[test]
fn rotated_box_face() {
    let axes = DMat3::from_rotation_y(FRAC_PI_6);
    let s = scene(
        10.0,
        1.0,
        0.1,
        vec![light([0.0, 0.0, 1.0], 0.8)],
        vec![cube([0.0, 0.0, 0.0], [2.0, 2.0, 2.0], axes, material([1.0, 1.0, 1.0], 0.6, 0.3, 2.0))],
    );
    assert_eq!(centre_pixel(&s, 5), [167, 167, 167]);
}

/// Camera at (0,0,0.5) inside a sphere of radius 2 at the origin: the hit is
/// the exit point (0,0,-2) with N = (0,0,1) facing the ray. The light along
/// +z is blocked by the sphere itself (any object at any distance): ambient
/// only, kd*Ia*C = 0.5*0.3*(1,0.5,0.25) = (0.15,0.075,0.0375). With ks = 0.5
/// and depth 1 the reflected ray hits the inside at (0,0,2), same local
/// colour: c0 = 1.5 * local = (0.225,0.1125,0.05625) -> (57.4,28.7,14.3)
/// -> (57,29,14). With ks = 0: (38.25,19.1,9.6) -> (38,19,10).
#[test]
fn camera_inside_a_sphere() {
    let lights = vec![light([0.0, 0.0, 1.0], 1.0)];
    let mirror = scene(
        0.5,
        1.0,
        0.3,
        lights.clone(),
        vec![sphere([0.0, 0.0, 0.0], 2.0, material([1.0, 0.5, 0.25], 0.5, 0.5, 3.0))],
    );
    assert_eq!(centre_pixel(&mirror, 1), [57, 29, 14]);
    let matte =
        scene(0.5, 1.0, 0.3, lights, vec![sphere([0.0, 0.0, 0.0], 2.0, material([1.0, 0.5, 0.25], 0.5, 0.0, 3.0))]);
    assert_eq!(centre_pixel(&matte, 5), [38, 19, 10]);
}

/// Camera inside a box: the hit is the exit face, N faces the camera; the
/// same numbers as inside the sphere.
#[test]
fn camera_inside_a_box() {
    let s = scene(
        0.5,
        1.0,
        0.3,
        vec![light([0.0, 0.0, 1.0], 1.0)],
        vec![cube([0.0, 0.0, 0.0], [4.0, 4.0, 4.0], DMat3::IDENTITY, material([1.0, 0.5, 0.25], 0.5, 0.5, 3.0))],
    );
    assert_eq!(centre_pixel(&s, 1), [57, 29, 14]);
}

// ------------------------------------------------------ acne at scale

/// Every pixel is either black or `expected`; returns how many are not black.
fn count_lit_exactly(image: &RgbImage, expected: [u8; 3]) -> usize {
    let mut lit = 0;
    for (x, y, p) in image.enumerate_pixels() {
        if p.0 != [0, 0, 0] {
            assert_eq!(p.0, expected, "pixel ({x}, {y})");
            lit += 1;
        }
    }
    lit
}

/// A box 30,000 wide whose front face sits at coordinates around 50,000,
/// lit at N·L = 1/√1.34 with ks = 0 (so the face has one colour): a
/// self-shadowed pixel would show ambient only.
/// Face colour: 0.5*0.2 + 0.5*(1/√1.34)*1 = 0.1 + 0.43193 = 0.53193 -> 135.6
/// -> 136.
#[test]
fn no_acne_at_coordinates_of_50000() {
    let face = material([1.0, 1.0, 1.0], 0.5, 0.0, 1.0);
    let s = scene(
        100_000.0,
        1.2,
        0.2,
        vec![light([0.3, 0.5, 1.0], 1.0)],
        vec![cube([40_000.0, 30_000.0, 0.0], [30_000.0, 30_000.0, 30_000.0], DMat3::IDENTITY, face)],
    );
    let n_dot_l = 1.0 / 1.34f64.sqrt();
    assert_eq!((255.0 * (0.1 + 0.5 * n_dot_l)).round(), 136.0);
    let (image, _) = render_with(&s, &options(160, 120));
    // The bottom face (N·L < 0, ambient only: 0.1 -> 26) is seen too: count
    // pixels of the front face only, which is the region nearer the centre.
    let mut front = 0;
    for p in image.pixels() {
        match p.0 {
            [0, 0, 0] | [26, 26, 26] => {}
            [136, 136, 136] => front += 1,
            other => panic!("unexpected pixel {other:?}"),
        }
    }
    assert!(front > 1000, "{front} front-face pixels");
}

/// A slab 15 units thin and 50,000 wide and deep under the camera, rotated
/// slightly so that its frame is not the world's; its top face is lit with
/// ks = 0, hence one colour, out to the horizon 25,000 units away.
#[test]
fn no_acne_on_a_thin_wide_box() {
    let axes = DMat3::from_rotation_z(0.01) * DMat3::from_rotation_x(0.02);
    let top = material([0.8, 0.6, 0.4], 0.7, 0.0, 1.0);
    let l = DVec3::new(0.2, 1.0, 0.3).normalize();
    let s = scene(
        100.0,
        1.0,
        0.2,
        vec![Light { direction: l, intensity: 0.8 }],
        vec![cube([0.0, -17.5, 0.0], [50_000.0, 15.0, 50_000.0], axes, top)],
    );
    let n = axes * DVec3::Y;
    let c = DVec3::new(0.8, 0.6, 0.4) * (0.7 * 0.2 + 0.7 * n.dot(l) * 0.8);
    let expected = [(255.0 * c.x).round() as u8, (255.0 * c.y).round() as u8, (255.0 * c.z).round() as u8];
    let (image, _) = render_with(&s, &options(200, 150));
    let lit = count_lit_exactly(&image, expected);
    assert!(lit > 200 * 70, "{lit} lit pixels");
}

/// Scaling a whole scene (camera distance included) leaves every ray
/// direction and normal unchanged, so the image too. A scene around 50,000
/// with mirrors, shadows and boxes renders like its copy scaled to around 5.
#[test]
fn large_coordinates_render_like_small_ones() {
    let build = |k: f64| {
        let m = |c: [f64; 3], kd, ks| material(c, kd, ks, 20.0);
        scene(
            80_000.0 * k,
            1.0,
            0.2,
            vec![light([0.4, 1.0, 0.6], 0.7), light([-0.5, 0.8, 0.3], 0.4)],
            vec![
                plane([0.0, 1.0, 0.0], -20_000.0 * k, m([0.9, 0.9, 0.9], 0.6, 0.5)),
                plane([1.0, 0.0, 0.0], -45_000.0 * k, m([0.3, 0.5, 0.9], 0.5, 0.6)),
                sphere([-10_000.0 * k, -5_000.0 * k, 10_000.0 * k], 15_000.0 * k, m([1.0, 0.3, 0.2], 0.7, 0.3)),
                cube(
                    [25_000.0 * k, -12_500.0 * k, 0.0],
                    [15_000.0 * k, 15_000.0 * k, 15_000.0 * k],
                    DMat3::from_rotation_y(0.5),
                    m([0.2, 0.9, 0.3], 0.7, 0.4),
                ),
            ],
        )
    };
    let (large, _) = render_with(&build(1.0), &options(160, 120));
    let (small, _) = render_with(&build(1e-4), &options(160, 120));
    let differing: Vec<_> =
        large.enumerate_pixels().filter(|(x, y, p)| small.get_pixel(*x, *y) != *p).map(|(x, y, _)| (x, y)).collect();
    // Only silhouette pixels may flip (a ray grazing an edge at both
    // scales); acne would flip whole regions.
    assert!(differing.len() <= 3, "{} pixels differ: {:?}", differing.len(), &differing[..differing.len().min(10)]);
}

// ------------------------------------------------------ skips, options

/// The bench's solar scene, small: a sun, an earth and a moon over a mirror
/// floor between two mirror walls, two lights.
fn solar() -> Scene {
    let m = |c: [f64; 3], kd, ks, n| material(c, kd, ks, n);
    scene(
        20.0,
        1.0,
        0.2,
        vec![light([0.0, 1.0, 0.5], 0.8), light([0.0, 0.8, -0.4], 0.4)],
        vec![
            sphere([0.0, 0.0, 0.0], 2.5, m([1.0, 0.8, 0.2], 0.9, 0.2, 30.0)),
            sphere([5.0, 0.5, -1.0], 0.8, m([0.2, 0.4, 1.0], 0.8, 0.3, 20.0)),
            sphere([6.2, 1.0, -0.5], 0.25, m([0.7, 0.7, 0.7], 0.8, 0.0, 5.0)),
            plane([0.0, 1.0, 0.0], -3.0, m([0.6, 0.6, 0.6], 0.4, 0.6, 50.0)),
            plane([1.0, 0.0, 0.0], -9.0, m([0.9, 0.6, 0.6], 0.3, 0.7, 50.0)),
            plane([-1.0, 0.0, 0.0], -9.0, m([0.6, 0.6, 0.9], 0.3, 0.7, 50.0)),
        ],
    )
}

/// Faint mirrors (ks 0.04): the reflection-weight cutoff stops paths after
/// two levels, and many pixels sit close enough to a rounding boundary to
/// resume their paths.
fn faint_mirrors() -> Scene {
    let m = |c: [f64; 3], kd, ks| material(c, kd, ks, 8.0);
    scene(
        10.0,
        1.4,
        0.3,
        vec![light([0.2, 1.0, 0.7], 0.9)],
        vec![
            plane([0.0, 0.0, 1.0], -5.0, m([0.9, 0.5, 0.2], 0.6, 0.04)),
            plane([0.0, 0.0, -1.0], -30.0, m([0.2, 0.6, 0.9], 0.6, 0.04)),
            plane([0.0, 1.0, 0.0], -2.0, m([0.8, 0.8, 0.8], 0.5, 0.04)),
            sphere([0.0, 0.0, -2.0], 1.5, m([1.0, 1.0, 1.0], 0.5, 0.04)),
        ],
    )
}

fn random_scene(seed: u64, count: usize) -> Scene {
    let mut state = seed;
    let mut next = move || {
        // xorshift64*: deterministic, no dependency.
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut primitives = vec![plane([0.0, 1.0, 0.0], -6.0, material([0.7, 0.7, 0.7], 0.5, 0.5, 40.0))];
    for k in 0..count {
        let c = [next() * 16.0 - 8.0, next() * 12.0 - 6.0, next() * 12.0 - 12.0];
        let m = material([next(), next(), next()], next(), next() * next(), 1.0 + 50.0 * next());
        if k % 2 == 0 {
            primitives.push(sphere(c, 0.2 + next(), m));
        } else {
            let axes = DMat3::from_euler(glam::EulerRot::ZYX, next() * 3.0, next() * 3.0, next() * 3.0);
            primitives.push(cube(c, [0.3 + next(), 0.3 + next(), 0.3 + next()], axes, m));
        }
    }
    scene(15.0, 1.1, 0.15, vec![light([0.3, 1.0, 0.5], 0.7), light([-0.6, 0.5, 0.4], 0.5)], primitives)
}

#[test]
fn each_skip_leaves_the_image_byte_identical() {
    let variants =
        [Skips::all(), Skips { back_facing_light: false, ..Skips::all() }, Skips { zero_ks: false, ..Skips::all() }];
    for (name, s) in [("solar", solar()), ("faint", faint_mirrors()), ("random", random_scene(7, 60))] {
        for samples in [1, 3] {
            let base = RenderOptions { skips: Skips::none(), samples, depth: 6, ..options(96, 72) };
            let (reference, full) = render_with(&s, &base);
            for skips in variants {
                let (image, stats) = render_with(&s, &RenderOptions { skips, ..base });
                assert!(image == reference, "{name}, {samples} samples, {skips:?} changed the image");
                assert!(stats.total_rays() <= full.total_rays());
            }
        }
    }
}

/// A depth beyond [`MAX_DEPTH`] is taken as it, so a path between two
/// facing mirrors stays bounded in time and memory (it used to keep a
/// growing list of levels, and abort after 4 GB).
#[test]
fn depth_beyond_the_maximum_is_the_maximum() {
    let s = faint_mirrors();
    let base = RenderOptions { depth: MAX_DEPTH, ..options(8, 6) };
    let (at_max, stats) = render_with(&s, &base);
    let (beyond, beyond_stats) = render_with(&s, &RenderOptions { depth: u32::MAX, ..base });
    assert!(at_max == beyond);
    assert_eq!(stats.rays, beyond_stats.rays);
}

/// Renders `s` with `o` on pools of 1 and of 2 threads: the bytes must match.
fn assert_same_bytes_with_one_and_two_threads(s: &Scene, o: &RenderOptions) {
    let prepared = SceneGeometry::new(s);
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool");
        pool.install(|| render(s, &prepared, o, &RenderControl::default()).expect("no cancel").0)
    };
    assert!(run(1) == run(2));
}

#[test]
fn same_bytes_with_one_and_two_threads() {
    assert_same_bytes_with_one_and_two_threads(
        &random_scene(11, 300),
        &RenderOptions { samples: 2, ..options(120, 90) },
    );
}

#[test]
fn static_and_timed_parts_render_like_one_scene() {
    // Large parts (two trees) and small ones (merged into one flat list).
    for (whole, split_at) in [(random_scene(3, 40), 20), (solar(), 2)] {
        let mut split = whole.clone();
        split.timed_primitives = split.primitives.split_off(split_at);
        let o = options(80, 60);
        let (a, _) = render_with(&whole, &o);
        let static_part =
            SceneGeometry::new(&Scene { timed_primitives: Vec::new(), ..split.clone() }).static_part().clone();
        let prepared = SceneGeometry::with_static(Arc::clone(&static_part), &split.timed_primitives);
        let (b, _) = render(&split, &prepared, &o, &RenderControl::default()).expect("no cancel");
        assert!(a == b);
    }
}

#[test]
fn progress_adds_up_and_cancel_stops() {
    let s = solar();
    let prepared = SceneGeometry::new(&s);
    let o = options(50, 37);
    let done = AtomicU64::new(0);
    let progress = |n: u64| {
        done.fetch_add(n, Ordering::Relaxed);
    };
    let control = RenderControl { progress: Some(&progress), cancel: None };
    let (_, stats) = render(&s, &prepared, &o, &control).expect("no cancel");
    assert_eq!(done.load(Ordering::Relaxed), 50 * 37);
    assert_eq!(stats.rays.primary, 50 * 37);
    let cancel = AtomicBool::new(true);
    let control = RenderControl { progress: None, cancel: Some(&cancel) };
    assert_eq!(render(&s, &prepared, &o, &control).map(|_| ()), Err(Cancelled));
}

#[test]
fn anti_aliasing_averages_samples() {
    let s = solar();
    let (one, _) = render_with(&s, &options(64, 48));
    let (four, stats) = render_with(&s, &RenderOptions { samples: 4, ..options(64, 48) });
    assert_eq!(stats.rays.primary, 64 * 48 * 4);
    assert!(one != four);
    // Flat regions stay the same; edges change.
    let same = one.pixels().zip(four.pixels()).filter(|(a, b)| a == b).count();
    assert!(same > 64 * 48 / 2);
}

#[test]
fn empty_and_degenerate_images_do_not_panic() {
    let s = solar();
    assert_eq!(render_with(&s, &options(0, 0)).0.dimensions(), (0, 0));
    assert_eq!(render_with(&s, &options(7, 0)).0.dimensions(), (7, 0));
    let mut flat = s.clone();
    flat.camera.angle = 0.0;
    let (image, _) = render_with(&flat, &options(3, 3));
    assert_eq!(image.dimensions(), (3, 3));
    let mut empty = s;
    empty.primitives.clear();
    assert!(render_with(&empty, &options(8, 8)).0.pixels().all(|p| p.0 == [0, 0, 0]));
}

// ------------------------------------------------------ BVH vs brute force

fn bounded_strategy() -> impl Strategy<Value = Bounded> {
    let coord = -10.0..10.0f64;
    prop_oneof![
        ((coord.clone(), coord.clone(), coord.clone()), 0.05..3.0f64)
            .prop_map(|(c, r)| { Bounded::Sphere(SphereShape { center: DVec3::new(c.0, c.1, c.2), radius: r }) }),
        ((coord.clone(), coord.clone(), coord), (0.05..3.0f64, 0.05..3.0f64, 0.05..3.0f64), (0.0..6.3f64, 0.0..6.3f64))
            .prop_map(|(c, h, (a, b))| {
                let axes = DMat3::from_rotation_y(a) * DMat3::from_rotation_x(b);
                Bounded::Box(BoxShape {
                    center: DVec3::new(c.0, c.1, c.2),
                    half: DVec3::new(h.0, h.1, h.2),
                    to_local: axes.transpose(),
                })
            }),
    ]
}

fn ray_strategy() -> impl Strategy<Value = Ray> {
    ((-15.0..15.0f64, -15.0..15.0f64, -15.0..15.0f64), (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64))
        .prop_filter("non-zero direction", |(_, d)| d.0 * d.0 + d.1 * d.1 + d.2 * d.2 > 1e-4)
        .prop_map(|(o, d)| Ray::new(DVec3::new(o.0, o.1, o.2), DVec3::new(d.0, d.1, d.2).normalize()))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn bvh_closest_hit_agrees_with_brute_force(
        objects in prop::collection::vec(bounded_strategy(), 0..120),
        rays in prop::collection::vec(ray_strategy(), 1..20),
    ) {
        bvh_agrees_with_brute_force(&objects, &rays, false)?;
    }
}

/// Checks the BVH over `objects` against testing every object, for the
/// closest hit (distance and object) and the any-hit answer of each ray;
/// with `secondary`, also for a ray leaving each hit along its normal, the
/// way shading starts them. Of hits within a billionth of the nearest
/// distance (coinciding faces), any is accepted here; which one the BVH
/// must take (the one put first) is checked by the tests of coinciding
/// faces below.
fn bvh_agrees_with_brute_force(objects: &[Bounded], rays: &[Ray], secondary: bool) -> Result<(), TestCaseError> {
    let (bvh, order) = Bvh::build(objects.len(), |k| objects[k]);
    let brute_force = |ray: &Ray| objects.iter().map(|o| o.hit(ray)).fold(f64::INFINITY, f64::min);
    let same_distance = |t: f64, nearest: f64| nearest <= t && t <= nearest * (1.0 + 1e-9);
    for ray in rays {
        let brute = brute_force(ray);
        let (t, index) = bvh.closest_hit(ray, f64::INFINITY);
        if brute == f64::INFINITY {
            prop_assert_eq!(index, u32::MAX);
        } else {
            prop_assert!(same_distance(t, brute), "{} for {}", t, brute);
            let hit = &objects[order[index as usize] as usize];
            prop_assert_eq!(hit.hit(ray), t);
            if secondary {
                let n = hit.normal(ray, t);
                let out = Ray::new(ray.at(t) + n * 1e-9, n);
                let brute_out = brute_force(&out);
                let t_out = bvh.closest_hit(&out, f64::INFINITY).0;
                prop_assert!(t_out == brute_out || same_distance(t_out, brute_out), "{} for {}", t_out, brute_out);
                prop_assert_eq!(bvh.any_hit(&out, f64::INFINITY), brute_out < f64::INFINITY);
            }
        }
        prop_assert_eq!(bvh.any_hit(ray, f64::INFINITY), brute < f64::INFINITY);
    }
    Ok(())
}

/// Boxes that all share one turned frame (the renderer groups them in that
/// frame), on a grid where neighbours touch, and some randomly placed.
fn shared_axes_boxes() -> impl Strategy<Value = Vec<Bounded>> {
    let cell = (0..6i32, 0..6i32, 0..6i32);
    ((0.0..6.3f64, 0.0..6.3f64), prop::collection::vec(cell, 0..120), prop::collection::vec(-8.0..8.0f64, 0..30))
        .prop_map(|((a, b), cells, loose)| {
            let axes = DMat3::from_rotation_y(a) * DMat3::from_rotation_x(b);
            let boxed = |c: DVec3, half: DVec3| Bounded::Box(BoxShape { center: c, half, to_local: axes.transpose() });
            let grid = cells.into_iter().map(|(x, y, z)| {
                boxed(axes * (DVec3::new(f64::from(x), f64::from(y), f64::from(z)) - 2.5), DVec3::splat(0.5))
            });
            let scattered = loose
                .chunks(3)
                .map(|c| boxed(DVec3::from_slice(&[c[0], c[0] * 0.7, c[0] * -0.3]), DVec3::new(0.3, 0.6, 0.2)));
            grid.chain(scattered).collect()
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn bvh_over_boxes_with_shared_axes_agrees_with_brute_force(
        objects in shared_axes_boxes(),
        rays in prop::collection::vec(ray_strategy(), 1..20),
    ) {
        bvh_agrees_with_brute_force(&objects, &rays, true)?;
    }
}

fn primitive_strategy() -> impl Strategy<Value = Primitive> {
    let m = material([0.5, 0.5, 0.5], 0.5, 0.5, 10.0);
    prop_oneof![
        3 => bounded_strategy().prop_map(move |b| match b {
            Bounded::Sphere(s) => sphere(s.center.into(), s.radius, m),
            Bounded::Box(b) => Primitive {
                shape: Shape::Box { center: b.center, half: b.half, axes: b.to_local.transpose() },
                material: m,
            },
        }),
        1 => ((-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64), -10.0..10.0f64)
            .prop_filter("non-zero normal", |(n, _)| n.0 * n.0 + n.1 * n.1 + n.2 * n.2 > 1e-4)
            .prop_map(move |(n, d)| plane([n.0, n.1, n.2], d, m)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]

    /// Shadow rays (any hit, planes pre-filtered per light direction) agree
    /// with the existence of a closest hit, with and without a tree, with
    /// and without a timed part.
    #[test]
    fn any_hit_and_blocked_agree_with_closest_hit(
        primitives in prop::collection::vec(primitive_strategy(), 0..40),
        split in 0usize..40,
        rays in prop::collection::vec(ray_strategy(), 1..20),
    ) {
        let mut s = scene(10.0, 1.0, 0.1, vec![], primitives);
        s.timed_primitives = s.primitives.split_off(split.min(s.primitives.len()));
        let prepared = SceneGeometry::new(&s);
        for ray in &rays {
            let exists = prepared.closest_hit(ray).is_some();
            prop_assert_eq!(prepared.any_hit(ray), exists);
            let planes = prepared.planes_blocking(ray.dir);
            prop_assert_eq!(prepared.blocked(ray, &planes), exists);
        }
    }
}
// ------------------------------------------------- adaptive anti-aliasing

/// Pixels not flagged keep the 1-sample bytes; flagged ones get the uniform
/// bytes.
#[test]
fn adaptive_refines_exactly_the_flagged_pixels_with_the_uniform_bytes() {
    for (name, s) in [("solar", solar()), ("random", random_scene(5, 200))] {
        let base = options(96, 72);
        let (one, glimpses) = glimpse_pass(&s, &SceneGeometry::new(&s), &base);
        let (uniform, _) = render_with(&s, &RenderOptions { samples: 9, ..base });
        let (adaptive, stats) = render_with(&s, &RenderOptions { samples: 9, adaptive: true, ..base });
        let mask = refinement_mask(&one, &glimpses);
        let flagged = mask.iter().filter(|&&f| f).count();
        assert!(0 < flagged && flagged < mask.len(), "{name}: {flagged} pixels flagged");
        assert_eq!(stats.refined_pixels, flagged as u64, "{name}");
        for (k, &refine) in mask.iter().enumerate() {
            let (x, y) = ((k % 96) as u32, (k / 96) as u32);
            let expected = if refine { uniform.get_pixel(x, y) } else { one.get_pixel(x, y) };
            assert_eq!(adaptive.get_pixel(x, y), expected, "{name}: pixel ({x}, {y})");
        }
    }
}

/// Given the detector's own mask, `render_refining` is `render`; given other
/// pixels, it refines exactly those (no pixel: the 1-sample image).
#[test]
fn render_refining_refines_the_pixels_given() {
    let s = solar();
    let prepared = SceneGeometry::new(&s);
    let o = RenderOptions { samples: 9, adaptive: true, ..options(96, 72) };
    let refining = |flags: &[bool]| render_refining(&s, &prepared, &o, flags, &RenderControl::default()).unwrap();
    let (one, glimpses) = glimpse_pass(&s, &prepared, &o);
    let (adaptive, stats) = render_with(&s, &o);
    let (given, given_stats) = refining(&refinement_mask(&one, &glimpses));
    assert!(given == adaptive);
    assert_eq!(given_stats.rays, stats.rays);
    let (none, none_stats) = refining(&[false; 96 * 72]);
    assert!(none == one);
    assert_eq!((none_stats.refined_pixels, none_stats.rays.primary), (0, 96 * 72));
    let mut corner = [false; 96 * 72];
    corner[0] = true;
    let (_, corner_stats) = refining(&corner);
    assert_eq!(corner_stats.refined_pixels, 1);
    assert_eq!(corner_stats.rays.primary, 96 * 72 + 9);
}

/// The centre pixel of a 101x101 image looks down the camera's axis. A
/// sphere of radius 1 at the origin, seen from distance 10, is hit at t = 9
/// and spans 2 / 9 radians; a pixel spans 2 tan(angle / 2) / 101.
#[test]
fn a_glimpse_measures_the_apparent_size_of_what_it_hits() {
    let ball = sphere([0.0, 0.0, 0.0], 1.0, material([1.0, 1.0, 1.0], 0.8, 0.0, 1.0));
    let s = scene(10.0, 1.0, 0.2, vec![light([0.0, 0.0, 1.0], 0.8)], vec![ball]);
    let (_, glimpses) = glimpse_pass(&s, &SceneGeometry::new(&s), &options(101, 101));
    let pixel_angle = 2.0 * 0.5f64.tan() / 101.0;
    let expected = (2.0 / 9.0) / pixel_angle;
    let centre = glimpses[50 * 101 + 50].finest;
    assert!((centre - expected).abs() < 1e-9 * expected, "{centre} against {expected}");
    // A ray that misses everything meets nothing.
    assert_eq!(glimpses[0].finest, f64::INFINITY);
}

/// A convex mirror spreads the beam of a pixel: the centre ray hits a
/// mirror sphere of radius 1 head-on at t = 9, where the beam is 9 pixel
/// angles wide; the normal turns by 9 pixel angles across it, so the
/// reflected beam spreads by 1 + 2 * 9 = 19 pixel angles. It goes back along
/// +z to a sphere of radius 2 behind the camera (centre z = 20), 17 further:
/// 9 + 19 * 17 = 332 pixel angles wide there, for a width of 4.
#[test]
fn a_glimpse_follows_the_beam_through_a_curved_mirror() {
    let mirror = sphere([0.0, 0.0, 0.0], 1.0, material([1.0, 1.0, 1.0], 0.0, 0.9, 1.0));
    let behind = sphere([0.0, 0.0, 20.0], 2.0, material([1.0, 1.0, 1.0], 1.0, 0.0, 1.0));
    let s = scene(10.0, 1.0, 0.5, vec![], vec![mirror, behind]);
    let (_, glimpses) = glimpse_pass(&s, &SceneGeometry::new(&s), &options(101, 101));
    let pixel_angle = 2.0 * 0.5f64.tan() / 101.0;
    let expected = 4.0 / (332.0 * pixel_angle);
    let centre = glimpses[50 * 101 + 50].finest;
    assert!((centre - expected).abs() < 1e-9 * expected, "{centre} against {expected}");
}

/// Pixels of one colour on one matt surface share a signature; a shadow, a
/// box's other face, or another object changes it.
#[test]
fn glimpse_signatures_change_where_the_colour_may_jump() {
    let matt = |c: [f64; 3]| material(c, 0.8, 0.0, 1.0);
    let wall = plane([0.0, 0.0, 1.0], -4.0, matt([1.0, 1.0, 1.0]));
    let turned = DMat3::from_rotation_y(FRAC_PI_6) * DMat3::from_rotation_x(FRAC_PI_8);
    let block = cube([-2.0, 0.0, 0.0], [2.0, 2.0, 2.0], turned, matt([0.2, 0.6, 1.0]));
    let ball = sphere([2.5, 1.0, 0.0], 1.0, matt([1.0, 0.3, 0.1]));
    let s = scene(12.0, 1.0, 0.2, vec![light([0.3, 0.5, 1.0], 0.8)], vec![wall, block, ball]);
    let (image, glimpses) = glimpse_pass(&s, &SceneGeometry::new(&s), &options(160, 120));
    // The wall and each face of the box are flat and matt: one colour each,
    // in light or in shadow. The most frequent colours are the lit wall,
    // the wall in the shadows, and the faces.
    let mut by_colour: std::collections::HashMap<[u8; 3], Vec<u64>> = std::collections::HashMap::new();
    for (pixel, glimpse) in image.pixels().zip(&glimpses) {
        by_colour.entry(pixel.0).or_default().push(glimpse.signature);
    }
    let mut flat: Vec<(usize, u64)> = by_colour
        .values()
        .filter(|signatures| signatures.len() >= 100)
        .map(|signatures| {
            assert!(signatures.iter().all(|&s| s == signatures[0]), "one colour, one flat surface, one signature");
            (signatures.len(), signatures[0])
        })
        .collect();
    flat.sort();
    assert!(flat.len() >= 4, "lit wall, shadowed wall, and at least two faces: {flat:?}");
    let mut distinct: Vec<u64> = flat.iter().map(|&(_, s)| s).collect();
    distinct.dedup();
    assert_eq!(distinct.len(), flat.len(), "different colours, different signatures");
    // The ball's pixels are no flat surface's.
    let ball_pixel = glimpses[(120 / 2 - 10) * 160 + 160 / 2 + 25];
    assert!(flat.iter().all(|&(_, s)| s != ball_pixel.signature));
}

/// Where the shading is smooth (a sphere filling the frame: no edge), adaptive
/// sampling leaves most pixels at one sample, and no pixel ends more than
/// one level from the uniform render. The two highlights (Phong 20,000) are a
/// few pixels wide: without the bend test, their centres would be up to 8
/// levels off.
#[test]
fn adaptive_leaves_smooth_shading_within_a_level_of_uniform() {
    let ball = sphere([0.0, 0.0, 0.0], 2.0, material([1.0, 0.8, 0.6], 0.7, 0.3, 20_000.0));
    let lights = vec![light([0.3, 0.3, 1.0], 0.6), light([-0.7, 0.2, 0.4], 0.3)];
    let s = scene(10.0, 0.3, 0.2, lights, vec![ball]);
    let base = options(120, 90);
    let (uniform, _) = render_with(&s, &RenderOptions { samples: 16, ..base });
    let (adaptive, stats) = render_with(&s, &RenderOptions { samples: 16, adaptive: true, ..base });
    assert!(stats.refined_pixels < 120 * 90 / 4, "{stats:?}");
    for (a, u) in adaptive.pixels().zip(uniform.pixels()) {
        assert!(a.0.iter().zip(u.0).all(|(&p, q)| p.abs_diff(q) <= 1), "{a:?} against {u:?}");
    }
}

#[test]
fn adaptive_on_a_flat_image_is_the_one_sample_image() {
    // A matt wall filling the view: one colour everywhere, no edge.
    let wall = plane([0.0, 0.0, 1.0], -5.0, material([0.8, 0.4, 0.2], 0.9, 0.0, 1.0));
    let s = scene(10.0, 0.8, 0.2, vec![light([0.2, 0.5, 1.0], 0.7)], vec![wall]);
    let base = options(40, 30);
    let (one, glimpses) = glimpse_pass(&s, &SceneGeometry::new(&s), &base);
    assert!(refinement_mask(&one, &glimpses).iter().all(|&f| !f));
    let (adaptive, stats) = render_with(&s, &RenderOptions { samples: 16, adaptive: true, ..base });
    assert!(adaptive == one);
    assert_eq!(stats.rays.primary, 40 * 30);
}

#[test]
fn adaptive_gives_the_same_bytes_with_one_and_two_threads() {
    let o = RenderOptions { samples: 4, adaptive: true, ..options(120, 90) };
    assert_same_bytes_with_one_and_two_threads(&random_scene(11, 300), &o);
}

/// A huge depth between two perfect mirrors is taken as [`MAX_DEPTH`]: it
/// neither overflows the stack nor produces anything but the clamped sum.
/// local = kd*Ia*C = 0.5*0.2 = 0.1 per level, ks = 1: the sum saturates at
/// 1 -> 255.
#[test]
fn huge_depth_between_perfect_mirrors() {
    let m = material([1.0, 1.0, 1.0], 0.5, 1.0, 1.0);
    let s = scene(10.0, 1.0, 0.2, vec![], vec![plane([0.0, 0.0, 1.0], 0.0, m), plane([0.0, 0.0, -1.0], -20.0, m)]);
    let (image, stats) = render_with(&s, &RenderOptions { depth: 100_000, ..options(1, 1) });
    assert_eq!(image.get_pixel(0, 0).0, [255, 255, 255]);
    assert_eq!(stats.rays.reflection, u64::from(MAX_DEPTH));
}

/// Two grids of 48 cubes whose front faces lie in the plane z = 0: thin
/// red cubes on a unit grid and deep blue ones on the grid moved by half a
/// cell, so that most camera rays meet a red and a blue face at one
/// distance, and the cubes' centres lie apart (a tree orders them as it
/// likes). Each pixel must show the grid put first where both cover the
/// pixel (docs/language.md: "the object put first is seen"), the only one
/// where one does; pixels whose ray passes within 0.01 of an edge or
/// through a gap of both grids are not checked. With `sphere`, a
/// sphere out of view joins them (objects that are not all boxes of one
/// frame take the tree's other path).
fn assert_coinciding_faces_show_the_first_put(red_first: bool, sphere_too: bool) {
    let (width, height, distance, angle) = (64u32, 48u32, 20.0, 0.5f64);
    let (red, blue) = (material([1.0, 0.0, 0.0], 1.0, 0.0, 1.0), material([0.0, 0.0, 1.0], 1.0, 0.0, 1.0));
    let grid = |shift: f64, depth: f64, m: Material| {
        (0..48).map(move |k| {
            let (x, y) = (f64::from(k % 8) - 3.5 + shift, f64::from(k / 8) - 2.5 + shift);
            cube([x, y, -depth / 2.0], [0.9, 0.9, depth], DMat3::IDENTITY, m)
        })
    };
    let (reds, blues) = (grid(0.0, 0.2, red), grid(0.5, 1.0, blue));
    let mut primitives: Vec<Primitive> =
        if red_first { reds.chain(blues).collect() } else { blues.chain(reds).collect() };
    if sphere_too {
        primitives.push(sphere([0.0, 0.0, 40.0], 1.0, red));
    }
    let s = scene(distance, angle, 1.0, vec![], primitives);
    let (image, _) = render_with(&s, &options(width, height));
    // Where the ray of pixel (i, j) meets z = 0, and whether a grid moved
    // by `shift` covers it (`None` near an edge).
    let f = f64::from(width) / (2.0 * (angle / 2.0).tan());
    let covers = |i: u32, j: u32, shift: f64| {
        let dir =
            DVec3::new(f64::from(i) + 0.5 - f64::from(width) / 2.0, f64::from(height) / 2.0 - (f64::from(j) + 0.5), -f);
        let p = DVec3::new(0.0, 0.0, distance) + dir * (distance / f);
        // On one of `n` cells 0.9 wide centred at `first`, `first + 1`, ...
        let inside = |v: f64, first: f64, n: f64| {
            let cell = (v - first).round();
            let off = (v - first - cell).abs();
            ((off - 0.45).abs() > 0.01).then_some(off < 0.45 && (0.0..n).contains(&cell))
        };
        Some(inside(p.x, -3.5 + shift, 8.0)? && inside(p.y, -2.5 + shift, 6.0)?)
    };
    let mut checked = 0;
    for (i, j, pixel) in image.enumerate_pixels() {
        let (Some(r), Some(b)) = (covers(i, j, 0.0), covers(i, j, 0.5)) else { continue };
        let expected = match (r, b) {
            (true, true) => {
                if red_first {
                    [255, 0, 0]
                } else {
                    [0, 0, 255]
                }
            }
            (true, false) => [255, 0, 0],
            (false, true) => [0, 0, 255],
            // Through a gap: the side of a cube behind may be seen.
            (false, false) => continue,
        };
        assert_eq!(pixel.0, expected, "pixel ({i}, {j}), red first: {red_first}, sphere: {sphere_too}");
        checked += 1;
    }
    assert!(checked > 1000, "{checked} pixels checked");
}

#[test]
fn of_coinciding_faces_the_object_put_first_is_seen() {
    for (red_first, sphere_too) in [(true, false), (false, false), (true, true), (false, true)] {
        assert_coinciding_faces_show_the_first_put(red_first, sphere_too);
    }
}

/// Of a fixed object and one that depends on `time`, met at one distance,
/// the fixed one is seen (spheres and boxes still before planes), whether
/// the two parts are merged into one list (few objects) or asked one after
/// the other (the fixed part has a tree): the language guide's order.
#[test]
fn of_coinciding_fixed_and_timed_surfaces_the_fixed_one_is_seen() {
    let (red, blue) = (material([1.0, 0.0, 0.0], 1.0, 0.0, 1.0), material([0.0, 0.0, 1.0], 1.0, 0.0, 1.0));
    // Boxes whose front faces lie in z = 0, on the camera's axis.
    let front_at_zero = |depth: f64, m: Material| cube([0.0, 0.0, -depth / 2.0], [1.0, 1.0, depth], DMat3::IDENTITY, m);
    let far_spheres = || (0..5).map(|k| sphere([f64::from(k) * 3.0 - 6.0, 8.0, -20.0], 0.5, blue));
    for tree in [false, true] {
        let extra: Vec<Primitive> = if tree { far_spheres().collect() } else { Vec::new() };
        let fixed_box: Vec<Primitive> = [front_at_zero(1.0, blue)].into_iter().chain(extra.clone()).collect();
        let s = Scene { timed_primitives: vec![front_at_zero(2.0, red)], ..scene(10.0, 1.0, 1.0, vec![], fixed_box) };
        assert_eq!(centre_pixel(&s, 0), [0, 0, 255], "fixed box against a timed box, tree {tree}");
        let fixed_plane: Vec<Primitive> = [plane([0.0, 0.0, 1.0], 0.0, blue)].into_iter().chain(extra).collect();
        let s = Scene { timed_primitives: vec![front_at_zero(2.0, red)], ..scene(10.0, 1.0, 1.0, vec![], fixed_plane) };
        assert_eq!(centre_pixel(&s, 0), [255, 0, 0], "fixed plane against a timed box, tree {tree}");
    }
}
