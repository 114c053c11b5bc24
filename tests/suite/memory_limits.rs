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
