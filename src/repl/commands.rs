//! The session's commands (`:render`, `:time`, `:save`, ...), one function each.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use image::RgbImage;

use crate::explain::ExplainedScene;
use crate::lang::Diagnostic;
use crate::lang::suggest::closest;
use crate::output::{self, Content, FrameSink, OutputError};
use crate::progress::Progress;
use crate::render::{RenderControl, SceneGeometry};
use crate::scene::Scene;
use crate::settings::{DEPTH, FRAMES, HEIGHT, Limit, SAMPLES, WIDTH, check_size, parse_time};

use super::cancel::cancel_flag;
use super::console::Console;
use super::help;
use super::inspect;
use super::lessons;
pub(crate) use super::outcome::{CommandError, CommandResult, Flow};
use super::play;
use super::preview::{Preview, PreviewSize, mark_pixel};
use super::reload;
use super::rendering::{RenderError, RenderSettings, Size, render_image, render_options};
use super::report::{self, counted, number};
use super::session::{Session, Undone};
use super::write_back;
use super::{show_printed, show_scene_warnings};
use crate::animation::{AnimationError, render_animation};
use crate::playback::{AnimationOptions, Timeline};

/// A command: its name, its usage line and the function that runs it.
pub(crate) struct CommandSpec {
    /// The name, colon included.
    pub name: &'static str,
    /// How to call it.
    pub usage: &'static str,
    run: fn(&mut Session, &[String], &mut Console) -> CommandResult,
}

/// Every command, in the order `:help` lists them.
pub(crate) const COMMANDS: &[CommandSpec] = &[
    CommandSpec { name: ":help", usage: ":help [NAME]", run: help_command },
    CommandSpec { name: ":lesson", usage: ":lesson [NUMBER|stop]", run: lessons::lesson },
    CommandSpec { name: ":render", usage: ":render [WIDTH HEIGHT]", run: render },
    CommandSpec { name: ":save", usage: ":save FILE [WIDTH HEIGHT]", run: save },
    CommandSpec {
        name: ":anim",
        usage: ":anim FRAMES FILE [--fps F] [--loop N|forever] [--time-start A] [--time-step S] [--apng]",
        run: anim,
    },
    CommandSpec { name: ":play", usage: ":play [FRAMES [FPS]]", run: play::play },
    CommandSpec { name: ":time", usage: ":time [NUMBER]", run: time },
    CommandSpec { name: ":size", usage: ":size [WIDTH HEIGHT]", run: size },
    CommandSpec { name: ":depth", usage: ":depth [REFLECTIONS]", run: depth },
    CommandSpec { name: ":samples", usage: ":samples [RAYS PER PIXEL]", run: samples },
    CommandSpec { name: ":preview", usage: ":preview [fit|small|off]", run: preview },
    CommandSpec { name: ":pick", usage: ":pick X Y", run: pick },
    CommandSpec { name: ":limits", usage: ":limits [calls N] [primitives N]", run: limits },
    CommandSpec { name: ":load", usage: ":load FILE", run: load },
    CommandSpec { name: ":reload", usage: ":reload", run: reload::reload },
    CommandSpec { name: ":watch", usage: ":watch FILE", run: watch },
    CommandSpec { name: ":write", usage: ":write FILE.ray", run: write_back::write },
    CommandSpec { name: ":env", usage: ":env", run: env },
    CommandSpec { name: ":scene", usage: ":scene", run: scene },
    CommandSpec { name: ":show", usage: ":show NAME", run: inspect::show },
    CommandSpec { name: ":list", usage: ":list", run: inspect::list },
    CommandSpec { name: ":history", usage: ":history [LINES]", run: inspect::history },
    CommandSpec { name: ":undo", usage: ":undo", run: undo },
    CommandSpec { name: ":reset", usage: ":reset", run: reset },
    CommandSpec { name: ":quit", usage: ":quit", run: quit },
];

/// Other names for commands.
const ALIASES: &[(&str, &str)] = &[(":q", ":quit"), (":exit", ":quit"), (":h", ":help"), (":?", ":help")];

/// Whether `line` is a command rather than program text.
pub(crate) fn is_command(line: &str) -> bool {
    line.trim_start().starts_with(':')
}

/// Whether the command on `line` writes image files (`:save`, `:anim`).
pub(crate) fn writes_files(line: &str) -> bool {
    matches!(line.split_whitespace().next(), Some(":save" | ":anim"))
}

/// Runs the command on `line`, reporting any failure on the console.
/// Returns `Err(())` if it failed, so scripts can count errors.
pub(crate) fn execute(session: &mut Session, line: &str, console: &mut Console) -> Result<Flow, ()> {
    let result =
        split_arguments(line).map_err(CommandError::Failed).and_then(|words| dispatch(session, &words, console));
    show_printed(session, console);
    match result {
        Ok(flow) => Ok(flow),
        Err(error) => {
            error.report(session, console);
            Err(())
        }
    }
}

fn dispatch(session: &mut Session, words: &[String], console: &mut Console) -> CommandResult {
    let Some((name, arguments)) = words.split_first().filter(|(name, _)| name.as_str() != ":") else {
        return Err(CommandError::Failed("type a command name after `:`, for example `:help`".to_string()));
    };
    let name = ALIASES.iter().find(|(alias, _)| alias == name).map_or(name.as_str(), |(_, real)| real);
    let Some(command) = COMMANDS.iter().find(|command| command.name == name) else {
        return Err(unknown_command(name));
    };
    (command.run)(session, arguments, console).map_err(|error| match error {
        CommandError::Usage(problem) => CommandError::Usage(format!("{problem}\nusage: {}", command.usage)),
        other => other,
    })
}

fn unknown_command(name: &str) -> CommandError {
    let names = COMMANDS.iter().map(|c| c.name).chain(ALIASES.iter().map(|(alias, _)| *alias));
    let mut message = format!("there is no command `{name}`");
    if let Some(close) = closest(name, names) {
        message.push_str(&format!("; did you mean `{close}`?"));
    }
    message.push_str("\n`:help` lists the commands");
    CommandError::Failed(message)
}

/// Splits a command line into words. Double quotes keep spaces in a word,
/// and (except on Windows, where it separates folders) a backslash keeps the
/// next character as it is, as file name completion writes `my\ scene.ray`.
pub(crate) fn split_arguments(line: &str) -> Result<Vec<String>, String> {
    let mut words = Vec::new();
    let mut word: Option<String> = None;
    let mut quoted = false;
    let mut chars = line.trim().chars();
    while let Some(c) = chars.next() {
        match c {
            '"' => {
                quoted = !quoted;
                word.get_or_insert_with(String::new);
            }
            '\\' if cfg!(not(windows)) && !quoted => {
                let escaped = chars.next().unwrap_or('\\');
                word.get_or_insert_with(String::new).push(escaped);
            }
            c if c.is_whitespace() && !quoted => words.extend(word.take()),
            c => word.get_or_insert_with(String::new).push(c),
        }
    }
    if quoted {
        return Err("a `\"` is not closed".to_string());
    }
    words.extend(word);
    Ok(words)
}

// ---------------------------------------------------------------- arguments

fn no_arguments(arguments: &[String]) -> Result<(), CommandError> {
    match arguments {
        [] => Ok(()),
        _ => Err(CommandError::Usage("this command takes no arguments".to_string())),
    }
}

/// A whole-number setting from `text`, within `limit`.
pub(crate) fn parse_count(text: &str, limit: &'static Limit) -> Result<u32, CommandError> {
    limit.parse(text).map_err(usage)
}

fn parse_size(width: &str, height: &str) -> Result<Size, CommandError> {
    let size = Size { width: parse_count(width, &WIDTH)?, height: parse_count(height, &HEIGHT)? };
    check_size(size.width, size.height).map_err(usage)?;
    Ok(size)
}

fn usage(error: impl std::fmt::Display) -> CommandError {
    CommandError::Usage(error.to_string())
}

/// Checks that `path` can receive `content` before any work is done.
fn check_output(path: &Path, content: Content) -> Result<(), CommandError> {
    output::check_output(path, content).map(drop).map_err(|e| CommandError::Failed(e.to_string()))
}

// ---------------------------------------------------------------- commands

fn help_command(_session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    match arguments {
        [] => console.say(help::overview()),
        [name] => match help::find(name) {
            Some(topic) => console.say(topic.text),
            None => {
                let hint = help::suggestion(name).map(|s| format!("; did you mean `{s}`?")).unwrap_or_default();
                return Err(CommandError::Failed(format!(
                    "no help about `{name}`{hint}\n`:help` lists what it explains"
                )));
            }
        },
        _ => {
            return Err(CommandError::Usage("ask about one name at a time".to_string()));
        }
    }
    Ok(Flow::Continue)
}

fn render(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    let configured = Size { width: session.settings().width, height: session.settings().height };
    let size = match arguments {
        [] => shown(console).map_or(configured, |preview| preview.render_size(configured)),
        [width, height] => parse_size(width, height)?,
        _ => {
            return Err(CommandError::Usage("give both a width and a height, or neither".to_string()));
        }
    };
    explain_defaults(session, console);
    show_scene_warnings(session, console, size, false);
    let (image, took) = render_scene(session.scene(), size, session.settings(), console)?;
    session.remember_picture(&image);
    match shown(console) {
        Some(preview) => {
            preview.show(&image).map_err(|e| CommandError::Failed(format!("cannot show the image here: {e}")))?;
            console.say(format!("{size} in {}", duration(took)));
        }
        None => console.say(format!("rendered {size} in {} (previews are off)", duration(took))),
    }
    Ok(Flow::Continue)
}

/// The previewer, unless previews are off.
pub(crate) fn shown(console: &Console) -> Option<Preview> {
    console.preview.filter(|preview| preview.size != PreviewSize::Off)
}

fn preview(_session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    let Some(preview) = console.preview.as_mut() else {
        return Err(CommandError::Failed(
            "previews need a terminal on standard output (and no `--no-preview`)".to_string(),
        ));
    };
    match arguments {
        [] => {}
        [name] => {
            preview.size = PreviewSize::parse(name)
                .ok_or_else(|| CommandError::Usage(format!("`{name}`: give `fit`, `small` or `off`")))?;
        }
        _ => return Err(CommandError::Usage("give one of `fit`, `small` or `off`".to_string())),
    }
    let size = preview.size.name();
    console.say(format!("preview = {size}"));
    Ok(Flow::Continue)
}

/// `:pick X Y`: why pixel (X, Y) of the last picture has its colour, the
/// pixel marked on the picture.
fn pick(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    let [x, y] = arguments else {
        return Err(CommandError::Usage("give the pixel's X (from the left) and Y (from the top)".to_string()));
    };
    let Some(picture) = session.last_picture() else {
        return Err(CommandError::Failed("no picture yet: `:render` first, then pick one of its pixels".to_string()));
    };
    let size = Size { width: picture.width(), height: picture.height() };
    let coordinate = |text: &str, limit: u32, axis: &str| match text.parse::<u32>() {
        Ok(value) if value < limit => Ok(value),
        _ => Err(CommandError::Usage(format!(
            "`{text}`: {axis} is a whole number from 0 to {} in the last picture ({size})",
            limit - 1
        ))),
    };
    let (x, y) = (coordinate(x, size.width, "X")?, coordinate(y, size.height, "Y")?);
    let interpreter = session.replay_recording_calls().map_err(|d| CommandError::Program(Box::new(d)))?;
    let options = render_options(size, session.settings());
    let explanation = ExplainedScene::new(&interpreter, session.sources(), &options).explain(x, y);
    let picture = session.last_picture().expect("checked above");
    if let Some(preview) = shown(console) {
        let marked = mark_pixel(picture, x, y);
        preview.show(&marked).map_err(|e| CommandError::Failed(format!("cannot show the image here: {e}")))?;
    }
    let changed = explanation.paths.rgb != picture.get_pixel(x, y).0;
    console.say(explanation.to_string().trim_end());
    if changed {
        console.note("the scene or the settings changed since that picture: this is the pixel as it is now");
    }
    Ok(Flow::Continue)
}

fn save(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    let (file, size) = match arguments {
        [file] => (file, Size { width: session.settings().width, height: session.settings().height }),
        [file, width, height] => (file, parse_size(width, height)?),
        [] => {
            return Err(CommandError::Usage("give the name of the file to write".to_string()));
        }
        _ => {
            return Err(CommandError::Usage("give a file name, then optionally a width and a height".to_string()));
        }
    };
    let path = PathBuf::from(file);
    check_output(&path, Content::Still)?;
    explain_defaults(session, console);
    show_scene_warnings(session, console, size, false);
    let (image, took) = render_scene(session.scene(), size, session.settings(), console)?;
    session.remember_picture(&image);
    output::write_image_cancellable(&path, &image, cancel_flag(console.cancel)).map_err(write_failure)?;
    console.say(format!("saved {} ({size}, {})", path.display(), duration(took)));
    Ok(Flow::Continue)
}

fn anim(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    let [frames, file, options @ ..] = arguments else {
        return Err(CommandError::Usage("give the number of frames and a file name".to_string()));
    };
    let frames = parse_count(frames, &FRAMES)?;
    let animation = AnimationOptions::parse_words(options).map_err(usage)?;
    let path = PathBuf::from(file);
    let format = output::check_animation_output(&path, &animation).map_err(|e| CommandError::Failed(e.to_string()))?;
    explain_defaults(session, console);
    let size = Size { width: session.settings().width, height: session.settings().height };
    show_scene_warnings(session, console, size, true);
    let started = Instant::now();
    let mut sink = FrameSink::new(&path, format, frames as usize, animation.playback, cancel_flag(console.cancel));
    let rendered = render_frames(session, frames, animation.timeline, size, console, &mut |frame, image| {
        sink.add(frame, image).map_err(write_failure)
    });
    if let Err(error) = rendered {
        // Numbered frames already written stay: say which (an unfinished GIF is removed).
        if !sink.written().is_empty() {
            console.say(format!("{} written before it stopped", output::describe_files(sink.written())));
        }
        return Err(error);
    }
    let written = sink.finish().map_err(write_failure)?;
    let names = output::describe_files(&written);
    console.say(format!(
        "wrote {names} ({} of {size}, {})",
        counted(frames as usize, "frame"),
        duration(started.elapsed())
    ));
    Ok(Flow::Continue)
}

fn time(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    let [value] = arguments else {
        if arguments.is_empty() {
            console.say(format!("time = {}", number(session.settings().time)));
            return Ok(Flow::Continue);
        }
        return Err(CommandError::Usage("give one number".to_string()));
    };
    let value = parse_time(value).map_err(usage)?;
    let previous = session.settings().time;
    match session.set_time(value) {
        Ok(false) => console.say(format!("time = {}", number(value))),
        Ok(true) => console.say(format!("time = {} (the scene was computed again)", number(value))),
        Err(diagnostic) => {
            console.diagnostic(&diagnostic, session.sources());
            return Err(CommandError::Failed(format!(
                "at time {} an earlier input fails, so time stays {}",
                number(value),
                number(previous)
            )));
        }
    }
    Ok(Flow::Continue)
}

fn size(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    match arguments {
        [] => {}
        [width, height] => {
            let size = parse_size(width, height)?;
            session.set_size(size.width, size.height);
        }
        _ => {
            return Err(CommandError::Usage("give a width and a height in pixels".to_string()));
        }
    }
    let settings = session.settings();
    console.say(format!("size = {}", Size { width: settings.width, height: settings.height }));
    Ok(Flow::Continue)
}

fn depth(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    match arguments {
        [] => {}
        [value] => session.set_depth(parse_count(value, &DEPTH)?),
        _ => return Err(CommandError::Usage("give one whole number".to_string())),
    }
    console.say(format!("depth = {}", session.settings().depth));
    Ok(Flow::Continue)
}

fn samples(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    match arguments {
        [] => {}
        [value] => session.set_samples(parse_count(value, &SAMPLES)?),
        _ => return Err(CommandError::Usage("give one whole number".to_string())),
    }
    console.say(format!("samples = {}", session.settings().samples));
    Ok(Flow::Continue)
}

fn limits(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    let mut limits = session.limits();
    for pair in arguments.chunks(2) {
        let [name, value] = pair else {
            return Err(CommandError::Usage(format!("give a number after `{}`", pair[0])));
        };
        let value = value.parse::<usize>().ok().filter(|n| *n > 0);
        let value = value.ok_or_else(|| CommandError::Usage(format!("`{name}` takes a whole number above 0")))?;
        match name.as_str() {
            "calls" => limits.max_call_depth = value,
            "primitives" => limits.max_primitives = value,
            _ => return Err(CommandError::Usage(format!("there is no limit `{name}`: `calls` or `primitives`"))),
        }
    }
    session.set_limits(limits).map_err(|error| CommandError::Program(Box::new(error)))?;
    console.say(format!(
        "calls = {} (deepest chain of procedure calls), primitives = {}",
        limits.max_call_depth, limits.max_primitives
    ));
    Ok(Flow::Continue)
}

fn load(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    let [file] = arguments else {
        let problem = if arguments.is_empty() {
            "give the file to load"
        } else {
            "give one file (put quotes around a name with spaces)"
        };
        return Err(CommandError::Usage(problem.to_string()));
    };
    load_file(session, Path::new(file), console)
}

/// Runs the file at `path` into the session, reporting any failure on the
/// console; `Err(())` if it failed (the session is then unchanged).
pub(crate) fn load_reporting(session: &mut Session, path: &Path, console: &mut Console) -> Result<(), ()> {
    let loaded = load_file(session, path, console);
    show_printed(session, console);
    loaded.map(|_| ()).map_err(|error| error.report(session, console))
}

/// Runs the file at `path` into the session, as one input.
fn load_file(session: &mut Session, path: &Path, console: &mut Console) -> CommandResult {
    let text = reload::read(path)?;
    let accepted = session.load(path, &text).map_err(|d| CommandError::Program(Box::new(d)))?;
    for warning in &accepted.warnings {
        console.diagnostic(warning, session.sources());
    }
    console.say(format!("loaded {}", path.display()));
    report::confirm(&accepted, session, console);
    Ok(Flow::Continue)
}

/// `:watch FILE`, rendering each version as `:render` does.
fn watch(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    reload::watch(session, arguments, console, render)
}

fn env(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    no_arguments(arguments)?;
    let numbers: Vec<String> =
        session.numbers().iter().map(|(name, value)| format!("{name} = {}", number(*value))).collect();
    let objects: Vec<String> = session.objects().iter().map(|(name, what)| format!("{name} ({what})")).collect();
    let procedures: Vec<String> =
        session.procedures().iter().map(|(name, params)| format!("{name}({})", params.join(", "))).collect();
    console.say(format!("numbers:    {}", numbers.join(", ")));
    let no_objects = format!("none yet: `object {} = sphere ... end` names one", free_name(session, "ball"));
    console.say(format!("objects:    {}", or_none(&objects, &no_objects)));
    let no_procedures = "none yet: see `:help proc`";
    console.say(format!("procedures: {}", or_none(&procedures, no_procedures)));
    Ok(Flow::Continue)
}

/// `base`, or `base2`, `base3`...: the first that names nothing yet, so an
/// example never suggests redefining a number or a procedure.
fn free_name(session: &Session, base: &str) -> String {
    let taken = |name: &str| {
        session.numbers().iter().any(|(n, _)| &**n == name) || session.procedures().iter().any(|(n, _)| &**n == name)
    };
    let mut candidates = std::iter::once(base.to_string()).chain((2..).map(|n| format!("{base}{n}")));
    candidates.find(|name| !taken(name)).unwrap_or_default()
}

fn or_none(items: &[String], none: &str) -> String {
    if items.is_empty() { none.to_string() } else { items.join(", ") }
}

fn scene(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    no_arguments(arguments)?;
    let scene = session.scene();
    let default = |given: bool| {
        if given { "" } else { " (default: none given yet)" }
    };
    console.say(format!(
        "camera:   distance {}, angle {}{}",
        number(scene.camera.distance),
        number(scene.camera.angle),
        default(session.has_camera())
    ));
    console.say(format!("ambient:  {}{}", number(scene.ambient), default(session.has_ambient())));
    console.say(format!("lights:   {}", scene.lights.len()));
    for (index, light) in scene.lights.iter().enumerate() {
        let d = light.direction;
        console.say(format!(
            "  {}. towards ({}, {}, {}), intensity {}",
            index + 1,
            number(d.x),
            number(d.y),
            number(d.z),
            number(light.intensity)
        ));
    }
    let counts = scene.counts();
    let mut objects = format!(
        "objects:  {} ({}, {}, {})",
        report::objects(&counts),
        counted(counts.spheres, "sphere"),
        counted(counts.planes, "plane"),
        counted(counts.boxes, "box")
    );
    if !scene.timed_primitives.is_empty() {
        objects.push_str(&format!(", {} depending on time", scene.timed_primitives.len()));
    }
    console.say(objects);
    let s = session.settings();
    console.say(format!(
        "settings: time {}, size {}, depth {}, samples {}",
        number(s.time),
        Size { width: s.width, height: s.height },
        s.depth,
        s.samples
    ));
    Ok(Flow::Continue)
}

fn undo(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    no_arguments(arguments)?;
    match session.undo().map_err(|d| CommandError::Program(Box::new(d)))? {
        Undone::Nothing => console.say("nothing to undo"),
        Undone::Input(text) => console.say(format!("took back: {}", first_line(&text))),
        Undone::Reset(count) => console.say(format!("took back the :reset ({} back)", counted(count, "input"))),
        Undone::Reload(path) => console.say(format!("took back the :reload of {}", path.display())),
    }
    console.say(format!("{} in the scene", counted(report::objects(&session.counts()), "object")));
    Ok(Flow::Continue)
}

fn reset(session: &mut Session, arguments: &[String], console: &mut Console) -> CommandResult {
    no_arguments(arguments)?;
    session.reset();
    console.say("the session is empty again (`:undo` brings it all back)");
    Ok(Flow::Continue)
}

fn quit(_session: &mut Session, arguments: &[String], _console: &mut Console) -> CommandResult {
    no_arguments(arguments)?;
    Ok(Flow::Quit)
}

// ---------------------------------------------------------------- rendering

/// Prints one note about the defaults a render falls back on, and about
/// an empty or unlit scene.
pub(crate) fn explain_defaults(session: &Session, console: &mut Console) {
    let scene = session.scene();
    let camera = format!("camera (distance {}, angle {})", number(scene.camera.distance), number(scene.camera.angle));
    let ambient = format!("ambient light ({})", number(scene.ambient));
    let set_camera = "set yours with `camera distance 12 angle 0.8 end`";
    match (session.has_camera(), session.has_ambient()) {
        (false, false) => console.note(format!("default {camera} and {ambient}; {set_camera}")),
        (false, true) => console.note(format!("default {camera}; {set_camera}")),
        (true, false) => console.note(format!("default {ambient}; set yours with `ambient 0.3`")),
        (true, true) => {}
    }
    if scene.all_primitives().next().is_none() {
        console.note("nothing has been put yet, so the picture is black (see `:help put`)");
    } else if scene.lights.is_empty() {
        console.note("no light yet, only the ambient light shows (see `:help light`)");
    }
}

/// Renders `scene` with the session's settings, with progress and Ctrl-C.
fn render_scene(
    scene: &Scene,
    size: Size,
    settings: &RenderSettings,
    console: &Console,
) -> Result<(RgbImage, Duration), CommandError> {
    let started = Instant::now();
    let total = size.width as usize * size.height as usize;
    let progress = Progress::in_session(total as u64, "rendering", console.progress);
    let armed = console.cancel.map(|switch| switch.arm());
    let never = AtomicBool::new(false);
    let cancel = armed.as_ref().map_or(&never, |armed| armed.flag());
    let tick = |pixels: u64| progress.advance(pixels);
    let image =
        render_image(scene, &SceneGeometry::new(scene), size, settings, cancel, &tick).map_err(render_failure)?;
    Ok((image, started.elapsed()))
}

/// Renders frames 1..=`frames` of the animation, frame k at the time
/// `timeline` gives it, and hands each to `sink` with its number (see
/// [`render_animation`] for what is computed once and what per frame).
pub(crate) fn render_frames(
    session: &Session,
    frames: u32,
    timeline: Timeline,
    size: Size,
    console: &Console,
    sink: &mut dyn FnMut(usize, RgbImage) -> Result<(), CommandError>,
) -> Result<(), CommandError> {
    let timed = session.depends_on_time();
    let total = u64::from(frames) * u64::from(size.width) * u64::from(size.height);
    let progress = Progress::in_session(total, "animating", console.progress);
    let armed = console.cancel.map(|switch| switch.arm());
    let tick = |pixels: u64| progress.advance(pixels);
    let control = RenderControl { progress: Some(&tick), cancel: armed.as_ref().map(|armed| armed.flag()) };
    let evaluate = |frame: u32, skip_static: bool| {
        if !timed {
            // Nothing reads `time`: the session's scene is every frame.
            return Ok(session.scene().clone());
        }
        let time = timeline.time_of(frame);
        let replayed = session.replay_at(time, skip_static);
        replayed.map(|interpreter| interpreter.into_scene()).map_err(|d| frame_failure(d, frame, time))
    };
    let options = render_options(size, session.settings());
    let sink = |frame: u32, image: RgbImage| sink(frame as usize, image);
    match render_animation(1..=frames, evaluate, &options, &control, sink) {
        Ok(_) => Ok(()),
        Err(AnimationError::Failed(error)) => Err(error),
        Err(AnimationError::Cancelled) => Err(render_failure(RenderError::Cancelled)),
    }
}

fn frame_failure(diagnostic: Diagnostic, frame: u32, time: f64) -> CommandError {
    let note = format!("while computing frame {frame}, with time = {}", number(time));
    CommandError::Program(Box::new(diagnostic.with_note(note)))
}

fn render_failure(error: RenderError) -> CommandError {
    match error {
        RenderError::Cancelled => CommandError::Cancelled("render cancelled; the session is as it was".to_string()),
    }
}

/// A write that failed, or that Ctrl-C cancelled.
pub(super) fn write_failure(error: OutputError) -> CommandError {
    match error {
        OutputError::Cancelled { .. } => CommandError::Cancelled(format!("{error}; the session is as it was")),
        error => CommandError::Failed(error.to_string()),
    }
}

/// "12 ms" or "1.3 s".
fn duration(took: Duration) -> String {
    if took < Duration::from_secs(1) {
        format!("{} ms", took.as_millis())
    } else {
        format!("{:.1} s", took.as_secs_f64())
    }
}

fn first_line(text: &str) -> String {
    let mut lines = text.lines().filter(|line| !line.trim().is_empty());
    let first = lines.next().unwrap_or("").trim().to_string();
    if lines.next().is_some() { format!("{first} ...") } else { first }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arguments_split_on_spaces_and_keep_quoted_ones() {
        assert_eq!(split_arguments(" :save  a.png 10 20 ").unwrap(), vec![":save", "a.png", "10", "20"]);
        assert_eq!(split_arguments(":load \"my scene.ray\"").unwrap(), vec![":load", "my scene.ray"]);
        assert_eq!(split_arguments(":load \"\"").unwrap(), vec![":load", ""]);
        assert!(split_arguments(":load \"oops").is_err());
        if cfg!(not(windows)) {
            assert_eq!(split_arguments(r":load my\ scene.ray").unwrap(), vec![":load", "my scene.ray"]);
        }
    }

    #[test]
    fn counts_and_sizes_are_checked() {
        assert_eq!(parse_count("5", &DEPTH).ok(), Some(5));
        assert!(parse_count("-1", &DEPTH).is_err());
        assert!(parse_count("1001", &DEPTH).is_err());
        assert!(parse_count("x", &DEPTH).is_err());
        assert!(parse_size("0", "10").is_err());
        assert!(parse_size("65535", "65535").is_err());
    }

    #[test]
    fn durations_read_plainly() {
        assert_eq!(duration(Duration::from_millis(12)), "12 ms");
        assert_eq!(duration(Duration::from_millis(1340)), "1.3 s");
        assert_eq!(first_line("\nput sphere\n  center"), "put sphere ...");
    }
}
