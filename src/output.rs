//! Writing images and animations: PNG, PPM, GIF, and the names of frames.
//!
//! Files are written atomically: into a temporary file in the target's
//! directory, then renamed over the target, so a failed write never leaves a
//! partial image behind.

use std::fmt;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ImageEncoder, RgbImage};
use rayon::prelude::*;

/// An image format that [`write_image`] can produce.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// PNG, 8 bits per channel.
    Png,
    /// Binary PPM (P6).
    Ppm,
}

impl ImageFormat {
    /// The format named by `path`'s extension (case-insensitive), if known.
    pub fn from_path(path: &Path) -> Option<ImageFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(ImageFormat::Png),
            "ppm" => Some(ImageFormat::Ppm),
            _ => None,
        }
    }
}

/// Why an image could not be written.
#[derive(Debug)]
pub enum OutputError {
    /// The file name's extension names no supported format.
    UnknownFormat {
        /// The path given.
        path: PathBuf,
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
}

impl fmt::Display for OutputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OutputError::UnknownFormat { path } => write!(
                f,
                "cannot write `{}`: unknown image format (use a file name ending in .png or .ppm)",
                path.display()
            ),
            OutputError::Io { path, source } => {
                write!(f, "cannot write `{}`: {}", path.display(), io_reason(source))
            }
            OutputError::Encode { path, source } => {
                write!(f, "cannot encode `{}`: {source}", path.display())
            }
            OutputError::NoFrames { path } => {
                write!(f, "cannot write `{}`: the animation has no frame", path.display())
            }
        }
    }
}

impl std::error::Error for OutputError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            OutputError::Io { source, .. } => Some(source),
            OutputError::Encode { source, .. } => Some(source),
            OutputError::UnknownFormat { .. } | OutputError::NoFrames { .. } => None,
        }
    }
}

/// Writes `image` to `path` in the format named by its extension (`.png` or
/// `.ppm`), atomically.
pub fn write_image(path: &Path, image: &RgbImage) -> Result<(), OutputError> {
    let format = ImageFormat::from_path(path).ok_or_else(|| OutputError::UnknownFormat { path: path.to_owned() })?;
    write_atomically(path, |writer| match format {
        ImageFormat::Png => write_png(writer, image).map_err(|e| encode_error(path, e)),
        ImageFormat::Ppm => write_ppm(writer, image).map_err(|e| io_error(path, e)),
    })
}

/// Writes `image` as binary PPM (P6) to `writer` (used for `-o -`).
pub fn write_ppm(writer: &mut dyn Write, image: &RgbImage) -> io::Result<()> {
    write!(writer, "P6\n{} {}\n255\n", image.width(), image.height())?;
    writer.write_all(image.as_raw())?;
    writer.flush()
}

/// Writes `image` as PNG to `writer`.
pub fn write_png(writer: &mut dyn Write, image: &RgbImage) -> image::ImageResult<()> {
    // Fast compression: large renders and 100-frame animations would
    // otherwise spend more time compressing than tracing.
    let encoder = PngEncoder::new_with_quality(writer, CompressionType::Fast, FilterType::Adaptive);
    encoder.write_image(image.as_raw(), image.width(), image.height(), image::ExtendedColorType::Rgb8)
}

/// Writes `frames` as an animated GIF looping forever, each frame shown for
/// `delay_ms` milliseconds (in steps of 10 ms, GIF's unit), atomically.
///
/// All frames share one 256-colour palette, learnt (NeuQuant) from pixels
/// spread over every frame: an animation's frames mostly show the same
/// colours, and learning a palette per frame took most of the time of a
/// 100-frame GIF. Each frame is then mapped to the palette in parallel.
pub fn write_gif(path: &Path, frames: &[RgbImage], delay_ms: u32) -> Result<(), OutputError> {
    let Some(first) = frames.first() else {
        return Err(OutputError::NoFrames { path: path.to_owned() });
    };
    let too_large = || OutputError::Io {
        path: path.to_owned(),
        source: io::Error::new(io::ErrorKind::InvalidInput, "a GIF is at most 65535 pixels wide and high"),
    };
    let width = u16::try_from(first.width()).map_err(|_| too_large())?;
    let height = u16::try_from(first.height()).map_err(|_| too_large())?;
    let delay = u16::try_from(delay_ms / 10).unwrap_or(u16::MAX);
    let palette = learn_palette(frames);
    let indexed: Vec<Vec<u8>> = frames
        .par_iter()
        .map(|frame| frame.pixels().map(|p| palette.index_of(&[p[0], p[1], p[2], 0xFF]) as u8).collect())
        .collect();
    write_atomically(path, |writer| {
        let gif_error = |e| gif_encode_error(path, e);
        let mut encoder = gif::Encoder::new(writer, width, height, &palette.color_map_rgb()).map_err(gif_error)?;
        encoder.set_repeat(gif::Repeat::Infinite).map_err(gif_error)?;
        for pixels in indexed {
            let mut frame = gif::Frame::from_indexed_pixels(width, height, pixels, None);
            frame.delay = delay;
            encoder.write_frame(&frame).map_err(gif_error)?;
        }
        Ok(())
    })
}

/// The NeuQuant sampling factor for the GIF palette, 1 (best) to 30
/// (fastest).
pub const GIF_QUANTISATION_SPEED: i32 = 10;

/// About how many pixels the GIF palette is learnt from, taken evenly from
/// all frames (as many as in two 800x600 frames).
const GIF_PALETTE_SAMPLE: usize = 960_000;

/// A 256-colour palette for all of `frames` (at least one, all the same size).
fn learn_palette(frames: &[RgbImage]) -> color_quant::NeuQuant {
    let pixels = frames.len() * frames[0].width() as usize * frames[0].height() as usize;
    let stride = pixels.div_ceil(GIF_PALETTE_SAMPLE).max(1);
    let mut sample = Vec::with_capacity(4 * pixels.div_ceil(stride));
    for (k, p) in frames.iter().flat_map(|f| f.pixels()).enumerate() {
        if k % stride == 0 {
            sample.extend_from_slice(&[p[0], p[1], p[2], 0xFF]);
        }
    }
    color_quant::NeuQuant::new(GIF_QUANTISATION_SPEED, 256, &sample)
}

/// How long each frame of an animated GIF is shown: 25 frames a second.
pub const GIF_FRAME_DELAY_MS: u32 = 40;

/// Where the frames of an animation go as they are rendered: kept for one
/// animated GIF if the file name ends in `.gif`, otherwise written at once as
/// numbered images (`spin.png` gives `spin0001.png`, ...), so that a long
/// animation does not have to fit in memory.
pub struct FrameSink {
    path: PathBuf,
    count: usize,
    gif_frames: Option<Vec<RgbImage>>,
    written: Vec<PathBuf>,
}

impl FrameSink {
    /// A sink for `count` frames named after `path`.
    pub fn new(path: &Path, count: usize) -> FrameSink {
        let gif = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("gif"));
        FrameSink {
            path: path.to_path_buf(),
            count,
            gif_frames: gif.then(|| Vec::with_capacity(count)),
            written: Vec::new(),
        }
    }

    /// Takes frame number `frame` (from 1).
    pub fn add(&mut self, frame: usize, image: RgbImage) -> Result<(), OutputError> {
        if let Some(frames) = &mut self.gif_frames {
            frames.push(image);
            return Ok(());
        }
        let path = frame_path(&self.path, frame, self.count);
        write_image(&path, &image)?;
        self.written.push(path);
        Ok(())
    }

    /// Writes what is left to write; returns the files written.
    pub fn finish(mut self) -> Result<Vec<PathBuf>, OutputError> {
        if let Some(frames) = self.gif_frames.take() {
            write_gif(&self.path, &frames, GIF_FRAME_DELAY_MS)?;
            self.written.push(self.path);
        }
        Ok(self.written)
    }
}

/// The file name of frame `k` of `n`: the frame number, zero-padded to at
/// least 4 digits (more if `n` needs them), inserted before the extension:
/// `out.png` gives `out0001.png`.
pub fn frame_path(base: &Path, k: usize, n: usize) -> PathBuf {
    let digits = n.to_string().len().max(4);
    let stem = base.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let mut name = format!("{stem}{k:0digits$}");
    if let Some(ext) = base.extension() {
        name.push('.');
        name.push_str(&ext.to_string_lossy());
    }
    base.with_file_name(name)
}

/// Runs `write` on a temporary file next to `path`, then renames it to
/// `path`. On any error the temporary file is removed and `path` untouched.
fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<&mut tempfile::NamedTempFile>) -> Result<(), OutputError>,
) -> Result<(), OutputError> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut file = temp_file_in(dir).map_err(|e| io_error(path, e))?;
    {
        let mut writer = BufWriter::new(&mut file);
        write(&mut writer)?;
        writer.flush().map_err(|e| io_error(path, e))?;
    }
    file.as_file().sync_all().map_err(|e| io_error(path, e))?;
    file.persist(path).map_err(|e| io_error(path, e.error))?;
    Ok(())
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

fn gif_encode_error(path: &Path, source: gif::EncodingError) -> OutputError {
    match source {
        gif::EncodingError::Io(source) => io_error(path, source),
        other => {
            let hint = image::error::ImageFormatHint::Exact(image::ImageFormat::Gif);
            let source = image::ImageError::Encoding(image::error::EncodingError::new(hint, other));
            OutputError::Encode { path: path.to_owned(), source }
        }
    }
}

fn encode_error(path: &Path, source: image::ImageError) -> OutputError {
    match source {
        image::ImageError::IoError(source) => io_error(path, source),
        source => OutputError::Encode { path: path.to_owned(), source },
    }
}

/// An I/O error in plain words, without Rust's `(os error 2)` suffix.
pub fn io_reason(error: &io::Error) -> String {
    match error.kind() {
        io::ErrorKind::NotFound => "no such file or folder".into(),
        io::ErrorKind::PermissionDenied => "permission denied".into(),
        io::ErrorKind::IsADirectory => "it is a directory".into(),
        io::ErrorKind::InvalidData => "it is not UTF-8 text".into(),
        io::ErrorKind::ReadOnlyFilesystem => "the file system is read-only".into(),
        io::ErrorKind::StorageFull => "the disk is full".into(),
        _ => error.to_string(),
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
    fn unknown_extension_is_a_clear_error() {
        let err = write_image(Path::new("x.jpg"), &sample()).expect_err("jpg unsupported");
        assert!(err.to_string().contains("unknown image format"), "{err}");
    }

    #[test]
    fn failed_write_names_the_path_and_leaves_nothing() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("missing-dir").join("a.png");
        let err = write_image(&path, &sample()).expect_err("no such directory");
        assert!(err.to_string().contains("missing-dir"), "{err}");
        assert!(!path.exists());
    }

    #[test]
    fn gif_round_trips_frame_count() {
        use image::AnimationDecoder;
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("anim.gif");
        write_gif(&path, &[sample(), sample(), sample()], 40).expect("write gif");
        let file = std::io::BufReader::new(std::fs::File::open(&path).expect("open"));
        let decoder = image::codecs::gif::GifDecoder::new(file).expect("decode");
        assert_eq!(decoder.into_frames().count(), 3);
    }

    #[test]
    fn one_gif_palette_keeps_the_colours_of_every_frame() {
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
        write_gif(&path, &frames, 40).expect("write gif");
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
