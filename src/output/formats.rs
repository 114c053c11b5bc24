//! The formats rayrepl writes, named by a file's extension, and what a file
//! will hold.

use std::path::Path;

/// An image format rayrepl writes, named by a file's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
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
    pub(super) fn is_still(self) -> bool {
        matches!(self, ImageFormat::Png | ImageFormat::Ppm)
    }

    /// Whether one file of the format holds all the frames of an animation.
    pub fn holds_every_frame(self) -> bool {
        !self.is_still()
    }

    /// The format's name in messages.
    pub(super) fn name(self) -> &'static str {
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
