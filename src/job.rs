//! The command line turned into a job, in one step: which flags go together
//! is decided here (from the table of `cli::flags`), and the settings,
//! limits and outputs are resolved and checked before any work, so that what
//! runs the job (`app`) reads only what this step gives it, never the flags.

use std::fmt;
use std::io::IsTerminal;
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

mod compare;
mod formatting;

pub use compare::{GradingJob, Report};
pub use formatting::{Formatted, FormattingJob};

use crate::cli::flags::{FLAGS, flag_with_id};
use crate::cli::{Cli, Command};
use crate::lang::Limits;
use crate::lint::{Allowed, Picture};
use crate::output::{self, Content, ImageFormat, OutputError};
use crate::playback::{AnimationOptions, Playback};
use crate::render::RenderOptions;
use crate::session::SessionOptions;
use crate::settings::{DEFAULTS, RenderSettings};

/// What the command line asks for, checked: the task and the threads it
/// runs on.
#[derive(Debug)]
pub struct Job {
    /// Worker threads (`--threads`); 0 for one per core.
    pub threads: usize,
    /// What to do.
    pub task: Task,
}

/// The tasks of the command line, each with what it needs.
#[derive(Debug)]
pub enum Task {
    /// `lsp`: serve the Language Server Protocol on standard input and output.
    #[cfg(feature = "lsp")]
    LanguageServer,
    /// `jupyter --connection-file FILE`: serve a notebook kernel.
    #[cfg(feature = "jupyter")]
    Kernel(PathBuf),
    /// `jupyter install`: write the kernelspec under `prefix`.
    #[cfg(feature = "jupyter")]
    KernelInstall {
        /// Where.
        prefix: crate::jupyter::KernelPrefix,
        /// The kernelspec's `interrupt_mode`.
        interrupt_mode: &'static str,
    },
    /// `--check`: evaluate the scene and say what it holds.
    Check(SceneFile),
    /// Render one image at the scene's time and write it to `output`.
    Still { scene: SceneFile, render: Render, output: Destination },
    /// `--anim N`: render frames of an animation.
    Animation { scene: SceneFile, render: Render, animation: Animation },
    /// `--watch`: render again at every save of the scene file, show each
    /// picture in the terminal unless `no_preview`, and write it to
    /// `output` if given.
    Watch { scene: SceneFile, render: Render, output: Option<PathBuf>, no_preview: bool },
    /// `--explain X,Y`: why `pixel` of the image `options` render has its
    /// colour, in words or (`json`) as one JSON object.
    Explain { scene: SceneFile, options: RenderOptions, pixel: (u32, u32), json: bool },
    /// `--export-pov`: the scene at its time as a POV-Ray scene for
    /// `depth` reflections, saying what was written unless `quiet`.
    PovExport { scene: SceneFile, depth: u32, output: Destination, quiet: bool },
    /// `rayrepl compare`: grade submissions against a reference.
    Compare(GradingJob),
    /// `rayrepl fmt`: format scene files in place, or standard input.
    Format(FormattingJob),
    /// No scene file, or `-i`, with standard input a terminal: the
    /// interactive session.
    Session(SessionOptions),
    /// No scene file, or `-i`, with standard input not a terminal: a script
    /// read from it (`cat script | rayrepl`).
    Script(SessionOptions),
}

/// The scene file a task reads, and how it is evaluated and checked.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneFile {
    /// Its path; `-` reads standard input.
    pub path: PathBuf,
    /// The value of `time` of a single image (`--time`).
    pub time: f64,
    /// Limits on procedure calls and primitives.
    pub limits: Limits,
    /// The checks of the scene turned off (`--allow`).
    pub allowed: Allowed,
    /// How the scene is rendered, for the checks of the scene.
    pub picture: Picture,
    /// How warnings and errors are shown.
    pub diagnostics: DiagnosticFormat,
}

/// How diagnostics are shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DiagnosticFormat {
    /// Drawn for people, on standard error.
    Rendered,
    /// One JSON object per line, on standard output (`--check --json`).
    JsonLines,
}

/// How pictures are rendered, and what is said about them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Render {
    /// The renderer's settings.
    pub options: RenderOptions,
    /// Say nothing of what was written (`--quiet`).
    pub quiet: bool,
    /// Print ray counts and timings (`--stats`).
    pub stats: bool,
}

/// The frames of an animation and the file or files they go to.
#[derive(Debug, Clone, PartialEq)]
pub struct Animation {
    /// How many frames the whole animation has.
    pub count: u32,
    /// The frames rendered (`--frames`, all by default), within `1..=count`.
    pub frames: RangeInclusive<u32>,
    /// One animation file, or the pattern of numbered images.
    pub output: PathBuf,
    /// The output's format, which suits `options`.
    pub format: ImageFormat,
    /// The frames' times and how the file plays them.
    pub options: AnimationOptions,
}

/// Where one image or one text is written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Destination {
    /// Standard output (`-`).
    Stdout,
    /// A file, checked before any work.
    File(PathBuf),
}

impl Destination {
    /// Standard output for `-`, otherwise the file `path`.
    fn of(path: &Path) -> Destination {
        if path == Path::new("-") { Destination::Stdout } else { Destination::File(path.to_owned()) }
    }
}

/// Where it is, as "wrote ..." says.
impl fmt::Display for Destination {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Destination::Stdout => f.write_str("standard output"),
            Destination::File(path) => path.display().fmt(f),
        }
    }
}

/// Why the command line gives no job.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum JobError {
    /// A flag that would do nothing with the others given, or a setting
    /// out of its limits: a usage error, as clap's own are.
    Misuse(String),
    /// What the job writes cannot be written as asked: an output that
    /// cannot receive it, or frames the animation does not have.
    Output(String),
}

impl fmt::Display for JobError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            JobError::Misuse(message) | JobError::Output(message) => f.write_str(message),
        }
    }
}

impl From<OutputError> for JobError {
    fn from(error: OutputError) -> JobError {
        JobError::Output(error.to_string())
    }
}

impl Job {
    /// The job `cli` asks for, or why there is none. Its outputs are
    /// checked on disk (a file can be made in their folder), before the
    /// scene is read.
    pub fn from_cli(cli: Cli) -> Result<Job, JobError> {
        Job::resolve(&cli, std::io::stdin().is_terminal(), std::io::stdout().is_terminal())
    }

    /// [`Job::from_cli`], with standard input and output terminals or not.
    fn resolve(cli: &Cli, stdin_is_terminal: bool, stdout_is_terminal: bool) -> Result<Job, JobError> {
        match &cli.command {
            Some(Command::Compare(args)) => {
                let threads = args.threads.unwrap_or(0) as usize;
                return Ok(Job { threads, task: Task::Compare(compare::grading_job(args)?) });
            }
            Some(Command::Fmt(args)) => {
                return Ok(Job { threads: 1, task: Task::Format(formatting::formatting_job(args)?) });
            }
            #[cfg(feature = "lsp")]
            Some(Command::Lsp) => return Ok(Job { threads: 0, task: Task::LanguageServer }),
            #[cfg(feature = "jupyter")]
            Some(Command::Jupyter(args)) => return Ok(Job { threads: 0, task: kernel_task(args)? }),
            None => {}
        }
        if let Some(misuse) = misuse(cli) {
            return Err(JobError::Misuse(misuse));
        }
        let task = match scene_path(cli) {
            Some(path) => file_task(cli, path, stdout_is_terminal)?,
            None if stdin_is_terminal => Task::Session(session_options(cli)),
            None => Task::Script(session_options(cli)),
        };
        Ok(Job { threads: cli.threads.unwrap_or(0) as usize, task })
    }
}

/// The scene file to check or render; none starts a session.
fn scene_path(cli: &Cli) -> Option<&Path> {
    cli.scene.as_deref().filter(|_| !cli.interactive)
}

/// The task for the scene file at `path`, with its outputs checked.
fn file_task(cli: &Cli, path: &Path, stdout_is_terminal: bool) -> Result<Task, JobError> {
    let scene = scene_file(cli, path);
    let render = Render { options: render_options(cli), quiet: cli.quiet, stats: cli.stats };
    Ok(if cli.watch {
        let output = cli.output.as_deref().map(|output| still_file(output, path)).transpose()?;
        Task::Watch { scene, render, output, no_preview: cli.no_preview }
    } else if let Some(pov) = &cli.export_pov {
        not_the_scene(pov, path)?;
        Task::PovExport { scene, depth: cli.picture.depth, output: Destination::of(pov), quiet: cli.quiet }
    } else if cli.check {
        Task::Check(scene)
    } else if let Some(pixel) = cli.explain {
        Task::Explain { scene, options: render.options, pixel, json: cli.json }
    } else if let Some(count) = cli.anim {
        Task::Animation { animation: animation(cli, count, path)?, scene, render }
    } else {
        Task::Still { output: still_output(cli, path, stdout_is_terminal)?, scene, render }
    })
}

/// The render settings the command line asks for.
fn settings(cli: &Cli) -> RenderSettings {
    RenderSettings {
        width: cli.picture.width,
        height: cli.picture.height,
        depth: cli.picture.depth,
        samples: cli.picture.samples,
        adaptive: cli.adaptive,
        time: cli.time.unwrap_or(DEFAULTS.time),
        screen: cli.screen.screen(),
    }
}

/// The renderer's settings: [`settings`], or the reference render's.
fn render_options(cli: &Cli) -> RenderOptions {
    if cli.reference {
        return RenderOptions {
            screen: cli.screen.screen(),
            ..RenderOptions::reference(cli.picture.width, cli.picture.height, cli.picture.depth)
        };
    }
    settings(cli).render_options()
}

/// The evaluator's limits (`--max-calls`, `--max-primitives`).
fn limits(cli: &Cli) -> Limits {
    cli.limits.limits()
}

/// The checks of the scene turned off (`--allow`).
fn allowed(cli: &Cli) -> Allowed {
    cli.allow.iter().fold(Allowed::default(), |all, allowed| all.and(*allowed))
}

/// The scene file at `path`, with how it is evaluated and checked.
fn scene_file(cli: &Cli, path: &Path) -> SceneFile {
    let picture = Picture {
        width: cli.picture.width,
        height: cli.picture.height,
        screen: cli.screen.screen(),
        animation: cli.anim.is_some(),
    };
    let diagnostics = if cli.check && cli.json { DiagnosticFormat::JsonLines } else { DiagnosticFormat::Rendered };
    let (time, limits, allowed) = (settings(cli).time, limits(cli), allowed(cli));
    SceneFile { path: path.to_owned(), time, limits, allowed, picture, diagnostics }
}

/// The session's options.
fn session_options(cli: &Cli) -> SessionOptions {
    SessionOptions {
        no_preview: cli.no_preview,
        keep_going: cli.keep_going,
        initial_file: cli.scene.clone(),
        lesson: cli.lesson.clone(),
        settings: settings(cli),
        limits: limits(cli),
        allowed: allowed(cli),
    }
}

/// The output file named by `-o`, or the scene's name with `extension` in
/// the current directory.
fn output_name(cli: &Cli, scene: &Path, extension: &str) -> PathBuf {
    cli.output.clone().unwrap_or_else(|| {
        let stem = scene.file_stem().filter(|_| scene != Path::new("-")).unwrap_or("out".as_ref());
        PathBuf::from(stem).with_extension(extension)
    })
}

/// Refuses an output that is the scene file itself.
fn not_the_scene(output: &Path, scene: &Path) -> Result<(), JobError> {
    if output::same_file(output, scene) {
        return Err(JobError::Output(format!(
            "`{}` is the scene file itself; give another output name",
            output.display()
        )));
    }
    Ok(())
}

/// `output`, checked to receive one image.
fn still_file(output: &Path, scene: &Path) -> Result<PathBuf, JobError> {
    not_the_scene(output, scene)?;
    output::check_output(output, Content::Still)?;
    Ok(output.to_owned())
}

/// Where the still image goes: `-o` (`-`: standard output, which must not
/// be a terminal), or `SCENE.png`.
fn still_output(cli: &Cli, scene: &Path, stdout_is_terminal: bool) -> Result<Destination, JobError> {
    match Destination::of(&output_name(cli, scene, "png")) {
        Destination::Stdout if stdout_is_terminal => Err(JobError::Output(
            "`-o -` writes binary image data, not for a terminal: \
             redirect it (`> out.ppm`, `| display`) or give a file name"
                .into(),
        )),
        Destination::Stdout => Ok(Destination::Stdout),
        Destination::File(path) => still_file(&path, scene).map(Destination::File),
    }
}

/// The animation of `count` frames, with its output (`-o`, or `SCENE.gif`)
/// checked for its format and the frames asked for.
fn animation(cli: &Cli, count: u32, scene: &Path) -> Result<Animation, JobError> {
    let output = output_name(cli, scene, "gif");
    if output == Path::new("-") {
        return Err(JobError::Output("`-o -` writes a single image; give a file name for an animation".into()));
    }
    not_the_scene(&output, scene)?;
    let timeline = cli.timeline.timeline();
    let options = AnimationOptions { timeline, playback: Playback { fps: cli.fps, loops: cli.loops }, apng: cli.apng };
    let format = output::check_animation_output(&output, &options)?;
    if format.holds_every_frame() && cli.frames.is_some() {
        return Err(JobError::Output(
            "--frames writes numbered images: use a .png or .ppm name with it, and put the \
             frames together afterwards with ffmpeg (docs/guide/scale-out.md shows how)"
                .into(),
        ));
    }
    let frames = cli.frames.clone().unwrap_or(1..=count);
    if *frames.end() > count {
        return Err(JobError::Output(format!(
            "--frames {}..{} goes past the last frame, {count}",
            frames.start(),
            frames.end()
        )));
    }
    options.timeline.check(frames.clone()).map_err(|e| JobError::Misuse(e.to_string()))?;
    if let Some((frame, name)) = output::frame_over(scene, &output, format, frames.clone(), count) {
        return Err(JobError::Output(format!(
            "`{}`, frame {frame} of the animation, is the scene file itself; give another output name",
            name.display()
        )));
    }
    Ok(Animation { count, frames, output, format, options })
}

/// A flag that would do nothing with the others given, said in words, or
/// a setting out of its limits. Which flags go together is the table of
/// `cli::flags` (clap has already refused the pairs it lists as conflicts);
/// the rules here depend on the values given.
fn misuse(cli: &Cli) -> Option<String> {
    let session = scene_path(cli).is_none().then_some(if cli.interactive {
        "-i starts a session"
    } else {
        "without a scene file, rayrepl starts a session"
    });
    let given = |id: &str| (flag_with_id(id).given)(cli);
    if let Some(misuse) = FLAGS.iter().find_map(|flag| flag.misuse(&given, session)) {
        return Some(misuse);
    }
    if session.is_some() {
        return None;
    }
    if cli.watch && cli.scene.as_deref() == Some(Path::new("-")) {
        return Some("--watch follows a file as it is saved: give its name, not `-`".into());
    }
    if cli.watch && cli.output.as_deref() == Some(Path::new("-")) {
        return Some("--watch writes an image at every save: give -o a file name, not `-`".into());
    }
    if let Some((x, y)) = cli.explain
        && (x >= cli.picture.width || y >= cli.picture.height)
    {
        return Some(format!(
            "--explain {x},{y} is outside the {}x{} image: x goes from 0 to {}, y from 0 to {}",
            cli.picture.width,
            cli.picture.height,
            cli.picture.width - 1,
            cli.picture.height - 1
        ));
    }
    settings(cli).validate().err().map(|error| error.to_string())
}

/// The task `rayrepl jupyter` asks for.
#[cfg(feature = "jupyter")]
fn kernel_task(args: &crate::cli::JupyterArgs) -> Result<Task, JobError> {
    use crate::cli::{InterruptMode, JupyterAction};
    use crate::jupyter::KernelPrefix;
    match (&args.action, &args.connection_file) {
        (Some(JupyterAction::Install(install)), _) => {
            let prefix = match (&install.prefix, install.sys_prefix) {
                (Some(prefix), _) => KernelPrefix::Prefix(prefix.clone()),
                (None, true) => KernelPrefix::SysPrefix,
                (None, false) => KernelPrefix::User,
            };
            let interrupt_mode = match install.interrupt_mode {
                InterruptMode::Message => "message",
                InterruptMode::Signal => "signal",
            };
            Ok(Task::KernelInstall { prefix, interrupt_mode })
        }
        (None, Some(file)) => Ok(Task::Kernel(file.clone())),
        (None, None) => Err(JobError::Misuse(
            "Jupyter starts the kernel with --connection-file FILE; to let it, run `rayrepl jupyter install` first"
                .to_string(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;
    use crate::cli::flags::tests::example;
    use crate::cli::flags::{Flag, InASession, Needs};
    use crate::lint::Check;
    use crate::playback::Timeline;
    use crate::render::Screen;

    /// The job of `args` after `rayrepl`, with standard output not a terminal.
    fn job(args: &[&str]) -> Result<Job, JobError> {
        Job::resolve(&Cli::parse_from(["rayrepl"].iter().chain(args)), true, false)
    }

    /// The task of `args`, which must give one.
    fn task(args: &[&str]) -> Task {
        job(args).expect("a job").task
    }

    /// `name` in a fresh folder, as text, and the folder (kept while used).
    fn output_in_temp(name: &str) -> (tempfile::TempDir, String) {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let path = dir.path().join(name).display().to_string();
        (dir, path)
    }

    #[test]
    fn a_scene_file_is_a_still_image_with_its_settings_and_output() {
        let (_dir, out) = output_in_temp("a.png");
        let args = ["a.ray", "--width", "40", "--height", "30", "--samples", "4", "--time", "2", "-q", "-o", &out];
        let Task::Still { scene, render, output } = task(&args) else { panic!("a still image") };
        assert_eq!(scene.path, Path::new("a.ray"));
        assert_eq!(scene.time, 2.0);
        assert_eq!(scene.picture, Picture { width: 40, height: 30, screen: Screen::Centered, animation: false });
        assert_eq!(scene.diagnostics, DiagnosticFormat::Rendered);
        assert_eq!((render.options.width, render.options.height, render.options.samples), (40, 30, 4));
        assert!(render.quiet && !render.stats);
        assert_eq!(output, Destination::File(out.into()));
    }

    #[test]
    fn without_dash_o_the_output_is_named_after_the_scene() {
        let cli = Cli::parse_from(["rayrepl", "scenes/solar.ray"]);
        assert_eq!(output_name(&cli, Path::new("scenes/solar.ray"), "gif"), Path::new("solar.gif"));
        assert_eq!(output_name(&cli, Path::new("-"), "png"), Path::new("out.png"));
    }

    #[test]
    fn dash_o_dash_is_standard_output_for_one_image_only_and_never_a_terminal() {
        assert!(matches!(task(&["a.ray", "-o", "-"]), Task::Still { output: Destination::Stdout, .. }));
        let on_a_terminal = Job::resolve(&Cli::parse_from(["rayrepl", "a.ray", "-o", "-"]), true, true);
        assert!(matches!(on_a_terminal, Err(JobError::Output(message)) if message.contains("redirect it")));
        let animation = job(&["a.ray", "--anim", "3", "-o", "-"]);
        assert!(matches!(animation, Err(JobError::Output(message)) if message.contains("single image")));
    }

    #[test]
    fn an_animation_carries_its_frames_times_and_checked_output() {
        let (_dir, out) = output_in_temp("f.png");
        let args = ["a.ray", "--anim", "5", "--frames", "2..3", "--time-start", "0", "--time-step", "0.5", "-o", &out];
        let Task::Animation { scene, animation, .. } = task(&args) else { panic!("an animation") };
        assert!(scene.picture.animation);
        assert_eq!((animation.count, animation.frames, animation.format), (5, 2..=3, ImageFormat::Png));
        assert_eq!(animation.options.timeline, Timeline { start: 0.0, step: 0.5 });
        assert_eq!(animation.output, Path::new(&out));
        let (_dir, gif) = output_in_temp("f.gif");
        let Task::Animation { animation, .. } = task(&["a.ray", "--anim", "4", "-o", &gif]) else { panic!() };
        assert_eq!((animation.frames, animation.format), (1..=4, ImageFormat::Gif));
    }

    #[test]
    fn frames_an_animation_cannot_have_are_refused_before_any_work() {
        let (_dir, out) = output_in_temp("f.png");
        let past = job(&["a.ray", "--anim", "3", "--frames", "2..5", "-o", &out]);
        assert_eq!(past.err(), Some(JobError::Output("--frames 2..5 goes past the last frame, 3".into())));
        let (_dir, gif) = output_in_temp("f.gif");
        let one_file = job(&["a.ray", "--anim", "3", "--frames", "1..2", "-o", &gif]);
        assert!(matches!(one_file, Err(JobError::Output(message)) if message.starts_with("--frames writes numbered")));
    }

    #[test]
    fn outputs_are_checked_in_the_job_step() {
        let (_dir, jpeg) = output_in_temp("a.jpeg");
        assert!(matches!(job(&["a.ray", "-o", &jpeg]), Err(JobError::Output(message)) if message.contains("format")));
        let dir = tempfile::tempdir().expect("a temporary folder");
        let scene = dir.path().join("a.ray");
        std::fs::write(&scene, "").expect("a scene file");
        let scene = scene.display().to_string();
        for flags in [["-o", scene.as_str()], ["--export-pov", scene.as_str()]] {
            let itself = job(&[scene.as_str(), flags[0], flags[1]]);
            assert!(matches!(itself, Err(JobError::Output(m)) if m.contains("is the scene file itself")), "{flags:?}");
        }
    }

    #[test]
    fn check_explain_and_export_carry_what_they_need() {
        let Task::Check(scene) = task(&["--check", "--json", "--time", "3", "a.ray"]) else { panic!("a check") };
        assert_eq!(scene.diagnostics, DiagnosticFormat::JsonLines);
        assert_eq!(scene.picture.width, DEFAULTS.width);
        let explain = task(&["a.ray", "--explain", "3,4", "--json", "--reference", "--width", "10", "--height", "8"]);
        let Task::Explain { scene, options, pixel, json } = explain else { panic!("an explanation") };
        assert_eq!((pixel, json, options.samples, options.width), ((3, 4), true, 256, 10));
        assert_eq!(scene.diagnostics, DiagnosticFormat::Rendered);
        let Task::PovExport { depth, output, quiet, .. } = task(&["a.ray", "--depth", "3", "--export-pov", "-"]) else {
            panic!("an export")
        };
        assert_eq!((depth, output, quiet), (3, Destination::Stdout, false));
    }

    #[test]
    fn watch_writes_only_where_told() {
        let Task::Watch { output, no_preview, .. } = task(&["a.ray", "--watch", "--no-preview"]) else { panic!() };
        assert_eq!((output, no_preview), (None, true));
        let (_dir, out) = output_in_temp("w.png");
        let Task::Watch { output, .. } = task(&["a.ray", "--watch", "-o", &out]) else { panic!("a watch") };
        assert_eq!(output, Some(PathBuf::from(out)));
    }

    #[test]
    fn no_scene_or_dash_i_is_a_session_with_the_settings_given() {
        let Task::Session(options) = task(&["--width", "64", "--max-calls", "7", "--keep-going"]) else { panic!() };
        assert_eq!((options.settings.width, options.limits.max_call_depth, options.keep_going), (64, 7, true));
        assert_eq!(options.initial_file, None);
        let Task::Session(options) = task(&["-i", "a.ray", "--no-preview"]) else { panic!("a session") };
        assert_eq!((options.initial_file, options.no_preview), (Some("a.ray".into()), true));
        let piped = Job::resolve(&Cli::parse_from(["rayrepl", "--keep-going"]), false, false).expect("a job");
        assert!(matches!(piped.task, Task::Script(options) if options.keep_going));
        assert_eq!(job(&["--threads", "3"]).expect("a job").threads, 3);
        assert_eq!(job(&[]).expect("a job").threads, 0);
    }

    #[test]
    fn flags_that_do_not_go_together_are_a_misuse() {
        let cases: [(&[&str], &str); 6] = [
            (&["a.ray", "--json"], "--json is for --check"),
            (&["a.ray", "--fps", "10"], "--fps is for an animation: give --anim N too"),
            (&["--stats"], "--stats does nothing in a session (without a scene file, rayrepl starts a session)"),
            (&["-i", "a.ray", "--watch"], "--watch does nothing in a session (-i starts a session)"),
            (&["a.ray", "--explain", "8,0", "--width", "8"], "--explain 8,0 is outside the 8x600 image"),
            (&["a.ray", "--width", "8192", "--height", "8193"], "the most is 67108864"),
        ];
        for (args, said) in cases {
            let misuse = job(args).expect_err("a misuse");
            assert!(matches!(&misuse, JobError::Misuse(message) if message.contains(said)), "{args:?}: {misuse}");
        }
    }

    /// The job of `rayrepl`, `before`, then `flags` given as the table's tests give them.
    fn job_with(before: &[&str], flags: &[&Flag]) -> Result<Job, JobError> {
        let args: Vec<&str> = before.iter().copied().chain(flags.iter().flat_map(|flag| example(flag))).collect();
        job(&args)
    }

    /// The misuse `result` says, if it says one.
    fn misuse_of(result: Result<Job, JobError>) -> Option<String> {
        match result {
            Err(JobError::Misuse(message)) => Some(message),
            _ => None,
        }
    }

    #[test]
    fn each_flag_that_would_do_nothing_is_refused_in_the_words_of_the_table() {
        for flag in &FLAGS {
            let (name, alone) = (flag.name, misuse_of(job_with(&["a.ray"], &[flag])));
            match flag.needs {
                Needs::Nothing => assert_eq!(alone, None, "{name}"),
                Needs::OneOf { flags, words, .. } => {
                    assert_eq!(alone, Some(format!("{name} {words}")));
                    for other in flags.iter().map(|id| flag_with_id(id)) {
                        assert_eq!(misuse_of(job_with(&["a.ray"], &[flag, other])), None, "{name} {}", other.name);
                    }
                }
                Needs::NoneOf { flags, words } => {
                    assert_eq!(alone, None, "{name}");
                    for other in flags.iter().map(|id| flag_with_id(id)) {
                        let refused = misuse_of(job_with(&["a.ray"], &[flag, other]));
                        assert_eq!(refused, Some(format!("{name} {words}")), "{name} {}", other.name);
                    }
                }
            }
            let in_a_session = match (flag.in_a_session, flag.needs) {
                (InASession::DoesNothing { instead }, _) => {
                    let with_dash_i = format!("{name} does nothing in a session (-i starts a session){instead}");
                    assert_eq!(misuse_of(job_with(&["-i", "a.ray"], &[flag])), Some(with_dash_i));
                    Some(format!(
                        "{name} does nothing in a session (without a scene file, rayrepl starts a session){instead}"
                    ))
                }
                (InASession::NotRefused, Needs::OneOf { or_a_session: false, words, .. }) => {
                    Some(format!("{name} {words}"))
                }
                (InASession::NotRefused, _) => None,
            };
            assert_eq!(misuse_of(job_with(&[], &[flag])), in_a_session, "{name} in a session");
        }
    }

    #[test]
    fn allow_takes_check_names_and_all() {
        let cli = Cli::parse_from(["rayrepl", "--allow", "camera-inside,colours", "--allow", "no-light", "a.ray"]);
        let some = allowed(&cli);
        for check in Check::ALL {
            let expected = matches!(check, Check::CameraInside | Check::Colours | Check::NoLight);
            assert_eq!(some.contains(check), expected, "{check:?}");
        }
        let every = allowed(&Cli::parse_from(["rayrepl", "--allow", "all", "a.ray"]));
        assert!(Check::ALL.iter().all(|check| every.contains(*check)));
        let degrees = allowed(&Cli::parse_from(["rayrepl", "--allow", "degrees", "a.ray"]));
        assert!(degrees.contains(Check::Degrees) && !degrees.contains(Check::Colours));
        assert!(Cli::try_parse_from(["rayrepl", "--allow", "degree", "a.ray"]).is_err());
    }

    #[test]
    fn fmt_formats_files_or_standard_input_alone() {
        let formatting = |args: &[&str]| match task(args) {
            Task::Format(job) => job,
            other => panic!("{args:?}: {other:?}"),
        };
        let files = formatting(&["fmt", "--check", "a.ray", "b.ray"]);
        assert_eq!(files.input, Formatted::Files(vec![PathBuf::from("a.ray"), PathBuf::from("b.ray")]));
        assert!(files.check);
        assert_eq!(formatting(&["fmt", "-"]), FormattingJob { input: Formatted::Stdin, check: false });
        let misuse = job(&["fmt", "a.ray", "-"]).expect_err("a misuse");
        assert!(matches!(&misuse, JobError::Misuse(message) if message.contains("give it alone")), "{misuse}");
    }
}
