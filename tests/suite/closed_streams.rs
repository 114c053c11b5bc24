//! Standard error that cannot be written (issue "nothing lost, nothing
//! crashes", point 2): a full disk fails the run with the outputs complete,
//! a closed pipe ends it quietly with status 141; never a panic.

use std::fs::File;
use std::path::Path;
use std::process::{Command, Stdio};

use crate::common::interrupt::names_in;

/// A small scene that prints one line, and a light so nothing warns.
const SCENE: &str = "\
camera distance 10 angle 0.8 end
ambient 0.2
light vector 0.5, 0, -0.5 intensity 0.8 end
put sphere center 0, 0, 0 radius 2 kd 0.7 ks 0.3 phong 20 color 255, 80, 40 end
print 1 + 1
";

/// `rayrepl` on `scene.ray` (holding [`SCENE`]) in a fresh folder with
/// `args`, standard error going to `stderr`; its status and the folder.
fn run(args: &[&str], stderr: Stdio) -> (Option<i32>, tempfile::TempDir) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    std::fs::write(dir.path().join("scene.ray"), SCENE).expect("the scene is written");
    let mut child = Command::new(env!("CARGO_BIN_EXE_rayrepl"))
        .current_dir(dir.path())
        .arg("scene.ray")
        .args(args)
        .stdout(Stdio::null())
        .stderr(stderr)
        .spawn()
        .expect("rayrepl starts");
    // A pipe whose reader is gone before anything is written to it.
    drop(child.stderr.take());
    let status = child.wait().expect("rayrepl ends");
    (status.code(), dir)
}

fn full_disk() -> Stdio {
    File::options().write(true).open("/dev/full").expect("/dev/full opens").into()
}

/// Whether `path` is a whole PNG of 40×30.
fn whole_picture(path: &Path) -> bool {
    image::open(path).is_ok_and(|image| (image.width(), image.height()) == (40, 30))
}

#[test]
fn a_full_disk_under_the_messages_fails_the_run_and_keeps_the_picture() {
    let (code, dir) = run(&["-o", "out.png", "--width", "40", "--height", "30"], full_disk());
    assert_eq!(code, Some(1), "the run failed, without a panic (status 2)");
    assert!(whole_picture(&dir.path().join("out.png")));
}

#[test]
fn a_closed_pipe_under_the_statistics_ends_quietly() {
    let (code, dir) = run(&["-o", "out.png", "--width", "40", "--height", "30", "--stats"], Stdio::piped());
    assert_eq!(code, Some(141), "a closed pipe ends the run as SIGPIPE would");
    // The print comes before the render: nothing was finished, nothing is left.
    assert_eq!(names_in(dir.path()), ["scene.ray"]);
}

#[test]
fn an_animation_whose_messages_pipe_closes_leaves_no_unfinished_file() {
    let (code, dir) = run(&["--anim", "3", "-o", "f.png", "--width", "40", "--height", "30"], Stdio::piped());
    assert_eq!(code, Some(141));
    let names = names_in(dir.path());
    assert!(names.iter().all(|name| name == "scene.ray" || name.starts_with('f')), "{names:?}");
    for name in names.iter().filter(|name| name.starts_with('f')) {
        assert!(whole_picture(&dir.path().join(name)), "{name} is whole");
    }
}

#[test]
fn an_explanation_to_a_full_disk_fails_saying_why() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    std::fs::write(dir.path().join("scene.ray"), SCENE).expect("the scene is written");
    let output = Command::new(env!("CARGO_BIN_EXE_rayrepl"))
        .current_dir(dir.path())
        .args(["scene.ray", "--explain", "20,15", "--width", "40", "--height", "30"])
        .stdout(full_disk())
        .output()
        .expect("rayrepl runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("rayrepl: cannot write the explanation to standard output: the disk is full"), "{stderr}");
}

#[test]
fn a_script_whose_answers_cannot_be_written_fails_saying_why() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rayrepl"))
        .stdin(Stdio::piped())
        .stdout(full_disk())
        .stderr(Stdio::piped())
        .spawn()
        .expect("rayrepl starts");
    let script = b":size 8 6\n:scene\n";
    std::io::Write::write_all(&mut child.stdin.take().expect("its input"), script).expect("the script is written");
    let output = child.wait_with_output().expect("rayrepl ends");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("error: some of the script's answers could not be written: the disk is full"), "{stderr}");
}
