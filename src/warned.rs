//! The one rule for showing a warning once: a warning is known by its code
//! and the place it points at. The batch renderer (over the frames of an
//! animation) and the session (over its renders) each show a warning only
//! the first time one of their evaluations or renders raises it.

use std::collections::HashSet;

use crate::lang::{Diagnostic, Span};

/// The warnings already shown.
#[derive(Debug, Default)]
pub(crate) struct Warned {
    shown: HashSet<(&'static str, Span)>,
}

impl Warned {
    /// Whether `warning` was not shown yet; from now on it counts as shown.
    pub(crate) fn first_time(&mut self, warning: &Diagnostic) -> bool {
        self.shown.insert((warning.code, warning.span))
    }
}
