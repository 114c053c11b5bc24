//! The commands that make pictures: `:render`, `:save`, `:anim`, `:pick`
//! and `:preview`.

use std::path::{Path, PathBuf};

use crate::clock::Stopwatch;
use crate::explain::ExplainedScene;
use crate::output::{self, Content, FrameSink};
use crate::playback::AnimationOptions;
use crate::settings::FRAMES;

use super::cancel::cancel_flag;
use super::console::Console;
use super::outcome::{CommandError, CommandResult, Flow, parse_count, parse_size, usage};
use super::preview::{PreviewSize, mark_pixel};
use super::render_steps::{duration, explain_defaults, render_frames, render_scene, shown, write_failure};
use super::rendering::{Size, render_options};
use super::report::{counted, show_scene_warnings};
use super::shell::Shell;

pub(crate) fn render_command(shell: &mut Shell, arguments: &[String], console: &mut Console) -> CommandResult {
    let session = &mut shell.session;
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
    shell.last_picture = Some(image.clone());
    match shown(console) {
        Some(preview) => {
            preview.show(&image).map_err(|e| CommandError::Failed(format!("cannot show the image here: {e}")))?;
            console.say(format!("{size} in {}", duration(took)));
        }
        None => console.say(format!("rendered {size} in {} (previews are off)", duration(took))),
    }
    Ok(Flow::Continue)
}

pub(crate) fn preview_command(_shell: &mut Shell, arguments: &[String], console: &mut Console) -> CommandResult {
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
pub(crate) fn pick(shell: &mut Shell, arguments: &[String], console: &mut Console) -> CommandResult {
    let session = &shell.session;
    let [x, y] = arguments else {
        return Err(CommandError::Usage("give the pixel's X (from the left) and Y (from the top)".to_string()));
    };
    let Some(picture) = &shell.last_picture else {
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

pub(crate) fn save(shell: &mut Shell, arguments: &[String], console: &mut Console) -> CommandResult {
    let session = &mut shell.session;
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
    shell.last_picture = Some(image.clone());
    output::write_image_cancellable(&path, &image, cancel_flag(console.cancel)).map_err(write_failure)?;
    console.say(format!("saved {} ({size}, {})", path.display(), duration(took)));
    Ok(Flow::Continue)
}

pub(crate) fn anim(shell: &mut Shell, arguments: &[String], console: &mut Console) -> CommandResult {
    let session = &mut shell.session;
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
    let started = Stopwatch::start();
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

/// Checks that `path` can receive `content` before any work is done.
fn check_output(path: &Path, content: Content) -> Result<(), CommandError> {
    output::check_output(path, content).map(drop).map_err(|e| CommandError::Failed(e.to_string()))
}
