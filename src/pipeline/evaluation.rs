//! A program evaluated and its scene checked, as every front-end does it.
//!
//! The front-ends differ on purpose in these ways, each a field of
//! [`Evaluation`]:
//!
//! | front-end | `time` | `cancel` | `lint` | `skip_static` |
//! |---|---|---|---|---|
//! | batch renderer (`app`) | `--time`, or each frame's | Ctrl-C, `kill` | the picture asked for, `--allow` | an animation's later frames |
//! | session (terminal, scripts, notebook, page) | `:time` | Ctrl-C, the kernel's interrupt | the picture `:render` makes, `--allow` | replays of later frames |
//! | language server | 0 | its time budget | the command line's default picture | never |
//! | grader (`compare`) | each graded frame's | none (its own limits) | none: it compares scenes, and says how they differ | never |
//!
//! The session evaluates input by input into one interpreter, so it takes
//! the interpreter ([`Evaluation::interpreter`]) and the scene's warnings
//! ([`scene_warnings`]) from here rather than [`Evaluation::run`].

use std::sync::atomic::AtomicBool;

use crate::lang::ast::Program;
use crate::lang::{Diagnostic, Interpreter, Limits};
use crate::lint::{Allowed, Picture, check_scene};

/// How a program is evaluated and its scene checked: the parameters where
/// front-ends differ (see the module's table).
#[derive(Debug, Clone, Copy)]
pub struct Evaluation {
    /// The value of `time`.
    pub time: f64,
    /// The limits on procedure calls and primitives.
    pub limits: Limits,
    /// Raised to stop the evaluation at its next procedure call (Ctrl-C,
    /// the kernel's interrupt, the language server's time budget); `None`
    /// where nothing stops it.
    pub cancel: Option<&'static AtomicBool>,
    /// What the scene's warnings are judged against, or `None` for no
    /// warnings about the scene (the program's own warnings stay).
    pub lint: Option<Lint>,
    /// Whether primitives that do not depend on `time` are left out (an
    /// animation's later frames reuse the first frame's).
    pub skip_static: bool,
}

/// The picture a scene's warnings are judged for, and the warnings turned
/// off (`--allow`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Lint {
    /// How the scene is about to be rendered.
    pub picture: Picture,
    /// The checks turned off.
    pub allowed: Allowed,
}

/// A program evaluated: its interpreter (the scene, where each part of it
/// comes from, what `print` wrote), whether it ran, and its warnings.
pub struct Evaluated {
    /// The interpreter after the run.
    pub interpreter: Interpreter,
    /// The program's error, if it stopped on one.
    pub result: Result<(), Diagnostic>,
    /// The program's warnings, then (if it ran) those about its scene.
    pub warnings: Vec<Diagnostic>,
}

impl Evaluation {
    /// The evaluation at `time` within `limits`, with no cancel flag, no
    /// warnings about the scene and every primitive kept.
    pub fn at(time: f64, limits: Limits) -> Evaluation {
        Evaluation { time, limits, cancel: None, lint: None, skip_static: false }
    }

    /// An interpreter set up as this evaluation says, for a program run
    /// later ([`Evaluation::run_on`]) or input by input (the session).
    pub fn interpreter(&self) -> Interpreter {
        let interpreter = Interpreter::new(self.time, self.limits).skip_static(self.skip_static);
        match self.cancel {
            Some(flag) => interpreter.interruptible(flag),
            None => interpreter,
        }
    }

    /// Runs `program` on a new interpreter ([`Evaluation::interpreter`]).
    pub fn run(&self, program: &Program) -> Evaluated {
        self.run_on(self.interpreter(), program)
    }

    /// Runs `program` on `interpreter` (one set up by
    /// [`Evaluation::interpreter`], perhaps recording more), then checks
    /// its scene if it ran and this evaluation lints.
    pub fn run_on(&self, mut interpreter: Interpreter, program: &Program) -> Evaluated {
        let result = interpreter.run(program);
        let mut warnings = interpreter.take_warnings();
        if let (Ok(()), Some(lint)) = (&result, &self.lint) {
            warnings.extend(scene_warnings(&interpreter, lint));
        }
        Evaluated { interpreter, result, warnings }
    }
}

/// The warnings about the scene `interpreter` built, judged as `lint` says.
pub fn scene_warnings(interpreter: &Interpreter, lint: &Lint) -> Vec<Diagnostic> {
    let warnings = check_scene(interpreter.scene(), interpreter.origins(), &lint.picture, lint.allowed);
    warnings.into_iter().map(|warning| warning.diagnostic).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::{SourceMap, parse_file};
    use crate::render::Screen;

    /// `text` parsed as a file.
    fn program(text: &str) -> Program {
        let mut sources = SourceMap::new();
        let id = sources.add("test.ray".to_owned(), text.to_owned(), 0);
        parse_file(id, text).expect("parses")
    }

    const PICTURE: Picture = Picture { width: 800, height: 600, screen: Screen::Centered, animation: false };

    /// A scene whose camera is inside a sphere: a warning about the scene.
    const INSIDE: &str = "camera distance 0.5 angle 1 end\nambient 0.2\nput sphere center 0, 0, 0 radius 2 kd 0.8 ks 0 phong 1 color 200, 0, 0 end\nlet t = time\n";

    #[test]
    fn the_scene_is_checked_only_when_asked_and_only_when_it_ran() {
        let linted = Evaluation {
            lint: Some(Lint { picture: PICTURE, allowed: Allowed::default() }),
            ..Evaluation::at(2.0, Limits::DEFAULT)
        };
        let evaluated = linted.run(&program(INSIDE));
        assert!(evaluated.result.is_ok());
        assert_eq!(evaluated.interpreter.global_number("t"), Some(2.0));
        assert!(!evaluated.warnings.is_empty(), "the camera inside a sphere is said");
        let unlinted = Evaluation::at(2.0, Limits::DEFAULT).run(&program(INSIDE));
        assert!(unlinted.warnings.is_empty());
        let failing = linted.run(&program(&format!(
            "{INSIDE}put sphere center 0, 0, 0 radius -1 kd 0.8 ks 0 phong 1 color 200, 0, 0 end\n"
        )));
        assert!(failing.result.is_err());
        assert!(failing.warnings.is_empty(), "a scene that did not run is not judged");
    }

    #[test]
    fn a_raised_flag_stops_the_evaluation() {
        static RAISED: AtomicBool = AtomicBool::new(true);
        let stopped = Evaluation { cancel: Some(&RAISED), ..Evaluation::at(0.0, Limits::DEFAULT) };
        let evaluated = stopped.run(&program("camera distance 10 angle 1 end\nambient 0.2\nproc f(n) put sphere center 0, 0, 0 radius 1 kd 0.8 ks 0 phong 1 color 9, 9, 9 end end\nf(1)\n"));
        assert!(evaluated.result.is_err());
    }
}
