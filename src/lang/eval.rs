//! Evaluation (SPEC 3 and 4): environments, procedures, and building the scene.

use super::ast::Program;
use super::diagnostic::Diagnostic;
use crate::scene::Scene;

/// Resource limits that turn runaway programs into clear errors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Deepest chain of procedure calls allowed (default 100,000).
    pub max_call_depth: usize,
    /// Most primitives a program may create, in objects and in the scene (default 50 million).
    pub max_primitives: usize,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits { max_call_depth: 100_000, max_primitives: 50_000_000 }
    }
}

/// Runs programs against one global environment and accumulates a scene.
///
/// A file is one `run`; the interactive session calls `run` once per input.
/// A `run` that fails leaves the interpreter exactly as it was (SPEC 7).
#[derive(Debug)]
pub struct Interpreter {
    scene: Scene,
}

impl Interpreter {
    /// A fresh interpreter evaluating with `time` bound to the given value.
    pub fn new(time: f64, limits: Limits) -> Interpreter {
        let _ = (time, limits);
        todo!()
    }

    /// Runs every item of `program`; on error the interpreter is unchanged.
    pub fn run(&mut self, program: &Program) -> Result<(), Diagnostic> {
        let _ = program;
        todo!()
    }

    /// The warnings (clamped colours, ...) raised since the last call.
    pub fn take_warnings(&mut self) -> Vec<Diagnostic> {
        todo!()
    }

    /// The scene built so far.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The scene built so far, by value.
    pub fn into_scene(self) -> Scene {
        self.scene
    }
}
