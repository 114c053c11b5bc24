//! The commands that make pictures: `:render`, `:save`, `:anim`, `:pick`
//! and `:preview`.

use std::path::{Path, PathBuf};

use crate::clock::Stopwatch;
use crate::explain::ExplainedScene;
use crate::output::{self, Content, FrameSink, ImageFormat};
use crate::playback::AnimationOptions;
use crate::render::reserve_for;
use crate::settings::FRAMES;

use super::outcome::{CommandError, CommandResult, Flow, parse_count, parse_size, usage};
use super::outputs::{FrontEnd, Output, Picture, PixelExplanation, PreviewSize};
use super::render_steps::{
    duration, notes_before_rendering, out_of_memory, render_frames, render_scene, write_failure,
};
use super::rendering::{Size, render_options};
use super::report::counted;
use super::shell::Shell;
use super::state::Session;
use crate::process::cancel::cancel_flag;

pub(crate) fn render_command(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    let configured = Size { width: session.settings().width, height: session.settings().height };
    let shown = front.picture_size(configured);
    let size = match arguments {
        [] => shown.unwrap_or(configured),
        [width, height] => parse_size(width, height)?,
        _ => {
            return Err(CommandError::Usage("give both a width and a height, or neither".to_string()));
        }
    };
    notes_before_rendering(session, &mut shell.warned, front, size, false);
    let (image, took) = render_scene(session.scene(), size, session.settings(), front)?;
    shell.last_picture = Some(image.clone());
    if shown.is_some() {
        show_picture(front, Picture { image, marked: None, saved_to: None })?;
        front.say(format!("{size} in {}", duration(took)));
    } else {
        front.say(format!("rendered {size} in {} (previews are off)", duration(took)));
    }
    Ok(Flow::Continue)
}

pub(crate) fn preview_command(_shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let Some(preview) = front.preview_size() else {
        return Err(CommandError::Failed(
            "previews need a terminal on standard output (and no `--no-preview`)".to_string(),
        ));
    };
    match arguments {
        [] => {}
        [name] => {
            *preview = PreviewSize::parse(name)
                .ok_or_else(|| CommandError::Usage(format!("`{name}`: give `fit`, `small` or `off`")))?;
        }
        _ => return Err(CommandError::Usage("give one of `fit`, `small` or `off`".to_string())),
    }
    let size = preview.name();
    front.say(format!("preview = {size}"));
    Ok(Flow::Continue)
}

/// `:pick X Y`: why pixel (X, Y) of the last picture has its colour, the
/// pixel marked on the picture.
pub(crate) fn pick(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
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
    reserve_for(interpreter.scene(), &options).map_err(out_of_memory)?;
    let explanation = ExplainedScene::new(&interpreter, session.sources(), &options).explain(x, y);
    if front.picture_size(size).is_some() {
        show_picture(front, Picture { image: picture.clone(), marked: Some((x, y)), saved_to: None })?;
    }
    let changed = explanation.paths.rgb != picture.get_pixel(x, y).0;
    let text = explanation.to_string().trim_end().to_string();
    let _ = front.present(Output::Explanation(Box::new(PixelExplanation { text, json: explanation.to_json() })));
    if changed {
        front.note("the scene or the settings changed since that picture: this is the pixel as it is now");
    }
    Ok(Flow::Continue)
}

pub(crate) fn save(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
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
    not_a_file_read(session, &path, None)?;
    check_output(&path, Content::Still)?;
    notes_before_rendering(session, &mut shell.warned, front, size, false);
    let (image, took) = render_scene(session.scene(), size, session.settings(), front)?;
    shell.last_picture = Some(image.clone());
    output::write_image_cancellable(&path, &image, cancel_flag(front.cancel())).map_err(write_failure)?;
    let _ = front.present(Output::Picture(Picture { image, marked: None, saved_to: Some(path.clone()) }));
    front.say(format!("saved {} ({size}, {})", path.display(), duration(took)));
    Ok(Flow::Continue)
}

pub(crate) fn anim(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    let [frames, file, options @ ..] = arguments else {
        return Err(CommandError::Usage("give the number of frames and a file name".to_string()));
    };
    let frames = parse_count(frames, &FRAMES)?;
    let animation = AnimationOptions::parse_words(options).map_err(usage)?;
    animation.timeline.check(1..=frames).map_err(usage)?;
    let path = PathBuf::from(file);
    not_a_file_read(session, &path, None)?;
    let format = output::check_animation_output(&path, &animation).map_err(|e| CommandError::Failed(e.to_string()))?;
    not_a_file_read(session, &path, Some((format, frames)))?;
    let size = Size { width: session.settings().width, height: session.settings().height };
    notes_before_rendering(session, &mut shell.warned, front, size, true);
    let started = Stopwatch::start();
    let mut sink = FrameSink::new(&path, format, frames as usize, animation.playback, cancel_flag(front.cancel()));
    let rendered = render_frames(session, frames, animation.timeline, size, front, &mut |frame, image| {
        sink.add(frame, image).map_err(write_failure)
    });
    if let Err(error) = rendered {
        // Numbered frames already written stay: say which (an unfinished GIF is removed).
        if !sink.written().is_empty() {
            front.say(format!("{} written before it stopped", output::describe_files(sink.written())));
        }
        return Err(error);
    }
    let written = sink.finish().map_err(write_failure)?;
    if let [file] = written.as_slice() {
        let _ = front.present(Output::AnimationFile(file.clone()));
    }
    let names = output::describe_files(&written);
    front.say(format!(
        "wrote {names} ({} of {size}, {})",
        counted(frames as usize, "frame"),
        duration(started.elapsed())
    ));
    Ok(Flow::Continue)
}

/// Shows `picture`, or fails saying why it cannot be shown here.
fn show_picture(front: &mut dyn FrontEnd, picture: Picture) -> Result<(), CommandError> {
    front
        .present(Output::Picture(picture))
        .map_err(|e| CommandError::Failed(format!("cannot show the image here: {e}")))
}

/// Refuses an output that would write over a file the session read its
/// inputs from (by any path or link), as the command line refuses the scene
/// file: the file `path` names, or, with `numbered` (a format and the
/// number of frames), one of the numbered images named after it. (`:write`
/// writes the session's scene file over one on purpose.)
fn not_a_file_read(session: &Session, path: &Path, numbered: Option<(ImageFormat, u32)>) -> Result<(), CommandError> {
    for read in session.files_read() {
        let over = match numbered {
            None => output::same_file(path, read).then(|| (path.to_owned(), String::new())),
            Some((format, frames)) => output::frame_over(read, path, format, 1..=frames, frames)
                .map(|(frame, name)| (name, format!(", frame {frame} of the animation,"))),
        };
        if let Some((name, which)) = over {
            return Err(CommandError::Failed(format!(
                "`{}`{which} is the file loaded into the session (`:load {}`); give another output name",
                name.display(),
                read.display()
            )));
        }
    }
    Ok(())
}

/// Checks that `path` can receive `content` before any work is done.
fn check_output(path: &Path, content: Content) -> Result<(), CommandError> {
    output::check_output(path, content).map(drop).map_err(|e| CommandError::Failed(e.to_string()))
}
