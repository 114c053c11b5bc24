//! The steps the commands that make pictures share: the note about defaults, rendering a still or an animation's frames with
//! progress and Ctrl-C, and how their failures read.

use std::sync::atomic::AtomicBool;
use std::time::Duration;

use image::RgbImage;

use crate::animation::{AnimationError, render_animation};
use crate::clock::Stopwatch;
use crate::lang::Diagnostic;
use crate::output::OutputError;
use crate::playback::Timeline;
use crate::render::{OutOfMemory, RenderControl};
use crate::scene::Scene;

use super::outcome::CommandError;
use super::outputs::FrontEnd;
use super::rendering::{RenderSettings, Size, render_image, render_options};
use super::report::{number, show_scene_warnings};
use super::state::Session;
use crate::pipeline::PictureError;
use crate::warned::Warned;

/// What every command that makes pictures of `size` (frames of an
/// animation if `animation`) shows before it renders: the note about the
/// defaults the scene falls back on, then the warnings about the scene not
/// shown yet.
pub(crate) fn notes_before_rendering(
    session: &Session,
    warned: &mut Warned,
    front: &mut dyn FrontEnd,
    size: Size,
    animation: bool,
) {
    explain_defaults(session, front);
    show_scene_warnings(session, warned, front, size, animation);
}

/// Prints one note about the defaults a render falls back on, and about
/// an empty or unlit scene.
fn explain_defaults(session: &Session, front: &mut dyn FrontEnd) {
    let scene = session.scene();
    let camera = format!("camera (distance {}, angle {})", number(scene.camera.distance), number(scene.camera.angle));
    let ambient = format!("ambient light ({})", number(scene.ambient));
    let set_camera = "set yours with `camera distance 12 angle 0.8 end`";
    match (session.has_camera(), session.has_ambient()) {
        (false, false) => front.note(format!("default {camera} and {ambient}; {set_camera}")),
        (false, true) => front.note(format!("default {camera}; {set_camera}")),
        (true, false) => front.note(format!("default {ambient}; set yours with `ambient 0.3`")),
        (true, true) => {}
    }
    if scene.all_primitives().next().is_none() {
        front.note("nothing has been put yet, so the picture is black (see `:help put`)");
    } else if scene.lights.is_empty() {
        front.note("no light yet, only the ambient light shows (see `:help light`)");
    }
}

/// Renders `scene` with the session's settings, with progress and Ctrl-C.
pub(crate) fn render_scene(
    scene: &Scene,
    size: Size,
    settings: &RenderSettings,
    front: &mut dyn FrontEnd,
) -> Result<(RgbImage, Duration), CommandError> {
    let started = Stopwatch::start();
    let total = size.width as usize * size.height as usize;
    front.flush();
    let tick = front.progress(total as u64, "rendering");
    let armed = front.cancel().map(|switch| switch.arm());
    let never = AtomicBool::new(false);
    let cancel = armed.as_ref().map_or(&never, |armed| armed.flag());
    let image = render_image(scene, size, settings, cancel, &*tick).map_err(render_failure)?;
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
    front: &mut dyn FrontEnd,
    sink: &mut dyn FnMut(usize, RgbImage) -> Result<(), CommandError>,
) -> Result<(), CommandError> {
    let timed = session.depends_on_time();
    let total = u64::from(frames) * u64::from(size.width) * u64::from(size.height);
    front.flush();
    let tick = front.progress(total, "animating");
    let armed = front.cancel().map(|switch| switch.arm());
    let control = RenderControl { progress: Some(&*tick), cancel: armed.as_ref().map(|armed| armed.flag()) };
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
        Err(AnimationError::Cancelled) => Err(render_failure(PictureError::Cancelled)),
        Err(AnimationError::OutOfMemory(error)) => Err(out_of_memory(error)),
    }
}

/// The memory a render needs cannot be had: the session goes on as it was.
pub(crate) fn out_of_memory(error: OutOfMemory) -> CommandError {
    CommandError::Failed(format!("{error}; the session is as it was"))
}

fn frame_failure(diagnostic: Diagnostic, frame: u32, time: f64) -> CommandError {
    let note = format!("while computing frame {frame}, with time = {}", number(time));
    CommandError::Program(Box::new(diagnostic.with_note(note)))
}

fn render_failure(error: PictureError) -> CommandError {
    match error {
        PictureError::Cancelled => CommandError::Cancelled("render cancelled; the session is as it was".to_string()),
        PictureError::OutOfMemory(error) => out_of_memory(error),
    }
}

/// A write that failed, or that Ctrl-C cancelled.
pub(crate) fn write_failure(error: OutputError) -> CommandError {
    match error {
        OutputError::Cancelled { .. } => CommandError::Cancelled(format!("{error}; the session is as it was")),
        error => CommandError::Failed(error.to_string()),
    }
}

/// "12 ms" or "1.3 s".
pub(crate) fn duration(took: Duration) -> String {
    if took < Duration::from_secs(1) {
        format!("{} ms", took.as_millis())
    } else {
        format!("{:.1} s", took.as_secs_f64())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_read_plainly() {
        assert_eq!(duration(Duration::from_millis(12)), "12 ms");
        assert_eq!(duration(Duration::from_millis(1340)), "1.3 s");
    }
}
