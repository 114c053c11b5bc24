//! Writing images and animations: PNG, PPM, animated GIF and PNG, video,
//! and the names of frames.
//!
//! Files are written atomically: into a temporary file in the target's
//! directory, then renamed over the target, so a failed or interrupted
//! write never leaves a partial image behind, and a replaced file keeps its
//! permissions. An animation is encoded frame by frame as the frames
//! arrive, so its memory does not grow with the number of frames.

mod apng;
mod gif;
mod video;

use std::fmt;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ImageEncoder, RgbImage};

use crate::playback::{AnimationOptions, Loops, Playback};
use apng::ApngStream;
use gif::GifStream;
use video::VideoStream;

/// An image format rayrepl writes, named by a file's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ImageFormat {
    /// PNG, 8 bits per channel.
    Png,
    /// Binary PPM (P6).
    Ppm,
    /// Animated GIF, for animations only.
    Gif,
    /// Animated PNG, for animations only.
    Apng,
    /// H.264 video in MP4, made by ffmpeg, for animations only.
    Mp4,
    /// VP9 video in WebM, made by ffmpeg, for animations only.
    Webm,
}

impl ImageFormat {
    /// The format named by `path`'s extension (case-insensitive), if known.
    pub fn from_path(path: &Path) -> Option<ImageFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(ImageFormat::Png),
            "ppm" => Some(ImageFormat::Ppm),
            "gif" => Some(ImageFormat::Gif),
            "apng" => Some(ImageFormat::Apng),
            "mp4" => Some(ImageFormat::Mp4),
            "webm" => Some(ImageFormat::Webm),
            _ => None,
        }
    }

    /// Whether the format holds one image (an animation in it is numbered
    /// files).
    fn is_still(self) -> bool {
        matches!(self, ImageFormat::Png | ImageFormat::Ppm)
    }

    /// Whether one file of the format holds all the frames of an animation.
    pub fn holds_every_frame(self) -> bool {
        !self.is_still()
    }

    /// The format's name in messages.
    fn name(self) -> &'static str {
        match self {
            ImageFormat::Png => "PNG",
            ImageFormat::Ppm => "PPM",
            ImageFormat::Gif => "GIF",
            ImageFormat::Apng => "APNG",
            ImageFormat::Mp4 => "MP4",
            ImageFormat::Webm => "WebM",
        }
    }
}

/// What an output file will hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Content {
    /// One image.
    Still,
    /// The frames of an animation: one GIF, APNG or video, or numbered images.
    Animation,
}

/// Checks, before any work, that `path` can receive `content`: a file name
/// (not a folder) in an existing folder where files can be made, with an
/// extension naming a format that suits the content. Returns that format.
pub(crate) fn check_output(path: &Path, content: Content) -> Result<ImageFormat, OutputError> {
    let names_folder = path.as_os_str().to_string_lossy().ends_with(std::path::is_separator);
    if names_folder || path.is_dir() {
        return Err(OutputError::Folder { path: path.to_owned() });
    }
    if let Some(folder) = path.parent().filter(|f| !f.as_os_str().is_empty() && !f.is_dir()) {
        return Err(OutputError::NoFolder { path: path.to_owned(), folder: folder.to_owned() });
    }
    let format = match (ImageFormat::from_path(path), content) {
        (Some(format), Content::Still) if !format.is_still() => {
            Err(OutputError::OnlyForAnimations { path: path.to_owned(), format: format.name() })
        }
        (Some(format), _) => Ok(format),
        (None, _) => Err(OutputError::UnknownFormat { path: path.to_owned(), content }),
    }?;
    // The write goes through a temporary file in the folder: make one now.
    temp_file_in(folder_of(path)).map_err(|e| io_error(path, e))?;
    Ok(format)
}

/// Checks, before any work, that `path` can receive an animation made as
/// `options` say: [`check_output`], a `.png` or `.apng` name for `--apng`,
/// a speed and looping only for a format that plays, and `ffmpeg` for a
/// video. Returns the format.
pub(crate) fn check_animation_output(path: &Path, options: &AnimationOptions) -> Result<ImageFormat, OutputError> {
    let format = match (check_output(path, Content::Animation)?, options.apng) {
        (ImageFormat::Png | ImageFormat::Apng, true) => ImageFormat::Apng,
        (_, true) => return Err(OutputError::ApngName { path: path.to_owned() }),
        (format, false) => format,
    };
    if format.is_still() && options.playback.is_given() {
        return Err(OutputError::NumberedFramesDoNotPlay { path: path.to_owned() });
    }
    if matches!(format, ImageFormat::Mp4 | ImageFormat::Webm) {
        if options.playback.loops == Some(Loops::Forever) {
            return Err(OutputError::VideoLoopsForever { path: path.to_owned() });
        }
        video::check_ffmpeg(path)?;
    }
    Ok(format)
}

/// Whether `a` and `b` name the same existing file (through `./`, `..` or
/// symbolic links).
pub(crate) fn same_file(a: &Path, b: &Path) -> bool {
    matches!((a.canonicalize(), b.canonicalize()), (Ok(a), Ok(b)) if a == b)
}

/// Why an image could not be written.
#[derive(Debug)]
pub enum OutputError {
    /// The file name's extension names no supported format.
    UnknownFormat {
        /// The path given.
        path: PathBuf,
        /// What was to be written.
        content: Content,
    },
    /// An animation format was asked for one image.
    OnlyForAnimations {
        /// The path given.
        path: PathBuf,
        /// The format's name.
        format: &'static str,
    },
    /// `--apng` with a name that is not `.png` or `.apng`.
    ApngName {
        /// The path given.
        path: PathBuf,
    },
    /// A frame rate or looping for numbered images, which do not play.
    NumberedFramesDoNotPlay {
        /// The path given.
        path: PathBuf,
    },
    /// A video asked to loop forever, which no video file can say.
    VideoLoopsForever {
        /// The path given.
        path: PathBuf,
    },
    /// A video was asked for and `ffmpeg` cannot be run.
    NoFfmpeg {
        /// The path given.
        path: PathBuf,
    },
    /// ffmpeg failed to make a video.
    Ffmpeg {
        /// The video's path.
        path: PathBuf,
        /// What ffmpeg said.
        message: String,
    },
    /// The path names a folder, not a file.
    Folder {
        /// The path given.
        path: PathBuf,
    },
    /// The folder the file should go into does not exist.
    NoFolder {
        /// The path given.
        path: PathBuf,
        /// The missing folder.
        folder: PathBuf,
    },
    /// Reading or writing a file failed.
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The underlying error.
        source: io::Error,
    },
    /// The encoder failed.
    Encode {
        /// The file concerned.
        path: PathBuf,
        /// The underlying error.
        source: image::ImageError,
    },
    /// An animation needs at least one frame.
    NoFrames {
        /// The file concerned.
        path: PathBuf,
    },
    /// Ctrl-C stopped the writing: the file is as it was before.
    Cancelled {
        /// The file concerned.
        path: PathBuf,
    },
}

impl fmt::Display for OutputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OutputError::UnknownFormat { path, content } => {
                let formats = match content {
                    Content::Still => ".png or .ppm",
                    Content::Animation => ".gif, .apng, .mp4, .webm, .png or .ppm",
                };
                write!(f, "cannot tell the image format of `{}`: end the name in {formats}", path.display())
            }
            OutputError::OnlyForAnimations { path, format } => write!(
                f,
                "cannot write `{}`: {format} is for animations (--anim N, or :anim in a session); \
                 write one image as .png or .ppm",
                path.display()
            ),
            OutputError::ApngName { path } => {
                write!(f, "cannot write `{}` with --apng: an animated PNG's name ends in .png or .apng", path.display())
            }
            OutputError::NumberedFramesDoNotPlay { path } => write!(
                f,
                "cannot give `{}` a frame rate or looping: numbered images do not play; \
                 write a .gif, .apng, .mp4 or .webm (or add --apng for one animated .png)",
                path.display()
            ),
            OutputError::VideoLoopsForever { path } => write!(
                f,
                "cannot write `{}` looping forever: a video file cannot say so (players loop it on request); \
                 give --loop N to hold N plays",
                path.display()
            ),
            OutputError::NoFfmpeg { path } => write!(
                f,
                "cannot write `{}`: videos are made by the `ffmpeg` program, which is not installed \
                 (install the package `ffmpeg`: `apt install ffmpeg`, `brew install ffmpeg`); \
                 or write a .gif or .apng",
                path.display()
            ),
            OutputError::Ffmpeg { path, message } => {
                write!(f, "cannot write `{}`: ffmpeg failed: {message}", path.display())
            }
            OutputError::Folder { path } => write!(
                f,
                "cannot write `{}`: it is a folder; give a file name in it, such as `{}`",
                path.display(),
                path.join("out.png").display()
            ),
            OutputError::NoFolder { path, folder } => {
                write!(f, "cannot write `{}`: the folder `{}` does not exist", path.display(), folder.display())
            }
            OutputError::Io { path, source } => {
                write!(f, "cannot write `{}`: {}", path.display(), io_reason(source))
            }
            OutputError::Encode { path, source } => {
                write!(f, "cannot encode `{}`: {source}", path.display())
            }
            OutputError::NoFrames { path } => {
                write!(f, "cannot write `{}`: the animation has no frame", path.display())
            }
            OutputError::Cancelled { path } => {
                write!(f, "writing `{}` was cancelled: the file is as it was before", path.display())
            }
        }
    }
}

impl std::error::Error for OutputError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            OutputError::Io { source, .. } => Some(source),
            OutputError::Encode { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// A cancel flag that is never raised, for writes that Ctrl-C does not stop
/// (it ends the process instead, see [`exit_discarding_unfinished`]).
pub(crate) static NEVER_CANCELLED: AtomicBool = AtomicBool::new(false);

/// Writes `image` to `path` as PNG or PPM, as its extension says, atomically.
pub fn write_image(path: &Path, image: &RgbImage) -> Result<(), OutputError> {
    write_image_cancellable(path, image, &NEVER_CANCELLED)
}

/// [`write_image`], stopped with [`OutputError::Cancelled`] as soon as
/// `cancel` is raised (Ctrl-C in a session): the target is left as it was.
pub(crate) fn write_image_cancellable(
    path: &Path,
    image: &RgbImage,
    cancel: &'static AtomicBool,
) -> Result<(), OutputError> {
    let format = check_output(path, Content::Still)?;
    let (pending, mut writer) = PendingFile::create(path, cancel)?;
    let written = match format {
        ImageFormat::Ppm => write_ppm(&mut writer, image).map_err(|e| io_error(path, e)),
        _ => write_png(&mut writer, image).map_err(|e| encode_error(path, e)),
    };
    written.and_then(|()| writer.flush().map_err(|e| io_error(path, e))).map_err(|e| pending.failure(e))?;
    drop(writer);
    pending.commit()
}

/// Writes `text` to `path` atomically, as images are written (a scene file
/// written back by the session), unless `cancel` is raised meanwhile.
pub(crate) fn write_text(path: &Path, text: &str, cancel: &'static AtomicBool) -> Result<(), OutputError> {
    let (pending, mut writer) = PendingFile::create(path, cancel)?;
    let written = writer.write_all(text.as_bytes()).and_then(|()| writer.flush());
    written.map_err(|e| pending.failure(io_error(path, e)))?;
    drop(writer);
    pending.commit()
}

/// Writes `image` as binary PPM (P6) to `writer` (used for `-o -`).
pub(crate) fn write_ppm(writer: &mut dyn Write, image: &RgbImage) -> io::Result<()> {
    write!(writer, "P6\n{} {}\n255\n", image.width(), image.height())?;
    writer.write_all(image.as_raw())?;
    writer.flush()
}

/// Writes `image` as PNG to `writer`.
fn write_png(writer: &mut dyn Write, image: &RgbImage) -> image::ImageResult<()> {
    // Fast compression: large renders and 100-frame animations would
    // otherwise spend more time compressing than tracing.
    let encoder = PngEncoder::new_with_quality(writer, CompressionType::Fast, FilterType::Adaptive);
    encoder.write_image(image.as_raw(), image.width(), image.height(), image::ExtendedColorType::Rgb8)
}

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
    /// [`check_animation_output`]), named after `path` and played as
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

/// The file name of frame `k` of `n`: the frame number, zero-padded to at
/// least 4 digits (more if `n` needs them), inserted before the extension:
/// `out.png` gives `out0001.png`.
pub(crate) fn frame_path(base: &Path, k: usize, n: usize) -> PathBuf {
    let digits = n.to_string().len().max(4);
    let stem = base.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let mut name = format!("{stem}{k:0digits$}");
    if let Some(ext) = base.extension() {
        name.push('.');
        name.push_str(&ext.to_string_lossy());
    }
    base.with_file_name(name)
}

/// The temporary files being written, which an interruption removes.
static UNFINISHED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn unfinished() -> MutexGuard<'static, Vec<PathBuf>> {
    UNFINISHED.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The exit code after Ctrl-C or `kill` (128 + SIGINT, as shells report it).
pub(crate) const INTERRUPTED_EXIT_CODE: i32 = 130;

/// Removes the temporary files of unfinished writes and ends the process
/// with `code`: what an interruption (Ctrl-C, `kill`) does, so that it
/// leaves no temporary file behind and every target as it was.
pub(crate) fn exit_discarding_unfinished(code: i32) -> ! {
    // The lock is held until the end: no write starts or finishes meanwhile.
    let unfinished = unfinished();
    for path in unfinished.iter() {
        let _ = std::fs::remove_file(path);
    }
    std::process::exit(code)
}

/// A file being written: a temporary file next to its target, which
/// [`PendingFile::commit`] renames over the target. Dropped without a
/// commit, the temporary file is removed and the target left as it was.
struct PendingFile {
    path: PathBuf,
    temp_path: PathBuf,
    temp: Option<tempfile::NamedTempFile>,
    cancel: &'static AtomicBool,
}

impl PendingFile {
    /// A temporary file for `path`, and a writer into it that fails as soon
    /// as `cancel` is raised.
    fn create(
        path: &Path,
        cancel: &'static AtomicBool,
    ) -> Result<(PendingFile, BufWriter<Cancellable<File>>), OutputError> {
        let mut unfinished = unfinished();
        let temp = temp_file_in(folder_of(path)).map_err(|e| io_error(path, e))?;
        unfinished.push(temp.path().to_owned());
        let file = temp.as_file().try_clone().map_err(|e| io_error(path, e))?;
        let pending =
            PendingFile { path: path.to_owned(), temp_path: temp.path().to_owned(), temp: Some(temp), cancel };
        Ok((pending, BufWriter::new(Cancellable { inner: file, cancel })))
    }

    /// Whether `cancel` was raised: the file is not to be put in place.
    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::SeqCst)
    }

    /// `error`, or [`OutputError::Cancelled`] if the write failed because
    /// `cancel` was raised (encoders pass the writer's error on in their own
    /// words).
    fn failure(&self, error: OutputError) -> OutputError {
        if self.cancelled() { OutputError::Cancelled { path: self.path.clone() } } else { error }
    }

    /// Puts the written file in place of the target, with the target's
    /// permissions if it existed; not if `cancel` was raised meanwhile
    /// (syncing a large file to disk can take a while).
    fn commit(mut self) -> Result<(), OutputError> {
        let temp = self.temp.take().expect("a pending file is committed once");
        temp.as_file().sync_all().map_err(|e| io_error(&self.path, e))?;
        if self.cancelled() {
            return Err(OutputError::Cancelled { path: self.path.clone() });
        }
        if let Ok(existing) = std::fs::metadata(&self.path) {
            temp.as_file().set_permissions(existing.permissions()).map_err(|e| io_error(&self.path, e))?;
        }
        let mut unfinished = unfinished();
        let persisted = temp.persist(&self.path);
        unfinished.retain(|p| *p != self.temp_path);
        persisted.map(drop).map_err(|e| io_error(&self.path, e.error))
    }
}

impl Drop for PendingFile {
    fn drop(&mut self) {
        let mut unfinished = unfinished();
        drop(self.temp.take());
        unfinished.retain(|p| *p != self.temp_path);
    }
}

/// The largest piece written at once, so that a large image written in one
/// call still sees Ctrl-C within a few milliseconds.
const CANCELLABLE_PIECE: usize = 1 << 20;

/// A file (or a pipe) whose writes fail once `cancel` is raised. It sits
/// under a `BufWriter`, so the flag is read once per buffer's worth, not
/// per byte.
struct Cancellable<W> {
    inner: W,
    cancel: &'static AtomicBool,
}

impl<W: Write> Write for Cancellable<W> {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        if self.cancel.load(Ordering::Relaxed) {
            // Not `ErrorKind::Interrupted`: `write_all` would retry it.
            return Err(io::Error::other("cancelled"));
        }
        self.inner.write(&bytes[..bytes.len().min(CANCELLABLE_PIECE)])
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

/// The folder a file at `path` goes into.
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

/// A temporary file in `dir`, readable by others like an ordinary new file
/// (tempfile's default is owner-only).
fn temp_file_in(dir: &Path) -> io::Result<tempfile::NamedTempFile> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(".rayrepl-").suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o644));
    }
    builder.tempfile_in(dir)
}

fn io_error(path: &Path, source: io::Error) -> OutputError {
    OutputError::Io { path: path.to_owned(), source }
}

/// An encoder's own error (not an I/O one) while writing `path` in `format`.
fn format_error(
    path: &Path,
    format: image::ImageFormat,
    source: impl std::error::Error + Send + Sync + 'static,
) -> OutputError {
    let hint = image::error::ImageFormatHint::Exact(format);
    let source = image::ImageError::Encoding(image::error::EncodingError::new(hint, source));
    OutputError::Encode { path: path.to_owned(), source }
}

fn encode_error(path: &Path, source: image::ImageError) -> OutputError {
    match source {
        image::ImageError::IoError(source) => io_error(path, source),
        source => OutputError::Encode { path: path.to_owned(), source },
    }
}

/// An I/O error in plain words, without Rust's `(os error 2)` suffix.
pub(crate) fn io_reason(error: &io::Error) -> String {
    match error.kind() {
        io::ErrorKind::NotFound => "no such file or folder".into(),
        io::ErrorKind::PermissionDenied => "permission denied".into(),
        io::ErrorKind::IsADirectory => "it is a folder".into(),
        io::ErrorKind::NotADirectory => "a part of the path is a file, not a folder".into(),
        io::ErrorKind::InvalidData => "it is not UTF-8 text".into(),
        io::ErrorKind::ReadOnlyFilesystem => "the file system is read-only".into(),
        io::ErrorKind::StorageFull => "the disk is full".into(),
        io::ErrorKind::QuotaExceeded => "the disk quota is used up".into(),
        io::ErrorKind::BrokenPipe => "the program reading it has stopped".into(),
        io::ErrorKind::ExecutableFileBusy | io::ErrorKind::ResourceBusy => "the file is in use".into(),
        _ => {
            let text = error.to_string();
            let plain = text.split(" (os error").next().unwrap_or(&text);
            let mut chars = plain.chars();
            chars.next().map(|first| first.to_lowercase().chain(chars).collect()).unwrap_or_default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> RgbImage {
        RgbImage::from_fn(3, 2, |x, y| image::Rgb([x as u8 * 80, y as u8 * 200, 7]))
    }

    #[test]
    fn frame_names_pad_to_four_digits_or_more() {
        assert_eq!(frame_path(Path::new("out.png"), 1, 100), PathBuf::from("out0001.png"));
        assert_eq!(frame_path(Path::new("dir/a.ppm"), 42, 12345), PathBuf::from("dir/a00042.ppm"));
        assert_eq!(frame_path(Path::new("noext"), 7, 9), PathBuf::from("noext0007"));
    }

    #[test]
    fn ppm_has_header_and_raw_bytes() {
        let mut out = Vec::new();
        write_ppm(&mut out, &sample()).expect("writing to memory");
        assert!(out.starts_with(b"P6\n3 2\n255\n"));
        assert_eq!(&out[11..], sample().as_raw().as_slice());
    }

    #[test]
    fn png_and_ppm_round_trip() {
        let dir = tempfile::tempdir().expect("temp dir");
        for name in ["a.png", "b.PPM"] {
            let path = dir.path().join(name);
            write_image(&path, &sample()).expect("write");
            let back = image::open(&path).expect("read back").into_rgb8();
            assert_eq!(back, sample());
        }
        // Only the two images: no temporary file left behind.
        assert_eq!(std::fs::read_dir(dir.path()).expect("list").count(), 2);
    }

    #[test]
    fn outputs_are_checked_before_any_work() {
        let dir = tempfile::tempdir().expect("temp dir");
        let message = |path: &Path, content| check_output(path, content).expect_err("refused").to_string();
        assert!(message(Path::new("x.jpg"), Content::Still).contains("end the name in .png or .ppm"));
        assert!(message(Path::new("x.gif"), Content::Still).contains("GIF is for animations"));
        assert_eq!(check_output(Path::new("x.GIF"), Content::Animation).ok(), Some(ImageFormat::Gif));
        assert!(message(dir.path(), Content::Still).contains("it is a folder"));
        assert!(message(Path::new("somedir/"), Content::Still).contains("it is a folder"));
        assert!(message(&dir.path().join("none/a.png"), Content::Still).contains("does not exist"));
    }

    #[test]
    fn a_replaced_file_keeps_its_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("private.png");
        std::fs::write(&path, b"old").expect("written");
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o600)).expect("chmod");
        write_image(&path, &sample()).expect("replaced");
        assert_eq!(std::fs::metadata(&path).expect("exists").permissions().mode() & 0o777, 0o600);
    }

    #[test]
    fn a_cancelled_write_leaves_the_target_as_it_was_and_no_temporary_file() {
        static RAISED: AtomicBool = AtomicBool::new(true);
        let dir = tempfile::tempdir().expect("temp dir");
        let (png, ppm, text) = (dir.path().join("a.png"), dir.path().join("b.ppm"), dir.path().join("c.ray"));
        for path in [&png, &ppm, &text] {
            std::fs::write(path, b"old").expect("written");
        }
        // Large enough that the encoders write through the buffer before the end.
        let large = RgbImage::from_fn(400, 300, |x, y| image::Rgb([x as u8, y as u8, (x ^ y) as u8]));
        for path in [&png, &ppm] {
            let error = write_image_cancellable(path, &large, &RAISED).expect_err("cancelled");
            assert!(matches!(&error, OutputError::Cancelled { path: p } if p == path), "{error:?}");
        }
        let error = write_text(&text, "camera distance 8 angle 1 end\n", &RAISED).expect_err("cancelled");
        assert_eq!(
            error.to_string(),
            format!("writing `{}` was cancelled: the file is as it was before", text.display())
        );
        for path in [&png, &ppm, &text] {
            assert_eq!(std::fs::read(path).expect("still there"), b"old");
        }
        assert_eq!(std::fs::read_dir(dir.path()).expect("list").count(), 3, "no temporary file left");
    }

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

    #[test]
    fn io_errors_read_without_os_error_numbers() {
        let busy = io::Error::from_raw_os_error(26);
        assert_eq!(io_reason(&busy), "the file is in use");
        let odd = io::Error::from_raw_os_error(71);
        assert!(!io_reason(&odd).contains("os error"), "{}", io_reason(&odd));
    }

    #[test]
    fn failed_write_names_the_path_and_leaves_nothing() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("missing-dir").join("a.png");
        let err = write_image(&path, &sample()).expect_err("no such directory");
        assert!(err.to_string().contains("missing-dir"), "{err}");
        assert!(!path.exists());
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
