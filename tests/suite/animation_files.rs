//! Animation files as viewers read them: GIF, APNG and video read back by
//! independent decoders (frame count, delays, looping, pixels against the
//! PPM frames), the time of each frame, and interrupted animations.

use std::path::{Path, PathBuf};
use std::process::Stdio;

use assert_cmd::Command;
use image::RgbImage;
use predicates::str::contains;

/// Flat colours (ambient light only, kd 1): a sphere at x = time - 2 of
/// colour (200, 100, 50) before a plane of colour (0, 0, 255), so every
/// pixel is one of three colours, exactly: round(255 * 1 * 1 * c / 255) = c.
const FLAT: &str = "camera distance 10 angle 1 end
ambient 1
put sphere center time - 2, 0, 0 radius 1 kd 1 ks 0 phong 10 color 200, 100, 50 end
put plane rotation pi / 2, 0, 0 shift -3 kd 1 ks 0 phong 10 color 0, 0, 255 end
";

/// A lit scene with many shades, moving with `time`.
const SHADED: &str = "camera distance 10 angle 1 end
ambient 0.2
light vector 0.5, 0, 0.3 intensity 0.8 end
put sphere center time - 2, 0, 0 radius 1.5 kd 0.7 ks 0.4 phong 30 color 255, 60, 20 end
put plane rotation 0, 0, 0 shift -1.5 kd 0.8 ks 0 phong 10 color 40, 90, 255 end
";

fn rayrepl() -> Command {
    let mut command = Command::cargo_bin("rayrepl").expect("the binary is built");
    command.args(["--allow", "all", "-q"]);
    command
}

/// A fresh temporary folder holding `scene.ray` with `text`.
fn scene(text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let path = dir.path().join("scene.ray");
    std::fs::write(&path, text).expect("scene written");
    (dir, path)
}

/// Renders `frames` frames of the scene at `path`, 32x24, with `flags`, to `out`.
fn animate(path: &Path, frames: u32, flags: &[&str], out: &Path) {
    rayrepl()
        .arg(path)
        .args(["--width", "32", "--height", "24", "--anim", &frames.to_string()])
        .args(flags)
        .arg("-o")
        .arg(out)
        .assert()
        .success();
}

/// The numbered PPM frames of the scene at `path`: the reference pixels.
fn ppm_frames(path: &Path, frames: u32, flags: &[&str]) -> Vec<RgbImage> {
    let dir = tempfile::tempdir().expect("temporary folder");
    animate(path, frames, flags, &dir.path().join("f.ppm"));
    (1..=frames).map(|k| image::open(dir.path().join(format!("f{k:04}.ppm"))).expect("a PPM frame").to_rgb8()).collect()
}

fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

/// The frames of a GIF, its delays in milliseconds and its looping, read
/// with the `gif` crate's decoder.
fn read_gif(path: &Path) -> (Vec<RgbImage>, Vec<u32>, gif::Repeat) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(std::fs::File::open(path).expect("the GIF")).expect("a GIF");
    let (width, height) = (decoder.width() as u32, decoder.height() as u32);
    let (mut frames, mut delays) = (Vec::new(), Vec::new());
    while let Some(frame) = decoder.read_next_frame().expect("a frame decodes") {
        assert_eq!((frame.width as u32, frame.height as u32), (width, height), "whole frames");
        let rgb = frame.buffer.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
        frames.push(RgbImage::from_raw(width, height, rgb).expect("the frame's size"));
        delays.push(u32::from(frame.delay) * 10);
    }
    (frames, delays, decoder.repeat())
}

/// The frames of an APNG, each delay as (numerator, denominator) seconds,
/// the number of frames and of plays it declares, read with the `png`
/// crate's decoder.
fn read_apng(path: &Path) -> (Vec<RgbImage>, Vec<(u16, u16)>, u32, u32) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).expect("the APNG")));
    let mut reader = decoder.read_info().expect("a PNG");
    let control = *reader.info().animation_control().expect("an animated PNG");
    let (mut frames, mut delays) = (Vec::new(), Vec::new());
    let mut buffer = vec![0; reader.output_buffer_size().expect("a size")];
    for _ in 0..control.num_frames {
        let output = reader.next_frame(&mut buffer).expect("a frame decodes");
        let frame = reader.info().frame_control().expect("a frame control");
        delays.push((frame.delay_num, frame.delay_den));
        let image = RgbImage::from_raw(output.width, output.height, buffer[..output.buffer_size()].to_vec());
        frames.push(image.expect("RGB frames"));
    }
    (frames, delays, control.num_frames, control.num_plays)
}

/// The largest difference of a channel between `a` and `b`.
fn largest_difference(a: &RgbImage, b: &RgbImage) -> u8 {
    assert_eq!(a.dimensions(), b.dimensions());
    a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0)
}

#[test]
fn an_apng_holds_the_ppm_frames_exactly_with_the_asked_rate_and_plays() {
    let (dir, path) = scene(SHADED);
    let expected = ppm_frames(&path, 4, &[]);
    // .apng, and .png with --apng: the same file.
    for (name, apng) in [("a.apng", &[][..]), ("a.png", &["--apng"][..])] {
        let out = dir.path().join(name);
        animate(&path, 4, &[&["--fps", "12.5", "--loop", "3"], apng].concat(), &out);
        let (frames, delays, count, plays) = read_apng(&out);
        assert_eq!((count, plays), (4, 3), "{name}");
        // 1/12.5 s = 100/1250.
        assert_eq!(delays, [(100, 1250); 4], "{name}");
        assert_eq!(frames, expected, "{name}");
    }
    // By default 25 frames a second, looping forever (0 plays).
    let out = dir.path().join("default.apng");
    animate(&path, 2, &[], &out);
    let (_, delays, _, plays) = read_apng(&out);
    assert_eq!((delays, plays), (vec![(100, 2500); 2], 0));
}

#[test]
fn a_gif_holds_the_ppm_frames_with_the_asked_delay_and_looping() {
    let (dir, path) = scene(FLAT);
    let expected = ppm_frames(&path, 4, &[]);
    // Hand-computed: frame 2 (time 2) has the sphere's colour at the centre, the plane's at a corner.
    assert_eq!(expected[1].get_pixel(16, 12).0, [200, 100, 50]);
    assert_eq!(expected[1].get_pixel(0, 0).0, [0, 0, 255]);
    let cases: [(&[&str], u32, gif::Repeat); 3] = [
        (&[], 40, gif::Repeat::Infinite),
        (&["--fps", "20", "--loop", "2"], 50, gif::Repeat::Finite(1)),
        (&["--fps", "10", "--loop", "forever"], 100, gif::Repeat::Infinite),
    ];
    for (flags, delay, repeat) in cases {
        let out = dir.path().join("a.gif");
        animate(&path, 4, flags, &out);
        let (frames, delays, repeated) = read_gif(&out);
        assert_eq!((delays, repeated), (vec![delay; 4], repeat), "{flags:?}");
        // Three colours fit a palette of 256 exactly.
        for (k, (frame, expected)) in frames.iter().zip(&expected).enumerate() {
            assert_eq!(largest_difference(frame, expected), 0, "{flags:?}: frame {}", k + 1);
        }
    }
    // Played once: no looping extension at all.
    let once = dir.path().join("once.gif");
    animate(&path, 2, &["--loop", "1"], &once);
    let bytes = std::fs::read(&once).expect("the GIF");
    assert!(!bytes.windows(11).any(|w| w == b"NETSCAPE2.0"), "a GIF played once has no looping extension");
}

#[test]
fn a_gif_of_many_shades_stays_close_to_the_ppm_frames() {
    let (dir, path) = scene(SHADED);
    let expected = ppm_frames(&path, 3, &[]);
    let out = dir.path().join("a.gif");
    animate(&path, 3, &[], &out);
    let (frames, _, _) = read_gif(&out);
    assert_eq!(frames.len(), 3);
    for (frame, expected) in frames.iter().zip(&expected) {
        let error: u64 = frame.as_raw().iter().zip(expected.as_raw()).map(|(a, b)| u64::from(a.abs_diff(*b))).sum();
        let mean = error as f64 / frame.as_raw().len() as f64;
        assert!(mean < 2.0, "mean error {mean} levels");
        // A palette keeps serving while at most 32 pixels (or 1 in 1000) are off by more than 24 levels.
        let misfits = frame.pixels().zip(expected.pixels()).filter(|(a, b)| (0..3).any(|c| a[c].abs_diff(b[c]) > 24));
        assert!(misfits.count() <= 32);
    }
}

#[test]
fn frame_k_is_computed_at_time_start_plus_k_minus_one_steps() {
    // The sphere is there while time < 1: at times 0 and 0.5, not at 1.
    let text = FLAT.replace("put sphere", "if time < 1 then put sphere").replace("50 end\n", "50 end end\n");
    let (dir, path) = scene(&text);
    let frames = ppm_frames(&path, 3, &["--time-start", "0", "--time-step", "0.5"]);
    assert_eq!(
        frames[0].get_pixel(10, 12).0,
        [200, 100, 50],
        "time 0: the sphere at x = -2, pixel 16 - 2 * 29.3 / 10 - 0.5"
    );
    assert_eq!(frames[1].get_pixel(16, 12).0, [0, 0, 255], "time 0.5: the sphere moved on, the plane shows");
    assert_eq!(frames[2].get_pixel(10, 12).0, [0, 0, 255], "time 1: no sphere");
    for (k, time) in [(1, "0"), (2, "0.5"), (3, "1")] {
        let still = dir.path().join("still.ppm");
        rayrepl()
            .arg(&path)
            .args(["--width", "32", "--height", "24", "--time", time, "-o"])
            .arg(&still)
            .assert()
            .success();
        assert_eq!(image::open(&still).expect("still").to_rgb8(), frames[k - 1], "frame {k} is time {time}");
    }
}

#[test]
fn anim_in_a_session_takes_the_same_options() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let out = dir.path().join("s.apng");
    let script =
        format!("{FLAT}:size 32 24\n:anim 3 {} --fps 10 --loop 2 --time-start 0 --time-step 0.5\n", out.display());
    Command::cargo_bin("rayrepl").expect("built").write_stdin(script).assert().success();
    let (frames, delays, count, plays) = read_apng(&out);
    assert_eq!((count, plays, delays), (3, 2, vec![(100, 1000); 3]));
    assert_eq!(frames[0].get_pixel(10, 12).0, [200, 100, 50], "frame 1 has time 0: the sphere at x = -2");
    let refused = format!("{FLAT}:anim 3 {} --speed 2\n", out.display());
    Command::cargo_bin("rayrepl")
        .expect("built")
        .write_stdin(refused)
        .assert()
        .failure()
        .stderr(contains("`--speed` is not an option of :anim"));
}

#[test]
fn playing_options_that_would_do_nothing_are_refused() {
    let (dir, path) = scene(FLAT);
    let cases: [(&[&str], &str, &str); 6] = [
        (&["--fps", "30"], "a.gif", "--fps is for an animation: give --anim N too"),
        (&["--anim", "2", "--fps", "30"], "a.png", "numbered images do not play"),
        (&["--anim", "2", "--loop", "2"], "a.ppm", "numbered images do not play"),
        (&["--anim", "2", "--apng"], "a.gif", "an animated PNG's name ends in .png or .apng"),
        (&["--anim", "2", "--fps", "500"], "a.gif", "the frame rate must be a number from 0.01 to 100"),
        (&["--anim", "2", "--frames", "1..2"], "a.apng", "--frames writes numbered images"),
    ];
    for (flags, name, message) in cases {
        let out = dir.path().join(name);
        rayrepl().arg(&path).args(flags).arg("-o").arg(&out).assert().failure().stderr(contains(message));
    }
    assert_eq!(names_in(dir.path()), ["scene.ray"], "nothing written");
}

#[test]
fn a_video_without_ffmpeg_names_the_package_to_install() {
    let (dir, path) = scene(FLAT);
    let empty = tempfile::tempdir().expect("a folder with no programs");
    rayrepl()
        .env("PATH", empty.path())
        .arg(&path)
        .args(["--anim", "2", "-o"])
        .arg(dir.path().join("a.mp4"))
        .assert()
        .failure()
        .stderr(contains("install the package `ffmpeg`"));
    assert_eq!(names_in(dir.path()), ["scene.ray"]);
}

/// Whether `program` runs; if not, says the test that needed it is skipped.
fn installed(program: &str, test: &str) -> bool {
    let runs = std::process::Command::new(program)
        .arg("-version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|status| status.success());
    if !runs {
        eprintln!("skipped {test}: `{program}` is not installed");
    }
    runs
}

/// What ffprobe says of the video stream at `path`: codec, size, frame
/// rate and the frames it counts.
fn probe(path: &Path) -> String {
    let output = std::process::Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-select_streams", "v:0", "-of", "compact=p=0"])
        .args(["-show_entries", "stream=codec_name,width,height,r_frame_rate,nb_read_frames"])
        .arg(path)
        .output()
        .expect("ffprobe runs");
    String::from_utf8(output.stdout).expect("text").trim().to_string()
}

#[test]
fn a_video_has_every_frame_at_the_asked_rate() {
    if !installed("ffmpeg", "a_video_has_every_frame_at_the_asked_rate") || !installed("ffprobe", "the video test") {
        return;
    }
    let (dir, path) = scene(SHADED);
    // Odd sides are padded to even ones, as 4:2:0 video needs.
    let mp4 = dir.path().join("a.mp4");
    rayrepl()
        .arg(&path)
        .args(["--width", "33", "--height", "24", "--anim", "6", "--fps", "30", "-o"])
        .arg(&mp4)
        .assert()
        .success();
    assert_eq!(probe(&mp4), "codec_name=h264|width=34|height=24|r_frame_rate=30/1|nb_read_frames=6");
    // Two plays: the frames twice over.
    let twice = dir.path().join("twice.webm");
    animate(&path, 6, &["--loop", "2"], &twice);
    assert_eq!(probe(&twice), "codec_name=vp9|width=32|height=24|r_frame_rate=25/1|nb_read_frames=12");
    // The first frame decoded is close to the PPM frame (lossy, in YUV).
    let expected = ppm_frames(&path, 1, &[]);
    let first = dir.path().join("first.ppm");
    let decoded = std::process::Command::new("ffmpeg")
        .args(["-v", "error", "-i"])
        .arg(&twice)
        .args(["-frames:v", "1", "-y"])
        .arg(&first)
        .status()
        .expect("ffmpeg runs");
    assert!(decoded.success());
    let first = image::open(&first).expect("a frame").to_rgb8();
    let error: u64 = first.as_raw().iter().zip(expected[0].as_raw()).map(|(a, b)| u64::from(a.abs_diff(*b))).sum();
    assert!((error as f64 / first.as_raw().len() as f64) < 12.0, "mean error {}", error as f64 / 2304.0);
    rayrepl()
        .arg(&path)
        .args(["--anim", "2", "--loop", "forever", "-o"])
        .arg(dir.path().join("b.mp4"))
        .assert()
        .failure()
        .stderr(contains("a video file cannot say so"));
}

/// Starts a long animation of the scene at `path` to `out`, waits until
/// `started` holds of the folder's names, interrupts it with SIGINT, and
/// returns the names left.
fn interrupt(path: &Path, out: &Path, size: &str, started: impl Fn(&[String]) -> bool) -> Vec<String> {
    let dir = out.parent().expect("a folder");
    let mut child = std::process::Command::new(assert_cmd::cargo::cargo_bin("rayrepl"))
        .arg(path)
        .args(["--width", size, "--height", size, "--anim", "100000", "-o"])
        .arg(out)
        .stderr(Stdio::null())
        .spawn()
        .expect("started");
    while !started(&names_in(dir)) {
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    let killed = std::process::Command::new("kill").args(["-INT", &child.id().to_string()]).status();
    assert!(killed.expect("kill runs").success());
    assert_eq!(child.wait().expect("ended").code(), Some(130));
    names_in(dir)
}

#[test]
fn an_interrupted_animation_leaves_whole_frames_and_nothing_partial() {
    // Numbered frames: every one written is whole, and no temporary file stays.
    let (dir, path) = scene(SHADED);
    let names = interrupt(&path, &dir.path().join("f.ppm"), "400", |names| names.len() > 4);
    assert!(names.iter().all(|name| !name.ends_with(".tmp")), "{names:?}");
    let frames: Vec<_> = names.iter().filter(|name| name.starts_with('f')).collect();
    assert!(frames.len() >= 3, "{names:?}");
    for name in frames {
        let frame = image::open(dir.path().join(name)).expect("a whole frame").to_rgb8();
        assert_eq!(frame.dimensions(), (400, 400), "{name}");
    }
    // One file: none at all, whatever the format.
    let mut formats = vec!["a.apng", "a.gif"];
    if installed("ffmpeg", "the interrupted video") {
        formats.push("a.mp4");
    }
    for name in formats {
        let (dir, path) = scene(SHADED);
        let names = interrupt(&path, &dir.path().join(name), "64", |names| names.iter().any(|n| n.ends_with(".tmp")));
        assert_eq!(names, ["scene.ray"], "{name}");
    }
}
