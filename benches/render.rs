//! Rendering benchmarks: the solar scene (few objects, many mirror bounces)
//! at 1920x1080 depth 5, a 100-frame 800x600 animation of it, and a field of
//! 160,000 boxes at 1920x1080 including the BVH build.
//!
//! `cargo bench --bench render` runs them under criterion.
//! `RAYREPL_BENCH_REPORT=1 cargo bench --bench render` instead renders each
//! once (after a warm-up) and prints times, ray counts and rays per second
//! per core; handy under `perf record`.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group};
use glam::{DMat3, DVec3};
use rayrepl::render::{RenderControl, RenderOptions, RenderStats, SceneGeometry, render};
use rayrepl::scene::{Camera, Light, Material, Primitive, Scene, Shape, TimeUse};

fn material(color: [f64; 3], kd: f64, ks: f64, phong: f64) -> Material {
    Material { color: DVec3::from(color), kd, ks, phong }
}

fn sphere(center: DVec3, radius: f64, material: Material) -> Primitive {
    Primitive { shape: Shape::Sphere { center, radius }, material }
}

fn plane(normal: DVec3, shift: f64, material: Material) -> Primitive {
    Primitive { shape: Shape::Plane { normal: normal.normalize(), shift }, material }
}

fn light(direction: [f64; 3], intensity: f64) -> Light {
    Light { direction: DVec3::from(direction).normalize(), intensity }
}

/// The sun, the earth and the moon over a mirror floor (ks 0.6) between two
/// mirror walls, two lights. `time` moves the earth and the moon (they are
/// the timed part).
fn solar(time: f64) -> Scene {
    let angle = time * 0.05;
    let earth = DVec3::new(5.0 * angle.cos(), 0.5, -5.0 * angle.sin());
    let moon = earth + DVec3::new(1.3 * (4.0 * angle).cos(), 0.3, -1.3 * (4.0 * angle).sin());
    Scene {
        camera: Camera { distance: 20.0, angle: 1.0 },
        ambient: 0.2,
        // Lights in the walls' plane: the walls are infinite planes, so a light
        // with an x component would be blocked by one of them everywhere.
        lights: vec![light([0.0, 1.0, 0.5], 0.8), light([0.0, 0.8, -0.4], 0.4)],
        primitives: vec![
            sphere(DVec3::ZERO, 2.5, material([1.0, 0.8, 0.2], 0.9, 0.2, 30.0)),
            plane(DVec3::Y, -3.0, material([0.6, 0.6, 0.6], 0.4, 0.6, 50.0)),
            plane(DVec3::X, -9.0, material([0.9, 0.6, 0.6], 0.3, 0.7, 50.0)),
            plane(-DVec3::X, -9.0, material([0.6, 0.6, 0.9], 0.3, 0.7, 50.0)),
        ],
        timed_primitives: vec![
            sphere(earth, 0.8, material([0.2, 0.4, 1.0], 0.8, 0.3, 20.0)),
            sphere(moon, 0.25, material([0.7, 0.7, 0.7], 0.8, 0.0, 5.0)),
        ],
        time_use: TimeUse::default(),
    }
}

/// 400 x 400 boxes of random heights and turns on a floor, under two lights;
/// one box in eight is a mirror.
fn box_field() -> Scene {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut primitives = vec![plane(DVec3::Y, -4.0, material([0.5, 0.5, 0.5], 0.7, 0.2, 10.0))];
    for gx in 0..400 {
        for gz in 0..400 {
            let height = 0.2 + 1.5 * next() * next();
            let center = DVec3::new(-100.0 + gx as f64 * 0.5, -4.0 + height / 2.0, 10.0 - gz as f64 * 0.5);
            let axes = DMat3::from_rotation_y(next() * 1.5);
            let ks = if next() < 0.125 { 0.5 } else { 0.0 };
            let m = material([0.3 + 0.7 * next(), 0.3 + 0.7 * next(), 0.3 + 0.7 * next()], 0.7, ks, 20.0);
            let half = DVec3::new(0.18, height / 2.0, 0.18);
            primitives.push(Primitive { shape: Shape::Box { center, half, axes }, material: m });
        }
    }
    Scene {
        camera: Camera { distance: 20.0, angle: 1.2 },
        ambient: 0.15,
        lights: vec![light([0.4, 1.0, 0.6], 0.7), light([-0.7, 0.6, 0.2], 0.4)],
        primitives,
        timed_primitives: Vec::new(),
        time_use: TimeUse::default(),
    }
}

fn options(width: u32, height: u32) -> RenderOptions {
    RenderOptions { width, height, depth: 5, ..RenderOptions::default() }
}

fn render_once(scene: &Scene, prepared: &SceneGeometry, width: u32, height: u32) -> RenderStats {
    let (image, stats) =
        render(scene, prepared, &options(width, height), &RenderControl::default()).expect("no cancel");
    black_box(image);
    stats
}

/// Renders `frames` frames of the solar animation, reusing the static part.
fn solar_animation(frames: u32, width: u32, height: u32) -> RenderStats {
    let static_part = SceneGeometry::new(&Scene { timed_primitives: Vec::new(), ..solar(0.0) }).static_part().clone();
    let mut total = RenderStats::default();
    for k in 1..=frames {
        let scene = solar(f64::from(k));
        let prepared = SceneGeometry::with_static(static_part.clone(), &scene.timed_primitives);
        let stats = render_once(&scene, &prepared, width, height);
        total.rays += stats.rays;
        total.elapsed += stats.elapsed;
    }
    total
}

fn bench_solar(c: &mut Criterion) {
    let scene = solar(0.0);
    let prepared = SceneGeometry::new(&scene);
    let mut group = c.benchmark_group("solar");
    group.sample_size(10).measurement_time(Duration::from_secs(8));
    group.bench_function("1920x1080 depth 5", |b| b.iter(|| render_once(&scene, &prepared, 1920, 1080)));
    group.bench_function("100 frames 800x600", |b| b.iter(|| solar_animation(100, 800, 600)));
    group.finish();
}

fn bench_boxes(c: &mut Criterion) {
    let scene = box_field();
    let mut group = c.benchmark_group("boxes");
    group.sample_size(10).measurement_time(Duration::from_secs(15));
    group.bench_function("160k build", |b| b.iter(|| SceneGeometry::new(&scene)));
    group.bench_function("160k build + 1920x1080", |b| {
        b.iter(|| {
            let prepared = SceneGeometry::new(&scene);
            render_once(&scene, &prepared, 1920, 1080)
        })
    });
    group.finish();
}

criterion_group!(benches, bench_solar, bench_boxes);

/// One line of the report: time, rays and rays per second per core.
fn report(name: &str, elapsed: Duration, stats: &RenderStats) {
    let cores = rayon::current_num_threads() as f64;
    let rays = stats.total_rays() as f64;
    println!(
        "{name:<28} {:>8.3} s  {:>6.1} Mrays (primary {:.1} M, shadow {:.1} M, reflection {:.1} M)  {:>6.1} Mrays/s/core on {cores} threads",
        elapsed.as_secs_f64(),
        rays / 1e6,
        stats.rays.primary as f64 / 1e6,
        stats.rays.shadow as f64 / 1e6,
        stats.rays.reflection as f64 / 1e6,
        rays / 1e6 / elapsed.as_secs_f64() / cores,
    );
}

fn run_report(which: &str) {
    if let Some(size) = which.strip_prefix("solar-") {
        // One frame of a given size, e.g. `solar-320x180` (for callgrind).
        let (w, h) = size.split_once('x').expect("solar-WxH");
        let (w, h) = (w.parse().expect("width"), h.parse().expect("height"));
        let scene = solar(0.0);
        let prepared = SceneGeometry::new(&scene);
        let start = Instant::now();
        let (image, stats) = render(&scene, &prepared, &options(w, h), &RenderControl::default()).expect("no cancel");
        report(&format!("solar {w}x{h} d5"), start.elapsed(), &stats);
        if let Ok(path) = std::env::var("RAYREPL_BENCH_SAVE") {
            rayrepl::output::write_image(std::path::Path::new(&path), &image).expect("write image");
        }
        return;
    }
    if which == "skips" {
        // What each skip saves on the solar scene (one frame, 1920x1080).
        use rayrepl::render::Skips;
        let scene = solar(0.0);
        let prepared = SceneGeometry::new(&scene);
        let variants = [
            ("all skips", Skips::all()),
            ("no back-facing skip", Skips { back_facing_light: false, ..Skips::all() }),
            ("no ks=0 skip", Skips { zero_ks: false, ..Skips::all() }),
            ("no skips", Skips::none()),
        ];
        for (name, skips) in variants {
            let o = RenderOptions { skips, ..options(1920, 1080) };
            let start = Instant::now();
            let (_, stats) = render(&scene, &prepared, &o, &RenderControl::default()).expect("no cancel");
            report(name, start.elapsed(), &stats);
        }
        return;
    }
    if which == "animation" {
        let start = Instant::now();
        let stats = solar_animation(100, 800, 600);
        report("solar 100 x 800x600 d5", start.elapsed(), &stats);
        return;
    }
    if which.contains("solar") || which == "1" {
        let scene = solar(0.0);
        let prepared = SceneGeometry::new(&scene);
        render_once(&scene, &prepared, 1920, 1080);
        let start = Instant::now();
        let stats = render_once(&scene, &prepared, 1920, 1080);
        report("solar 1920x1080 d5", start.elapsed(), &stats);
        let start = Instant::now();
        let stats = solar_animation(100, 800, 600);
        report("solar 100 x 800x600 d5", start.elapsed(), &stats);
    }
    if which.contains("boxes") || which == "1" {
        let scene = box_field();
        let start = Instant::now();
        let prepared = SceneGeometry::new(&scene);
        let build = start.elapsed();
        let stats = render_once(&scene, &prepared, 1920, 1080);
        println!("boxes 160k BVH build         {:>8.3} s", build.as_secs_f64());
        report("boxes 160k build+1920x1080", start.elapsed(), &stats);
    }
}

fn main() {
    match std::env::var("RAYREPL_BENCH_REPORT") {
        Ok(which) => run_report(&which),
        Err(_) => {
            benches();
            Criterion::default().configure_from_args().final_summary();
        }
    }
}
