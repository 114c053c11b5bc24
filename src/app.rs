//! The application: dispatches what the command line asks for to a check, a
//! render of a still image or an animation, or a session. Maps failures to
//! exit codes.

use std::cell::RefCell;
use std::collections::HashSet;
use std::io::{IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use image::RgbImage;

use crate::animation::{AnimationError, render_animation};
use crate::cli::Cli;
use crate::lang::ast::Program;
use crate::lang::eval::PrintLog;
use crate::lang::{Diagnostic, Interpreter, Limits, SourceId, SourceMap, Span, parse_file};
use crate::lint::{Allowed, Picture, check_scene};
use crate::output::{self, Content, FrameSink, ImageFormat};
use crate::progress::Progress;
use crate::render::{self, RenderControl, RenderOptions, RenderStats, SceneGeometry};
use crate::repl::{self, SessionOptions};
use crate::scene::Scene;

/// The exit code of a command line that asks for something impossible or
/// meaningless (the same as clap's for its own usage errors).
const USAGE_EXIT_CODE: u8 = 2;

/// Runs what the command line asks for and returns the process's exit code.
///
/// With no scene, or with `-i`, that is a session (interactive on a
/// terminal, a script otherwise); with a scene, a check or a render.
pub fn run(cli: Cli) -> ExitCode {
    if let Some(misuse) = cli.misuse() {
        eprintln!("rayrepl: {misuse}");
        return ExitCode::from(USAGE_EXIT_CODE);
    }
    let pool = match rayon::ThreadPoolBuilder::new().num_threads(cli.threads.unwrap_or(0) as usize).build() {
        Ok(pool) => pool,
        Err(e) => {
            eprintln!("rayrepl: cannot start worker threads: {e}");
            return ExitCode::FAILURE;
        }
    };
    if !cli.starts_session() || !std::io::stdin().is_terminal() {
        // The interactive session installs its own handler, which cancels renders.
        let _ = ctrlc::set_handler(|| output::exit_discarding_unfinished(INTERRUPTED_EXIT_CODE));
    }
    match cli.scene.clone() {
        Some(path) if !cli.interactive => pool.install(|| exit_code(run_file(&cli, &path))),
        _ => pool.install(|| repl::run(&session_options(&cli))),
    }
}

/// The exit code after Ctrl-C or `kill` (128 + SIGINT, as shells report it).
const INTERRUPTED_EXIT_CODE: i32 = 130;

/// The session's options from the command line.
fn session_options(cli: &Cli) -> SessionOptions {
    SessionOptions {
        no_preview: cli.no_preview,
        keep_going: cli.keep_going,
        initial_file: cli.scene.clone(),
        settings: cli.settings(),
        limits: limits(cli),
        allowed: cli.allowed(),
    }
}

/// The evaluator's limits from the command line.
fn limits(cli: &Cli) -> Limits {
    Limits { max_call_depth: cli.max_calls, max_primitives: cli.max_primitives }
}

/// Prints a batch error, if any, and gives the exit code.
fn exit_code(result: Result<(), String>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("{}", message.trim_end());
            ExitCode::FAILURE
        }
    }
}

/// Checks or renders one scene file.
fn run_file(cli: &Cli, path: &Path) -> Result<(), String> {
    let mut sources = SourceMap::new();
    let id = load(&mut sources, path)?;
    let parsed = ParsedScene::parse(sources, id, cli)?;
    let result = if cli.check {
        parsed.evaluate(cli.settings().time, false).map(|scene| {
            println!("{}: {}", parsed.sources.get(id).name, summary(&scene));
        })
    } else {
        output_path(cli, path).and_then(|output| match cli.anim {
            Some(count) => animate(cli, &parsed, count, &output),
            None => still(cli, &parsed, &output),
        })
    };
    if let Some(note) = parsed.printed.borrow().hidden_note() {
        eprintln!("note: {note}");
    }
    result
}

/// A parsed scene file, ready to be evaluated at any `time`.
struct ParsedScene {
    sources: SourceMap,
    program: Program,
    limits: Limits,
    /// The warnings already printed.
    warned: RefCell<HashSet<(Span, String)>>,
    /// How the scene is rendered, for the checks of the scene.
    picture: Picture,
    /// The checks turned off.
    allowed: Allowed,
    /// What `print` wrote, over every evaluation (the limit is for the whole run).
    printed: RefCell<PrintLog>,
}

impl ParsedScene {
    /// Parses the file `id` of `sources`.
    fn parse(sources: SourceMap, id: SourceId, cli: &Cli) -> Result<ParsedScene, String> {
        let program = parse_file(id, &sources.get(id).text).map_err(|d| show(&sources, &d))?;
        let picture = Picture {
            width: cli.width,
            height: cli.height,
            screen: cli.screen.screen(),
            animation: cli.anim.is_some(),
        };
        Ok(ParsedScene {
            sources,
            program,
            limits: limits(cli),
            warned: RefCell::default(),
            picture,
            allowed: cli.allowed(),
            printed: RefCell::default(),
        })
    }

    /// Evaluates the program at `time`, printing warnings on stderr. With
    /// `skip_static`, primitives that do not depend on `time` are not kept
    /// (an animation's later frames reuse the first frame's).
    /// A warning is printed once per run, however many frames raise it.
    /// What `print` writes comes first; the whole scene (not `skip_static`)
    /// is also checked for the mistakes that spoil a picture.
    fn evaluate(&self, time: f64, skip_static: bool) -> Result<Scene, String> {
        let mut interpreter = Interpreter::new(time, self.limits).skip_static(skip_static);
        let result = interpreter.run_with_sources(&self.program, &self.sources);
        let mut printed = self.printed.borrow_mut();
        printed.absorb(interpreter.take_printed());
        for line in printed.take_lines() {
            eprintln!("{}", line.render(&self.sources));
        }
        let mut warnings = interpreter.take_warnings();
        if result.is_ok() && !skip_static {
            let checked = check_scene(interpreter.scene(), interpreter.origins(), &self.picture, self.allowed);
            warnings.extend(checked.into_iter().map(|warning| warning.diagnostic));
        }
        for warning in warnings {
            if self.warned.borrow_mut().insert((warning.span, warning.message.clone())) {
                eprint!("{}", show(&self.sources, &warning));
            }
        }
        result.map_err(|d| show(&self.sources, &d))?;
        Ok(interpreter.into_scene())
    }
}

/// A diagnostic rendered for stderr (coloured on a terminal).
fn show(sources: &SourceMap, diagnostic: &Diagnostic) -> String {
    diagnostic.render(sources, std::io::stderr().is_terminal())
}

/// Reads a scene file (or standard input for `-`) into `sources`.
fn load(sources: &mut SourceMap, path: &Path) -> Result<SourceId, String> {
    if path == Path::new("-") {
        let mut text = String::new();
        std::io::stdin()
            .read_to_string(&mut text)
            .map_err(|e| format!("rayrepl: cannot read the scene from standard input: {}", output::io_reason(&e)))?;
        return Ok(sources.add("<stdin>", text, 0));
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("rayrepl: cannot read `{}`: {}", path.display(), output::io_reason(&e)))?;
    Ok(sources.add(path.display().to_string(), text, 0))
}

/// "3 spheres, 1 plane, 0 boxes, 2 lights".
fn summary(scene: &Scene) -> String {
    let counts = scene.counts();
    format!(
        "{}, {}, {}, {}",
        counted(counts.spheres, "sphere", "spheres"),
        counted(counts.planes, "plane", "planes"),
        counted(counts.boxes, "box", "boxes"),
        counted(counts.lights, "light", "lights"),
    )
}

/// The output file: `-o`, or the scene's name with `.png` (`.gif` for an
/// animation) in the current directory. Checks it before any work.
fn output_path(cli: &Cli, scene: &Path) -> Result<PathBuf, String> {
    let path = match &cli.output {
        Some(path) => path.clone(),
        None => {
            let stem = scene.file_stem().filter(|_| scene != Path::new("-")).unwrap_or("out".as_ref());
            PathBuf::from(stem).with_extension(if cli.anim.is_some() { "gif" } else { "png" })
        }
    };
    if path == Path::new("-") {
        if cli.anim.is_some() {
            return Err("rayrepl: `-o -` writes a single image; give a file name for an animation".into());
        }
        if std::io::stdout().is_terminal() {
            return Err("rayrepl: `-o -` writes binary image data, not for a terminal: \
                        redirect it (`> out.ppm`, `| display`) or give a file name"
                .into());
        }
        return Ok(path);
    }
    if output::same_file(&path, scene) {
        return Err(format!("rayrepl: `{}` is the scene file itself; give another output name", path.display()));
    }
    let content = if cli.anim.is_some() { Content::Animation } else { Content::Still };
    let format = output::check_output(&path, content).map_err(|e| format!("rayrepl: {e}"))?;
    if format == ImageFormat::Gif && cli.frames.is_some() {
        return Err("rayrepl: --frames writes numbered images; use a .png or .ppm name with it".into());
    }
    Ok(path)
}

/// The renderer's settings from the command line.
fn render_options(cli: &Cli) -> RenderOptions {
    if cli.reference {
        return RenderOptions {
            screen: cli.screen.screen(),
            ..RenderOptions::reference(cli.width, cli.height, cli.depth)
        };
    }
    cli.settings().render_options()
}

/// Renders one image at `--time`.
fn still(cli: &Cli, parsed: &ParsedScene, output: &Path) -> Result<(), String> {
    let start = Instant::now();
    let scene = parsed.evaluate(cli.settings().time, false)?;
    let evaluated = start.elapsed();
    let prepared = SceneGeometry::new(&scene);
    let built = start.elapsed() - evaluated;
    let options = render_options(cli);
    let progress = Progress::new(u64::from(options.width) * u64::from(options.height), "rendering");
    let (image, stats) = render_frame(&scene, &prepared, &options, &progress);
    progress.finish();
    if cli.stats {
        eprintln!("evaluate {:.3} s, build {:.3} s", evaluated.as_secs_f64(), built.as_secs_f64());
        print_stats(&stats, 1);
    }
    let name = if output == Path::new("-") {
        let mut stdout = std::io::stdout().lock();
        output::write_ppm(&mut stdout, &image)
            .and_then(|()| stdout.flush())
            .map_err(|e| format!("rayrepl: cannot write the image to standard output: {}", output::io_reason(&e)))?;
        "standard output".to_string()
    } else {
        output::write_image(output, &image).map_err(|e| format!("rayrepl: {e}"))?;
        output.display().to_string()
    };
    report_written(cli, &name, &format!("{}x{}", cli.width, cli.height), start);
    Ok(())
}

/// Says on stderr, unless `--quiet`, what was written to `name`: `what`
/// ("800x600"), the reflections, the samples and the time since `start`.
fn report_written(cli: &Cli, name: &str, what: &str, start: Instant) {
    if cli.quiet {
        return;
    }
    let mut line = format!("wrote {name}: {what}, {}", counted(cli.depth as usize, "reflection", "reflections"));
    let samples = render_options(cli).samples;
    if samples > 1 {
        let adaptive = if cli.adaptive { " (adaptive)" } else { "" };
        line.push_str(&format!(", {}{adaptive}", counted(samples as usize, "sample", "samples")));
    }
    eprintln!("{line}, {:.2} s", start.elapsed().as_secs_f64());
}

/// "1 box", "3 boxes".
fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// Renders one frame with the progress bar attached.
fn render_frame(
    scene: &Scene,
    prepared: &SceneGeometry,
    options: &RenderOptions,
    progress: &Progress,
) -> (RgbImage, RenderStats) {
    let tick = |pixels: u64| progress.advance(pixels);
    let control = RenderControl { progress: Some(&tick), cancel: None };
    render::render(scene, prepared, options, &control).expect("a batch render is never cancelled")
}

/// Renders frames `--frames` (default all) of an animation of `count`
/// frames, frame k with `time = k`, to numbered images or one GIF (see
/// [`animation`] for what is computed once and what per frame).
fn animate(cli: &Cli, parsed: &ParsedScene, count: u32, output: &Path) -> Result<(), String> {
    let start = Instant::now();
    let frames = cli.frames.clone().unwrap_or(1..=count);
    if *frames.end() > count {
        return Err(format!(
            "rayrepl: --frames {}..{} goes past the last frame, {count}",
            frames.start(),
            frames.end()
        ));
    }
    let options = render_options(cli);
    let per_frame = u64::from(options.width) * u64::from(options.height);
    let progress = Progress::new(per_frame * u64::from(frames.end() - frames.start() + 1), "animating");
    let tick = |pixels: u64| progress.advance(pixels);
    let control = RenderControl { progress: Some(&tick), cancel: None };
    let mut frames_out = FrameSink::new(output, count as usize);
    let evaluate = |k: u32, skip_static: bool| parsed.evaluate(f64::from(k), skip_static);
    let sink = |k: u32, image: RgbImage| frames_out.add(k as usize, image).map_err(|e| format!("rayrepl: {e}"));
    let total = match render_animation(frames.clone(), evaluate, &options, &control, sink) {
        Ok(total) => total,
        Err(AnimationError::Failed(message)) => return Err(message),
        Err(AnimationError::Cancelled) => unreachable!("a batch render is never cancelled"),
    };
    progress.finish();
    if cli.stats {
        print_stats(&total, frames.clone().count());
    }
    let written = frames_out.finish().map_err(|e| format!("rayrepl: {e}"))?;
    let what = format!("{} of {}x{}", counted(frames.count(), "frame", "frames"), cli.width, cli.height);
    report_written(cli, &output::describe_files(&written), &what, start);
    Ok(())
}

/// Prints `--stats`: rays of each kind, render time and throughput, and
/// what adaptive anti-aliasing refined.
fn print_stats(stats: &RenderStats, frames: usize) {
    let seconds = stats.elapsed.as_secs_f64();
    let threads = rayon::current_num_threads();
    let total = stats.total_rays();
    let mrays = total as f64 / seconds.max(1e-9) / 1e6;
    eprintln!(
        "frames {frames}: {} primary, {} shadow, {} reflection rays in {seconds:.3} s: {mrays:.1} Mrays/s ({:.1} per thread, {threads} threads)",
        stats.rays.primary,
        stats.rays.shadow,
        stats.rays.reflection,
        mrays / threads as f64,
    );
    if stats.refined_pixels > 0 {
        eprintln!("adaptive: {} pixels refined", stats.refined_pixels);
    }
}
