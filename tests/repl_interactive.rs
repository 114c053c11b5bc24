//! The interactive session driven through a pseudo-terminal: multi-line
//! input, completion, Ctrl-C, Ctrl-D, colours and the history file.

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use expectrl::process::unix::WaitStatus;
use expectrl::{ControlCode, Eof, Expect, Session};

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

/// A plain session without previews, with its own history directory.
fn plain() -> (expectrl::session::OsSession, tempfile::TempDir) {
    let data_home = tempfile::tempdir().expect("temporary directory");
    let session = spawn(&["--no-preview"], data_home.path(), false);
    (session, data_home)
}

/// At the next prompt, Ctrl-D, then the exit status. (Keys typed before the
/// editor reads the terminal again would reach the terminal in its normal
/// mode, where Ctrl-D means something else.)
fn leave(mut session: expectrl::session::OsSession) -> i32 {
    session.expect("ray> ").expect("a prompt");
    session.send(ControlCode::EndOfTransmission).expect("Ctrl-D is sent");
    session.expect(Eof).expect("the session ends");
    match session.get_process().wait().expect("the exit status") {
        WaitStatus::Exited(_, code) => code,
        other => panic!("the session did not exit normally: {other:?}"),
    }
}

#[test]
fn an_input_continues_while_a_construct_is_open() {
    let (mut session, _home) = plain();
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
    let (mut session, _home) = plain();
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
    let (mut session, _home) = plain();
    session.send_line("camera distance 10 angle 45 end").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line("print 2 * 3").unwrap();
    session.expect("<input 3>:1: 2 * 3 = 6").unwrap();
    session.expect("ray> ").unwrap();
    session.send_line(":render 8 6").unwrap();
    session.expect("the camera angle 45 looks like degrees").unwrap();
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
    let (mut session, _home) = plain();
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
    let (mut session, _home) = plain();
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
fn keywords_are_coloured_on_a_terminal() {
    let data_home = tempfile::tempdir().expect("temporary directory");
    let mut session = spawn(&["--no-preview"], data_home.path(), true);
    session.send("put").unwrap();
    session.expect("\x1b[1;34mput\x1b[0m").unwrap();
    session.send(ControlCode::EndOfText).unwrap();
    assert_eq!(leave(session), 0);
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
