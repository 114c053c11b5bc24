//! The checks made before any work: that a path can receive an image or an
//! animation, and that it is not the scene being read.

use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

use super::atomic::{folder_of, link_target, probe_folder};
use super::error::{OutputError, io_error};
use super::formats::{Content, ImageFormat};
use super::frame_names::frame_names;
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
    // The write goes through a temporary file in the folder of the file
    // replaced (through symbolic links): make one now.
    let target = link_target(path).map_err(|e| io_error(path, e))?;
    probe_folder(folder_of(&target)).map_err(|e| io_error(path, e))?;
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

/// Whether `a` and `b` name the same existing file (through `./`, `..`,
/// symbolic links or hard links).
pub(crate) fn same_file(a: &Path, b: &Path) -> bool {
    matches!((identity(a), identity(b)), (Some(a), Some(b)) if a == b)
}

/// For numbered images (`format` holds one image), the first image of
/// `frames` (of `count` in all) named after `path` that is the existing
/// file `kept`, by any path or link: its number and name. An animation
/// must not write one of its frames over the scene it is made from.
pub(crate) fn frame_over(
    kept: &Path,
    path: &Path,
    format: ImageFormat,
    frames: RangeInclusive<u32>,
    count: u32,
) -> Option<(u32, PathBuf)> {
    let kept = identity(kept).filter(|_| format.is_still())?;
    frame_names(path, frames, count).find(|(_, frame)| identity(frame).as_ref() == Some(&kept))
}

/// What makes an existing file the one it is, whatever its name: its
/// device and inode.
#[cfg(unix)]
fn identity(path: &Path) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    std::fs::metadata(path).ok().map(|meta| (meta.dev(), meta.ino()))
}

/// What makes an existing file the one it is: its path without `./`, `..`
/// or symbolic links (hard links are not told apart here).
#[cfg(not(unix))]
fn identity(path: &Path) -> Option<PathBuf> {
    path.canonicalize().ok()
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

    #[test]
    fn the_same_file_by_any_name_or_link_and_the_frames_that_would_be_it() {
        let dir = tempfile::tempdir().expect("temp dir");
        let scene = dir.path().join("s.ray");
        std::fs::write(&scene, "").expect("written");
        let (hard, soft) = (dir.path().join("f0002.png"), dir.path().join("soft.png"));
        std::fs::hard_link(&scene, &hard).expect("linked");
        std::os::unix::fs::symlink("s.ray", &soft).expect("linked");
        assert!(same_file(&hard, &scene) && same_file(&soft, &scene) && same_file(&dir.path().join("./s.ray"), &scene));
        assert!(!same_file(&dir.path().join("none.png"), &dir.path().join("none.png")), "only existing files");
        let base = dir.path().join("f.png");
        assert_eq!(frame_over(&scene, &base, ImageFormat::Png, 1..=3, 3), Some((2, hard)));
        assert_eq!(frame_over(&scene, &base, ImageFormat::Png, 3..=3, 3), None, "frame 2 is not written");
        assert_eq!(frame_over(&scene, &base, ImageFormat::Gif, 1..=3, 3), None, "one file holds the frames");
    }
}
