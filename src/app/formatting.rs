//! Runs `rayrepl fmt`: formats each file ([`crate::lang::format`]) and
//! writes it back atomically when its text changes, or says which would
//! change (`--check`), or formats standard input to standard output.

use std::fmt::Display;
use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

use super::{load, show, write_stdout};
use crate::job::{DiagnosticFormat, Formatted, FormattingJob};
use crate::lang::SourceMap;
use crate::lang::format::format;
use crate::output;
use crate::process::failure::report_failure;

/// What became of one text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Outcome {
    /// Already formatted.
    Unchanged,
    /// Formatted: written back, or with `--check` said to change.
    Changed,
    /// Not read, not a program, or not written back: said on standard error.
    Failed,
}

/// Formats what `job` names and gives the exit code: 0 when every text is
/// formatted (with `--check`: none would change), 1 when one does not parse
/// or cannot be read or written (with `--check`: or would change).
pub(super) fn format_all(job: &FormattingJob) -> ExitCode {
    let outcomes: Vec<Outcome> = match &job.input {
        Formatted::Stdin => vec![format_stdin(job.check)],
        Formatted::Files(files) => files.iter().map(|file| format_file(file, job.check)).collect(),
    };
    let failed = outcomes.contains(&Outcome::Failed) || (job.check && outcomes.contains(&Outcome::Changed));
    if failed { ExitCode::FAILURE } else { ExitCode::SUCCESS }
}

/// Formats the file at `path` and writes it back if its text changes
/// (with `check`, says so instead).
fn format_file(path: &Path, check: bool) -> Outcome {
    let Some((text, formatted)) = read_and_format(path) else { return Outcome::Failed };
    if formatted == text {
        return Outcome::Unchanged;
    }
    if check {
        return report_change(&path.display().to_string(), &text, &formatted);
    }
    reported(output::write_text(path, &formatted, &output::NEVER_CANCELLED), Outcome::Changed)
}

/// Formats standard input to standard output (with `check`, only says
/// whether it would change).
fn format_stdin(check: bool) -> Outcome {
    let Some((text, formatted)) = read_and_format(Path::new("-")) else { return Outcome::Failed };
    if check {
        return if formatted == text { Outcome::Unchanged } else { report_change("<stdin>", &text, &formatted) };
    }
    let written = write_stdout("the formatted scene", |stdout| stdout.write_all(formatted.as_bytes()));
    reported(written, if formatted == text { Outcome::Unchanged } else { Outcome::Changed })
}

/// The text at `path` (`-`: standard input), as rayrepl reads a scene, and
/// that text formatted; or, having said why on standard error, nothing.
fn read_and_format(path: &Path) -> Option<(String, String)> {
    let mut sources = SourceMap::new();
    let id = load(&mut sources, path).map_err(report_failure).ok()?;
    let text = sources.get(id).text.to_string();
    match format(id, &text) {
        Ok(formatted) => Some((text, formatted)),
        Err(diagnostic) => {
            show(&diagnostic, &sources, DiagnosticFormat::Rendered);
            None
        }
    }
}

/// Says on standard output that the text `name` would change, and from
/// which line.
fn report_change(name: &str, text: &str, formatted: &str) -> Outcome {
    let line = first_different_line(text, formatted);
    let said = write_stdout("the files to format", |stdout| {
        writeln!(stdout, "{name}: would be reformatted, from line {line}")
    });
    reported(said, Outcome::Changed)
}

/// `done` if the write `result` succeeded; otherwise, having said why on
/// standard error, [`Outcome::Failed`].
fn reported(result: Result<(), impl Display>, done: Outcome) -> Outcome {
    match result {
        Ok(()) => done,
        Err(why) => {
            report_failure(why);
            Outcome::Failed
        }
    }
}

/// The number of the first line where `text` and `formatted` differ,
/// counted from 1.
fn first_different_line(text: &str, formatted: &str) -> usize {
    let mut formatted_lines = formatted.split('\n');
    text.split('\n').take_while(|line| formatted_lines.next() == Some(*line)).count() + 1
}
