//! The session core (SPEC 7): what a session does with an input or a
//! command, and what it shows.
//!
//! A [`Session`] keeps one interpreter across inputs: items typed one at a
//! time accumulate into one global environment and one scene, and an input
//! that fails changes nothing. A `Shell` holds it with what a front-end
//! keeps beside it (the lesson followed, the last picture). Inputs and
//! commands hand what they show, as [`Output`] values, to the [`FrontEnd`]
//! that drives them: the terminal (`crate::terminal`) writes them as text
//! and previews their pictures, piped scripts write them as text, the
//! notebook kernel and the page run cells through a [`CellSession`], and
//! [`Collected`] keeps them in a list. `script` runs lines of text as a
//! script, for all of them.
//!
//! Commands (`:render`, `:save`, `:time`, ...) are described once in
//! [`crate::ide::commands`]; the registry, `commands`, gives each its
//! handler, in the modules of their topic below it (`picture_commands`,
//! `setting_commands`, `file_commands`, `inspect`, `session_commands`,
//! `play`, `reload`, `write_back`, `lesson_commands`). Completion, help and
//! inspection at a place are the editor services of [`crate::ide`].

mod cells;
pub(crate) mod commands;
mod describe;
mod excerpt;
pub(crate) mod file_commands;
pub(crate) mod inputs;
pub(crate) mod inspect;
pub(crate) mod lesson_commands;
pub(crate) mod options;
mod outcome;
mod outputs;
mod picture_commands;
mod play;
mod reload;
mod render_steps;
mod rendering;
pub(crate) mod report;
pub(crate) mod script;
mod session_commands;
mod setting_commands;
pub(crate) mod shell;
mod state;
pub(crate) mod write_back;

pub use crate::process::cancel::CancelSwitch;
pub use cells::{CellEnd, CellSession, Completeness, Completions};
pub use options::SessionOptions;
pub use outputs::{
    Collected, FrontEnd, LessonStep, LessonVerdict, Output, Picture, PixelExplanation, PreviewSize, SaveWatcher,
    TextRole, Ticker, Waited, mark_pixel,
};
pub use rendering::{RenderSettings, Size};
pub use state::{MOST_INPUTS, Session};
