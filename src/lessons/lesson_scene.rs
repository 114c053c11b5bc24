//! A lesson's own programs run with the language, one after another as a
//! session runs its inputs, each text a source of its own: the scene of a
//! step's goal, and the answers a lesson file is proved with.

use crate::lang::ast::Program;
use crate::lang::eval::Origins;
use crate::lang::name::Name;
use crate::lang::{Diagnostic, Interpreter, Limits, SourceMap, parse_items};
use crate::pipeline;
use crate::scene::{Primitive, Scene};

use super::learner::Learner;

/// Programs evaluated in order into one scene, with the default limits.
#[derive(Debug)]
pub(crate) struct LessonScene {
    /// The value of `time` the programs see.
    time: f64,
    interpreter: Interpreter,
    sources: SourceMap,
    /// The programs that ran and hold items, for [`LessonScene::undo`].
    programs: Vec<Program>,
}

impl LessonScene {
    /// Nothing run yet, with `time` bound to `time`.
    pub(crate) fn new(time: f64) -> LessonScene {
        LessonScene {
            time,
            interpreter: pipeline::Evaluation::at(time, Limits::default()).interpreter(),
            sources: SourceMap::new(),
            programs: Vec::new(),
        }
    }

    /// Parses and runs `text`, shown in diagnostics as `name`; on error
    /// nothing changes but the sources, which keep the text.
    pub(crate) fn run(&mut self, name: &str, text: &str) -> Result<(), Diagnostic> {
        let source = self.sources.add(name, text, 0);
        let program = parse_items(source, text)?;
        self.interpreter.run(&program)?;
        if !program.items.is_empty() {
            self.programs.push(program);
        }
        Ok(())
    }

    /// Takes back the last program that held items, running the ones
    /// before it again.
    pub(crate) fn undo(&mut self) -> Result<(), Diagnostic> {
        let Some(last) = self.programs.pop() else {
            return Ok(());
        };
        let mut interpreter = pipeline::Evaluation::at(self.time, Limits::default()).interpreter();
        if let Err(error) = self.programs.iter().try_for_each(|program| interpreter.run(program)) {
            self.programs.push(last);
            return Err(error);
        }
        self.interpreter = interpreter;
        Ok(())
    }
}

impl Learner for LessonScene {
    fn scene(&self) -> &Scene {
        self.interpreter.scene()
    }

    fn origins(&self) -> &Origins {
        self.interpreter.origins()
    }

    fn sources(&self) -> &SourceMap {
        &self.sources
    }

    fn has_camera(&self) -> bool {
        self.interpreter.has_camera()
    }

    fn has_ambient(&self) -> bool {
        self.interpreter.has_ambient()
    }

    fn numbers(&self) -> Vec<(Name, f64)> {
        let names = self.interpreter.global_names();
        names.into_iter().filter_map(|name| Some((name, self.interpreter.global_number(&name)?))).collect()
    }

    fn object_names(&self) -> Vec<Name> {
        let names = self.interpreter.global_names();
        names.into_iter().filter(|name| self.interpreter.global_object(name).is_some()).collect()
    }

    fn object(&self, name: &str) -> Option<&[Primitive]> {
        self.interpreter.global_object(name)
    }

    fn procedures(&self) -> Vec<(Name, usize)> {
        let names = self.interpreter.procedure_names();
        let parameters = |name: &Name| Some(self.interpreter.procedure(name)?.params.len());
        names.into_iter().filter_map(|name| Some((name, parameters(&name)?))).collect()
    }
}
