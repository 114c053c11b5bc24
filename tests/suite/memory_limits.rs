//! Memory stays bounded, or running out of it is a message (issue 35,
//! points 8 and 9): explaining a pixel of any depth and any number of
//! samples keeps a bounded record of it, and a scene too large for the
//! memory the process may use is refused with what it would need, on the
//! command line and in a session, never by an abort.

use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

use crate::common::limited::run_limited_to;

/// Two facing mirrors that reflect nearly everything: every ray from the
/// camera bounces between them down to the last reflection.
const MIRRORS: &str = "camera distance 3 angle 1 end
ambient 0.2
light vector 0, 1, 0.3 intensity 0.5 end
put plane rotation 0, 0, -pi / 2 shift -5 kd 0.3 ks 0.9 phong 10 color 200, 150, 100 end
put plane rotation 0, 0, pi / 2 shift -5 kd 0.3 ks 0.9 phong 10 color 100, 150, 200 end
";

/// The most a process may use in these tests, in KiB: far below what an
/// unbounded record of the paths or an unchecked scene would take.
const SMALL_KIB: u64 = 400 << 10;

/// The deepest and the most sampled explanation the limits allow, on a
/// 2x1 image (the left pixel looks towards a mirror).
const DEEPEST: [&str; 8] = ["--width", "2", "--height", "1", "--depth", "1000", "--samples", "4096"];

/// A scene file holding `text` in `folder`.
fn scene_file(folder: &Path, name: &str, text: &str) -> PathBuf {
    let path = folder.join(name);
    std::fs::write(&path, text).expect("the scene is written");
    path
}

/// The standard error of `output`, shortened, for assertion messages.
fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).chars().take(2000).collect()
}

/// Pixel `(x, y)` of a binary PPM.
fn ppm_pixel(bytes: &[u8], x: usize, y: usize) -> [u8; 3] {
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(64)]).to_string();
    let header: Vec<&str> = text.split_whitespace().take(4).collect();
    let width: usize = header[1].parse().expect("a width");
    let start = header.iter().map(|part| part.len() + 1).sum::<usize>();
    let at = start + (y * width + x) * 3;
    [bytes[at], bytes[at + 1], bytes[at + 2]]
}

#[test]
fn explaining_4096_samples_of_1000_reflections_keeps_a_bounded_record() {
    let folder = tempfile::tempdir().expect("a temporary folder");
    let scene = scene_file(folder.path(), "mirrors.ray", MIRRORS);
    let scene = scene.to_str().expect("a UTF-8 path");
    let explain = [&[scene, "--explain", "0,0", "--json"][..], &DEEPEST].concat();
    let output = run_limited_to(SMALL_KIB, &explain, "");
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let json: Value = serde_json::from_slice(&output.stdout).expect("one JSON object");
    let samples = json["samples"].as_array().expect("the recorded samples");
    assert_eq!(samples.len(), 8, "the first samples in full");
    assert_eq!(json["more_samples"]["count"], 4088);
    for sample in samples {
        assert_eq!(sample["path"].as_array().map(Vec::len), Some(16), "the first rays of each path");
        assert_eq!(sample["more_reflections"], 985, "the camera ray, 15 reflections shown, 985 counted");
    }
    assert_eq!(json["more_reflections"], 985);
    assert!(json["note"].as_str().is_some_and(|note| note.contains("only the paths of the first 8 samples")));
    // The bytes are those of the render.
    let image = folder.path().join("mirrors.ppm");
    let render = [&[scene, "-q", "-o", image.to_str().expect("UTF-8")][..], &DEEPEST].concat();
    let rendered = run_limited_to(SMALL_KIB, &render, "");
    assert_eq!(rendered.status.code(), Some(0), "{}", stderr(&rendered));
    let pixel = ppm_pixel(&std::fs::read(&image).expect("the image"), 0, 0);
    assert_eq!(json["rgb"], serde_json::json!(pixel));
    // In words, the same cut, said.
    let words = run_limited_to(SMALL_KIB, &[&[scene, "--explain", "0,0"][..], &DEEPEST].concat(), "");
    let text = String::from_utf8_lossy(&words.stdout);
    assert_eq!(words.status.code(), Some(0), "{}", stderr(&words));
    assert_eq!(text.matches("... and 985 more reflections, traced but not shown").count(), 8, "{text}");
    assert!(text.contains("... and 4088 more samples (9 to 4096), traced but not shown"), "{text}");
    assert!(text.contains("note: only the paths of the first 8 samples"), "{text}");
    let [r, g, b] = pixel;
    assert!(text.contains(&format!("rgb ({r}, {g}, {b}) = round(255 × the average of 4096 samples, (")), "{text}");
}

#[test]
fn pick_of_4096_samples_of_1000_reflections_keeps_a_bounded_record() {
    let script = format!("{MIRRORS}:depth 1000\n:samples 4096\n:render 2 1\n:pick 0 0\n:pick 1 0\n");
    let output = run_limited_to(SMALL_KIB, &[], &script);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let out = String::from_utf8_lossy(&output.stdout);
    assert_eq!(out.matches("... and 4088 more samples").count(), 2, "{out}");
    assert!(!out.contains("changed since"), "{out}");
}

/// 2^20 = 1,048,576 rotated boxes, from a recursion 20 calls deep: about
/// 190 MB to evaluate, 520 MB to render.
const MILLION_BOXES: &str = "camera distance 30 angle 1 end
ambient 0.2
light vector 1, 1, 1 intensity 1 end
proc tree(d, x, y)
  if d > 0 then
    tree(d - 1, x * 2, y + 1)
    tree(d - 1, x * 2 + 1, y + 1)
  else
    put rotate box center x * 0.0001, y * 0.01, 0 length 0.005, 0.005, 0.005
      kd 0.7 ks 0.2 phong 10 color 200, 100, 50 end by 0.3, 0.2, 0.1 end
  end
end
tree(20, 0, 0)
";

/// Room to evaluate [`MILLION_BOXES`] but not to render it, in KiB (on two
/// threads: each thread adds its stack and its allocator's arena to the
/// address space `ulimit -v` counts).
const EVALUATION_ONLY_KIB: u64 = 580 << 10;

/// The message of a scene too large for the memory.
const NOT_ENOUGH: &str = "not enough memory for 1048576 primitives: about ";

/// The files in `folder`, sorted.
fn files_in(folder: &Path) -> Vec<String> {
    let entries = std::fs::read_dir(folder).expect("the folder is read");
    let mut names: Vec<String> =
        entries.map(|entry| entry.expect("an entry").file_name().to_string_lossy().into()).collect();
    names.sort();
    names
}

#[test]
fn a_scene_too_large_for_the_memory_is_a_message_on_the_command_line() {
    let folder = tempfile::tempdir().expect("a temporary folder");
    let scene = scene_file(folder.path(), "boxes.ray", MILLION_BOXES);
    let scene = scene.to_str().expect("a UTF-8 path");
    let size = ["--width", "64", "--height", "48", "--threads", "2"];
    for output in ["boxes.png", "frames.gif"] {
        let target = folder.path().join(output);
        let mut args = vec![scene, "-q", "-o", target.to_str().expect("UTF-8")];
        args.extend(size);
        if output.ends_with(".gif") {
            args.extend(["--anim", "2"]);
        }
        let run = run_limited_to(EVALUATION_ONLY_KIB, &args, "");
        let message = stderr(&run);
        assert_eq!(run.status.code(), Some(1), "{output}: {message}");
        assert!(message.starts_with(&format!("rayrepl: {NOT_ENOUGH}")) && message.contains(" GB needed"), "{message}");
        assert_eq!(files_in(folder.path()), ["boxes.ray"], "{output}: nothing written, nothing left");
    }
}

#[test]
fn a_scene_too_large_for_the_memory_is_a_message_in_a_session_that_goes_on() {
    let folder = tempfile::tempdir().expect("a temporary folder");
    let scene = scene_file(folder.path(), "boxes.ray", MILLION_BOXES);
    let saved = folder.path().join("saved.png");
    let script = format!(":load {}\n:save {} 64 48\n:render 64 48\nprint 6 * 7\n", scene.display(), saved.display());
    // `--keep-going`: the script runs on after an error, as a typed session does.
    let run = run_limited_to(EVALUATION_ONLY_KIB, &["--keep-going", "--threads", "2"], &script);
    let (out, message) = (String::from_utf8_lossy(&run.stdout), stderr(&run));
    let everything = format!("{out}{message}");
    assert_eq!(everything.matches(NOT_ENOUGH).count(), 2, "{everything}");
    assert!(everything.contains("42"), "the session goes on: {everything}");
    assert_eq!(run.status.code(), Some(1), "the errors said at the end: {everything}");
    assert_eq!(files_in(folder.path()), ["boxes.ray"], "nothing written, nothing left");
}

#[test]
fn a_program_whose_evaluation_runs_out_of_memory_is_an_error_at_its_construct() {
    // Room for neither the million boxes' evaluation nor their render.
    let folder = tempfile::tempdir().expect("a temporary folder");
    let scene = scene_file(folder.path(), "boxes.ray", MILLION_BOXES);
    let run = run_limited_to(120 << 10, &["--check", scene.to_str().expect("a UTF-8 path")], "");
    let message = stderr(&run);
    assert_eq!(run.status.code(), Some(1), "{message}");
    assert!(message.starts_with("error: not enough memory for "), "{message}");
    assert!(message.contains("boxes.ray:9:16") && message.contains("no memory for these"), "{message}");
}
