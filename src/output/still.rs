//! Writing a still image (PNG or PPM) or a text file, atomically.

use std::io::{self, Write};
use std::path::Path;
use std::sync::atomic::AtomicBool;

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ImageEncoder, RgbImage};

use super::atomic::{NEVER_CANCELLED, PendingFile};
use super::checks::check_output;
use super::error::{OutputError, encode_error, io_error};
use super::formats::{Content, ImageFormat};

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
pub fn write_ppm(writer: &mut dyn Write, image: &RgbImage) -> io::Result<()> {
    write!(writer, "P6\n{} {}\n255\n", image.width(), image.height())?;
    writer.write_all(image.as_raw())?;
    writer.flush()
}

/// Writes `image` as PNG to `writer`: the bytes of every PNG file the
/// program writes, and of the browser playground's downloads (`web/`).
pub fn write_png(writer: &mut dyn Write, image: &RgbImage) -> image::ImageResult<()> {
    // Fast compression: large renders and 100-frame animations would
    // otherwise spend more time compressing than tracing.
    let encoder = PngEncoder::new_with_quality(writer, CompressionType::Fast, FilterType::Adaptive);
    encoder.write_image(image.as_raw(), image.width(), image.height(), image::ExtendedColorType::Rgb8)
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// A small image whose pixels all differ (the frames' tests use it too).
    pub(in crate::output) fn sample() -> RgbImage {
        RgbImage::from_fn(3, 2, |x, y| image::Rgb([x as u8 * 80, y as u8 * 200, 7]))
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
    fn a_symbolic_link_stays_a_link_and_its_file_gets_the_image() {
        use std::os::unix::fs::PermissionsExt;
        let (dir, elsewhere) = (tempfile::tempdir().expect("temp dir"), tempfile::tempdir().expect("temp dir"));
        let target = elsewhere.path().join("real.png");
        std::fs::write(&target, b"old").expect("written");
        std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o640)).expect("chmod");
        let link = dir.path().join("link.png");
        std::os::unix::fs::symlink(&target, &link).expect("linked");
        // A relative link, through the first one, and one to a file not made yet.
        let relative = dir.path().join("relative.png");
        std::os::unix::fs::symlink("link.png", &relative).expect("linked");
        let dangling = dir.path().join("dangling.png");
        std::os::unix::fs::symlink("made.png", &dangling).expect("linked");
        for path in [&link, &relative, &dangling] {
            write_image(path, &sample()).expect("written through");
            assert!(std::fs::symlink_metadata(path).expect("there").file_type().is_symlink(), "{path:?}");
        }
        assert_eq!(image::open(&target).expect("the target is the image").into_rgb8(), sample());
        assert_eq!(std::fs::metadata(&target).expect("there").permissions().mode() & 0o777, 0o640);
        assert_eq!(image::open(dir.path().join("made.png")).expect("made").into_rgb8(), sample());
        assert_eq!(std::fs::read_dir(dir.path()).expect("list").count(), 4, "no temporary file left");
        assert_eq!(std::fs::read_dir(elsewhere.path()).expect("list").count(), 1, "no temporary file left");
    }

    #[test]
    fn a_hard_linked_output_keeps_its_inode_and_every_name_sees_the_image() {
        use std::os::unix::fs::MetadataExt;
        let dir = tempfile::tempdir().expect("temp dir");
        let (first, second) = (dir.path().join("a.png"), dir.path().join("b.png"));
        std::fs::write(&first, vec![7; 100_000]).expect("written");
        std::fs::hard_link(&first, &second).expect("linked");
        let inode = std::fs::metadata(&first).expect("there").ino();
        write_image(&second, &sample()).expect("written in place");
        for path in [&first, &second] {
            assert_eq!(std::fs::metadata(path).expect("there").ino(), inode, "{path:?}");
            assert_eq!(image::open(path).expect("the image, whole and no longer").into_rgb8(), sample());
        }
        assert_eq!(std::fs::read_dir(dir.path()).expect("list").count(), 2, "no temporary file left");
    }

    #[test]
    fn a_replaced_file_keeps_its_owner_where_the_process_may_give_it() {
        use std::os::unix::fs::MetadataExt;
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("theirs.png");
        std::fs::write(&path, b"old").expect("written");
        if std::os::unix::fs::chown(&path, Some(4321), Some(4321)).is_err() {
            eprintln!("not root: only root gives a file to another owner; skipped");
            return;
        }
        write_image(&path, &sample()).expect("replaced");
        let meta = std::fs::metadata(&path).expect("there");
        assert_eq!((meta.uid(), meta.gid()), (4321, 4321));
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

    #[test]
    fn failed_write_names_the_path_and_leaves_nothing() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("missing-dir").join("a.png");
        let err = write_image(&path, &sample()).expect_err("no such directory");
        assert!(err.to_string().contains("missing-dir"), "{err}");
        assert!(!path.exists());
    }
}
