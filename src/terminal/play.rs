//! Playing an animation's frames in the terminal (`:play`): each drawn in
//! place of the one before until a key is pressed (Ctrl-C included: the
//! terminal is in raw mode meanwhile).

use std::io::Write;
use std::time::Duration;

use crossterm::event::{self, Event};
use crossterm::{cursor, terminal};
use image::RgbImage;

use super::preview::Preview;

/// Draws `images` in a loop, each in place of the one before, one every
/// `interval`, until a key is pressed; returns how many were drawn.
pub(crate) fn play_until_key(preview: &Preview, images: &[RgbImage], interval: Duration) -> Result<usize, String> {
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
