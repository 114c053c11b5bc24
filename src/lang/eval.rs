//! Evaluation (SPEC 3 and 4): environments, procedures, and building the scene.
//!
//! The [`Interpreter`] walks the AST directly. Values are numbers and objects;
//! an object is a shared list of primitives with every transformation already
//! baked in, so the scene it builds is flat.
//!
//! Two things ride along with every value:
//!
//! - a *taint* bit, set when the value depends on `time`. `time` is tainted,
//!   an operation is tainted when an operand is, and everything an `if` with a
//!   tainted condition produces is tainted. A `put` of a tainted object goes to
//!   [`Scene::timed_primitives`], the rest to [`Scene::primitives`], so an
//!   animation can build the static part of the scene once;
//! - atomicity: [`Interpreter::run`] either succeeds or leaves the interpreter
//!   exactly as it was, which is what an interactive session needs (SPEC 7).
//!   It is cheap: the maps of names are small and hold shared values, so they
//!   are cloned; the scene's vectors only grow during a run, so their lengths
//!   are recorded and they are truncated back on error.

mod env;
mod errors;
mod expr;
mod instr;
mod object;
mod value;

use std::collections::HashSet;
use std::rc::Rc;

use glam::{DMat3, DVec3};

use env::{Env, NameMap};
use errors::{EvalResult, summarise_chain};
use value::{Kind, Value};

use super::ast::{Item, ProcDef, Program};
use super::diagnostic::Diagnostic;
use super::source::{SourceMap, Span};
use crate::scene::transform::rotated_up;
use crate::scene::{Camera, Light, Primitive, Scene, TimeUse};

/// The camera used before a program defines one.
pub const DEFAULT_CAMERA: Camera = Camera { distance: 10.0, angle: 1.0 };

/// The ambient intensity used before a program defines one.
pub const DEFAULT_AMBIENT: f64 = 0.2;

/// Free native stack below which a nested evaluation switches to a new segment.
const RED_ZONE: usize = 256 * 1024;

/// Size of each new native stack segment.
const STACK_SEGMENT: usize = 8 * 1024 * 1024;

/// Runs `f` on a fresh stack segment if the current one is nearly full, so
/// deep recursion in the program (or deeply nested expressions) never
/// overflows the native stack.
fn grow<R>(f: impl FnOnce() -> R) -> R {
    stacker::maybe_grow(RED_ZONE, STACK_SEGMENT, f)
}

/// Resource limits that turn runaway programs into clear errors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Deepest chain of procedure calls allowed.
    pub max_call_depth: usize,
    /// Most primitives a program may create, in objects and in the scene.
    pub max_primitives: usize,
}

impl Limits {
    /// The limits of every entry point unless the user raises them. The
    /// primitive limit is set so that a scene at the limit can also be
    /// rendered (the scene and its BVH) within a 24 GB machine, with room to
    /// spare; the README gives the memory it takes.
    pub const DEFAULT: Limits = Limits { max_call_depth: 100_000, max_primitives: 10_000_000 };
}

impl Default for Limits {
    fn default() -> Limits {
        Limits::DEFAULT
    }
}

/// Runs programs against one global environment and accumulates a scene.
///
/// A file is one `run`; the interactive session calls `run` once per input.
/// A `run` that fails leaves the interpreter exactly as it was (SPEC 7).
#[derive(Debug)]
pub struct Interpreter {
    /// The scene built so far.
    scene: Scene,
    limits: Limits,
    /// Globals and the locals of active calls.
    env: Env,
    /// Procedures by name; a redefinition replaces.
    procs: NameMap<Rc<ProcDef>>,
    has_camera: bool,
    has_ambient: bool,
    /// Warnings not yet taken.
    warnings: Vec<Diagnostic>,
    /// Spans already warned about: a spot warns once, however often it runs.
    warned: HashSet<Span>,
    /// Whether to drop static primitives (later frames of an animation).
    skip_static: bool,
    /// Primitives created so far, against `limits.max_primitives`.
    created: usize,
    /// Whether the instructions running now depend on `time` (inside an `if`
    /// whose condition does).
    context_tainted: bool,
    /// How many procedure calls are active.
    depth: usize,
    /// The procedure the last call found, to skip the hash lookup when the
    /// same procedure is called again (as recursion does). Cleared whenever
    /// the procedures change.
    last_proc: Option<Rc<ProcDef>>,
    /// The last rotation computed, with its angles (see `rotation`).
    last_rotation: (DVec3, DMat3),
    /// A reusable buffer for building `object` values.
    scratch: Vec<Primitive>,
}

/// What a failed run restores.
struct Snapshot {
    globals: NameMap<Value>,
    procs: NameMap<Rc<ProcDef>>,
    camera: Camera,
    ambient: f64,
    has_camera: bool,
    has_ambient: bool,
    time_use: TimeUse,
    created: usize,
    lights: usize,
    primitives: usize,
    timed_primitives: usize,
    warnings: usize,
}

impl Interpreter {
    /// A fresh interpreter evaluating with `time` bound to the given value.
    /// Every number a program sees is finite, so a non-finite `time` is taken
    /// as 0 (the command line should refuse one).
    pub fn new(time: f64, limits: Limits) -> Interpreter {
        let time = if time.is_finite() { time } else { 0.0 };
        let mut env = Env::default();
        env.globals.insert("time".into(), Value::number(time, true));
        Interpreter {
            scene: Scene {
                camera: DEFAULT_CAMERA,
                ambient: DEFAULT_AMBIENT,
                lights: Vec::new(),
                primitives: Vec::new(),
                timed_primitives: Vec::new(),
                time_use: TimeUse::default(),
            },
            limits,
            env,
            procs: NameMap::default(),
            has_camera: false,
            has_ambient: false,
            warnings: Vec::new(),
            warned: HashSet::new(),
            skip_static: false,
            created: 0,
            context_tainted: false,
            depth: 0,
            last_proc: None,
            last_rotation: (DVec3::ZERO, DMat3::IDENTITY),
            scratch: Vec::new(),
        }
    }

    /// Whether to leave out the primitives that do not depend on `time`.
    ///
    /// An animation builds its first frame normally and keeps its static
    /// primitives (and their BVH); later frames re-run the program with this
    /// set, so they only hold the timed primitives.
    pub fn skip_static(mut self, skip: bool) -> Interpreter {
        self.skip_static = skip;
        self
    }

    /// Runs every item of `program`; on error the interpreter is unchanged.
    pub fn run(&mut self, program: &Program) -> Result<(), Diagnostic> {
        self.run_inner(program, None)
    }

    /// Like [`Interpreter::run`], but a recursion error's call chain names the
    /// line of each call, read from `sources`.
    pub fn run_with_sources(&mut self, program: &Program, sources: &SourceMap) -> Result<(), Diagnostic> {
        self.run_inner(program, Some(sources))
    }

    /// The warnings (clamped colours, ...) raised since the last call.
    pub fn take_warnings(&mut self) -> Vec<Diagnostic> {
        std::mem::take(&mut self.warnings)
    }

    /// The scene built so far.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The scene built so far, by value.
    pub fn into_scene(self) -> Scene {
        self.scene
    }

    /// Whether a `camera` was given (otherwise [`DEFAULT_CAMERA`] is used).
    pub fn has_camera(&self) -> bool {
        self.has_camera
    }

    /// Whether an `ambient` was given (otherwise [`DEFAULT_AMBIENT`] is used).
    pub fn has_ambient(&self) -> bool {
        self.has_ambient
    }

    /// Whether evaluation read `time` at all. When it did not, every frame of
    /// an animation is the same picture.
    pub fn has_time_reads(&self) -> bool {
        self.scene.time_use.read
    }

    /// The limits this interpreter enforces.
    pub fn limits(&self) -> Limits {
        self.limits
    }

    /// The names of the defined procedures, sorted (for completion and `:help`).
    pub fn procedure_names(&self) -> Vec<Rc<str>> {
        sorted(self.procs.keys())
    }

    /// The names of the global variables, sorted (for completion).
    pub fn global_names(&self) -> Vec<Rc<str>> {
        sorted(self.env.globals.keys())
    }

    /// The definition of a procedure, if there is one by that name.
    pub fn procedure(&self, name: &str) -> Option<&ProcDef> {
        self.procs.get(name).map(|p| &**p)
    }

    /// The value of a global number variable, if `name` holds a number.
    pub fn global_number(&self, name: &str) -> Option<f64> {
        match self.env.globals.get(name)?.kind {
            Kind::Number(value) => Some(value),
            Kind::Object(_) => None,
        }
    }

    /// How many primitives a global object variable holds, if `name` holds an object.
    pub fn global_object_size(&self, name: &str) -> Option<usize> {
        match &self.env.globals.get(name)?.kind {
            Kind::Object(primitives) => Some(primitives.len()),
            Kind::Number(_) => None,
        }
    }

    /// Runs the items; on error, restores the snapshot and explains the error.
    fn run_inner(&mut self, program: &Program, sources: Option<&SourceMap>) -> Result<(), Diagnostic> {
        let snapshot = self.snapshot();
        self.created = self.live_primitives();
        let result = program.items.iter().try_for_each(|item| self.run_item(item));
        self.env.reset_locals();
        self.depth = 0;
        self.context_tainted = false;
        result.map_err(|error| {
            self.restore(snapshot);
            let mut diagnostic = error.diagnostic;
            if !error.chain.is_empty() {
                // Collected while unwinding, innermost first.
                let chain: Vec<_> = error.chain.into_iter().rev().collect();
                diagnostic = diagnostic.with_note(format!("call chain: {}", summarise_chain(&chain, sources)));
            }
            diagnostic
        })
    }

    /// Runs one top-level item.
    fn run_item(&mut self, item: &Item) -> EvalResult<()> {
        match item {
            Item::Camera(def) => {
                let distance = self.eval_expr(&def.distance)?;
                let angle = self.eval_expr(&def.angle)?;
                self.scene.camera = Camera { distance: distance.value, angle: angle.value };
                self.scene.time_use.camera = distance.tainted | angle.tainted;
                self.has_camera = true;
            }
            Item::Ambient(def) => {
                let ambient = self.eval_expr(&def.intensity)?;
                self.scene.ambient = ambient.value;
                self.scene.time_use.ambient = ambient.tainted;
                self.has_ambient = true;
            }
            Item::Light(def) => {
                let (angles, rotation_tainted) = self.eval_triple(&def.rotation)?;
                let intensity = self.eval_expr(&def.intensity)?;
                let direction = rotated_up(&self.rotation(angles));
                self.scene.lights.push(Light { direction, intensity: intensity.value });
                self.scene.time_use.lights |= rotation_tainted | intensity.tainted | self.context_tainted;
            }
            Item::Proc(def) => {
                self.procs.insert(def.name.name.clone(), def.clone());
                self.last_proc = None;
            }
            Item::Instr(instr) => self.exec(instr)?,
        }
        Ok(())
    }

    /// Records a warning, once per source spot.
    fn warn(&mut self, span: Span, message: String) {
        if self.warned.insert(span) {
            self.warnings.push(Diagnostic::warning(span, message));
        }
    }

    /// Primitives alive now: in the scene and in global objects.
    fn live_primitives(&self) -> usize {
        let in_objects: usize = self
            .env
            .globals
            .values()
            .map(|v| match &v.kind {
                Kind::Object(primitives) => primitives.len(),
                Kind::Number(_) => 0,
            })
            .sum();
        self.scene.primitives.len() + self.scene.timed_primitives.len() + in_objects
    }

    fn snapshot(&self) -> Snapshot {
        Snapshot {
            globals: self.env.globals.clone(),
            procs: self.procs.clone(),
            camera: self.scene.camera,
            ambient: self.scene.ambient,
            has_camera: self.has_camera,
            has_ambient: self.has_ambient,
            time_use: self.scene.time_use,
            created: self.created,
            lights: self.scene.lights.len(),
            primitives: self.scene.primitives.len(),
            timed_primitives: self.scene.timed_primitives.len(),
            warnings: self.warnings.len(),
        }
    }

    fn restore(&mut self, snapshot: Snapshot) {
        self.env.globals = snapshot.globals;
        self.procs = snapshot.procs;
        self.last_proc = None;
        self.scene.camera = snapshot.camera;
        self.scene.ambient = snapshot.ambient;
        self.has_camera = snapshot.has_camera;
        self.has_ambient = snapshot.has_ambient;
        self.scene.time_use = snapshot.time_use;
        self.created = snapshot.created;
        self.scene.lights.truncate(snapshot.lights);
        self.scene.primitives.truncate(snapshot.primitives);
        self.scene.timed_primitives.truncate(snapshot.timed_primitives);
        for warning in self.warnings.drain(snapshot.warnings..) {
            self.warned.remove(&warning.span);
        }
    }
}

/// The names, sorted.
fn sorted<'a>(names: impl Iterator<Item = &'a Rc<str>>) -> Vec<Rc<str>> {
    let mut names: Vec<Rc<str>> = names.cloned().collect();
    names.sort();
    names
}
