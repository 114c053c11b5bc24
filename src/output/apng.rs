//! Animated PNG (APNG), encoded frame by frame as the frames arrive: every
//! pixel exact, unlike a GIF's 256 colours.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;
use std::sync::atomic::AtomicBool;

use image::RgbImage;

use super::atomic::{Cancellable, PendingFile};
use super::error::{OutputError, format_error, io_error};
use crate::playback::{Loops, Playback};

/// An animated PNG being written.
pub(super) struct ApngStream {
    pending: PendingFile,
    writer: png::Writer<BufWriter<Cancellable<File>>>,
}

/// The denominator of APNG frame delays: a delay of 1/fps seconds is
/// written as `100 / round(100 * fps)`, exact to a hundredth of a frame a
/// second.
const DELAY_NUMERATOR: u16 = 100;

impl ApngStream {
    /// Starts an APNG at `path` of `frames` frames the size of `first`, played
    /// as `playback` says, until `cancel` is raised.
    pub(super) fn start(
        path: &Path,
        first: &RgbImage,
        frames: u32,
        playback: &Playback,
        cancel: &'static AtomicBool,
    ) -> Result<ApngStream, OutputError> {
        let (pending, writer) = PendingFile::create(path, cancel)?;
        let writer =
            start_encoding(writer, first, frames, playback).map_err(|e| pending.failure(png_encode_error(path, e)))?;
        Ok(ApngStream { pending, writer })
    }

    /// Encodes the next frame.
    pub(super) fn add(&mut self, image: &RgbImage) -> Result<(), OutputError> {
        self.writer.write_image_data(image.as_raw()).map_err(|e| self.failure(e))
    }

    /// Ends the APNG and puts it in place.
    pub(super) fn finish(self) -> Result<(), OutputError> {
        // Writes the end chunk, checks every frame came and flushes the file.
        let pending = self.pending;
        self.writer.finish().map_err(|e| pending.failure(png_encode_error(&pending.path, e)))?;
        pending.commit()
    }

    /// The encoder's `error`, or [`OutputError::Cancelled`].
    fn failure(&self, error: png::EncodingError) -> OutputError {
        self.pending.failure(png_encode_error(&self.pending.path, error))
    }
}

/// Writes the header of an APNG of `frames` frames the size of `first`,
/// played as `playback` says, to `writer`: the frames follow.
fn start_encoding<W: Write>(
    writer: W,
    first: &RgbImage,
    frames: u32,
    playback: &Playback,
) -> Result<png::Writer<W>, png::EncodingError> {
    let mut encoder = png::Encoder::new(writer, first.width(), first.height());
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    // The same trade as single PNGs: fast compression, so that encoding never outweighs tracing.
    encoder.set_compression(png::Compression::Fast);
    encoder.set_filter(png::Filter::Adaptive);
    // APNG counts plays in all; 0 is forever.
    let plays = match playback.loops.unwrap_or(Loops::Forever) {
        Loops::Forever => 0,
        Loops::Times(times) => times,
    };
    encoder.set_animated(frames, plays)?;
    // fps is at most 100, so the denominator is at most 10000.
    let denominator = (playback.fps() * f64::from(DELAY_NUMERATOR)).round() as u16;
    encoder.set_frame_delay(DELAY_NUMERATOR, denominator)?;
    encoder.write_header()
}

/// `frames` (at least one, all of one size) as the bytes of an APNG played
/// as `playback` says, for a front-end that shows it (a notebook) or
/// offers it to download (the browser playground, `web/`, which has no
/// files): the bytes `--anim` and `:anim` write of the same frames.
pub fn apng_bytes(frames: &[RgbImage], playback: &Playback) -> Result<Vec<u8>, png::EncodingError> {
    let mut bytes = Vec::new();
    let first = frames.first().ok_or(png::EncodingError::LimitsExceeded)?;
    let mut writer = start_encoding(&mut bytes, first, frames.len() as u32, playback)?;
    for frame in frames {
        writer.write_image_data(frame.as_raw())?;
    }
    writer.finish()?;
    Ok(bytes)
}

fn png_encode_error(path: &Path, source: png::EncodingError) -> OutputError {
    match source {
        png::EncodingError::IoError(source) => io_error(path, source),
        other => format_error(path, image::ImageFormat::Png, other),
    }
}
