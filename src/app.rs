//! The application: runs the job the command line was turned into
//! (`job`): a check, a still image, an animation, renders at every save of
//! a file (`--watch`), an explanation, a POV-Ray export, a grading
//! (`compare`), a formatting (`fmt`) or a session. Maps failures to exit
//! codes.

mod compare;
mod formatting;

use std::cell::RefCell;
use std::io::{self, Read, StdoutLock, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use image::RgbImage;

use crate::animation::{AnimationError, render_animation};
use crate::cli::Cli;
use crate::clock::Stopwatch;
use crate::explain::ExplainedScene;
use crate::job::{Animation, Destination, DiagnosticFormat, Job, JobError, Render, SceneFile, Task};
use crate::lang::ast::Program;
use crate::lang::diagnostic::emit;
use crate::lang::eval::PrintLog;
use crate::lang::source::text_of;
use crate::lang::{Diagnostic, Interpreter, SourceId, SourceMap, parse_file};
use crate::output::{self, FrameSink};
use crate::pipeline::{Evaluated, Evaluation, Lint, PictureError, render_picture};
use crate::pov;
use crate::process::cancel::{CancelSwitch, cancel_flag};
use crate::process::failure::{end_if_closed_pipe, report_failure, tell};
use crate::process::interruption::may_block;
use crate::process::signals;
use crate::render::{self, Region, RenderControl, RenderOptions, RenderStats};
use crate::scene::Scene;
use crate::terminal::preview::Preview;
use crate::terminal::progress::Progress;
use crate::terminal::watch::FileWatcher;
use crate::terminal::{run_script_on_stdin, run_session};
use crate::warned::Warned;

/// The exit code of a command line that asks for something impossible or
/// meaningless (the same as clap's for its own usage errors).
const USAGE_EXIT_CODE: u8 = 2;

/// Runs what the command line asks for and returns the process's exit code.
///
/// With no scene, or with `-i`, that is a session (interactive on a
/// terminal, a script otherwise); with a scene, a check or a render.
pub fn run(cli: Cli) -> ExitCode {
    // Before the job is built: the check of an output folder makes a file,
    // which a signal must remove.
    signals::install();
    let job = match Job::from_cli(cli) {
        Ok(job) => job,
        Err(error) => {
            report_failure(&error);
            return match error {
                JobError::Misuse(_) => ExitCode::from(USAGE_EXIT_CODE),
                JobError::Output(_) => ExitCode::FAILURE,
            };
        }
    };
    let pool = match rayon::ThreadPoolBuilder::new().num_threads(job.threads).build() {
        Ok(pool) => pool,
        Err(e) => {
            report_failure(format_args!("cannot start worker threads: {e}"));
            return ExitCode::FAILURE;
        }
    };
    pool.install(|| dispatch(job.task))
}

/// Writes the kernelspec and says where, or why it could not.
#[cfg(feature = "jupyter")]
fn install_kernel(prefix: &crate::jupyter::KernelPrefix, interrupt_mode: &str) -> ExitCode {
    let installed = std::env::current_exe()
        .map_err(|error| format!("this program's path is not known: {}", output::io_reason(&error)))
        .and_then(|program| crate::jupyter::install(prefix, &program, interrupt_mode));
    match installed {
        Ok(folder) => {
            tell!("installed the kernel `rayrepl` (\"rayrepl (.ray)\") in {}", folder.display());
            ExitCode::SUCCESS
        }
        Err(message) => {
            report_failure(message);
            ExitCode::FAILURE
        }
    }
}

/// Does `task` and gives the exit code. While a still image or an
/// animation renders and writes, Ctrl-C (or `kill`) stops it; at any other
/// time it ends the process.
fn dispatch(task: Task) -> ExitCode {
    // Sessions and scripts install the same switch (one per process), and
    // arm it for each entry.
    let switch = signals::install();
    match task {
        Task::Session(options) => run_session(&options),
        Task::Compare(job) => compare::grade_all(&job),
        Task::Format(job) => formatting::format_all(&job),
        #[cfg(feature = "lsp")]
        Task::LanguageServer => match crate::lsp::serve_stdio() {
            Ok(()) => ExitCode::SUCCESS,
            Err(message) => {
                report_failure(message);
                ExitCode::FAILURE
            }
        },
        #[cfg(feature = "jupyter")]
        Task::Kernel(connection_file) => match crate::jupyter::serve(&connection_file) {
            Ok(()) => ExitCode::SUCCESS,
            Err(message) => {
                report_failure(message);
                ExitCode::FAILURE
            }
        },
        #[cfg(feature = "jupyter")]
        Task::KernelInstall { prefix, interrupt_mode } => install_kernel(&prefix, interrupt_mode),
        Task::Script(options) => run_script_on_stdin(&options, switch),
        Task::Watch { scene, render, output, no_preview } => {
            exit_code(watch(&scene, &render, output.as_deref(), no_preview), DiagnosticFormat::Rendered)
        }
        Task::Check(scene) => run_file(&scene, switch, check),
        Task::Explain { scene, options, pixel, json } => {
            run_file(&scene, switch, |parsed| explain(parsed, &options, pixel, json))
        }
        Task::PovExport { scene, depth, output, quiet } => {
            run_file(&scene, switch, |parsed| export_pov(parsed, depth, &output, quiet))
        }
        Task::Still { scene, render, output } => {
            run_file(&scene, switch, |parsed| cancellable(switch, |cancel| still(parsed, &render, &output, cancel)))
        }
        Task::Animation { scene, render, animation } => run_file(&scene, switch, |parsed| {
            cancellable(switch, |cancel| animate(parsed, &render, &animation, cancel))
        }),
    }
}

/// Does `work` with `switch` armed: Ctrl-C then raises the flag `work` is
/// given instead of ending the process.
fn cancellable<T>(switch: Option<&'static CancelSwitch>, work: impl FnOnce(&'static AtomicBool) -> T) -> T {
    let _armed = switch.map(CancelSwitch::arm);
    work(cancel_flag(switch))
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

/// Shows `diagnostic`, which points into `sources`, in `format`.
fn show(diagnostic: &Diagnostic, sources: &SourceMap, format: DiagnosticFormat) {
    match format {
        DiagnosticFormat::Rendered => emit(&mut anstream::stderr(), diagnostic, sources),
        DiagnosticFormat::JsonLines => {
            // A reader that stopped early (`| head`) is no failure.
            let _ = writeln!(std::io::stdout().lock(), "{}", diagnostic.to_json(sources));
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
        BatchError::Scene(diagnostic, sources) => show(diagnostic, sources, format),
        BatchError::Other(message) => report_failure(message),
        BatchError::Interrupted(written) if written.is_empty() => report_failure("interrupted: no file was written"),
        BatchError::Interrupted(written) => {
            report_failure(format_args!("interrupted: {} written before it stopped", output::describe_files(written)))
        }
    }
}

/// Reads and parses the scene file, does `work` with it and gives the exit
/// code. The evaluations stop when `switch` is armed and Ctrl-C raises its
/// flag.
fn run_file(
    scene: &SceneFile,
    switch: Option<&'static CancelSwitch>,
    work: impl FnOnce(&ParsedScene) -> Result<(), BatchError>,
) -> ExitCode {
    let mut sources = SourceMap::new();
    let result = load(&mut sources, &scene.path).map_err(BatchError::from).and_then(|id| {
        let parsed = ParsedScene::parse(sources, id, scene.clone(), cancel_flag(switch))?;
        let result = work(&parsed);
        if let Some(note) = parsed.printed.borrow().hidden_note() {
            tell!("note: {note}");
        }
        result
    });
    exit_code(result, scene.diagnostics)
}

/// A parsed scene file, ready to be evaluated at any `time`.
struct ParsedScene {
    sources: SourceMap,
    /// The scene file's text in `sources`.
    id: SourceId,
    program: Program,
    /// The file and how it is evaluated and checked.
    file: SceneFile,
    /// The warnings already printed.
    warned: RefCell<Warned>,
    /// What `print` wrote, over every evaluation (the limit is for the whole run).
    printed: RefCell<PrintLog>,
    /// Raised by Ctrl-C while a render is under way: stops an evaluation.
    cancel: &'static AtomicBool,
}

impl ParsedScene {
    /// Parses the file `id` of `sources`, for evaluations that `cancel` stops.
    fn parse(
        sources: SourceMap,
        id: SourceId,
        file: SceneFile,
        cancel: &'static AtomicBool,
    ) -> Result<ParsedScene, BatchError> {
        match parse_file(id, &sources.get(id).text) {
            Ok(program) => Ok(ParsedScene {
                sources,
                id,
                program,
                file,
                warned: RefCell::default(),
                printed: RefCell::default(),
                cancel,
            }),
            Err(diagnostic) => Err(BatchError::Scene(Box::new(diagnostic), sources)),
        }
    }

    /// The scene file's name, as messages give it.
    fn name(&self) -> &str {
        &self.sources.get(self.id).name
    }

    /// Evaluates the program at `time`, printing warnings on stderr. With
    /// `skip_static`, primitives that do not depend on `time` are not kept
    /// (an animation's later frames reuse the first frame's).
    /// A warning is printed once per run, however many frames raise it.
    /// What `print` writes comes first; the whole scene (not `skip_static`)
    /// is also checked for the mistakes that spoil a picture.
    fn evaluate(&self, time: f64, skip_static: bool) -> Result<Scene, BatchError> {
        let evaluation = self.evaluation(time, skip_static);
        self.run(&evaluation, evaluation.interpreter()).map(Interpreter::into_scene)
    }

    /// How the file is evaluated at `time` (see [`ParsedScene::evaluate`]).
    fn evaluation(&self, time: f64, skip_static: bool) -> Evaluation {
        let SceneFile { limits, picture, allowed, .. } = self.file;
        let lint = (!skip_static).then_some(Lint { picture, allowed });
        Evaluation { time, limits, cancel: Some(self.cancel), lint, skip_static }
    }

    /// Runs the program on `interpreter` (one `evaluation` set up, perhaps
    /// recording more), printing warnings on stderr as
    /// [`ParsedScene::evaluate`] says.
    fn run(&self, evaluation: &Evaluation, interpreter: Interpreter) -> Result<Interpreter, BatchError> {
        let Evaluated { mut interpreter, result, warnings } = evaluation.run_on(interpreter, &self.program);
        let mut printed = self.printed.borrow_mut();
        printed.absorb(interpreter.take_printed());
        for line in printed.take_lines() {
            tell!("{}", line.render(&self.sources));
        }
        for warning in self.warned.borrow_mut().unseen(warnings) {
            show(&warning, &self.sources, self.file.diagnostics);
        }
        match result {
            Ok(()) => Ok(interpreter),
            Err(diagnostic) => Err(BatchError::Scene(Box::new(diagnostic), self.sources.clone())),
        }
    }
}

/// Evaluates the scene at its time and says what it holds, unless the
/// diagnostics go out as JSON.
fn check(parsed: &ParsedScene) -> Result<(), BatchError> {
    let scene = parsed.evaluate(parsed.file.time, false)?;
    if parsed.file.diagnostics == DiagnosticFormat::Rendered {
        write_stdout("the summary", |stdout| writeln!(stdout, "{}: {}", parsed.name(), summary(&scene)))?;
    }
    Ok(())
}

/// Explains pixel `(x, y)` of the image `options` render, in words or
/// (`json`) as one JSON object, on standard output.
fn explain(parsed: &ParsedScene, options: &RenderOptions, (x, y): (u32, u32), json: bool) -> Result<(), BatchError> {
    let evaluation = parsed.evaluation(parsed.file.time, false);
    let interpreter = parsed.run(&evaluation, evaluation.interpreter().recording_calls())?;
    render::reserve_for(interpreter.scene(), options).map_err(|error| error.to_string())?;
    let explanation = ExplainedScene::new(&interpreter, &parsed.sources, options).explain(x, y);
    let text = if json { format!("{}\n", explanation.to_json()) } else { explanation.to_string() };
    write_stdout("the explanation", |stdout| stdout.write_all(text.as_bytes()))?;
    Ok(())
}

/// Reads a scene file (or standard input for `-`) into `sources`.
fn load(sources: &mut SourceMap, path: &Path) -> Result<SourceId, String> {
    if path == Path::new("-") {
        let mut bytes = Vec::new();
        std::io::stdin()
            .read_to_end(&mut bytes)
            .map_err(|e| format!("cannot read the scene from standard input: {}", output::io_reason(&e)))?;
        let text = text_of(bytes).map_err(|place| format!("cannot read the scene from standard input: {place}"))?;
        return Ok(sources.add("<stdin>", text, 0));
    }
    let failed = |reason: String| format!("cannot read `{}`: {reason}", path.display());
    let bytes = std::fs::read(path).map_err(|e| failed(output::io_reason(&e)))?;
    Ok(sources.add(path.display().to_string(), text_of(bytes).map_err(failed)?, 0))
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

/// Writes the scene evaluated at its time as a POV-Ray scene for `depth`
/// reflections to `output`, saying so unless `quiet`.
fn export_pov(parsed: &ParsedScene, depth: u32, output: &Destination, quiet: bool) -> Result<(), BatchError> {
    let start = Stopwatch::start();
    let SceneFile { time, picture, .. } = parsed.file;
    let scene = parsed.evaluate(time, false)?;
    let export = pov::Export { source: parsed.name(), time, depth, width: picture.width, height: picture.height };
    // Refused before anything is written: no file, nothing on standard output.
    let text = pov::to_pov(&scene, &export).map_err(|e| e.to_string())?;
    match output {
        Destination::Stdout => write_stdout("the POV-Ray scene", |stdout| stdout.write_all(text.as_bytes()))?,
        Destination::File(pov) => {
            output::write_text(pov, &text, &output::NEVER_CANCELLED).map_err(|e| e.to_string())?
        }
    }
    if !quiet {
        tell!("wrote {output}: {}, {:.2} s", summary(&scene), start.elapsed().as_secs_f64());
    }
    Ok(())
}

/// Renders one image at the scene's time, unless `cancel` is raised.
fn still(
    parsed: &ParsedScene,
    render: &Render,
    output: &Destination,
    cancel: &'static AtomicBool,
) -> Result<(), BatchError> {
    let start = Stopwatch::start();
    let written = render_still(parsed, render, cancel).and_then(|image| write_still(output, &image, cancel));
    written.map_err(|e| unless_interrupted(e, cancel, &[]))?;
    report_done(render, &format!("wrote {output}"), &image_size(&render.options), start);
    Ok(())
}

/// Writes `image` to `output` (standard output as PPM), unless `cancel` is
/// raised.
fn write_still(output: &Destination, image: &RgbImage, cancel: &'static AtomicBool) -> Result<(), BatchError> {
    match output {
        Destination::Stdout => write_stdout("the image", |stdout| output::write_ppm(stdout, image))?,
        Destination::File(path) => output::write_image_cancellable(path, image, cancel).map_err(|e| e.to_string())?,
    }
    Ok(())
}

/// Writes `what` ("the image") to standard output with `write`, and
/// flushes it.
fn write_stdout(what: &str, write: impl FnOnce(&mut StdoutLock<'static>) -> io::Result<()>) -> Result<(), String> {
    let mut stdout = std::io::stdout().lock();
    // A reader that does not read blocks the write: a signal then ends the
    // process (`crate::process::interruption`).
    may_block(|| write(&mut stdout).and_then(|()| stdout.flush())).map_err(|e| {
        end_if_closed_pipe(&e);
        format!("cannot write {what} to standard output: {}", output::io_reason(&e))
    })
}

/// Evaluates the scene at its time and renders it, with the progress bar
/// and `--stats`, unless `cancel` is raised.
fn render_still(parsed: &ParsedScene, render: &Render, cancel: &AtomicBool) -> Result<RgbImage, BatchError> {
    let start = Stopwatch::start();
    let scene = parsed.evaluate(parsed.file.time, false)?;
    let evaluated = start.elapsed();
    let options = &render.options;
    let progress = Progress::new(u64::from(options.width) * u64::from(options.height), "rendering");
    let tick = |pixels: u64| progress.advance(pixels);
    let control = RenderControl { progress: Some(&tick), cancel: Some(cancel) };
    let rendered = render_picture(&scene, options, Region::whole(options), &control).map_err(|error| match error {
        PictureError::OutOfMemory(error) => BatchError::from(error.to_string()),
        PictureError::Cancelled => BatchError::Interrupted(Vec::new()),
    })?;
    progress.finish();
    if render.stats {
        let (search, built) = (rendered.geometry.search(), rendered.built.as_secs_f64());
        tell!("evaluate {:.3} s, build {built:.3} s ({search})", evaluated.as_secs_f64());
        print_stats(&rendered.stats, 1);
    }
    Ok(rendered.image)
}

/// Renders the scene file again each time it is saved, until Ctrl-C ends
/// the process: shows each picture in the terminal (unless `no_preview`)
/// and writes it to `output` if given. A version that fails is reported,
/// and the last good picture stays.
fn watch(scene: &SceneFile, render: &Render, output: Option<&Path>, no_preview: bool) -> Result<(), BatchError> {
    let path = &scene.path;
    let preview = Preview::new(no_preview);
    let watcher = FileWatcher::new(path).map_err(|e| e.to_string())?;
    tell!("watching {}: every save renders it again; Ctrl-C stops", path.display());
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
                if let Err(error) = render_version(sources, id, scene.clone(), render, output, preview) {
                    print_error(&error, DiagnosticFormat::Rendered);
                    tell!("note: the last good picture stays: fix {} and save it again", path.display());
                }
            }
        }
        watcher.wait(&never).map_err(|e| e.to_string())?;
    }
}

/// Renders one version of a watched file, shows it with `preview` and
/// writes it to `output`.
fn render_version(
    sources: SourceMap,
    id: SourceId,
    file: SceneFile,
    render: &Render,
    output: Option<&Path>,
    preview: Option<Preview>,
) -> Result<(), BatchError> {
    let start = Stopwatch::start();
    let parsed = ParsedScene::parse(sources, id, file, &output::NEVER_CANCELLED)?;
    let image = render_still(&parsed, render, &output::NEVER_CANCELLED)?;
    if let Some(preview) = preview {
        preview.show(&image).map_err(|e| format!("cannot show the picture here: {e}"))?;
    }
    let done = match output {
        Some(output) => {
            output::write_image(output, &image).map_err(|e| e.to_string())?;
            format!("wrote {}", output.display())
        }
        None => format!("rendered {}", parsed.name()),
    };
    report_done(render, &done, &image_size(&render.options), start);
    Ok(())
}

/// "800x600": the size of the images `options` render.
fn image_size(options: &RenderOptions) -> String {
    format!("{}x{}", options.width, options.height)
}

/// Says on stderr, unless `--quiet`, what was `done` ("wrote out.png"):
/// `what` ("800x600"), the reflections, the samples and the time since `start`.
fn report_done(render: &Render, done: &str, what: &str, start: Stopwatch) {
    if render.quiet {
        return;
    }
    let RenderOptions { depth, samples, adaptive, .. } = render.options;
    let mut line = format!("{done}: {what}, {}", counted(depth as usize, "reflection", "reflections"));
    if samples > 1 {
        let adaptive = if adaptive { " (adaptive)" } else { "" };
        line.push_str(&format!(", {}{adaptive}", counted(samples as usize, "sample", "samples")));
    }
    tell!("{line}, {:.2} s", start.elapsed().as_secs_f64());
}

/// "1 box", "3 boxes".
fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// `error`, or, if `cancel` was raised (Ctrl-C, `kill`: the error comes
/// from that), the interruption, after the files `written`.
fn unless_interrupted(error: BatchError, cancel: &AtomicBool, written: &[PathBuf]) -> BatchError {
    if cancel.load(Ordering::SeqCst) { BatchError::Interrupted(written.to_vec()) } else { error }
}

/// Renders the frames of `animation` (see [`crate::animation`] for what is
/// computed once and what per frame), frame k at the time its timeline
/// gives it, to numbered images or one file, unless `cancel` is raised.
fn animate(
    parsed: &ParsedScene,
    render: &Render,
    animation: &Animation,
    cancel: &'static AtomicBool,
) -> Result<(), BatchError> {
    let start = Stopwatch::start();
    let Animation { count, ref frames, ref output, format, options } = *animation;
    let per_frame = u64::from(render.options.width) * u64::from(render.options.height);
    let progress = Progress::new(per_frame * u64::from(frames.end() - frames.start() + 1), "animating");
    let tick = |pixels: u64| progress.advance(pixels);
    let control = RenderControl { progress: Some(&tick), cancel: Some(cancel) };
    let mut frames_out = FrameSink::new(output, format, count as usize, options.playback, cancel);
    let evaluate = |k: u32, skip_static: bool| parsed.evaluate(options.timeline.time_of(k), skip_static);
    let sink =
        |k: u32, image: RgbImage| frames_out.add(k as usize, image).map_err(|e| BatchError::Other(format!("{e}")));
    let total = match render_animation(frames.clone(), evaluate, &render.options, &control, sink) {
        Ok(total) => total,
        Err(AnimationError::Failed(error)) => return Err(unless_interrupted(error, cancel, frames_out.written())),
        Err(AnimationError::Cancelled) => return Err(BatchError::Interrupted(frames_out.written().to_vec())),
        Err(AnimationError::OutOfMemory(error)) => return Err(BatchError::Other(error.to_string())),
    };
    progress.finish();
    if render.stats {
        print_stats(&total, frames.clone().count());
    }
    let written = frames_out.finish();
    let written = written.map_err(|e| unless_interrupted(format!("{e}").into(), cancel, &[]))?;
    let what = format!("{} of {}", counted(frames.clone().count(), "frame", "frames"), image_size(&render.options));
    report_done(render, &format!("wrote {}", output::describe_files(&written)), &what, start);
    Ok(())
}

/// Prints `--stats`: rays of each kind, render time and throughput, and
/// what adaptive anti-aliasing refined.
fn print_stats(stats: &RenderStats, frames: usize) {
    let seconds = stats.elapsed.as_secs_f64();
    let threads = rayon::current_num_threads();
    let total = stats.total_rays();
    let mrays = total as f64 / seconds.max(1e-9) / 1e6;
    tell!(
        "frames {frames}: {} primary, {} shadow, {} reflection rays in {seconds:.3} s: {mrays:.1} Mrays/s ({:.1} per thread, {threads} threads)",
        stats.rays.primary,
        stats.rays.shadow,
        stats.rays.reflection,
        mrays / threads as f64,
    );
    if stats.refined_pixels > 0 {
        tell!("adaptive: {} pixels refined", stats.refined_pixels);
    }
}
