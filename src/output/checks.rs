//! The checks made before any work: that a path can receive an image or an
//! animation, and that it is not the scene being read.

use std::path::Path;

use super::atomic::{folder_of, temp_file_in};
use super::error::{OutputError, io_error};
use super::formats::{Content, ImageFormat};
use super::video;
use crate::playback::{AnimationOptions, Loops};

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

#[cfg(test)]
mod tests {
    use super::*;

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
}
