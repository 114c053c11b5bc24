//! Scale invariance of the bundled scenarios (SPEC 6): each scenario is
//! evaluated, every length of the evaluated scene (positions, radii, box
//! sizes, plane shifts, the camera distance) is multiplied by 10^k, and the
//! render is compared with the unscaled one.
//!
//! `cargo bench --bench scale` prints, for each k and scenario, the share of
//! pixels that differ by more than 2 levels (and, in brackets, at all).
//! `cargo bench --bench scale -- -150 150 5` takes the first k, the last and
//! the step (default: every k from -150 to 150 by 10, and ±1..±9).

use std::path::Path;

use image::RgbImage;
use rayrepl::lang::{Interpreter, Limits, SourceMap, parse_file};
use rayrepl::render::{RenderControl, RenderOptions, SceneGeometry, render};
use rayrepl::scene::Scene;

/// The scene of the scenario file at `path`, at `time` 0.
fn evaluate(path: &Path) -> Scene {
    let text = std::fs::read_to_string(path).expect("a readable scenario");
    let mut sources = SourceMap::new();
    let id = sources.add(path.display().to_string(), text.clone(), 0);
    let program = parse_file(id, &text).unwrap_or_else(|d| panic!("{}: {}", path.display(), d.message));
    let mut interpreter = Interpreter::new(0.0, Limits::default());
    interpreter.run(&program).unwrap_or_else(|d| panic!("{}: {}", path.display(), d.message));
    interpreter.into_scene()
}

/// `scene` with every length multiplied by `factor`.
fn scaled(scene: &Scene, factor: f64) -> Scene {
    let mut scene = scene.clone();
    scene.camera.distance *= factor;
    for primitive in scene.primitives.iter_mut().chain(&mut scene.timed_primitives) {
        primitive.scale(factor);
    }
    scene
}

fn image(scene: &Scene, options: &RenderOptions) -> RgbImage {
    let prepared = SceneGeometry::new(scene);
    render(scene, &prepared, options, &RenderControl::default()).expect("not cancelled").0
}

/// The shares of pixels of `b` that differ from `a` by more than 2 levels
/// in some channel, and at all.
fn differences(a: &RgbImage, b: &RgbImage) -> (f64, f64) {
    let (mut off, mut differ) = (0usize, 0usize);
    for (p, q) in a.pixels().zip(b.pixels()) {
        let worst = p.0.iter().zip(q.0).map(|(&x, y)| x.abs_diff(y)).max().unwrap_or(0);
        off += usize::from(worst > 2);
        differ += usize::from(worst > 0);
    }
    let n = a.pixels().len() as f64;
    (off as f64 / n, differ as f64 / n)
}

fn main() {
    let numbers: Vec<i32> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let powers: Vec<i32> = match numbers[..] {
        [first, last, step] => (first..=last).step_by(step.max(1) as usize).collect(),
        _ => (-15..=15).map(|k| k * 10).chain((1..10).flat_map(|k| [-k, k])).collect(),
    };
    let mut powers = powers;
    powers.sort_unstable();
    let options = RenderOptions { width: 160, height: 120, ..RenderOptions::default() };
    let mut paths: Vec<_> =
        std::fs::read_dir("scenarios").expect("run from the repository").flatten().map(|e| e.path()).collect();
    paths.sort();
    let scenes: Vec<_> =
        paths.iter().map(|p| (p.file_stem().unwrap().to_string_lossy().into_owned(), evaluate(p))).collect();
    let originals: Vec<_> = scenes.iter().map(|(_, s)| image(s, &options)).collect();
    print!("| k |");
    for (name, _) in &scenes {
        print!(" {name} |");
    }
    println!(" all |");
    println!("|---:|{}---:|", "---:|".repeat(scenes.len()));
    for k in powers {
        let factor: f64 = format!("1e{k}").parse().expect("a number");
        print!("| {k} |");
        let (mut all_off, mut all_differ) = (0.0, 0.0);
        for ((_, scene), original) in scenes.iter().zip(&originals) {
            let (off, differ) = differences(original, &image(&scaled(scene, factor), &options));
            print!(" {:.3}% ({:.3}%) |", 100.0 * off, 100.0 * differ);
            all_off += off / scenes.len() as f64;
            all_differ += differ / scenes.len() as f64;
        }
        println!(" {:.3}% ({:.3}%) |", 100.0 * all_off, 100.0 * all_differ);
    }
}
