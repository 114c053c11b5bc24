//! Evaluation errors: the internal error type and the messages of SPEC 3.

use crate::lang::degrees::{field_of_view_looks_like_degrees, in_radians_help};
use crate::lang::diagnostic::{Diagnostic, Note, shown_name};
use crate::lang::name::Name;
use crate::lang::number::format_number;
use crate::lang::source::Span;
use crate::lang::suggest;

/// An evaluation error on its way up to [`super::Interpreter::run`].
#[derive(Debug)]
pub(crate) struct EvalError {
    /// What is reported.
    pub diagnostic: Diagnostic,
    /// For a too deep recursion: every active call (procedure, call site),
    /// innermost first, as they are collected while the error unwinds; the
    /// note that summarises them once the sources are known reads them
    /// outermost first. `None` for the other errors.
    pub chain: Option<Vec<(Name, Span)>>,
}

/// Boxed, so that results on the hot path stay two words wide.
pub(crate) type EvalResult<T> = Result<T, Box<EvalError>>;

impl From<Diagnostic> for Box<EvalError> {
    fn from(diagnostic: Diagnostic) -> Box<EvalError> {
        Box::new(EvalError { diagnostic, chain: None })
    }
}

/// Fails with `diagnostic`.
pub(crate) fn fail<T>(diagnostic: Diagnostic) -> EvalResult<T> {
    Err(diagnostic.into())
}

/// SPEC 6: a camera `angle` (the horizontal field of view, in radians)
/// outside (0, pi) cannot make a picture.
pub(crate) fn check_camera_angle(angle: f64, span: Span) -> EvalResult<()> {
    if angle > 0.0 && angle < std::f64::consts::PI { Ok(()) } else { bad_camera_angle(angle, span) }
}

/// The error of [`check_camera_angle`]: a number from pi to 180 was most
/// likely meant in degrees.
#[cold]
#[inline(never)]
fn bad_camera_angle(angle: f64, span: Span) -> EvalResult<()> {
    let a = format_number(angle);
    let diagnostic = if field_of_view_looks_like_degrees(angle) {
        Diagnostic::error(span, format!("the camera angle {a} looks like degrees, but angles are in radians"))
            .with_code("angle-in-degrees")
            .with_label(format!("read as {a} radians, more than half a turn"))
            .with_help(in_radians_help(angle, "angle "))
    } else {
        Diagnostic::error(span, format!("the camera angle must be between 0 and pi, but it is {a}"))
            .with_code("angle-out-of-range")
            .with_label("the field of view, in radians: no picture has this one")
            .with_help("1 (about 57 degrees) is a usual field of view; a smaller angle zooms in")
    };
    fail(diagnostic)
}

/// Adds "did you mean `x`?" when a candidate is close to `name`.
pub(crate) fn with_suggestion<'a>(
    diagnostic: Diagnostic,
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Diagnostic {
    match suggest::closest(name, candidates) {
        Some(close) => {
            let span = diagnostic.span;
            diagnostic.with_help(format!("did you mean `{close}`?")).with_replacement(span, close)
        }
        None => diagnostic,
    }
}

/// "`x` is a number, but an object is needed here".
pub(crate) fn wrong_kind(span: Span, name: &str, found: &str, needed: &str) -> Diagnostic {
    Diagnostic::error(span, format!("`{name}` is {found}, but {needed} is needed here"))
        .with_code("wrong-kind")
        .with_label(format!("this is {found}"))
}

/// "`orbit` takes 3 arguments (x, y, r) but was given 2".
pub(crate) fn wrong_arity(span: Span, name: &str, params: &[&str], given: usize) -> Diagnostic {
    let takes = match params.len() {
        0 => "no arguments".to_string(),
        1 => format!("1 argument ({})", params[0]),
        n => format!("{n} arguments ({})", params.join(", ")),
    };
    Diagnostic::error(span, format!("`{name}` takes {takes} but was given {given}")).with_code("wrong-arity")
}

/// The summary of a call chain, outermost call first, each call named with
/// its place: `f (line 9) -> f (line 3) -> ... `f (line 3)` repeated 99998
/// more times`. Runs of a repeated call, or of a repeated cycle of up to four
/// calls (mutual recursion), are folded.
pub(crate) fn summarise_chain(chain: &[(Name, Span)]) -> Note {
    let calls = |calls: &[(Name, Span)]| {
        Note::joined(
            calls.iter().map(|(name, span)| Note::from(format!("{} (", shown_name(name))).place(*span).text(")")),
            " -> ",
        )
    };
    let mut parts = Vec::new();
    let mut i = 0;
    while i < chain.len() {
        match longest_cycle(chain, i) {
            Some((period, repeats)) => {
                let cycle = calls(&chain[i..i + period]);
                parts.push(cycle.clone());
                let what = if period == 1 { "`" } else { "the cycle `" };
                let folded = Note::from(format!("... {what}")).then(cycle);
                parts.push(folded.text(format!("` repeated {} more times", repeats - 1)));
                i += period * repeats;
            }
            None => {
                parts.push(calls(&chain[i..=i]));
                i += 1;
            }
        }
    }
    Note::joined(parts, " -> ")
}

/// The period (1..=4) and repeat count of the longest run of a repeated cycle
/// starting at `start`, if it repeats at least three times.
fn longest_cycle<T: PartialEq>(chain: &[T], start: usize) -> Option<(usize, usize)> {
    let mut best: Option<(usize, usize)> = None;
    for period in 1..=4 {
        let mut repeats = 1;
        while start + (repeats + 1) * period <= chain.len()
            && (0..period).all(|k| chain[start + k] == chain[start + repeats * period + k])
        {
            repeats += 1;
        }
        let covers = |(p, r): (usize, usize)| p * r;
        if repeats >= 3 && best.is_none_or(|b| covers((period, repeats)) > covers(b)) {
            best = Some((period, repeats));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::source::{SourceId, SourceMap};

    /// A call of `name` at byte `offset` of source 0.
    fn call(name: &str, offset: u32) -> (Name, Span) {
        (name.into(), Span { source: SourceId(0), start: offset, end: offset + 1 })
    }

    /// The chain as read in a diagnostic about source 0 of `map`.
    fn read(chain: &[(Name, Span)], map: &SourceMap) -> String {
        summarise_chain(chain).display(map, SourceId(0))
    }

    fn lines() -> SourceMap {
        let mut map = SourceMap::new();
        map.add("a.ray", "a\nb\nc\n", 0);
        map
    }

    #[test]
    fn repeated_calls_are_folded() {
        let mut chain = vec![call("f", 0)];
        chain.extend(std::iter::repeat_n(call("f", 2), 10));
        assert_eq!(read(&chain, &lines()), "f (line 1) -> f (line 2) -> ... `f (line 2)` repeated 9 more times");
    }

    #[test]
    fn mutual_recursion_folds_the_cycle() {
        let mut chain = vec![call("main", 0)];
        for _ in 0..5 {
            chain.push(call("even", 2));
            chain.push(call("odd", 4));
        }
        chain.push(call("even", 2));
        assert_eq!(
            read(&chain, &lines()),
            "main (line 1) -> even (line 2) -> odd (line 3) -> ... the cycle `even (line 2) -> odd (line 3)` \
             repeated 4 more times -> even (line 2)"
        );
    }

    #[test]
    fn calls_in_other_inputs_are_named_with_them() {
        let mut map = lines();
        let other = map.add("<input 2>", "f()", 0);
        let chain = vec![(Name::new("f"), Span::new(other, 0, 3)), call("g", 2)];
        assert_eq!(read(&chain, &map), "f (<input 2>:1) -> g (line 2)");
    }

    #[test]
    fn arity_messages_read_well() {
        let span = Span::default();
        assert_eq!(
            wrong_arity(span, "orbit", &["x", "y", "r"], 2).message,
            "`orbit` takes 3 arguments (x, y, r) but was given 2"
        );
        assert_eq!(wrong_arity(span, "f", &["x"], 0).message, "`f` takes 1 argument (x) but was given 0");
        assert_eq!(wrong_arity(span, "f", &[], 1).message, "`f` takes no arguments but was given 1");
    }
}
