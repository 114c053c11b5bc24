//! Cancelling a render with Ctrl-C without leaving the session.
//!
//! At the prompt the terminal is in raw mode and rustyline reads Ctrl-C as a
//! key. During a render it is not, so Ctrl-C raises SIGINT. One handler is
//! installed per process (the `ctrlc` crate allows no more); while a render
//! runs it raises the cancel flag the render polls, and at any other time it
//! does what Ctrl-C does by default: end the program.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};

/// Exit status of a program ended by Ctrl-C (128 + SIGINT).
const INTERRUPTED_EXIT_CODE: i32 = 130;

/// The switch, once the handler is installed; `None` inside if installing failed.
static SWITCH: OnceLock<Option<CancelSwitch>> = OnceLock::new();

/// The process-wide Ctrl-C switch.
#[derive(Debug, Default)]
pub(crate) struct CancelSwitch {
    /// Raised by Ctrl-C while `armed`; polled by renders.
    cancel: AtomicBool,
    /// Whether a cancellable job is running.
    armed: AtomicBool,
}

impl CancelSwitch {
    /// The switch, with its Ctrl-C handler installed on first use. `None` if
    /// the handler could not be installed (another one was set already).
    pub(crate) fn install() -> Option<&'static CancelSwitch> {
        SWITCH.get_or_init(|| ctrlc::set_handler(on_ctrl_c).is_ok().then(CancelSwitch::default)).as_ref()
    }

    /// Arms the switch for one job; it is disarmed when the guard drops.
    pub(crate) fn arm(&'static self) -> ArmedSwitch {
        self.cancel.store(false, Ordering::SeqCst);
        self.armed.store(true, Ordering::SeqCst);
        ArmedSwitch { switch: self }
    }
}

/// A switch armed for the duration of one job.
#[derive(Debug)]
pub(crate) struct ArmedSwitch {
    switch: &'static CancelSwitch,
}

impl ArmedSwitch {
    /// The flag Ctrl-C raises: the job polls it and stops when it is set.
    pub(crate) fn flag(&self) -> &AtomicBool {
        &self.switch.cancel
    }
}

impl Drop for ArmedSwitch {
    fn drop(&mut self) {
        self.switch.armed.store(false, Ordering::SeqCst);
        self.switch.cancel.store(false, Ordering::SeqCst);
    }
}

fn on_ctrl_c() {
    match SWITCH.get() {
        Some(Some(switch)) if switch.armed.load(Ordering::SeqCst) => switch.cancel.store(true, Ordering::SeqCst),
        _ => crate::output::exit_discarding_unfinished(INTERRUPTED_EXIT_CODE),
    }
}
