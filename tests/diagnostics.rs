//! Snapshots of the whole standard error for every invalid case of
//! `tests/cases/invalid`, in the three ways a learner meets it:
//!
//! - `file`: `rayrepl --check FILE`;
//! - `script`: the file's text piped into `rayrepl`;
//! - `typed`: the file's lines typed one by one into the session, through
//!   [`run_typed`], the terminal session's own entry loop fed from a list
//!   instead of the line editor (a pseudo-terminal would add prompts, echo
//!   and the editor's escape codes to what is compared, and time).
//!
//! The snapshots are in `tests/snapshots/{file,script,typed}/`. After a
//! change of a message, review the differences and accept them with
//! `INSTA_UPDATE=always cargo test --release --test diagnostics` (or
//! `cargo insta review`); on CI (`CI` set) nothing is written and any
//! difference fails.

use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

use rayrepl::repl::{SessionOptions, run_typed};

mod common;

use common::cases::cases;

/// The invalid cases: their path relative to the crate, as shown in
/// diagnostics, and their text.
fn invalid_cases() -> Vec<(String, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    cases("invalid")
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("case is readable");
            let relative = path.strip_prefix(root).expect("cases are in the crate").display().to_string();
            (relative, text)
        })
        .collect()
}

/// The case's name: its file name without `.ray`.
fn name(path: &str) -> &str {
    Path::new(path).file_stem().and_then(|stem| stem.to_str()).expect("a case has a file name")
}

/// `rayrepl ARGS` in the crate's folder, with `stdin` as its input: exit
/// status and standard error. Colours are off whatever the environment says
/// (standard error is a pipe).
fn rayrepl(args: &[&str], stdin: &str) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rayrepl"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env_remove("CLICOLOR_FORCE")
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    child.stdin.take().expect("a pipe").write_all(stdin.as_bytes()).expect("the input is written");
    let output = child.wait_with_output().expect("the binary ends");
    (output.status.code(), String::from_utf8(output.stderr).expect("standard error is text"))
}

/// Compares `stderr` with the snapshot `snapshots/{mode}/{case name}.snap`;
/// on a difference, adds the case to `failures` (insta prints the diff).
fn compare(mode: &str, path: &str, command: &str, stderr: &str, failures: &mut Vec<String>) {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path(format!("snapshots/{mode}"));
    settings.set_prepend_module_to_snapshot(false);
    settings.set_omit_expression(true);
    settings.set_input_file(path);
    settings.set_description(command);
    let assert = || settings.bind(|| insta::assert_snapshot!(name(path), stderr));
    let matched = std::panic::catch_unwind(std::panic::AssertUnwindSafe(assert));
    if matched.is_err() {
        failures.push(format!("{mode}/{}", name(path)));
    }
}

/// Fails with the cases whose standard error differs from its snapshot.
fn report(failures: &[String]) {
    assert!(failures.is_empty(), "{} snapshot(s) differ: {}", failures.len(), failures.join(", "));
}

#[test]
fn checking_a_file() {
    let mut failures = Vec::new();
    for (path, _) in invalid_cases() {
        let (code, stderr) = rayrepl(&["--check", &path], "");
        assert_eq!(code, Some(1), "{path}:\n{stderr}");
        compare("file", &path, &format!("rayrepl --check {path}"), &stderr, &mut failures);
    }
    report(&failures);
}

#[test]
fn piping_a_script() {
    let mut failures = Vec::new();
    for (path, text) in invalid_cases() {
        let (code, stderr) = rayrepl(&[], &text);
        // A session takes items in any order: a file's order errors are no
        // errors there, and such a script succeeds.
        let failed = stderr.lines().any(|line| line.starts_with("error"));
        assert_eq!(code, Some(i32::from(failed)), "{path}:\n{stderr}");
        compare("script", &path, &format!("rayrepl < {path}"), &stderr, &mut failures);
    }
    report(&failures);
}

#[test]
fn typing_into_the_session() {
    // As on a terminal that does not want colours, whatever the environment says.
    anstream::ColorChoice::Never.write_global();
    let mut failures = Vec::new();
    let options = SessionOptions { no_preview: true, ..SessionOptions::default() };
    for (path, text) in invalid_cases() {
        let (mut out, mut err) = (Vec::new(), Vec::new());
        run_typed(text.lines().map(String::from), &mut out, &mut err, &options);
        let stderr = String::from_utf8(err).expect("standard error is text");
        compare("typed", &path, &format!("{path} typed line by line into the session"), &stderr, &mut failures);
    }
    report(&failures);
}
