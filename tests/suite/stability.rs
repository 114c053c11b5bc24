//! Numerical stability under stress: extreme coordinates and aspect ratios,
//! grazing rays, coinciding faces, the camera inside objects, objects behind
//! the camera, extreme depths and phong exponents, long chains of
//! transformations.
//!
//! Every case checks three things:
//! - every hit along every pixel's path (primary ray and its chain of
//!   reflections) is finite, in front of the ray, with a unit normal facing
//!   the ray ([`assert_sane_paths`]): NaN or infinity never reaches shading;
//! - no acne: the 1-sample image matches either colours computed by hand
//!   from SPEC 6, or the reference render ([`RenderOptions::reference`]) on
//!   its smooth pixels (away from edges, where anti-aliasing rightly
//!   differs), within 2 levels on all but a tiny share of pixels;
//! - determinism: identical bytes with 1 and 2 threads.

use glam::{DMat3, DVec3};
use image::RgbImage;
use rayrepl::lang::{Interpreter, Limits, SourceMap, parse_items};
use rayrepl::render::shade::offset_origin;
use rayrepl::render::{Ray, RenderControl, RenderOptions, SceneGeometry, Screen, Skips, render};
use rayrepl::scene::{Material, Scene, Shape};

use crate::common::scenes::{cube, light, material, plane, scene, sphere};

// ---------------------------------------------------------------- helpers

/// A matte material (ks = 0): flat faces under directional lights get one
/// uniform colour, which makes acne easy to see.
fn matte(color: [f64; 3]) -> Material {
    material(color, 0.8, 0.0, 1.0)
}

/// The scene of a `.ray` program (session-style items) that must succeed.
fn eval(text: &str) -> Scene {
    let mut sources = SourceMap::new();
    let id = sources.add("stability.ray", text.to_string(), 0);
    let program = parse_items(id, text).unwrap_or_else(|d| panic!("syntax error: {}\n{text}", d.message));
    let mut interpreter = Interpreter::new(0.0, Limits::default());
    if let Err(d) = interpreter.run(&program) {
        panic!("evaluation error: {}\n{text}", d.message);
    }
    interpreter.into_scene()
}

fn options(width: u32, height: u32, depth: u32) -> RenderOptions {
    RenderOptions { width, height, depth, ..RenderOptions::default() }
}

/// Renders in a pool of `threads` rayon threads.
fn render_in_pool(scene: &Scene, options: &RenderOptions, threads: usize) -> RgbImage {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a rayon pool");
    pool.install(|| {
        let prepared = SceneGeometry::new(scene);
        render(scene, &prepared, options, &RenderControl::default()).expect("no cancel flag").0
    })
}

/// Renders with 1 and with 2 threads, asserts the bytes are identical and
/// that every path is sane, and returns the image.
fn render_checked(scene: &Scene, options: &RenderOptions) -> RgbImage {
    assert_sane_paths(scene, options);
    let one = render_in_pool(scene, options, 1);
    let two = render_in_pool(scene, options, 2);
    assert!(one.as_raw() == two.as_raw(), "the image depends on the number of threads");
    one
}

/// Follows the primary ray of every pixel centre and its mirror reflections
/// up to `options.depth`, as the shader does (SPEC 6), and checks each hit:
/// finite `t > 0`, finite point, unit normal facing the ray, and a finite
/// offset origin. Shadow rays start from that same origin along unit light
/// directions, so they are covered too. Returns the number of hits checked.
fn assert_sane_paths(scene: &Scene, options: &RenderOptions) -> usize {
    let prepared = SceneGeometry::new(scene);
    let rays = prepared.primary_rays(&scene.camera, options.width, options.height, options.screen);
    let mut hits = 0;
    for j in 0..options.height {
        for i in 0..options.width {
            let mut ray = rays.ray(i, j, glam::DVec2::splat(0.5));
            assert!(ray.dir.is_finite() && ray.origin.is_finite());
            for _level in 0..=options.depth {
                let Some(hit) = prepared.closest_hit(&ray) else { break };
                hits += 1;
                let at = format!("pixel ({i}, {j}), ray {ray:?}, hit {hit:?}");
                assert!(hit.t.is_finite() && hit.t > 0.0, "bad t at {at}");
                assert!(hit.point.is_finite(), "bad point at {at}");
                assert!((hit.normal.length() - 1.0).abs() < 1e-9, "normal not unit at {at}");
                assert!(hit.normal.dot(ray.dir) <= 1e-12, "normal not facing the ray at {at}");
                let origin = offset_origin(hit.point, hit.normal, hit.t);
                assert!(origin.is_finite(), "bad offset origin at {at}");
                let d = ray.dir;
                let reflected = d - hit.normal * (2.0 * d.dot(hit.normal));
                assert!((reflected.length() - 1.0).abs() < 1e-9, "reflection not unit at {at}");
                ray = Ray::new(origin, reflected);
            }
        }
    }
    hits
}

/// The largest difference of one channel between two pixels.
fn channel_diff(a: [u8; 3], b: [u8; 3]) -> u8 {
    (0..3).map(|k| a[k].abs_diff(b[k])).max().unwrap_or(0)
}

/// Pixels whose 3x3 neighbourhood in `reference` is uniform within 2
/// levels: away from silhouettes and shadow edges, where one sample and 256
/// rightly differ.
fn smooth_pixels(reference: &RgbImage) -> Vec<(u32, u32)> {
    let (w, h) = reference.dimensions();
    let mut smooth = Vec::new();
    for y in 1..h.saturating_sub(1) {
        for x in 1..w.saturating_sub(1) {
            let c = reference.get_pixel(x, y).0;
            let flat =
                (y - 1..=y + 1).all(|yy| (x - 1..=x + 1).all(|xx| channel_diff(reference.get_pixel(xx, yy).0, c) <= 2));
            if flat {
                smooth.push((x, y));
            }
        }
    }
    smooth
}

/// Compares a 1-sample image with the reference render on the reference's
/// smooth pixels: returns (pixels compared, pixels off by more than 2 levels).
fn compare_with_reference(scene: &Scene, width: u32, height: u32, depth: u32) -> (usize, usize) {
    let image = render_checked(scene, &options(width, height, depth));
    let reference = render_in_pool(scene, &RenderOptions::reference(width, height, depth), 2);
    let smooth = smooth_pixels(&reference);
    let bad = smooth
        .iter()
        .filter(|&&(x, y)| channel_diff(image.get_pixel(x, y).0, reference.get_pixel(x, y).0) > 2)
        .inspect(|&&(x, y)| {
            eprintln!("  ({x}, {y}): {:?} vs reference {:?}", image.get_pixel(x, y).0, reference.get_pixel(x, y).0)
        })
        .count();
    if std::env::var_os("STABILITY_IMAGES").is_some() {
        let name = format!("/tmp/stability-{width}x{height}-{depth}-{}", scene.primitives.len());
        image.save(format!("{name}.png")).expect("write");
        reference.save(format!("{name}-ref.png")).expect("write");
    }
    (smooth.len(), bad)
}

/// Asserts that a render agrees with the reference on all but 1% of its
/// smooth pixels, and that there are enough smooth pixels to mean something.
fn assert_matches_reference(name: &str, scene: &Scene, width: u32, height: u32, depth: u32) {
    let (compared, bad) = compare_with_reference(scene, width, height, depth);
    eprintln!("{name}: {bad} of {compared} smooth pixels off by more than 2 levels");
    assert!(compared * 8 >= (width * height) as usize, "{name}: too few smooth pixels ({compared})");
    assert!(bad * 100 <= compared, "{name}: {bad} of {compared} smooth pixels differ from the reference");
}

/// `round(255 * c)` per channel (SPEC 6).
fn bytes(c: DVec3) -> [u8; 3] {
    let c = c.clamp(DVec3::ZERO, DVec3::ONE) * 255.0;
    [c.x.round() as u8, c.y.round() as u8, c.z.round() as u8]
}

/// How many pixels are within `tolerance` levels of `expected`.
fn count_near(image: &RgbImage, expected: [u8; 3], tolerance: u8) -> usize {
    image.pixels().filter(|p| channel_diff(p.0, expected) <= tolerance).count()
}

/// Pixels whose primary ray hits `target`'s face with the given outward
/// normal (within `1e-9`), and the image's bytes there.
fn face_pixels(scene: &Scene, options: &RenderOptions, image: &RgbImage, normal: DVec3) -> Vec<[u8; 3]> {
    let prepared = SceneGeometry::new(scene);
    let rays = prepared.primary_rays(&scene.camera, options.width, options.height, Screen::Centered);
    let mut out = Vec::new();
    for j in 0..options.height {
        for i in 0..options.width {
            let ray = rays.ray(i, j, glam::DVec2::splat(0.5));
            if let Some(hit) = prepared.closest_hit(&ray)
                && (hit.normal - normal).length() < 1e-9
            {
                out.push(image.get_pixel(i, j).0);
            }
        }
    }
    out
}

// ------------------------------------------------------------ the cases

/// Sizes from 1e-4 to 1e7 in one scene: a sphere of radius 1e-4 a
/// millimetre from the eye, in front of a box ten million units wide and a
/// floor plane ten million units below.
#[test]
fn coordinates_from_1e_minus_4_to_1e7_in_one_scene() {
    let lights = vec![light([0.3, 1.0, 0.5], 0.7)];
    let s = scene(
        2e-3,
        1.0,
        0.2,
        lights,
        vec![
            sphere([0.0, 0.0, 0.0], 1e-4, material([0.9, 0.2, 0.2], 0.7, 0.3, 40.0)),
            sphere([3e-4, 2e-4, -1e-4], 5e-5, material([0.2, 0.9, 0.2], 0.7, 0.5, 200.0)),
            cube([0.0, 0.0, -1e7], [1e7, 1e7, 1e5], DMat3::IDENTITY, matte([0.2, 0.3, 0.9])),
            plane([0.0, 1.0, 0.0], -1e7, matte([0.8, 0.8, 0.8])),
        ],
    );
    assert_matches_reference("1e-4..1e7", &s, 32, 24, 5);
    // The far box's front face: ambient + diffuse, the same everywhere.
    let o = options(64, 48, 5);
    let image = render_checked(&s, &o);
    let l = s.lights[0].direction;
    let expected = bytes(DVec3::new(0.2, 0.3, 0.9) * (0.8 * 0.2 + 0.8 * l.z * 0.7));
    let face = face_pixels(&s, &o, &image, DVec3::Z);
    let off = face.iter().filter(|&&p| channel_diff(p, expected) > 0).count();
    eprintln!("1e-4..1e7: far face {} pixels, {off} not {expected:?}", face.len());
    assert!(face.len() > 500 && off == 0);
}

/// Sizes from 1e-300 to 1e300 in one scene: a sphere of radius 1e-300 at
/// the origin, one of radius 1e300 whose top is a floor 2 below it, a
/// ball of radius 1, a box a million times longer than thick, and a light
/// that grazes the floor and the box's top. Nothing here can be drawn
/// exactly in f64 (the huge sphere's squares overflow), but every path is
/// finite, the picture does not depend on threads, and the ball is drawn.
#[test]
fn sizes_from_1e_minus_300_to_1e300_in_one_scene() {
    let ball = sphere([2.0, 0.0, 0.0], 1.0, material([0.9, 0.2, 0.2], 0.7, 0.3, 40.0));
    let lights = vec![light([1.0, 0.0, 0.0], 0.5), light([0.3, 1.0, 0.5], 0.5)];
    let s = scene(
        10.0,
        1.0,
        0.2,
        lights,
        vec![
            sphere([0.0, 0.0, 0.0], 1e-300, matte([0.2, 0.9, 0.2])),
            sphere([0.0, -1e300 - 2.0, 0.0], 1e300, matte([0.8, 0.8, 0.8])),
            ball,
            cube([-2.0, 1.5, -1.0], [10.0, 1e-5, 10.0], DMat3::from_rotation_x(0.3), matte([0.2, 0.3, 0.9])),
        ],
    );
    let o = options(64, 48, 5);
    let image = render_checked(&s, &o);
    // The ball's centre is seen 2 f / 10 = 11.7 pixels right of the middle.
    let [r, g, b] = image.get_pixel(43, 24).0;
    assert!(r > 2 * g.max(b), "the ball is red: {:?}", [r, g, b]);
}

/// The eye on a surface: on a sphere, on a box face and on a plane, with a
/// light grazing the plane (N·L = 0): finite paths, no panic.
#[test]
fn the_camera_on_a_surface() {
    let m = material([0.8, 0.6, 0.4], 0.5, 0.4, 20.0);
    let lights = vec![light([1.0, 0.0, 0.0], 0.6), light([0.2, 1.0, 0.4], 0.4)];
    for (name, wall) in [
        ("sphere", sphere([0.0, 0.0, 0.0], 5.0, m)),
        ("box", cube([0.0, 0.0, 0.0], [4.0, 4.0, 10.0], DMat3::IDENTITY, m)),
        ("plane", plane([0.0, 0.0, 1.0], 5.0, m)),
    ] {
        let floor = plane([0.0, 1.0, 0.0], -1.0, m);
        let s = scene(5.0, 1.2, 0.3, lights.clone(), vec![wall, floor]);
        let hits = assert_sane_paths(&s, &options(32, 24, 5));
        eprintln!("the eye on a {name}: {hits} hits");
        render_checked(&s, &options(32, 24, 5));
    }
}

/// A box of aspect 1:10,000 (a sheet 10 wide, 1e-3 thick), slightly tilted,
/// and a needle (1e-3 x 10 x 1e-3): the sheet's top face is uniform.
#[test]
fn boxes_with_an_aspect_of_1_to_10000() {
    let axes = DMat3::from_rotation_x(0.5) * DMat3::from_rotation_y(0.2);
    let lights = vec![light([0.0, 1.0, 0.2], 0.8)];
    let sheet = cube([0.0, 0.0, 0.0], [10.0, 1e-3, 10.0], axes, matte([0.9, 0.7, 0.3]));
    let needle = cube([1.0, 0.5, 2.0], [1e-3, 10.0, 1e-3], DMat3::from_rotation_z(0.3), matte([0.9, 0.9, 0.9]));
    let s = scene(12.0, 1.0, 0.2, lights, vec![sheet, needle]);
    let o = options(64, 48, 5);
    let image = render_checked(&s, &o);
    let top = axes * DVec3::Y;
    let n_dot_l = top.dot(s.lights[0].direction);
    let expected = bytes(DVec3::new(0.9, 0.7, 0.3) * (0.8 * 0.2 + 0.8 * n_dot_l * 0.8));
    // The needle casts a shadow on the sheet: those pixels get ambient only.
    let shadow = bytes(DVec3::new(0.9, 0.7, 0.3) * (0.8 * 0.2));
    let face = face_pixels(&s, &o, &image, top);
    let lit = face.iter().filter(|&&p| p == expected).count();
    let shaded = face.iter().filter(|&&p| p == shadow).count();
    eprintln!("1:10000: top face {} pixels, {lit} lit, {shaded} in the needle's shadow", face.len());
    assert!(face.len() > 1000 && lit + shaded == face.len());
    assert_matches_reference("1:10000", &s, 32, 24, 5);
}

/// Rays that graze surfaces: a sphere whose silhouette passes exactly
/// through pixel centres, a plane and a box face parallel to pixel-centre
/// rays (direction component exactly 0: `0 * ∞` in the slab test).
#[test]
fn grazing_rays() {
    let (w, h) = (63u32, 47u32); // odd: the middle column and row have x = 0 and y = 0
    let angle: f64 = 1.0;
    let distance = 10.0;
    let f = f64::from(w) / (2.0 * (angle / 2.0).tan());
    // The ray of the pixel 10 columns right of the middle, on the middle row:
    // direction (10, 0, -f) from (0, 0, D). Its distance to the origin is
    // D * 10 / sqrt(100 + f²): a sphere of that radius is tangent to it.
    let tangent = distance * 10.0 / (100.0 + f * f).sqrt();
    let lights = vec![light([0.4, 1.0, 0.3], 0.8)];
    let s = scene(
        distance,
        angle,
        0.2,
        lights,
        vec![
            sphere([0.0, 0.0, 0.0], tangent, material([0.9, 0.3, 0.3], 0.7, 0.3, 30.0)),
            // The plane x = 0 seen from +x: the middle column's rays (x = 0)
            // run inside it; rays to the left of it start on its solid side.
            plane([1.0, 0.0, 0.0], -3.0, material([0.3, 0.9, 0.3], 0.7, 0.2, 10.0)),
            // A box whose top face is the plane y = 0: the middle row's rays
            // run exactly along it.
            cube([2.0, -0.5, -2.0], [2.0, 1.0, 2.0], DMat3::IDENTITY, material([0.3, 0.3, 0.9], 0.7, 0.2, 10.0)),
            // And one whose side face is x = 0.
            cube([-0.5, 2.0, -2.0], [1.0, 2.0, 2.0], DMat3::IDENTITY, material([0.9, 0.9, 0.3], 0.7, 0.2, 10.0)),
        ],
    );
    let o = options(w, h, 5);
    let hits = assert_sane_paths(&s, &o);
    let image = render_checked(&s, &o);
    // The tangent ray itself either touches the sphere (one point) or misses
    // it; both are fine, as long as the pixel is one or the other.
    let grazing = image.get_pixel(w / 2 + 10, h / 2).0;
    eprintln!("grazing: {hits} hits checked; the tangent pixel is {grazing:?}");
    assert_matches_reference("grazing", &s, 31, 23, 5);
}

/// Neighbouring cubes of a Menger sponge share faces: the front faces are
/// coplanar and touch along edges, and shadow rays leave from faces that
/// touch other cubes. Axis-aligned and lit from the front, every front face
/// must get exactly the same colour (no speckles along the shared edges).
#[test]
fn coinciding_faces_of_a_fractal() {
    let text = "
camera distance 12 angle 0.9 end
ambient 0.25
light vector 0.6, 0.3, 0 intensity 0.7 end
proc menger(x, y, z, s, d)
  if d = 0 then
    put box center x, y, z length s, s, s kd 0.8 ks 0 phong 1 color 200, 150, 100 end
  else
    let t = s / 3
    ring(x, y - t, z, t, d - 1)
    corners(x, y, z, t, d - 1)
    ring(x, y + t, z, t, d - 1)
  end
end
proc ring(x, y, z, t, d)
  menger(x - t, y, z - t, t, d)
  menger(x, y, z - t, t, d)
  menger(x + t, y, z - t, t, d)
  menger(x - t, y, z, t, d)
  menger(x + t, y, z, t, d)
  menger(x - t, y, z + t, t, d)
  menger(x, y, z + t, t, d)
  menger(x + t, y, z + t, t, d)
end
proc corners(x, y, z, t, d)
  menger(x - t, y, z - t, t, d)
  menger(x + t, y, z - t, t, d)
  menger(x - t, y, z + t, t, d)
  menger(x + t, y, z + t, t, d)
end
menger(0, 0, 0, 6, 2)
";
    let s = eval(text);
    assert_eq!(s.primitives.len(), 400);
    let o = options(64, 48, 5);
    let image = render_checked(&s, &o);
    let l = s.lights[0].direction;
    let c = DVec3::new(200.0, 150.0, 100.0) / 255.0;
    let front = bytes(c * (0.8 * 0.25 + 0.8 * l.z * 0.7));
    let face = face_pixels(&s, &o, &image, DVec3::Z);
    // Faces at the front (z = 3) are never shadowed; faces deeper in the holes
    // may be. Count the front ones by their colour: the lit colour or the
    // shadowed one, nothing in between.
    let shadowed = bytes(c * (0.8 * 0.25));
    let lit = face.iter().filter(|&&p| p == front).count();
    let dark = face.iter().filter(|&&p| p == shadowed).count();
    eprintln!("menger: {} +z face pixels: {lit} lit, {dark} shadowed", face.len());
    assert!(lit > 1000 && lit + dark == face.len());
    // Turned so that three faces show, against the reference.
    let mut turned = s.clone();
    let r = DMat3::from_rotation_y(-0.6) * DMat3::from_rotation_x(0.45);
    for p in &mut turned.primitives {
        p.rotate(&r);
    }
    assert_matches_reference("menger turned", &turned, 32, 24, 5);
}

/// The camera inside a closed sphere and inside a closed box: every shadow
/// ray is blocked by the walls, every reflected ray hits a wall, so the
/// image is one uniform colour, the fixed point of `c = kd Ia C + ks c`
/// folded `depth` times (SPEC 6).
#[test]
fn camera_inside_a_sphere_and_inside_a_box() {
    let m = material([0.8, 0.6, 0.4], 0.5, 0.4, 20.0);
    let lights = vec![light([0.3, 1.0, 0.2], 0.9)];
    for (name, wall) in [
        ("sphere", sphere([0.5, -0.3, 0.2], 20.0, m)),
        ("box", cube([0.5, -0.3, 0.2], [30.0, 20.0, 40.0], DMat3::from_rotation_y(0.4), m)),
    ] {
        for depth in [0, 5, 50] {
            let s = scene(3.0, 1.2, 0.3, lights.clone(), vec![wall]);
            let image = render_checked(&s, &options(64, 48, depth));
            let local = m.color * (m.kd * 0.3);
            let mut c = DVec3::ZERO;
            for _ in 0..=depth {
                c = (local + c * m.ks).clamp(DVec3::ZERO, DVec3::ONE);
            }
            let expected = bytes(c);
            let near = count_near(&image, expected, 0);
            eprintln!("inside a {name}, depth {depth}: {near} of 3072 pixels are {expected:?}");
            assert_eq!(near, 64 * 48, "inside a {name} at depth {depth}");
        }
    }
}

/// Objects behind the eye are never seen: a sphere and a box just behind it,
/// a sphere whose front reaches to within 1e-9 of the eye, and a plane whose
/// visible side faces away.
#[test]
fn objects_behind_the_camera_are_not_visible() {
    let m = material([0.9, 0.9, 0.9], 0.9, 0.5, 10.0);
    let lights = vec![light([0.0, 0.0, -1.0], 1.0), light([0.0, 1.0, 0.0], 1.0)];
    let s = scene(
        5.0,
        2.5,
        0.5,
        lights,
        vec![
            sphere([0.0, 0.0, 8.0], 2.0, m),
            sphere([0.0, 0.0, 15.0], 10.0 - 1e-9, m),
            cube([3.0, 1.0, 6.0], [2.0, 2.0, 1.0], DMat3::IDENTITY, m),
            // z = 5.5 seen from +z: behind the eye, facing away from it.
            plane([0.0, 0.0, 1.0], 5.5, m),
        ],
    );
    let image = render_checked(&s, &options(64, 48, 5));
    assert!(image.pixels().all(|p| p.0 == [0, 0, 0]), "something behind the camera is visible");
}

/// Depth 0 (no reflection) and depth 50 between two facing mirrors: sane
/// paths, the skips still byte-identical at depth 50, and both match the
/// reference.
#[test]
fn depth_0_and_depth_50() {
    let mirror = material([0.9, 0.9, 0.9], 0.1, 0.9, 50.0);
    let lights = vec![light([0.2, 1.0, 0.4], 0.8)];
    let s = scene(
        6.0,
        1.0,
        0.2,
        lights,
        vec![
            cube([-3.0, 0.0, 0.0], [0.5, 8.0, 8.0], DMat3::from_rotation_y(0.05), mirror),
            cube([3.0, 0.0, 0.0], [0.5, 8.0, 8.0], DMat3::from_rotation_y(-0.03), mirror),
            sphere([0.0, 0.0, -1.0], 1.0, material([0.9, 0.2, 0.2], 0.7, 0.3, 30.0)),
            plane([0.0, 1.0, 0.0], -2.0, material([0.5, 0.5, 0.5], 0.7, 0.3, 10.0)),
        ],
    );
    for depth in [0, 50] {
        let fast = render_checked(&s, &options(48, 36, depth));
        let literal = render_in_pool(&s, &RenderOptions { skips: Skips::none(), ..options(48, 36, depth) }, 2);
        assert!(fast.as_raw() == literal.as_raw(), "skips change the image at depth {depth}");
    }
    assert_matches_reference("depth 0", &s, 32, 24, 0);
    assert_matches_reference("depth 50", &s, 24, 18, 50);
}

/// `phong 10000`: a pin-point highlight; powers of numbers just below 1 stay
/// finite and the image matches the reference.
#[test]
fn phong_10000() {
    let lights = vec![light([0.3, 0.3, 1.0], 1.0)];
    let s = scene(
        6.0,
        0.8,
        0.2,
        lights,
        vec![
            sphere([0.0, 0.0, 0.0], 1.5, material([0.8, 0.8, 0.8], 0.5, 1.0, 10_000.0)),
            cube(
                [2.5, 0.0, -1.0],
                [1.0, 1.0, 1.0],
                DMat3::from_rotation_y(0.4),
                material([0.3, 0.8, 0.3], 0.5, 1.0, 10_000.0),
            ),
        ],
    );
    let image = render_checked(&s, &options(64, 48, 5));
    assert!(image.pixels().any(|p| p.0[0] > 0));
    assert_matches_reference("phong 10000", &s, 32, 24, 5);
}

/// 1,000 successive rotations by 0.001 in the language give the same
/// primitives as one rotation by 1, within 1e-9, about each axis, for a
/// sphere, a box and a plane.
///
/// Procedure arguments are numbers (SPEC 2: `expr`), so a procedure cannot
/// hand a rotated object to its recursive call; the program instead rebinds
/// a global object 1,000 times, each time rotating the previous one.
#[test]
fn a_thousand_small_rotations_equal_one_rotation() {
    for axis in ["a, 0, 0", "0, a, 0", "0, 0, a"] {
        let program = |body: &str| {
            format!(
                "camera distance 10 angle 1 end
ambient 0.2
object thing = group
  sphere center 1, 2, 3 radius 0.5 kd 0.5 ks 0.5 phong 10 color 200, 100, 50 end
  box center -2, 0.5, 1 length 1, 2, 3 kd 0.5 ks 0.5 phong 10 color 200, 100, 50 end
  plane rotation 0.3, 0.2, 0.1 shift 2 kd 0.5 ks 0.5 phong 10 color 200, 100, 50 end
end
{body}
put thing"
            )
        };
        let step = format!("object thing = rotate thing by {axis} end\n");
        let many = eval(&program(&format!("let a = 1 / 1000\n{}", step.repeat(1000))));
        let once = eval(&program(&format!("let a = 1\n{step}")));
        assert_eq!(many.primitives.len(), 3);
        let mut worst: f64 = 0.0;
        for (a, b) in many.primitives.iter().zip(&once.primitives) {
            worst = worst.max(shape_distance(&a.shape, &b.shape));
        }
        eprintln!("1000 rotations by 0.001 about ({axis}): largest difference {worst:e}");
        assert!(worst < 1e-9, "{axis}: {worst:e}");
    }
}

/// The largest difference between the numbers describing two shapes of the
/// same kind (infinity for different kinds).
fn shape_distance(a: &Shape, b: &Shape) -> f64 {
    let v = |x: DVec3, y: DVec3| (x - y).abs().max_element();
    let m = |x: &DMat3, y: &DMat3| v(x.x_axis, y.x_axis).max(v(x.y_axis, y.y_axis)).max(v(x.z_axis, y.z_axis));
    match (a, b) {
        (Shape::Sphere { center: c1, radius: r1 }, Shape::Sphere { center: c2, radius: r2 }) => {
            v(*c1, *c2).max((r1 - r2).abs())
        }
        (Shape::Plane { normal: n1, shift: d1 }, Shape::Plane { normal: n2, shift: d2 }) => {
            v(*n1, *n2).max((d1 - d2).abs())
        }
        (Shape::Box { center: c1, half: h1, axes: a1 }, Shape::Box { center: c2, half: h2, axes: a2 }) => {
            v(*c1, *c2).max(v(*h1, *h2)).max(m(a1, a2))
        }
        _ => f64::INFINITY,
    }
}

/// A small scene (sphere on a box on a floor, two lights, reflections)
/// scaled by 1e-6 and by 1e6 with the camera distance scaled alike: the
/// same rays meet the same geometry, so the image is the same as at scale 1
/// (no acne at either end).
#[test]
fn scaled_by_1e_minus_6_and_1e6() {
    let text = |k: &str| {
        format!(
            "camera distance 8 * {k} angle 1 end
ambient 0.2
light vector 0.5, 0, 0.5 intensity 0.6 end
light vector -0.7, 0, 0.2 intensity 0.3 end
object world = group
  sphere center 0, 1, 0 radius 1 kd 0.7 ks 0.3 phong 50 color 220, 40, 40 end
  rotate box center 0, -0.5, 0 length 4, 1, 3 kd 0.8 ks 0.2 phong 10 color 40, 200, 40 end by 0, 0.3, 0 end
  plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0.2 phong 10 color 180, 180, 180 end
end
put scale world by {k} end"
        )
    };
    let o = options(64, 48, 5);
    let unit = render_checked(&eval(&text("1")), &o);
    for k in ["1 / 1000000", "1000000"] {
        let s = eval(&text(k));
        let image = render_checked(&s, &o);
        let off = unit.pixels().zip(image.pixels()).filter(|(a, b)| channel_diff(a.0, b.0) > 2).count();
        let differ = unit.pixels().zip(image.pixels()).filter(|(a, b)| a != b).count();
        eprintln!("scale {k}: {differ} pixels differ from scale 1, {off} by more than 2 levels");
        assert!(off <= 3, "scale {k}: {off} pixels differ from scale 1 by more than 2 levels");
    }
}

/// A ray reflected 1,000 times inside a sphere stays on it: the error of
/// each hit point (its distance to the sphere) stays at rounding level
/// instead of growing bounce after bounce.
#[test]
fn a_thousand_reflections_inside_a_sphere_stay_on_it() {
    let m = material([0.8, 0.6, 0.4], 0.5, 0.4, 20.0);
    let center = DVec3::new(0.5, -0.3, 0.2);
    let s = scene(3.0, 1.2, 0.3, vec![], vec![sphere(center.into(), 20.0, m)]);
    let prepared = SceneGeometry::new(&s);
    let rays = prepared.primary_rays(&s.camera, 8, 6, Screen::Centered);
    // The geometry's points are in its own unit.
    let (center, radius) = (center * prepared.scale(), 20.0 * prepared.scale());
    let mut worst: f64 = 0.0;
    for (i, j) in [(0, 0), (3, 2), (7, 5), (1, 4)] {
        let mut ray = rays.ray(i, j, glam::DVec2::splat(0.5));
        for _ in 0..1000 {
            let hit = prepared.closest_hit(&ray).expect("inside a closed sphere every ray hits");
            worst = worst.max(((hit.point - center).length() - radius).abs() / radius);
            let d = ray.dir;
            ray = Ray::new(offset_origin(hit.point, hit.normal, hit.t), d - hit.normal * (2.0 * d.dot(hit.normal)));
        }
    }
    eprintln!("1000 reflections inside a sphere of radius 20: hit points at most {worst:e} radii off it");
    assert!(worst < 1e-9, "{worst:e}");
}
