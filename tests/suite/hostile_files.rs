//! Issue 35, points 1, 4 and 5, run through the binary: a scene file is
//! never written over (by a frame's name, an export, a session's `:save`
//! or `:anim`), an output that is a link stays one, an export holds only
//! numbers POV-Ray reads, and a time that is not a finite number is an
//! error, never 0.

use std::path::{Path, PathBuf};

use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

use crate::common::interrupt::names_in;

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

// Point 4: nothing written that cannot be read back.

/// [`SCENE`] with its sphere of radius `radius`.
fn sphere_of_radius(radius: &str) -> String {
    SCENE.replace("radius 1 ", &format!("radius {radius} "))
}

/// The numbers of a POV-Ray file outside its comments, as written.
fn numbers_of(pov: &str) -> Vec<String> {
    let code = pov.lines().filter(|line| !line.trim_start().starts_with("//")).collect::<Vec<_>>().join("\n");
    let words = code.split(|c: char| c.is_whitespace() || "<>{},*;".contains(c));
    words.filter(|word| word.starts_with(|c: char| c.is_ascii_digit() || c == '-')).map(String::from).collect()
}

#[test]
fn an_export_of_a_huge_scene_holds_only_finite_numbers_that_povray_reads() {
    let dir = folder();
    file(dir.path(), "big.ray", &sphere_of_radius("1e303"));
    rayrepl().current_dir(dir.path()).args(["big.ray", "--export-pov", "big.pov"]).assert().success();
    let pov = std::fs::read_to_string(dir.path().join("big.pov")).expect("the export");
    let numbers = numbers_of(&pov);
    assert!(numbers.iter().any(|n| n == "1e303"), "{numbers:?}");
    for number in &numbers {
        let value: f64 = number.parse().unwrap_or_else(|_| panic!("`{number}` is a number"));
        assert!(value.is_finite(), "`{number}` in\n{pov}");
    }
    let runs = std::process::Command::new("povray").arg("--version").output();
    if !runs.is_ok_and(|out| out.status.success()) {
        eprintln!("skipped the POV-Ray parse of the export: `povray` is not installed");
        return;
    }
    let rendered = std::process::Command::new("povray")
        .current_dir(dir.path())
        .args(["+Ibig.pov", "+Obig.png", "+W8", "+H6", "-A", "-D", "-V", "-GA", "File_Gamma=1.0"])
        .output()
        .expect("povray runs");
    assert!(rendered.status.success(), "{}", String::from_utf8_lossy(&rendered.stderr));
}

#[test]
fn an_export_povray_could_not_read_is_refused_and_nothing_is_written() {
    let dir = folder();
    file(dir.path(), "huge.ray", &sphere_of_radius("1e308"));
    let old = file(dir.path(), "huge.pov", "// the old export\n");
    let reason = "cannot export to POV-Ray: the scene reaches 1e308 from the origin, too far to put its \
                  parallel lights beyond it at a distance POV-Ray can read (it reads finite numbers only); \
                  scale the scene down";
    rayrepl()
        .current_dir(dir.path())
        .args(["huge.ray", "--export-pov", "huge.pov"])
        .assert()
        .code(1)
        .stderr(contains(format!("rayrepl: {reason}")));
    assert_eq!(std::fs::read_to_string(&old).expect("kept"), "// the old export\n");
    rayrepl()
        .current_dir(dir.path())
        .args(["huge.ray", "--export-pov", "new.pov"])
        .assert()
        .code(1)
        .stderr(contains(reason));
    rayrepl()
        .current_dir(dir.path())
        .args(["huge.ray", "--export-pov", "-"])
        .assert()
        .code(1)
        .stdout("")
        .stderr(contains(reason));
    assert_eq!(names_in(dir.path()), ["huge.pov", "huge.ray"], "no file, no temporary file");
}

// Point 1: a scene file is never overwritten.

#[test]
fn an_animation_never_writes_a_frame_over_the_scene() {
    let dir = folder();
    let scene = file(dir.path(), "f0001.png", SCENE);
    rayrepl().current_dir(dir.path()).args(["f0001.png", "--anim", "2", "-o", "f.png"]).assert().code(1).stderr(
        contains("rayrepl: `f0001.png`, frame 1 of the animation, is the scene file itself; give another output name"),
    );
    assert_eq!(std::fs::read_to_string(&scene).expect("kept"), SCENE);
    // The same through a hard link and through a symbolic link; a frame
    // outside --frames is not written, so it is not refused.
    std::fs::hard_link(&scene, dir.path().join("g0002.png")).expect("linked");
    std::os::unix::fs::symlink("f0001.png", dir.path().join("h0002.png")).expect("linked");
    for output in ["g.png", "h.png"] {
        rayrepl()
            .current_dir(dir.path())
            .args(["f0001.png", "--anim", "3", "-o", output])
            .assert()
            .code(1)
            .stderr(contains("0002.png`, frame 2 of the animation, is the scene file itself"));
    }
    rayrepl()
        .current_dir(dir.path())
        .args(["f0001.png", "--anim", "3", "--frames", "3..3", "-q", "-o", "g.png"])
        .assert()
        .success();
    assert_eq!(std::fs::read_to_string(&scene).expect("kept"), SCENE);
    assert_eq!(names_in(dir.path()), ["f0001.png", "g0002.png", "g0003.png", "h0002.png"]);
}

#[test]
fn an_output_that_is_a_hard_link_to_the_scene_is_refused() {
    let dir = folder();
    let scene = file(dir.path(), "s.ray", SCENE);
    std::fs::hard_link(&scene, dir.path().join("s.png")).expect("linked");
    std::fs::hard_link(&scene, dir.path().join("s.pov")).expect("linked");
    for flags in [["-o", "s.png"], ["--export-pov", "s.pov"]] {
        rayrepl()
            .current_dir(dir.path())
            .arg("s.ray")
            .args(flags)
            .assert()
            .code(1)
            .stderr(contains("is the scene file itself; give another output name"));
    }
    assert_eq!(std::fs::read_to_string(&scene).expect("kept"), SCENE);
}

#[test]
fn a_session_never_saves_or_animates_over_the_file_it_loaded() {
    let dir = folder();
    let scene = file(dir.path(), "scene.png", SCENE);
    std::os::unix::fs::symlink("scene.png", dir.path().join("link.png")).expect("linked");
    std::fs::hard_link(&scene, dir.path().join("a0002.png")).expect("linked");
    let cases = [
        (":save scene.png", "`scene.png` is the file loaded into the session (`:load scene.png`)"),
        (":save link.png", "`link.png` is the file loaded into the session (`:load scene.png`)"),
        (":anim 2 scene.png", "`scene.png` is the file loaded into the session (`:load scene.png`)"),
        (
            ":anim 3 a.png",
            "`a0002.png`, frame 2 of the animation, is the file loaded into the session (`:load scene.png`)",
        ),
    ];
    for (command, said) in cases {
        rayrepl()
            .current_dir(dir.path())
            .write_stdin(format!(":load scene.png\n{command}\n"))
            .assert()
            .code(1)
            .stderr(contains(format!("{said}; give another output name")));
        // Loaded by -i, the same.
        rayrepl()
            .current_dir(dir.path())
            .args(["-i", "scene.png"])
            .write_stdin(format!("{command}\n"))
            .assert()
            .code(1)
            .stderr(contains(format!("{said}; give another output name")));
    }
    assert_eq!(std::fs::read_to_string(&scene).expect("kept"), SCENE);
    assert_eq!(names_in(dir.path()), ["a0002.png", "link.png", "scene.png"]);
}

#[test]
fn write_writes_the_session_over_its_file_on_purpose_keeping_links() {
    let dir = folder();
    let elsewhere = folder();
    let scene = file(elsewhere.path(), "real.ray", SCENE);
    std::os::unix::fs::symlink(&scene, dir.path().join("link.ray")).expect("linked");
    rayrepl()
        .current_dir(dir.path())
        .write_stdin(":load link.ray\nput sphere center 2, 0, 0 radius 1 kd 0.5 ks 0.5 phong 10 color 1, 2, 3 end\n:write link.ray\n")
        .assert()
        .success();
    assert!(std::fs::symlink_metadata(dir.path().join("link.ray")).expect("there").file_type().is_symlink());
    let written = std::fs::read_to_string(&scene).expect("written through the link");
    assert!(written.contains("center 2, 0, 0") && written.contains("print time"), "{written}");
    assert_eq!(names_in(dir.path()), ["link.ray"], "no temporary file");
    assert_eq!(names_in(elsewhere.path()), ["real.ray"], "no temporary file");
}

#[test]
fn an_output_that_is_a_link_stays_a_link_with_its_mode() {
    use std::os::unix::fs::{MetadataExt, PermissionsExt};
    let dir = folder();
    file(dir.path(), "t.ray", SCENE);
    let target = file(dir.path(), "real.png", "old");
    std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o600)).expect("chmod");
    std::os::unix::fs::symlink("real.png", dir.path().join("out.png")).expect("linked");
    let hard = dir.path().join("hard.gif");
    std::fs::write(&hard, "old").expect("written");
    std::fs::hard_link(&hard, dir.path().join("other-name.gif")).expect("linked");
    let inode = std::fs::metadata(&hard).expect("there").ino();
    rayrepl().current_dir(dir.path()).args(["t.ray", "-q", "-o", "out.png"]).assert().success();
    rayrepl().current_dir(dir.path()).args(["t.ray", "-q", "--anim", "2", "-o", "hard.gif"]).assert().success();
    assert!(std::fs::symlink_metadata(dir.path().join("out.png")).expect("there").file_type().is_symlink());
    assert_eq!(std::fs::metadata(&target).expect("there").permissions().mode() & 0o777, 0o600);
    image::open(&target).expect("the image went to the link's file");
    assert_eq!(std::fs::metadata(&hard).expect("there").ino(), inode, "the hard link is not split");
    let other = std::fs::read(dir.path().join("other-name.gif")).expect("there");
    assert!(other.starts_with(b"GIF89a"), "both names see the animation");
    assert_eq!(names_in(dir.path()), ["hard.gif", "other-name.gif", "out.png", "real.png", "t.ray"]);
}
