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
//! `INSTA_UPDATE=always cargo test --release --test suite diagnostics::` (or
//! `cargo insta review`); on CI (`CI` set) nothing is written and any
//! difference fails.

use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

use rayrepl::session::SessionOptions;
use rayrepl::terminal::run_typed;
use serde_json::Value;
use unicode_width::UnicodeWidthChar;

use crate::common::cases::cases;

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
    let (code, _, stderr) = rayrepl_with_output(args, stdin);
    (code, stderr)
}

/// As [`rayrepl`], with standard output too: exit status, standard output
/// and standard error.
fn rayrepl_with_output(args: &[&str], stdin: &str) -> (Option<i32>, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rayrepl"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env_remove("CLICOLOR_FORCE")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    child.stdin.take().expect("a pipe").write_all(stdin.as_bytes()).expect("the input is written");
    let output = child.wait_with_output().expect("the binary ends");
    let text = |bytes: Vec<u8>| String::from_utf8(bytes).expect("the output is text");
    (output.status.code(), text(output.stdout), text(output.stderr))
}

/// Compares `stderr` with the snapshot `snapshots/{mode}/{case name}.snap`;
/// on a difference, adds the case to `failures` (insta prints the diff).
fn compare(mode: &str, path: &str, command: &str, stderr: &str, failures: &mut Vec<String>) {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path(format!("../snapshots/{mode}"));
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

/// The `--check --json` diagnostics of `args` (with `stdin`): exit status
/// and the objects, one a line.
fn json_diagnostics(args: &[&str], stdin: &str) -> (Option<i32>, Vec<Value>) {
    let mut args = args.to_vec();
    args.extend(["--check", "--json"]);
    let (code, stdout, _) = rayrepl_with_output(&args, stdin);
    let objects =
        stdout.lines().map(|line| serde_json::from_str(line).expect("each line is one JSON object")).collect();
    (code, objects)
}

/// The `source:line:column` of each rendered diagnostic's ` --> ` line.
fn rendered_places(stderr: &str) -> Vec<String> {
    let mut places = Vec::new();
    let mut in_diagnostic = false;
    for line in stderr.lines() {
        if line.starts_with("error") || line.starts_with("warning") {
            in_diagnostic = true;
        } else if let Some(place) = line.split_once("--> ").map(|(_, place)| place).filter(|_| in_diagnostic) {
            places.push(place.to_string());
            in_diagnostic = false;
        }
    }
    places
}

/// `source:line:column` of a JSON place.
fn json_place(place: &Value) -> String {
    format!("{}:{}:{}", place["source"].as_str().expect("a source"), place["line"], place["column"])
}

#[test]
fn json_places_agree_with_the_rendering_for_every_invalid_case() {
    for (path, text) in invalid_cases() {
        for (args, stdin) in [([path.as_str()], ""), (["-"], text.as_str())] {
            let (code, stderr) = rayrepl(&[&["--check"], &args[..]].concat(), stdin);
            let (json_code, objects) = json_diagnostics(&args, stdin);
            assert_eq!(json_code, code, "{path} {args:?}");
            let places: Vec<String> = objects.iter().map(|object| json_place(&object["place"])).collect();
            assert_eq!(places, rendered_places(&stderr), "{path} {args:?}");
            // Every diagnostic has a code of its own, not the constructors' default.
            assert!(
                objects
                    .iter()
                    .all(|object| !["error", "warning"].contains(&object["code"].as_str().unwrap_or("error"))),
                "{path}"
            );
            let last = objects.last().expect("an invalid case has an error");
            assert_eq!(last["severity"], "error", "{path}");
            assert!(stderr.contains(&format!("error: {}", last["message"].as_str().expect("a message"))), "{path}");
        }
    }
}

/// For `text` checked from standard input, its first diagnostic's code,
/// (line, column, UTF-16 column), and the character that the caret of the
/// rendering sits under.
fn first_place(text: &str) -> (String, (u64, u64, u64), char) {
    let (_, stderr) = rayrepl(&["--check", "-"], text);
    let (_, objects) = json_diagnostics(&["-"], text);
    let first = &objects[0];
    let place = &first["place"];
    let at = |field: &str| place[field].as_u64().expect("a number");
    assert_eq!(Some(json_place(place)), rendered_places(&stderr).first().cloned(), "{stderr}");
    // The source line `N | text` and, below it, the marks `  | ^`.
    let lines: Vec<&str> = stderr.lines().collect();
    let caret_line = lines.iter().position(|line| line.contains('^')).expect("a caret");
    let (margin, marks) = lines[caret_line].split_once('|').expect("a gutter");
    let source_line = &lines[caret_line - 1][margin.len() + 1..];
    let caret_width: usize = marks[..marks.find('^').expect("a caret")].chars().map(|c| c.width().unwrap_or(0)).sum();
    let mut width = 0;
    let under = source_line
        .chars()
        .find(|c| {
            width += c.width().unwrap_or(0);
            width > caret_width
        })
        .expect("the caret is under a character");
    let code = first["code"].as_str().expect("a code").to_string();
    (code, (at("line"), at("column"), at("column_utf16")), under)
}

#[test]
fn json_lines_and_columns_are_those_of_the_caret() {
    // 31 + 12 bytes; with CRLF, 32 + 13.
    let start = "camera distance 10 angle 1 end\nambient 0.2\n";
    let crlf = "camera distance 10 angle 1 end\r\nambient 0.2\r\n";
    let cases = [
        // Lexer: `$` is the 5th character of line 3.
        (format!("{start}let $ = 1\n"), ("unexpected-character", (3, 5, 5), '$')),
        // Parser: a second `put` where `end` was wanted.
        (format!("{start}put sphere center 0, 0, 0 radius 1\nput"), ("unexpected-token", (4, 1, 1), 'p')),
        // After a line of multibyte characters, at one: `🎨` is 4 bytes, 2 UTF-16 units, 2 columns wide.
        (format!("{start}# é 🎨\nlet x = 🎨\n"), ("unexpected-character", (4, 9, 9), '🎨')),
        // A French word with an accent: the caret is under `è`.
        (format!("{start}put sphère center 0, 0, 0 radius 1 end\n"), ("unexpected-character", (3, 8, 8), 'è')),
        // A warning: `kd 2`, clamped to 1.
        (
            format!("{start}put sphere center 0, 0, -1 radius 1 kd 2 ks 0 phong 1 color 255, 0, 0 end\n"),
            ("clamped-coefficient", (3, 40, 40), '2'),
        ),
        // A warning of the scene checks: the `0` of `ambient 0`, with no light.
        (
            "camera distance 10 angle 1 end\nambient 0\nput sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end\n"
                .to_string(),
            ("no-light", (2, 9, 9), '0'),
        ),
        // CRLF line ends.
        (
            format!("{crlf}put sphere center 0, 0, 0 radius x kd 1 ks 0 phong 1 color 255, 0, 0 end\r\n"),
            ("unknown-variable", (3, 34, 34), 'x'),
        ),
        // A tab is one column, and the caret follows its width on screen.
        (format!("{start}\tlet $ = 1\n"), ("unexpected-character", (3, 6, 6), '$')),
    ];
    for (text, (code, position, under)) in cases {
        assert_eq!(first_place(&text), (code.to_string(), position, under), "{text:?}");
    }
}

#[test]
fn json_ends_bytes_and_replacements_count_multibyte_characters() {
    let start = "camera distance 10 angle 1 end\nambient 0.2\n";
    // Line 3 is 10 bytes: line 4 starts at byte 53, and `🎨` is bytes 61..65.
    let (_, objects) = json_diagnostics(&["-"], &format!("{start}# é 🎨\nlet x = 🎨\n"));
    let place = &objects[0]["place"];
    assert_eq!((&place["end_column"], &place["end_column_utf16"]), (&Value::from(10), &Value::from(11)));
    assert_eq!(place["bytes"], serde_json::json!([61, 65]));
    // `sphère` is bytes 47..54 (`è` is two); its `è`, 50..52, is the error.
    let (code, objects) = json_diagnostics(&["-"], &format!("{start}put sphère center 0, 0, 0 radius 1 end\n"));
    assert_eq!(code, Some(1));
    assert_eq!(objects[0]["place"]["bytes"], serde_json::json!([50, 52]));
    let replacement = &objects[0]["help"][0]["replacements"][0];
    assert_eq!(replacement["text"], "sphere");
    assert_eq!(replacement["place"]["bytes"], serde_json::json!([47, 54]));
    assert_eq!(
        (&replacement["place"]["column"], &replacement["place"]["end_column"]),
        (&Value::from(5), &Value::from(11))
    );
    // CRLF: `x` is byte 45 + 33.
    let crlf = "camera distance 10 angle 1 end\r\nambient 0.2\r\nput sphere center 0, 0, 0 radius x kd 1 ks 0 phong 1 color 255, 0, 0 end\r\n";
    let (_, objects) = json_diagnostics(&["-"], crlf);
    assert_eq!(objects[0]["place"]["bytes"], serde_json::json!([78, 79]));
}

#[test]
fn json_replacements_for_a_misspelt_keyword_and_a_decimal_comma() {
    let start = "camera distance 10 angle 1 end\nambient 0,5\n";
    let (_, objects) = json_diagnostics(&["-"], start);
    let replacement = &objects[0]["help"][0]["replacements"][0];
    assert_eq!(
        (&replacement["text"], &replacement["place"]["bytes"]),
        (&Value::from("0.5"), &serde_json::json!([39, 42]))
    );
    let text = "camera distance 10 angle 1 end\nambient 0.2\nput spehre center 0, 0, 0 radius 1 end\n";
    let (_, objects) = json_diagnostics(&["-"], text);
    let replacement = &objects[0]["help"][0]["replacements"][0];
    assert_eq!(objects[0]["help"][0]["message"], "did you mean `sphere`?");
    assert_eq!(
        (&replacement["text"], &replacement["place"]["bytes"]),
        (&Value::from("sphere"), &serde_json::json!([47, 53]))
    );
}

#[test]
fn json_is_only_for_check_and_explain() {
    let (code, stdout, stderr) = rayrepl_with_output(&["--json", "tests/cases/invalid/lex_dollar.ray"], "");
    assert_eq!((code, stdout.as_str()), (Some(2), ""));
    assert_eq!(stderr, "rayrepl: --json is for --check (the diagnostics) and --explain X,Y (the explanation)\n");
}
