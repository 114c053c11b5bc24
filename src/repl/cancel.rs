//! Stopping what an entry does without leaving the session: a switch that
//! is armed while a job runs, and whose flag evaluation and renders poll.
//! The front-end raises it (the terminal's Ctrl-C handler,
//! `crate::terminal::ctrl_c`); at any other time the front-end does what
//! it would do anyway.

use std::sync::atomic::{AtomicBool, AtomicU8, AtomicUsize, Ordering};

use crate::interruption::Signal;

/// The switch that stops a running job.
#[derive(Debug, Default)]
pub struct CancelSwitch {
    /// Raised by Ctrl-C while armed; polled by evaluation and renders.
    cancel: AtomicBool,
    /// How many cancellable jobs are running (an entry, a render inside it).
    armed: AtomicUsize,
    /// The signal that raised the flag ([`Signal::code`]), 0 before one.
    signal: AtomicU8,
}

impl CancelSwitch {
    /// Raises the flag if a job is running, recording that `signal` asked;
    /// says whether one was.
    pub(crate) fn cancel_if_armed(&self, signal: Signal) -> bool {
        let armed = self.is_armed();
        if armed {
            self.signal.store(signal.code(), Ordering::SeqCst);
            self.cancel.store(true, Ordering::SeqCst);
        }
        armed
    }

    /// Whether a cancellable job is running.
    pub(crate) fn is_armed(&self) -> bool {
        self.armed.load(Ordering::SeqCst) > 0
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

    /// Whether Ctrl-C was pressed (or another signal asked to stop) since
    /// the outermost job started.
    pub(crate) fn pressed(&self) -> bool {
        self.switch.cancel.load(Ordering::SeqCst)
    }

    /// The signal that raised the flag since the outermost job started.
    pub(crate) fn signal(&self) -> Option<Signal> {
        self.pressed().then(|| Signal::from_code(self.switch.signal.load(Ordering::SeqCst))).flatten()
    }
}

impl Drop for ArmedSwitch {
    fn drop(&mut self) {
        if self.switch.armed.fetch_sub(1, Ordering::SeqCst) == 1 {
            self.switch.cancel.store(false, Ordering::SeqCst);
        }
    }
}
