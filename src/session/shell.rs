//! The session with what a front-end keeps beside it: the lesson being
//! followed, the last picture and the warnings already shown. The [`Session`] itself holds the
//! language's state only.

use image::RgbImage;

use super::state::Session;
use crate::lessons::Tutor;
use crate::warned::Warned;

/// What the commands work on: the session, and the front-end's state.
#[derive(Debug)]
pub(crate) struct Shell {
    /// The language's state: inputs, scene, settings, history, undo.
    pub session: Session,
    /// The lesson being followed, if any (`:lesson`).
    pub tutor: Tutor,
    /// The last picture rendered or saved, whose pixels `:pick` explains.
    pub last_picture: Option<RgbImage>,
    /// The warnings about the scene already shown: a cause is warned about
    /// once, not at every render.
    pub warned: Warned,
}

impl Shell {
    /// `session`, with no lesson followed and no picture yet.
    pub(crate) fn new(session: Session) -> Shell {
        Shell { session, tutor: Tutor::default(), last_picture: None, warned: Warned::default() }
    }
}
