//! `rayrepl compare`'s command line turned into a grading job, in one
//! step: the submissions found (a folder gives its `.ray` files), the
//! settings, the frames, the tolerances and the outputs checked.

use std::path::{Path, PathBuf};

use super::JobError;
use crate::cli::CompareArgs;
use crate::cli::flags::flag_with_id;
use crate::compare::{Frames, Grading, Tolerances};
use crate::output;
use crate::settings::{DEFAULTS, RenderSettings};

/// What `rayrepl compare` asks for, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct GradingJob {
    /// The reference scene file.
    pub reference: PathBuf,
    /// The submissions' scene files, in the order graded.
    pub submissions: Vec<PathBuf>,
    /// How they are graded.
    pub grading: Grading,
    /// What standard output shows.
    pub report: Report,
    /// Where the CSV file goes (`--csv FILE`), if anywhere.
    pub csv_file: Option<PathBuf>,
    /// Where the pictures of the differences go (`--diff DIR`), if anywhere.
    pub diff_folder: Option<PathBuf>,
}

/// What standard output shows of the grades.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Report {
    /// Each grade in words, then a summary line.
    Words,
    /// Each grade as one JSON object a line (`--json`).
    JsonLines,
    /// The CSV rows, after their header (`--csv -`).
    Csv,
}

/// The flags of `compare` that share the rules of the command line's own
/// (`cli::flags`), in the order they are checked.
const SHARED_FLAGS: [&str; 3] = ["time", "time_start", "time_step"];

/// A flag of [`SHARED_FLAGS`] that would do nothing with the others given,
/// said in the words of `cli::flags`.
fn misuse(args: &CompareArgs) -> Option<String> {
    let given = |id: &str| match id {
        "time" => args.time.is_some(),
        "anim" => args.anim.is_some(),
        "time_start" => args.timeline.time_start.is_some(),
        "time_step" => args.timeline.time_step.is_some(),
        _ => false,
    };
    SHARED_FLAGS.iter().find_map(|id| flag_with_id(id).misuse(&given, None))
}

/// The grading job `args` ask for, or why there is none.
pub(super) fn grading_job(args: &CompareArgs) -> Result<GradingJob, JobError> {
    if let Some(misuse) = misuse(args) {
        return Err(JobError::Misuse(misuse));
    }
    let picture = &args.picture;
    let time = args.time.unwrap_or(DEFAULTS.time);
    let (width, height, depth, samples) = (picture.width, picture.height, picture.depth, picture.samples);
    let settings = RenderSettings { width, height, depth, samples, time, ..DEFAULTS };
    settings.validate().map_err(|error| JobError::Misuse(error.to_string()))?;
    let frames = match args.anim {
        Some(count) => {
            let timeline = args.timeline.timeline();
            timeline.check(1..=count).map_err(|error| JobError::Misuse(error.to_string()))?;
            Frames::Animation { count, timeline }
        }
        None => Frames::Still(time),
    };
    let tolerances = Tolerances {
        length: args.length_tolerance,
        colour: args.colour_tolerance,
        coefficient: args.coefficient_tolerance,
        pixel: args.pixel_tolerance,
        off_pixels: args.off_pixels,
    };
    if let Some(folder) = args.diff.as_deref().filter(|folder| folder.exists() && !folder.is_dir()) {
        return Err(JobError::Misuse(format!("--diff {}: that is a file, not a folder", folder.display())));
    }
    let (report, csv_file) = match args.csv.as_deref() {
        Some(path) if path == Path::new("-") => (Report::Csv, None),
        Some(path) if path.is_dir() => {
            return Err(JobError::Misuse(format!("--csv {}: that is a folder; give a file name", path.display())));
        }
        Some(path) => (Report::Words, Some(path.to_owned())),
        None if args.json => (Report::JsonLines, None),
        None => (Report::Words, None),
    };
    let grading = Grading {
        options: settings.render_options(),
        frames,
        tolerances,
        limits: args.limits.limits(),
        difference_pictures: args.diff.is_some(),
    };
    let submissions = submissions(&args.submissions, &args.reference)?;
    Ok(GradingJob {
        reference: args.reference.clone(),
        submissions,
        grading,
        report,
        csv_file,
        diff_folder: args.diff.clone(),
    })
}

/// The submissions named: each file as given, each folder as its `.ray`
/// files sorted by name (without the reference, should it be there).
fn submissions(named: &[PathBuf], reference: &Path) -> Result<Vec<PathBuf>, JobError> {
    let mut found = Vec::new();
    for path in named {
        if !path.is_dir() {
            found.push(path.clone());
            continue;
        }
        let unreadable = |error: std::io::Error| {
            JobError::Misuse(format!("cannot read the folder `{}`: {}", path.display(), output::io_reason(&error)))
        };
        let mut files = Vec::new();
        for entry in std::fs::read_dir(path).map_err(unreadable)? {
            let file = entry.map_err(unreadable)?.path();
            let is_scene = file.extension().is_some_and(|extension| extension == "ray") && !file.is_dir();
            if is_scene && !output::same_file(&file, reference) {
                files.push(file);
            }
        }
        if files.is_empty() {
            return Err(JobError::Misuse(format!("the folder `{}` holds no .ray file to compare", path.display())));
        }
        files.sort();
        found.extend(files);
    }
    Ok(found)
}
