//! Scene builders for the renderer's integration tests.

use glam::{DMat3, DVec3};
use rayrepl::scene::{Camera, Light, Material, Primitive, Scene, Shape, TimeUse};

/// A material with colour components in 0..1.
pub fn material(color: [f64; 3], kd: f64, ks: f64, phong: f64) -> Material {
    Material { color: DVec3::from(color), kd, ks, phong }
}

/// A sphere.
pub fn sphere(center: [f64; 3], radius: f64, material: Material) -> Primitive {
    Primitive { shape: Shape::Sphere { center: DVec3::from(center), radius }, material }
}

/// The plane `normal·p = shift` (the normal is normalised).
pub fn plane(normal: [f64; 3], shift: f64, material: Material) -> Primitive {
    Primitive { shape: Shape::Plane { normal: DVec3::from(normal).normalize(), shift }, material }
}

/// A box of full sizes `length` whose own axes are the columns of `axes`.
pub fn cube(center: [f64; 3], length: [f64; 3], axes: DMat3, material: Material) -> Primitive {
    Primitive { shape: Shape::Box { center: DVec3::from(center), half: DVec3::from(length) / 2.0, axes }, material }
}

/// A directional light towards `direction` (normalised).
pub fn light(direction: [f64; 3], intensity: f64) -> Light {
    Light { direction: DVec3::from(direction).normalize(), intensity }
}

/// A scene with no time-dependent part.
pub fn scene(distance: f64, angle: f64, ambient: f64, lights: Vec<Light>, primitives: Vec<Primitive>) -> Scene {
    Scene {
        camera: Camera { distance, angle },
        ambient,
        lights,
        primitives,
        timed_primitives: Vec::new(),
        time_use: TimeUse::default(),
    }
}
