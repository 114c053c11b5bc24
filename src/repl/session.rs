//! The state of a session (SPEC 7): one interpreter whose global environment
//! and scene accumulate across inputs, the source texts, and the history of
//! accepted inputs that `:undo` and `:time` replay.

use std::rc::Rc;

use crate::lang::ast::Program;
use crate::lang::{Diagnostic, Interpreter, Limits, SourceMap, parse_items};
use crate::scene::Scene;

use super::defined::Defined;
use super::facts;
use super::rendering::RenderSettings;

/// One accepted input, kept so the session can be rebuilt without it.
#[derive(Debug, Clone)]
pub(crate) struct Input {
    /// The text as typed (or the file's name, for `:load`), for `:undo`'s message.
    pub text: String,
    /// The parsed items.
    pub program: Rc<Program>,
    /// Whether it reads `time` (then a change of time must evaluate it again).
    pub reads_time: bool,
}

/// What `:undo` takes back.
#[derive(Debug, Clone)]
enum UndoStep {
    /// The last accepted input.
    Input,
    /// A `:reset`, with the history it cleared.
    Reset(Vec<Input>),
}

/// What an accepted input did, for the confirmation printed after it.
#[derive(Debug, Clone, Default)]
pub(crate) struct Accepted {
    /// The parsed items.
    pub program: Rc<Program>,
    /// Warnings the interpreter raised (clamped colours, ...).
    pub warnings: Vec<Diagnostic>,
    /// What was defined before the input (to tell new names from redefined ones).
    pub defined_before: Defined,
    /// The scene before the input.
    pub scene_before: Census,
}

/// What `:undo` did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Undone {
    /// There was nothing to take back.
    Nothing,
    /// The input with this text was taken back.
    Input(String),
    /// A `:reset` was taken back: this many inputs are back.
    Reset(usize),
}

/// Counts of what a scene holds, to report changes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Census {
    /// Spheres put.
    pub spheres: usize,
    /// Planes put.
    pub planes: usize,
    /// Boxes put.
    pub boxes: usize,
    /// Lights.
    pub lights: usize,
}

impl Census {
    /// Counts the primitives and lights of `scene`.
    pub(crate) fn of(scene: &Scene) -> Census {
        use crate::scene::Shape;
        let mut census = Census {
            lights: scene.lights.len(),
            ..Census::default()
        };
        for primitive in scene.all_primitives() {
            match primitive.shape {
                Shape::Sphere { .. } => census.spheres += 1,
                Shape::Plane { .. } => census.planes += 1,
                Shape::Box { .. } => census.boxes += 1,
            }
        }
        census
    }

    /// All primitives.
    pub(crate) fn objects(&self) -> usize {
        self.spheres + self.planes + self.boxes
    }
}

/// An interactive session or a script run: everything that accumulates.
#[derive(Debug)]
pub struct Session {
    interpreter: Interpreter,
    /// The time `interpreter` was created with; it differs from
    /// `settings.time` after a `:time` that needed no replay, until an input
    /// that reads `time` arrives.
    interpreter_time: f64,
    sources: SourceMap,
    history: Vec<Input>,
    undo_steps: Vec<UndoStep>,
    defined: Defined,
    settings: RenderSettings,
    limits: Limits,
}

impl Session {
    /// An empty session rendering with `settings`.
    pub fn new(settings: RenderSettings, limits: Limits) -> Session {
        Session {
            interpreter: Interpreter::new(settings.time, limits),
            interpreter_time: settings.time,
            sources: SourceMap::new(),
            history: Vec::new(),
            undo_steps: Vec::new(),
            defined: Defined::new(settings.time),
            settings,
            limits,
        }
    }

    /// Parses and runs one input. `name` is shown in diagnostics and
    /// `line_offset` is the number of lines before it in its script (SPEC 7:
    /// on error the session is unchanged).
    pub(crate) fn submit(
        &mut self,
        name: &str,
        text: &str,
        line_offset: usize,
    ) -> Result<Accepted, Diagnostic> {
        let source = self.sources.add(name, text, line_offset);
        let program = parse_items(source, text)?;
        self.run(text.to_string(), program)
    }

    /// Runs an already parsed input and records it in the history.
    fn run(&mut self, text: String, program: Program) -> Result<Accepted, Diagnostic> {
        let reads_time = facts::reads_time(&program);
        if reads_time && self.interpreter_time != self.settings.time {
            self.rebuild(self.history.clone())?;
        }
        let scene_before = Census::of(self.interpreter.scene());
        if let Err(error) = self.interpreter.run(&program) {
            self.interpreter.take_warnings();
            return Err(error);
        }
        let warnings = self.interpreter.take_warnings();
        let defined_before = self.defined.clone();
        self.defined.record(&program);
        let program = Rc::new(program);
        if !program.items.is_empty() {
            self.history.push(Input {
                text,
                program: Rc::clone(&program),
                reads_time,
            });
            self.undo_steps.push(UndoStep::Input);
        }
        Ok(Accepted {
            program,
            warnings,
            defined_before,
            scene_before,
        })
    }

    /// Runs the text of a file, all of it as one input (its items in any order).
    pub(crate) fn load(&mut self, name: &str, text: &str) -> Result<Accepted, Diagnostic> {
        let source = self.sources.add(name, text, 0);
        let program = parse_items(source, text)?;
        self.run(format!(":load {name}"), program)
    }

    /// Takes back the last input, or the last `:reset`.
    pub(crate) fn undo(&mut self) -> Result<Undone, Diagnostic> {
        let Some(step) = self.undo_steps.pop() else {
            return Ok(Undone::Nothing);
        };
        let mut history = self.history.clone();
        let undone = match &step {
            UndoStep::Input => {
                Undone::Input(history.pop().map(|input| input.text).unwrap_or_default())
            }
            UndoStep::Reset(cleared) => {
                history = cleared.clone();
                Undone::Reset(history.len())
            }
        };
        if let Err(error) = self.rebuild(history) {
            self.undo_steps.push(step);
            return Err(error);
        }
        Ok(undone)
    }

    /// Forgets every input; `:undo` brings them back.
    pub(crate) fn reset(&mut self) {
        let cleared = std::mem::take(&mut self.history);
        self.interpreter = Interpreter::new(self.settings.time, self.limits);
        self.interpreter_time = self.settings.time;
        self.defined = Defined::new(self.settings.time);
        self.undo_steps.push(UndoStep::Reset(cleared));
    }

    /// Sets `time`. Inputs that read it are evaluated again at once; if one
    /// of them fails at the new time, nothing changes. Returns how many
    /// inputs read `time`.
    pub(crate) fn set_time(&mut self, time: f64) -> Result<usize, Diagnostic> {
        let readers = self.history.iter().filter(|input| input.reads_time).count();
        let previous = self.settings.time;
        self.settings.time = time;
        if readers > 0 {
            if let Err(error) = self.rebuild(self.history.clone()) {
                self.settings.time = previous;
                return Err(error);
            }
        } else {
            self.defined = self.defined_at(time);
        }
        Ok(readers)
    }

    /// The scene as it would be at `time`, leaving the session as it is.
    pub(crate) fn scene_at(&self, time: f64) -> Result<Scene, Diagnostic> {
        if !self.history.iter().any(|input| input.reads_time) {
            return Ok(self.interpreter.scene().clone());
        }
        Ok(self.replay(time, &self.history)?.into_scene())
    }

    /// Whether any accepted input reads `time`.
    pub(crate) fn depends_on_time(&self) -> bool {
        self.history.iter().any(|input| input.reads_time)
    }

    /// Replaces the interpreter by one that ran `history` at the current time.
    fn rebuild(&mut self, history: Vec<Input>) -> Result<(), Diagnostic> {
        let time = self.settings.time;
        self.interpreter = self.replay(time, &history)?;
        self.interpreter_time = time;
        self.history = history;
        self.defined = self.defined_at(time);
        Ok(())
    }

    /// A fresh interpreter that ran `history` at `time`.
    fn replay(&self, time: f64, history: &[Input]) -> Result<Interpreter, Diagnostic> {
        let mut interpreter = Interpreter::new(time, self.limits);
        for input in history {
            interpreter.run(&input.program)?;
        }
        interpreter.take_warnings();
        Ok(interpreter)
    }

    /// What the history defines at `time`.
    fn defined_at(&self, time: f64) -> Defined {
        let mut defined = Defined::new(time);
        for input in &self.history {
            defined.record(&input.program);
        }
        defined
    }

    /// The scene built so far.
    pub fn scene(&self) -> &Scene {
        self.interpreter.scene()
    }

    /// The source texts seen so far, to render diagnostics.
    pub fn sources(&self) -> &SourceMap {
        &self.sources
    }

    /// The names and procedures defined so far.
    pub fn defined(&self) -> &Defined {
        &self.defined
    }

    /// The render settings.
    pub fn settings(&self) -> &RenderSettings {
        &self.settings
    }

    /// Sets the size of the images `:save` and `:anim` write.
    pub(crate) fn set_size(&mut self, width: u32, height: u32) {
        self.settings.width = width;
        self.settings.height = height;
    }

    /// Sets how many reflections are followed.
    pub(crate) fn set_depth(&mut self, depth: u32) {
        self.settings.depth = depth;
    }

    /// Sets how many rays each pixel averages.
    pub(crate) fn set_samples(&mut self, samples: u32) {
        self.settings.samples = samples;
    }

    /// How many accepted inputs the session holds.
    pub fn history_len(&self) -> usize {
        self.history.len()
    }

    /// Whether an accepted input set the camera (otherwise the default is used).
    pub(crate) fn camera_given(&self) -> bool {
        self.history
            .iter()
            .any(|input| facts::sets_camera(&input.program))
    }

    /// Whether an accepted input set the ambient light.
    pub(crate) fn ambient_given(&self) -> bool {
        self.history
            .iter()
            .any(|input| facts::sets_ambient(&input.program))
    }
}
