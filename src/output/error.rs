//! Why an image could not be written: the error type and its plain words.

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};

use super::formats::Content;

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

pub(super) fn io_error(path: &Path, source: io::Error) -> OutputError {
    OutputError::Io { path: path.to_owned(), source }
}

/// An encoder's own error (not an I/O one) while writing `path` in `format`.
pub(super) fn format_error(
    path: &Path,
    format: image::ImageFormat,
    source: impl std::error::Error + Send + Sync + 'static,
) -> OutputError {
    let hint = image::error::ImageFormatHint::Exact(format);
    let source = image::ImageError::Encoding(image::error::EncodingError::new(hint, source));
    OutputError::Encode { path: path.to_owned(), source }
}

pub(super) fn encode_error(path: &Path, source: image::ImageError) -> OutputError {
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

    #[test]
    fn io_errors_read_without_os_error_numbers() {
        let busy = io::Error::from_raw_os_error(26);
        assert_eq!(io_reason(&busy), "the file is in use");
        let odd = io::Error::from_raw_os_error(71);
        assert!(!io_reason(&odd).contains("os error"), "{}", io_reason(&odd));
    }
}
