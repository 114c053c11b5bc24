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
//!   It is cheap: each change a run makes to a map of names (globals,
//!   procedures) is journaled with the value it replaced, and a failed run
//!   undoes the journal newest first; the scene's vectors only grow during a
//!   run, so their lengths are recorded and they are truncated back.

mod env;
mod errors;
mod expr;
mod instr;
mod object;
mod origins;
mod print;
mod stack;
mod value;

use std::collections::HashSet;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use glam::{DMat3, DVec3};

use env::{Env, NameMap};
use errors::{EvalResult, summarise_chain};
use value::{Kind, Value};

pub use origins::{
    Call, CameraOrigin, DegreesOrigin, LightOrigin, ObjectDefinition, ObjectDefinitions, Origins, PutCalls, PutSpans,
    Turned,
};
pub use print::{PRINT_LIMIT, PrintLine, PrintLog};

use super::ast::{Item, ProcDef, Program};
use super::diagnostic::{Diagnostic, Note};
use super::name::Name;
use super::source::Span;
use crate::scene::transform::rotated_up;
use crate::scene::{Camera, Light, Primitive, Scene, TimeUse};

/// The camera used before a program defines one.
pub const DEFAULT_CAMERA: Camera = Camera { distance: 10.0, angle: 1.0 };

/// The ambient intensity used before a program defines one.
pub const DEFAULT_AMBIENT: f64 = 0.2;

/// Resource limits that turn runaway programs into clear errors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Deepest chain of procedure calls allowed.
    pub max_call_depth: usize,
    /// Most primitives a program may create, in objects and in the scene.
    pub max_primitives: usize,
    /// How the user raises these limits, for the help of the errors they cause.
    pub raised_with: RaisedWith,
}

/// Where the limits are set: flags on the command line, or commands in the
/// interactive session (where a flag cannot be given any more).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RaisedWith {
    /// `--max-calls N`, `--max-primitives N`.
    Flags,
    /// `:limits calls N`, `:limits primitives N`.
    Commands,
}

impl RaisedWith {
    /// How to raise the limit on calls (`calls`) or primitives (`primitives`).
    pub(crate) fn how(self, limit: &str) -> String {
        match self {
            RaisedWith::Flags => format!("`--max-{limit} N`"),
            RaisedWith::Commands => format!("`:limits {limit} N`"),
        }
    }
}

impl Limits {
    /// The limits of every entry point unless the user raises them. The
    /// primitive limit is set so that a scene at the limit can also be
    /// rendered (the scene and its BVH) within a 24 GB machine, with room to
    /// spare; docs/language.md (its limits) gives the memory it takes.
    pub const DEFAULT: Limits =
        Limits { max_call_depth: 100_000, max_primitives: 10_000_000, raised_with: RaisedWith::Flags };
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
    /// Raised (by Ctrl-C) to stop the evaluation at the next procedure call.
    interrupt: Option<&'static AtomicBool>,
    /// Procedures by name; a redefinition replaces.
    procs: NameMap<Arc<ProcDef>>,
    /// What each procedure name held before each definition of the current
    /// run, oldest first, so that a failed run takes them back.
    procs_undo: Vec<(Name, Option<Arc<ProcDef>>)>,
    /// Where the scene's parts come from.
    origins: Origins,
    /// What `print` wrote and was not yet taken.
    printed: PrintLog,
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
    last_proc: Option<Arc<ProcDef>>,
    /// The last rotation computed, with its angles (see `rotation`).
    last_rotation: (DVec3, DMat3),
    /// A reusable buffer for building `object` values.
    scratch: Vec<Primitive>,
    /// Where the primitives go as they are made, if not into the scene.
    stream: Option<Stream>,
}

/// Where [`Interpreter::streaming`] sends the primitives it makes.
struct Stream {
    /// How many primitives of a kind (static, timed) are sent at once.
    batch: usize,
    /// Takes each batch, with whether it holds timed primitives.
    sink: Box<dyn FnMut(bool, Vec<Primitive>)>,
}

impl std::fmt::Debug for Stream {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Stream").field("batch", &self.batch).finish_non_exhaustive()
    }
}

/// What a failed run restores.
struct Snapshot {
    camera: Camera,
    ambient: f64,
    time_use: TimeUse,
    created: usize,
    lights: usize,
    primitives: usize,
    timed_primitives: usize,
    warnings: usize,
    camera_origin: Option<CameraOrigin>,
    ambient_origin: Option<Span>,
    branched_on_time: bool,
    degrees: usize,
}

impl Interpreter {
    /// A fresh interpreter evaluating with `time` bound to the given value.
    /// Every number a program sees is finite: the command line and the
    /// session refuse a time that is not, naming the flag, the command or
    /// the frame; should one get here all the same, a program that reads
    /// `time` fails where it reads it (never a silent 0).
    pub fn new(time: f64, limits: Limits) -> Interpreter {
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
            interrupt: None,
            procs: NameMap::default(),
            procs_undo: Vec::new(),
            origins: Origins::default(),
            printed: PrintLog::default(),
            warnings: Vec::new(),
            warned: HashSet::new(),
            skip_static: false,
            created: 0,
            context_tainted: false,
            depth: 0,
            last_proc: None,
            last_rotation: (DVec3::ZERO, DMat3::IDENTITY),
            scratch: Vec::new(),
            stream: None,
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

    /// Sends the primitives `put` makes to `sink`, `batch` at a time, in the
    /// order they are made (static and timed ones apart: the second
    /// argument says which), instead of keeping them: the scene then holds
    /// only those made since the last batch, and an evaluation to compare
    /// with a scene (`:write`'s check) needs no second copy of it. Only for
    /// one run: a failed run cannot take back what was sent.
    pub fn streaming(mut self, batch: usize, sink: impl FnMut(bool, Vec<Primitive>) + 'static) -> Interpreter {
        self.stream = Some(Stream { batch: batch.max(1), sink: Box::new(sink) });
        self
    }

    /// Records the procedure calls, with their arguments, that led to each
    /// `put` ([`Origins::calls`]), to explain a pixel. A plain evaluation
    /// does not: it costs a record per call.
    pub fn recording_calls(mut self) -> Interpreter {
        self.origins.calls = Some(PutCalls::default());
        self
    }

    /// Makes the evaluation stop with an error at the next procedure call
    /// once `flag` is raised (the session's Ctrl-C): a runaway program can
    /// be stopped without losing what came before it.
    pub fn interruptible(mut self, flag: &'static AtomicBool) -> Interpreter {
        self.interrupt = Some(flag);
        self
    }

    /// Runs every item of `program`; on error the interpreter is unchanged
    /// and the error explains itself (a recursion error names the chain of
    /// calls).
    pub fn run(&mut self, program: &Program) -> Result<(), Diagnostic> {
        let snapshot = self.snapshot();
        self.created = self.live_primitives();
        let result = program.items.iter().try_for_each(|item| {
            self.stop_if_interrupted(item.span(), || "it was running this".to_string())?;
            self.run_item(item)
        });
        self.env.reset_locals();
        if let Some(calls) = &mut self.origins.calls {
            calls.end_run();
        }
        self.depth = 0;
        self.context_tainted = false;
        result.map_err(|error| {
            self.restore(snapshot);
            let mut diagnostic = error.diagnostic;
            if let Some(chain) = error.chain.filter(|chain| !chain.is_empty()) {
                // Collected while unwinding, innermost first.
                let chain: Vec<_> = chain.into_iter().rev().collect();
                diagnostic = diagnostic.with_note(Note::from("call chain: ").then(summarise_chain(&chain)));
            }
            diagnostic
        })
    }

    /// The warnings (clamped colours, ...) raised since the last call.
    pub fn take_warnings(&mut self) -> Vec<Diagnostic> {
        std::mem::take(&mut self.warnings)
    }

    /// What `print` wrote since the last call (at most [`PRINT_LIMIT`]
    /// lines, the others counted). A failed run keeps what it printed: it
    /// may tell why it failed.
    pub fn take_printed(&mut self) -> PrintLog {
        std::mem::take(&mut self.printed)
    }

    /// The scene built so far.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Where the parts of the scene built so far come from.
    pub fn origins(&self) -> &Origins {
        &self.origins
    }

    /// The scene built so far, by value.
    pub fn into_scene(self) -> Scene {
        self.scene
    }

    /// Whether a `camera` was given (otherwise [`DEFAULT_CAMERA`] is used).
    pub fn has_camera(&self) -> bool {
        self.origins.camera.is_some()
    }

    /// Whether an `ambient` was given (otherwise [`DEFAULT_AMBIENT`] is used).
    pub fn has_ambient(&self) -> bool {
        self.origins.ambient.is_some()
    }

    /// Whether evaluation read `time` at all. When it did not, every frame of
    /// an animation is the same picture.
    pub fn has_time_reads(&self) -> bool {
        self.scene.time_use.read
    }

    /// The names of the defined procedures, sorted (for completion and `:help`).
    pub fn procedure_names(&self) -> Vec<Name> {
        sorted(self.procs.keys())
    }

    /// The names of the global variables, sorted (for completion).
    pub fn global_names(&self) -> Vec<Name> {
        sorted(self.env.globals.keys())
    }

    /// The definition of a procedure, if there is one by that name.
    pub fn procedure(&self, name: &str) -> Option<&ProcDef> {
        self.procs.get(&Name::find(name)?).map(|p| &**p)
    }

    /// The value of a global number variable, if `name` holds a number.
    pub fn global_number(&self, name: &str) -> Option<f64> {
        match self.env.globals.get(&Name::find(name)?)?.kind {
            Kind::Number(value) => Some(value),
            Kind::Object(_) => None,
        }
    }

    /// The primitives of a global object variable, if `name` holds an object.
    pub fn global_object(&self, name: &str) -> Option<&[Primitive]> {
        match &self.env.globals.get(&Name::find(name)?)?.kind {
            Kind::Object(primitives) => Some(primitives),
            Kind::Number(_) => None,
        }
    }

    /// Runs one top-level item.
    fn run_item(&mut self, item: &Item) -> EvalResult<()> {
        match item {
            Item::Camera(def) => {
                let distance = self.eval_expr(&def.distance)?;
                let angle = self.eval_expr(&def.angle)?;
                errors::check_camera_angle(angle.value, def.angle.span)?;
                self.scene.camera = Camera { distance: distance.value, angle: angle.value };
                self.scene.time_use.camera = distance.tainted | angle.tainted;
                self.origins.camera =
                    Some(CameraOrigin { item: def.span, distance: def.distance.span, angle: def.angle.span });
            }
            Item::Ambient(def) => {
                let ambient = self.eval_expr(&def.intensity)?;
                self.scene.ambient = ambient.value;
                self.scene.time_use.ambient = ambient.tainted;
                self.origins.ambient = Some(def.intensity.span);
            }
            Item::Light(def) => {
                let (angles, rotation_tainted) = self.eval_angles(&def.rotation, Turned::Light)?;
                let intensity = self.eval_expr(&def.intensity)?;
                let direction = rotated_up(&self.rotation(angles));
                self.scene.lights.push(Light { direction, intensity: intensity.value });
                self.origins.lights.push(LightOrigin { item: def.span, intensity: def.intensity.span });
                self.scene.time_use.lights |= rotation_tainted | intensity.tainted | self.context_tainted;
            }
            Item::Proc(def) => {
                let before = self.procs.insert(def.name.name, def.clone());
                self.procs_undo.push((def.name.name, before));
                self.last_proc = None;
            }
            Item::Instr(instr) => self.exec(instr)?,
        }
        Ok(())
    }

    /// Records a warning, once per source spot.
    fn warn(&mut self, warning: Diagnostic) {
        if self.warned.insert(warning.span) {
            self.warnings.push(warning);
        }
    }

    /// Primitives alive now: in the scene and in global objects.
    fn live_primitives(&self) -> usize {
        self.scene.primitives.len() + self.scene.timed_primitives.len() + self.env.object_primitives()
    }

    fn snapshot(&mut self) -> Snapshot {
        self.env.begin();
        self.procs_undo.clear();
        self.origins.objects.begin();
        Snapshot {
            camera: self.scene.camera,
            ambient: self.scene.ambient,
            time_use: self.scene.time_use,
            created: self.created,
            lights: self.scene.lights.len(),
            primitives: self.scene.primitives.len(),
            timed_primitives: self.scene.timed_primitives.len(),
            warnings: self.warnings.len(),
            camera_origin: self.origins.camera,
            ambient_origin: self.origins.ambient,
            branched_on_time: self.origins.branched_on_time,
            degrees: self.origins.degrees.len(),
        }
    }

    fn restore(&mut self, snapshot: Snapshot) {
        self.env.rollback();
        while let Some((name, before)) = self.procs_undo.pop() {
            match before {
                Some(def) => self.procs.insert(name, def),
                None => self.procs.remove(&name),
            };
        }
        self.last_proc = None;
        self.scene.camera = snapshot.camera;
        self.scene.ambient = snapshot.ambient;
        self.scene.time_use = snapshot.time_use;
        self.created = snapshot.created;
        self.scene.lights.truncate(snapshot.lights);
        self.scene.primitives.truncate(snapshot.primitives);
        self.scene.timed_primitives.truncate(snapshot.timed_primitives);
        self.origins.camera = snapshot.camera_origin;
        self.origins.ambient = snapshot.ambient_origin;
        self.origins.lights.truncate(snapshot.lights);
        self.origins.truncate_primitives(snapshot.primitives, snapshot.timed_primitives);
        self.origins.objects.rollback();
        self.origins.branched_on_time = snapshot.branched_on_time;
        self.origins.degrees.truncate(snapshot.degrees);
        for warning in self.warnings.drain(snapshot.warnings..) {
            self.warned.remove(&warning.span);
        }
    }
}

/// The names, sorted.
fn sorted<'a>(names: impl Iterator<Item = &'a Name>) -> Vec<Name> {
    let mut names: Vec<Name> = names.copied().collect();
    names.sort();
    names
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::{SourceMap, parse_items};

    #[test]
    fn a_time_that_is_not_finite_fails_where_it_is_read_never_zero() {
        let mut sources = SourceMap::new();
        let reads = sources.add("<test>", "print time", 0);
        let program = parse_items(reads, "print time").expect("parses");
        for time in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            let error = Interpreter::new(time, Limits::DEFAULT).run(&program).expect_err("refused");
            assert_eq!(error.message, format!("`time` is {time} here, not a finite number"));
        }
        let ignores = sources.add("<test>", "let a = 1", 0);
        let program = parse_items(ignores, "let a = 1").expect("parses");
        Interpreter::new(f64::INFINITY, Limits::DEFAULT).run(&program).expect("`time` is not read");
    }

    #[test]
    fn a_streaming_run_sends_every_primitive_in_order_and_keeps_only_the_last_batch() {
        let text = "proc f(n) if n > 0 then put sphere center n, 0, 0 radius 1 kd 0.5 ks 0.5 phong 10 \
                    color 1, 2, 3 end f(n - 1) end end\n\
                    f(10)\nif time > 0 then put sphere center time, 1, 0 radius 1 kd 0.5 ks 0.5 phong 10 \
                    color 1, 2, 3 end end";
        let mut sources = SourceMap::new();
        let program = parse_items(sources.add("<test>", text, 0), text).expect("parses");
        let mut whole = Interpreter::new(1.0, Limits::DEFAULT);
        whole.run(&program).expect("runs");
        let whole = whole.into_scene();
        let sent = std::rc::Rc::new(std::cell::RefCell::new((Vec::new(), Vec::new())));
        let into = std::rc::Rc::clone(&sent);
        let mut streaming = Interpreter::new(1.0, Limits::DEFAULT).streaming(3, move |timed, batch| {
            assert_eq!(batch.len(), if timed { 1 } else { 3 });
            let mut sent = into.borrow_mut();
            if timed { &mut sent.1 } else { &mut sent.0 }.extend(batch);
        });
        streaming.run(&program).expect("runs");
        let rest = streaming.into_scene();
        assert_eq!(rest.primitives.len(), 1, "10 primitives, 3 batches of 3 sent");
        let (mut primitives, mut timed) = sent.take();
        primitives.extend(rest.primitives);
        timed.extend(rest.timed_primitives);
        assert_eq!((primitives, timed), (whole.primitives, whole.timed_primitives));
    }
}
