//! Ctrl-C while an entry runs.
//!
//! At the prompt the terminal is in raw mode and rustyline reads Ctrl-C as a
//! key. While an entry runs (evaluation, a render, the writing of a file) it
//! is not, so Ctrl-C raises SIGINT. One handler is installed per process (the
//! `ctrlc` crate allows no more); while the session's switch is armed it
//! raises the cancel flag that evaluation and renders poll, and at any other
//! time it does what Ctrl-C does by default: end the program.

use std::sync::OnceLock;

use crate::output::{INTERRUPTED_EXIT_CODE, exit_discarding_unfinished};
use crate::repl::CancelSwitch;

/// The switch, once the handler is installed; `None` inside if installing failed.
static SWITCH: OnceLock<Option<CancelSwitch>> = OnceLock::new();

/// The switch Ctrl-C raises, with its handler installed on first use.
/// `None` if the handler could not be installed (another one was set already).
pub(crate) fn install() -> Option<&'static CancelSwitch> {
    SWITCH.get_or_init(|| ctrlc::set_handler(on_ctrl_c).is_ok().then(CancelSwitch::default)).as_ref()
}

fn on_ctrl_c() {
    let cancelled = matches!(SWITCH.get(), Some(Some(switch)) if switch.cancel_if_armed());
    if !cancelled {
        exit_discarding_unfinished(INTERRUPTED_EXIT_CODE);
    }
}
