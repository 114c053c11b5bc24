//! `rayrepl compare`: a reference and submissions built in other ways,
//! each change named in words with its line, broken submissions as rows,
//! JSON, CSV, pictures of the differences, animations, usage errors.
//! Every expected line and number below was checked by hand against the
//! scenes' text.

use std::path::{Path, PathBuf};

use assert_cmd::Command;
use predicates::str::contains;
use serde_json::Value;

/// Three spheres made by a recursive procedure (the first made is at
/// x = 2, then 0, then -2), a floor and a box.
const REFERENCE: &str = "\
camera distance 10 angle 1 end
ambient 0.2
light vector 0.5, 0, 0.5 intensity 0.8 end

proc row(n)
  if n > 0 then
    put sphere center 2 * n - 4, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 220 end
    row(n - 1)
  end
end

put plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0 phong 1 color 180, 180, 180 end
row(3)
put box center 0, 2, 0 length 2, 1, 1 kd 0.7 ks 0.1 phong 10 color 200, 60, 60 end
";

/// The reference's scene built another way: in another order, the box
/// with its lengths swapped and turned a quarter, a sphere translated.
const SAME: &str = "\
camera distance 10 angle 1 end
ambient 0.2
light vector 0.5, 0, 0.5 intensity 0.8 end
put translate rotate box center 0, 0, 0 length 1, 2, 1 kd 0.7 ks 0.1 phong 10 color 200, 60, 60 end by 0, 0, pi / 2 end by 0, 2, 0 end
put sphere center 2, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 220 end
put translate sphere center 0, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 220 end by -2, 0, 0 end
put sphere center 0, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 220 end
put plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0 phong 1 color 180, 180, 180 end
";

/// Does not parse: a sphere without its `end`.
const BROKEN: &str = "\
camera distance 10 angle 1 end
put sphere center 0, 0, 0 radius 1 kd 0.8 ks 0.2 phong 20 color 40, 40, 220
put box
";

/// A ball moving along x with `time`.
const MOVING: &str = "\
camera distance 10 angle 1 end
ambient 0.2
light vector 0.5, 0, 0.5 intensity 0.8 end
put sphere center time - 2, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 220 end
";

/// [`MOVING`], but the ball stops at x = 1 from time 3 on.
const STOPPING: &str = "\
camera distance 10 angle 1 end
ambient 0.2
light vector 0.5, 0, 0.5 intensity 0.8 end
if time < 3 then
  put sphere center time - 2, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 220 end
else
  put sphere center 1, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 220 end
end
";

fn rayrepl() -> Command {
    Command::cargo_bin("rayrepl").expect("the binary is built")
}

/// A folder holding `ref.ray` ([`REFERENCE`]) and the `files` given.
fn folder(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("a temporary folder");
    std::fs::write(dir.path().join("ref.ray"), REFERENCE).expect("the reference is written");
    for (name, text) in files {
        let path = dir.path().join(name);
        std::fs::create_dir_all(path.parent().expect("a file in a folder")).expect("its folder is made");
        std::fs::write(path, text).expect("a submission is written");
    }
    dir
}

/// `rayrepl compare ARGS...` in `dir`, at 80x60 pixels.
fn compare(dir: &Path, args: &[&str]) -> assert_cmd::assert::Assert {
    rayrepl().current_dir(dir).arg("compare").args(args).args(["--width", "80", "--height", "60"]).assert()
}

/// [`SAME`] with line `line` (from 1) replaced by `by`.
fn same_but(line: usize, by: &str) -> String {
    let mut lines: Vec<&str> = SAME.lines().collect();
    lines[line - 1] = by;
    lines.join("\n") + "\n"
}

#[test]
fn the_same_scene_built_another_way_matches() {
    let dir = folder(&[("same.ray", SAME)]);
    compare(dir.path(), &["ref.ray", "same.ray"])
        .success()
        .stdout("same.ray: matches\n1 submission: 1 matches, 0 differ, 0 do not run\n");
}

#[test]
fn one_colour_changed_is_named_with_its_line() {
    let changed = "put sphere center 2, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 221 end";
    let dir = folder(&[("colour.ray", &same_but(5, changed))]);
    // One level of blue changes no pixel by more than 2: only the scene says it.
    compare(dir.path(), &["ref.ray", "colour.ray"]).code(1).stdout(
        "colour.ray: differs\n  \
         the first sphere, put at line 5, has colour 40, 40, 221; the reference's has 40, 40, 220\n\
         1 submission: 0 match, 1 differs, 0 do not run\n",
    );
}

#[test]
fn one_position_changed_is_named_with_its_line_and_the_pictures_differ() {
    let changed = "put sphere center 2.5, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 220 end";
    let dir = folder(&[("position.ray", &same_but(5, changed))]);
    compare(dir.path(), &["ref.ray", "position.ray"])
        .code(1)
        .stdout(contains(
            "position.ray: differs\n  the first sphere, put at line 5, is at 2.5, 0, 0; the reference's is at 2, 0, 0\n  \
             the pictures differ: ",
        ))
        .stdout(contains("are off by more than 2 levels; the largest difference"));
}

#[test]
fn a_missing_object_is_the_references_named_with_its_file() {
    let mut lines: Vec<&str> = SAME.lines().collect();
    lines.remove(5); // the sphere at x = -2: the third the reference's procedure makes
    let dir = folder(&[("missing.ray", &(lines.join("\n") + "\n"))]);
    compare(dir.path(), &["ref.ray", "missing.ray"]).code(1).stdout(contains(
        "missing.ray: differs\n  the reference's third sphere, put at line 7 of ref.ray, is missing \
         (the submission has 2 spheres, the reference 3)\n",
    ));
}

#[test]
fn an_extra_object_and_a_changed_light_are_named() {
    let extra = format!("{SAME}put sphere center 0, 3, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 220 end\n");
    let light = same_but(3, "light vector 0.5, 0, 0.5 intensity 0.6 end");
    let dir = folder(&[("extra.ray", &extra), ("light.ray", &light)]);
    compare(dir.path(), &["ref.ray", "extra.ray", "light.ray"])
        .code(1)
        .stdout(contains(
            "extra.ray: differs\n  the fourth sphere, put at line 9, is not in the reference \
             (the submission has 4 spheres, the reference 3)\n",
        ))
        .stdout(contains(
            "light.ray: differs\n  the first light, at line 3, has intensity 0.6; the reference's has 0.8\n",
        ))
        .stdout(contains("2 submissions: 0 match, 2 differ, 0 do not run\n"));
}

#[test]
fn a_camera_moved_and_a_box_turned_are_named() {
    let camera = same_but(1, "camera distance 12 angle 1 end");
    let turned =
        "put translate box center 0, 0, 0 length 1, 2, 1 kd 0.7 ks 0.1 phong 10 color 200, 60, 60 end by 0, 2, 0 end";
    let dir = folder(&[("camera.ray", &camera), ("turned.ray", &same_but(4, turned))]);
    compare(dir.path(), &["ref.ray", "camera.ray", "turned.ray"])
        .code(1)
        .stdout(contains("camera.ray: differs\n  the camera, at line 1, has distance 12; the reference's has 10\n"))
        .stdout(contains(
            // The corner (0.5, 3, 0.5) is 0.707107 = sqrt(0.5² + 0.5²) from the reference's nearest, (1, 2.5, 0.5).
            "turned.ray: differs\n  the first box, put at line 4, is turned otherwise: its corners are up to 0.707107 from the reference's\n",
        ));
}

#[test]
fn a_folder_gives_a_row_each_and_a_broken_submission_is_a_row_with_its_diagnostic() {
    let dir = folder(&[("work/a_broken.ray", BROKEN), ("work/b_same.ray", SAME), ("work/notes.txt", "not a scene")]);
    compare(dir.path(), &["ref.ray", "work"])
        .code(1)
        .stdout(contains(
            "work/a_broken.ray: does not run\nerror: expected `end` to close this `sphere`\n --> work/a_broken.ray:3:1\n",
        ))
        .stdout(contains("work/b_same.ray: matches\n"))
        .stdout(contains("2 submissions: 1 matches, 0 differ, 1 does not run\n"));
}

#[test]
fn json_gives_one_object_per_submission() {
    let changed = "put sphere center 2, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 221 end";
    let dir = folder(&[("a.ray", BROKEN), ("b.ray", &same_but(5, changed)), ("c.ray", SAME)]);
    let output = compare(dir.path(), &["ref.ray", "a.ray", "b.ray", "c.ray", "--json"]).code(1).get_output().clone();
    let text = String::from_utf8(output.stdout).expect("UTF-8");
    let rows: Vec<Value> = text.lines().map(|line| serde_json::from_str(line).expect("a JSON object")).collect();
    assert_eq!(rows.len(), 3, "{text}");
    assert_eq!((&rows[0]["submission"], &rows[0]["result"]), (&"a.ray".into(), &"broken".into()));
    let diagnostic = &rows[0]["failed"]["diagnostic"];
    assert_eq!((&diagnostic["code"], &diagnostic["place"]["line"]), (&"unclosed-block".into(), &3.into()));
    assert_eq!(rows[1]["result"], "differ");
    let difference = &rows[1]["frames"][0]["differences"][0];
    assert_eq!(
        *difference,
        serde_json::json!({
            "kind": "sphere", "ordinal": 1, "line": 5, "reference_ordinal": 1, "reference_line": 7,
            "property": "colour", "submission": [40.0, 40.0, 221.0], "reference": [40.0, 40.0, 220.0],
            "message": "the first sphere, put at line 5, has colour 40, 40, 221; the reference's has 40, 40, 220",
        })
    );
    assert_eq!(rows[1]["frames"][0]["pictures"]["pixels"], 4800);
    assert_eq!(rows[2]["result"], "match");
    assert_eq!(
        rows[2]["frames"][0]["pictures"],
        serde_json::json!({"pixels": 4800, "off": 0, "largest": 0, "at": null})
    );
}

#[test]
fn csv_writes_a_row_per_submission_to_a_file_or_standard_output() {
    let changed = "put sphere center 2, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 221 end";
    let dir = folder(&[("a.ray", BROKEN), ("b.ray", &same_but(5, changed)), ("c.ray", SAME)]);
    let expected = "submission,result,frames_differing,differences,pixels_off,largest_difference,details\n\
                    a.ray,broken,,,,,expected `end` to close this `sphere`\n\
                    b.ray,differ,1,1,0,1,\"the first sphere, put at line 5, has colour 40, 40, 221; the reference's has 40, 40, 220\"\n\
                    c.ray,match,0,0,0,0,\n";
    compare(dir.path(), &["ref.ray", "a.ray", "b.ray", "c.ray", "--csv", "grades.csv"])
        .code(1)
        .stdout(contains("3 submissions: 1 matches, 1 differs, 1 does not run"));
    assert_eq!(std::fs::read_to_string(dir.path().join("grades.csv")).expect("the CSV file"), expected);
    compare(dir.path(), &["ref.ray", "a.ray", "b.ray", "c.ray", "--csv", "-"]).code(1).stdout(expected);
}

#[test]
fn diff_writes_a_picture_of_the_differences() {
    let changed = "put sphere center 2.5, 0, 0 radius 0.5 kd 0.8 ks 0.2 phong 20 color 40, 40, 220 end";
    let dir = folder(&[("position.ray", &same_but(5, changed)), ("same.ray", SAME)]);
    compare(dir.path(), &["ref.ray", "position.ray", "same.ray", "--diff", "diffs"]).code(1);
    let picture = |name: &str| image::open(dir.path().join("diffs").join(name)).expect("a PNG").to_rgb8();
    let moved = picture("position.png");
    assert_eq!(moved.dimensions(), (80, 60));
    let red = |p: &image::Rgb<u8>| p.0[0] >= 128 && p.0[1] == 0 && p.0[2] == 0;
    assert!(moved.pixels().filter(|p| red(p)).count() > 20, "the moved ball's pixels are red");
    assert!(!picture("same.png").pixels().any(red), "nothing differs");
}

#[test]
fn animations_are_compared_frame_by_frame() {
    let dir = folder(&[("moving.ray", MOVING), ("stopping.ray", STOPPING)]);
    let args = ["moving.ray", "stopping.ray", "moving.ray", "--anim", "4", "--diff", "diffs"];
    compare(dir.path(), &args)
        .code(1)
        .stdout(contains(
            // Frame k has time k: at 4, the reference's ball is at 4 - 2 = 2, the submission's stays at 1.
            "stopping.ray: differs in 1 of 4 frames (4); at frame 4 (time 4):\n  \
             the first sphere, put at line 7, is at 1, 0, 0; the reference's is at 2, 0, 0\n",
        ))
        .stdout(contains("moving.ray: matches, all 4 frames\n"));
    let written: Vec<PathBuf> = (1..=4).map(|k| dir.path().join(format!("diffs/stopping{k:04}.png"))).collect();
    assert!(written.iter().all(|file| file.is_file()), "a picture per frame");
    compare(dir.path(), &["moving.ray", "stopping.ray", "--anim", "2", "--time-start", "0.5"])
        .success()
        .stdout(contains("stopping.ray: matches, all 2 frames\n"));
}

#[test]
fn usage_errors_and_a_reference_that_does_not_run_exit_with_2() {
    let dir = folder(&[("broken.ray", BROKEN), ("same.ray", SAME), ("empty/notes.txt", "")]);
    let cases: [(&[&str], &str); 7] = [
        (&["ref.ray"], "<SUBMISSION>"),
        (&["ref.ray", "same.ray", "--time", "2", "--anim", "3"], "--time sets the time of one image"),
        (&["ref.ray", "same.ray", "--time-step", "2"], "--time-step is for an animation: give --anim N too"),
        (&["ref.ray", "same.ray", "--off-pixels", "200"], "is not a percentage"),
        (&["ref.ray", "empty"], "holds no .ray file"),
        (&["nothere.ray", "same.ray"], "cannot read `nothere.ray`"),
        (&["broken.ray", "same.ray"], "the reference does not run: there is nothing to compare with"),
    ];
    for (args, said) in cases {
        compare(dir.path(), args).code(2).stderr(contains(said));
    }
}

#[test]
fn a_scene_file_still_renders_beside_the_command() {
    let dir = folder(&[]);
    rayrepl()
        .current_dir(dir.path())
        .args(["ref.ray", "-o", "ref.png", "--width", "8", "--height", "6", "-q"])
        .assert()
        .success();
    assert!(dir.path().join("ref.png").is_file());
}
