//! Hostile programs and streams stay within memory (issue 35, points 9 and
//! 11): nesting deeper than the limit is an error at its construct before
//! memory grows, a recursion deeper than the memory allows is an error with
//! its chain of calls (never a panic), an endless script stops at the
//! session's limit on inputs, and long names are shortened in messages.
//! Each runs the binary under a cap on its memory.

use std::io::Write;

use rayrepl::lang::MAX_NESTING;

use crate::common::limited::{run_limited, run_limited_to};

/// A sphere that raises no warning.
const SPHERE: &str = "sphere center 0, 0, 0 radius 1 kd 0.5 ks 0.5 phong 10 color 255, 0, 0 end";

/// The first lines of a scene file.
const HEADER: &str = "camera distance 10 angle 1 end\nambient 0.2\nlight vector 1, 1, 1 intensity 1 end\n";

/// A temporary scene file holding `text`.
fn scene_file(text: &str) -> tempfile::NamedTempFile {
    let mut file = tempfile::Builder::new().suffix(".ray").tempfile().expect("a temporary file");
    file.write_all(text.as_bytes()).expect("scene written");
    file
}

/// The status and standard error of `rayrepl ARGS` run under the usual cap.
fn run(args: &[&str], stdin: &str) -> (Option<i32>, String) {
    let output = run_limited(args, stdin);
    (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned())
}

/// The start of `text`, for an assertion's message.
fn start(text: &str) -> String {
    text.chars().take(3000).collect()
}

/// Asserts that `stderr` is the nesting error, pointing at line `line` and
/// column `column` of `name`, with the construct `construct` marked.
fn assert_nesting_error(stderr: &str, name: &str, line: usize, column: usize, construct: &str) {
    let message = format!("error: nesting deeper than {MAX_NESTING} levels");
    assert!(stderr.starts_with(&message), "{}", start(stderr));
    assert!(stderr.contains(&format!("{name}:{line}:{column}\n")), "{}", start(stderr));
    let caret = format!("{} this `{construct}` is one level too deep", "^".repeat(construct.len()));
    assert!(stderr.contains(&caret), "{}", start(stderr));
    assert!(!stderr.contains("internal error") && !stderr.contains("panicked"), "{}", start(stderr));
}

#[test]
fn a_million_nested_groups_are_an_error_at_the_group_too_deep() {
    let levels = 1_000_000;
    let file = scene_file(&format!("{HEADER}put {}{SPHERE}{}\n", "group ".repeat(levels), " end".repeat(levels)));
    let path = file.path().to_str().expect("a UTF-8 path");
    let (status, stderr) = run(&["--check", path], "");
    assert_eq!(status, Some(1), "{}", start(&stderr));
    assert_nesting_error(&stderr, path, 4, 5 + 6 * MAX_NESTING, "group");
}

#[test]
fn nested_ifs_parentheses_and_negations_past_the_limit_are_errors_not_panics() {
    let past = MAX_NESTING + 10;
    let put = format!("put {SPHERE}");
    let cases = [
        ("if", format!("{}{put}{}", "if 1 < 2 then ".repeat(past), " end".repeat(past)), 1 + 14 * MAX_NESTING),
        ("(", format!("let x = {}1{} {put}", "(".repeat(past), ")".repeat(past)), 9 + MAX_NESTING),
        ("-", format!("let x = {}1 {put}", "-".repeat(past),), 9 + MAX_NESTING),
        ("!", format!("if {}(1 < 0) then {put} end", "!".repeat(past)), 3 + MAX_NESTING),
    ];
    for (construct, body, column) in cases {
        let file = scene_file(&format!("{HEADER}{body}\n"));
        let path = file.path().to_str().expect("a UTF-8 path");
        let (status, stderr) = run(&["--check", path], "");
        assert_eq!(status, Some(1), "{construct}: {}", start(&stderr));
        assert_nesting_error(&stderr, path, 4, column, construct);
    }
}

#[test]
fn nesting_at_the_limit_still_runs() {
    let file = scene_file(&format!(
        "{HEADER}put {}{SPHERE}{}\n",
        "group ".repeat(MAX_NESTING - 1),
        " end".repeat(MAX_NESTING - 1)
    ));
    let (status, stderr) = run(&["--check", file.path().to_str().expect("a UTF-8 path")], "");
    assert_eq!(status, Some(0), "{}", start(&stderr));
}

#[test]
fn a_piped_script_nested_over_many_lines_is_stopped_at_the_line_too_deep() {
    // One `group` a line: the script reads the entry line by line, and the
    // count goes on from one line to the next.
    let script = format!("put\n{}{SPHERE}\n{}", "group\n".repeat(MAX_NESTING + 5), "end\n".repeat(MAX_NESTING + 5));
    let (status, stderr) = run(&[], &script);
    assert_eq!(status, Some(1), "{}", start(&stderr));
    assert_nesting_error(&stderr, "<stdin>", MAX_NESTING + 2, 1, "group");
}

#[test]
fn a_recursion_deeper_than_the_memory_allows_is_an_error_with_its_chain_of_calls() {
    let program = "proc f(n)\n  f(n + 1)\nend\nf(1)\n";
    let file = scene_file(&format!("{HEADER}{program}"));
    let path = file.path().to_str().expect("a UTF-8 path");
    // Under 1 GiB the stack fills after a few hundred thousand calls.
    let output = run_limited_to(1 << 20, &["--check", "--max-calls", "1000000000", path], "");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{}", start(&stderr));
    assert!(stderr.starts_with("error: recursion too deep for the memory"), "{}", start(&stderr));
    assert!(
        stderr.contains("= note: call chain: f (line 7) -> f (line 5) -> ... `f (line 5)` repeated "),
        "{}",
        start(&stderr)
    );
    assert!(!stderr.contains("internal error") && !stderr.contains("panicked"), "{}", start(&stderr));
}

#[test]
fn an_endless_script_stops_at_the_limit_on_inputs_even_going_on_after_errors() {
    use rayrepl::session::MOST_INPUTS;
    let script = "let a = 1\n".repeat(MOST_INPUTS + 3);
    for args in [&[][..], &["--keep-going"][..]] {
        // The inputs the session keeps at the limit fit well under 1 GiB.
        let output = run_limited_to(1 << 20, args, &script);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {}", start(&stderr));
        let message = format!("error: the session already holds {MOST_INPUTS} inputs, the most it may\n");
        assert!(stderr.starts_with(&message), "{args:?}: {}", start(&stderr));
        let place = format!(" --> <stdin>:{}:1\n", MOST_INPUTS + 1);
        assert!(stderr.contains(&place), "{args:?}: {}", start(&stderr));
        assert_eq!(stderr.matches("error:").count(), 1, "{args:?}: {}", start(&stderr));
    }
}

#[test]
fn a_megabyte_long_name_is_shortened_in_every_message() {
    let name = "a".repeat(1 << 20);
    let shown = format!("`{}…` ({} characters)", "a".repeat(40), 1 << 20);
    let near = format!("{}b", &name[1..]);
    let long_bare = format!("{}… ({} characters)", "a".repeat(40), (1 << 20) + 1);
    let long_shown = format!("`{}…` ({} characters)", "a".repeat(40), (1 << 20) + 1);
    let script = [
        format!("let {name} = 1"),
        format!("put {name}"),
        format!("{name}(1)"),
        format!("let y = {near}"),
        format!("proc {name}x(r) {name}x(r) end"),
        format!("{name}x(1, 2)"),
        format!("{name}x(1)"),
    ]
    .join("\n");
    let output = run_limited(&["--keep-going", "--max-calls", "10"], &script);
    let (stdout, stderr) = (String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    assert_eq!(output.status.code(), Some(1), "{}", start(&stderr));
    for message in [
        format!("error: {shown} is a number, but an object is needed here"),
        format!("error: unknown procedure {shown}"),
        format!("note: {shown} is a number, not a procedure"),
        format!("error: unknown variable {shown}"),
        format!("error: {long_shown} takes 1 argument (r) but was given 2"),
        "error: recursion deeper than 10 calls".to_string(),
        format!("in this call of {long_shown}"),
        format!(
            "call chain: {long_bare} (line 7) -> {long_bare} (line 5) -> ... `{long_bare} (line 5)` repeated 9 more times"
        ),
    ] {
        assert!(stderr.contains(&message), "{message}\n{}", start(&stderr));
    }
    assert!(stdout.starts_with(&format!("{}… ({} characters) = 1\n", "a".repeat(40), 1 << 20)), "{}", start(&stdout));
    // The source lines are shown cut too: nothing near the name's length is written.
    assert!(stderr.len() + stdout.len() < 20_000, "{} bytes", stderr.len() + stdout.len());
}

#[test]
fn an_input_that_never_ends_stops_the_script_before_it_fills_the_memory() {
    // Every line leaves the input unfinished: it would grow forever. (A
    // line `let a = 1 +` again would break it: `+ let` cannot go on.)
    let script = format!("let a = 1 +\n{}", "1 +\n".repeat((64 << 20) / 4 + 10));
    let (status, stderr) = run(&[], &script);
    assert_eq!(status, Some(1), "{}", start(&stderr));
    let message = "error: the input starting at line 1 of the script is longer than 64 MiB, the most an input may be";
    assert!(stderr.starts_with(message), "{}", start(&stderr));
}

/// `n` with a comma between each group of three digits, as the docs write it.
fn with_commas(n: usize) -> String {
    let digits = n.to_string();
    let mut written = String::new();
    for (index, digit) in digits.chars().enumerate() {
        if index > 0 && (digits.len() - index).is_multiple_of(3) {
            written.push(',');
        }
        written.push(digit);
    }
    written
}

#[test]
fn the_limits_are_documented_beside_the_others() {
    use rayrepl::session::MOST_INPUTS;
    let language = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/language.md")).expect("the docs");
    let limits = language.split_once("## 10. Limits").expect("section 10").1.split_once("\n## ").expect("its end").0;
    assert!(limits.contains(&format!("- **Nesting**: at most {} levels", with_commas(MAX_NESTING))));
    assert!(limits.contains(&format!("- **Inputs of a session**: at most {}", with_commas(MOST_INPUTS))));
    assert!(limits.contains("- **Stack**:"));
    let help = include_str!("../../src/ide/help_pages/commands/limits.txt");
    assert!(help.contains(&format!("nested at most {MAX_NESTING} levels")), "{help}");
    assert!(help.contains(&format!("at most {MOST_INPUTS}\n  inputs")), "{help}");
}
