//! The application: dispatches what the command line asks for to a check, a
//! render of a still image or an animation, renders at every save of a file
//! (`--watch`), or a session. Maps failures to exit codes.

use std::cell::RefCell;
use std::collections::HashSet;
use std::io::{IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use image::RgbImage;

use crate::animation::{AnimationError, render_animation};
use crate::cli::Cli;
use crate::clock::Stopwatch;
use crate::explain::ExplainedScene;
use crate::failure::report_failure;
use crate::lang::ast::Program;
use crate::lang::diagnostic::emit;
use crate::lang::eval::PrintLog;
use crate::lang::{Diagnostic, Interpreter, Limits, SourceId, SourceMap, Span, parse_file};
use crate::lint::{Allowed, Picture, check_scene};
use crate::output::{self, Content, FrameSink, ImageFormat};
use crate::pov;
use crate::render::{self, RenderControl, RenderOptions, RenderStats, SceneGeometry};
use crate::repl::{CancelSwitch, SessionOptions, cancel_flag};
use crate::scene::Scene;
use crate::terminal::preview::Preview;
use crate::terminal::progress::Progress;
use crate::terminal::watch::FileWatcher;
use crate::terminal::{ctrl_c, run_session};

/// The exit code of a command line that asks for something impossible or
/// meaningless (the same as clap's for its own usage errors).
const USAGE_EXIT_CODE: u8 = 2;

/// Runs what the command line asks for and returns the process's exit code.
///
/// With no scene, or with `-i`, that is a session (interactive on a
/// terminal, a script otherwise); with a scene, a check or a render.
pub fn run(cli: Cli) -> ExitCode {
    if let Some(misuse) = cli.misuse() {
        report_failure(misuse);
        return ExitCode::from(USAGE_EXIT_CODE);
    }
    let pool = match rayon::ThreadPoolBuilder::new().num_threads(cli.threads.unwrap_or(0) as usize).build() {
        Ok(pool) => pool,
        Err(e) => {
            report_failure(format_args!("cannot start worker threads: {e}"));
            return ExitCode::FAILURE;
        }
    };
    match cli.scene.clone() {
        Some(path) if !cli.interactive => {
            // Sessions and scripts install it too, and arm it for each entry.
            let switch = ctrl_c::install();
            pool.install(|| exit_code(run_file(&cli, &path, switch), DiagnosticFormat::of(&cli)))
        }
        _ => pool.install(|| run_session(&session_options(&cli))),
    }
}

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
    Limits { max_call_depth: cli.max_calls, max_primitives: cli.max_primitives, ..Limits::DEFAULT }
}

/// Why a check or a render failed.
#[derive(Debug)]
enum BatchError {
    /// A diagnostic about the scene, with the texts it points into.
    Scene(Box<Diagnostic>, SourceMap),
    /// Any other problem, in one message (`cannot read ...`), which
    /// [`report_failure`] writes after the program's name.
    Other(String),
    /// Ctrl-C or `kill` stopped a render or a write: the files written
    /// before it, each whole (no other file changed).
    Interrupted(Vec<PathBuf>),
}

impl From<String> for BatchError {
    fn from(message: String) -> BatchError {
        BatchError::Other(message)
    }
}

/// How diagnostics are shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum DiagnosticFormat {
    /// Drawn for people, on standard error.
    Rendered,
    /// One JSON object per line, on standard output (`--check --json`).
    JsonLines,
}

impl DiagnosticFormat {
    /// The format the command line asks for.
    fn of(cli: &Cli) -> DiagnosticFormat {
        if cli.check && cli.json { DiagnosticFormat::JsonLines } else { DiagnosticFormat::Rendered }
    }

    /// Shows `diagnostic`, which points into `sources`, in this format.
    fn show(self, diagnostic: &Diagnostic, sources: &SourceMap) {
        match self {
            DiagnosticFormat::Rendered => emit(&mut anstream::stderr(), diagnostic, sources),
            DiagnosticFormat::JsonLines => {
                // A reader that stopped early (`| head`) is no failure.
                let _ = writeln!(std::io::stdout().lock(), "{}", diagnostic.to_json(sources));
            }
        }
    }
}

/// Prints a batch error, if any, and gives the exit code.
fn exit_code(result: Result<(), BatchError>, format: DiagnosticFormat) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            print_error(&error, format);
            match error {
                BatchError::Interrupted(_) => ExitCode::from(output::INTERRUPTED_EXIT_CODE as u8),
                _ => ExitCode::FAILURE,
            }
        }
    }
}

/// Prints a batch error on stderr (a diagnostic in `format`).
fn print_error(error: &BatchError, format: DiagnosticFormat) {
    match error {
        BatchError::Scene(diagnostic, sources) => format.show(diagnostic, sources),
        BatchError::Other(message) => report_failure(message),
        BatchError::Interrupted(written) if written.is_empty() => report_failure("interrupted: no file was written"),
        BatchError::Interrupted(written) => {
            report_failure(format_args!("interrupted: {} written before it stopped", output::describe_files(written)))
        }
    }
}

/// Checks or renders one scene file, or follows it with `--watch`. While
/// it renders and writes, `switch` (Ctrl-C, `kill`) stops it; at any
/// other time they end the process.
fn run_file(cli: &Cli, path: &Path, switch: Option<&'static CancelSwitch>) -> Result<(), BatchError> {
    if cli.watch {
        return watch(cli, path);
    }
    let mut sources = SourceMap::new();
    let id = load(&mut sources, path)?;
    let parsed = ParsedScene::parse(sources, id, cli, cancel_flag(switch))?;
    let result = if let Some(pov) = &cli.export_pov {
        export_pov(cli, &parsed, id, pov, path)
    } else if cli.check {
        parsed.evaluate(cli.settings().time, false).map(|scene| {
            if parsed.diagnostics == DiagnosticFormat::Rendered {
                // A closed pipe or a full disk loses the summary, as it
                // would the JSON or an explanation: the check itself is done.
                let _ = writeln!(std::io::stdout().lock(), "{}: {}", parsed.sources.get(id).name, summary(&scene));
            }
        })
    } else if let Some((x, y)) = cli.explain {
        explain(cli, &parsed, x, y)
    } else {
        output_path(cli, path).map_err(BatchError::from).and_then(|output| {
            let _armed = switch.map(CancelSwitch::arm);
            let cancel = cancel_flag(switch);
            match cli.anim {
                Some(count) => animation_format(cli, &output)
                    .and_then(|format| animate(cli, &parsed, count, &output, format, cancel)),
                None => still(cli, &parsed, &output, cancel),
            }
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
    /// Raised by Ctrl-C while a render is under way: stops an evaluation.
    cancel: &'static AtomicBool,
    /// How the warnings are shown.
    diagnostics: DiagnosticFormat,
}

impl ParsedScene {
    /// Parses the file `id` of `sources`, for evaluations that `cancel` stops.
    fn parse(
        sources: SourceMap,
        id: SourceId,
        cli: &Cli,
        cancel: &'static AtomicBool,
    ) -> Result<ParsedScene, BatchError> {
        let program = match parse_file(id, &sources.get(id).text) {
            Ok(program) => program,
            Err(diagnostic) => return Err(BatchError::Scene(Box::new(diagnostic), sources)),
        };
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
            cancel,
            diagnostics: DiagnosticFormat::of(cli),
        })
    }

    /// Evaluates the program at `time`, printing warnings on stderr. With
    /// `skip_static`, primitives that do not depend on `time` are not kept
    /// (an animation's later frames reuse the first frame's).
    /// A warning is printed once per run, however many frames raise it.
    /// What `print` writes comes first; the whole scene (not `skip_static`)
    /// is also checked for the mistakes that spoil a picture.
    fn evaluate(&self, time: f64, skip_static: bool) -> Result<Scene, BatchError> {
        let interpreter = Interpreter::new(time, self.limits).skip_static(skip_static).interruptible(self.cancel);
        self.run(interpreter, !skip_static).map(Interpreter::into_scene)
    }

    /// Runs the program on `interpreter`, printing warnings on stderr (and,
    /// with `check`, checking the scene), as [`ParsedScene::evaluate`] says.
    fn run(&self, mut interpreter: Interpreter, check: bool) -> Result<Interpreter, BatchError> {
        let result = interpreter.run(&self.program);
        let mut printed = self.printed.borrow_mut();
        printed.absorb(interpreter.take_printed());
        for line in printed.take_lines() {
            eprintln!("{}", line.render(&self.sources));
        }
        let mut warnings = interpreter.take_warnings();
        if result.is_ok() && check {
            let checked = check_scene(interpreter.scene(), interpreter.origins(), &self.picture, self.allowed);
            warnings.extend(checked.into_iter().map(|warning| warning.diagnostic));
        }
        for warning in warnings {
            if self.warned.borrow_mut().insert((warning.span, warning.message.clone())) {
                self.diagnostics.show(&warning, &self.sources);
            }
        }
        match result {
            Ok(()) => Ok(interpreter),
            Err(diagnostic) => Err(BatchError::Scene(Box::new(diagnostic), self.sources.clone())),
        }
    }
}

/// Explains pixel `(x, y)` of the image the command line describes, in
/// words or (`--json`) as one JSON object, on standard output.
fn explain(cli: &Cli, parsed: &ParsedScene, x: u32, y: u32) -> Result<(), BatchError> {
    let interpreter = Interpreter::new(cli.settings().time, parsed.limits).recording_calls();
    let interpreter = parsed.run(interpreter, true)?;
    let scene = ExplainedScene::new(&interpreter, &parsed.sources, &render_options(cli));
    let explanation = scene.explain(x, y);
    let text = if cli.json { format!("{}\n", explanation.to_json()) } else { explanation.to_string() };
    // A reader that stopped early (`| head`) is no failure.
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
    Ok(())
}

/// Reads a scene file (or standard input for `-`) into `sources`.
fn load(sources: &mut SourceMap, path: &Path) -> Result<SourceId, String> {
    if path == Path::new("-") {
        let mut text = String::new();
        std::io::stdin()
            .read_to_string(&mut text)
            .map_err(|e| format!("cannot read the scene from standard input: {}", output::io_reason(&e)))?;
        return Ok(sources.add("<stdin>", text, 0));
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read `{}`: {}", path.display(), output::io_reason(&e)))?;
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
            return Err("`-o -` writes a single image; give a file name for an animation".into());
        }
        if std::io::stdout().is_terminal() {
            return Err("`-o -` writes binary image data, not for a terminal: \
                        redirect it (`> out.ppm`, `| display`) or give a file name"
                .into());
        }
        return Ok(path);
    }
    if output::same_file(&path, scene) {
        return Err(format!("`{}` is the scene file itself; give another output name", path.display()));
    }
    if cli.anim.is_none() {
        output::check_output(&path, Content::Still).map_err(|e| e.to_string())?;
    }
    Ok(path)
}

/// The format of the animation's `output`, checked before any work.
fn animation_format(cli: &Cli, output: &Path) -> Result<ImageFormat, BatchError> {
    let format = output::check_animation_output(output, &cli.animation_options()).map_err(|e| e.to_string())?;
    if format.holds_every_frame() && cli.frames.is_some() {
        return Err(BatchError::Other(
            "--frames writes numbered images: use a .png or .ppm name with it, and put the \
             frames together afterwards with ffmpeg (the README's \"Many machines\" shows how)"
                .into(),
        ));
    }
    Ok(format)
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

/// Writes the scene evaluated at `--time` as a POV-Ray scene to `pov`
/// (`-`: standard output).
fn export_pov(cli: &Cli, parsed: &ParsedScene, id: SourceId, pov: &Path, scene_path: &Path) -> Result<(), BatchError> {
    let start = Stopwatch::start();
    if output::same_file(pov, scene_path) {
        return Err(format!("`{}` is the scene file itself; give another output name", pov.display()).into());
    }
    let scene = parsed.evaluate(cli.settings().time, false)?;
    let export = pov::Export {
        source: &parsed.sources.get(id).name,
        time: cli.settings().time,
        depth: cli.depth,
        width: cli.width,
        height: cli.height,
    };
    let text = pov::to_pov(&scene, &export);
    let name = if pov == Path::new("-") {
        let mut stdout = std::io::stdout().lock();
        stdout
            .write_all(text.as_bytes())
            .and_then(|()| stdout.flush())
            .map_err(|e| format!("cannot write the POV-Ray scene to standard output: {}", output::io_reason(&e)))?;
        "standard output".to_string()
    } else {
        output::write_text(pov, &text, &output::NEVER_CANCELLED).map_err(|e| e.to_string())?;
        pov.display().to_string()
    };
    if !cli.quiet {
        eprintln!("wrote {name}: {}, {:.2} s", summary(&scene), start.elapsed().as_secs_f64());
    }
    Ok(())
}

/// Renders one image at `--time`, unless `cancel` is raised.
fn still(cli: &Cli, parsed: &ParsedScene, output: &Path, cancel: &'static AtomicBool) -> Result<(), BatchError> {
    let start = Stopwatch::start();
    let written = render_still(cli, parsed, cancel).and_then(|image| write_still(output, &image, cancel));
    let name = written.map_err(|e| unless_interrupted(e, cancel, &[]))?;
    report_done(cli, &format!("wrote {name}"), &image_size(cli), start);
    Ok(())
}

/// Writes `image` to `output` (`-`: standard output, as PPM), unless
/// `cancel` is raised; returns the name of where it went.
fn write_still(output: &Path, image: &RgbImage, cancel: &'static AtomicBool) -> Result<String, BatchError> {
    if output == Path::new("-") {
        let mut stdout = std::io::stdout().lock();
        output::write_ppm(&mut stdout, image)
            .and_then(|()| stdout.flush())
            .map_err(|e| format!("cannot write the image to standard output: {}", output::io_reason(&e)))?;
        return Ok("standard output".to_string());
    }
    output::write_image_cancellable(output, image, cancel).map_err(|e| e.to_string())?;
    Ok(output.display().to_string())
}

/// Evaluates the scene at `--time` and renders it, with the progress bar
/// and `--stats`, unless `cancel` is raised.
fn render_still(cli: &Cli, parsed: &ParsedScene, cancel: &AtomicBool) -> Result<RgbImage, BatchError> {
    let start = Stopwatch::start();
    let scene = parsed.evaluate(cli.settings().time, false)?;
    let evaluated = start.elapsed();
    let prepared = SceneGeometry::new(&scene);
    let built = start.elapsed() - evaluated;
    let options = render_options(cli);
    let progress = Progress::new(u64::from(options.width) * u64::from(options.height), "rendering");
    let (image, stats) = render_frame(&scene, &prepared, &options, &progress, cancel)?;
    progress.finish();
    if cli.stats {
        let search = prepared.search();
        eprintln!("evaluate {:.3} s, build {:.3} s ({search})", evaluated.as_secs_f64(), built.as_secs_f64());
        print_stats(&stats, 1);
    }
    Ok(image)
}

/// Renders the scene file at `path` again each time it is saved, until
/// Ctrl-C ends the process: shows each picture in the terminal and writes
/// it to `-o` if given. A version that fails is reported, and the last
/// good picture stays.
fn watch(cli: &Cli, path: &Path) -> Result<(), BatchError> {
    let output = match cli.output {
        Some(_) => Some(output_path(cli, path)?),
        None => None,
    };
    let preview = Preview::new(cli.no_preview);
    let watcher = FileWatcher::new(path).map_err(|e| e.to_string())?;
    eprintln!("watching {}: every save renders it again; Ctrl-C stops", path.display());
    // A batch process ends at Ctrl-C: nothing raises this flag.
    let never = AtomicBool::new(false);
    // The text of the version last rendered or reported.
    let mut shown: Option<Arc<str>> = None;
    loop {
        let mut sources = SourceMap::new();
        match load(&mut sources, path) {
            Err(message) if shown.is_none() => return Err(message.into()),
            Err(message) => report_failure(message),
            Ok(id) if shown.as_ref() == Some(&sources.get(id).text) => {}
            Ok(id) => {
                shown = Some(Arc::clone(&sources.get(id).text));
                if let Err(error) = render_version(cli, sources, id, output.as_deref(), preview) {
                    print_error(&error, DiagnosticFormat::Rendered);
                    eprintln!("note: the last good picture stays: fix {} and save it again", path.display());
                }
            }
        }
        watcher.wait(&never).map_err(|e| e.to_string())?;
    }
}

/// Renders one version of a watched file, shows it with `preview` and
/// writes it to `output`.
fn render_version(
    cli: &Cli,
    sources: SourceMap,
    id: SourceId,
    output: Option<&Path>,
    preview: Option<Preview>,
) -> Result<(), BatchError> {
    let start = Stopwatch::start();
    let name = sources.get(id).name.clone();
    let parsed = ParsedScene::parse(sources, id, cli, &output::NEVER_CANCELLED)?;
    let image = render_still(cli, &parsed, &output::NEVER_CANCELLED)?;
    if let Some(preview) = preview {
        preview.show(&image).map_err(|e| format!("cannot show the picture here: {e}"))?;
    }
    let done = match output {
        Some(output) => {
            output::write_image(output, &image).map_err(|e| e.to_string())?;
            format!("wrote {}", output.display())
        }
        None => format!("rendered {name}"),
    };
    report_done(cli, &done, &image_size(cli), start);
    Ok(())
}

/// "800x600": the size of the images asked for.
fn image_size(cli: &Cli) -> String {
    format!("{}x{}", cli.width, cli.height)
}

/// Says on stderr, unless `--quiet`, what was `done` ("wrote out.png"):
/// `what` ("800x600"), the reflections, the samples and the time since `start`.
fn report_done(cli: &Cli, done: &str, what: &str, start: Stopwatch) {
    if cli.quiet {
        return;
    }
    let mut line = format!("{done}: {what}, {}", counted(cli.depth as usize, "reflection", "reflections"));
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

/// Renders one frame with the progress bar attached, unless `cancel` is
/// raised.
fn render_frame(
    scene: &Scene,
    prepared: &SceneGeometry,
    options: &RenderOptions,
    progress: &Progress,
    cancel: &AtomicBool,
) -> Result<(RgbImage, RenderStats), BatchError> {
    let tick = |pixels: u64| progress.advance(pixels);
    let control = RenderControl { progress: Some(&tick), cancel: Some(cancel) };
    render::render(scene, prepared, options, &control).map_err(|_| BatchError::Interrupted(Vec::new()))
}

/// `error`, or, if `cancel` was raised (Ctrl-C, `kill`: the error comes
/// from that), the interruption, after the files `written`.
fn unless_interrupted(error: BatchError, cancel: &AtomicBool, written: &[PathBuf]) -> BatchError {
    if cancel.load(Ordering::SeqCst) { BatchError::Interrupted(written.to_vec()) } else { error }
}

/// Renders frames `--frames` (default all) of an animation of `count`
/// frames, frame k at the time `--time-start` and `--time-step` give it,
/// to numbered images or one file in `format` (see [`animation`] for what
/// is computed once and what per frame), unless `cancel` is raised.
fn animate(
    cli: &Cli,
    parsed: &ParsedScene,
    count: u32,
    output: &Path,
    format: ImageFormat,
    cancel: &'static AtomicBool,
) -> Result<(), BatchError> {
    let start = Stopwatch::start();
    let frames = cli.frames.clone().unwrap_or(1..=count);
    if *frames.end() > count {
        return Err(BatchError::Other(format!(
            "--frames {}..{} goes past the last frame, {count}",
            frames.start(),
            frames.end()
        )));
    }
    let options = render_options(cli);
    let per_frame = u64::from(options.width) * u64::from(options.height);
    let progress = Progress::new(per_frame * u64::from(frames.end() - frames.start() + 1), "animating");
    let tick = |pixels: u64| progress.advance(pixels);
    let control = RenderControl { progress: Some(&tick), cancel: Some(cancel) };
    let animation = cli.animation_options();
    let mut frames_out = FrameSink::new(output, format, count as usize, animation.playback, cancel);
    let evaluate = |k: u32, skip_static: bool| parsed.evaluate(animation.timeline.time_of(k), skip_static);
    let sink =
        |k: u32, image: RgbImage| frames_out.add(k as usize, image).map_err(|e| BatchError::Other(format!("{e}")));
    let total = match render_animation(frames.clone(), evaluate, &options, &control, sink) {
        Ok(total) => total,
        Err(AnimationError::Failed(error)) => return Err(unless_interrupted(error, cancel, frames_out.written())),
        Err(AnimationError::Cancelled) => return Err(BatchError::Interrupted(frames_out.written().to_vec())),
    };
    progress.finish();
    if cli.stats {
        print_stats(&total, frames.clone().count());
    }
    let written = frames_out.finish();
    let written = written.map_err(|e| unless_interrupted(format!("{e}").into(), cancel, &[]))?;
    let what = format!("{} of {}", counted(frames.count(), "frame", "frames"), image_size(cli));
    report_done(cli, &format!("wrote {}", output::describe_files(&written)), &what, start);
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
