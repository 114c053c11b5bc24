//! `embree-render`: renders a `.ray` scene by rayrepl's pixel contract
//! (SPEC 5 and 6) with Intel Embree 3 doing the BVH build and the
//! traversal, and rayrepl's own f64 sphere and box tests at the leaves:
//! the Embree-based side of rayrepl's side-by-side benchmark
//! (`benches/embree/run.sh`).
//!
//! ```text
//! embree-render SCENE.ray --width W --height H -o OUT.ppm [--threads N]
//!               [--quality low|medium|high] [--packets] [--depth N] [--verbose]
//!               [--brute-force]
//! ```
//!
//! `--brute-force` finds closest hits by testing every object in the
//! scene's order, without Embree (a check of the culling: its image must be
//! the Embree image's); `--verbose` has Embree print its configuration
//! (its ISA among it) on standard output.

mod embree;
mod geometry;
mod render;
mod shade;

use std::process::ExitCode;
use std::time::Instant;

use rayrepl::lang::source::SourceMap;
use rayrepl::lang::{Interpreter, Limits, parse_file};
use rayrepl::render::geometry::working_scale;
use rayrepl::render::{PrimaryRays, RayCounts, Screen};
use rayrepl::scene::{Camera, Scene};

use crate::embree::{BuildQuality, EmbreeDevice};
use crate::geometry::{Geometry, Parts};
use crate::shade::Lighting;

/// What the command line asks for.
struct Options {
    scene: String,
    width: u32,
    height: u32,
    output: String,
    threads: usize,
    depth: u32,
    quality: BuildQuality,
    packets: bool,
    brute_force: bool,
    verbose: bool,
}

const USAGE: &str = "usage: embree-render SCENE.ray --width W --height H -o OUT.ppm [--threads N] \
                     [--quality low|medium|high] [--packets] [--depth N] [--verbose] [--brute-force]";

fn main() -> ExitCode {
    let options = match parse_args(std::env::args().skip(1)) {
        Ok(options) => options,
        Err(message) => {
            eprintln!("embree-render: {message}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    match run(&options) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("embree-render: {message}");
            ExitCode::FAILURE
        }
    }
}

/// Reads the command line.
fn parse_args(mut args: impl Iterator<Item = String>) -> Result<Options, String> {
    let mut options = Options {
        scene: String::new(),
        width: 800,
        height: 600,
        output: String::new(),
        threads: 2,
        depth: 5,
        quality: BuildQuality::Medium,
        packets: false,
        brute_force: false,
        verbose: false,
    };
    while let Some(arg) = args.next() {
        let mut value = |name: &str| args.next().ok_or_else(|| format!("{name} needs a value"));
        match arg.as_str() {
            "--width" => options.width = number(&value("--width")?)?,
            "--height" => options.height = number(&value("--height")?)?,
            "--threads" => options.threads = number(&value("--threads")?)?,
            "--depth" => options.depth = number(&value("--depth")?)?,
            "-o" => options.output = value("-o")?,
            "--quality" => {
                options.quality = match value("--quality")?.as_str() {
                    "low" => BuildQuality::Low,
                    "medium" => BuildQuality::Medium,
                    "high" => BuildQuality::High,
                    other => return Err(format!("unknown build quality {other:?}")),
                }
            }
            "--verbose" => options.verbose = true,
            "--packets" => options.packets = true,
            "--brute-force" => options.brute_force = true,
            _ if arg.starts_with('-') => return Err(format!("unknown flag {arg}")),
            _ if options.scene.is_empty() => options.scene = arg,
            _ => return Err(format!("a second scene {arg:?}")),
        }
    }
    if options.scene.is_empty() || options.output.is_empty() {
        return Err("a scene and -o OUT.ppm are needed".to_owned());
    }
    if options.width == 0 || options.height == 0 || options.threads == 0 {
        return Err("width, height and threads must be at least 1".to_owned());
    }
    Ok(options)
}

/// A whole number from the command line.
fn number<T: std::str::FromStr>(text: &str) -> Result<T, String> {
    text.parse().map_err(|_| format!("not a whole number: {text:?}"))
}

/// Loads, builds, renders, writes, and prints the times and counts.
fn run(options: &Options) -> Result<(), String> {
    let start = Instant::now();
    let scene = evaluate(&options.scene)?;
    let evaluated = start.elapsed();

    let mut config = format!("threads={}", options.threads);
    if options.verbose {
        config.push_str(",verbose=1");
    }
    let device = EmbreeDevice::new(&config)?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(options.threads).build().map_err(|e| e.to_string())?;

    let build_start = Instant::now();
    let scale = working_scale(&scene);
    let parts = Parts::new(&scene, scale, scene.camera.distance * scale);
    let commit_start = Instant::now();
    let mut geometry = Geometry::build(&device, &parts, options.quality)?;
    geometry.brute_force = options.brute_force;
    let committed = commit_start.elapsed();
    let built = build_start.elapsed();
    eprintln!(
        "evaluate {:.3} s, build {:.3} s (rtcCommitScene {:.3} s, {} objects{}, {} planes, quality {:?})",
        evaluated.as_secs_f64(),
        built.as_secs_f64(),
        committed.as_secs_f64(),
        parts.objects.list.len(),
        if parts.objects.in_frame() { " in their common frame" } else { "" },
        parts.planes.len(),
        options.quality,
    );

    let render_start = Instant::now();
    let (image, counts) = pool.install(|| render_image(&scene, scale, &geometry, &parts, options));
    let seconds = render_start.elapsed().as_secs_f64();
    let total = counts.primary + counts.shadow + counts.reflection;
    let mrays = total as f64 / seconds.max(1e-9) / 1e6;
    eprintln!(
        "frames 1: {} primary, {} shadow, {} reflection rays in {seconds:.3} s: {mrays:.1} Mrays/s ({:.1} per thread, {} threads)",
        counts.primary,
        counts.shadow,
        counts.reflection,
        mrays / options.threads as f64,
        options.threads,
    );
    eprintln!(
        "isa: {}, {}",
        isa(),
        if options.packets { "packets of 16 camera and shadow rays" } else { "single rays" }
    );
    write_ppm(&options.output, options.width, options.height, &image)
}

/// Renders the image of `scene` (whose geometry, in the unit `scale`, is
/// `geometry` over `parts`) as `options` says: RGB bytes and the rays traced.
fn render_image(
    scene: &Scene,
    scale: f64,
    geometry: &Geometry,
    parts: &Parts,
    options: &Options,
) -> (Vec<u8>, RayCounts) {
    // rayrepl's `SceneGeometry::primary_rays`: the camera in the geometry's unit.
    let camera = Camera { distance: scene.camera.distance * scale, ..scene.camera };
    let rays = PrimaryRays::new(&camera, options.width, options.height, Screen::Centered);
    let lighting = Lighting::new(scene, &parts.planes, options.depth);
    let mut image = vec![0u8; options.width as usize * options.height as usize * 3];
    let counts = render::render(&rays, geometry, &lighting, options.width, &mut image, options.packets);
    (image, counts)
}

/// Parses and evaluates the scene file at `time = 0`.
fn evaluate(path: &str) -> Result<Scene, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let mut sources = SourceMap::new();
    let id = sources.add(path.to_owned(), text.clone(), 0);
    let program = parse_file(id, &text).map_err(|d| d.render(&sources, false))?;
    let mut interpreter = Interpreter::new(0.0, Limits::default());
    interpreter.run(&program).map_err(|d| d.render(&sources, false))?;
    Ok(interpreter.into_scene())
}

/// The widest vector ISA this CPU offers among those Embree 3.13 is built
/// for (Embree picks the widest it has code for; `--verbose` makes Embree
/// print its own choice).
fn isa() -> &'static str {
    if is_x86_feature_detected!("avx512f")
        && is_x86_feature_detected!("avx512dq")
        && is_x86_feature_detected!("avx512cd")
        && is_x86_feature_detected!("avx512bw")
        && is_x86_feature_detected!("avx512vl")
    {
        "AVX512 (SKX)"
    } else if is_x86_feature_detected!("avx2") {
        "AVX2"
    } else if is_x86_feature_detected!("avx") {
        "AVX"
    } else if is_x86_feature_detected!("sse4.2") {
        "SSE4.2"
    } else {
        "SSE2"
    }
}

/// Writes a binary PPM (`P6`), with the header rayrepl writes.
fn write_ppm(path: &str, width: u32, height: u32, pixels: &[u8]) -> Result<(), String> {
    let mut bytes = format!("P6\n{width} {height}\n255\n").into_bytes();
    bytes.extend_from_slice(pixels);
    std::fs::write(path, bytes).map_err(|e| format!("{path}: {e}"))
}

#[cfg(test)]
mod tests {
    use rayrepl::render::{RenderControl, RenderOptions, SceneGeometry};

    use super::*;

    /// Renders `scene` at `width` x `height` with rayrepl and with Embree
    /// (single rays, then packets) and checks the bytes and the ray counts
    /// are the same.
    fn same_as_rayrepl(path: &str, width: u32, height: u32) {
        let scene = evaluate(&format!("{}/../../{path}", env!("CARGO_MANIFEST_DIR"))).expect("the scene evaluates");
        let expected = RenderOptions { width, height, ..RenderOptions::default() };
        let (reference, stats) =
            rayrepl::render::render(&scene, &SceneGeometry::new(&scene), &expected, &RenderControl::default())
                .expect("not cancelled");
        let device = EmbreeDevice::new("threads=2").expect("an Embree device");
        let scale = working_scale(&scene);
        let parts = Parts::new(&scene, scale, scene.camera.distance * scale);
        let geometry = Geometry::build(&device, &parts, BuildQuality::Medium).expect("Embree builds the scene");
        for packets in [false, true] {
            let options = parse_args(
                [path, "--width", &width.to_string(), "--height", &height.to_string(), "-o", "unused.ppm"]
                    .into_iter()
                    .map(String::from),
            )
            .expect("valid arguments");
            let options = Options { packets, ..options };
            let (image, counts) = render_image(&scene, scale, &geometry, &parts, &options);
            assert_eq!(counts, stats.rays, "{path}, packets {packets}");
            assert!(image == reference.as_raw().as_slice(), "{path}, packets {packets}: the images differ");
        }
    }

    #[test]
    fn the_benchmark_scenes_render_as_rayrepl_renders_them() {
        same_as_rayrepl("benches/scenes/solar.ray", 160, 90);
        same_as_rayrepl("benches/scenes/spheres100k.ray", 160, 120);
        same_as_rayrepl("benches/scenes/sponge4.ray", 160, 90);
        same_as_rayrepl("benches/scenes/menger.ray", 160, 120);
    }

    #[test]
    fn scenes_at_extreme_scales_render_as_rayrepl_renders_them() {
        same_as_rayrepl("benches/scenes/scales.ray", 160, 120);
    }

    /// Every scenario, `boxes.ray` among them, where two boxes of the F
    /// share a face: the one put first must be seen by both renderers.
    #[test]
    fn the_scenarios_render_as_rayrepl_renders_them() {
        let folder = format!("{}/../../scenarios", env!("CARGO_MANIFEST_DIR"));
        let mut names: Vec<String> = std::fs::read_dir(folder)
            .expect("the scenarios folder")
            .map(|entry| entry.expect("a folder entry").file_name().to_string_lossy().into_owned())
            .filter(|name| name.ends_with(".ray"))
            .collect();
        names.sort();
        assert!(names.len() >= 10, "{names:?}");
        for name in names {
            same_as_rayrepl(&format!("scenarios/{name}"), 320, 240);
        }
    }
}
