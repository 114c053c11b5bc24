//! The one rule for showing a warning once: a warning is known by its code
//! and the place it points at. The batch renderer (over the frames of an
//! animation) and the session (over its inputs and renders) pass every
//! warning of an evaluation and every warning about the scene through
//! [`Warned::unseen`], and show only what it gives back.

use std::collections::HashSet;

use crate::lang::{Diagnostic, Span};

/// The warnings already shown.
#[derive(Debug, Default)]
pub(crate) struct Warned {
    shown: HashSet<(&'static str, Span)>,
}

impl Warned {
    /// The `warnings` not shown yet, in order; from now on they count as shown.
    pub(crate) fn unseen(&mut self, warnings: impl IntoIterator<Item = Diagnostic>) -> Vec<Diagnostic> {
        warnings.into_iter().filter(|warning| self.shown.insert((warning.code, warning.span))).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::SourceId;

    #[test]
    fn a_warning_is_shown_once_by_its_code_and_place() {
        let at = |start| Span::new(SourceId(0), start, start + 1);
        let warning = |code, start| Diagnostic::warning(at(start), "w").with_code(code);
        let mut warned = Warned::default();
        assert_eq!(warned.unseen([warning("a", 0), warning("a", 0), warning("b", 0)]).len(), 2);
        let again = warned.unseen([warning("a", 0), warning("a", 1)]);
        assert_eq!(again, [warning("a", 1)], "only the new place");
    }
}
