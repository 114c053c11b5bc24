//! The names of an animation's numbered images (`out0001.png`, ...): one
//! rule, used by the writer of the frames and by the check that none of
//! them is the scene file.

use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

/// The numbered images of `frames` (from 1, of `count` in all) named after
/// `base`, with their numbers.
pub(crate) fn frame_names(
    base: &Path,
    frames: RangeInclusive<u32>,
    count: u32,
) -> impl Iterator<Item = (u32, PathBuf)> {
    frames.map(move |k| (k, frame_path(base, k as usize, count as usize)))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_names_pad_to_four_digits_or_more() {
        assert_eq!(frame_path(Path::new("out.png"), 1, 100), PathBuf::from("out0001.png"));
        assert_eq!(frame_path(Path::new("dir/a.ppm"), 42, 12345), PathBuf::from("dir/a00042.ppm"));
        assert_eq!(frame_path(Path::new("noext"), 7, 9), PathBuf::from("noext0007"));
    }
}
