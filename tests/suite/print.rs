//! `print` (an extension of this project, docs/language.md section 12): allowed
//! wherever an instruction is, its line format, its limit, and what it does
//! in a batch render, an animation, a piped script and a session.

use assert_cmd::Command;
use predicates::prelude::*;
use predicates::str::contains;
use rayrepl::lang::eval::PRINT_LIMIT;
use rayrepl::session::SessionOptions;
use rayrepl::terminal::run_script;

fn rayrepl() -> Command {
    Command::cargo_bin("rayrepl").expect("the binary is built")
}

/// A lit sphere, so that the programs below raise no other warning.
const SCENE: &str = "camera distance 10 angle 1 end
ambient 0.2
light vector 0, 0, 0 intensity 1 end
";

/// A fresh folder holding `scene.ray` with `SCENE` then `text`.
fn scene(text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let path = dir.path().join("scene.ray");
    std::fs::write(&path, format!("{SCENE}{text}")).expect("scene written");
    (dir, path)
}

/// What `rayrepl --check` writes on stderr for the scene, which must succeed.
fn check_stderr(text: &str) -> String {
    let (_dir, path) = scene(text);
    let output = rayrepl().arg("--check").arg(&path).output().expect("runs");
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8_lossy(&output.stderr).replace(&path.display().to_string(), "scene.ray")
}

#[test]
fn print_works_at_top_level_in_procedures_and_in_both_branches() {
    let text = "\
proc show(n)
  print n
  if n < 2 then
    print n, 1
  else
    print n * 10
  end
end
let r = 2
print r,  r * (1 +
  1), pi, -r / 4
show(1)
show(2)
put sphere center 0, 0, 0 radius r kd 1 ks 0 phong 1 color 255, 0, 0 end
";
    let expected = "\
scene.ray:13: r = 2, r * (1 + 1) = 4, pi = 3.141593, -r / 4 = -0.5
scene.ray:5: n = 1
scene.ray:7: n = 1, 1
scene.ray:5: n = 2
scene.ray:9: n * 10 = 20
";
    assert_eq!(check_stderr(text), expected);
}

#[test]
fn print_describes_objects_and_numbers_as_they_are_written() {
    let text = "\
object ball = sphere center 0, 1.5, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end
object pair = group ball translate box center 0, 0, 0 length 1, 2, 3 kd 1 ks 0 phong 1 color 255, 0, 0 end by 2, 0, 0 end end
object tilted = rotate box center 0, 0, 0 length 1, 1, 1 kd 1 ks 0 phong 1 color 255, 0, 0 end by 0, 1, 0 end
object floor = plane rotation 0, 0, 0 shift -1 kd 1 ks 0 phong 1 color 255, 0, 0 end
print ball, pair, tilted, floor, 1 / 3, 1e-12, time
put pair put tilted put floor
";
    let stderr = check_stderr(text);
    assert_eq!(
        stderr,
        "scene.ray:8: ball = sphere center 0, 1.5, 0 radius 1, pair = group of 1 sphere and 1 box, \
         tilted = box center 0, 0, 0 length 1, 1, 1, turned, floor = plane normal 0, 1, 0 shift -1, \
         1 / 3 = 0.333333, 1e-12, time = 0\n"
    );
}

#[test]
fn print_needs_an_expression() {
    let (_dir, path) = scene("print\n");
    rayrepl().arg("--check").arg(&path).assert().code(1).stderr(contains("expected an expression"));
    let (_dir, path) = scene("print 1,\n");
    rayrepl().arg("--check").arg(&path).assert().code(1);
}

#[test]
fn what_was_printed_before_an_error_is_shown_before_it() {
    let (_dir, path) = scene("let a = 1\nprint a\nprint a / 0\nprint 3\n");
    let output = rayrepl().arg("--check").arg(&path).output().expect("runs");
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    let printed = stderr.find(":5: a = 1").expect("the first print is shown");
    let error = stderr.find("error: division by zero").expect("the error is shown");
    assert!(printed < error, "{stderr}");
    assert!(!stderr.contains(": 3\n"), "nothing runs after the error: {stderr}");
}

#[test]
fn a_print_run_a_million_times_shows_the_first_lines_and_counts_the_rest() {
    let text = "\
proc loop(n)
  if n > 0 then
    print n
    loop(n - 1)
  end
end
loop(1500)
";
    let stderr = check_stderr(text);
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), PRINT_LIMIT + 1, "{}", lines.last().unwrap_or(&""));
    assert_eq!(lines[0], "scene.ray:6: n = 1500");
    assert_eq!(lines[PRINT_LIMIT], "note: `print` wrote 500 more lines, not shown: at most 1000 are shown at a time");
}

#[test]
fn a_render_to_standard_output_keeps_the_image_clean() {
    let (_dir, path) = scene("print 42\nput sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end\n");
    let output = rayrepl().arg(&path).args(["--width", "4", "--height", "3", "-o", "-"]).output().expect("runs");
    assert!(output.status.success());
    assert!(output.stdout.starts_with(b"P6\n4 3\n255\n"), "only the image on stdout");
    assert_eq!(output.stdout.len(), b"P6\n4 3\n255\n".len() + 4 * 3 * 3);
    assert!(String::from_utf8_lossy(&output.stderr).contains(":4: 42\n"));
}

#[test]
fn an_animation_prints_for_every_evaluation() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let out = dir.path().join("a.gif");
    let sphere = "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end\n";
    // Reading `time` makes each frame evaluate the program again.
    let (_scene_dir, path) = scene(&format!("print time\n{sphere}"));
    let output = rayrepl().arg(&path).args(["--width", "4", "--height", "3", "--anim", "3", "-o"]).arg(&out).output();
    let stderr = String::from_utf8_lossy(&output.expect("runs").stderr).into_owned();
    let lines: Vec<&str> = stderr.lines().filter(|line| line.contains(": time = ")).collect();
    assert_eq!(lines.len(), 3, "{stderr}");
    assert!(lines[2].ends_with(": time = 3"), "{stderr}");
    // A scene that does not depend on `time` is evaluated once.
    let (_scene_dir, path) = scene(&format!("print 7\n{sphere}"));
    let output = rayrepl().arg(&path).args(["--width", "4", "--height", "3", "--anim", "3", "-o"]).arg(&out).output();
    let stderr = String::from_utf8_lossy(&output.expect("runs").stderr).into_owned();
    assert_eq!(stderr.matches(": 7\n").count(), 1, "{stderr}");
}

/// Runs a script through the session; returns its exit status and stderr.
fn script(text: &str) -> (i32, String) {
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let code = run_script(text.as_bytes(), &mut out, &mut err, &SessionOptions::default());
    (code, String::from_utf8(err).expect("text"))
}

#[test]
fn a_script_prints_with_its_own_line_numbers() {
    let (code, stderr) = script("let r = 2\n\nprint r\nproc p(x)\n  print x\nend\np(r + 1)\n");
    assert_eq!(code, 0);
    assert!(stderr.starts_with("<stdin>:3: r = 2\n<stdin>:5: x = 3\n"), "{stderr}");
}

#[test]
fn a_session_prints_again_at_another_time_but_not_on_undo() {
    let text = "print time\nlet t = time\n:time 4\nlet a = 1\n:undo\n:anim 2 OUT\n";
    let dir = tempfile::tempdir().expect("temporary folder");
    let text = text.replace("OUT", &dir.path().join("a.gif").display().to_string());
    let (code, stderr) = script(&text);
    assert_eq!(code, 0, "{stderr}");
    let times: Vec<&str> = stderr.lines().filter_map(|line| line.strip_prefix("<stdin>:1: time = ")).collect();
    // Typed (0), `:time 4` (4), then the two frames of `:anim` (1 and 2);
    // `:undo` evaluates again without printing.
    assert_eq!(times, ["0", "4", "1", "2"], "{stderr}");
}

mod piped {
    use super::*;

    #[test]
    fn a_piped_script_prints_on_stderr() {
        rayrepl()
            .write_stdin("let r = 2\nprint r * 2\n")
            .assert()
            .success()
            .stdout(contains("print").not())
            .stderr(contains("<stdin>:2: r * 2 = 4\n"));
    }
}
