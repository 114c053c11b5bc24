//! Very deep nesting never overflows the stack: the parser keeps its stack
//! on the heap, evaluation grows its stack on demand, and syntax trees are
//! dropped without recursion. The parse tests run on the test harness's
//! ordinary threads; the others run the binary on every deeply nested
//! construct, from a file, from a piped script and in the interactive session.

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use expectrl::process::unix::WaitStatus;
use expectrl::{ControlCode, Eof, Expect, Session};
use rayrepl::lang::ast::{ExprKind, InstrKind, Item};
use rayrepl::lang::{SourceId, is_incomplete, parse_items};

use crate::common::limited::run_limited;

const DEPTH: usize = 100_000;

#[test]
fn deeply_nested_parentheses() {
    let text = format!("let x = {}1{}", "(".repeat(DEPTH), ")".repeat(DEPTH));
    let program = parse_items(SourceId(0), &text).expect("parses");
    let Item::Instr(instr) = &program.items[0] else { panic!("expected an instruction") };
    let InstrKind::Let(_, e) = &instr.kind else { panic!("expected a let") };
    assert_eq!(e.kind, ExprKind::Number(1.0));
    assert_eq!((e.span.start as usize, e.span.end as usize), (8, text.len()));
}

#[test]
fn deeply_right_nested_sums() {
    let text = format!("let x = {}1{}", "1+(".repeat(DEPTH), ")".repeat(DEPTH));
    let program = parse_items(SourceId(0), &text).expect("parses");
    assert_eq!(program.items.len(), 1);
}

#[test]
fn deeply_left_nested_sums() {
    let text = format!("let x = 1{}", "+1".repeat(DEPTH));
    assert!(parse_items(SourceId(0), &text).is_ok());
}

#[test]
fn deeply_nested_negations_and_conditions() {
    let text = format!("let x = {}1", "-".repeat(DEPTH));
    assert!(parse_items(SourceId(0), &text).is_ok());
    let text = format!("if {}a < 1 then end", "!".repeat(DEPTH));
    assert!(parse_items(SourceId(0), &text).is_ok());
    let text = format!("if {}a < 1{} then end", "(".repeat(DEPTH), ")".repeat(DEPTH));
    assert!(parse_items(SourceId(0), &text).is_ok());
}

#[test]
fn deeply_nested_objects_and_ifs() {
    let text = format!("put {}s{}", "group ".repeat(DEPTH), " end".repeat(DEPTH));
    assert!(parse_items(SourceId(0), &text).is_ok());
    let text = format!("put {}s{}", "scale ".repeat(DEPTH), " by 2 end".repeat(DEPTH));
    assert!(parse_items(SourceId(0), &text).is_ok());
    let text = format!("{}put s{}", "if a < 1 then ".repeat(DEPTH), " end".repeat(DEPTH));
    assert!(parse_items(SourceId(0), &text).is_ok());
}

#[test]
fn deep_unclosed_nesting_is_a_clear_error() {
    let text = format!("let x = {}1", "(".repeat(DEPTH));
    let error = parse_items(SourceId(0), &text).expect_err("unclosed");
    assert!(error.message.starts_with("unexpected end of file"), "{}", error.message);
    assert!(is_incomplete(&text));
    let text = format!("put {}s", "group ".repeat(DEPTH));
    let error = parse_items(SourceId(0), &text).expect_err("unclosed");
    assert_eq!(error.message, "unexpected end of file: expected `end` to close this `group`");
    let text = format!("let x = {}1{}", "(".repeat(DEPTH), ")".repeat(DEPTH + 1));
    assert!(parse_items(SourceId(0), &text).is_err());
}

/// A sphere that raises no warning.
const SPHERE: &str = "sphere center 0, 0, 0 radius 1 kd 0.5 ks 0.5 phong 10 color 255, 0, 0 end";

/// The items of each deeply nested construct, each putting one sphere: a
/// procedure whose body nests 100,000 `if`s and its call (first, so that
/// all of them together still make a file in the order SPEC 2 gives), a sum
/// of 70,000 terms, then 100,000 nested `-`, `!`, `sin(`, parentheses,
/// `if`, `else`, `group`, `translate`, `rotate` and `scale`.
fn deep_constructs() -> Vec<(&'static str, String)> {
    let put = format!("put {SPHERE}");
    let nested = |open: &str, inner: &str, close: &str| format!("{}{inner}{}", open.repeat(DEPTH), close.repeat(DEPTH));
    vec![
        ("procedure", format!("proc p() {} end\np()", nested("if 1 < 2 then ", &put, " end"))),
        ("sum", format!("let x = {}1 {put}", "1 + ".repeat(70_000))),
        ("minus", format!("let x = {}1 {put}", "-".repeat(DEPTH))),
        ("not", format!("if {} then {put} end", nested("!", "(1 < 0)", ""))),
        ("sin", format!("let x = {} {put}", nested("sin(", "1", ")"))),
        ("parentheses", format!("let x = {} {put}", nested("(", "1", ")"))),
        ("if", nested("if 1 < 2 then ", &put, " end")),
        ("else", nested(&format!("if 1 < 0 then {put} else "), &put, " end")),
        ("group", format!("object o = {} put o", nested("group ", SPHERE, " end"))),
        ("translate", format!("put {}", nested("translate ", SPHERE, " by 0, 0, 0 end"))),
        ("rotate", format!("put {}", nested("rotate ", SPHERE, " by 0, 0, 0 end"))),
        ("scale", format!("put {}", nested("scale ", SPHERE, " by 1 end"))),
    ]
}

/// A scene file whose instructions are `body`.
fn scene_file(body: &str) -> String {
    format!("camera distance 10 angle 1 end\nambient 0.2\nlight vector 1, 1, 1 intensity 1 end\n{body}\n")
}

/// Asserts that `rayrepl ARGS` (with a cap on its memory) ended well.
fn assert_success(what: &str, args: &[&str], stdin: &str) {
    let output = run_limited(args, stdin);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{what}: {}", stderr.chars().take(2000).collect::<String>());
}

#[test]
fn deep_files_render() {
    let folder = tempfile::tempdir().expect("a temporary folder");
    for (name, body) in deep_constructs() {
        let scene = folder.path().join(format!("{name}.ray"));
        std::fs::write(&scene, scene_file(&body)).expect("the scene is written");
        let image = folder.path().join(format!("{name}.png"));
        let args = [scene.to_str().unwrap(), "-o", image.to_str().unwrap(), "--width", "16", "--height", "12"];
        assert_success(name, &args, "");
        assert!(image.exists(), "{name}: no image");
    }
}

/// Writes every deep construct into one scene file, `deep.ray` in `folder`.
fn write_all_constructs(folder: &Path) -> String {
    let bodies: Vec<String> = deep_constructs().into_iter().map(|(_, body)| body).collect();
    let scene = folder.join("deep.ray");
    std::fs::write(&scene, scene_file(&bodies.join("\n"))).expect("the scene is written");
    scene.to_str().expect("a UTF-8 path").to_string()
}

#[test]
fn deep_scripts_render_load_and_undo() {
    let folder = tempfile::tempdir().expect("a temporary folder");
    let scene = write_all_constructs(folder.path());
    let image = folder.path().join("script.png");
    let mut script: Vec<String> = deep_constructs().into_iter().map(|(_, body)| body).collect();
    script.push(format!(":save {} 16 12", image.display()));
    script.extend([format!(":load {scene}"), ":undo".into(), ":reset".into(), ":undo".into(), ":env".into()]);
    assert_success("script", &[], &script.join("\n"));
    assert!(image.exists(), "no image");
}

#[test]
fn deep_sessions_load_and_undo() {
    let folder = tempfile::tempdir().expect("a temporary folder");
    let scene = write_all_constructs(folder.path());
    let mut command = Command::new(env!("CARGO_BIN_EXE_rayrepl"));
    command.arg("--no-preview").env("XDG_DATA_HOME", folder.path()).env("TERM", "xterm-256color").env("NO_COLOR", "1");
    let mut session = Session::spawn(command).expect("the binary starts");
    session.set_expect_timeout(Some(Duration::from_secs(120)));
    session.expect("ray> ").expect("a first prompt");
    session.send_line(format!(":load {scene}")).unwrap();
    session.expect("ray> ").expect("the file is loaded");
    session.send_line(":undo").unwrap();
    session.expect("took back").expect("the load is undone");
    session.expect("ray> ").expect("a prompt");
    session.send(ControlCode::EndOfTransmission).expect("Ctrl-D is sent");
    session.expect(Eof).expect("the session ends");
    let status = session.get_process().wait().expect("the exit status");
    assert!(matches!(status, WaitStatus::Exited(_, 0)), "{status:?}");
}
