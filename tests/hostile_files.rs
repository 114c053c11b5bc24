//! Issue 35, points 1, 4 and 5, run through the binary: a scene file is
//! never written over (by a frame's name, an export, a session's `:save`
//! or `:anim`), an output that is a link stays one, an export holds only
//! numbers POV-Ray reads, and a time that is not a finite number is an
//! error, never 0.

use std::path::{Path, PathBuf};

use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

/// A small scene that reads `time`, in the order a file needs.
const SCENE: &str = "camera distance 8 angle 1 end
ambient 0.2
light vector 0, 1, 1 intensity 1 end
print time
put sphere center 0, 0, 0 radius 1 kd 0.5 ks 0.5 phong 10 color 200, 100, 50 end
";

/// The binary, with the scene checks off and a tiny picture.
fn rayrepl() -> assert_cmd::Command {
    let mut command = assert_cmd::Command::cargo_bin("rayrepl").expect("the binary is built");
    command.args(["--allow", "all", "--width", "8", "--height", "6"]);
    command
}

/// A fresh folder, the current directory of the runs.
fn folder() -> tempfile::TempDir {
    tempfile::tempdir().expect("a temporary folder")
}

/// Writes `text` to `name` in `dir`; gives its path.
fn file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("written");
    path
}

/// The names in `dir`, sorted.
fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("listed")
        .map(|entry| entry.expect("an entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

// Point 5: a time that is not a finite number.

#[test]
fn an_animation_whose_frame_time_overflows_is_refused_naming_the_frame() {
    let dir = folder();
    file(dir.path(), "t.ray", SCENE);
    rayrepl()
        .current_dir(dir.path())
        .args(["t.ray", "--anim", "3", "--time-start", "1e308", "--time-step", "1e308", "-o", "f.png"])
        .assert()
        .code(2)
        .stderr(contains(
            "frame 2 would have time = 1e308 + 1 * 1e308, which is not a finite number: \
             give a smaller --time-start or --time-step",
        ))
        .stderr(contains("time = 0").not());
    assert_eq!(names_in(dir.path()), ["t.ray"], "no frame written");
}

#[test]
fn a_session_animation_whose_frame_time_overflows_is_refused_naming_the_frame() {
    let dir = folder();
    file(dir.path(), "t.ray", SCENE);
    rayrepl()
        .current_dir(dir.path())
        .write_stdin(":load t.ray\n:anim 3 g.png --time-start 1e308 --time-step 1e308\n")
        .assert()
        .code(1)
        .stderr(contains("frame 2 would have time = 1e308 + 1 * 1e308, which is not a finite number"))
        .stdout(contains("time = 0").not());
    assert_eq!(names_in(dir.path()), ["t.ray"], "no frame written");
}

#[test]
fn a_time_that_is_not_finite_is_refused_by_the_flag_and_the_command() {
    let dir = folder();
    file(dir.path(), "t.ray", SCENE);
    rayrepl()
        .current_dir(dir.path())
        .args(["t.ray", "--time", "1e309", "-o", "x.png"])
        .assert()
        .code(2)
        .stderr(contains("the time must be a finite number"));
    rayrepl()
        .current_dir(dir.path())
        .write_stdin(":load t.ray\n:time inf\n")
        .assert()
        .code(1)
        .stderr(contains("the time must be a finite number"));
    assert_eq!(names_in(dir.path()), ["t.ray"]);
}
