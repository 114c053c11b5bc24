//! Video (MP4 with H.264, WebM with VP9), made by the `ffmpeg` program: the
//! frames are streamed to it raw as they arrive, so nothing is kept here.
//! Hand-rolled around `std::process` rather than bound to libav: ffmpeg's
//! command line is stable and everywhere, and its libraries would make
//! every build need their development packages.

use std::io::{self, Read, Write};
use std::path::Path;
use std::process::{Child, ChildStdin, Command, ExitStatus, Stdio};
use std::sync::atomic::AtomicBool;
use std::thread::JoinHandle;
use std::time::Duration;

use image::RgbImage;

use super::atomic::{Cancellable, PendingFile};
use super::error::{OutputError, io_error};
use super::formats::ImageFormat;
use crate::playback::{Loops, Playback};

/// The program that encodes videos.
const FFMPEG: &str = "ffmpeg";

/// Checks that `ffmpeg` can be run, before any work on a video for `path`.
pub(super) fn check_ffmpeg(path: &Path) -> Result<(), OutputError> {
    let ran =
        Command::new(FFMPEG).arg("-version").stdin(Stdio::null()).stdout(Stdio::null()).stderr(Stdio::null()).status();
    match ran {
        Ok(status) if status.success() => Ok(()),
        _ => Err(OutputError::NoFfmpeg { path: path.to_owned() }),
    }
}

/// A video being encoded by an `ffmpeg` process.
pub(super) struct VideoStream {
    /// Before `pending`: an unfinished ffmpeg is stopped before its file is
    /// removed, or it could make the file again.
    ffmpeg: Ffmpeg,
    /// The file ffmpeg writes: one play of the frames.
    pending: PendingFile,
    format: ImageFormat,
    /// How many plays the final file holds.
    plays: u32,
    width: u32,
    height: u32,
}

impl VideoStream {
    /// Starts ffmpeg on a video at `path` in `format` (MP4 or WebM) of frames
    /// the size of `first`, played as `playback` says (a count of plays is
    /// written out in full; a video cannot loop forever, which
    /// [`check_animation_output`](super::checks::check_animation_output) refuses before), until `cancel` is raised.
    pub(super) fn start(
        path: &Path,
        format: ImageFormat,
        first: &RgbImage,
        playback: &Playback,
        cancel: &'static AtomicBool,
    ) -> Result<VideoStream, OutputError> {
        let (pending, writer) = PendingFile::create(path, cancel)?;
        // ffmpeg opens the file by name; the writer is not needed.
        drop(writer);
        let (width, height) = first.dimensions();
        let mut command = ffmpeg_command();
        command
            .args(["-f", "rawvideo", "-pix_fmt", "rgb24", "-video_size", &format!("{width}x{height}")])
            .args(["-framerate", &playback.fps().to_string(), "-i", "pipe:0"])
            // 4:2:0 video needs even sides: pad with one black column or row.
            .args(["-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p"])
            .args(encoder_arguments(format))
            .arg(&pending.temp_path)
            .stdin(Stdio::piped());
        let ffmpeg = Ffmpeg::spawn(&mut command, path, cancel)?;
        let plays = match playback.loops {
            Some(Loops::Times(times)) => times,
            _ => 1,
        };
        Ok(VideoStream { ffmpeg, pending, format, plays, width, height })
    }

    /// Sends the next frame to ffmpeg.
    pub(super) fn add(&mut self, image: &RgbImage) -> Result<(), OutputError> {
        if image.dimensions() != (self.width, self.height) {
            let different = io::Error::new(io::ErrorKind::InvalidInput, "the frames of a video must all be one size");
            return Err(io_error(&self.pending.path, different));
        }
        let stdin = self.ffmpeg.stdin.as_mut().expect("frames come before finish");
        match stdin.write_all(image.as_raw()) {
            Ok(()) => Ok(()),
            Err(_) if self.pending.cancelled() => Err(OutputError::Cancelled { path: self.pending.path.clone() }),
            // ffmpeg stopped: what it said is the reason.
            Err(_) => Err(self.ffmpeg.failure(&self.pending.path)),
        }
    }

    /// Lets ffmpeg end the video and puts it in place, repeated `plays`
    /// times.
    pub(super) fn finish(mut self) -> Result<(), OutputError> {
        drop(self.ffmpeg.stdin.take());
        let status = self.ffmpeg.wait(&self.pending)?;
        if !status.success() {
            return Err(self.ffmpeg.failure(&self.pending.path));
        }
        if self.plays == 1 {
            return self.pending.commit();
        }
        repeat(&self.pending.temp_path, &self.pending.path, self.plays, self.format, self.pending.cancel)?.commit()
    }
}

/// The video at `once` played `plays` times over, for the file `path`, by a
/// second ffmpeg that copies the streams; it is stopped when `cancel` is
/// raised (a long video takes a while), and then nothing is left behind.
fn repeat(
    once: &Path,
    path: &Path,
    plays: u32,
    format: ImageFormat,
    cancel: &'static AtomicBool,
) -> Result<PendingFile, OutputError> {
    let (repeated, writer) = PendingFile::create(path, cancel)?;
    drop(writer);
    let mut command = ffmpeg_command();
    command
        .args(["-stream_loop", &(plays - 1).to_string(), "-i"])
        .arg(once)
        .args(["-c", "copy", "-f", container(format)])
        .arg(&repeated.temp_path)
        .stdin(Stdio::null());
    // After `repeated`, so dropped before it: stopped before its file goes.
    let mut ffmpeg = Ffmpeg::spawn(&mut command, path, cancel)?;
    if !ffmpeg.wait(&repeated)?.success() {
        return Err(ffmpeg.failure(path));
    }
    Ok(repeated)
}

/// The running ffmpeg of a video: frames go to its standard input.
struct Ffmpeg {
    child: Child,
    /// Closed when the frames end.
    stdin: Option<Cancellable<ChildStdin>>,
    /// What ffmpeg says on stderr, read as it comes so that it never blocks.
    messages: Option<JoinHandle<String>>,
}

/// How often a wait for ffmpeg to end looks at the cancel flag.
const CANCEL_CHECK: Duration = Duration::from_millis(20);

impl Ffmpeg {
    /// Starts `command` (from [`ffmpeg_command`]), for the file `path`; its
    /// standard input, if piped, fails once `cancel` is raised.
    fn spawn(command: &mut Command, path: &Path, cancel: &'static AtomicBool) -> Result<Ffmpeg, OutputError> {
        let mut child = command.spawn().map_err(|_| OutputError::NoFfmpeg { path: path.to_owned() })?;
        let stdin = child.stdin.take().map(|inner| Cancellable { inner, cancel });
        let messages = child.stderr.take().map(read_all_in_background);
        Ok(Ffmpeg { child, stdin, messages })
    }

    /// Waits for ffmpeg to end the video it writes into `pending`, or for
    /// `pending`'s cancel flag (encoding the last frames of a large video
    /// takes a while).
    fn wait(&mut self, pending: &PendingFile) -> Result<ExitStatus, OutputError> {
        loop {
            if let Some(status) = self.child.try_wait().map_err(|e| io_error(&pending.path, e))? {
                return Ok(status);
            }
            if pending.cancelled() {
                return Err(OutputError::Cancelled { path: pending.path.clone() });
            }
            std::thread::sleep(CANCEL_CHECK);
        }
    }

    /// Why ffmpeg failed on the video at `path`, in its own words, once it
    /// has ended.
    fn failure(&mut self, path: &Path) -> OutputError {
        drop(self.stdin.take());
        let _ = self.child.wait();
        let said = self.messages.take().and_then(|reading| reading.join().ok()).unwrap_or_default();
        let said = said.trim();
        let message = if said.is_empty() { "it stopped without saying why" } else { said };
        OutputError::Ffmpeg { path: path.to_owned(), message: message.to_string() }
    }
}

impl Drop for Ffmpeg {
    /// An unfinished video (cancelled, failed): ffmpeg, if still running, is
    /// stopped.
    fn drop(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

/// ffmpeg, quiet but for errors, overwriting the temporary file made for
/// it, and in a process group of its own: Ctrl-C in a session cancels the
/// animation, which then stops ffmpeg itself.
fn ffmpeg_command() -> Command {
    let mut command = Command::new(FFMPEG);
    command.args(["-hide_banner", "-loglevel", "error", "-y"]).stdout(Stdio::null()).stderr(Stdio::piped());
    #[cfg(unix)]
    {
        use std::os::unix::process::CommandExt;
        command.process_group(0);
    }
    command
}

/// ffmpeg's container name for `format`.
fn container(format: ImageFormat) -> &'static str {
    match format {
        ImageFormat::Webm => "webm",
        _ => "mp4",
    }
}

/// The encoder and container for `format`: H.264 in MP4 (played everywhere,
/// the index at the front for the web), or VP9 in WebM (open, for the web).
/// x264 looks 10 frames ahead rather than the preset's 30, so that its
/// memory stops growing after a few frames (see BENCHMARKS.md).
fn encoder_arguments(format: ImageFormat) -> Vec<&'static str> {
    let codec: &[&str] = match format {
        ImageFormat::Webm => {
            &["-c:v", "libvpx-vp9", "-crf", "32", "-b:v", "0", "-deadline", "realtime", "-cpu-used", "8"]
        }
        _ => &[
            "-c:v",
            "libx264",
            "-preset",
            "fast",
            "-crf",
            "18",
            "-x264-params",
            "rc-lookahead=10",
            "-movflags",
            "+faststart",
        ],
    };
    codec.iter().copied().chain(["-f", container(format)]).collect()
}

/// Reads all of `stream` on a thread of its own.
fn read_all_in_background(mut stream: impl Read + Send + 'static) -> JoinHandle<String> {
    std::thread::spawn(move || {
        let mut text = String::new();
        let _ = stream.read_to_string(&mut text);
        text
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cancel flag raised from the start.
    static RAISED: AtomicBool = AtomicBool::new(true);

    #[test]
    fn ctrl_c_stops_the_pass_that_repeats_a_video_and_leaves_nothing() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let once = dir.path().join("once.mp4");
        let made = Command::new(FFMPEG)
            .args(["-loglevel", "error", "-f", "lavfi", "-i", "color=c=red:s=32x24:d=0.2", "-c:v", "libx264"])
            .arg(&once)
            .status();
        if !made.is_ok_and(|status| status.success()) {
            eprintln!("skipped: ffmpeg with libx264 is not installed");
            return;
        }
        // Twenty thousand plays take ffmpeg about a second.
        let path = dir.path().join("looped.mp4");
        let result = repeat(&once, &path, 20_000, ImageFormat::Mp4, &RAISED);
        assert!(matches!(result, Err(OutputError::Cancelled { .. })), "not cancelled");
        let left: Vec<_> =
            std::fs::read_dir(dir.path()).expect("the folder").map(|e| e.expect("an entry").file_name()).collect();
        assert_eq!(left, ["once.mp4"]);
    }
}
