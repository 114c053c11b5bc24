//! `:play [FRAMES] [FPS]`: the animation of the session's scene played in
//! the terminal. The frames are rendered once at the preview's size (by the
//! same machinery as `:anim`), then drawn again and again in place until a
//! key is pressed (Ctrl-C included: the terminal is in raw mode meanwhile).

use std::io::Write;
use std::time::Duration;

use crossterm::event::{self, Event};
use crossterm::{cursor, terminal};
use image::RgbImage;

use crate::playback::Timeline;
use crate::settings::Limit;

use super::console::Console;
use super::outcome::{CommandError, CommandResult, Flow, parse_count};
use super::preview::Preview;
use super::render_steps::{explain_defaults, render_frames, shown};
use super::rendering::Size;
use super::report::show_scene_warnings;
use super::shell::Shell;

/// Frames played when none are asked for: two seconds at the default rate.
const DEFAULT_FRAMES: u32 = 24;
/// Frames a second when not asked for.
const DEFAULT_FPS: u32 = 12;

/// Frames `:play` keeps: all of them stay in memory to be replayed.
const PLAY_FRAMES: Limit =
    Limit { name: "the number of frames", min: 1, max: 1000, why: "every frame is kept in memory to be played again" };
/// Most bytes the frames may take together, so that a long animation on a
/// large graphics terminal does not fill the memory.
const PLAY_BYTES: u64 = 512 << 20;
/// Frames a second.
const PLAY_FPS: Limit = Limit { name: "the frames a second", min: 1, max: 60, why: "a terminal redraws no faster" };

/// `:play [FRAMES] [FPS]`.
pub(crate) fn play(shell: &mut Shell, arguments: &[String], console: &mut Console) -> CommandResult {
    let session = &mut shell.session;
    let (frames, fps) = match arguments {
        [] => (DEFAULT_FRAMES, DEFAULT_FPS),
        [frames] => (parse_count(frames, &PLAY_FRAMES)?, DEFAULT_FPS),
        [frames, fps] => (parse_count(frames, &PLAY_FRAMES)?, parse_count(fps, &PLAY_FPS)?),
        _ => return Err(CommandError::Usage("give the number of frames, then the frames a second".to_string())),
    };
    let Some(preview) = shown(console) else {
        return Err(CommandError::Failed(
            "`:play` shows the animation in the terminal, and pictures are off here\n\
             `:anim 24 anim.gif` writes it to a file"
                .to_string(),
        ));
    };
    let size = preview.render_size(Size { width: session.settings().width, height: session.settings().height });
    let most = frames_that_fit(size);
    if u64::from(frames) > most {
        return Err(CommandError::Failed(format!(
            "{frames} frames of {size} take more than {} MiB: at most {most} fit (`:preview small` makes them smaller)",
            PLAY_BYTES >> 20
        )));
    }
    explain_defaults(session, console);
    show_scene_warnings(session, console, size, true);
    if !session.depends_on_time() {
        console.note("nothing in the scene depends on `time`: every frame is the same (see `:help time`)");
    }
    let mut images = Vec::with_capacity(frames as usize);
    render_frames(session, frames, Timeline::default(), size, console, &mut |_, image| {
        images.push(image);
        Ok(())
    })?;
    console.say(format!("playing {frames} frames of {size} at {fps} a second; any key stops"));
    let shown = play_until_key(&preview, &images, Duration::from_secs(1) / fps)
        .map_err(|problem| CommandError::Failed(format!("cannot play here: {problem}")))?;
    console.say(format!("stopped after {shown} frames"));
    Ok(Flow::Continue)
}

/// How many frames of `size` fit in [`PLAY_BYTES`] (3 bytes a pixel).
fn frames_that_fit(size: Size) -> u64 {
    PLAY_BYTES / (3 * u64::from(size.width) * u64::from(size.height)).max(1)
}

/// Draws `images` in a loop, each in place of the one before, one every
/// `interval`, until a key is pressed; returns how many were drawn.
fn play_until_key(preview: &Preview, images: &[RgbImage], interval: Duration) -> Result<usize, String> {
    let _raw = RawMode::enable()?;
    let mut stdout = std::io::stdout();
    for (shown, image) in images.iter().cycle().enumerate() {
        let rows = preview.show(image)?;
        stdout.flush().map_err(|e| e.to_string())?;
        if key_pressed(interval)? {
            crossterm::execute!(stdout, cursor::MoveToColumn(0)).map_err(|e| e.to_string())?;
            return Ok(shown + 1);
        }
        // Back to the first row of the picture, to draw the next over it.
        let up = u16::try_from(rows).unwrap_or(u16::MAX);
        crossterm::execute!(stdout, cursor::MoveUp(up), cursor::MoveToColumn(0)).map_err(|e| e.to_string())?;
    }
    Ok(0)
}

/// Whether a key is pressed within `wait`.
fn key_pressed(wait: Duration) -> Result<bool, String> {
    if !event::poll(wait).map_err(|e| e.to_string())? {
        return Ok(false);
    }
    Ok(matches!(event::read().map_err(|e| e.to_string())?, Event::Key(_)))
}

/// The terminal in raw mode (keys arrive one by one, Ctrl-C as a key) until
/// dropped.
struct RawMode;

impl RawMode {
    fn enable() -> Result<RawMode, String> {
        terminal::enable_raw_mode().map_err(|e| e.to_string())?;
        Ok(RawMode)
    }
}

impl Drop for RawMode {
    fn drop(&mut self) {
        let _ = terminal::disable_raw_mode();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_kept_within_the_memory_allowed() {
        // A small half-block preview keeps every frame allowed; a large
        // graphics preview (1600x928 pixels) about 120.
        assert!(frames_that_fit(Size { width: 60, height: 32 }) > u64::from(PLAY_FRAMES.max));
        assert_eq!(frames_that_fit(Size { width: 1600, height: 928 }), 120);
    }
}
