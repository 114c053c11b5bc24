//! The warnings about the scene (`src/lint.rs`): each program of
//! `tests/cases/warnings/` renders black or wrong for the reason its first
//! line names (`# warns: CHECK`) and gets that warning, from a file and from
//! a piped script; the bundled scenes get none; a warning changes neither
//! the picture nor the exit status, is given once, and `--allow` turns it
//! off.

use std::path::{Path, PathBuf};

use crate::common::programs::evaluated;
use assert_cmd::Command;
use glam::DVec3;
use rayrepl::lang::eval::Origins;
use rayrepl::lint::{Allowed, Check, Picture, check_scene};
use rayrepl::render::{self, RenderControl, RenderOptions, SceneGeometry, Screen};
use rayrepl::scene::Scene;
use rayrepl::session::SessionOptions;
use rayrepl::terminal::run_script;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn rayrepl() -> Command {
    Command::cargo_bin("rayrepl").expect("the binary is built")
}

/// The `.ray` files of a folder, sorted.
fn ray_files(folder: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join(folder))
        .expect("the folder exists")
        .map(|entry| entry.expect("readable entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "ray"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no scenes in {folder}");
    files
}

/// Each warning case with the check its first line names.
fn cases() -> Vec<(PathBuf, Check)> {
    let cases: Vec<_> = ray_files("tests/cases/warnings")
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("readable case");
            let name = text.lines().next().and_then(|line| line.strip_prefix("# warns: ")).expect("a `# warns:` line");
            let check = Check::ALL.into_iter().find(|c| c.name() == name.trim()).expect("a known check");
            (path, check)
        })
        .collect();
    for check in Check::ALL {
        assert!(cases.iter().any(|(_, c)| *c == check), "no case for {}", check.name());
    }
    cases
}

/// The checks that stderr shows warnings of (each warning of a check names
/// it in its note), with the number of warnings.
fn checks_warned(stderr: &str) -> Vec<&'static str> {
    Check::ALL.into_iter().map(Check::name).filter(|name| stderr.contains(&format!("`--allow {name}`"))).collect()
}

fn stderr_of(output: &std::process::Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn each_case_gets_its_warning_from_a_file_and_allow_turns_it_off() {
    for (path, check) in cases() {
        let output = rayrepl().arg("--check").arg(&path).output().expect("runs");
        let stderr = stderr_of(&output);
        assert_eq!(output.status.code(), Some(0), "{}: {stderr}", path.display());
        assert_eq!(checks_warned(&stderr), [check.name()], "{}: {stderr}", path.display());
        assert_eq!(stderr.matches("warning:").count(), 1, "{}: {stderr}", path.display());
        assert!(stderr.contains("help: "), "{}: a likely fix: {stderr}", path.display());
        let file = path.file_name().expect("a file name").to_string_lossy();
        assert!(stderr.contains(&format!("{file}:")), "{}: the place: {stderr}", path.display());

        let allowed = rayrepl().args(["--check", "--allow"]).arg(check.name()).arg(&path).output().expect("runs");
        assert_eq!(stderr_of(&allowed), "", "{}", path.display());
        let all = rayrepl().args(["--check", "--allow", "all"]).arg(&path).output().expect("runs");
        assert_eq!(stderr_of(&all), "", "{}", path.display());
    }
}

#[test]
fn each_case_gets_its_warning_in_a_piped_script_when_it_is_saved() {
    let dir = tempfile::tempdir().expect("temporary folder");
    for (path, check) in cases() {
        let text = std::fs::read_to_string(&path).expect("readable case");
        let out = dir.path().join("out.png");
        // Saved twice: the warning comes with the first picture only.
        let script = format!("{text}\n:save {0} 24 18\n:save {0} 24 18\n", out.display());
        let (mut stdout, mut stderr) = (Vec::new(), Vec::new());
        let code = run_script(script.as_bytes(), &mut stdout, &mut stderr, &SessionOptions::default());
        let stderr = String::from_utf8(stderr).expect("text");
        assert_eq!(code, 0, "{}: {stderr}", path.display());
        assert_eq!(checks_warned(&stderr), [check.name()], "{}: {stderr}", path.display());
        assert_eq!(stderr.matches("warning:").count(), 1, "{}: {stderr}", path.display());
        assert!(stderr.contains("<stdin>:"), "{stderr}");
    }
}

#[test]
fn a_script_that_renders_nothing_is_not_warned() {
    let (path, _) = cases().into_iter().find(|(_, check)| *check == Check::Colours).expect("a colours case");
    let text = std::fs::read_to_string(path).expect("readable case");
    let (mut stdout, mut stderr) = (Vec::new(), Vec::new());
    assert_eq!(run_script(text.as_bytes(), &mut stdout, &mut stderr, &SessionOptions::default()), 0);
    let stderr = String::from_utf8(stderr).expect("text");
    assert!(!stderr.contains("warning:"), "warnings come with a render, not with each input: {stderr}");
}

#[test]
fn a_warning_changes_neither_the_picture_nor_the_exit_status() {
    let dir = tempfile::tempdir().expect("temporary folder");
    for (path, _) in cases() {
        let warned = dir.path().join("warned.png");
        let quiet = dir.path().join("quiet.png");
        let size = ["--width", "24", "--height", "18", "-o"];
        let first = rayrepl().arg(&path).args(size).arg(&warned).output().expect("runs");
        let second = rayrepl().arg(&path).args(size).arg(&quiet).args(["--allow", "all"]).output().expect("runs");
        assert!(stderr_of(&first).contains("warning:"), "{}", path.display());
        assert!(!stderr_of(&second).contains("warning:"), "{}", path.display());
        assert_eq!(first.status.code(), Some(0), "{}", path.display());
        assert_eq!(second.status.code(), Some(0), "{}", path.display());
        let read = |p: &Path| image::open(p).expect("an image").to_rgb8();
        assert_eq!(read(&warned), read(&quiet), "{}", path.display());
    }
}

#[test]
fn an_animation_warns_once_and_leaves_out_what_moves() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let run = |text: &str, frames: Option<&str>| {
        let path = dir.path().join("scene.ray");
        std::fs::write(&path, text).expect("scene written");
        let mut command = rayrepl();
        command.arg(&path).args(["--width", "8", "--height", "6", "-o"]);
        match frames {
            Some(frames) => command.arg(dir.path().join("out.gif")).args(["--anim", frames]),
            None => command.arg(dir.path().join("out.png")),
        };
        let output = command.output().expect("runs");
        assert_eq!(output.status.code(), Some(0));
        stderr_of(&output)
    };
    let behind = "camera distance -10 angle 1 end\nambient 0.2\nlight vector 0, 0, 0 intensity 1 end\n\
                  put sphere center time, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end\n";
    assert_eq!(checks_warned(&run(behind, Some("4"))), ["camera-distance"]);
    assert_eq!(run(behind, Some("4")).matches("warning:").count(), 1);
    // A light that fades in from 0: at time 0 it lights nothing, but an
    // animation means it.
    let fading = "camera distance 10 angle 1 end\nambient 0.2\nlight vector 0, 0, 0 intensity (time - 1) / 3 end\n\
                  put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end\n";
    assert_eq!(checks_warned(&run(fading, None)), ["zero-light"]);
    assert!(checks_warned(&run(fading, Some("4"))).is_empty());
}

#[test]
fn an_object_put_only_at_some_times_or_in_a_branch_not_taken_is_not_warned() {
    let ball = "object ball = sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end";
    let floor = "put plane rotation 0, 0, 0 shift -1 kd 1 ks 0 phong 1 color 200, 200, 200 end";
    for put in ["if time > 5 then put ball end", "if 2 < 1 then put ball else put group end end"] {
        let text = format!("camera distance 10 angle 1 end\nambient 0.2\n{ball}\n{floor}\n{put}\n");
        let dir = tempfile::tempdir().expect("temporary folder");
        let path = dir.path().join("scene.ray");
        std::fs::write(&path, text).expect("scene written");
        let output = rayrepl().arg("--check").arg(&path).output().expect("runs");
        assert_eq!(stderr_of(&output), "", "{put}");
    }
}

/// The scene of the file at `path`, at `time`, with its origins.
fn evaluate(path: &Path, time: f64) -> (Scene, Origins) {
    let text = std::fs::read_to_string(path).expect("readable scene");
    let interpreter = evaluated(&path.display().to_string(), &text, time);
    let origins = interpreter.origins().clone();
    (interpreter.into_scene(), origins)
}

#[test]
fn the_bundled_scenes_get_no_warning() {
    let mut files = ray_files("scenarios");
    files.extend(ray_files("tests/cases/valid"));
    let pictures = [
        Picture { width: 800, height: 600, screen: Screen::Centered, animation: false },
        Picture { width: 96, height: 72, screen: Screen::Centered, animation: false },
        Picture { width: 64, height: 64, screen: Screen::Bottom, animation: false },
        Picture { width: 800, height: 600, screen: Screen::Centered, animation: true },
    ];
    for path in files {
        // 7 is the time of the golden images.
        for time in [0.0, 1.0, 7.0] {
            let (scene, origins) = evaluate(&path, time);
            for picture in &pictures {
                let warnings = check_scene(&scene, &origins, picture, Allowed::default());
                let shown: Vec<_> = warnings.iter().map(|w| &w.diagnostic.message).collect();
                assert!(shown.is_empty(), "{} at time {time}, {picture:?}: {shown:?}", path.display());
            }
        }
    }
}

/// A tiny deterministic generator (xorshift), for the test below.
struct Random(u64);

impl Random {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn between(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.next()
    }

    fn vector(&mut self, size: f64) -> DVec3 {
        DVec3::new(self.between(-size, size), self.between(-size, size), self.between(-size, size))
    }
}

#[test]
fn out_of_view_is_said_only_of_scenes_that_render_black() {
    let mut random = Random(0x5eed_1234_abcd_ef01);
    let texture = "kd 1 ks 0 phong 1 color 255, 255, 255";
    let (mut warned, mut seen) = (0, 0);
    for case in 0..300 {
        let (distance, angle) = (random.between(0.5, 20.0), random.between(0.2, 3.0));
        // Near the eye, so that many shapes straddle the edges of the view.
        let c = DVec3::new(0.0, 0.0, distance) + random.vector(8.0);
        let r = random.vector(3.0);
        let put = match case % 3 {
            0 => format!(
                "put sphere center {:?}, {:?}, {:?} radius {:?} {texture} end",
                c.x,
                c.y,
                c.z,
                random.between(0.05, 3.0)
            ),
            1 => format!(
                "put translate rotate box center 0, 0, 0 length {:?}, 0.6, 0.2 {texture} end by {:?}, {:?}, {:?} end by {:?}, {:?}, {:?} end",
                random.between(0.1, 4.0),
                r.x,
                r.y,
                r.z,
                c.x,
                c.y,
                c.z
            ),
            _ => format!(
                "put translate plane rotation {:?}, {:?}, {:?} shift 0 {texture} end by {:?}, {:?}, {:?} end",
                r.x, r.y, r.z, c.x, c.y, c.z
            ),
        };
        let text = format!("camera distance {distance:?} angle {angle:?} end\nambient 1\n{put}\n");
        let interpreter = evaluated("case.ray", &text, 0.0);
        let (width, height) = (40, 30);
        let picture = Picture { width, height, screen: Screen::Centered, animation: false };
        let warnings = check_scene(interpreter.scene(), interpreter.origins(), &picture, Allowed::default());
        let out_of_view = warnings.iter().any(|warning| warning.check == Check::OutOfView);
        let scene = interpreter.into_scene();
        let options = RenderOptions { width, height, samples: 4, ..RenderOptions::default() };
        let control = RenderControl { progress: None, cancel: None };
        let image = render::render(&scene, &SceneGeometry::new(&scene), &options, &control).expect("not cancelled").0;
        let black = image.pixels().all(|p| p.0 == [0, 0, 0]);
        assert!(!out_of_view || black, "case {case}: warned out of view, but the picture shows it:\n{text}");
        warned += usize::from(out_of_view);
        seen += usize::from(!black);
    }
    assert!(warned > 30 && seen > 30, "both kinds occur: {warned} out of view, {seen} seen");
}
