//! `rayrepl fmt` and the formatter under it: on every `.ray` file of the
//! repository and every `ray` block of the lessons and docs, formatting
//! twice gives what formatting once gives, the tokens stay the same, every
//! comment stays, and the scene at time 0 does not change; mutated
//! programs never make it panic; the command rewrites files in place
//! (only those that change), checks them, formats standard input, and
//! reports a file that does not parse as everywhere else.

use std::path::{Path, PathBuf};

use assert_cmd::Command;
use predicates::prelude::*;
use predicates::str::contains;
use proptest::prelude::*;
use rayrepl::lang::format::format;
use rayrepl::lang::lexer::tokenize;
use rayrepl::lang::token::Token;
use rayrepl::lang::{Interpreter, Limits, SourceId, parse_items};

use crate::fuzz::vocabulary;

/// The folders of the repository that hold `.ray` files.
const RAY_FOLDERS: &[&str] =
    &["scenarios", "tests/cases/valid", "tests/cases/invalid", "tests/cases/warnings", BENCHMARK_SCENES];

/// The files, besides the `.ray` files, whose ```` ```ray ```` blocks are programs.
const MARKDOWN_FOLDERS: &[&str] = &["lessons", "docs"];

fn repository() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The files of `folder` (relative to the repository) whose name ends with `extension`, sorted.
fn files_in(folder: &str, extension: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(repository().join(folder))
        .expect("a folder of the repository")
        .map(|entry| entry.expect("a readable folder").path())
        .filter(|path| path.extension().is_some_and(|found| found == extension))
        .collect();
    files.sort();
    files
}

/// Every `.ray` text of the repository, and the `ray` blocks of its
/// lessons and docs, each with a name for the messages.
fn every_program_text() -> Vec<(String, String)> {
    let mut texts = Vec::new();
    for folder in RAY_FOLDERS {
        for path in files_in(folder, "ray") {
            let text = std::fs::read_to_string(&path).expect("a readable scene");
            texts.push((path.display().to_string(), text));
        }
    }
    for folder in MARKDOWN_FOLDERS {
        for path in files_in(folder, "md") {
            let markdown = std::fs::read_to_string(&path).expect("a readable page");
            for (number, block) in ray_blocks(&markdown).into_iter().enumerate() {
                texts.push((format!("{} block {}", path.display(), number + 1), block));
            }
        }
    }
    texts
}

/// The ```` ```ray ```` blocks of `markdown`.
fn ray_blocks(markdown: &str) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut open: Option<String> = None;
    for line in markdown.lines() {
        match open.as_mut() {
            None if line.starts_with("```ray") => open = Some(String::new()),
            None => {}
            Some(block) if line.starts_with("```") => {
                blocks.push(std::mem::take(block));
                open = None;
            }
            Some(block) => {
                block.push_str(line);
                block.push('\n');
            }
        }
    }
    blocks
}

/// The tokens of `text`, without their places.
fn tokens(text: &str) -> Vec<Token> {
    tokenize(SourceId(0), text).expect("tokens").into_iter().map(|(_, token, _)| token).collect()
}

/// The comments of `text`, in order, without the blanks that end them: in
/// what lies between its tokens, from each `#` to the end of its line.
fn comments(text: &str) -> Vec<String> {
    let spans = tokenize(SourceId(0), text).expect("tokens");
    let mut gaps = Vec::new();
    let mut after = 0;
    for (start, _, end) in spans {
        gaps.push(&text[after..start]);
        after = end;
    }
    gaps.push(&text[after..]);
    let mut found = Vec::new();
    for gap in gaps {
        let mut rest = gap;
        while let Some(hash) = rest.find('#') {
            let comment = &rest[hash..];
            let line_end = comment.find('\n').unwrap_or(comment.len());
            found.push(comment[..line_end].trim_end().to_string());
            rest = &comment[line_end..];
        }
    }
    found
}

/// What `text` builds at time 0: the camera, the ambient light, the lights
/// and the primitives, or the message of the error that stops it.
fn scene_at_time_zero(text: &str) -> Result<String, String> {
    let program = parse_items(SourceId(0), text).map_err(|diagnostic| diagnostic.message)?;
    let mut interpreter = Interpreter::new(0.0, Limits::default());
    interpreter.run(&program).map_err(|diagnostic| diagnostic.message)?;
    let scene = interpreter.scene();
    Ok(format!(
        "{:?} {:?} {:?} {:?} {:?}",
        scene.camera, scene.ambient, scene.lights, scene.primitives, scene.timed_primitives
    ))
}

#[test]
fn the_corpus_is_found() {
    let texts = every_program_text();
    assert!(texts.iter().filter(|(name, _)| name.ends_with(".ray")).count() > 150, "{}", texts.len());
    assert!(texts.iter().filter(|(name, _)| name.contains(" block ")).count() > 30, "{}", texts.len());
}

#[test]
fn formatting_every_program_twice_changes_nothing_more() {
    for (name, text) in every_program_text() {
        if let Ok(once) = format(SourceId(0), &text) {
            let twice = format(SourceId(0), &once).unwrap_or_else(|error| panic!("{name}: {}", error.message));
            assert_eq!(twice, once, "{name}");
        }
    }
}

#[test]
fn formatting_keeps_every_token_and_every_comment() {
    for (name, text) in every_program_text() {
        if let Ok(formatted) = format(SourceId(0), &text) {
            assert_eq!(tokens(&formatted), tokens(&text), "{name}");
            assert_eq!(comments(&formatted), comments(&text), "{name}");
        }
    }
}

/// The folder of [`RAY_FOLDERS`] whose scenes are too large to evaluate
/// twice in a test (millions of boxes): the same tokens show that their
/// scenes do not change either.
const BENCHMARK_SCENES: &str = "benches/scenes";

#[test]
fn formatting_never_changes_the_scene() {
    let benchmarks = repository().join(BENCHMARK_SCENES).display().to_string();
    let mut scenes = 0;
    for (name, text) in every_program_text().into_iter().filter(|(name, _)| !name.starts_with(&benchmarks)) {
        if let Ok(formatted) = format(SourceId(0), &text) {
            let scene = scene_at_time_zero(&text);
            scenes += usize::from(scene.is_ok());
            assert_eq!(scene_at_time_zero(&formatted), scene, "{name}");
        }
    }
    assert!(scenes > 100, "only {scenes} texts ran");
}

#[test]
fn a_text_that_does_not_parse_gets_the_parsers_diagnostic() {
    for path in files_in("tests/cases/invalid", "ray") {
        let text = std::fs::read_to_string(&path).expect("a readable scene");
        if let Err(parse_error) = parse_items(SourceId(0), &text) {
            let format_error = format(SourceId(0), &text).expect_err("not a program");
            assert_eq!(format_error.message, parse_error.message, "{}", path.display());
            assert_eq!(format_error.span, parse_error.span, "{}", path.display());
        }
    }
}

#[test]
fn the_scenarios_are_in_the_house_style() {
    let changed: Vec<String> = files_in("scenarios", "ray")
        .into_iter()
        .filter(|path| {
            let text = std::fs::read_to_string(path).expect("a readable scene");
            format(SourceId(0), &text).expect("a scenario parses") != text
        })
        .map(|path| path.file_name().expect("a file").to_string_lossy().into_owned())
        .collect();
    assert_eq!(changed, Vec::<String>::new());
}

/// Programs of the repository with some of their blanks, line ends and
/// tokens changed, deleted or added.
fn mutated_program() -> impl Strategy<Value = String> {
    let scenarios: Vec<String> = files_in("scenarios", "ray")
        .iter()
        .map(|path| std::fs::read_to_string(path).expect("a readable scene"))
        .collect();
    let insertions: Vec<&'static str> =
        vocabulary().into_iter().chain([" ", "  ", "\t", "\r\n", "\n\n", "#"]).collect();
    (
        prop::sample::select(scenarios),
        prop::collection::vec((any::<prop::sample::Index>(), 0..3u8, prop::sample::select(insertions)), 1..8),
    )
        .prop_map(|(mut text, edits)| {
            for (at, kind, insertion) in edits {
                let mut place = at.index(text.len() + 1);
                while !text.is_char_boundary(place) {
                    place -= 1;
                }
                let end = text[place..].char_indices().nth(3).map_or(text.len(), |(offset, _)| place + offset);
                match kind {
                    0 => text.insert_str(place, insertion),
                    1 => text.replace_range(place..end, ""),
                    _ => text.replace_range(place..end, insertion),
                }
            }
            text
        })
}

/// The tokens of a scenario joined again by random blanks, line ends
/// and comments: always a program, with lines cut anywhere.
fn scenario_cut_anywhere() -> impl Strategy<Value = String> {
    let scenarios: Vec<String> = files_in("scenarios", "ray")
        .iter()
        .map(|path| std::fs::read_to_string(path).expect("a readable scene"))
        .collect();
    let separators = vec![" ", "  ", "\t", "\n", "\n\n\n", "\r\n  ", " # a comment\n", "\n    # a comment line\n"];
    (prop::sample::select(scenarios), prop::collection::vec(prop::sample::select(separators), 64)).prop_map(
        |(text, separators)| {
            let spans = tokenize(SourceId(0), &text).expect("tokens");
            let mut joined = String::new();
            for (number, (start, _, end)) in spans.into_iter().enumerate() {
                joined.push_str(&text[start..end]);
                joined.push_str(separators[number % separators.len()]);
            }
            joined
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn mutated_programs_never_make_it_panic_and_format_stably(text in mutated_program()) {
        if let Ok(once) = format(SourceId(0), &text) {
            prop_assert_eq!(format(SourceId(0), &once).ok(), Some(once.clone()));
            prop_assert_eq!(tokens(&once), tokens(&text));
            prop_assert_eq!(comments(&once), comments(&text));
        }
    }

    #[test]
    fn programs_cut_anywhere_format_stably(text in scenario_cut_anywhere()) {
        let once = format(SourceId(0), &text).expect("a program");
        prop_assert_eq!(format(SourceId(0), &once).ok(), Some(once.clone()));
        prop_assert_eq!(tokens(&once), tokens(&text));
        prop_assert_eq!(comments(&once), comments(&text));
    }

    #[test]
    fn token_soup_never_makes_it_panic(
        words in prop::collection::vec(prop::sample::select(vocabulary()), 0..60),
        spaced in any::<bool>(),
    ) {
        let text = words.join(if spaced { " " } else { "" });
        if let Ok(once) = format(SourceId(0), &text) {
            prop_assert_eq!(format(SourceId(0), &once).ok(), Some(once.clone()));
            prop_assert_eq!(tokens(&once), tokens(&text));
        }
    }
}

#[test]
fn the_guides_example_is_the_formatters() {
    let readme = std::fs::read_to_string(repository().join("docs/guide/batch.md")).expect("the guide");
    let section = &readme[readme.find("## Formatting").expect("a section on formatting")..];
    let example = &section[..section.find("\n```\n").expect("the example ends")];
    let shown = |after: &str, until: &str| {
        let start = example.find(after).expect("the example shows it") + after.len();
        let length = example[start..].find(until).unwrap_or(example.len() - start);
        example[start..start + length].to_string()
    };
    let typed = shown("$ cat row.ray\n", "$ rayrepl fmt --check");
    let formatted = shown("$ rayrepl fmt row.ray\n$ cat row.ray\n", "\n```");
    assert_eq!(format(SourceId(0), &typed).expect("a program"), format!("{formatted}\n"));
}

// ---- The command ----------------------------------------------------------------

fn rayrepl() -> Command {
    Command::cargo_bin("rayrepl").expect("the binary is built")
}

/// A formatted program: a procedure, a comment after code.
const FORMATTED: &str = "\
camera distance 8 angle 1 end
ambient 0.2
proc ball(x)
  put sphere center x, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end # a red ball
end
ball(1)
";

/// [`FORMATTED`] with its indentation taken away, a space before each
/// comma instead of after it, and one after each `(`.
fn unformatted() -> String {
    FORMATTED.lines().map(|line| format!("{}\n", line.trim_start().replace(", ", " ,").replace('(', "( "))).collect()
}

/// Does not parse: a sphere without its `end`.
const BROKEN: &str = "\
camera distance 10 angle 1 end
put sphere center 0, 0, 0 radius 1 kd 0.8 ks 0.2 phong 20 color 40, 40, 220
put box
";

/// A folder holding the `files` given.
fn folder(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("a temporary folder");
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).expect("written");
    }
    dir
}

fn read(dir: &tempfile::TempDir, name: &str) -> String {
    std::fs::read_to_string(dir.path().join(name)).expect("readable")
}

#[test]
fn fmt_rewrites_the_files_that_change_in_place() {
    let dir = folder(&[("a.ray", unformatted().as_str()), ("b.ray", FORMATTED)]);
    let untouched = std::fs::metadata(dir.path().join("b.ray")).and_then(|m| m.modified()).expect("a time");
    std::thread::sleep(std::time::Duration::from_millis(20));
    rayrepl().current_dir(dir.path()).args(["fmt", "a.ray", "b.ray"]).assert().success().stdout("").stderr("");
    assert_eq!(read(&dir, "a.ray"), FORMATTED);
    assert_eq!(read(&dir, "b.ray"), FORMATTED);
    let after = std::fs::metadata(dir.path().join("b.ray")).and_then(|m| m.modified()).expect("a time");
    assert_eq!(after, untouched, "a formatted file is not written");
}

#[test]
fn fmt_check_says_which_files_would_change_and_writes_none() {
    let dir = folder(&[("a.ray", unformatted().as_str()), ("b.ray", FORMATTED)]);
    rayrepl()
        .current_dir(dir.path())
        .args(["fmt", "--check", "a.ray", "b.ray"])
        .assert()
        .code(1)
        .stdout("a.ray: would be reformatted, from line 3\n")
        .stderr("");
    assert_eq!(read(&dir, "a.ray"), unformatted());
    rayrepl().current_dir(dir.path()).args(["fmt", "--check", "b.ray"]).assert().success().stdout("");
}

#[test]
fn fmt_of_standard_input_writes_standard_output() {
    rayrepl().args(["fmt", "-"]).write_stdin(unformatted()).assert().success().stdout(FORMATTED).stderr("");
    rayrepl()
        .args(["fmt", "--check", "-"])
        .write_stdin(unformatted())
        .assert()
        .code(1)
        .stdout("<stdin>: would be reformatted, from line 3\n");
    rayrepl().args(["fmt", "--check", "-"]).write_stdin(FORMATTED).assert().success().stdout("");
}

#[test]
fn a_file_that_does_not_parse_is_reported_and_left_the_others_formatted() {
    let dir = folder(&[("broken.ray", BROKEN), ("a.ray", unformatted().as_str())]);
    rayrepl()
        .current_dir(dir.path())
        .args(["fmt", "broken.ray", "a.ray"])
        .env("NO_COLOR", "1")
        .assert()
        .code(1)
        .stdout("")
        .stderr(
            contains("error: expected `end` to close this `sphere`")
                .and(contains(" --> broken.ray:3:1"))
                .and(contains("3 | put box"))
                .and(contains("  | ^^^ unexpected `put`")),
        );
    assert_eq!(read(&dir, "broken.ray"), BROKEN);
    assert_eq!(read(&dir, "a.ray"), FORMATTED);
}

#[test]
fn a_file_that_cannot_be_read_is_reported() {
    let dir = folder(&[("a.ray", unformatted().as_str())]);
    rayrepl()
        .current_dir(dir.path())
        .args(["fmt", "missing.ray", "a.ray"])
        .assert()
        .code(1)
        .stderr(contains("rayrepl: cannot read `missing.ray`"));
    assert_eq!(read(&dir, "a.ray"), FORMATTED);
}

#[test]
fn usage_errors_exit_with_status_2() {
    rayrepl().args(["fmt"]).assert().code(2).stderr(contains("FILE"));
    rayrepl()
        .args(["fmt", "-", "a.ray"])
        .assert()
        .code(2)
        .stderr(contains("`-` formats standard input to standard output: give it alone"));
}

#[test]
fn fmt_help_gives_examples() {
    rayrepl()
        .args(["fmt", "--help"])
        .assert()
        .success()
        .stdout(contains("rayrepl fmt --check scenarios/*.ray").and(contains("--check")));
}
