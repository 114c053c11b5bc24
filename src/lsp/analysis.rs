//! What the server knows of one version of a document: its program and
//! names if it parses, and every diagnostic the command line's `--check`
//! gives for it (the parse error, or the evaluation's error and warnings,
//! then the warnings about the scene), evaluated at `time` 0.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use crate::lang::ast::Program;
use crate::lang::names::Names;
use crate::lang::{Diagnostic, Interpreter, Limits, SourceId, SourceMap, parse_file};
use crate::lint::{Allowed, Picture};
use crate::pipeline::{self, Evaluated, Lint};
use crate::settings::DEFAULTS;

/// How long an evaluation may take before it is stopped: the diagnostics
/// of a keystroke must not wait for a runaway recursion.
pub(crate) const EVALUATION_BUDGET: Duration = Duration::from_secs(2);

/// Raised when an evaluation has run past [`EVALUATION_BUDGET`]. The server
/// evaluates one document at a time, so one flag serves them all.
static EVALUATION_STOPPED: AtomicBool = AtomicBool::new(false);

/// One version of a document, analysed.
pub(crate) struct Analysis {
    /// The document's text, as the only source.
    pub(crate) sources: SourceMap,
    /// The program, if the text parses.
    pub(crate) program: Option<Program>,
    /// The program's names (none if it does not parse).
    pub(crate) names: Names,
    /// The errors and warnings, as the command line gives them.
    pub(crate) diagnostics: Vec<Diagnostic>,
    /// How the evaluation at time 0 went.
    pub(crate) evaluation: Evaluation,
}

/// How the evaluation at time 0 went.
pub(crate) enum Evaluation {
    /// Not tried: the text does not parse.
    NotRun,
    /// It ran to its end (or to its error): the globals at its end.
    Done(Box<Interpreter>),
    /// It ran past [`EVALUATION_BUDGET`] and was stopped.
    TooLong,
}

impl Analysis {
    /// Analyses `text`, named `name` in diagnostics.
    pub(crate) fn of(name: &str, text: &str) -> Analysis {
        let mut sources = SourceMap::new();
        let id: SourceId = sources.add(name, text.to_string(), 0);
        let program = match parse_file(id, text) {
            Ok(program) => program,
            Err(diagnostic) => {
                let diagnostics = vec![diagnostic];
                return Analysis {
                    sources,
                    program: None,
                    names: Names::default(),
                    diagnostics,
                    evaluation: Evaluation::NotRun,
                };
            }
        };
        let names = Names::of(&program);
        let (evaluation, diagnostics) = evaluate(&program);
        Analysis { sources, program: Some(program), names, diagnostics, evaluation }
    }

    /// The evaluation's interpreter, if it ran.
    pub(crate) fn interpreter(&self) -> Option<&Interpreter> {
        match &self.evaluation {
            Evaluation::Done(interpreter) => Some(interpreter),
            Evaluation::NotRun | Evaluation::TooLong => None,
        }
    }
}

/// How the server evaluates a document: as the command line renders it by
/// default (its time, limits and picture, so that the warnings are the
/// command line's), stopped when it runs past [`EVALUATION_BUDGET`].
fn as_the_command_line() -> pipeline::Evaluation {
    let picture = Picture { width: DEFAULTS.width, height: DEFAULTS.height, screen: DEFAULTS.screen, animation: false };
    pipeline::Evaluation {
        time: DEFAULTS.time,
        limits: Limits::default(),
        cancel: Some(&EVALUATION_STOPPED),
        lint: Some(Lint { picture, allowed: Allowed::default() }),
        skip_static: false,
    }
}

/// Evaluates `program` at time 0 within [`EVALUATION_BUDGET`]: its
/// warnings, its error if any, and the warnings about the scene as the
/// command line renders it at its default size.
fn evaluate(program: &Program) -> (Evaluation, Vec<Diagnostic>) {
    EVALUATION_STOPPED.store(false, Ordering::Relaxed);
    let (finished, watched) = mpsc::channel::<()>();
    let watchdog = std::thread::spawn(move || {
        if watched.recv_timeout(EVALUATION_BUDGET) == Err(mpsc::RecvTimeoutError::Timeout) {
            EVALUATION_STOPPED.store(true, Ordering::Relaxed);
        }
    });
    let Evaluated { interpreter, result, warnings: mut diagnostics } = as_the_command_line().run(program);
    drop(finished);
    let _ = watchdog.join();
    match result {
        Err(_) if EVALUATION_STOPPED.load(Ordering::Relaxed) => return (Evaluation::TooLong, diagnostics),
        Err(error) => diagnostics.push(error),
        Ok(()) => {}
    }
    (Evaluation::Done(Box::new(interpreter)), diagnostics)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_runaway_recursion_is_stopped_and_said() {
        let text =
            "camera distance 10 angle 1 end\nambient 0.2\nproc f(n) if n > 0 then f(n - 1) f(n - 1) end end\nf(60)\n";
        let analysis = Analysis::of("runaway.ray", text);
        assert!(matches!(analysis.evaluation, Evaluation::TooLong), "{:?}", analysis.diagnostics);
        let quick = Analysis::of("quick.ray", "camera distance 10 angle 1 end\nambient 0.2\nlet r = 2\n");
        assert_eq!(quick.interpreter().and_then(|interpreter| interpreter.global_number("r")), Some(2.0));
    }
}
