//! `:play [FRAMES] [FPS]`: the animation of the session's scene, played
//! where the front-end shows pictures. The frames are rendered once at the
//! size it shows them (by the same machinery as `:anim`), then handed to it
//! to play (the terminal draws them again and again in place until a key is
//! pressed).

use crate::playback::Timeline;
use crate::settings::Limit;

use super::outcome::{CommandError, CommandResult, Flow, parse_count};
use super::outputs::{FrontEnd, Output};
use super::render_steps::{notes_before_rendering, render_frames};
use super::rendering::Size;
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
pub(crate) fn play(shell: &mut Shell, arguments: &[String], front: &mut dyn FrontEnd) -> CommandResult {
    let session = &mut shell.session;
    let (frames, fps) = match arguments {
        [] => (DEFAULT_FRAMES, DEFAULT_FPS),
        [frames] => (parse_count(frames, &PLAY_FRAMES)?, DEFAULT_FPS),
        [frames, fps] => (parse_count(frames, &PLAY_FRAMES)?, parse_count(fps, &PLAY_FPS)?),
        _ => return Err(CommandError::Usage("give the number of frames, then the frames a second".to_string())),
    };
    let configured = Size { width: session.settings().width, height: session.settings().height };
    let Some(size) = front.picture_size(configured) else {
        return Err(CommandError::Failed(
            "`:play` shows the animation in the terminal, and pictures are off here\n\
             `:anim 24 anim.gif` writes it to a file"
                .to_string(),
        ));
    };
    let most = frames_that_fit(size);
    if u64::from(frames) > most {
        return Err(CommandError::Failed(format!(
            "{frames} frames of {size} take more than {} MiB: at most {most} fit (`:preview small` makes them smaller)",
            PLAY_BYTES >> 20
        )));
    }
    notes_before_rendering(session, &mut shell.warned, front, size, true);
    if !session.depends_on_time() {
        front.note("nothing in the scene depends on `time`: every frame is the same (see `:help time`)");
    }
    let mut images = Vec::with_capacity(frames as usize);
    render_frames(session, frames, Timeline::default(), size, front, &mut |_, image| {
        images.push(image);
        Ok(())
    })?;
    front
        .present(Output::Frames { frames: images, fps })
        .map_err(|problem| CommandError::Failed(format!("cannot play here: {problem}")))?;
    Ok(Flow::Continue)
}

/// How many frames of `size` fit in [`PLAY_BYTES`] (3 bytes a pixel).
fn frames_that_fit(size: Size) -> u64 {
    PLAY_BYTES / (3 * u64::from(size.width) * u64::from(size.height)).max(1)
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
