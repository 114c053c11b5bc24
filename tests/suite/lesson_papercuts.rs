//! What a learner met in the lessons (issue 33, points 6 and 8): angles
//! written in degrees and one colour written from 0 to 1 are warned about,
//! the documentation says what the program does (its sample message, the
//! `--allow` names it suggests, the install line), and numbers print as a
//! learner reads them (`0`, not `-0`; `1e308`, not 309 digits).

use std::path::PathBuf;

use assert_cmd::Command;
use rayrepl::lint::Check;
use rayrepl::session::SessionOptions;
use rayrepl::terminal::run_script;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn rayrepl() -> Command {
    Command::cargo_bin("rayrepl").expect("the binary is built")
}

fn read(path: &str) -> String {
    std::fs::read_to_string(root().join(path)).expect("readable file")
}

/// A camera, an ambient light and a ball, lit from the front.
const SCENE: &str = "camera distance 10 angle 1 end
ambient 0.2
light vector 0.5, 0, 0.5 intensity 0.8 end
put sphere center 0, 0, 0 radius 1 kd 0.8 ks 0.2 phong 20 color 255, 120, 40 end
";

/// What `rayrepl --check` writes on stderr for `text`, which must evaluate.
fn check_stderr(text: &str) -> String {
    let dir = tempfile::tempdir().expect("temporary folder");
    let path = dir.path().join("scene.ray");
    std::fs::write(&path, text).expect("scene written");
    let output = rayrepl().arg("--check").arg(&path).output().expect("runs");
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    stderr
}

/// What a piped script writes on stdout and stderr.
fn script(text: &str) -> (String, String) {
    let (mut stdout, mut stderr) = (Vec::new(), Vec::new());
    run_script(text.as_bytes(), &mut stdout, &mut stderr, &SessionOptions::default());
    (String::from_utf8(stdout).expect("text"), String::from_utf8(stderr).expect("text"))
}

#[test]
fn angles_in_degrees_are_warned_about_in_lights_planes_and_rotations() {
    let lesson1 = SCENE.replace("light vector 0.5, 0, 0.5", "light vector 45, 0, 0");
    let warned = check_stderr(&lesson1);
    assert!(warned.contains("warning: the light's angle 45 looks like degrees, but angles are in radians"), "{warned}");
    assert!(warned.contains("write `45 * pi / 180` (that is 0.785398 radians)"), "{warned}");
    let lesson5 = format!(
        "{SCENE}put rotate box center 3, 0, 0 length 1, 1, 1 kd 1 ks 0 phong 1 color 0, 0, 255 end by 0, 0, 45 end\n"
    );
    assert!(check_stderr(&lesson5).contains("warning: the rotation 45 looks like degrees"));
    let wall = format!("{SCENE}put plane rotation -90, 0, 0 shift -5 kd 1 ks 0 phong 1 color 200, 200, 200 end\n");
    assert!(check_stderr(&wall).contains("warning: the plane's rotation -90 looks like degrees"));
    // Once per place, however often a procedure runs it.
    let spin = "proc spin(n)\n  put rotate box center n, 0, 0 length 1, 1, 1 kd 1 ks 0 phong 1 color 0, 0, 255 end by 0, 90, 0 end\n\
                end\n";
    let repeated = format!("{}spin(1)\nspin(2)\n", SCENE.replacen("put sphere", &format!("{spin}put sphere"), 1));
    assert_eq!(check_stderr(&repeated).matches("warning:").count(), 1);
}

#[test]
fn angles_in_radians_are_not_warned_about() {
    for turn in ["0, pi / 4, 0", "0, 0.785398, 0", "0, 7, 0", "1, 2, 3", "0, 2 * pi, 0", "0, 365, 0"] {
        let text = format!(
            "{SCENE}put rotate box center 3, 0, 0 length 1, 1, 1 kd 1 ks 0 phong 1 color 0, 0, 255 end by {turn} end\n"
        );
        assert_eq!(check_stderr(&text), "", "{turn}");
    }
    // What depends on `time` may be other angles in other frames.
    let timed = format!(
        "{SCENE}put rotate box center 3, 0, 0 length 1, 1, 1 kd 1 ks 0 phong 1 color 0, 0, 255 end by 0, time * 90, 0 end\n"
    );
    let dir = tempfile::tempdir().expect("temporary folder");
    let path = dir.path().join("scene.ray");
    std::fs::write(&path, timed).expect("scene written");
    let output = rayrepl().args(["--check", "--time", "1"]).arg(&path).output().expect("runs");
    assert_eq!(String::from_utf8_lossy(&output.stderr), "");
}

#[test]
fn an_entry_that_fails_takes_its_degrees_back() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let out = dir.path().join("out.png");
    let (_, stderr) = script(&format!(
        "{SCENE}put rotate box center 3, 0, 0 length 1, 1, 1 kd 1 ks 0 phong 1 color 0, 0, 255 end by 0, 45, 1 / 0 end\n\
         :save {} 8 6\n",
        out.display()
    ));
    assert!(stderr.contains("error:"), "{stderr}");
    assert!(!stderr.contains("looks like degrees"), "{stderr}");
}

#[test]
fn one_colour_from_0_to_1_among_colours_up_to_255_is_warned_about() {
    let text = format!("{SCENE}put sphere center 3, 0, 0 radius 1 kd 0.8 ks 0.2 phong 20 color 0.2, 0.4, 1 end\n");
    let warned = check_stderr(&text);
    assert!(warned.contains("warning: this object's colour is at most 1, but the others go up to 255"), "{warned}");
    assert!(warned.contains("write `color 51, 102, 255`"), "{warned}");
    assert!(warned.contains("`--allow dark-colour`"), "{warned}");
    // Black is black, whatever the scale.
    let black = format!("{SCENE}put sphere center 3, 0, 0 radius 1 kd 0.8 ks 0.2 phong 20 color 0, 0, 0 end\n");
    assert_eq!(check_stderr(&black), "");
}

/// The text of each fenced block of `markdown`, in order.
fn fenced_blocks(markdown: &str) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in markdown.lines() {
        match (&mut current, line.starts_with("```")) {
            (None, true) => current = Some(String::new()),
            (Some(block), true) => {
                blocks.push(std::mem::take(block));
                current = None;
            }
            (Some(block), false) => {
                block.push_str(line);
                block.push('\n');
            }
            (None, false) => {}
        }
    }
    blocks
}

#[test]
fn the_missing_end_message_the_docs_show_is_the_programs() {
    for document in ["README.md", "docs/guide/errors.md"] {
        the_missing_end_message_is_the_programs(document);
    }
}

fn the_missing_end_message_is_the_programs(document: &str) {
    let text = read(document);
    let sample = fenced_blocks(&text)
        .into_iter()
        .find(|block| block.starts_with("error: expected `end`"))
        .unwrap_or_else(|| panic!("{document} shows a missing `end`"));
    // The scene the sample shows: its lines 3 and 4, after a camera and an ambient light.
    let shown = |number: &str| {
        let prefix = format!("{number} | ");
        let line = sample.lines().find_map(|line| line.strip_prefix(&prefix)).expect("the sample shows the line");
        line.to_string()
    };
    let text = format!("camera distance 10 angle 1 end\nambient 0.2\n{}\n{}\n", shown("3"), shown("4"));
    let dir = tempfile::tempdir().expect("temporary folder");
    std::fs::write(dir.path().join("scene.ray"), text).expect("scene written");
    let output = rayrepl().current_dir(dir.path()).args(["--check", "scene.ray"]).output().expect("runs");
    assert_eq!(output.status.code(), Some(1));
    assert_eq!(String::from_utf8_lossy(&output.stderr), sample, "{document}");
}

#[test]
fn every_allow_name_the_documents_suggest_is_accepted() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let path = dir.path().join("scene.ray");
    std::fs::write(&path, SCENE).expect("scene written");
    let mut names = Vec::new();
    let guide = std::fs::read_dir(root().join("docs/guide")).expect("the guide");
    let chapters = guide.map(|entry| format!("docs/guide/{}", entry.expect("a chapter").file_name().to_string_lossy()));
    for document in ["README.md".to_string(), "docs/language.md".to_string()].into_iter().chain(chapters) {
        let text = read(&document);
        for (at, _) in text.match_indices("rayrepl --allow ") {
            let rest = &text[at + "rayrepl --allow ".len()..];
            let name: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '-').collect();
            names.push(name);
        }
    }
    assert!(names.iter().any(|name| name == "degrees"), "{names:?}");
    for name in names {
        assert!(name == "all" || Check::ALL.iter().any(|check| check.name() == name), "`--allow {name}`");
        let output = rayrepl().args(["--check", "--allow", &name]).arg(&path).output().expect("runs");
        assert_eq!(output.status.code(), Some(0), "`--allow {name}`: {}", String::from_utf8_lossy(&output.stderr));
    }
}

#[test]
fn the_readme_installs_with_the_lock_file() {
    let readme = read("README.md");
    assert!(readme.contains("\ncargo install --locked --path .\n"));
    assert!(!readme.contains("\ncargo install --path .\n"));
}

#[test]
fn env_and_print_write_0_for_minus_0() {
    let (stdout, stderr) = script("let z = 0 * -1\nprint z\n:env\n");
    assert!(!stdout.contains("-0") && !stderr.contains("-0"), "{stdout}{stderr}");
    assert!(stdout.contains("z = 0"), "{stdout}");
}

#[test]
fn print_writes_huge_numbers_in_the_shortest_form_with_an_exponent() {
    let (stdout, stderr) = script("print 1e308, -1.5e300, 1e-300\n");
    let all = format!("{stdout}{stderr}");
    assert!(all.contains("1e308, -1.5e300, 1e-300"), "{all}");
}
