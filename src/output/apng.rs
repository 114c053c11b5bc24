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

/// An animated PNG being written to a file.
pub(super) struct ApngStream {
    pending: PendingFile,
    encoder: ApngEncoder<BufWriter<Cancellable<File>>>,
}

/// An animated PNG being encoded into a writer: a file, or memory
/// ([`apng_bytes`], for the browser playground, which has no files).
struct ApngEncoder<W: Write> {
    writer: png::Writer<W>,
}

/// The denominator of APNG frame delays: a delay of 1/fps seconds is
/// written as `100 / round(100 * fps)`, exact to a hundredth of a frame a
/// second.
const DELAY_NUMERATOR: u16 = 100;

impl<W: Write> ApngEncoder<W> {
    /// Starts an APNG in `writer` of `frames` frames the size of `first`,
    /// played as `playback` says.
    fn start(writer: W, first: &RgbImage, frames: u32, playback: &Playback) -> Result<Self, png::EncodingError> {
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
        Ok(ApngEncoder { writer: encoder.write_header()? })
    }

    /// Encodes the next frame.
    fn add(&mut self, image: &RgbImage) -> Result<(), png::EncodingError> {
        self.writer.write_image_data(image.as_raw())
    }

    /// Writes the end chunk, having checked that every frame came.
    fn finish(self) -> Result<(), png::EncodingError> {
        self.writer.finish()
    }
}

/// `frames` as the bytes of the APNG file `:anim N FILE.apng` writes of
/// them, played as `playback` says.
pub fn apng_bytes(frames: &[RgbImage], playback: &Playback) -> Result<Vec<u8>, png::EncodingError> {
    let mut bytes = Vec::new();
    let Some(first) = frames.first() else { return Ok(bytes) };
    let count = u32::try_from(frames.len()).unwrap_or(u32::MAX);
    let mut encoder = ApngEncoder::start(&mut bytes, first, count, playback)?;
    for frame in frames {
        encoder.add(frame)?;
    }
    encoder.finish()?;
    Ok(bytes)
}

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
        let encoder = ApngEncoder::start(writer, first, frames, playback)
            .map_err(|e| pending.failure(png_encode_error(path, e)))?;
        Ok(ApngStream { pending, encoder })
    }

    /// Encodes the next frame.
    pub(super) fn add(&mut self, image: &RgbImage) -> Result<(), OutputError> {
        self.encoder.add(image).map_err(|e| self.failure(e))
    }

    /// Ends the APNG and puts it in place.
    pub(super) fn finish(self) -> Result<(), OutputError> {
        // Writes the end chunk, checks every frame came and flushes the file.
        let pending = self.pending;
        self.encoder.finish().map_err(|e| pending.failure(png_encode_error(&pending.path, e)))?;
        pending.commit()
    }

    /// The encoder's `error`, or [`OutputError::Cancelled`].
    fn failure(&self, error: png::EncodingError) -> OutputError {
        self.pending.failure(png_encode_error(&self.pending.path, error))
    }
}

fn png_encode_error(path: &Path, source: png::EncodingError) -> OutputError {
    match source {
        png::EncodingError::IoError(source) => io_error(path, source),
        other => format_error(path, image::ImageFormat::Png, other),
    }
}
