//! `--export-pov`: the scene written for POV-Ray 3.7. When `povray` is
//! installed, the export is rendered and must show every object where
//! rayrepl shows it (the same object masks); skipped, saying so, otherwise.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use predicates::str::contains;

/// Objects of flat, distinct colours (ambient 1, kd 1, ks 0, no light: every
/// pixel is exactly its object's colour, or black), moved by every kind of
/// transformation.
const LAYOUT: &str = "camera distance 12 angle 0.9 end
ambient 1
put sphere center -3, 1, 0 radius 1.2 kd 1 ks 0 phong 1 color 255, 0, 0 end
put translate rotate box center 0, 0, 0 length 2, 1, 1.5 kd 1 ks 0 phong 1 color 0, 255, 0 end
  by 0.3, 0.7, 0.2 end by 2.5, 1.2, -1 end
put scale group
    sphere center 0, -1, 1 radius 0.5 kd 1 ks 0 phong 1 color 0, 0, 255 end
    box center 1, -1, 0 length 1, 1, 1 kd 1 ks 0 phong 1 color 255, 255, 0 end
  end by 1.5 end
put plane rotation 0.3, 0, 0 shift -3 kd 1 ks 0 phong 1 color 100, 100, 100 end
";

fn rayrepl() -> assert_cmd::Command {
    let mut command = assert_cmd::Command::cargo_bin("rayrepl").expect("the binary is built");
    command.args(["--allow", "all"]);
    command
}

/// A temporary folder holding `layout.ray` with [`LAYOUT`].
fn layout_scene() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let scene = dir.path().join("layout.ray");
    std::fs::write(&scene, LAYOUT).expect("scene written");
    (dir, scene)
}

/// The object each pixel shows, by its colour's index in `colours` (none: black).
fn mask(image: &image::RgbImage, colours: &[[u8; 3]]) -> Vec<Option<usize>> {
    image.pixels().map(|p| colours.iter().position(|c| (0..3).all(|k| c[k].abs_diff(p[k]) <= 2))).collect()
}

#[test]
fn the_export_renders_in_povray_with_the_same_layout() {
    let (dir, scene) = layout_scene();
    let pov = dir.path().join("layout.pov");
    rayrepl()
        .arg(&scene)
        .arg("--export-pov")
        .arg(&pov)
        .assert()
        .success()
        .stderr(contains("2 spheres, 1 plane, 2 boxes, 0 lights"));
    let text = std::fs::read_to_string(&pov).expect("the export");
    assert!(text.contains("#version 3.7;") && text.contains("What POV-Ray cannot match exactly"));
    assert_eq!(text.lines().filter(|line| line.starts_with("box {")).count(), 2);
    let runs = Command::new("povray").arg("--version").stdout(Stdio::null()).stderr(Stdio::null()).status();
    if !runs.is_ok_and(|status| status.success()) {
        eprintln!("skipped the POV-Ray render of the export: `povray` is not installed (apt install povray)");
        return;
    }
    let (width, height) = (160, 120);
    let ours = dir.path().join("ours.png");
    rayrepl().arg(&scene).args(["--width", "160", "--height", "120", "-q", "-o"]).arg(&ours).assert().success();
    let theirs = dir.path().join("theirs.png");
    let rendered = Command::new("povray")
        .arg(format!("+I{}", pov.display()))
        .arg(format!("+O{}", theirs.display()))
        .args([format!("+W{width}"), format!("+H{height}")])
        .args(["-A", "-D", "-V", "-GA", "File_Gamma=1.0"])
        .output()
        .expect("povray runs");
    assert!(rendered.status.success(), "{}", String::from_utf8_lossy(&rendered.stderr));
    let colours = [[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 0], [100, 100, 100], [0, 0, 0]];
    let ours = mask(&image::open(&ours).expect("rayrepl's").to_rgb8(), &colours);
    let theirs = mask(&image::open(&theirs).expect("POV-Ray's").to_rgb8(), &colours);
    for (k, colour) in colours.iter().enumerate() {
        assert!(ours.contains(&Some(k)), "rayrepl shows colour {colour:?}");
    }
    let differing = ours.iter().zip(&theirs).filter(|(a, b)| a != b).count();
    // Only pixels on an edge may fall on either side of it.
    assert!(differing * 100 < ours.len(), "{differing} of {} pixels show another object", ours.len());
}

#[test]
fn export_pov_is_refused_with_flags_it_would_ignore() {
    let (dir, scene) = layout_scene();
    let pov = dir.path().join("a.pov");
    for flags in [&["--anim", "3"][..], &["-o", "x.png"], &["--check"]] {
        rayrepl().arg(&scene).arg("--export-pov").arg(&pov).args(flags).assert().code(2);
    }
    assert!(!Path::new(&pov).exists());
    rayrepl().arg(&scene).args(["--export-pov", "-"]).assert().success().stdout(contains("#version 3.7;"));
}
