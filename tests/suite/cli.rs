//! The command line, as a user runs it: every flag and every error.

use std::path::{Path, PathBuf};

use assert_cmd::Command;
use predicates::prelude::*;
use predicates::str::contains;
use rayrepl::render::isa::ISA_VARIABLE;

use crate::common::interrupt::{interrupt, is_temporary, names_in, wait_for_a_write, wait_for_files};

/// A scene with one lit red sphere in the middle of the picture.
const SPHERE: &str = "camera distance 10 angle 1 end
ambient 0.2
light vector 0.5, 0, 0 intensity 0.8 end
put sphere center 0, 0, 0 radius 2 kd 0.8 ks 0 phong 10 color 255, 0, 0 end
";

/// The same sphere moving right with `time`.
const MOVING: &str = "camera distance 10 angle 1 end
ambient 0.2
light vector 0.5, 0, 0 intensity 0.8 end
put sphere center time - 2, 0, 0 radius 1 kd 0.8 ks 0 phong 10 color 255, 0, 0 end
put plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0 phong 10 color 0, 0, 255 end
";

fn rayrepl() -> Command {
    Command::cargo_bin("rayrepl").expect("the binary is built")
}

/// A fresh temporary folder holding `scene.ray` with `text`.
fn scene(text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let path = dir.path().join("scene.ray");
    std::fs::write(&path, text).expect("scene written");
    (dir, path)
}

fn read_image(path: &Path) -> image::RgbImage {
    image::open(path).expect("a readable image").to_rgb8()
}

#[test]
fn renders_a_png_of_the_requested_size() {
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("out.png");
    rayrepl().arg(&path).args(["--width", "40", "--height", "30", "-o"]).arg(&out).assert().success();
    let image = read_image(&out);
    assert_eq!(image.dimensions(), (40, 30));
    assert!(image.get_pixel(20, 15)[0] > 0, "the centre shows the red sphere");
}

#[test]
fn the_default_size_is_800_by_600() {
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("out.png");
    rayrepl().arg(&path).arg("-o").arg(&out).assert().success();
    assert_eq!(read_image(&out).dimensions(), (800, 600));
}

#[test]
fn legacy_course_flags_are_accepted() {
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("out.ppm");
    rayrepl().arg(&path).args(["-hsize", "16", "-vsize", "8", "-depth", "2", "-o"]).arg(&out).assert().success();
    let bytes = std::fs::read(&out).expect("ppm written");
    assert!(bytes.starts_with(b"P6\n16 8\n255\n"));
    assert_eq!(bytes.len(), "P6\n16 8\n255\n".len() + 16 * 8 * 3);
}

#[test]
fn dash_o_dash_writes_ppm_to_stdout() {
    let (_dir, path) = scene(SPHERE);
    let output = rayrepl().arg(&path).args(["--width", "4", "--height", "2", "-o", "-"]).output().expect("runs");
    assert!(output.status.success());
    assert!(output.stdout.starts_with(b"P6\n4 2\n255\n"));
}

#[test]
fn a_scene_can_come_from_stdin() {
    rayrepl()
        .args(["--check", "-"])
        .write_stdin(SPHERE)
        .assert()
        .success()
        .stdout(contains("1 sphere, 0 planes, 0 boxes, 1 light"));
}

#[test]
fn check_prints_a_summary_and_writes_nothing() {
    let (dir, path) = scene(SPHERE);
    rayrepl().current_dir(dir.path()).arg("--check").arg(&path).assert().success().stdout(contains("1 sphere"));
    assert!(!dir.path().join("scene.png").exists());
}

#[test]
fn check_to_a_full_disk_fails_saying_why() {
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        return; // Not on this platform.
    };
    let (dir, path) = scene(SPHERE);
    let binary = assert_cmd::cargo::cargo_bin("rayrepl");
    let mut checked = std::process::Command::new(binary);
    let output = checked.current_dir(dir.path()).arg("--check").arg(&path).stdout(full).output().expect("rayrepl runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.starts_with("rayrepl: cannot write the summary to standard output: "), "{stderr}");
}

#[test]
fn without_dash_o_the_image_is_named_after_the_scene() {
    let (dir, path) = scene(SPHERE);
    rayrepl().current_dir(dir.path()).arg(&path).args(["--width", "8", "--height", "8"]).assert().success();
    assert!(dir.path().join("scene.png").exists());
}

#[test]
fn time_moves_the_scene() {
    let (dir, path) = scene(MOVING);
    let at = |time: &str| {
        let out = dir.path().join(format!("t{time}.png"));
        rayrepl()
            .arg(&path)
            .args(["--width", "32", "--height", "16", "--time", time, "-o"])
            .arg(&out)
            .assert()
            .success();
        read_image(&out)
    };
    assert_ne!(at("0"), at("3"));
}

#[test]
fn samples_threads_screen_and_stats_are_accepted() {
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("out.png");
    rayrepl()
        .arg(&path)
        .args([
            "--width",
            "16",
            "--height",
            "12",
            "--samples",
            "4",
            "--threads",
            "1",
            "--screen",
            "bottom",
            "--stats",
            "-o",
        ])
        .arg(&out)
        .assert()
        .success()
        .stderr(contains("primary").and(contains("Mrays/s")).and(contains("(spheres and boxes: a list of 1; ")));
}

/// `--stats` says how the objects are searched (past 4 objects, a tree)
/// and which compiled form of the renderer runs: the widest the processor
/// has, or the portable one that `RAYREPL_ISA=portable` asks for, which
/// gives the same bytes.
#[test]
fn stats_name_the_tree_and_the_compiled_form_and_the_forms_give_the_same_bytes() {
    let spheres: String = (0..5)
        .map(|k| format!("put sphere center {k}, 0, 0 radius 0.4 kd 1 ks 0.5 phong 7 color 255, 0, 0 end\n"))
        .collect();
    let (dir, path) = scene(&format!(
        "camera distance 10 angle 1 end\nambient 0.2\nlight vector 0.5, 0.3, 1 intensity 0.8 end\n{spheres}\
         put sphere center time - 2, 1, 0 radius 0.5 kd 0.8 ks 0.4 phong 10 color 0, 255, 0 end\n\
         put plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0.3 phong 10 color 0, 0, 255 end\n"
    ));
    let render = |isa: Option<&str>, form: &str| {
        let out = dir.path().join(format!("{form}.png"));
        let line = format!(
            r"build [0-9.]+ s \(spheres and boxes: a tree of 5; those depending on time: a list of 1; {form} code\)"
        );
        let names_the_form = predicates::str::is_match(line).expect("a valid pattern");
        let mut command = rayrepl();
        if let Some(isa) = isa {
            command.env(ISA_VARIABLE, isa);
        }
        command
            .arg(&path)
            .args(["--width", "40", "--height", "30", "--stats", "-o"])
            .arg(&out)
            .assert()
            .success()
            .stderr(names_the_form);
        std::fs::read(out).expect("written")
    };
    let widest = if cfg!(target_arch = "x86_64") { "(AVX2|portable)" } else { "portable" };
    assert_eq!(render(None, widest), render(Some("portable"), "portable"));
}

#[test]
fn the_image_does_not_depend_on_the_thread_count() {
    let (dir, path) = scene(MOVING);
    let render = |threads: &str| {
        let out = dir.path().join(format!("threads{threads}.png"));
        rayrepl()
            .arg(&path)
            .args(["--width", "37", "--height", "23", "--threads", threads, "-o"])
            .arg(&out)
            .assert()
            .success();
        std::fs::read(out).expect("written")
    };
    assert_eq!(render("1"), render("2"));
}

#[test]
fn an_animation_writes_numbered_frames_that_change() {
    let (dir, path) = scene(MOVING);
    let out = dir.path().join("frame.png");
    rayrepl().arg(&path).args(["--width", "24", "--height", "12", "--anim", "3", "-o"]).arg(&out).assert().success();
    let frames: Vec<_> = (1..=3).map(|k| read_image(&dir.path().join(format!("frame000{k}.png")))).collect();
    assert_ne!(frames[0], frames[1]);
    assert_ne!(frames[1], frames[2]);
}

#[test]
fn animation_frames_match_still_renders_at_the_same_time() {
    let (dir, path) = scene(MOVING);
    let out = dir.path().join("frame.png");
    rayrepl().arg(&path).args(["--width", "24", "--height", "12", "--anim", "2", "-o"]).arg(&out).assert().success();
    let still = dir.path().join("still.png");
    rayrepl().arg(&path).args(["--width", "24", "--height", "12", "--time", "2", "-o"]).arg(&still).assert().success();
    assert_eq!(read_image(&dir.path().join("frame0002.png")), read_image(&still));
}

#[test]
fn frames_renders_only_the_asked_subset() {
    let (dir, path) = scene(MOVING);
    let out = dir.path().join("f.png");
    rayrepl()
        .arg(&path)
        .args(["--width", "8", "--height", "8", "--anim", "10", "--frames", "3..4", "-o"])
        .arg(&out)
        .assert()
        .success();
    let mut names: Vec<String> =
        std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, ["f0003.png", "f0004.png", "scene.ray"]);
}

#[test]
fn frames_past_the_end_are_refused() {
    let (dir, path) = scene(MOVING);
    let out = dir.path().join("f.png");
    rayrepl()
        .arg(&path)
        .args(["--anim", "3", "--frames", "2..5", "-o"])
        .arg(&out)
        .assert()
        .failure()
        .stderr(contains("past the last frame"));
}

#[test]
fn a_gif_animation_has_every_frame() {
    let (dir, path) = scene(MOVING);
    let out = dir.path().join("anim.gif");
    rayrepl().arg(&path).args(["--width", "16", "--height", "8", "--anim", "4", "-o"]).arg(&out).assert().success();
    let file = std::io::BufReader::new(std::fs::File::open(&out).expect("gif written"));
    let decoder = image::codecs::gif::GifDecoder::new(file).expect("a gif");
    let frames = image::AnimationDecoder::into_frames(decoder).collect_frames().expect("frames decode");
    assert_eq!(frames.len(), 4);
}

#[test]
fn a_failing_frame_keeps_the_frames_before_it() {
    // Frame 4 divides by zero; frames 1 to 3 are written first.
    let (dir, path) = scene(&format!("{MOVING}let bad = 1 / (time - 4)\n"));
    let out = dir.path().join("f.png");
    rayrepl()
        .arg(&path)
        .args(["--width", "8", "--height", "8", "--anim", "6", "-o"])
        .arg(&out)
        .assert()
        .failure()
        .stderr(contains("division by zero").and(contains("scene.ray:6:")));
    let mut names: Vec<String> =
        std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, ["f0001.png", "f0002.png", "f0003.png", "scene.ray"]);
}

#[test]
fn a_static_animation_repeats_one_image() {
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("s.png");
    rayrepl()
        .arg(&path)
        .args(["--width", "8", "--height", "8", "--anim", "3", "--stats", "-o"])
        .arg(&out)
        .assert()
        .success();
    assert_eq!(read_image(&dir.path().join("s0001.png")), read_image(&dir.path().join("s0003.png")));
}

#[test]
fn a_missing_scene_is_a_clear_error() {
    rayrepl()
        .arg("no/such/scene.ray")
        .assert()
        .code(1)
        .stderr(contains("cannot read `no/such/scene.ray`: no such file or folder"));
}

#[test]
fn an_unknown_output_format_is_refused_before_rendering() {
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("out.jpeg");
    rayrepl().arg(&path).arg("-o").arg(&out).assert().code(1).stderr(contains("image format"));
    assert!(!out.exists());
}

#[test]
fn an_output_mistake_is_said_before_the_scene_is_read() {
    let (dir, _path) = scene(SPHERE);
    let out = dir.path().join("out.jpeg");
    rayrepl().arg("no/such/scene.ray").arg("-o").arg(&out).assert().code(1).stderr(contains("image format"));
}

#[test]
fn a_missing_output_folder_is_refused_before_rendering() {
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("nowhere/out.png");
    rayrepl().arg(&path).arg("-o").arg(&out).assert().code(1).stderr(contains("does not exist"));
}

#[test]
fn an_unwritable_output_leaves_no_file_behind() {
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("taken");
    std::fs::create_dir(out.join("")).expect("folder made");
    let out = out.join("x.png");
    std::fs::create_dir(&out).expect("a folder where the image should go");
    rayrepl().arg(&path).args(["--width", "4", "--height", "4", "-o"]).arg(&out).assert().code(1);
    let leftovers = std::fs::read_dir(dir.path().join("taken")).unwrap().count();
    assert_eq!(leftovers, 1, "only the blocking folder remains");
}

#[test]
fn zero_width_is_refused() {
    let (_dir, path) = scene(SPHERE);
    rayrepl().arg(&path).args(["--width", "0"]).assert().code(2).stderr(contains("width"));
}

#[test]
fn a_bad_frame_range_is_refused() {
    let (_dir, path) = scene(SPHERE);
    rayrepl().arg(&path).args(["--anim", "3", "--frames", "x"]).assert().code(2).stderr(contains("frame range"));
}

#[test]
fn dash_o_dash_is_refused_for_animations() {
    let (_dir, path) = scene(SPHERE);
    rayrepl().arg(&path).args(["--anim", "3", "-o", "-"]).assert().code(1).stderr(contains("single image"));
}

#[test]
fn a_syntax_error_shows_file_line_column_and_caret() {
    let (_dir, path) = scene(
        "camera distance 10 angle 1 end\nambient 0.2\nput sphere center 0, 0 radius 1 kd 1 ks 0 phong 1 color 1, 1, 1 end\n",
    );
    let assert = rayrepl().arg(&path).assert().code(1);
    let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(stderr.contains("scene.ray:3:"), "{stderr}");
    assert!(stderr.contains('^'), "{stderr}");
}

#[test]
fn colours_follow_the_conventions_in_checks_and_scripts() {
    let text = "camera distance 10 angle 1 end\nambient 0.2\nlet a = 1 / 0\n";
    let (_dir, path) = scene(text);
    // Standard error is a pipe here: no colours unless forced, and `NO_COLOR` wins.
    let cases: [(&[(&str, &str)], bool); 4] = [
        (&[], false),
        (&[("CLICOLOR_FORCE", "1")], true),
        (&[("CLICOLOR_FORCE", "1"), ("NO_COLOR", "1")], false),
        (&[("CLICOLOR_FORCE", "1"), ("CLICOLOR", "0")], true),
    ];
    for (variables, coloured) in cases {
        for script in [false, true] {
            let mut command = rayrepl();
            command.env_remove("NO_COLOR").env_remove("CLICOLOR_FORCE").env_remove("CLICOLOR").envs(variables.to_vec());
            if script {
                command.write_stdin(text);
            } else {
                command.arg("--check").arg(&path);
            }
            let output = command.assert().code(1).get_output().clone();
            let stderr = String::from_utf8_lossy(&output.stderr);
            assert_eq!(stderr.contains("\x1b["), coloured, "{variables:?}, script {script}: {stderr}");
            assert!(stderr.contains("division by zero"), "{stderr}");
        }
    }
}

#[test]
fn an_evaluation_error_writes_no_image() {
    let (dir, path) = scene("camera distance 10 angle 1 end\nambient 0.2\nlet a = 1 / 0\n");
    let out = dir.path().join("out.png");
    rayrepl().arg(&path).arg("-o").arg(&out).assert().code(1).stderr(contains("scene.ray:3:"));
    assert!(!out.exists());
}

#[test]
fn the_recursion_limit_is_configurable() {
    let text = "camera distance 10 angle 1 end\nambient 0.2\nproc f(n)\n  if 0 < n then f(n - 1) end\nend\nf(50)\n";
    let (_dir, path) = scene(text);
    rayrepl().arg("--check").arg(&path).assert().success();
    rayrepl().arg("--check").arg(&path).args(["--max-calls", "10"]).assert().code(1).stderr(contains("recursion"));
}

#[test]
fn the_primitive_cap_is_configurable() {
    let (_dir, path) = scene(SPHERE);
    rayrepl().arg("--check").arg(&path).args(["--max-primitives", "0"]).assert().code(1);
}

#[test]
fn help_lists_the_examples() {
    rayrepl().arg("--help").assert().success().stdout(contains("--anim").and(contains("-hsize")));
}

#[test]
fn a_non_finite_time_is_refused() {
    let (_dir, path) = scene(SPHERE);
    rayrepl().arg(&path).args(["--time", "nan"]).assert().code(2).stderr(contains("finite"));
}

#[test]
fn adaptive_sampling_is_accepted() {
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("out.ppm");
    rayrepl()
        .arg(&path)
        .args(["--width", "32", "--height", "24", "--samples", "4", "--adaptive", "--stats", "-o"])
        .arg(&out)
        .assert()
        .success()
        .stderr(contains("adaptive: ").and(contains(" pixels refined")));
    assert!(out.exists());
}

#[test]
fn an_animation_warns_once_not_once_per_frame() {
    let text = "camera distance 10 angle 1 end\nambient 0.2\n\
                put sphere center time, 0, 0 radius 1 kd 2 ks 0 phong 1 color 255, 0, 0 end\n";
    let (dir, path) = scene(text);
    let out = dir.path().join("w.png");
    let assert = rayrepl().arg(&path).args(["--width", "8", "--height", "8", "--anim", "3", "-o"]).arg(&out).assert();
    let stderr = String::from_utf8_lossy(&assert.success().get_output().stderr).into_owned();
    assert_eq!(stderr.matches("warning:").count(), 1, "{stderr}");
}

#[test]
fn an_image_too_large_for_memory_is_refused_before_rendering() {
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("out.png");
    rayrepl()
        .arg(&path)
        .args(["--width", "65535", "--height", "65535", "-o"])
        .arg(&out)
        .assert()
        .code(2)
        .stderr(contains("has 4294836225 pixels; the most is 67108864").and(contains("4 GiB of memory")));
    rayrepl()
        .arg(&path)
        .args(["--width", "65536", "--height", "65536"])
        .assert()
        .code(2)
        .stderr(contains("the width must be a whole number from 1 to 65535"));
    assert!(!out.exists());
}

#[test]
fn every_entry_point_shares_the_depth_limit() {
    let (_dir, path) = scene(SPHERE);
    rayrepl()
        .arg(&path)
        .args(["--depth", "4294967295"])
        .assert()
        .code(2)
        .stderr(contains("the depth must be a whole number from 0 to 1000"));
}

#[test]
fn flags_that_would_do_nothing_are_refused() {
    let (_dir, path) = scene(SPHERE);
    let cases: [(&[&str], &str); 8] = [
        (&["--frames", "1..2"], "--frames is for an animation: give --anim N too"),
        (&["--adaptive"], "--adaptive gives more samples to some pixels: give --samples N too"),
        (&["--adaptive", "--samples", "1"], "give --samples N too, with N > 1"),
        (&["--anim", "3", "--time", "2"], "frame k of an animation has time = k"),
        (&["--no-preview"], "--no-preview is for the interactive session"),
        (&["--keep-going"], "--keep-going is for a script on standard input"),
        (&["--lesson", "1"], "--lesson is for the session"),
        (&["-i", "-o", "x.png"], "-o does nothing in a session (-i starts a session)"),
    ];
    for (flags, message) in cases {
        rayrepl().arg(&path).args(flags).assert().code(2).stderr(contains(message));
    }
    rayrepl()
        .args(["--anim", "3"])
        .write_stdin(":quit\n")
        .assert()
        .code(2)
        .stderr(contains("--anim does nothing in a session (without a scene file, rayrepl starts a session)"));
    rayrepl()
        .arg(&path)
        .args(["--check", "-o", "x.png"])
        .assert()
        .code(2)
        .stderr(contains("'--check' cannot be used with '--output <FILE>'"));
    // Flags the explanation, the check and the export have no use for.
    let unused: [(&[&str], &str); 5] = [
        (&["--explain", "1,1", "--stats"], "'--explain <X,Y>' cannot be used with '--stats'"),
        (&["--export-pov", "x.pov", "--explain", "1,1"], "'--export-pov <OUT.pov>' cannot be used with '--explain"),
        (&["--export-pov", "x.pov", "--threads", "2"], "'--export-pov <OUT.pov>' cannot be used with '--threads"),
        (&["--export-pov", "x.pov", "--screen", "bottom"], "'--export-pov <OUT.pov>' cannot be used with '--screen"),
        (&["--check", "--threads", "2"], "'--check' cannot be used with '--threads"),
    ];
    for (flags, message) in unused {
        rayrepl().arg(&path).args(flags).assert().code(2).stderr(contains(message));
    }
}

/// Whether `ffmpeg` can be run (videos need it).
fn has_ffmpeg() -> bool {
    std::process::Command::new("ffmpeg").arg("-version").output().is_ok_and(|out| out.status.success())
}

#[test]
fn an_interrupted_animation_leaves_no_temporary_file_and_the_old_output_intact() {
    let videos: &[&str] = if has_ffmpeg() { &["anim.mp4"] } else { &[] };
    for name in ["anim.gif"].iter().chain(videos) {
        for signal in ["-INT", "-TERM"] {
            let (dir, path) = scene(MOVING);
            let out = dir.path().join(name);
            std::fs::write(&out, b"the old animation").expect("old output");
            let child = std::process::Command::new(assert_cmd::cargo::cargo_bin("rayrepl"))
                .arg(&path)
                .args(["--width", "64", "--height", "48", "--anim", "1000000", "-o"])
                .arg(&out)
                .stderr(std::process::Stdio::piped())
                .spawn()
                .expect("started");
            // Wait until the file is being written, frame by frame, into its temporary file.
            while !names_in(dir.path()).iter().any(|name| is_temporary(name)) {
                std::thread::sleep(std::time::Duration::from_millis(20));
            }
            let killed = std::process::Command::new("kill").arg(signal).arg(child.id().to_string()).status();
            assert!(killed.expect("kill runs").success());
            let output = child.wait_with_output().expect("ended");
            let stderr = String::from_utf8_lossy(&output.stderr);
            assert_eq!(output.status.code(), Some(130), "{name} {signal}: {stderr}");
            assert!(stderr.contains("rayrepl: interrupted: no file was written"), "{stderr}");
            assert_eq!(names_in(dir.path()), [*name, "scene.ray"], "{signal}");
            assert_eq!(std::fs::read(&out).expect("still there"), b"the old animation");
        }
    }
}

#[test]
fn ctrl_c_while_a_large_image_is_written_leaves_the_old_one_and_no_temporary_file() {
    // Nothing to trace: the time goes into writing 8192x8192 pixels.
    let (dir, path) = scene("camera distance 10 angle 1 end\nambient 0.2\n");
    let out = dir.path().join("big.ppm");
    std::fs::write(&out, b"the old image").expect("old output");
    let child = std::process::Command::new(assert_cmd::cargo::cargo_bin("rayrepl"))
        .arg(&path)
        .args(["--width", "8192", "--height", "8192", "-o"])
        .arg(&out)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("started");
    wait_for_a_write(dir.path());
    interrupt(child.id());
    let output = child.wait_with_output().expect("ended");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("rayrepl: interrupted: no file was written"), "{stderr}");
    assert_eq!(names_in(dir.path()), ["big.ppm", "scene.ray"]);
    assert_eq!(std::fs::read(&out).expect("still there"), b"the old image");
}

#[test]
fn ctrl_c_during_numbered_frames_keeps_whole_frames_and_says_which() {
    let (dir, path) = scene(MOVING);
    let child = std::process::Command::new(assert_cmd::cargo::cargo_bin("rayrepl"))
        .arg(&path)
        .args(["--width", "320", "--height", "240", "--anim", "1000000", "-o"])
        .arg(dir.path().join("f.png"))
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("started");
    wait_for_files(dir.path(), ".png", 3);
    interrupt(child.id());
    let output = child.wait_with_output().expect("ended");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(130), "{stderr}");
    let mut frames = names_in(dir.path());
    assert_eq!(frames.pop().as_deref(), Some("scene.ray"), "no temporary file: {frames:?}");
    let (first, last) = (dir.path().join(&frames[0]), dir.path().join(&frames[frames.len() - 1]));
    let said = format!("rayrepl: interrupted: {} ... {} written before it stopped", first.display(), last.display());
    assert!(stderr.contains(&said), "{said}\n{stderr}");
    for (k, frame) in frames.iter().enumerate() {
        assert_eq!(*frame, format!("f{:07}.png", k + 1));
        assert_eq!(read_image(&dir.path().join(frame)).dimensions(), (320, 240), "{frame} is whole");
    }
}

#[test]
fn a_replaced_output_keeps_its_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("private.png");
    std::fs::write(&out, b"old").expect("old output");
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o600)).expect("chmod");
    rayrepl().arg(&path).args(["--width", "4", "--height", "4", "-o"]).arg(&out).assert().success();
    assert_eq!(std::fs::metadata(&out).expect("written").permissions().mode() & 0o777, 0o600);
}

#[test]
fn the_scene_file_is_never_overwritten() {
    let (dir, path) = scene(SPHERE);
    let link = dir.path().join("link.png");
    std::os::unix::fs::symlink(&path, &link).expect("symlink");
    let through_dot = dir.path().join(".").join("scene.ray");
    for output in [path.clone(), through_dot, link] {
        rayrepl().arg(&path).arg("-o").arg(&output).assert().code(1).stderr(contains("is the scene file itself"));
    }
    assert_eq!(std::fs::read_to_string(&path).expect("scene"), SPHERE);
}

#[test]
fn output_mistakes_are_said_in_plain_words() {
    let (dir, path) = scene(SPHERE);
    let folder = format!("{}/", dir.path().display());
    rayrepl().arg(&path).args(["-o", &folder]).assert().code(1).stderr(contains("it is a folder"));
    rayrepl()
        .arg(&path)
        .args(["-o", "x.gif"])
        .assert()
        .code(1)
        .stderr(contains("GIF is for animations").and(contains("cannot tell").not()));
    let blocked = dir.path().join("file");
    std::fs::write(&blocked, b"").expect("a file");
    rayrepl()
        .arg(&path)
        .args(["--width", "4", "--height", "4", "-o"])
        .arg(blocked.join("x.png"))
        .assert()
        .code(1)
        .stderr(contains("os error").not());
}

#[test]
fn image_data_is_not_written_to_a_terminal() {
    let (_dir, path) = scene(SPHERE);
    let mut command = std::process::Command::new(assert_cmd::cargo::cargo_bin("rayrepl"));
    command.arg(&path).args(["--width", "4", "--height", "4", "-o", "-"]);
    use expectrl::Expect;
    let mut session = expectrl::Session::spawn(command).expect("runs in a terminal");
    session.expect("redirect it").expect("the refusal is shown");
}

#[test]
fn a_successful_render_says_so_unless_quiet() {
    let (dir, path) = scene(MOVING);
    let out = dir.path().join("out.png");
    let size = ["--width", "8", "--height", "6", "--depth", "1"];
    let said = format!("wrote {}: 8x6, 1 reflection, ", out.display());
    rayrepl().arg(&path).args(size).arg("-o").arg(&out).assert().success().stderr(contains(said));
    rayrepl().arg(&path).args(size).args(["-q", "-o"]).arg(&out).assert().success().stderr("");
    let frames = dir.path().join("f.png");
    rayrepl()
        .arg(&path)
        .args(size)
        .args(["--anim", "2", "-o"])
        .arg(&frames)
        .assert()
        .success()
        .stderr(contains("f0001.png ... ").and(contains("f0002.png: 2 frames of 8x6, 1 reflection, ")));
    rayrepl().arg(&path).args(size).args(["-o", "-"]).assert().success().stderr(contains("wrote standard output: 8x6"));
}

#[test]
fn a_piped_script_that_writes_nothing_says_how_to_get_a_picture() {
    rayrepl().write_stdin(SPHERE).assert().success().stderr(contains("end it with `:save out.png`"));
    let dir = tempfile::tempdir().expect("temporary folder");
    let script = format!("{SPHERE}:save small.png 4 4\n");
    rayrepl()
        .current_dir(dir.path())
        .write_stdin(script)
        .assert()
        .success()
        .stdout(contains("saved small.png"))
        .stderr(contains(":save out.png").not());
}

/// The lines a running `rayrepl` writes on stderr, as they come.
struct StderrLines {
    lines: std::sync::mpsc::Receiver<String>,
    /// Everything read so far, for failure messages.
    seen: String,
}

impl StderrLines {
    fn of(child: &mut std::process::Child) -> StderrLines {
        use std::io::BufRead;
        let stderr = child.stderr.take().expect("stderr is piped");
        let (sender, lines) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            for line in std::io::BufReader::new(stderr).lines().map_while(Result::ok) {
                if sender.send(line).is_err() {
                    break;
                }
            }
        });
        StderrLines { lines, seen: String::new() }
    }

    /// Waits for a line containing `text` (a generous minute at most).
    fn wait_for(&mut self, text: &str) {
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
        loop {
            let left = deadline.saturating_duration_since(std::time::Instant::now());
            match self.lines.recv_timeout(left) {
                Ok(line) => {
                    self.seen.push_str(&line);
                    self.seen.push('\n');
                    if line.contains(text) {
                        return;
                    }
                }
                Err(_) => panic!("no line with `{text}` on stderr; it said:\n{}", self.seen),
            }
        }
    }
}

/// `rayrepl SCENE --watch` at 16×12, writing to `out`, with its stderr.
fn watch_16x12(scene: &Path, out: &Path) -> (std::process::Child, StderrLines) {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_rayrepl"))
        .arg(scene)
        .args(["--watch", "--width", "16", "--height", "12", "-o"])
        .arg(out)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the binary starts");
    let stderr = StderrLines::of(&mut child);
    (child, stderr)
}

#[test]
fn watch_renders_again_at_every_save_and_keeps_the_last_good_picture() {
    let (dir, path) = scene(SPHERE);
    let out = dir.path().join("out.png");
    let (mut child, mut stderr) = watch_16x12(&path, &out);
    stderr.wait_for("watching");
    stderr.wait_for("wrote");
    let first = std::fs::read(&out).expect("the first picture");
    // A save in place.
    std::fs::write(&path, SPHERE.replace("255, 0, 0", "0, 255, 0")).expect("saved");
    stderr.wait_for("wrote");
    let green = std::fs::read(&out).expect("the second picture");
    assert_ne!(first, green);
    // A broken save: the error, and the picture stays.
    std::fs::write(&path, SPHERE.replace("radius 2", "radius two")).expect("saved");
    stderr.wait_for("--> ");
    stderr.wait_for("the last good picture stays");
    assert_eq!(std::fs::read(&out).expect("the picture"), green);
    // A save by rename, as many editors do.
    let temp = dir.path().join(".scene.ray.swp");
    std::fs::write(&temp, SPHERE.replace("255, 0, 0", "0, 0, 255")).expect("written");
    std::fs::rename(&temp, &path).expect("renamed over the scene");
    stderr.wait_for("wrote");
    let blue = std::fs::read(&out).expect("the third picture");
    assert!(blue != green && blue != first);
    child.kill().expect("the watch ends");
    let _ = child.wait();
}

#[test]
fn watch_follows_the_scene_when_its_folder_is_made_again() {
    // As a `git checkout` or a build tool does: the folder removed, made
    // again, and the scene written in it.
    let dir = tempfile::tempdir().expect("temporary folder");
    let folder = dir.path().join("scenes");
    std::fs::create_dir(&folder).expect("made");
    let path = folder.join("scene.ray");
    std::fs::write(&path, SPHERE).expect("scene written");
    let out = dir.path().join("out.png");
    let (mut child, mut stderr) = watch_16x12(&path, &out);
    stderr.wait_for("wrote");
    let red = std::fs::read(&out).expect("the first picture");
    for colour in ["0, 255, 0", "0, 0, 255"] {
        std::fs::remove_dir_all(&folder).expect("removed");
        std::thread::sleep(std::time::Duration::from_millis(200));
        std::fs::create_dir(&folder).expect("made again");
        std::fs::write(&path, SPHERE.replace("255, 0, 0", colour)).expect("saved");
        stderr.wait_for("wrote");
        assert_ne!(std::fs::read(&out).expect("the new picture"), red, "{colour}");
    }
    child.kill().expect("the watch ends");
    let _ = child.wait();
}

#[test]
fn watch_needs_a_scene_file() {
    let (_dir, path) = scene(SPHERE);
    rayrepl().args(["--watch"]).assert().code(2).stderr(contains("--watch does nothing in a session"));
    rayrepl().args(["--watch", "-"]).assert().code(2).stderr(contains("give its name, not `-`"));
    rayrepl().arg(&path).args(["--watch", "--anim", "3"]).assert().code(2);
    rayrepl().arg(&path).args(["--watch", "-o", "-"]).assert().code(2).stderr(contains("give -o a file name"));
    rayrepl().arg("missing.ray").arg("--watch").assert().code(1).stderr(contains("cannot read `missing.ray`"));
}
