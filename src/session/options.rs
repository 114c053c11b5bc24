//! How a session starts: what the command line asked for.

use std::path::PathBuf;

use crate::lang::Limits;
use crate::lint::Allowed;

use super::rendering::RenderSettings;
use super::state::Session;
use crate::process::cancel::CancelSwitch;

/// How a session starts: what the command line asked for.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SessionOptions {
    /// Never show renders in the terminal (`--no-preview`).
    pub no_preview: bool,
    /// In a script, go on after an error (`--keep-going`); the exit status is
    /// still 1 at the end.
    pub keep_going: bool,
    /// A file to load before the first input (`-i scene.ray`).
    pub initial_file: Option<PathBuf>,
    /// The lesson to start after it (`--lesson N` or `--lesson FILE`).
    pub lesson: Option<String>,
    /// Size, depth, samples, time and screen convention to start with.
    pub settings: RenderSettings,
    /// Limits on procedure calls and primitives (`--max-calls`, `--max-primitives`).
    pub limits: Limits,
    /// The warnings about the scene turned off (`--allow`).
    pub allowed: Allowed,
}

/// A session set up with `options`' settings and limits, whose evaluations
/// `cancel` (Ctrl-C) can stop.
pub(crate) fn new_session(options: &SessionOptions, cancel: Option<&'static CancelSwitch>) -> Session {
    let session = Session::new(options.settings, options.limits).allowing(options.allowed);
    match cancel {
        Some(switch) => session.interruptible(switch.flag()),
        None => session,
    }
}
