//! Scripts run through the session's library entry point `run_script`, with
//! in-memory input and output: every command, every error path, the exit
//! status and the files written.

use std::path::Path;

use rayrepl::lang::{Interpreter, Limits, SourceMap, parse_file};
use rayrepl::render::{RenderControl, RenderOptions, SceneGeometry, render};
use rayrepl::session::{RenderSettings, SessionOptions};
use rayrepl::terminal::run_script;

use crate::common::interrupt::{interrupt, names_in, wait_for_a_write, wait_for_files};

/// A texture that raises no warning.
const TEX: &str = "kd 0.7 ks 0.3 phong 20 color 255, 80, 40";

/// A small complete scene, as session items.
const SCENE: &str = "\
camera distance 10 angle 0.8 end
ambient 0.2
light vector 0.5, 0, -0.5 intensity 0.8 end
put sphere center 0, 0, 0 radius 2 $T end
put plane rotation 0, 0, 0 shift -2 kd 0.8 ks 0 phong 1 color 200, 200, 200 end
";

/// What a script run printed, and its exit status.
struct Run {
    code: i32,
    out: String,
    err: String,
}

/// Runs `script` (with `$T` replaced by [`TEX`]) with `options`.
fn run_with(script: &str, options: &SessionOptions) -> Run {
    let script = script.replace("$T", TEX);
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let code = run_script(script.as_bytes(), &mut out, &mut err, options);
    Run {
        code,
        out: String::from_utf8(out).expect("output is text"),
        err: String::from_utf8(err).expect("errors are text"),
    }
}

/// Runs `script` with default options.
fn run(script: &str) -> Run {
    run_with(script, &SessionOptions::default())
}

/// Runs `script` and goes on after errors.
fn run_keep_going(script: &str) -> Run {
    run_with(script, &SessionOptions { keep_going: true, ..SessionOptions::default() })
}

fn small_size() -> SessionOptions {
    SessionOptions {
        settings: RenderSettings { width: 32, height: 24, ..RenderSettings::default() },
        ..SessionOptions::default()
    }
}

// ------------------------------------------------------------ items

#[test]
fn items_accumulate_and_are_confirmed() {
    let run = run(&format!("{SCENE}let r = 2 * 3\nobject ball = sphere center 0, 0, 0 radius 1 $T end\n"));
    assert_eq!(run.code, 0, "{}", run.err);
    // No diagnostic; only the advice to write a picture.
    assert!(run.err.starts_with("note: the script wrote no picture"), "{}", run.err);
    let expected = "\
camera: distance 10, angle 0.8
ambient light: 0.2
1 light added (1 light in the scene)
put 1 sphere (1 object in the scene)
put 1 plane (2 objects in the scene)
r = 6
object ball = sphere
";
    assert_eq!(run.out, expected);
}

#[test]
fn procedures_are_confirmed_with_their_parameters_and_calls_with_what_they_put() {
    let run = run("\
proc pair(x, y)
  put sphere center x, 0, 0 radius 1 $T end
  put box center y, 0, 0 length 1, 1, 1 $T end
end
pair(1, 2)
proc pair(x, y) end
pair(1, 2)
");
    assert_eq!(run.code, 0, "{}", run.err);
    assert_eq!(
        run.out,
        "defined proc pair(x, y)\nput 1 sphere and 1 box (2 objects in the scene)\n\
         redefined proc pair(x, y)\nnothing was put\n"
    );
}

#[test]
fn more_than_four_definitions_in_one_input_are_listed_on_one_line() {
    let four = run("let a = 1 let b = 2 object o = sphere center 0, 0, 0 radius a $T end ambient 0.5\n");
    assert_eq!(four.out, "a = 1\nb = 2\nobject o = sphere\nambient light: 0.5\n");
    let five = run("camera distance 2 angle 1 end ambient 0.5 let a = 1 let b = 2 proc p() end p()\n");
    assert_eq!(five.out, "defined the camera, the ambient light, a, b, proc p\nnothing was put\n");
}

#[test]
fn a_new_camera_or_ambient_replaces_the_old_one_and_lights_add_up() {
    let run = run("\
camera distance 10 angle 0.8 end
camera distance 20 angle 0.5 end
ambient 0.1
ambient 0.3
light vector 0, 0, 0 intensity 0.5 end
light vector 0, 0, 0 intensity 0.5 end
:scene
");
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.out.contains("camera:   distance 20, angle 0.5\n"), "{}", run.out);
    assert!(run.out.contains("ambient:  0.3\n"), "{}", run.out);
    assert!(run.out.contains("lights:   2\n"), "{}", run.out);
}

#[test]
fn inputs_continue_over_lines_while_a_construct_is_open() {
    let run = run("\
put sphere
  center 0, 0, 0
  radius 1
  $T
end
let x = 1 +
  2
");
    assert_eq!(run.code, 0, "{}", run.err);
    assert_eq!(run.out, "put 1 sphere (1 object in the scene)\nx = 3\n");
}

/// Runs `script` as [`run_with`] does, read one byte at a time: no input is
/// read ahead of the one running, so each is parsed on its own.
fn run_unbuffered(script: &str, options: &SessionOptions) -> Run {
    let script = script.replace("$T", TEX);
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let code = run_script(std::io::BufReader::with_capacity(1, script.as_bytes()), &mut out, &mut err, options);
    Run {
        code,
        out: String::from_utf8(out).expect("output is text"),
        err: String::from_utf8(err).expect("errors are text"),
    }
}

#[test]
fn inputs_read_ahead_run_as_inputs_read_one_at_a_time() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let file = dir.path().join("session.ray");
    let scripts = [
        // Each line is finished, but together two of them make one item.
        "let x = 1\n+ 2\nlet y = 3\n".to_string(),
        "let a = 1\nlet b = oops\nlet c = 3\n".to_string(),
        "let a = 1\nlet = 2\nlet c = 3\n".to_string(),
        "let a = 1 $\nlet b = 2\n".to_string(),
        "let a = 1\nend\nlet c = (1\n".to_string(),
        format!(
            "{SCENE}proc p(n)\n  put sphere center 0, 0, 0 radius n $T end\nend\np(1) p(2)\n\
             let x = (1 +\n2) # two lines\n# a comment\n:show p\n:list\nobject o = sphere center 0, 0, 0 radius x $T end\n\
             put o\n:write {}\nlet y = nowhere\nput sphere center 0, 0, 0 radius\n",
            file.display()
        ),
    ];
    for script in &scripts {
        for options in [SessionOptions::default(), SessionOptions { keep_going: true, ..SessionOptions::default() }] {
            let ahead = run_with(script, &options);
            let written = std::fs::read_to_string(&file).unwrap_or_default();
            let alone = run_unbuffered(script, &options);
            assert_eq!((ahead.code, &ahead.out, &ahead.err), (alone.code, &alone.out, &alone.err), "{script}");
            assert_eq!(written, std::fs::read_to_string(&file).unwrap_or_default(), "{script}");
        }
    }
}

#[test]
fn every_kind_of_failing_input_leaves_the_session_as_it_was() {
    let setup = format!(
        "{SCENE}let r = 1\nobject ball = sphere center 0, 0, 0 radius 1 $T end\n\
         proc two(x)\n  put sphere center 0, 0, 0 radius 1 $T end\n  put sphere center 0, 0, 0 radius x $T end\nend\n"
    );
    let failing = [
        "put sphere center 0, 0, 0 radius 1 $T", // syntax: no end (at end of script)
        "let r = )",                             // syntax error
        "let r = nowhere",                       // unknown name
        "let r = 1 / 0",                         // non-finite number
        "camera distance 1 / 0 angle 1 end",     // camera
        "ambient 1 / 0",                         // ambient
        "light vector 0, 0, 0 intensity sqrt(0 - 1) end", // light
        "proc broken(x) let = 1 end",            // proc with a syntax error
        "object ball = sphere center 0, 0, 0 radius 0 $T end", // object
        "put sphere center 0, 0, 0 radius 0 - 1 $T end", // put
        "two(0)",                                // call failing after one put
        "two(1, 2)",                             // arity
        "nothing(1)",                            // unknown procedure
        "if r = 1 then put ball let r = 2 put scale ball by 0 end end", // if failing halfway
        "let r = 5 put ball put sphere center 0, 0, 0 radius r - 5 $T end", // several items, the last fails
    ];
    for bad in failing {
        let script = format!("{setup}:scene\n:env\n:depth\n{bad}\n:scene\n:env\n:depth\n",);
        let run = run_keep_going(&script);
        assert_eq!(run.code, 1, "`{bad}` should fail:\n{}", run.out);
        assert!(!run.err.is_empty(), "`{bad}` printed no error");
        let lines: Vec<&str> = run.out.lines().collect();
        let first = lines.iter().position(|l| l.starts_with("camera:   ")).expect(":scene output");
        let depth = lines.iter().position(|l| l.starts_with("depth = ")).expect(":depth output");
        let before = &lines[first..=depth];
        let after_start = lines[depth + 1..].iter().position(|l| l.starts_with("camera:   ")).map(|i| i + depth + 1);
        let Some(after_start) = after_start else {
            // Unfinished input swallows the rest of the script: checked below.
            assert_eq!(bad, failing[0]);
            continue;
        };
        let after = &lines[after_start..after_start + before.len()];
        assert_eq!(before, after, "`{bad}` changed the session");
    }
}

#[test]
fn errors_point_at_the_script_line() {
    let run = run("let a = 1\n\n# comment\nput sphere center 0, 0, 0\n  radius nowhere $T end\n");
    assert_eq!(run.code, 1);
    assert!(run.err.contains("<stdin>:5:"), "{}", run.err);
    assert!(run.err.contains("nowhere"), "{}", run.err);
}

/// Whether `rendered` shows the source line `text` numbered `line`.
fn shows_line(rendered: &str, line: usize, text: &str) -> bool {
    rendered.lines().any(|shown| shown.trim_start().starts_with(&format!("{line} ")) && shown.ends_with(text))
}

#[test]
fn a_missing_end_is_shown_at_the_script_lines() {
    let script = "\
let a = 1

# the sphere below has no `end`
put sphere center 0, 0, 0 radius 1 $T
put sphere center 0, 0, 0 radius 2 $T end
";
    let run = run(script);
    assert_eq!(run.code, 1);
    assert!(run.err.starts_with("error: expected `end` to close this `sphere`\n"), "{}", run.err);
    assert!(run.err.contains("<stdin>:5:1"), "{}", run.err);
    assert!(shows_line(&run.err, 4, &format!("radius 1 {TEX}")), "{}", run.err);
    assert!(run.err.contains("this `sphere` is not closed"), "{}", run.err);
}

#[test]
fn a_missing_end_of_an_if_inside_a_proc_is_shown_at_the_script_lines() {
    let script = "\
let a = 1
# a procedure whose `if` lacks its `end`
proc p(n)
  if n < 1 then
    put sphere center 0, 0, 0 radius 1 $T end
end
proc q()
  p(0)
end
";
    let run = run(script);
    assert_eq!(run.code, 1);
    assert!(run.err.starts_with("error: expected `end` to close this `if`\n"), "{}", run.err);
    assert!(run.err.contains("<stdin>:7:1"), "{}", run.err);
    assert!(shows_line(&run.err, 4, "if n < 1 then"), "{}", run.err);
    assert!(shows_line(&run.err, 6, "end"), "{}", run.err);
    assert!(run.err.contains("this `end`, lined up with `proc p`, closed the `if`"), "{}", run.err);
    assert!(!run.err.contains("line "), "{}", run.err);
}

#[test]
fn the_first_error_stops_the_script() {
    let run = run("let a = 1\nlet b = oops\nlet c = 3\n");
    assert_eq!(run.code, 1);
    assert_eq!(run.out, "a = 1\n");
    assert!(run.err.contains("<stdin>:2:"), "{}", run.err);
}

#[test]
fn keep_going_runs_everything_and_still_fails() {
    let run = run_keep_going("let a = 1\nlet b = oops\nlet c = 3\n:nonsense\nlet d = 4\n");
    assert_eq!(run.code, 1);
    assert_eq!(run.out, "a = 1\nc = 3\nd = 4\n");
}

#[test]
fn an_unfinished_input_at_the_end_is_an_error() {
    let run = run("put sphere center 0, 0, 0 radius 1\n");
    assert_eq!(run.code, 1);
    assert!(run.err.contains("<stdin>:1"), "{}", run.err);
}

#[test]
fn warnings_are_shown_and_do_not_fail() {
    let run = run("put sphere center 0, 0, 0 radius 1 kd 2 ks 0 phong 1 color 300, 0, 0 end\n");
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.err.contains("warning"), "{}", run.err);
    assert!(run.out.contains("put 1 sphere"), "{}", run.out);
}

#[test]
fn a_command_typed_without_colon_gets_a_hint() {
    let run = run("render\n");
    assert_eq!(run.code, 1);
    assert!(run.out.contains("did you mean `:render`?"), "{}", run.out);
}

// ------------------------------------------------------------ commands

#[test]
fn help_lists_topics_and_explains_each() {
    let run = run(":help\n:help sphere\n:help :save\n:help kd\n");
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.out.contains("camera distance 10 angle 0.8 end"), "{}", run.out);
    assert!(run.out.contains("sphere center X, Y, Z radius R TEXTURE end"), "{}", run.out);
    assert!(run.out.contains(":save FILE W H"), "{}", run.out);
    assert!(run.out.contains("phong  how small the highlight is"), "{}", run.out);
}

#[test]
fn help_on_an_unknown_word_suggests_a_close_one() {
    let run = run(":help spehre\n");
    assert_eq!(run.code, 1);
    assert!(run.err.contains("no help about `spehre`; did you mean `sphere`?"), "{}", run.err);
}

#[test]
fn unknown_commands_get_a_did_you_mean() {
    let run = run(":rendr\n");
    assert_eq!(run.code, 1);
    assert!(run.err.contains("there is no command `:rendr`; did you mean `:render`?"), "{}", run.err);
    let run = run_keep_going(":\n:xyzzy\n");
    assert!(run.err.contains("type a command name after `:`"), "{}", run.err);
    assert!(run.err.contains("there is no command `:xyzzy`\n`:help` lists the commands"), "{}", run.err);
}

#[test]
fn bad_arguments_get_usage_messages() {
    let cases = [
        (":size 10", "usage: :size [WIDTH HEIGHT]"),
        (":size 0 10", "the width must be a whole number from 1 to 65535 (the largest side a GIF can have), not `0`"),
        (":size 65535 65535", "an image of 65535×65535 has 4294836225 pixels; the most is 67108864 (8192×8192)"),
        (":size a 10", "not `a`"),
        (":depth -1", "the depth must be a whole number from 0 to 1000"),
        (":depth 4294967295", "not `4294967295`"),
        (":depth 1 2", "usage: :depth [REFLECTIONS]"),
        (":samples 0", "the number of samples must be a whole number from 1 to 4096"),
        (":time x", "the time must be a finite number, not `x`"),
        (":time 1 2", "usage: :time [NUMBER]"),
        (":render 10", "give both a width and a height, or neither"),
        (":save", "give the name of the file to write"),
        (":save x.jpg", "cannot tell the image format of `x.jpg`: end the name in .png or .ppm"),
        (":anim 2 x.jpg", "end the name in .gif, .apng, .mp4, .webm, .png or .ppm"),
        (":save x.png 10", "usage: :save FILE [WIDTH HEIGHT]"),
        (":anim 0 x.gif", "the number of frames must be a whole number from 1 to 1000000"),
        (":anim 3", "usage: :anim FRAMES FILE"),
        (":load", "give the file to load"),
        (":load \"unclosed", "a `\"` is not closed"),
        (":env now", "this command takes no arguments"),
        (":help a b", "ask about one name at a time"),
    ];
    for (line, message) in cases {
        let run = run(&format!("{line}\n"));
        assert_eq!(run.code, 1, "`{line}` should fail");
        assert!(run.err.contains(message), "`{line}`: expected `{message}` in\n{}", run.err);
    }
}

#[test]
fn settings_are_shown_and_changed() {
    let run = run(":size\n:size 320 200\n:depth\n:depth 2\n:samples 4\n:time\n:scene\n");
    assert_eq!(run.code, 0, "{}", run.err);
    for expected in [
        "size = 800×600",
        "size = 320×200",
        "depth = 5",
        "depth = 2",
        "samples = 4",
        "time = 0",
        "settings: time 0, size 320×200, depth 2, samples 4",
    ] {
        assert!(run.out.contains(expected), "`{expected}` missing from\n{}", run.out);
    }
}

#[test]
fn env_lists_numbers_objects_and_procedures() {
    let run = run(
        "let r = 2\nobject g = group sphere center 0,0,0 radius 1 $T end box center 0,0,0 length 1,1,1 $T end end\nproc p(a, b) end\n:env\n",
    );
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.out.contains("numbers:    r = 2, time = 0\n"), "{}", run.out);
    assert!(run.out.contains("objects:    g (group of 2 objects)\n"), "{}", run.out);
    assert!(run.out.contains("procedures: p(a, b)\n"), "{}", run.out);
}

#[test]
fn scene_counts_what_was_put() {
    let run = run(&format!("{SCENE}put box center 0, 0, 0 length 1, 1, 1 $T end\n:scene\n"));
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.out.contains("objects:  3 (1 sphere, 1 plane, 1 box)"), "{}", run.out);
    let run = run_keep_going(":scene\n");
    assert!(run.out.contains("(default: none given yet)"), "{}", run.out);
}

#[test]
fn undo_takes_back_inputs_loads_and_resets() {
    let run = run("\
:undo
put sphere center 0, 0, 0 radius 1 $T end
put sphere center 0, 0, 0 radius 2 $T end
:undo
:reset
:env
:undo
:env
");
    assert_eq!(run.code, 0, "{}", run.err);
    let expected = "\
nothing to undo
0 objects in the scene
put 1 sphere (1 object in the scene)
put 1 sphere (2 objects in the scene)
took back: put sphere center 0, 0, 0 radius 2 kd 0.7 ks 0.3 phong 20 color 255, 80, 40 end
1 object in the scene
the session is empty again (`:undo` brings it all back)
";
    assert!(run.out.starts_with(expected), "{}", run.out);
    assert!(run.out.contains("took back the :reset (1 input back)\n1 object in the scene\n"), "{}", run.out);
}

#[test]
fn undo_restores_definitions_too() {
    let run = run("let a = 1\nlet a = 2\n:undo\n:env\n");
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.out.contains("numbers:    a = 1, time = 0"), "{}", run.out);
}

#[test]
fn load_runs_a_file_as_one_input() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let file = dir.path().join("scene.ray");
    std::fs::write(&file, SCENE.replace("$T", TEX)).expect("write the scene");
    let bad = dir.path().join("bad.ray");
    std::fs::write(&bad, "let a = 1\nlet b = nowhere\n").expect("write the bad scene");
    let script = format!(
        ":load {}\n:load {}\n:env\n:undo\n:scene\n:load {}\n",
        file.display(),
        bad.display(),
        dir.path().join("missing.ray").display()
    );
    let run = run_keep_going(&script);
    assert_eq!(run.code, 1);
    assert!(run.out.contains(&format!("loaded {}\n", file.display())), "{}", run.out);
    assert!(run.out.contains("put 1 sphere and 1 plane (2 objects in the scene)"), "{}", run.out);
    assert!(run.err.contains("bad.ray:2:"), "{}", run.err);
    assert!(run.out.contains("numbers:    time = 0\n"), "the failed load left `a`: {}", run.out);
    assert!(run.out.contains("took back: :load"), "{}", run.out);
    assert!(run.out.contains("objects:  0 "), "{}", run.out);
    assert!(run.err.contains("missing.ray: no such file"), "{}", run.err);
}

#[test]
fn an_initial_file_is_loaded_first() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let file = dir.path().join("start.ray");
    std::fs::write(&file, "let r = 4\n").expect("write the scene");
    let options = SessionOptions { initial_file: Some(file.clone()), ..SessionOptions::default() };
    let run = run_with("let s = r * 2\n", &options);
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.out.ends_with("r = 4\ns = 8\n"), "{}", run.out);
    let options = SessionOptions { initial_file: Some(dir.path().join("none.ray")), ..SessionOptions::default() };
    let run = run_with("let s = 1\n", &options);
    assert_eq!(run.code, 1);
    assert_eq!(run.out, "");
}

#[test]
fn quit_stops_the_script() {
    let run = run("let a = 1\n:quit\nlet b = oops\n");
    assert_eq!(run.code, 0, "{}", run.err);
    assert_eq!(run.out, "a = 1\n");
}

#[test]
fn a_word_typed_at_other_prompts_is_an_error_that_does_not_stop_the_script() {
    let run = run("exit\nlet a = 1\n  quit \nhelp\nlet clear = 2\nclear\ncls\nlet b = clear\n");
    assert_eq!(run.code, 1, "{}", run.err);
    assert_eq!(run.out, "a = 1\nclear = 2\nb = 2\n");
    for (line, word, command) in
        [(1, "exit", ":quit"), (3, "quit", ":quit"), (4, "help", ":help"), (6, "clear", ":clear"), (7, "cls", ":clear")]
    {
        let error =
            format!("error: line {line} of the script: `{word}` alone does nothing here; did you mean `{command}`?\n");
        assert!(run.err.contains(&error), "{error}{}", run.err);
    }
}

// ------------------------------------------------------------ time

#[test]
fn time_changes_reevaluate_what_reads_it() {
    let run = run("let t = time * 2\n:time 3\n:env\n:time 0.5\n:env\n");
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.out.contains("time = 3 (the scene was computed again)"), "{}", run.out);
    assert!(run.out.contains("numbers:    t = 6, time = 3"), "{}", run.out);
    assert!(run.out.contains("numbers:    t = 1, time = 0.5"), "{}", run.out);
}

#[test]
fn a_time_change_without_readers_applies_to_later_inputs() {
    let run = run("\
let a = 1
proc p()
  if time = 4 then put sphere center 0, 0, 0 radius 1 $T end end
end
:time 4
:env
let b = time
p()
");
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.out.contains("time = 4\n"), "no replay expected: {}", run.out);
    assert!(run.out.contains("numbers:    a = 1, time = 4\n"), "{}", run.out);
    assert!(run.out.contains("b = 4\n"), "{}", run.out);
    assert!(run.out.contains("put 1 sphere"), "the procedure saw the old time: {}", run.out);
}

#[test]
fn a_time_at_which_an_input_fails_is_refused() {
    let run = run_keep_going("let x = 1 / (time - 2)\n:time 2\n:time\n:env\n");
    assert_eq!(run.code, 1);
    assert!(run.err.contains("at time 2 an earlier input fails, so time stays 0"), "{}", run.err);
    assert!(run.out.contains("time = 0\n"), "{}", run.out);
    assert!(run.out.contains("x = -0.5"), "{}", run.out);
}

// ------------------------------------------------------------ images

/// Renders `file_text` the way the renderer does for a file.
fn render_file(file_text: &str, width: u32, height: u32, depth: u32, samples: u32) -> image::RgbImage {
    let mut sources = SourceMap::new();
    let id = sources.add("scene.ray", file_text, 0);
    let program = parse_file(id, file_text).expect("the file parses");
    let mut interpreter = Interpreter::new(0.0, Limits::default());
    interpreter.run(&program).expect("the file runs");
    let scene = interpreter.into_scene();
    let options = RenderOptions { width, height, depth, samples, ..RenderOptions::default() };
    render(&scene, &SceneGeometry::new(&scene), &options, &RenderControl::default()).expect("not cancelled").0
}

fn read_rgb(path: &Path) -> image::RgbImage {
    image::open(path).expect("the image can be read").to_rgb8()
}

#[test]
fn save_writes_the_same_image_as_rendering_the_file() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let png = dir.path().join("a.png");
    let ppm = dir.path().join("b.ppm");
    let big = dir.path().join("c.png");
    let script = format!(
        "{SCENE}:size 40 30\n:depth 2\n:samples 4\n:save {}\n:save {}\n:save {} 64 48\n",
        png.display(),
        ppm.display(),
        big.display()
    );
    let run = run(&script);
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.out.contains(&format!("saved {} (40×30, ", png.display())), "{}", run.out);
    let file = SCENE.replace("$T", TEX);
    let expected = render_file(&file, 40, 30, 2, 4);
    assert_eq!(read_rgb(&png), expected);
    assert_eq!(read_rgb(&ppm), expected);
    assert_eq!(read_rgb(&big), render_file(&file, 64, 48, 2, 4));
}

#[test]
fn save_refuses_a_gif_as_the_command_line_does() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let gif = dir.path().join("a.gif");
    let run = run_with(&format!("{SCENE}:save {}\n", gif.display()), &small_size());
    assert_eq!(run.code, 1);
    assert!(run.err.contains("GIF is for animations"), "{}", run.err);
    assert!(!gif.exists());
}

#[test]
fn save_explains_the_defaults_it_used() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let png = dir.path().join("a.png");
    let run = run_with(&format!(":save {}\n", png.display()), &small_size());
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(
        run.out.contains("note: default camera (distance 10, angle 1) and ambient light (0.2); set yours with `camera distance 12 angle 0.8 end`"),
        "{}",
        run.out
    );
    assert!(run.out.contains("nothing has been put yet"), "{}", run.out);
    assert!(png.exists());
}

#[test]
fn save_reports_a_file_it_cannot_write() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let target = dir.path().join("no/such/dir/a.png");
    let run = run_with(&format!(":save {}\n", target.display()), &small_size());
    assert_eq!(run.code, 1);
    assert!(run.err.contains("cannot write"), "{}", run.err);
}

#[test]
fn render_without_a_terminal_renders_and_says_so() {
    let run = run_with(&format!("{SCENE}:render\n:render 16 8\n"), &small_size());
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.out.contains("rendered 32×24 in "), "{}", run.out);
    assert!(run.out.contains("rendered 16×8 in "), "{}", run.out);
}

#[test]
fn anim_writes_a_gif_or_numbered_frames_following_time() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let gif = dir.path().join("rise.gif");
    let png = dir.path().join("rise.png");
    let script = format!(
        "{SCENE}put sphere center 0, time - 2, 2 radius 0.5 $T end\n:anim 3 {}\n:anim 3 {}\n:time\n",
        gif.display(),
        png.display()
    );
    let run = run_with(&script, &small_size());
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(gif.exists());
    assert!(run.out.contains("(3 frames of 32×24, "), "{}", run.out);
    assert!(run.out.ends_with("time = 0\n"), "the session's time changed: {}", run.out);
    let frames: Vec<_> = (1..=3).map(|k| read_rgb(&dir.path().join(format!("rise000{k}.png")))).collect();
    assert_ne!(frames[0], frames[1]);
    assert_ne!(frames[1], frames[2]);
    // Frame 2 is the scene at time 2.
    let at_two = run_with(
        &format!(
            "{SCENE}:time 2\nput sphere center 0, time - 2, 2 radius 0.5 $T end\n:save {}\n",
            dir.path().join("two.png").display()
        ),
        &small_size(),
    );
    assert_eq!(at_two.code, 0, "{}", at_two.err);
    assert_eq!(read_rgb(&dir.path().join("two.png")), frames[1]);
}

#[test]
fn anim_of_a_scene_without_time_repeats_one_picture() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let png = dir.path().join("still.ppm");
    let run = run_with(&format!("{SCENE}:anim 2 {}\n", png.display()), &small_size());
    assert_eq!(run.code, 0, "{}", run.err);
    let first = read_rgb(&dir.path().join("still0001.ppm"));
    assert_eq!(first, read_rgb(&dir.path().join("still0002.ppm")));
}

#[test]
fn anim_reports_the_frame_that_fails() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let gif = dir.path().join("bad.gif");
    let run = run_with(&format!("let x = 1 / (time - 2)\n:anim 3 {}\n", gif.display()), &small_size());
    assert_eq!(run.code, 1);
    assert!(run.err.contains("while computing frame 2, with time = 2"), "{}", run.err);
    assert!(!gif.exists());
}

// ------------------------------------------------------------ writing the session back

/// Runs `script` in `dir` (`$D` stands for it) with `:save saved.png` and
/// `:write scene.ray` at its end, then the command the written file's
/// header gives; returns the saved and the batch-rendered images' bytes.
fn save_and_write(dir: &Path, script: &str) -> (Vec<u8>, Vec<u8>) {
    let script = script.replace("$D", &dir.display().to_string());
    let ends = format!(":save {0}/saved.png\n:write {0}/scene.ray\n", dir.display());
    let run = run_with(&format!("{script}{ends}"), &small_size());
    assert_eq!(run.code, 0, "{}", run.err);
    let written = std::fs::read_to_string(dir.join("scene.ray")).expect("the file is written");
    let command = written.lines().nth(1).and_then(|line| line.split('`').nth(1)).expect("a command in the header");
    let args: Vec<&str> = command.split_whitespace().collect();
    assert_eq!(args[0], "rayrepl", "{command}");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_rayrepl")).args(&args[1..]).status();
    assert!(status.expect("the binary runs").success(), "{command} failed on:\n{written}");
    let bytes = |name: &str| std::fs::read(dir.join(name)).expect("an image");
    (bytes("saved.png"), bytes("scene.png"))
}

#[test]
fn a_written_session_renders_byte_for_byte_what_save_gives() {
    let moving = "put sphere center time - 2, 0, 0 radius 1 kd 0.8 ks 0.2 phong 10 color 0, 90, 255 end";
    let sessions = [
        // Items in any order, the camera and the ambient light given twice.
        format!("put sphere center 1, 0, 0 radius 1 $T end\ncamera distance 8 angle 1 end\n{SCENE}ambient 0.4\n"),
        // A procedure redefined before it is used, and a global it reads.
        format!(
            "{SCENE}proc row(n) put sphere center n, 1, 0 radius 0.3 $T end end\n\
             proc row(n)\n  if n > 0 then\n    put box center n, 1, 0 length 0.5, 0.5, 0.5 $T end # a box\n\
                 row(n - 1)\n  end\nend\nlet n = 3\nrow(n)\n"
        ),
        // `time`, size, depth and samples set in the session.
        format!("{SCENE}:time 2.5\n{moving}\n:size 40 30\n:depth 2\n:samples 4\n"),
        // Inputs taken back, and a `:reset` taken back.
        format!(
            "{SCENE}put sphere center 3, 3, 0 radius 1 $T end\n:undo\n:reset\n:undo\nlight vector 1, 0, 0 intensity 0.3 end\n"
        ),
        // No camera and no ambient light: the defaults.
        "put sphere center 0, 0, 0 radius 1 $T end\n".to_string(),
        // A loaded file, typed items on it, then the file again.
        ":load $D/part.ray\nball(2)\n:load $D/part.ray\nlet time = 3\nball(time)\n".to_string(),
    ];
    for session in sessions {
        let dir = tempfile::tempdir().expect("temporary directory");
        let part =
            format!("# a part\n{SCENE}proc ball(x)\n  put sphere center x, 1, 0 radius 0.5 $T end\nend\nball(-2)\n");
        std::fs::write(dir.path().join("part.ray"), part.replace("$T", TEX)).expect("the part is written");
        let (saved, written) = save_and_write(dir.path(), &session);
        assert!(saved == written, "the batch render differs from :save for:\n{session}");
    }
}

#[test]
fn a_written_file_keeps_the_comments_and_says_how_to_render_it() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let file = dir.path().join("lesson.ray");
    let script = format!("put sphere center 0, 0, 0 radius 1 $T end # the ball\n:time 4\n:write {}\n", file.display());
    let run = run_with(&script, &small_size());
    assert_eq!(run.code, 0, "{}", run.err);
    assert!(run.out.contains(&format!("wrote {} (the default camera, the default ambient light", file.display())));
    let written = std::fs::read_to_string(&file).expect("written");
    assert!(written.contains("--width 32 --height 24 --depth 5 --samples 1 --time 4`"), "{written}");
    assert!(written.contains("camera distance 10 angle 1 end # the session's default\nambient 0.2"), "{written}");
    assert!(written.contains(&format!("put sphere center 0, 0, 0 radius 1 {TEX} end # the ball\n")), "{written}");
}

#[test]
fn no_file_is_written_where_none_gives_the_scene() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let file = dir.path().join("x.ray");
    let cases = [
        (
            "proc p() put sphere center 0, 0, 0 radius 1 $T end end\np()\nproc p() end\n",
            "<stdin>:2 ran `p` as <stdin>:1 defined it, and <stdin>:3 redefined it afterwards",
        ),
        (
            "proc p() put sphere center 0, 0, 0 radius 1 $T end end\nproc q() p() end\nq()\nproc p() end\n",
            "<stdin>:3 ran `p` as <stdin>:1 defined it",
        ),
        ("let d = 8\ncamera distance d angle 1 end\n", "the camera at <stdin>:2 reads `d`"),
        ("let time = 2\nlight vector time, 0, 0 intensity 1 end\n", "reads `time`, as <stdin>:1 set it"),
    ];
    for (script, message) in cases {
        let run = run(&format!("{script}:write {}\n", file.display()));
        assert_eq!(run.code, 1, "{script}");
        assert!(run.err.contains(message), "{script}: {}", run.err);
        assert!(!file.exists());
    }
    let empty = run(&format!(":write {}\n", file.display()));
    assert!(empty.err.contains("the session is empty"), "{}", empty.err);
    let image = run("let a = 1\n:write x.png\n");
    assert!(image.err.contains("`x.png` is not a scene file: end its name in .ray"), "{}", image.err);
}

#[test]
fn reload_replaces_what_the_last_load_brought() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let file = dir.path().join("part.ray");
    std::fs::write(
        &file,
        format!("{SCENE}proc ball(x) put sphere center x, 1, 0 radius 0.5 $T end end\n").replace("$T", TEX),
    )
    .expect("written");
    let nothing = run(":reload\n");
    assert!(nothing.err.contains("nothing was loaded: `:load FILE` first"), "{}", nothing.err);
    let script = format!(":load {0}\nball(2)\n:reload\n:reload\n:undo\n:scene\n", file.display());
    let run = run(&script);
    assert_eq!(run.code, 0, "{}", run.err);
    let reloaded = format!("reloaded {} (3 objects and 1 light in the scene, as many as before)", file.display());
    assert_eq!(run.out.matches(&reloaded).count(), 2, "{}", run.out);
    assert!(run.out.contains(&format!("took back the :reload of {}", file.display())), "{}", run.out);
    assert!(run.out.contains("objects:  3 (2 spheres, 1 plane, 0 boxes)"), "{}", run.out);
}

#[test]
fn show_prints_a_definition_as_written_and_list_the_inputs() {
    let script = "\
let r = 2
proc row(n) # a row of balls
  put sphere center n, 0, 0 radius r $T end
end
if r > 1 then object big = sphere center 0, 0, 0 radius r $T end end
:show row
:show r
:show big
:show time
:show rw
:list
";
    let run = run_keep_going(script);
    let row =
        format!("# <stdin>:2\nproc row(n) # a row of balls\n  put sphere center n, 0, 0 radius r {TEX} end\nend\n");
    assert!(run.out.contains(&row), "{}", run.out);
    assert!(run.out.contains("# <stdin>:1 (r = 2 now)\nlet r = 2\n"), "{}", run.out);
    assert!(run.out.contains("# <stdin>:5 (big: 1 primitive)\nif r > 1 then object big"), "{}", run.out);
    assert!(run.out.contains("# predefined (time = 0 now)"), "{}", run.out);
    assert!(run.err.contains("`rw` is not defined; did you mean `r`?"), "{}", run.err);
    assert!(
        run.out.contains("<stdin>:1  let r = 2\n<stdin>:2  proc row(n) # a row of balls\n             put sphere"),
        "{}",
        run.out
    );
}

#[test]
fn save_checks_its_file_before_rendering_and_says_an_error_once() {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let run = run_with(&format!("{SCENE}:save /proc/rayrepl.png\n"), &small_size());
    assert_eq!(run.code, 1);
    assert_eq!(run.err, "error: cannot write `/proc/rayrepl.png`: no such file or folder\n");
}

#[test]
fn watch_needs_the_interactive_session() {
    let run = run(":watch scene.ray\n");
    assert!(run.err.contains("here, run `rayrepl FILE.ray --watch`"), "{}", run.err);
}

// ------------------------------------------------------------ the binary

/// Scripts piped into the `rayrepl` binary.
mod binary {
    use assert_cmd::Command;
    use predicates::prelude::PredicateBooleanExt;
    use predicates::str::contains;

    fn rayrepl() -> Command {
        Command::new(env!("CARGO_BIN_EXE_rayrepl"))
    }

    #[test]
    fn a_piped_script_runs_without_prompts_or_colours() {
        let script = "let r = 2\nput sphere center 0, 0, 0\n  radius r kd 1 ks 0 phong 1 color 255, 0, 0 end\n:scene\n";
        rayrepl()
            .write_stdin(script)
            .assert()
            .success()
            .stdout(contains("r = 2\nput 1 sphere (1 object in the scene)\n"))
            .stdout(contains("objects:  1 (1 sphere, 0 planes, 0 boxes)"))
            .stdout(contains("ray>").not())
            .stdout(contains("\x1b[").not());
    }

    #[test]
    fn the_first_error_stops_a_piped_script_with_status_1() {
        rayrepl()
            .write_stdin("let a = 1\nlet b = oops\nlet c = 3\n")
            .assert()
            .code(1)
            .stdout("a = 1\n")
            .stderr(contains("<stdin>:2:"));
    }

    #[test]
    fn keep_going_runs_the_whole_script_and_fails_at_the_end() {
        rayrepl().arg("--keep-going").write_stdin("let b = oops\nlet c = 3\n").assert().code(1).stdout("c = 3\n");
    }

    #[test]
    fn a_file_given_with_i_is_loaded_before_the_script() {
        let dir = tempfile::tempdir().expect("temporary directory");
        let file = dir.path().join("start.ray");
        std::fs::write(&file, "let r = 4\n").expect("write the scene");
        rayrepl().arg("-i").arg(&file).write_stdin("let s = r * 2\n").assert().success().stdout(contains("s = 8\n"));
    }
}

#[test]
fn answers_and_errors_to_one_stream_come_in_the_order_of_the_inputs() {
    use std::process::{Command, Stdio};
    let dir = tempfile::tempdir().expect("temporary directory");
    let (script, both) = (dir.path().join("script.ray"), dir.path().join("both.txt"));
    std::fs::write(&script, "let a = 1\nlet b = nowhere\nprint a\nlet c = 3\n").expect("write the script");
    let output = std::fs::File::create(&both).expect("create the output");
    let status = Command::new(env!("CARGO_BIN_EXE_rayrepl"))
        .arg("--keep-going")
        .stdin(std::fs::File::open(&script).expect("open the script"))
        .stdout(Stdio::from(output.try_clone().expect("the output again")))
        .stderr(Stdio::from(output))
        .status()
        .expect("the binary runs");
    assert_eq!(status.code(), Some(1));
    let both = std::fs::read_to_string(&both).expect("read the output");
    let at = |text: &str| both.find(text).unwrap_or_else(|| panic!("{text} in {both}"));
    assert!(at("a = 1") < at("nowhere") && at("nowhere") < at(":3: a = 1") && at(":3: a = 1") < at("c = 3"), "{both}");
}

#[test]
fn ctrl_c_stops_a_piped_script_with_status_130_and_says_where() {
    use std::io::{BufRead, BufReader};
    use std::process::Command;
    let mut child = piped_script(":limits calls 100000000\nproc f(n) f(n + 1) end\nf(1)\nlet never = 1\n");
    let mut stdout = BufReader::new(child.stdout.take().expect("stdout"));
    let mut line = String::new();
    while !line.contains("defined proc f(n)") {
        line.clear();
        assert!(stdout.read_line(&mut line).expect("stdout is readable") > 0, "the proc is defined");
    }
    std::thread::sleep(std::time::Duration::from_millis(300));
    let pid = child.id().to_string();
    Command::new("kill").args(["-INT", &pid]).status().expect("kill runs");
    let output = child.wait_with_output().expect("the script ends");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("stopped by Ctrl-C"), "{stderr}");
    assert!(stderr.contains("interrupted by Ctrl-C: the script stopped at line 3"), "{stderr}");
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stdout, &mut rest).expect("stdout is readable");
    assert!(!rest.contains("never"), "nothing after the interrupted line runs: {rest}");
}

/// The binary running `script` from a pipe left open, as a slow one would
/// be, with its stdout and stderr piped.
fn piped_script(script: &str) -> std::process::Child {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_rayrepl"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    let stdin = child.stdin.as_mut().expect("stdin");
    stdin.write_all(script.as_bytes()).expect("the script is sent");
    child
}

/// Pipes `script` into the binary, sends SIGINT once `ready` returns, and
/// gives the exit status, what was said on stdout and on stderr.
fn interrupted_script(script: &str, ready: impl FnOnce()) -> (Option<i32>, String, String) {
    let child = piped_script(script);
    ready();
    interrupt(child.id());
    let output = child.wait_with_output().expect("the script ends");
    let text = |bytes: &[u8]| String::from_utf8_lossy(bytes).into_owned();
    (output.status.code(), text(&output.stdout), text(&output.stderr))
}

#[test]
fn ctrl_c_while_a_script_saves_leaves_the_file_as_it_was() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let big = dir.path().join("big.ppm");
    std::fs::write(&big, b"the old image").expect("old image");
    // Nothing to trace: the time goes into writing 8192x8192 pixels.
    let script = format!("camera distance 10 angle 1 end\nambient 0.2\n:save {} 8192 8192\n", big.display());
    let (status, stdout, stderr) = interrupted_script(&script, || wait_for_a_write(dir.path()));
    assert_eq!(status, Some(130), "{stderr}");
    let said = format!("writing `{}` was cancelled: the file is as it was before", big.display());
    assert!(stdout.contains(&said), "{stdout}");
    assert!(stderr.contains("interrupted by Ctrl-C: the script stopped at line 3"), "{stderr}");
    assert_eq!(names_in(dir.path()), ["big.ppm"], "no temporary file");
    assert_eq!(std::fs::read(&big).expect("still there"), b"the old image");
}

#[test]
fn ctrl_c_while_a_script_animates_keeps_whole_frames_and_says_which() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let script = format!(
        ":size 320 240\ncamera distance 10 angle 1 end\nlight vector 0.5, 0, 0 intensity 0.8 end\n\
         put sphere center time - 2, 0, 0 radius 1 kd 0.8 ks 0 phong 10 color 255, 0, 0 end\n\
         :anim 1000000 {}\n",
        dir.path().join("f.ppm").display()
    );
    let (status, stdout, stderr) = interrupted_script(&script, || wait_for_files(dir.path(), ".ppm", 3));
    assert_eq!(status, Some(130), "{stderr}");
    let frames = names_in(dir.path());
    let (first, last) = (dir.path().join(&frames[0]), dir.path().join(&frames[frames.len() - 1]));
    let said = format!("{} ... {} written before it stopped", first.display(), last.display());
    assert!(stdout.contains(&said), "{said}\n{stdout}");
    assert!(stderr.contains("interrupted by Ctrl-C: the script stopped at line 5"), "{stderr}");
    for (k, frame) in frames.iter().enumerate() {
        assert_eq!(*frame, format!("f{:07}.ppm", k + 1), "no temporary file");
        let image = image::open(dir.path().join(frame)).expect("a whole frame").to_rgb8();
        assert_eq!(image.dimensions(), (320, 240));
    }
}
