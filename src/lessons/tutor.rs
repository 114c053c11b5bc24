//! Where a learner is in the lessons.

use std::sync::Arc;

use super::file::Lesson;

/// The lesson being followed in a session, if any.
#[derive(Debug, Default)]
pub(crate) struct Tutor {
    pub following: Option<Following>,
    /// Whether the scene is checked after each input accepted (the
    /// terminal, a cell), or only once a whole scene has run
    /// (`CellSession::run_scene`, which holds them while it runs).
    pub checks_held: bool,
}

/// A lesson being followed, and where the learner is in it.
#[derive(Debug, Clone)]
pub(crate) struct Following {
    pub lesson: Arc<Lesson>,
    /// Its number among the built-in lessons (from 1), whose progress is
    /// kept between sessions; `None` for a lesson read from a file.
    pub number: Option<usize>,
    /// The step worked on, from 0.
    pub step: usize,
    /// Wrong tries of that step.
    pub wrong_tries: u32,
}
