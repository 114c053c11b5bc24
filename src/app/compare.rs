//! Runs `rayrepl compare`: reads the reference and each submission,
//! grades them ([`crate::compare`]) and shows each grade as it comes, in
//! words, JSON or CSV, with the pictures of the differences and the CSV
//! file written atomically.

use std::io::{IsTerminal, Write};
use std::path::Path;
use std::process::ExitCode;

use super::{USAGE_EXIT_CODE, load, show, write_stdout};
use crate::compare::{CSV_HEADER, Grade, Outcome, Reference, ReferenceError, Verdict, summary};
use crate::job::{DiagnosticFormat, GradingJob, Report};
use crate::lang::SourceMap;
use crate::output::{self, frame_path};
use crate::process::failure::report_failure;

/// Grades every submission of `job` against its reference and gives the
/// exit code: 0 when all match, 1 when one differs or does not run (or an
/// output cannot be written), 2 when the reference cannot be read or run.
pub(super) fn grade_all(job: &GradingJob) -> ExitCode {
    let Some(reference) = reference(job) else { return ExitCode::from(USAGE_EXIT_CODE) };
    if let Some(folder) = &job.diff_folder
        && let Err(error) = std::fs::create_dir_all(folder)
    {
        report_failure(format_args!("cannot make the folder `{}`: {}", folder.display(), output::io_reason(&error)));
        return ExitCode::FAILURE;
    }
    let tolerances = &job.grading.tolerances;
    let color = matches!(
        anstream::AutoStream::choice(&std::io::stdout()),
        anstream::ColorChoice::Always | anstream::ColorChoice::AlwaysAnsi
    ) && std::io::stdout().is_terminal();
    let mut csv = format!("{CSV_HEADER}\n");
    let mut verdicts = Vec::new();
    let mut failed = false;
    if job.report == Report::Csv && show_text(&csv).is_err() {
        return ExitCode::FAILURE;
    }
    for path in &job.submissions {
        let grade = grade(&reference, path, job);
        if let Some(folder) = &job.diff_folder {
            failed |= write_difference_pictures(folder, path, &grade).is_err();
        }
        let row = format!("{}\n", grade.csv_row(tolerances));
        let shown = match job.report {
            Report::Words => grade.words(tolerances, color),
            Report::JsonLines => format!("{}\n", grade.to_json(tolerances)),
            Report::Csv => row.clone(),
        };
        if show_text(&shown).is_err() {
            return ExitCode::FAILURE;
        }
        csv.push_str(&row);
        verdicts.push(grade.verdict(tolerances));
    }
    if job.report == Report::Words && show_text(&format!("{}\n", summary(&verdicts))).is_err() {
        return ExitCode::FAILURE;
    }
    if let Some(file) = &job.csv_file
        && let Err(error) = output::write_text(file, &csv, &output::NEVER_CANCELLED)
    {
        report_failure(error);
        failed = true;
    }
    if failed || verdicts.iter().any(|&verdict| verdict != Verdict::Matches) {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// The reference of `job`, evaluated and rendered; or, having said why
/// on standard error, nothing.
fn reference(job: &GradingJob) -> Option<Reference> {
    let mut sources = SourceMap::new();
    let id = load(&mut sources, &job.reference).map_err(report_failure).ok()?;
    match Reference::prepare(sources, id, &job.grading) {
        Ok(reference) => Some(reference),
        Err((sources, ReferenceError::Scene(diagnostic))) => {
            show(&diagnostic, &sources, DiagnosticFormat::Rendered);
            report_failure("the reference does not run: there is nothing to compare with");
            None
        }
        Err((_, ReferenceError::Render(why))) => {
            report_failure(format_args!("cannot render the reference: {why}"));
            None
        }
    }
}

/// The submission at `path` read and graded against `reference`.
fn grade(reference: &Reference, path: &Path, job: &GradingJob) -> Grade {
    let name = path.display().to_string();
    let mut sources = reference.sources().clone();
    match load(&mut sources, path) {
        Ok(id) => reference.grade(name, sources, id, &job.grading),
        Err(why) => Grade::unreadable(name, why),
    }
}

/// Writes the pictures of the differences of `grade`, the grade of the
/// submission at `path`, into `folder`: `NAME.png`, or `NAME0001.png`...
/// for an animation's frames. A file that cannot be written is said on
/// standard error.
fn write_difference_pictures(folder: &Path, path: &Path, grade: &Grade) -> Result<(), ()> {
    let Outcome::Compared(frames) = &grade.outcome else { return Ok(()) };
    let stem = path.file_stem().unwrap_or(path.as_os_str());
    let base = folder.join(stem).with_extension("png");
    let mut result = Ok(());
    for frame in frames {
        let Some(picture) = &frame.difference_picture else { continue };
        let file = match frame.frame.number {
            Some(k) => frame_path(&base, k as usize, frames.len()),
            None => base.clone(),
        };
        if let Err(error) = output::write_image(&file, picture) {
            report_failure(error);
            result = Err(());
        }
    }
    result
}

/// Writes `text` on standard output, or says on standard error why it
/// could not.
fn show_text(text: &str) -> Result<(), ()> {
    write_stdout("the grades", |stdout| stdout.write_all(text.as_bytes())).map_err(report_failure)
}
