//! Guided lessons as a domain of their own: lesson files ([`file`]), the
//! checks a step makes of a learner's scene and the verdicts they give
//! ([`check`]), the progress kept between sessions ([`progress`]) and where
//! a learner is in a lesson ([`tutor`]). The nine lessons built in are
//! text files (`lessons/*.md`) read once here.
//!
//! A check reads the learner's state through the [`Learner`] view, and a
//! step's goal is its lesson's own program run with the language
//! ([`lesson_scene`]): nothing here knows the session, whose command layer
//! (`:lesson`, `:goal`, the check after each input) uses this module.

mod check;
mod file;
mod learner;
mod lesson_scene;
mod progress;
mod tutor;

use std::sync::{Arc, LazyLock};

use crate::lang::SourceMap;

pub(crate) use check::Shortfall;
pub(crate) use file::Lesson;
pub(crate) use learner::Learner;
pub(crate) use progress::Progress;
pub(crate) use tutor::{Following, Tutor};

/// The built-in lessons' files, in order.
const BUILT_IN_FILES: &[(&str, &str)] = &[
    ("lessons/1-first-sphere.md", include_str!("../lessons/1-first-sphere.md")),
    ("lessons/2-lights.md", include_str!("../lessons/2-lights.md")),
    ("lessons/3-textures.md", include_str!("../lessons/3-textures.md")),
    ("lessons/4-planes-and-boxes.md", include_str!("../lessons/4-planes-and-boxes.md")),
    ("lessons/5-transformations.md", include_str!("../lessons/5-transformations.md")),
    ("lessons/6-names.md", include_str!("../lessons/6-names.md")),
    ("lessons/7-procedures.md", include_str!("../lessons/7-procedures.md")),
    ("lessons/8-recursion.md", include_str!("../lessons/8-recursion.md")),
    ("lessons/9-time.md", include_str!("../lessons/9-time.md")),
];

/// The built-in lessons, read once. Their files are proved by the tests
/// (every check, example and answer), so reading them cannot fail.
pub(crate) static BUILT_IN: LazyLock<Vec<Arc<Lesson>>> = LazyLock::new(|| {
    let mut sources = SourceMap::new();
    let read = |(name, text): &(&str, &str)| {
        let id = sources.add(*name, *text, 0);
        let lesson = Lesson::parse(text, id);
        Arc::new(lesson.unwrap_or_else(|d| panic!("{}", d.render(&sources, false))))
    };
    BUILT_IN_FILES.iter().map(read).collect()
});

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use super::*;

    fn docs() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("docs")
    }

    /// Every built-in lesson reads and proves itself: its checks ask for
    /// something new at each step, its example and its answers that must
    /// pass pass, its answers that must fail fail with the words it says;
    /// and every step has at least two of each.
    #[test]
    fn the_built_in_lessons_prove_themselves() {
        for (name, text) in BUILT_IN_FILES {
            let mut sources = SourceMap::new();
            let id = sources.add(*name, *text, 0);
            let lesson = Lesson::read(text, id).unwrap_or_else(|d| panic!("{}", d.render(&sources, false)));
            for (index, step) in lesson.steps.iter().enumerate() {
                let place = format!("{name} step {}", index + 1);
                assert!(step.passes.len() >= 2 && step.fails.len() >= 2, "{place}: two answers of each kind");
            }
        }
    }

    /// docs/lessons.md documents every word of the checks, and its
    /// complete lesson reads and proves itself.
    #[test]
    fn the_lessons_page_documents_the_format_with_a_lesson_that_proves_itself() {
        let page = std::fs::read_to_string(docs().join("lessons.md")).expect("docs/lessons.md exists");
        for word in check::vocabulary() {
            assert!(page.contains(&format!("`{word}")), "docs/lessons.md does not document `{word}`");
        }
        let example = page.split("````markdown\n").nth(1).and_then(|rest| rest.split("\n````").next());
        let example = example.expect("docs/lessons.md has a complete lesson in a ````markdown block");
        let mut sources = SourceMap::new();
        let id = sources.add("docs/lessons.md", example, 0);
        let lesson = Lesson::read(example, id).unwrap_or_else(|d| panic!("{}", d.render(&sources, false)));
        assert_eq!(lesson.steps.len(), 2);
    }
}
