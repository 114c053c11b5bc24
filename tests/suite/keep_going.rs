//! A piped script with `--keep-going` goes on after a broken entry: the
//! entry ends at the line after which no line can mend it, as in the
//! interactive session, and the lines after it run (issue 33, point 7).

use assert_cmd::Command;
use rayrepl::session::SessionOptions;
use rayrepl::terminal::run_script;
use rayrepl::terminal::run_typed;

/// A sphere left without its `end`.
const UNCLOSED: &str = "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0";

/// A whole sphere.
const SPHERE: &str = "put sphere center 3, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end";

/// What a script run printed, and its exit status.
struct Run {
    code: i32,
    out: String,
    err: String,
}

/// Runs `script` as a piped script, with `--keep-going` if `keep_going`.
fn script(script: &str, keep_going: bool) -> Run {
    let options = SessionOptions { keep_going, ..SessionOptions::default() };
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let code = run_script(script.as_bytes(), &mut out, &mut err, &options);
    Run {
        code,
        out: String::from_utf8(out).expect("output is text"),
        err: String::from_utf8(err).expect("errors are text"),
    }
}

/// What the interactive session writes (messages, diagnostics) when
/// `script`'s lines are typed one by one.
fn typed(script: &str) -> (String, String) {
    let options = SessionOptions { no_preview: true, ..SessionOptions::default() };
    let (mut out, mut err) = (Vec::new(), Vec::new());
    run_typed(script.lines().map(String::from), &mut out, &mut err, &options);
    (String::from_utf8(out).expect("text"), String::from_utf8(err).expect("text"))
}

/// The number of errors in `err`.
fn errors(err: &str) -> usize {
    err.matches("error: ").count()
}

#[test]
fn the_script_of_the_issue_prints_7_and_8() {
    let script = format!("{UNCLOSED}\n{SPHERE}\nprint 7\nprint 8\n");
    let output = Command::new(env!("CARGO_BIN_EXE_rayrepl"))
        .arg("--keep-going")
        .write_stdin(script)
        .output()
        .expect("the binary runs");
    let err = String::from_utf8(output.stderr).expect("text");
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(err.contains("<stdin>:3: 7\n<stdin>:4: 8\n"), "{err}");
    assert_eq!(errors(&err), 1, "{err}");
}

#[test]
fn the_line_that_breaks_an_entry_is_shown_with_its_error_and_starts_the_next() {
    let run = script(&format!("{UNCLOSED}\n{SPHERE}\nprint 7\n"), true);
    let expected = "\
error: expected `end` to close this `sphere`
 --> <stdin>:2:1
  |
1 | put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0
  |     ------ this `sphere` is not closed
2 | put sphere center 3, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end
  | ^^^ unexpected `put`
";
    assert!(run.err.starts_with(expected), "{}", run.err);
    // The second sphere is put: one object in the scene.
    assert_eq!(run.out, "put 1 sphere (1 object in the scene)\n");
    assert!(run.err.contains("<stdin>:3: 7\n"), "{}", run.err);
}

#[test]
fn the_session_cuts_the_entry_where_the_script_does() {
    let lines = format!("{UNCLOSED}\n{SPHERE}\nprint 7\n");
    let run = script(&lines, true);
    let (out, err) = typed(&lines);
    assert!(out.starts_with("put 1 sphere (1 object in the scene)\n"), "{out}");
    // The second sphere is put in both (the session then warns that its
    // inputs are not written to a file).
    assert!(out.starts_with(&run.out), "{out}");
    assert!(err.contains("unexpected `put`"), "{err}");
    assert!(err.contains("<input 3>:1: 7\n"), "{err}");
    assert_eq!(errors(&err), 1, "{err}");
}

#[test]
fn an_unclosed_proc_ends_at_an_item_a_proc_cannot_hold() {
    let run = script(&format!("proc p()\n  {SPHERE}\nproc q()\n  print 7\nend\nq()\nprint 8\n{SPHERE}\n"), true);
    assert_eq!(run.code, 1);
    assert!(run.err.contains(" --> <stdin>:3:1\n"), "{}", run.err);
    assert!(run.err.contains("this `proc p` is not closed"), "{}", run.err);
    assert!(run.err.contains("<stdin>:4: 7\n<stdin>:7: 8\n"), "{}", run.err);
    assert!(run.out.starts_with("defined proc q()\n"), "{}", run.out);
    assert_eq!(errors(&run.err), 1, "{}", run.err);
}

#[test]
fn an_unclosed_if_ends_at_an_item_an_if_cannot_hold() {
    let run =
        script(&format!("if 1 < 2 then\n  {SPHERE}\nlight vector 0, 0, 0 intensity 1 end\nprint 7\nprint 8\n"), true);
    assert!(run.err.contains(" --> <stdin>:3:1\n"), "{}", run.err);
    assert!(run.err.contains("this `if` is not closed"), "{}", run.err);
    assert!(run.out.contains("1 light added"), "{}", run.out);
    assert!(run.err.contains("<stdin>:4: 7\n<stdin>:5: 8\n"), "{}", run.err);
    assert_eq!(errors(&run.err), 1, "{}", run.err);
}

#[test]
fn an_end_that_closes_nothing_open_ends_the_entry() {
    // The `end` comes while a parenthesis is open: it cannot close it.
    let run = script("put sphere center 0, 0, 0 radius (1\nend\nprint 7\nprint 8\n", true);
    assert!(run.err.contains(" --> <stdin>:2:1\n"), "{}", run.err);
    assert!(run.err.contains("<stdin>:3: 7\n<stdin>:4: 8\n"), "{}", run.err);
    assert_eq!(errors(&run.err), 1, "{}", run.err);
}

#[test]
fn a_broken_line_in_a_put_of_several_lines_ends_it_and_the_rest_runs() {
    let script_text = "\
put sphere center 0, 0, 0
  radius (1 + 2
  kd 1 ks 0 phong 1 color 255, 0, 0
end
print 7
print 8
";
    let run = script(script_text, true);
    // The missing `)` is certain at line 3; the put's `end` then closes
    // nothing, and the script goes on.
    assert!(run.err.contains(" --> <stdin>:3:3\n"), "{}", run.err);
    assert!(run.err.contains(" --> <stdin>:4:1\n"), "{}", run.err);
    assert!(run.err.contains("<stdin>:5: 7\n<stdin>:6: 8\n"), "{}", run.err);
    assert_eq!(errors(&run.err), 2, "{}", run.err);
}

#[test]
fn without_keep_going_the_first_broken_entry_stops_the_script() {
    // The same as before the entries were cut: the error, then nothing.
    let run = script(&format!("{UNCLOSED}\n{SPHERE}\nprint 7\n"), false);
    assert_eq!(run.code, 1);
    assert_eq!(run.out, "");
    assert!(run.err.contains("unexpected `put`"), "{}", run.err);
    assert!(!run.err.contains("7"), "{}", run.err);
    assert_eq!(errors(&run.err), 1, "{}", run.err);
}
