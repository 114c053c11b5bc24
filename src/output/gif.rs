//! Animated GIF, encoded frame by frame as the frames arrive.

use std::borrow::Cow;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;
use std::sync::atomic::AtomicBool;

use image::RgbImage;
use rayon::prelude::*;

use super::atomic::{Cancellable, PendingFile};
use super::error::{OutputError, format_error, io_error};
use crate::playback::{Loops, Playback};

/// An animated GIF being written.
///
/// Its palette of 256 colours is learnt (NeuQuant) from the first frame; a
/// later frame that the palette no longer fits (new colours came into view)
/// gets a palette of its own, which the frames after it keep while it fits.
pub(super) struct GifStream {
    pending: PendingFile,
    encoder: gif::Encoder<BufWriter<Cancellable<File>>>,
    width: u16,
    height: u16,
    delay: u16,
    /// The palette frames are mapped to.
    palette: color_quant::NeuQuant,
    /// Whether `palette` is the GIF's global one (the first frame's).
    global: bool,
    /// The last frame, mapped to `palette`.
    mapped: Mapped,
}

/// A frame mapped to a palette, updated in place from one frame to the
/// next: most pixels of an animation's frame are those of the frame
/// before, and keep their index without a search of the palette.
struct Mapped {
    /// The frame's bytes.
    pixels: Vec<u8>,
    /// Each pixel's index in the palette.
    indices: Vec<u8>,
    /// Whether each pixel is more than [`GIF_MISFIT_LEVELS`] off its
    /// palette colour.
    misfits: Vec<bool>,
}

/// The NeuQuant sampling factor for the GIF palette, 1 (best) to 30
/// (fastest).
const GIF_QUANTISATION_SPEED: usize = 10;

/// How many pixels NeuQuant should learn from at least, where the frame has them.
const GIF_LEARNT_PIXELS: usize = 48_000;

/// A pixel whose palette colour is off by more than this many levels in a
/// channel is badly mapped.
const GIF_MISFIT_LEVELS: u8 = 24;

/// A frame with more badly mapped pixels than one in this many, and more
/// than [`GIF_MISFIT_PIXELS`], gets a palette of its own.
const GIF_MISFIT_SHARE: usize = 1000;

/// Fewer badly mapped pixels than this never call for a new palette: in a
/// small frame a few such pixels are the palette's usual error, and
/// learning a palette for every frame would take most of the time.
const GIF_MISFIT_PIXELS: usize = 32;

impl GifStream {
    /// Starts a GIF at `path` of frames the size of `first`, played as
    /// `playback` says (its delays in steps of 10 ms, GIF's unit), until
    /// `cancel` is raised.
    pub(super) fn start(
        path: &Path,
        first: &RgbImage,
        playback: &Playback,
        cancel: &'static AtomicBool,
    ) -> Result<GifStream, OutputError> {
        let too_large = || OutputError::Io {
            path: path.to_owned(),
            source: io::Error::new(io::ErrorKind::InvalidInput, "a GIF is at most 65535 pixels wide and high"),
        };
        let width = u16::try_from(first.width()).map_err(|_| too_large())?;
        let height = u16::try_from(first.height()).map_err(|_| too_large())?;
        let palette = learn_palette(first);
        let (pending, writer) = PendingFile::create(path, cancel)?;
        let gif_error = |e| pending.failure(gif_encode_error(path, e));
        let mut encoder = gif::Encoder::new(writer, width, height, &palette.color_map_rgb()).map_err(gif_error)?;
        // Without the looping extension a GIF plays once; with it, the count is of repeats after the first play.
        match playback.loops.unwrap_or(Loops::Forever) {
            Loops::Forever => encoder.set_repeat(gif::Repeat::Infinite).map_err(gif_error)?,
            Loops::Times(1) => {}
            Loops::Times(times) => {
                let repeats = u16::try_from(times - 1).unwrap_or(u16::MAX);
                encoder.set_repeat(gif::Repeat::Finite(repeats)).map_err(gif_error)?;
            }
        }
        // The fastest rate, 100 fps, gives a delay of 1; the slowest, 0.01 fps, 10000.
        let delay = (100.0 / playback.fps()).round() as u16;
        let pixels = first.width() as usize * first.height() as usize;
        let mapped = Mapped { pixels: vec![0; pixels * 3], indices: vec![0; pixels], misfits: vec![false; pixels] };
        Ok(GifStream { pending, encoder, width, height, delay, palette, global: true, mapped })
    }

    /// Maps `image` to the palette (a new one if it does not fit, unless
    /// the palette was `learnt_from_it`) and encodes it.
    pub(super) fn add(&mut self, image: &RgbImage, learnt_from_it: bool) -> Result<(), OutputError> {
        self.mapped.update(image, &self.palette, learnt_from_it);
        let misfits = self.mapped.misfits.iter().filter(|misfit| **misfit).count();
        let fits = misfits <= GIF_MISFIT_PIXELS || misfits * GIF_MISFIT_SHARE <= self.mapped.indices.len();
        if !learnt_from_it && !fits {
            self.palette = learn_palette(image);
            self.global = false;
            self.mapped.update(image, &self.palette, true);
        }
        let mut frame = gif::Frame {
            width: self.width,
            height: self.height,
            delay: self.delay,
            buffer: Cow::Borrowed(&self.mapped.indices),
            ..gif::Frame::default()
        };
        if !self.global {
            frame.palette = Some(self.palette.color_map_rgb());
        }
        self.encoder.write_frame(&frame).map_err(|e| self.pending.failure(gif_encode_error(&self.pending.path, e)))
    }

    /// Ends the GIF and puts it in place.
    pub(super) fn finish(self) -> Result<(), OutputError> {
        let (pending, path) = (&self.pending, &self.pending.path);
        let mut writer = self.encoder.into_inner().map_err(|e| pending.failure(gif_encode_error(path, e)))?;
        writer.flush().map_err(|e| pending.failure(io_error(path, e)))?;
        drop(writer);
        self.pending.commit()
    }
}

/// About how many pixels a GIF palette is learnt from, taken evenly from
/// the frame (all of an 800x600 frame).
const GIF_PALETTE_SAMPLE: usize = 480_000;

/// A 256-colour palette for `image`.
fn learn_palette(image: &RgbImage) -> color_quant::NeuQuant {
    let stride = (image.len() / 3).div_ceil(GIF_PALETTE_SAMPLE).max(1);
    let rgba: Vec<u8> = image.pixels().step_by(stride).flat_map(|p| [p[0], p[1], p[2], 0xFF]).collect();
    // NeuQuant learns from one pixel in `speed`: all of them in small frames.
    let speed = (rgba.len() / 4 / GIF_LEARNT_PIXELS).clamp(1, GIF_QUANTISATION_SPEED);
    color_quant::NeuQuant::new(speed as i32, 256, &rgba)
}

impl Mapped {
    /// Maps the pixels of `image` that differ from the last frame's (all of
    /// them if `palette` is `new`) to their nearest colour in `palette`, in
    /// parallel.
    fn update(&mut self, image: &RgbImage, palette: &color_quant::NeuQuant, new: bool) {
        let nearest = |p: &[u8]| {
            let index = palette.index_of(&[p[0], p[1], p[2], 0xFF]);
            let colour = palette.lookup(index).unwrap_or_default();
            let misfit = (0..3).any(|c| p[c].abs_diff(colour[c]) > GIF_MISFIT_LEVELS);
            (index as u8, misfit)
        };
        self.pixels
            .par_chunks_exact_mut(3)
            .zip(self.indices.par_iter_mut())
            .zip(self.misfits.par_iter_mut())
            .zip(image.as_raw().par_chunks_exact(3))
            .with_min_len(4096)
            .for_each(|(((last, index), misfit), pixel)| {
                if new || last != pixel {
                    last.copy_from_slice(pixel);
                    (*index, *misfit) = nearest(pixel);
                }
            });
    }
}

fn gif_encode_error(path: &Path, source: gif::EncodingError) -> OutputError {
    match source {
        gif::EncodingError::Io(source) => io_error(path, source),
        other => format_error(path, image::ImageFormat::Gif, other),
    }
}
