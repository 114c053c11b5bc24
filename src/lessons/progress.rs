//! Which lessons a learner finished and where they stopped, kept between
//! sessions in a small text file: `done N` for each finished lesson and
//! `at N K` for the step reached in the last one. A format this small needs
//! no serialisation crate; a line that does not read is skipped.

use std::collections::BTreeSet;
use std::io::Read;
use std::path::PathBuf;

/// The variable that names the progress file in place of the user's data
/// directory (for tests, or to keep several learners apart).
pub(crate) const PROGRESS_VARIABLE: &str = "RAYREPL_LESSONS";

/// The most of the progress file read: a file of nine lessons takes under
/// a hundred bytes, and a path to something endless (`/dev/zero`) must not
/// fill the memory.
const MOST_BYTES: u64 = 64 << 10;

/// Lesson and step numbers count from 1, as the learner reads them.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub(crate) struct Progress {
    /// The lessons finished.
    pub done: BTreeSet<usize>,
    /// The lesson and step reached last, if a lesson was left unfinished.
    pub at: Option<(usize, usize)>,
}

impl Progress {
    /// The progress kept in the file (its first [`MOST_BYTES`]), or none
    /// if there is no file yet.
    pub(crate) fn load() -> Progress {
        let read = |file: std::fs::File| {
            let mut text = String::new();
            file.take(MOST_BYTES).read_to_string(&mut text).ok().map(|_| text)
        };
        let text = file().and_then(|path| std::fs::File::open(path).ok()).and_then(read);
        text.map_or_else(Progress::default, |text| Progress::parse(&text))
    }

    /// Writes the progress to its file.
    pub(crate) fn save(&self) -> Result<(), String> {
        let path = file().ok_or("there is no data directory to keep it in")?;
        if let Some(folder) = path.parent() {
            std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
        }
        std::fs::write(&path, self.to_text()).map_err(|e| format!("{}: {e}", path.display()))
    }

    fn parse(text: &str) -> Progress {
        let mut progress = Progress::default();
        for line in text.lines() {
            let words: Vec<&str> = line.split_whitespace().collect();
            let numbers: Option<Vec<usize>> = words.iter().skip(1).map(|word| word.parse().ok()).collect();
            match (words.first(), numbers.as_deref()) {
                (Some(&"done"), Some(&[lesson])) => {
                    progress.done.insert(lesson);
                }
                (Some(&"at"), Some(&[lesson, step])) => progress.at = Some((lesson, step)),
                _ => {}
            }
        }
        progress
    }

    fn to_text(&self) -> String {
        let mut text = String::from("# rayrepl's lessons: those done, and where the last one stopped\n");
        for lesson in &self.done {
            text.push_str(&format!("done {lesson}\n"));
        }
        if let Some((lesson, step)) = self.at {
            text.push_str(&format!("at {lesson} {step}\n"));
        }
        text
    }
}

/// `$RAYREPL_LESSONS`, or `rayrepl/lessons` in the user's data directory.
fn file() -> Option<PathBuf> {
    match std::env::var_os(PROGRESS_VARIABLE) {
        Some(path) => Some(PathBuf::from(path)),
        None => Some(crate::data_dir::data_dir()?.join("lessons")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn progress_reads_back_what_it_wrote_and_skips_bad_lines() {
        let progress = Progress { done: BTreeSet::from([1, 3]), at: Some((4, 2)) };
        assert_eq!(Progress::parse(&progress.to_text()), progress);
        let read = Progress::parse("done 2\ndone x\nat 5\nat 6 1 9\nnonsense\nat 3 2\n");
        assert_eq!(read, Progress { done: BTreeSet::from([2]), at: Some((3, 2)) });
    }
}
