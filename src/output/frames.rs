//! An animation's frames as they arrive: encoded into one file (GIF, APNG,
//! video) or written as numbered images, and the names of those images.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use image::RgbImage;

use super::apng::ApngStream;
use super::error::OutputError;
use super::formats::ImageFormat;
use super::frame_names::frame_path;
use super::gif::GifStream;
use super::still::write_image_cancellable;
use super::video::VideoStream;
use crate::playback::Playback;

/// Where the frames of an animation go as they are rendered, in order:
/// encoded at once into one file (GIF, APNG, video) in `format`, or written
/// at once as numbered images (`spin.png` gives `spin0001.png`, ...).
/// Nothing is kept but a GIF's palette, so a long animation takes no more
/// memory than a short one.
pub(crate) struct FrameSink {
    path: PathBuf,
    format: ImageFormat,
    /// The number of frames of the whole animation.
    count: usize,
    playback: Playback,
    /// Raised by Ctrl-C: the frame being written, or the one file, is dropped.
    cancel: &'static AtomicBool,
    /// The one file being encoded, from the first frame on.
    stream: Option<Stream>,
    written: Vec<PathBuf>,
}

/// A file that holds every frame.
enum Stream {
    Gif(GifStream),
    Apng(ApngStream),
    Video(VideoStream),
}

impl Stream {
    /// Starts `sink`'s one file, for frames the size of `first`; writing
    /// it fails as soon as the sink's cancel flag is raised.
    fn start(sink: &FrameSink, first: &RgbImage) -> Result<Stream, OutputError> {
        let (path, playback, cancel) = (&sink.path, &sink.playback, sink.cancel);
        Ok(match sink.format {
            ImageFormat::Gif => Stream::Gif(GifStream::start(path, first, playback, cancel)?),
            ImageFormat::Apng => {
                let frames = u32::try_from(sink.count).unwrap_or(u32::MAX);
                Stream::Apng(ApngStream::start(path, first, frames, playback, cancel)?)
            }
            format => Stream::Video(VideoStream::start(path, format, first, playback, cancel)?),
        })
    }
}

impl FrameSink {
    /// A sink for the `count` frames of an animation, in `format` (from
    /// [`check_animation_output`](super::checks::check_animation_output)), named after `path` and played as
    /// `playback` says. Raising `cancel` (Ctrl-C) stops the writing with
    /// [`OutputError::Cancelled`], even in the middle of a frame.
    pub fn new(
        path: &Path,
        format: ImageFormat,
        count: usize,
        playback: Playback,
        cancel: &'static AtomicBool,
    ) -> FrameSink {
        FrameSink { path: path.to_path_buf(), format, count, playback, cancel, stream: None, written: Vec::new() }
    }

    /// Takes frame number `frame` (from 1).
    pub fn add(&mut self, frame: usize, image: RgbImage) -> Result<(), OutputError> {
        if self.format.is_still() {
            let path = frame_path(&self.path, frame, self.count);
            write_image_cancellable(&path, &image, self.cancel)?;
            self.written.push(path);
            return Ok(());
        }
        let first = self.stream.is_none();
        if first {
            self.stream = Some(Stream::start(self, &image)?);
        }
        let stream = self.stream.as_mut().expect("started above");
        match stream {
            // A GIF's first palette is learnt from the first frame: it fits.
            Stream::Gif(gif) => gif.add(&image, first),
            Stream::Apng(apng) => apng.add(&image),
            Stream::Video(video) => video.add(&image),
        }
    }

    /// The numbered images written so far.
    pub fn written(&self) -> &[PathBuf] {
        &self.written
    }

    /// Finishes the one file, if any; returns the files written.
    pub fn finish(mut self) -> Result<Vec<PathBuf>, OutputError> {
        match self.stream.take() {
            Some(Stream::Gif(stream)) => stream.finish()?,
            Some(Stream::Apng(stream)) => stream.finish()?,
            Some(Stream::Video(stream)) => stream.finish()?,
            None if self.format.is_still() => return Ok(self.written),
            None => return Err(OutputError::NoFrames { path: self.path }),
        }
        self.written.push(self.path);
        Ok(self.written)
    }
}

/// The files an animation wrote, in words: `a.gif`, or `a0001.png ... a0100.png`.
pub(crate) fn describe_files(files: &[PathBuf]) -> String {
    match files {
        [only] => only.display().to_string(),
        [first, .., last] => format!("{} ... {}", first.display(), last.display()),
        [] => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::Ordering;

    use super::*;
    use crate::output::atomic::NEVER_CANCELLED;
    use crate::output::still::tests::sample;
    use crate::output::video;

    /// Frames 1 and 2 of an animation to `name` in `format`, with `cancel`
    /// raised after the first: the error, and the files written.
    fn cancelled_after_one_frame(
        dir: &Path,
        name: &str,
        format: ImageFormat,
        cancel: &'static AtomicBool,
    ) -> (OutputError, Vec<PathBuf>) {
        let frame = RgbImage::from_fn(400, 300, |x, y| image::Rgb([x as u8, y as u8, (x ^ y) as u8]));
        let mut sink = FrameSink::new(&dir.join(name), format, 3, Playback::default(), cancel);
        sink.add(1, frame.clone()).expect("the first frame is taken");
        cancel.store(true, Ordering::SeqCst);
        let error = sink.add(2, frame).err().or_else(|| sink.finish().err()).expect("cancelled");
        (error, names_in(dir))
    }

    /// The names in `dir`, sorted.
    fn names_in(dir: &Path) -> Vec<PathBuf> {
        let mut names: Vec<PathBuf> =
            std::fs::read_dir(dir).expect("list").map(|entry| entry.expect("entry").file_name().into()).collect();
        names.sort();
        names
    }

    #[test]
    fn a_cancelled_animation_keeps_whole_numbered_frames_and_no_partial_file() {
        static NUMBERED: AtomicBool = AtomicBool::new(false);
        static GIF: AtomicBool = AtomicBool::new(false);
        static APNG: AtomicBool = AtomicBool::new(false);
        let dir = tempfile::tempdir().expect("temp dir");
        let (error, files) = cancelled_after_one_frame(dir.path(), "f.png", ImageFormat::Png, &NUMBERED);
        assert!(matches!(&error, OutputError::Cancelled { path } if path.ends_with("f0002.png")), "{error:?}");
        assert_eq!(files, [PathBuf::from("f0001.png")], "frame 1 stays, no part of frame 2");
        image::open(dir.path().join("f0001.png")).expect("frame 1 is whole");
        std::fs::remove_file(dir.path().join("f0001.png")).expect("removed");
        for (name, format, cancel) in [("a.gif", ImageFormat::Gif, &GIF), ("a.apng", ImageFormat::Apng, &APNG)] {
            let (error, files) = cancelled_after_one_frame(dir.path(), name, format, cancel);
            assert!(matches!(&error, OutputError::Cancelled { path } if path.ends_with(name)), "{error:?}");
            assert_eq!(files, Vec::<PathBuf>::new(), "no {name}, no temporary file");
        }
    }

    #[test]
    fn a_cancelled_video_stops_ffmpeg_and_leaves_no_file() {
        static VIDEO: AtomicBool = AtomicBool::new(false);
        let dir = tempfile::tempdir().expect("temp dir");
        if video::check_ffmpeg(&dir.path().join("v.mp4")).is_err() {
            eprintln!("ffmpeg is not installed: skipped");
            return;
        }
        let (error, files) = cancelled_after_one_frame(dir.path(), "v.mp4", ImageFormat::Mp4, &VIDEO);
        assert!(matches!(&error, OutputError::Cancelled { path } if path.ends_with("v.mp4")), "{error:?}");
        assert_eq!(files, Vec::<PathBuf>::new(), "no video, no temporary file");
    }

    /// Writes `frames` to a GIF at `path` through a [`FrameSink`].
    fn write_gif(path: &Path, frames: &[RgbImage]) -> Result<Vec<PathBuf>, OutputError> {
        let mut sink = FrameSink::new(path, ImageFormat::Gif, frames.len(), Playback::default(), &NEVER_CANCELLED);
        for (k, frame) in frames.iter().enumerate() {
            sink.add(k + 1, frame.clone())?;
        }
        sink.finish()
    }

    #[test]
    fn gif_round_trips_frame_count() {
        use image::AnimationDecoder;
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("anim.gif");
        assert_eq!(write_gif(&path, &[sample(), sample(), sample()]).expect("write gif"), std::slice::from_ref(&path));
        let file = std::io::BufReader::new(std::fs::File::open(&path).expect("open"));
        let decoder = image::codecs::gif::GifDecoder::new(file).expect("decode");
        assert_eq!(decoder.into_frames().count(), 3);
        assert!(write_gif(&dir.path().join("empty.gif"), &[]).is_err());
        assert_eq!(std::fs::read_dir(dir.path()).expect("list").count(), 1, "no temporary file left");
    }

    #[test]
    fn gif_palettes_keep_the_colours_of_every_frame() {
        use image::AnimationDecoder;
        // Three frames of quite different colours, with a gradient each.
        let frame = |base: [u8; 3]| {
            RgbImage::from_fn(64, 48, |x, _| {
                let shade = (x * 2) as u8;
                image::Rgb([
                    base[0].saturating_add(shade),
                    base[1].saturating_add(shade),
                    base[2].saturating_add(shade),
                ])
            })
        };
        let frames = [frame([200, 10, 10]), frame([10, 10, 180]), frame([10, 150, 10])];
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("colours.gif");
        write_gif(&path, &frames).expect("write gif");
        let file = std::io::BufReader::new(std::fs::File::open(&path).expect("open"));
        let decoded = image::codecs::gif::GifDecoder::new(file).expect("decode").into_frames().collect_frames();
        let decoded = decoded.expect("frames decode");
        assert_eq!(decoded.len(), 3);
        for (original, decoded) in frames.iter().zip(&decoded) {
            assert_eq!(decoded.delay().numer_denom_ms(), (40, 1));
            for (a, b) in original.pixels().zip(decoded.buffer().pixels()) {
                let off = (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0);
                assert!(off <= 8, "{a:?} became {b:?}");
            }
        }
    }
}
