//! Asking a pixel why (`--explain X,Y`, `:pick X Y`): the explained bytes
//! are the rendered bytes, for every pixel of many scenes and settings; the
//! places named hold the `put` and the calls; a hand-computed pixel; the
//! command line.

use std::path::Path;

use assert_cmd::Command;
use predicates::str::contains;
use rayrepl::explain::ExplainedScene;
use rayrepl::lang::{Interpreter, Limits, SourceMap, parse_file};
use rayrepl::render::{RenderControl, RenderOptions, SceneGeometry, Screen, Skips, render};
use serde_json::Value;

/// A program evaluated with its calls recorded, and its source text.
struct Evaluated {
    sources: SourceMap,
    interpreter: Interpreter,
}

fn evaluated(name: &str, text: &str, time: f64) -> Evaluated {
    let mut sources = SourceMap::new();
    let id = sources.add(name, text, 0);
    let program = parse_file(id, text).unwrap_or_else(|e| panic!("{name} parses: {}", e.message));
    let mut interpreter = Interpreter::new(time, Limits::default()).recording_calls();
    interpreter.run(&program).unwrap_or_else(|e| panic!("{name} evaluates: {}", e.message));
    Evaluated { sources, interpreter }
}

/// The explanations of every pixel of `text` rendered with `options`, as JSON.
fn explain_all(name: &str, text: &str, time: f64, options: &RenderOptions) -> Vec<Value> {
    let evaluated = evaluated(name, text, time);
    let scene = ExplainedScene::new(&evaluated.interpreter, &evaluated.sources, options);
    let pixels = (0..options.height).flat_map(|y| (0..options.width).map(move |x| (x, y)));
    pixels.map(|(x, y)| scene.explain(x, y).to_json()).collect()
}

/// Checks, for every pixel, that the explained `rgb` is the rendered pixel,
/// and that every place named holds what it says: a `put` for an object,
/// a call of the procedure for a call. Returns how many objects and calls
/// were named, to check that the scene exercised them.
fn check_scene(name: &str, text: &str, time: f64, options: &RenderOptions) -> (usize, usize) {
    let scene = evaluated(name, text, time).interpreter.into_scene();
    let (image, _) =
        render(&scene, &SceneGeometry::new(&scene), options, &RenderControl::default()).expect("not cancelled");
    let lines: Vec<&str> = text.lines().collect();
    let (mut objects, mut calls) = (0, 0);
    for explanation in explain_all(name, text, time, options) {
        let (x, y) = (explanation["pixel"][0].as_u64().unwrap(), explanation["pixel"][1].as_u64().unwrap());
        let rendered = image.get_pixel(x as u32, y as u32).0;
        assert_eq!(explanation["rgb"], serde_json::json!(rendered), "{name} {options:?}: pixel ({x}, {y})");
        let mut paths = vec![&explanation["path"]];
        paths.extend(explanation["samples"].as_array().into_iter().flatten().map(|sample| &sample["path"]));
        for level in paths.into_iter().flat_map(|path| path.as_array().expect("a path is a list")) {
            let blockers = level["lights"].as_array().into_iter().flatten().map(|light| &light["blocker"]);
            for object in std::iter::once(&level["object"]).chain(blockers).filter(|o| !o.is_null()) {
                objects += 1;
                assert!(at(&lines, object).starts_with("put"), "{name}: {object} names no put");
                for call in object["calls"].as_array().expect("calls are a list") {
                    calls += 1;
                    let procedure = call["proc"].as_str().expect("a name");
                    assert!(at(&lines, call).starts_with(&format!("{procedure}(")), "{name}: {call}");
                }
            }
        }
    }
    (objects, calls)
}

/// The text from the place `{"line", "column"}` names to the end of its line.
fn at<'t>(lines: &[&'t str], place: &Value) -> &'t str {
    let (line, column) = (place["line"].as_u64().expect("a line"), place["column"].as_u64().expect("a column"));
    let text = lines[line as usize - 1];
    let start = text.char_indices().nth(column as usize - 1).map_or(text.len(), |(i, _)| i);
    &text[start..]
}

/// Small options: `samples` per pixel, adaptive or not.
fn small(samples: u32, adaptive: bool) -> RenderOptions {
    RenderOptions { width: 24, height: 18, samples, adaptive, ..RenderOptions::default() }
}

/// Mirrors, shadows, planes, boxes, groups, procedures, recursion and an
/// object that depends on `time`.
const HAND_MADE: &str = "camera distance 12 angle 1.1 end
ambient 0.2
light vector 0.5, 0, 0.4 intensity 0.7 end
light rotation -0.3, 0, -0.6 intensity 0.4 end
light vector 3, 0, 0 intensity 0.5 end
proc tower(n, x)
  if 0 < n then
    put translate scale block by 0.5 + 0.2 * n end by x, n - 2, 0 end
    tower(n - 1, x + 1.1)
  end
end
proc pair(x, y)
  put group
    sphere center x, y, 0 radius 0.8 kd 0.5 ks 0.7 phong 80 color 255, 255, 255 end
    rotate box center x + 2, y, 1 length 1, 1, 1 kd 0.8 ks 0 phong 1 color 40, 200, 90 end by 0.4, 0.5, 0 end
  end
end
put plane rotation 0, 0, 0 shift -2 kd 0.6 ks 0.5 phong 10 color 200, 200, 220 end
put plane rotation 1.2, 0, 0 shift -9 kd 0.5 ks 0.9 phong 50 color 120, 140, 255 end
object block = box center 0, 0, 0 length 1, 2, 1 kd 0.7 ks 0.2 phong 20 color 250, 120, 40 end
tower(4, -4)
pair(1, -1)
put sphere center 2 * sin(time), 2.5, -1 radius 1 kd 0.3 ks 0.8 phong 100 color 255, 220, 0 end
";

#[test]
fn every_pixel_of_the_hand_made_scene_is_explained_as_rendered() {
    for options in [small(1, false), small(4, false), small(9, true)] {
        for time in [0.0, 2.0] {
            let (objects, calls) = check_scene("hand.ray", HAND_MADE, time, &options);
            assert!(objects > 500 && calls > 100, "{objects} objects, {calls} calls named");
        }
    }
    let deep = RenderOptions { depth: 0, screen: Screen::Bottom, ..small(1, false) };
    check_scene("hand.ray", HAND_MADE, 0.0, &deep);
    // No shortcut: shadow rays towards lights behind the surface, mirrors of ks 0.
    let literal = RenderOptions { skips: Skips::none(), depth: 8, ..small(4, false) };
    check_scene("hand.ray", HAND_MADE, 2.0, &literal);
}

#[test]
fn a_deep_chain_of_calls_is_cut_short_in_words_and_whole_in_json() {
    let text = "camera distance 10 angle 1 end
ambient 0.2
proc nest(n)
  if n = 0 then
    put sphere center 0, 0, 0 radius 2 kd 1 ks 0 phong 1 color 255, 255, 255 end
  else
    nest(n - 1)
  end
end
nest(20)
";
    let options = RenderOptions { width: 3, height: 3, ..RenderOptions::default() };
    let evaluated = evaluated("nest.ray", text, 0.0);
    let explanation = ExplainedScene::new(&evaluated.interpreter, &evaluated.sources, &options).explain(1, 1);
    let words = explanation.to_string();
    assert!(words.contains("    in nest(n = 0) called at nest.ray:7:5\n"), "{words}");
    assert!(words.contains("    ... and 13 calls more\n"), "{words}");
    let calls = &explanation.to_json()["path"][0]["object"]["calls"];
    assert_eq!(calls.as_array().map(Vec::len), Some(21));
    assert_eq!((&calls[20]["args"]["n"], &calls[20]["line"]), (&20.0.into(), &10.into()));
}

#[test]
fn every_pixel_of_the_bundled_scenarios_is_explained_as_rendered() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let mut files: Vec<_> = std::fs::read_dir(folder).expect("scenarios").map(|e| e.expect("entry").path()).collect();
    files.sort();
    assert!(files.len() >= 10);
    let mut calls = 0;
    for path in files {
        let text = std::fs::read_to_string(&path).expect("readable");
        let name = path.display().to_string();
        calls += check_scene(&name, &text, 3.0, &small(1, false)).1;
        check_scene(&name, &text, 0.0, &small(4, true));
    }
    assert!(calls > 1000, "{calls} calls named");
}

/// One sphere straight ahead lit head-on: the centre pixel by hand.
const HEAD_ON: &str = "camera distance 10 angle 1 end
ambient 0.2
light vector 1.5707963267948966, 0, 0 intensity 0.8 end
light vector 0, 0, 0 intensity 0.5 end
put sphere center 0, 0, 0 radius 2 kd 0.5 ks 0 phong 1 color 255, 0, 0 end
";

#[test]
fn a_pixel_computed_by_hand() {
    let options = RenderOptions { width: 3, height: 3, ..RenderOptions::default() };
    let evaluated = evaluated("head.ray", HEAD_ON, 0.0);
    let scene = ExplainedScene::new(&evaluated.interpreter, &evaluated.sources, &options);
    let json = scene.explain(1, 1).to_json();
    // The ray (0, 0, -1) meets the sphere at (0, 0, 2), N = (0, 0, 1).
    // Ambient kd*Ia*C = 0.5 * 0.2 = 0.1; light 1 is L = (0, sin(pi/2), ...)
    // rotated about x: (0, 0, 1), N·L = 1, diffuse 0.5 * 1 * 0.8 = 0.4;
    // light 2 points up, N·L = 0: facing away. 0.5 * 255 = 127.5 -> 128.
    let level = &json["path"][0];
    assert_eq!(json["rgb"], serde_json::json!([128, 0, 0]));
    assert_eq!(level["object"]["kind"], "sphere");
    assert_eq!((&level["object"]["line"], &level["object"]["column"]), (&5.into(), &1.into()));
    assert_eq!(level["point"], serde_json::json!([0.0, 0.0, 2.0]));
    assert_eq!(level["ambient"], serde_json::json!([0.1, 0.0, 0.0]));
    assert_eq!(level["lights"][0]["state"], "lit");
    assert_eq!(level["lights"][0]["line"], 3);
    assert_eq!(level["lights"][0]["diffuse"], serde_json::json!([0.4, 0.0, 0.0]));
    assert_eq!(level["lights"][1]["state"], "facing away");
    assert_eq!(level["color"], serde_json::json!([0.5, 0.0, 0.0]));
    // The corner pixel's ray misses: background.
    let corner = scene.explain(0, 0).to_json();
    assert_eq!((&corner["rgb"], &corner["path"][0]["object"]), (&serde_json::json!([0, 0, 0]), &Value::Null));
}

/// A floor, a ball above it, a light straight up; a mirror ball off to the
/// side, put by a recursive procedure.
const SHADOW: &str = "camera distance 10 angle 1 end
ambient 0.1
light vector 0, 0, 0 intensity 0.9 end
proc balls(n)
  if 0 < n then
    put sphere center 3 * n, 1, 0 radius 1 kd 0.1 ks 0.9 phong 100 color 255, 255, 255 end
    balls(n - 1)
  end
end
put plane rotation 0, 0, 0 shift -2 kd 0.8 ks 0 phong 1 color 255, 255, 255 end
put sphere center 0, 0, 0 radius 1.5 kd 0.8 ks 0 phong 1 color 0, 0, 255 end
balls(2)
";

#[test]
fn a_shadow_names_its_object_and_a_reflection_its_calls() {
    let options = RenderOptions { width: 80, height: 60, ..RenderOptions::default() };
    let evaluated = evaluated("shadow.ray", SHADOW, 0.0);
    let scene = ExplainedScene::new(&evaluated.interpreter, &evaluated.sources, &options);
    // Just under the ball's silhouette, where the floor is in its shadow.
    let floor = (0..60).rev().map(|y| scene.explain(40, y).to_json()).find(|json| {
        json["path"][0]["object"]["kind"] == "plane" && json["path"][0]["lights"][0]["state"] == "shadowed"
    });
    let floor = floor.expect("a shadowed floor pixel in the middle column");
    let blocker = &floor["path"][0]["lights"][0]["blocker"];
    assert_eq!((&blocker["kind"], &blocker["line"]), (&"sphere".into(), &11.into()));
    // A mirror ball's pixel: the path names `balls(n = 1)` inside `balls(n = 2)`.
    let mirror = (0..80).map(|x| scene.explain(x, 25).to_json()).find(|json| json["path"][0]["object"]["line"] == 6);
    let calls = &mirror.expect("a mirror ball pixel on row 25")["path"][0]["object"]["calls"];
    let chain: Vec<(f64, u64)> = calls
        .as_array()
        .expect("a list")
        .iter()
        .map(|call| (call["args"]["n"].as_f64().expect("n"), call["line"].as_u64().expect("line")))
        .collect();
    assert_eq!(chain, [(1.0, 7), (2.0, 12)], "the leftmost ball, put by the inner call");
}

fn rayrepl() -> Command {
    Command::cargo_bin("rayrepl").expect("the binary is built")
}

#[test]
fn the_command_line_explains_in_words_and_in_json() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let path = dir.path().join("shadow.ray");
    std::fs::write(&path, SHADOW).expect("written");
    let size = ["--width", "80", "--height", "60"];
    let words = rayrepl().arg(&path).args(size).args(["--explain", "40,30"]).assert().success();
    let out = String::from_utf8_lossy(&words.get_output().stdout).to_string();
    assert!(out.contains("the camera ray met a sphere put at") && out.contains("shadow.ray:11:1"), "{out}");
    assert!(out.contains("light 1 (") && out.contains("rgb ("), "{out}");
    let json = rayrepl().arg(&path).args(size).args(["--explain", "40,30", "--json", "--samples", "4"]).assert();
    let json: Value = serde_json::from_slice(&json.success().get_output().stdout).expect("one JSON object");
    assert_eq!(json["pixel"], serde_json::json!([40, 30]));
    assert_eq!(json["samples"].as_array().map(Vec::len), Some(4));
    // The same pixel of the written image.
    let png = dir.path().join("out.png");
    rayrepl().arg(&path).args(size).args(["--samples", "4", "-q", "-o"]).arg(&png).assert().success();
    let image = image::open(&png).expect("an image").to_rgb8();
    assert_eq!(json["rgb"], serde_json::json!(image.get_pixel(40, 30).0));
}

#[test]
fn a_pixel_outside_the_image_or_misspelt_is_refused() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let path = dir.path().join("head.ray");
    std::fs::write(&path, HEAD_ON).expect("written");
    rayrepl()
        .arg(&path)
        .args(["--width", "40", "--height", "30", "--explain", "40,3"])
        .assert()
        .code(2)
        .stderr(contains("--explain 40,3 is outside the 40x30 image: x goes from 0 to 39, y from 0 to 29"));
    rayrepl().arg(&path).args(["--explain", "4;3"]).assert().code(2).stderr(contains("not a pixel like 120,45"));
    rayrepl().arg(&path).args(["--json"]).assert().code(2).stderr(contains("--explain"));
    rayrepl().arg(&path).args(["--explain", "1,1", "-o", "x.png"]).assert().code(2);
}

#[test]
fn pick_explains_a_pixel_of_the_last_picture_in_the_session() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let png = dir.path().join("saved.png");
    let script = format!(
        "camera distance 10 angle 1 end
light vector 0.5, 0, 0.5 intensity 0.8 end
proc ball(x, r)
  put sphere center x, 0, 0 radius r kd 0.7 ks 0.3 phong 20 color 255, 80, 40 end
end
ball(0, 2)
:save {} 40 30
:pick 20 15
",
        png.display()
    );
    let out = rayrepl().write_stdin(script).assert().success().get_output().stdout.clone();
    let out = String::from_utf8_lossy(&out);
    assert!(out.contains("pixel (20, 15)\nthe camera ray met a sphere put at <stdin>:4:3"), "{out}");
    assert!(out.contains("    in ball(x = 0, r = 2) called at <stdin>:6:1"), "{out}");
    let [r, g, b] = image::open(&png).expect("an image").to_rgb8().get_pixel(20, 15).0;
    assert!(out.contains(&format!("rgb ({r}, {g}, {b}) = round(255 × (")), "{out}");
    assert!(!out.contains("changed since"), "{out}");
}

#[test]
fn pick_needs_a_picture_and_a_pixel_in_it() {
    let script = "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end
:pick 1 1
:render 40 30
:pick 40 2
:pick 3
put sphere center 0, 0, 0 radius 3 kd 1 ks 0 phong 1 color 0, 255, 0 end
:pick 20 15
";
    let assert = rayrepl().arg("--keep-going").write_stdin(script).assert().code(1);
    let output = assert.get_output();
    let (out, err) = (String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    assert!(err.contains("no picture yet: `:render` first, then pick one of its pixels"), "{err}");
    assert!(err.contains("`40`: X is a whole number from 0 to 39 in the last picture (40×30)"), "{err}");
    assert!(err.contains("give the pixel's X (from the left) and Y (from the top)\nusage: :pick X Y"), "{err}");
    assert!(out.contains("the scene or the settings changed since that picture"), "{out}");
}

/// On a terminal, `:pick` shows the last picture with the pixel marked,
/// then the explanation.
#[test]
fn pick_on_a_terminal_shows_the_marked_picture() {
    use expectrl::{Any, Eof, Expect, Session};
    let home = tempfile::tempdir().expect("temporary directory");
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_rayrepl"));
    command.env("XDG_DATA_HOME", home.path()).env("TERM", "xterm-256color").env("NO_COLOR", "1");
    let mut session = Session::spawn(command).expect("the binary starts");
    session.set_expect_timeout(Some(std::time::Duration::from_secs(30)));
    session.expect("ray> ").expect("a first prompt");
    session.send_line("put sphere center 0, 0, 0 radius 2 kd 1 ks 0 phong 1 color 255, 0, 0 end").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":render 40 30").unwrap();
    // The first preview asks the terminal what it can show (kitty images,
    // then sixels, each query followed by a device attributes request):
    // answer as a terminal with neither, until the picture is shown.
    loop {
        let found = session.expect(Any::boxed(vec![Box::new("\x1b[c"), Box::new("40×30 in")])).unwrap();
        if found.get(0) != Some(b"\x1b[c".as_slice()) {
            break;
        }
        session.send("\x1b[?62;22c").unwrap();
    }
    session.expect("ray> ").unwrap();
    session.send_line(":pick 20 15").unwrap();
    let shown = session.expect("rgb (").expect("an explanation");
    let before = String::from_utf8_lossy(shown.before());
    let picture = before.find('▀').or_else(|| before.find('▄')).expect("the picture, in half blocks");
    let text = before.find("pixel (20, 15)").expect("the words");
    assert!(before.contains("the camera ray met a sphere put at <input 1>:1:1"), "{before}");
    assert!(picture < text, "the picture comes first: {before}");
    session.send_line(":quit").unwrap();
    session.send_line(":quit").unwrap();
    session.expect(Eof).unwrap();
}
