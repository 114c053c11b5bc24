//! The interactive session driven through a pseudo-terminal: multi-line
//! input, completion, Ctrl-C, Ctrl-D, colours and the history file; and its
//! entry loop fed typed lines in-process, for what it prints.

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use expectrl::process::unix::WaitStatus;
use expectrl::{Any, ControlCode, Eof, Expect, Session};
use rayrepl::lang::Limits;
use rayrepl::session::SessionOptions;
use rayrepl::terminal::run_typed;

use crate::common::interrupt::{names_in, wait_for_a_write, wait_for_files};

/// A session on a terminal, its history kept under `data_home`.
fn spawn(args: &[&str], data_home: &Path, color: bool) -> expectrl::session::OsSession {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rayrepl"));
    command.args(args).env("XDG_DATA_HOME", data_home).env("TERM", "xterm-256color");
    if color {
        command.env_remove("NO_COLOR");
    } else {
        command.env("NO_COLOR", "1");
    }
    let mut session = Session::spawn(command).expect("the binary starts");
    session.set_expect_timeout(Some(Duration::from_secs(30)));
    session.expect("ray> ").expect("a first prompt");
    session
}

/// A session without previews, with its own history directory, in colour or not.
fn fresh(color: bool) -> (expectrl::session::OsSession, tempfile::TempDir) {
    let data_home = tempfile::tempdir().expect("temporary directory");
    let session = spawn(&["--no-preview"], data_home.path(), color);
    (session, data_home)
}

/// At the next prompt, Ctrl-D, then the exit status. A session holding
/// typed inputs says first that they are not written to a file, and the
/// second Ctrl-D leaves. (Keys typed before the editor reads the terminal
/// again would reach the terminal in its normal mode, where Ctrl-D means
/// something else.)
fn leave(mut session: expectrl::session::OsSession) -> i32 {
    const NOTE: &str = "not written to a file";
    session.expect("ray> ").expect("a prompt");
    session.send(ControlCode::EndOfTransmission).expect("Ctrl-D is sent");
    let found = session.expect(Any::boxed(vec![Box::new(Eof), Box::new(NOTE)])).expect("the session ends or warns");
    if found.get(0) == Some(NOTE.as_bytes()) {
        session.expect("ray> ").expect("a prompt");
        session.send(ControlCode::EndOfTransmission).expect("Ctrl-D is sent");
        session.expect(Eof).expect("the session ends");
    }
    match session.get_process().wait().expect("the exit status") {
        WaitStatus::Exited(_, code) => code,
        other => panic!("the session did not exit normally: {other:?}"),
    }
}

#[test]
fn an_input_continues_while_a_construct_is_open() {
    let (mut session, _home) = fresh(false);
    session.send_line("proc row(n)").unwrap();
    session.expect("...proc> ").unwrap();
    session.send_line("  put sphere center n, 0, 0").unwrap();
    session.expect("...sphere> ").unwrap();
    // A command in the middle of an input runs, and the input goes on.
    session.send_line(":help sphere").unwrap();
    session.expect("sphere center X, Y, Z radius R TEXTURE end").unwrap();
    session.expect("...sphere> ").unwrap();
    session.send_line("    radius 0.5 kd 1 ks 0 phong 1 color 255, 0, 0").unwrap();
    session.expect("...sphere> ").unwrap();
    session.send_line("  end").unwrap();
    session.expect("...proc> ").unwrap();
    session.send_line("end").unwrap();
    session.expect("defined proc row(n)").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("let x = 1 +").unwrap();
    session.expect("...> ").unwrap();
    session.send_line("2").unwrap();
    session.expect("x = 3").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("row(1)").unwrap();
    session.expect("put 1 sphere (1 object in the scene)").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn an_error_leaves_the_session_running_and_unchanged() {
    let (mut session, _home) = fresh(false);
    session.send_line("let a = 1").unwrap();
    session.expect("a = 1").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("let a = nowhere").unwrap();
    session.expect("nowhere").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":env").unwrap();
    session.expect("numbers:    a = 1, time = 0").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn a_render_warns_about_the_scene_once_and_print_shows_values() {
    let (mut session, _home) = fresh(false);
    session.send_line("camera distance -10 angle 1 end").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("print 2 * 3").unwrap();
    session.expect("<input 3>:1: 2 * 3 = 6").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":render 8 6").unwrap();
    session.expect("the camera distance is -10").unwrap();
    session.expect("rendered 8×6").unwrap();
    session.expect("ray> ").unwrap();
    // The same cause is not warned about again.
    session.send_line(":render 8 6").unwrap();
    let between = session.expect("rendered 8×6").unwrap();
    assert!(!String::from_utf8_lossy(between.before()).contains("warning"));
    assert_eq!(leave(session), 0);
}

#[test]
fn ctrl_c_drops_the_input_being_typed_and_stays() {
    let (mut session, _home) = fresh(false);
    session.send_line("put sphere center 0, 0, 0").unwrap();
    session.expect("...sphere> ").unwrap();
    session.send(ControlCode::EndOfText).unwrap();
    session.expect("(input dropped)").unwrap();
    session.expect("ray> ").unwrap();
    // Ctrl-C on an empty line only gives a new prompt.
    session.send(ControlCode::EndOfText).unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":scene").unwrap();
    session.expect("objects:  0 ").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":quit").unwrap();
    session.expect(Eof).unwrap();
    assert!(matches!(session.get_process().wait().unwrap(), WaitStatus::Exited(_, 0)));
}

#[test]
fn tab_completes_names_procedures_and_commands() {
    let (mut session, _home) = fresh(false);
    session.send_line("let spin = 2").unwrap();
    session.expect("spin = 2").unwrap();
    session.expect("ray> ").unwrap();
    session.send("let x = spi\t").unwrap();
    session.send_line(" * 3").unwrap();
    session.expect("x = 6").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("proc spiral(size) end").unwrap();
    session.expect("defined proc spiral(size)").unwrap();
    session.expect("ray> ").unwrap();
    session.send("spir\t").unwrap();
    session.send_line("1)").unwrap();
    session.expect("nothing was put").unwrap();
    session.expect("ray> ").unwrap();
    session.send(":sce\t").unwrap();
    session.send_line("").unwrap();
    session.expect("settings: time 0").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn keywords_and_diagnostics_are_coloured_on_a_terminal() {
    let (mut session, _home) = fresh(true);
    session.send("put").unwrap();
    session.expect("\x1b[1;34mput\x1b[0m").unwrap();
    session.send(ControlCode::EndOfText).unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("let a = nowhere").unwrap();
    // `error` in bold bright red, as in every mode.
    session.expect("\x1b[91merror").unwrap();
    session.expect("not defined here").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn a_call_chain_across_inputs_is_in_call_order_and_names_the_inputs() {
    anstream::ColorChoice::Never.write_global();
    let lines = ["proc f(n)", "  g(n + 1)", "end", "proc g(n) f(n) end", "f(0)"];
    let limits = Limits { max_call_depth: 20, ..Limits::default() };
    let options = SessionOptions { no_preview: true, limits, ..SessionOptions::default() };
    let (mut out, mut err) = (Vec::new(), Vec::new());
    run_typed(lines.map(String::from), &mut out, &mut err, &options);
    let err = String::from_utf8(err).expect("text");
    assert!(err.contains(" --> <input 2>:1:11\n"), "{err}");
    let chain = "call chain: f (<input 3>:1) -> g (<input 1>:2) -> f (line 1) -> \
                 ... the cycle `g (<input 1>:2) -> f (line 1)` repeated 9 more times";
    assert!(err.contains(&format!("  = note: {chain}\n")), "{err}");
}

#[test]
fn history_is_kept_between_sessions() {
    let data_home = tempfile::tempdir().expect("temporary directory");
    let mut session = spawn(&["--no-preview"], data_home.path(), false);
    session.send_line("let kept = 42").unwrap();
    session.expect("kept = 42").unwrap();
    assert_eq!(leave(session), 0);
    let history = std::fs::read_to_string(data_home.path().join("rayrepl/history")).expect("a history file");
    assert!(history.contains("let kept = 42"), "{history}");
    let mut session = spawn(&["--no-preview"], data_home.path(), false);
    session.send("\x1b[A").unwrap();
    session.send_line("").unwrap();
    session.expect("kept = 42").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":history 1").unwrap();
    session.expect("(1 line before these: `:history 2` shows them all)").unwrap();
    session.expect("   2  :history 1").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn a_file_given_with_i_is_loaded_first() {
    let data_home = tempfile::tempdir().expect("temporary directory");
    let scene = data_home.path().join("start.ray");
    std::fs::write(&scene, "let r = 4\n").expect("write the scene");
    let mut command = Command::new(env!("CARGO_BIN_EXE_rayrepl"));
    command
        .args(["--no-preview", "-i"])
        .arg(&scene)
        .env("XDG_DATA_HOME", data_home.path())
        .env("TERM", "xterm-256color")
        .env("NO_COLOR", "1");
    let mut session = Session::spawn(command).expect("the binary starts");
    session.set_expect_timeout(Some(Duration::from_secs(30)));
    session.expect("r = 4").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("let s = r * 2").unwrap();
    session.expect("s = 8").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn prompts_number_the_inputs_that_messages_name() {
    let (mut session, _home) = fresh(false);
    session.send_line("let a = 1").unwrap();
    session.expect("[2] ray> ").unwrap();
    session.send_line(":env").unwrap();
    session.expect("[3] ray> ").unwrap();
    session.send_line("let b = nowhere").unwrap();
    session.expect("<input 3>:1:9").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn a_broken_line_is_reported_at_once_and_the_entry_comes_back() {
    let (mut session, _home) = fresh(false);
    session.send_line("proc p()").unwrap();
    session.expect("...proc> ").unwrap();
    // A person takes time to type a line (a line read at once was typed
    // ahead or pasted, and does not come back to the editor).
    std::thread::sleep(Duration::from_millis(100));
    // `sphre` could be an object's name, but not followed by `radius`.
    session.send_line("  put sphre radius 1").unwrap();
    session.expect("<input 1>:2:13").unwrap();
    session.expect("the entry is back in the editor").unwrap();
    session.expect("put sphre radius 1").unwrap();
    session.send(ControlCode::EndOfText).unwrap();
    session.expect("(input dropped)").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn leaving_in_the_middle_of_an_entry_warns_first() {
    let (mut session, _home) = fresh(false);
    session.send_line("proc p()").unwrap();
    session.expect("...proc> ").unwrap();
    session.send(ControlCode::EndOfTransmission).unwrap();
    session.expect("is not finished (`proc p()`, 1 line): Ctrl-D again leaves without it").unwrap();
    session.expect("...proc> ").unwrap();
    session.send(ControlCode::EndOfTransmission).unwrap();
    session.expect(Eof).unwrap();
}

#[test]
fn limits_are_raised_with_a_command_in_the_session() {
    let (mut session, _home) = fresh(false);
    session.send_line(":limits calls 50").unwrap();
    session.expect("calls = 50").unwrap();
    session.send_line("proc f(n) f(n + 1) end").unwrap();
    session.expect("defined proc f(n)").unwrap();
    session.send_line("f(1)").unwrap();
    session.expect("recursion deeper than 50 calls").unwrap();
    session.expect("`:limits calls N`").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("let ball = 1").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":env").unwrap();
    session.expect("`object ball2 = sphere ... end` names one").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn lines_typed_ahead_or_pasted_all_run_in_order() {
    let (mut session, _home) = fresh(false);
    // Without bracketed paste: the lines arrive at once, one broken.
    session.send("let a = 1\nproc p()\n  put sphre radius 1\nend\nlet b = a + 1\n:env\n").unwrap();
    session.expect("<input 2>:2:13").unwrap();
    session.expect("the arrow key up brings the entry back to fix it").unwrap();
    session.expect("this `end` closes nothing").unwrap();
    session.expect("b = 2").unwrap();
    session.expect("numbers:    a = 1, b = 2, time = 0").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn ctrl_c_stops_a_runaway_evaluation_and_keeps_the_session() {
    let (mut session, _home) = fresh(false);
    session.send_line("let keep = 7").unwrap();
    session.expect("keep = 7").unwrap();
    session.send_line(":limits calls 100000000").unwrap();
    session.expect("calls = 100000000").unwrap();
    session.send_line("proc f(n) f(n + 1) end").unwrap();
    session.expect("defined proc f(n)").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("f(1)").unwrap();
    std::thread::sleep(Duration::from_millis(300));
    session.send(ControlCode::EndOfText).unwrap();
    session.expect("stopped by Ctrl-C").unwrap();
    session.expect("nothing of this input was kept").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":env").unwrap();
    session.expect("numbers:    keep = 7").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn ctrl_c_stops_the_writing_of_a_file_and_keeps_the_session() {
    let (mut session, _home) = fresh(false);
    let dir = tempfile::tempdir().expect("temporary directory");
    let big = dir.path().join("big.ppm");
    session.send_line("let keep = 7").unwrap();
    session.expect("keep = 7").unwrap();
    // Nothing to trace: the time goes into writing 8192x8192 pixels.
    session.send_line("camera distance 10 angle 1 end").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(format!(":save {} 8192 8192", big.display())).unwrap();
    wait_for_a_write(dir.path());
    session.send(ControlCode::EndOfText).unwrap();
    session.expect(format!("writing `{}` was cancelled: the file is as it was before", big.display())).unwrap();
    session.expect("the session is as it was").unwrap();
    session.send_line(":env").unwrap();
    session.expect("numbers:    keep = 7").unwrap();
    assert_eq!(names_in(dir.path()), Vec::<String>::new(), "no image, no temporary file");
    assert_eq!(leave(session), 0);
}

#[test]
fn ctrl_c_stops_an_animation_and_says_which_frames_were_written() {
    let (mut session, _home) = fresh(false);
    let dir = tempfile::tempdir().expect("temporary directory");
    session.send_line(":size 320 240").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("put sphere center time - 2, 0, 0 radius 1 kd 0.8 ks 0 phong 10 color 255, 0, 0 end").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(format!(":anim 1000000 {}", dir.path().join("f.png").display())).unwrap();
    wait_for_files(dir.path(), ".png", 3);
    session.send(ControlCode::EndOfText).unwrap();
    session.expect("written before it stopped").unwrap();
    session.expect("the session is as it was").unwrap();
    session.send_line(":scene").unwrap();
    session.expect("1 sphere").unwrap();
    let frames = names_in(dir.path());
    for (k, frame) in frames.iter().enumerate() {
        assert_eq!(*frame, format!("f{:07}.png", k + 1), "no temporary file");
        let image = image::open(dir.path().join(frame)).expect("a whole frame").to_rgb8();
        assert_eq!(image.dimensions(), (320, 240));
    }
    assert_eq!(leave(session), 0);
}

#[test]
fn leaving_with_inputs_not_written_says_how_to_keep_them() {
    let (mut session, home) = fresh(false);
    session.send_line("let a = 1").unwrap();
    session.expect("a = 1").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":quit").unwrap();
    session
        .expect("1 input is not written to a file: `:write FILE.ray` keeps it; :quit again leaves without it")
        .unwrap();
    session.expect("ray> ").unwrap();
    let file = home.path().join("kept.ray");
    session.send_line(format!(":write {}", file.display())).unwrap();
    session.expect("wrote").unwrap();
    session.expect("ray> ").unwrap();
    // Everything is written now: the first Ctrl-D leaves.
    session.send(ControlCode::EndOfTransmission).unwrap();
    session.expect(Eof).unwrap();
    assert!(std::fs::read_to_string(&file).expect("written").contains("let a = 1"));
}

#[test]
fn watch_renders_at_every_save_until_ctrl_c() {
    let (mut session, home) = fresh(false);
    let file = home.path().join("watched.ray");
    let scene = "let r = 1\nput sphere center 0, 0, 0 radius r kd 1 ks 0 phong 1 color 255, 0, 0 end\n";
    std::fs::write(&file, scene).expect("written");
    session.send_line(":size 16 12").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(format!(":watch {}", file.display())).unwrap();
    session.expect("(1 object and 0 lights in the scene)").unwrap();
    session.expect("rendered 16×12").unwrap();
    std::fs::write(&file, format!("{scene}put sphere center 2, 0, 0 radius r kd 1 ks 0 phong 1 color 0, 0, 255 end\n"))
        .expect("saved");
    session.expect("(2 objects and 0 lights in the scene)").unwrap();
    session.expect("rendered 16×12").unwrap();
    // Emptied, as an editor that truncates before writing leaves it: the
    // last version stays (as `--watch` keeps its last good picture).
    std::fs::write(&file, "").expect("emptied");
    session.expect("watched.ray is empty: the last version stays until it is saved again").unwrap();
    session.send(ControlCode::EndOfText).unwrap();
    session.expect("stopped watching").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":scene").unwrap();
    session.expect("objects:  2 ").unwrap();
    // A loaded file is no typed input: nothing to write before leaving.
    session.expect("ray> ").unwrap();
    session.send(ControlCode::EndOfTransmission).unwrap();
    session.expect(Eof).unwrap();
}

/// `text` as a terminal sends a bracketed paste: its line ends as Enter (CR).
fn bracketed_paste(text: &str) -> String {
    format!("\x1b[200~{}\x1b[201~", text.replace('\n', "\r"))
}

#[test]
fn a_bracketed_paste_runs_its_lines_as_if_typed() {
    let (mut session, _home) = fresh(false);
    // A command among program lines, and a construct over two lines: each
    // line as if typed and ended with Enter, the last one included.
    let pasted = "let a = 1\nlet b = a + 1\n:scene\nput sphere center 0, 0, 0 radius b\n  kd 1 ks 0 phong 1 color 255, 0, 0 end\n";
    session.send(bracketed_paste(pasted)).unwrap();
    session.expect("b = 2").unwrap();
    session.expect("objects:  0").unwrap();
    session.expect("put 1 sphere").unwrap();
    session.expect("[5] ray> ").unwrap();
    // A second paste is an entry of its own.
    session.send(bracketed_paste("print a\n")).unwrap();
    session.expect("<input 5>:1: a = 1").unwrap();
    session.expect("[6] ray> ").unwrap();
    // A paste without a line end waits in the editor, to be edited.
    session.send(bracketed_paste("let c = 3")).unwrap();
    session.send(" + 1").unwrap();
    session.send("\r").unwrap();
    session.expect("c = 4").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn a_paste_that_leaves_an_entry_open_says_what_is_open_and_goes_on_at_its_prompt() {
    let (mut session, _home) = fresh(false);
    session.send(bracketed_paste("proc p()\n  put sphere center 0, 0, 0\n")).unwrap();
    session
        .expect("note: the entry (2 lines so far) leaves `proc`, `sphere` open, each waiting for its `end`")
        .unwrap();
    session.expect("...sphere> ").unwrap();
    session.send_line("  radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end").unwrap();
    session.expect("...proc> ").unwrap();
    session.send_line("end").unwrap();
    session.expect("[2] ray> ").unwrap();
    session.send(bracketed_paste("let a = 1 +\n  2 *\n")).unwrap();
    session.expect("note: the entry (2 lines so far) ends in the middle of an item").unwrap();
    session.expect("...> ").unwrap();
    session.send_line("3").unwrap();
    session.expect("a = 7").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn keys_typed_right_after_ctrl_c_are_kept() {
    let (mut session, _home) = fresh(false);
    session.send("let a = 1").unwrap();
    // Ctrl-C and the next line in one write: the editor reads them together.
    session.send("\x03let b = 2\r").unwrap();
    session.expect("b = 2").unwrap();
    session.send_line(":env").unwrap();
    session.expect("numbers:    b = 2, time = 0").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn ctrl_c_drops_the_rest_of_a_paste() {
    let (mut session, _home) = fresh(false);
    let pasted = "proc f(n) if n > 0 then f(n - 1) f(n - 1) end end\nf(60)\nlet after = 1\nlet also = 2\n";
    session.send(bracketed_paste(pasted)).unwrap();
    session.expect("defined proc f(n)").unwrap();
    std::thread::sleep(Duration::from_millis(300));
    session.send(ControlCode::EndOfText).unwrap();
    session.expect("stopped by Ctrl-C").unwrap();
    session.expect("(the rest of the paste dropped: 2 lines)").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":env").unwrap();
    session.expect("numbers:    time = 0").unwrap();
    assert_eq!(leave(session), 0);
}

#[test]
fn a_long_line_pasted_without_bracketed_paste_is_written_once() {
    // Each key of a pasted line arrives alone. The editor writes each at
    // the end of the line, a new row at every wrap: what reaches the
    // terminal grows with the line, not with its square (as when every
    // wrap, or every key with a hint from history, repainted the line).
    let (mut session, _home) = fresh(false);
    let line = format!("let long = 0{}", " + 1".repeat(2500));
    // The second time, the history holds the line.
    for round in 0..2 {
        if round > 0 {
            session.expect("ray> ").unwrap();
        }
        session.send_line(&line).unwrap();
        let answer = session.expect("long = 2500").unwrap();
        let written = answer.before().len();
        assert!(written < 2 * line.len(), "{written} bytes written for a line of {}", line.len());
    }
    assert_eq!(leave(session), 0);
}

#[test]
fn exit_alone_ends_the_session() {
    let (mut session, _home) = fresh(false);
    session.send_line("  exit ").unwrap();
    session.expect(Eof).unwrap();
}

#[test]
fn help_alone_shows_the_help_overview() {
    let (mut session, _home) = fresh(false);
    session.send_line("help").unwrap();
    session.expect("`:help NAME` explains one of these:").unwrap();
    // No input waits for more: the next prompt is a new one.
    session.expect("[2] ray> ").unwrap();
    session.send(ControlCode::EndOfTransmission).unwrap();
    session.expect(Eof).unwrap();
}

#[test]
fn quit_alone_with_inputs_not_written_warns_then_leaves() {
    let (mut session, _home) = fresh(false);
    session.send_line("let a = 1").unwrap();
    session.expect("a = 1").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("quit").unwrap();
    session.expect("1 input is not written to a file: `:write FILE.ray` keeps it; :quit again leaves").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("quit").unwrap();
    session.expect(Eof).unwrap();
}

#[test]
fn clear_alone_clears_the_screen_even_with_a_number_named_clear() {
    let (mut session, _home) = fresh(false);
    session.send_line("let clear = 2").unwrap();
    session.expect("clear = 2").unwrap();
    session.expect("[2] ray> ").unwrap();
    session.send_line("clear").unwrap();
    // The screen is cleared (the cursor goes home, the screen is erased).
    session.expect("\x1b[H\x1b[J").unwrap();
    session.expect("[3] ray> ").unwrap();
    // What is typed next is an input of its own, not glued onto `clear`.
    session.send_line("let b = clear + 1").unwrap();
    session.expect("b = 3").unwrap();
    assert_eq!(leave(session), 0);
}
