//! The guided lessons (`:lesson`) driven as a learner would, through a
//! pseudo-terminal: every lesson to its end with right answers, wrong
//! answers that get the hint, answers written otherwise than the examples,
//! and progress kept between sessions. Also `:play`, which plays frames on
//! the terminal until a key.

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use expectrl::process::unix::WaitStatus;
use expectrl::{Eof, Expect, Session};

type Terminal = expectrl::session::OsSession;

/// A session on a terminal keeping its lesson progress in `progress`, with
/// pictures only if `pictures`.
fn spawn(progress: &Path, pictures: bool) -> Terminal {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rayrepl"));
    let home = progress.parent().expect("the progress file is in a folder");
    command.env("RAYREPL_LESSONS", progress).env("XDG_DATA_HOME", home).env("TERM", "xterm-256color");
    command.env("NO_COLOR", "1");
    if pictures {
        // Inside tmux the pictures are half-blocks: no kitty or iTerm images to ask about.
        command.env("TMUX", "/tmp/tmux-test,1,0");
    } else {
        command.arg("--no-preview");
    }
    let mut session = Session::spawn(command).expect("the binary starts");
    session.set_expect_timeout(Some(Duration::from_secs(30)));
    session
}

/// Types `input` line by line (nothing if it is empty), then waits for
/// `expected`.
fn answer(session: &mut Terminal, input: &str, expected: &str) {
    for line in input.lines() {
        session.send_line(line).expect("a line is typed");
    }
    if let Err(error) = session.expect(expected) {
        let mut seen = vec![0; 1 << 16];
        let read = session.try_read(&mut seen).unwrap_or(0);
        panic!(
            "after `{input}`, no `{expected}` ({error}); the terminal shows:\n{}",
            String::from_utf8_lossy(&seen[..read])
        );
    }
}

/// What the session shows after `input`: the text up to what `:scene`
/// typed after it shows.
fn output_before_scene(session: &mut Terminal, input: &str) -> String {
    session.send_line(input).expect("a line is typed");
    session.send_line(":scene").expect(":scene is typed");
    let shown = session.expect("objects:  ").expect("what :scene shows");
    String::from_utf8_lossy(shown.before()).into_owned()
}

/// Leaves with `:quit` (twice: typed inputs are not written to a file) and
/// gives the exit status.
fn quit(mut session: Terminal) -> i32 {
    session.expect("ray> ").expect("a prompt");
    session.send_line(":quit").expect(":quit is typed");
    session.expect("ray> ").expect("the note about unwritten inputs, then a prompt");
    session.send_line(":quit").expect(":quit is typed");
    session.expect(Eof).expect("the session ends");
    match session.get_process().wait().expect("the exit status") {
        WaitStatus::Exited(_, code) => code,
        other => panic!("the session did not exit normally: {other:?}"),
    }
}

/// For each lesson, an answer to each step (one or more inputs).
const RIGHT_ANSWERS: &[&[&str]] = &[
    &[
        "camera distance 10 angle 0.8 end",
        "put sphere center 0, 0, 0 radius 2 kd 0.8 ks 0.2 phong 20 color 255, 120, 40 end",
        "light vector 0.5, 0, -0.5 intensity 0.8 end",
    ],
    &["light vector 0, 0, -0.9 intensity 0.8 end", "ambient 0.05", "light vector 0, 0, 0.9 intensity 0.4 end"],
    &[
        "put sphere center -2, 0, 0 radius 1 kd 0.9 ks 0 phong 1 color 220, 30, 30 end",
        "put sphere center 0, 0, 0 radius 1 kd 0.6 ks 0.4 phong 60 color 40, 90, 220 end",
        "put sphere center 2, 0, 0 radius 1 kd 0.1 ks 0.9 phong 200 color 255, 255, 255 end",
    ],
    &[
        "put plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0 phong 1 color 200, 200, 200 end",
        "put plane rotation pi/2, 0, 0 shift -5 kd 0.8 ks 0 phong 1 color 120, 160, 220 end",
        "put box center 0, -0.7, 0 length 3, 0.6, 2 kd 0.7 ks 0.2 phong 10 color 250, 200, 40 end",
    ],
    &[
        "put rotate box center 0, 0, 0 length 3, 1, 1 kd 0.7 ks 0.2 phong 10 color 40, 160, 90 end\n  by 0, 0, pi/4 end",
        "put translate scale sphere center 0, 0, 0 radius 1 kd 0.7 ks 0.3 phong 30 color 220, 60, 60 end\n  by 1.5 end by -3, 0.5, 0 end",
        "put translate group\n    sphere center 0, 0, 0 radius 0.8 kd 0.9 ks 0.1 phong 10 color 250, 250, 250 end\n    \
         sphere center 0, 1.2, 0 radius 0.5 kd 0.9 ks 0.1 phong 10 color 250, 250, 250 end\n  end by 3, -0.2, 0 end",
    ],
    &[
        "let r = 0.7",
        "object ball = sphere center 0, 0, 0 radius r kd 0.7 ks 0.3 phong 30 color 250, 200, 40 end",
        "put translate ball by -2, 0, 0 end put ball put translate ball by 2, 0, 0 end",
    ],
    &[
        "proc post(x)\n  put box center x, 0, 0 length 0.4, 2, 0.4 kd 0.7 ks 0.2 phong 10 color 150, 90, 40 end\nend",
        "post(-2) post(0) post(2)",
    ],
    &[
        "proc row(n)\n  if 0 < n then\n    put sphere center n - 4, -0.6, 1 radius 0.4 kd 0.7 ks 0.3 phong 30 color 40, 90, 220 end\n    \
         row(n - 1)\n  end\nend",
        "row(5)",
        "proc tower(n, r, y)\n  if 0 < n then\n    put sphere center 3, y + r, 0 radius r kd 0.7 ks 0.3 phong 30 color 220, 60, 60 end\n    \
         tower(n - 1, r * 0.7, y + 2 * r)\n  end\nend",
        "tower(5, 0.8, -1)",
    ],
    &[
        "put sphere center 3 * sin(time / 2), 0, 0 radius 0.7 kd 0.7 ks 0.3 phong 30 color 250, 200, 40 end",
        "proc spin(n)\n  if 0 < n then\n    put sphere center 2.5 * cos(n * pi / 4 + time / 4), n * 0.3 - 0.7, \
         2.5 * sin(n * pi / 4 + time / 4) radius 0.3\n      kd 0.7 ks 0.3 phong 30 color 40, 160, 90 end\n    spin(n - 1)\n  end\nend",
        "spin(8)",
    ],
];

#[test]
fn every_lesson_runs_to_its_end_and_is_remembered() {
    let home = tempfile::tempdir().expect("temporary directory");
    let progress = home.path().join("lessons");
    let mut session = spawn(&progress, false);
    for (index, steps) in RIGHT_ANSWERS.iter().enumerate() {
        let lesson = index + 1;
        answer(&mut session, &format!(":lesson {lesson}"), &format!("lesson {lesson} of 9: "));
        for (step, input) in steps.iter().enumerate() {
            session.expect(format!("step {} of {}: ", step + 1, steps.len())).expect("the step's task");
            answer(&mut session, input, &format!("✓ step {} done", step + 1));
        }
        session.expect(format!("✓ lesson {lesson} done")).expect("the end of the lesson");
    }
    session.expect("that was the last lesson").expect("the end of the last lesson");
    assert_eq!(quit(session), 0);
    let kept = std::fs::read_to_string(&progress).expect("a progress file");
    assert!((1..=9).all(|lesson| kept.contains(&format!("done {lesson}\n"))), "{kept}");
    // Another session lists them all as done.
    let mut session = spawn(&progress, false);
    answer(&mut session, ":lesson", "✓ 1. a camera and a first sphere");
    session.expect("✓ 9. time and animations").expect("the last lesson is done");
    session.send_line(":quit").expect(":quit is typed");
    session.expect(Eof).expect("the session ends");
}

#[test]
fn a_wrong_answer_gets_the_hint_then_the_example() {
    let home = tempfile::tempdir().expect("temporary directory");
    let mut session = spawn(&home.path().join("lessons"), false);
    answer(&mut session, ":lesson 3", "step 1 of 3");
    answer(&mut session, RIGHT_ANSWERS[2][0], "✓ step 1 done");
    // Shiny, but a broad highlight: not what step 2 asks.
    let broad = "put sphere center 0, 0, 0 radius 1 kd 0.6 ks 0.4 phong 5 color 40, 90, 220 end";
    answer(&mut session, broad, "has phong 5 (the goal: at least 30)");
    session.expect("hint: ks is how shiny the surface is").expect("the hint");
    session.expect("ray> ").expect("a prompt");
    // Something else entirely, then the example comes too.
    answer(&mut session, "let x = 1", "not yet: ");
    session.expect("for example:").expect("the example after two wrong tries");
    session.expect("phong 60").expect("the example's text");
    answer(&mut session, RIGHT_ANSWERS[2][1], "✓ step 2 done");
    // An input that fails is reported as ever and checks nothing.
    let zero = "put sphere center 2, 0, 0 radius 0 kd 0.1 ks 0.9 phong 200 color 255, 255, 255 end";
    let shown = output_before_scene(&mut session, zero);
    assert!(shown.contains("error") && !shown.contains("not yet"), "{shown}");
    assert_eq!(quit(session), 0);
}

/// Inputs, each with what the session answers, written otherwise than
/// the examples of the lessons.
const OTHER_ANSWERS: &[(&str, &str)] = &[
    (":lesson 5", "step 1 of 3"),
    // A cube turned about y then about z: not a long box turned an eighth of a turn.
    (
        "put rotate rotate box center 1, 0, 0 length 1, 1, 1 kd 1 ks 0 phong 1 color 9, 9, 9 end by 0, 0.3, 0 end \
         by 0, 0, 1 end",
        "not yet: your box, put in input [2],",
    ),
    // The long side along y, turned the other way: the same box.
    (
        "put rotate box center 1, 0, 0 length 1, 3, 1 kd 1 ks 0 phong 1 color 9, 9, 9 end by 0, 0, -pi/4 end",
        "✓ step 1 done",
    ),
    // The ball written where it belongs at once, through a name.
    ("let big = 1.5", "not yet: "),
    ("put sphere center -2 - 1, 1 / 2, 0 radius big kd 0.5 ks 0.5 phong 9 color 1, 2, 3 end", "✓ step 2 done"),
    // The snowman from a procedure, without a group.
    (
        "proc ball(y, r) put translate sphere center 0, y, 0 radius r kd 1 ks 0 phong 1 color 250, 250, 250 end \
         by 3, 0, 0 end end",
        "not yet: ",
    ),
    ("ball(-0.2, 0.8) ball(1, 0.5)", "✓ step 3 done"),
    (":lesson 8", "step 1 of 4"),
    ("proc row(k) if k < 5 then row(k + 1) end end", "✓ step 1 done"),
    // Five balls from one `put` by a recursion counting up, in another procedure.
    (
        "proc line(k) if k < 5 then put sphere center k, 1, 0 radius 0.2 kd 1 ks 0 phong 1 color 0, 0, 255 end \
         line(k + 1) end end",
        "not yet: ",
    ),
    ("line(0)", "✓ step 2 done"),
];

/// Runs `answers` (inputs, each with what the session says after it) in a
/// new session without pictures, then leaves it.
fn converse(answers: &[(&str, &str)]) {
    let home = tempfile::tempdir().expect("temporary directory");
    let mut session = spawn(&home.path().join("lessons"), false);
    for (input, expected) in answers {
        answer(&mut session, input, expected);
    }
    assert_eq!(quit(session), 0);
}

#[test]
fn answers_written_otherwise_than_the_examples_pass() {
    converse(OTHER_ANSWERS);
}

#[test]
fn a_step_the_scene_already_does_is_passed_at_once() {
    converse(&[
        (":lesson 2", "step 1 of 3"),
        // A light from the left first: wrong for step 1, but what step 3 asks.
        ("light vector 0, 0, 0.9 intensity 0.4 end", "not yet: your light in input [2]"),
        (RIGHT_ANSWERS[1][0], "✓ step 1 done"),
        ("ambient 0.1", "✓ step 2 done"),
        ("", "✓ step 3 done: your scene already does it"),
        ("", "✓ lesson 2 done"),
    ]);
}

#[test]
fn a_lesson_that_cannot_start_leaves_the_session_as_it_was() {
    converse(&[
        ("put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end", "put 1 sphere"),
        (":limits primitives 1", "primitives = 1"),
        // Lesson 2's scene has two objects: more than the limit.
        (":lesson 2", "error"),
        (":scene", "objects:  1 (1 sphere, 0 planes, 0 boxes)"),
    ]);
}

#[test]
fn a_lesson_left_halfway_goes_on_where_it_stopped() {
    let home = tempfile::tempdir().expect("temporary directory");
    let progress = home.path().join("lessons");
    let mut session = spawn(&progress, false);
    answer(&mut session, ":lesson 8", "step 1 of 4");
    answer(&mut session, RIGHT_ANSWERS[7][0], "✓ step 1 done");
    assert_eq!(quit(session), 0);
    let mut session = spawn(&progress, false);
    answer(&mut session, ":lesson", "you stopped at lesson 8 step 2: `:lesson 8` goes on from there");
    answer(&mut session, ":lesson 8", "going on at step 2, where you stopped");
    // The earlier step's example is in the scene: `row` is defined.
    answer(&mut session, "row(5)", "✓ step 2 done");
    answer(&mut session, ":lesson stop", "left the lesson");
    let shown = output_before_scene(&mut session, "let x = 1");
    assert!(shown.contains("x = 1") && !shown.contains("not yet"), "{shown}");
    assert_eq!(quit(session), 0);
}

#[test]
fn play_shows_frames_until_a_key() {
    let home = tempfile::tempdir().expect("temporary directory");
    let mut session = spawn(&home.path().join("lessons"), true);
    session.expect("ray> ").expect("a first prompt");
    session.send_line("put sphere center sin(time), 0, 0 radius 2 kd 1 ks 0 phong 1 color 255, 0, 0 end").unwrap();
    session.expect("put 1 sphere").expect("the sphere is put");
    session.send_line(":play 3 30").unwrap();
    // The first picture asks the terminal what it can show (no sixel here).
    session.expect("\x1b[c").expect("the terminal is asked about sixel images");
    session.send("\x1b[?1;2c").unwrap();
    session.expect("playing 3 frames of").expect("the frames are rendered");
    session.expect("▄").expect("a frame is drawn");
    std::thread::sleep(Duration::from_millis(300));
    session.send("q").unwrap();
    session.expect("stopped after").expect("a key stops it");
    assert_eq!(quit(session), 0);
}

/// A progress file that never ends (`/dev/zero`) is read no further than a
/// progress file could be long: the lessons start, nothing fills the memory.
#[test]
fn an_endless_progress_file_is_read_only_so_far() {
    let output = assert_cmd::Command::cargo_bin("rayrepl")
        .expect("the binary is built")
        .env("RAYREPL_LESSONS", "/dev/zero")
        .write_stdin(":lesson\n")
        .timeout(std::time::Duration::from_secs(60))
        .output()
        .expect("rayrepl runs");
    assert!(String::from_utf8_lossy(&output.stdout).starts_with("lessons (`:lesson N` starts one"));
}

/// What a piped script prints (standard output, then standard error), and
/// its exit status, with lesson progress kept in a new folder; `arguments`
/// go on the command line.
fn piped(script: &str, arguments: &[&str]) -> (String, i32) {
    let home = tempfile::tempdir().expect("temporary directory");
    let output = assert_cmd::Command::cargo_bin("rayrepl")
        .expect("the binary is built")
        .env("RAYREPL_LESSONS", home.path().join("lessons"))
        .env("NO_COLOR", "1")
        .args(arguments)
        .write_stdin(script)
        .timeout(Duration::from_secs(60))
        .output()
        .expect("rayrepl runs");
    let text = format!("{}{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    (unwrapped(&text), output.status.code().unwrap_or(-1))
}

/// `text` with the lines that the lessons wrap joined again: a line
/// indented by five spaces or more continues the one before (an example is
/// indented by four).
fn unwrapped(text: &str) -> String {
    let mut joined = String::new();
    for line in text.lines() {
        match line.strip_prefix("     ") {
            Some(rest) if !joined.is_empty() => {
                joined.pop();
                joined.push(' ');
                joined.push_str(rest.trim_start());
            }
            _ => joined.push_str(line),
        }
        joined.push('\n');
    }
    joined
}

/// Wrong answers the lessons' files do not hold, each given as a piped
/// script after the right answers to the steps before it: each gets "not
/// yet" and words about the learner's own scene.
#[test]
fn unseen_wrong_answers_get_not_yet_with_words_about_them() {
    let cases: &[(&str, &str, &str)] = &[
        // An orange ball of radius 2 asked, a red one of radius 1 given.
        (
            ":lesson 1\ncamera distance 10 angle 0.8 end",
            "put sphere center 0, 0, 0 radius 1 kd 0.8 ks 0.2 phong 20 color 255, 0, 0 end",
            "has radius 1 (the goal: 2)",
        ),
        // A light in degrees, which leaves the ball unlit.
        (
            ":lesson 1\ncamera distance 10 angle 0.8 end\nput sphere center 0, 0, 0 radius 2 kd 0.8 ks 0.2 phong 20 color 255, 120, 40 end",
            "light vector 45, 0, -45 intensity 0.8 end",
            "the angle 45 at line 4 looks like degrees",
        ),
        // A second light as bright as the first, for "weaker".
        (
            ":lesson 2\nlight vector 0, 0, -0.9 intensity 0.8 end\nambient 0.05",
            "light vector 0, 0, 0.9 intensity 0.8 end",
            "not weaker",
        ),
        // An eighth of a turn in degrees.
        (
            ":lesson 5",
            "put rotate box center 0, 0, 0 length 3, 1, 1 kd 0.7 ks 0.2 phong 10 color 40, 160, 90 end by 0, 0, 45 end",
            "the angle 45 at line 2 looks like degrees",
        ),
        // The wrong order of transformations.
        (
            ":lesson 5\nput rotate box center 0, 0, 0 length 3, 1, 1 kd 0.7 ks 0.2 phong 10 color 40, 160, 90 end by 0, 0, pi/4 end",
            "put scale translate sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end by -3, 0.5, 0 end by 1.5 end",
            "center -4.5, 0.75, 0",
        ),
        // A capital for `r`, then a wrong value.
        (":lesson 6", "let R = 0.7", "you named it `R`"),
        (":lesson 6", "let r = 0.07", "your `r` is 0.07"),
    ];
    let mut cases = cases.to_vec();
    // A tower floating above the floor.
    let lesson_8 = format!(":lesson 8\n{}", RIGHT_ANSWERS[7][..3].join("\n"));
    cases.push((&lesson_8, "tower(5, 0.8, 0.5)", "on the floor"));
    for (before, wrong, words) in cases {
        let (shown, _) = piped(&format!("{before}\n{wrong}\n"), &[]);
        assert!(shown.contains("not yet: ") && shown.contains(words), "after `{wrong}`, no \"{words}\":\n{shown}");
    }
}

/// After an input that is a right part of the step, "not yet" does not
/// offer to take it back; after a wrong one, it does.
#[test]
fn undo_is_offered_only_after_a_wrong_input() {
    let (shown, _) = piped(
        ":lesson 7\nproc post(x) put box center x, 0, 0 length 0.4, 2, 0.4 kd 1 ks 0 phong 1 color 9, 9, 9 end end\npost(-2)\n",
        &[],
    );
    assert!(shown.contains("your scene has 1 of the 3 boxes") && !shown.contains(":undo` takes"), "{shown}");
    let (shown, _) = piped(
        ":lesson 3\nput sphere center -2, 0, 0 radius 1 kd 0.9 ks 0.5 phong 1 color 220, 30, 30 end\nlet z = 1\n",
        &[],
    );
    assert!(shown.contains("has ks 0.5 (the goal: 0) (`:undo` takes your last input back)"), "{shown}");
}

/// A teacher's lesson, in a file: started with `--lesson FILE`, checked as
/// the built-in ones are, to its end.
#[test]
fn a_lesson_from_a_teachers_file_runs_to_its_end() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let file = folder.path().join("red.md");
    std::fs::write(
        &file,
        "# a red ball\n\n```ray setup\ncamera distance 10 angle 0.8 end\n```\n\n## the ball\n\n\
         Put a red ball of radius 1 at the origin.\n\n```ray example\n\
         put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end\n```\n\n\
         Hint: red is about 255, 0, 0.\n\nCheck: a sphere, radius 1, center 0 0 0, color 255 0 0 within 40\n\n\
         ```ray fails\nput sphere center 0, 0, 0 radius 2 kd 1 ks 0 phong 1 color 255, 0, 0 end\n```\nSays: radius 2\n",
    )
    .expect("the lesson is written");
    let script = "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 0, 0, 255 end\n:undo\n\
                  put scale sphere center 0, 0, 0 radius 0.5 kd 1 ks 0 phong 1 color 250, 10, 10 end by 2 end\n";
    let (shown, status) = piped(script, &["--lesson", file.to_str().expect("a UTF-8 path")]);
    assert!(shown.contains("lesson: a red ball"), "{shown}");
    assert!(shown.contains("has color 0, 0, 255 (the goal: 255, 0, 0 within 40)"), "{shown}");
    assert!(shown.contains("✓ step 1 done") && shown.contains("✓ lesson done: a red ball"), "{shown}");
    assert_eq!(status, 0, "{shown}");
}

/// A lesson file with a mistake gets a diagnostic with its file, line and
/// column, the line and a caret; so does one whose answers contradict its
/// checks.
#[test]
fn a_malformed_lesson_file_gets_a_diagnostic_with_its_line() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let file = folder.path().join("bad.md");
    std::fs::write(&file, "# a ball\n\n## the ball\n\nPut a ball.\n\n```ray example\nput sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end\n```\n\nCheck: a sphere, colour 9 9 9\n").expect("written");
    let (shown, status) = piped(&format!(":lesson {}\n", file.display()), &[]);
    assert!(shown.contains("`colour` is not a property a check knows"), "{shown}");
    assert!(
        shown.contains("bad.md:11:7") && shown.contains("Check: a sphere, colour 9 9 9") && shown.contains('^'),
        "{shown}"
    );
    assert_eq!(status, 1);
    let contradicting = "# a ball\n\n## the ball\n\nPut a ball.\n\n```ray example\nput sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end\n```\n\nCheck: a sphere, radius 2\n";
    std::fs::write(&file, contradicting).expect("written");
    let (shown, _) = piped(&format!(":lesson {}\n", file.display()), &[]);
    assert!(
        shown.contains("step 1 refuses its own example: your sphere, put at line 1, has radius 1 (the goal: 2)"),
        "{shown}"
    );
    assert!(shown.contains("bad.md:7:1"), "{shown}");
}

/// `:goal FILE` writes the step's goal with the bytes the batch renderer
/// writes for the same program at the same size.
#[test]
fn the_goal_written_is_the_batch_render_of_the_lessons_program() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let goal = folder.path().join("goal.png");
    let script = format!(":size 120 90\n:lesson 3\n:goal {}\n", goal.display());
    let (shown, status) = piped(&script, &[]);
    assert!(shown.contains("saved the goal of step 1 to") && status == 0, "{shown}");
    let lesson = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/3-textures.md"))
        .expect("the lesson file");
    let block = |kind: &str| {
        let start = lesson.find(&format!("```ray {kind}\n")).expect("the block") + kind.len() + 7;
        lesson[start..].split("```").next().expect("its end").to_string()
    };
    let program = folder.path().join("goal.ray");
    std::fs::write(&program, format!("{}{}", block("setup"), block("example shown"))).expect("written");
    let batch = folder.path().join("batch.png");
    assert_cmd::Command::cargo_bin("rayrepl")
        .expect("the binary is built")
        .args([program.as_os_str(), "-o".as_ref(), batch.as_os_str(), "--width".as_ref(), "120".as_ref()])
        .args(["--height", "90"])
        .assert()
        .success();
    assert!(std::fs::read(&goal).expect("the goal") == std::fs::read(&batch).expect("the batch render"));
}

/// With pictures, a lesson shows the goal beside the learner's render, and
/// the task again under them after a wrong try; `:preview off` hides them.
#[test]
fn lesson_pictures_follow_the_preview_setting() {
    let home = tempfile::tempdir().expect("temporary directory");
    let mut session = spawn(&home.path().join("lessons"), true);
    session.expect("ray> ").expect("a first prompt");
    session.send_line(":lesson 3").expect("typed");
    session.expect("\x1b[c").expect("the terminal is asked about sixel images");
    session.send("\x1b[?1;2c").expect("the answer: no sixel");
    answer(&mut session, "", "goal (left) and yours (right):");
    session.expect("▄").expect("the pictures are drawn");
    let shiny = "put sphere center -2, 0, 0 radius 1 kd 0.9 ks 0.5 phong 1 color 220, 30, 30 end";
    answer(&mut session, shiny, "goal (left) and yours (right):");
    answer(&mut session, "", "step 1 of 3: A matt red ball");
    answer(&mut session, "", "not yet: your sphere");
    answer(&mut session, ":preview off", "ray> ");
    let shown = output_before_scene(&mut session, "let x = 1");
    assert!(shown.contains("not yet") && !shown.contains("goal (left)"), "{shown}");
    assert_eq!(quit(session), 0);
}
