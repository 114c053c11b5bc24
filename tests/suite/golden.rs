//! Golden images: every scene of `scenarios/` rendered small and compared
//! with `tests/golden/NAME.png`.
//!
//! A scene passes when at most 0.5% of its pixels differ by more than 2
//! levels (of 255) in some channel from the golden image. On failure the
//! report names each scene, how many pixels differ and by how much, and where
//! the first ones are; the rendered image is saved next to the golden one as
//! `target/golden/NAME.actual.png` for a look. After a deliberate change,
//! `RAYREPL_BLESS=1 cargo test --release --test suite golden::` rewrites the goldens.

use std::path::{Path, PathBuf};

use crate::common::programs::evaluated;
use image::RgbImage;
use rayrepl::render::{self, RenderControl, RenderOptions, SceneGeometry};

const WIDTH: u32 = 96;
const HEIGHT: u32 = 72;
/// Levels of 255 a pixel may be off before it counts as different.
const LEVELS: u8 = 2;
/// Share of pixels that may differ by more than [`LEVELS`].
const SHARE: f64 = 0.005;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Renders the scene file at `path` at time `time`, small.
fn render_scene(path: &Path, time: f64) -> RgbImage {
    let text = std::fs::read_to_string(path).expect("scene is readable");
    let scene = evaluated(&path.display().to_string(), &text, time).into_scene();
    let options = RenderOptions { width: WIDTH, height: HEIGHT, ..RenderOptions::default() };
    let control = RenderControl { progress: None, cancel: None };
    render::render(&scene, &SceneGeometry::new(&scene), &options, &control).expect("not cancelled").0
}

/// What differs between `actual` and `golden`, or `None` when they agree.
fn compare(actual: &RgbImage, golden: &RgbImage) -> Option<String> {
    if actual.dimensions() != golden.dimensions() {
        return Some(format!("size {:?} instead of {:?}", actual.dimensions(), golden.dimensions()));
    }
    let mut differing = Vec::new();
    let mut worst = 0u8;
    for (x, y, pixel) in actual.enumerate_pixels() {
        let expected = golden.get_pixel(x, y);
        let off = (0..3).map(|c| pixel[c].abs_diff(expected[c])).max().unwrap_or(0);
        worst = worst.max(off);
        if off > LEVELS {
            differing.push(format!("({x},{y}) {:?} instead of {:?}", pixel.0, expected.0));
        }
    }
    let share = differing.len() as f64 / f64::from(WIDTH * HEIGHT);
    (share > SHARE).then(|| {
        let first: Vec<_> = differing.iter().take(5).cloned().collect();
        format!(
            "{} pixels ({:.2}%) differ by more than {LEVELS} levels, at worst {worst}; first: {}",
            differing.len(),
            share * 100.0,
            first.join(", ")
        )
    })
}

/// Checks one scene at one time against its golden image.
fn check(name: &str, time: f64, bless: bool) -> Option<String> {
    let scene = root().join("scenarios").join(format!("{name}.ray"));
    let golden_path = root().join("tests/golden").join(format!("{name}.png"));
    let actual = render_scene(&scene, time);
    if bless {
        actual.save(&golden_path).expect("golden image written");
        return None;
    }
    let golden = match image::open(&golden_path) {
        Ok(image) => image.to_rgb8(),
        Err(e) => return Some(format!("no golden image {} ({e}); bless with RAYREPL_BLESS=1", golden_path.display())),
    };
    let problem = compare(&actual, &golden)?;
    let out = root().join("target/golden");
    std::fs::create_dir_all(&out).expect("target/golden can be made");
    let actual_path = out.join(format!("{name}.actual.png"));
    actual.save(&actual_path).expect("actual image written");
    Some(format!("{problem}\n    rendered image: {}", actual_path.display()))
}

#[test]
fn every_scenario_matches_its_golden_image() {
    let bless = std::env::var_os("RAYREPL_BLESS").is_some();
    let mut names: Vec<String> = std::fs::read_dir(root().join("scenarios"))
        .expect("scenarios/ exists")
        .filter_map(|entry| {
            let path = entry.expect("readable entry").path();
            let stem = path.file_stem()?.to_string_lossy().into_owned();
            (path.extension()? == "ray").then_some(stem)
        })
        .collect();
    names.sort();
    assert!(names.len() >= 8, "scenarios/ holds at least eight scenes");
    let failures: Vec<String> =
        names.iter().filter_map(|name| check(name, 7.0, bless).map(|problem| format!("  {name}: {problem}"))).collect();
    assert!(
        failures.is_empty(),
        "{} of {} scenes differ from their golden images:\n{}",
        failures.len(),
        names.len(),
        failures.join("\n")
    );
}
