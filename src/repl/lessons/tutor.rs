//! Where a learner is in the lessons.

/// The lesson being followed in a session, if any.
#[derive(Debug, Default)]
pub(crate) struct Tutor {
    /// The lesson and step (from 0) being worked on.
    pub place: Option<(usize, usize)>,
    /// Wrong tries of the current step.
    pub wrong_tries: u32,
}
