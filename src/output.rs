//! Writing images and animations: PNG, PPM, animated GIF and PNG, video,
//! and the names of frames.
//!
//! Files are written atomically: into a temporary file in the target's
//! directory, then renamed over the target, so a failed or interrupted
//! write never leaves a partial image behind, and a replaced file keeps its
//! permissions and owner. A symbolic link is written through (the link
//! stays), and a file with hard links keeps its inode (see `atomic`). An animation is encoded frame by frame as the frames
//! arrive, so its memory does not grow with the number of frames.
//!
//! Read from the bottom up: `formats` names the formats, `error` says
//! why a write failed, `atomic` makes the files, `checks` refuses an
//! output before any work, `still` writes one image or a text, and
//! `frames` takes an animation's frames into `gif`, `apng`, `video`
//! or numbered images.

mod apng;
mod atomic;
mod checks;
mod error;
mod formats;
mod frame_names;
mod frames;
mod gif;
mod still;
mod video;

pub use apng::apng_bytes;
pub use atomic::INTERRUPTED_EXIT_CODE;
#[cfg(feature = "signals")]
pub(crate) use atomic::discarding_unfinished;
pub(crate) use atomic::{NEVER_CANCELLED, exit_discarding_unfinished};
pub(crate) use checks::{check_animation_output, check_output, frame_over, same_file};
pub use error::OutputError;
pub(crate) use error::io_reason;
pub use formats::Content;
pub use formats::ImageFormat;
pub use frame_names::frame_path;
pub(crate) use frames::{FrameSink, describe_files};
pub use still::write_ppm;
pub use still::{write_image, write_png};
pub(crate) use still::{write_image_cancellable, write_text};
