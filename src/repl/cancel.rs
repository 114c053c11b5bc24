//! Stopping what an entry does with Ctrl-C without leaving the session.
//!
//! At the prompt the terminal is in raw mode and rustyline reads Ctrl-C as a
//! key. While an entry runs (evaluation, a render, the writing of a file) it
//! is not, so Ctrl-C raises SIGINT. One handler is installed per process (the
//! `ctrlc` crate allows no more); while the switch is armed it raises the
//! cancel flag that evaluation and renders poll, and at any other time it
//! does what Ctrl-C does by default: end the program.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// The switch, once the handler is installed; `None` inside if installing failed.
static SWITCH: OnceLock<Option<CancelSwitch>> = OnceLock::new();

/// The process-wide Ctrl-C switch.
#[derive(Debug, Default)]
pub(crate) struct CancelSwitch {
    /// Raised by Ctrl-C while armed; polled by evaluation and renders.
    cancel: AtomicBool,
    /// How many cancellable jobs are running (an entry, a render inside it).
    armed: AtomicUsize,
}

impl CancelSwitch {
    /// The switch, with its Ctrl-C handler installed on first use. `None` if
    /// the handler could not be installed (another one was set already).
    pub(crate) fn install() -> Option<&'static CancelSwitch> {
        SWITCH.get_or_init(|| ctrlc::set_handler(on_ctrl_c).is_ok().then(CancelSwitch::default)).as_ref()
    }

    /// Arms the switch for one job; it is disarmed when the guard drops. A
    /// job inside another (a render inside an entry) shares its flag.
    pub(crate) fn arm(&'static self) -> ArmedSwitch {
        if self.armed.fetch_add(1, Ordering::SeqCst) == 0 {
            self.cancel.store(false, Ordering::SeqCst);
        }
        ArmedSwitch { switch: self }
    }

    /// The flag Ctrl-C raises while the switch is armed.
    pub(crate) fn flag(&'static self) -> &'static AtomicBool {
        &self.cancel
    }
}

/// The flag Ctrl-C raises while `switch` is armed; without a switch, one
/// never raised (Ctrl-C then ends the process).
pub(crate) fn cancel_flag(switch: Option<&'static CancelSwitch>) -> &'static AtomicBool {
    switch.map_or(&crate::output::NEVER_CANCELLED, CancelSwitch::flag)
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

    /// Whether Ctrl-C was pressed since the outermost job started.
    pub(crate) fn pressed(&self) -> bool {
        self.switch.cancel.load(Ordering::SeqCst)
    }
}

impl Drop for ArmedSwitch {
    fn drop(&mut self) {
        if self.switch.armed.fetch_sub(1, Ordering::SeqCst) == 1 {
            self.switch.cancel.store(false, Ordering::SeqCst);
        }
    }
}

fn on_ctrl_c() {
    match SWITCH.get() {
        Some(Some(switch)) if switch.armed.load(Ordering::SeqCst) > 0 => switch.cancel.store(true, Ordering::SeqCst),
        _ => crate::output::exit_discarding_unfinished(crate::output::INTERRUPTED_EXIT_CODE),
    }
}
