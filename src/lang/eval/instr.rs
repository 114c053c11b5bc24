//! Instructions (SPEC 3): `let`, `object`, procedure calls, `put` and `if`.

use std::mem;
use std::rc::Rc;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use super::Interpreter;

use super::errors::{EvalError, EvalResult, fail, with_suggestion, wrong_arity};
use super::stack::grow;
use super::value::{Kind, Value};
use crate::lang::ast::{Expr, Ident, Instr, InstrKind, Obj, ObjKind, ProcDef};
use crate::lang::diagnostic::{Diagnostic, STOPPED_BY, with_names_shortened};
use crate::lang::name::Name;
use crate::lang::source::Span;

/// How many calls of a failing call chain are shown as "in this call" places.
const CALLS_SHOWN: usize = 3;

/// The most primitives the buffer for building `object` values keeps room
/// for between uses: a huge object's buffer is freed rather than held.
const SCRATCH_KEPT: usize = 4096;

impl Interpreter {
    /// Runs instructions in order.
    pub(crate) fn exec_block(&mut self, body: &[Instr]) -> EvalResult<()> {
        body.iter().try_for_each(|instr| self.exec(instr))
    }

    /// Runs one instruction.
    pub(crate) fn exec(&mut self, instr: &Instr) -> EvalResult<()> {
        match &instr.kind {
            InstrKind::Let(name, expr) => {
                let n = self.eval_expr(expr)?;
                let tainted = n.tainted | self.context_tainted;
                self.env.bind(name.name, Value::number(n.value, tainted));
                Ok(())
            }
            InstrKind::Object(name, obj) => self.exec_object(name, obj),
            InstrKind::Call(name, args) => self.exec_call(name, args, instr.span),
            InstrKind::Put(obj) => self.exec_put(obj, instr.span),
            InstrKind::Print(values) => self.exec_print(values, instr.span),
            InstrKind::If(cond, then, otherwise) => grow(
                || instr.span,
                || {
                    let (holds, tainted) = self.eval_cond(cond)?;
                    self.origins.branched_on_time |= tainted;
                    // Under a tainted context every variable of this scope is
                    // already tainted (bound in that context, or tainted by the
                    // walk of the enclosing `if`), so the walk is needed once only.
                    if tainted && !self.context_tainted {
                        self.taint_bindings_in(then, otherwise.as_deref());
                    }
                    let (branch, skipped) =
                        if holds { (Some(then), otherwise.as_deref()) } else { (otherwise.as_ref(), Some(&then[..])) };
                    if let Some(skipped) = skipped
                        && self.origins.objects.has_unused()
                    {
                        self.mark_objects_named_in(skipped);
                    }
                    match branch {
                        Some(body) => self.exec_in_context(tainted, body),
                        None => Ok(()),
                    }
                },
            ),
        }
    }

    /// Runs a branch of an `if`; a condition that depends on `time` makes
    /// everything the branch produces depend on it too.
    fn exec_in_context(&mut self, tainted: bool, body: &[Instr]) -> EvalResult<()> {
        let outer = self.context_tainted;
        self.context_tainted |= tainted;
        let result = self.exec_block(body);
        self.context_tainted = outer;
        result
    }

    /// Marks as depending on `time` every existing variable that either branch
    /// of an `if` with a tainted condition may bind: after `let x = 0  if time
    /// < 5 then let x = 1 end`, `x` depends on `time` even in the frames where
    /// the branch is not taken. Nested `if`s are searched too (with a stack
    /// of their own, however deep they nest); calls are not, since a
    /// procedure cannot bind its caller's variables.
    fn taint_bindings_in(&mut self, then: &[Instr], otherwise: Option<&[Instr]>) {
        let mut blocks: Vec<&[Instr]> = vec![then];
        blocks.extend(otherwise);
        while let Some(block) = blocks.pop() {
            for instr in block {
                match &instr.kind {
                    InstrKind::Let(name, _) | InstrKind::Object(name, _) => self.env.taint(name.name),
                    InstrKind::If(_, then, otherwise) => {
                        blocks.push(then);
                        blocks.extend(otherwise.as_deref());
                    }
                    InstrKind::Call(..) | InstrKind::Put(_) | InstrKind::Print(_) => {}
                }
            }
        }
    }

    /// Marks as used the objects that the instructions of a branch not taken
    /// name in a `put` or an `object`: the program means to put them in some
    /// case, so they are not "defined but never put" (calls are not followed).
    #[inline(never)]
    fn mark_objects_named_in(&mut self, block: &[Instr]) {
        let mut blocks = vec![block];
        let mut objects: Vec<&Obj> = Vec::new();
        while let Some(block) = blocks.pop() {
            for instr in block {
                match &instr.kind {
                    InstrKind::Object(_, obj) | InstrKind::Put(obj) => objects.push(obj),
                    InstrKind::If(_, then, otherwise) => {
                        blocks.push(then);
                        blocks.extend(otherwise.as_deref());
                    }
                    InstrKind::Let(..) | InstrKind::Call(..) | InstrKind::Print(_) => {}
                }
            }
        }
        while let Some(obj) = objects.pop() {
            match &obj.kind {
                ObjKind::Var(name) => {
                    if let Some(Value { kind: Kind::Object(_), definition, .. }) = self.env.lookup(*name) {
                        let definition = *definition;
                        self.origins.objects.mark_used(definition);
                    }
                }
                ObjKind::Translate(inner, _) | ObjKind::Rotate(inner, _) | ObjKind::Scale(inner, _) => {
                    objects.push(inner)
                }
                ObjKind::Group(members) => objects.extend(members),
                ObjKind::Sphere { .. } | ObjKind::Plane { .. } | ObjKind::Box { .. } => {}
            }
        }
    }

    /// `object name = obj`.
    fn exec_object(&mut self, name: &Ident, obj: &Obj) -> EvalResult<()> {
        let mut buffer = mem::take(&mut self.scratch);
        buffer.clear();
        let result = self.emit_obj(obj, &mut buffer);
        let primitives: Rc<[_]> = Rc::from(&buffer[..]);
        buffer.clear();
        if buffer.capacity() <= SCRATCH_KEPT {
            self.scratch = buffer;
        }
        let tainted = result? | self.context_tainted;
        let definition = self.origins.objects.define(name.name, name.span);
        self.env.bind(name.name, Value::object(primitives, tainted, definition));
        Ok(())
    }

    /// `put obj` (the instruction at `span`): static primitives go to
    /// `scene.primitives` (or nowhere, when static primitives are skipped),
    /// those that depend on `time` to `scene.timed_primitives`; their origins
    /// record `span`.
    fn exec_put(&mut self, obj: &Obj, span: Span) -> EvalResult<()> {
        let result = self.put_primitives(obj, span);
        self.stream_primitives();
        result
    }

    /// [`Self::exec_put`] but for the streaming of what it made.
    fn put_primitives(&mut self, obj: &Obj, span: Span) -> EvalResult<()> {
        let timed_start = self.scene.timed_primitives.len();
        if self.context_tainted {
            let mut timed = mem::take(&mut self.scene.timed_primitives);
            let result = self.emit_obj(obj, &mut timed);
            self.scene.timed_primitives = timed;
            self.origins.record_put(true, timed_start..self.scene.timed_primitives.len(), span);
            return result.map(|_| ());
        }
        let mut primitives = mem::take(&mut self.scene.primitives);
        let start = primitives.len();
        let result = self.emit_obj(obj, &mut primitives);
        match result {
            Ok(true) => {
                self.scene.timed_primitives.extend(primitives.drain(start..));
                self.origins.record_put(true, timed_start..self.scene.timed_primitives.len(), span);
            }
            Ok(false) if self.skip_static => primitives.truncate(start),
            Ok(false) => self.origins.record_put(false, start..primitives.len(), span),
            Err(_) => {}
        }
        self.scene.primitives = primitives;
        result.map(|_| ())
    }

    /// Sends the primitives made so far to the stream once a batch is full
    /// ([`Interpreter::streaming`]).
    fn stream_primitives(&mut self) {
        let Some(stream) = &mut self.stream else { return };
        for (timed, made) in [(false, &mut self.scene.primitives), (true, &mut self.scene.timed_primitives)] {
            if made.len() >= stream.batch {
                (stream.sink)(timed, mem::take(made));
            }
        }
    }

    /// A procedure call: checks, binds the arguments, runs the body.
    fn exec_call(&mut self, name: &Ident, args: &[Expr], span: Span) -> EvalResult<()> {
        let proc = self.find_proc(name)?;
        if args.len() != proc.params.len() {
            let params: Vec<&str> = proc.params.iter().map(|p| &*p.name).collect();
            return fail(
                wrong_arity(span, &name.name, &params, args.len())
                    .with_related(proc.name.span, format!("`{}` is defined here", proc.name.name)),
            );
        }
        if self.depth >= self.limits.max_call_depth {
            return Err(self.too_deep(name, span));
        }
        self.stop_if_interrupted(span, || format!("it was calling `{}` here", name.name))?;
        let caller = self.env.prepare_call();
        for (param, arg) in proc.params.iter().zip(args) {
            let n = self.eval_expr(arg)?;
            self.env.push_argument(param.name, Value::number(n.value, n.tainted | self.context_tainted));
        }
        self.env.enter(caller);
        if self.origins.calls.is_some() {
            self.record_call(name, &proc.params, span);
        }
        self.depth += 1;
        let result = grow(|| span, || self.exec_block(&proc.body));
        self.depth -= 1;
        self.env.leave(caller);
        if let Some(calls) = &mut self.origins.calls {
            calls.leave();
        }
        result.map_err(|error| in_call(error, name.name, span))
    }

    /// Records the call of `name` at `span` that just started, with the
    /// values its parameters `params` were given (to explain a pixel).
    #[inline(never)]
    /// Fails, pointing at `span` with `label`, once Ctrl-C raised the
    /// interrupt flag: a runaway program, or a long file, stops there.
    pub(crate) fn stop_if_interrupted(&self, span: Span, label: impl FnOnce() -> String) -> EvalResult<()> {
        if self.interrupt.is_some_and(|flag| flag.load(Ordering::Relaxed)) {
            return fail(
                Diagnostic::error(span, format!("stopped by {STOPPED_BY}"))
                    .with_code("interrupted")
                    .with_label(label())
                    .with_note("nothing of this input was kept"),
            );
        }
        Ok(())
    }

    fn record_call(&mut self, name: &Ident, params: &[Ident], span: Span) {
        let arguments = params
            .iter()
            .map(|param| {
                let value = match self.env.lookup(param.name).map(|value| &value.kind) {
                    Some(Kind::Number(value)) => *value,
                    _ => f64::NAN,
                };
                (param.name, value)
            })
            .collect();
        if let Some(calls) = &mut self.origins.calls {
            calls.enter(name.name, arguments, span);
        }
    }

    /// The procedure a call names, looked up at the time of the call.
    fn find_proc(&mut self, name: &Ident) -> EvalResult<Arc<ProcDef>> {
        if let Some(last) = &self.last_proc
            && last.name.name == name.name
        {
            return Ok(last.clone());
        }
        match self.procs.get(&name.name) {
            Some(proc) => {
                self.last_proc = Some(proc.clone());
                Ok(proc.clone())
            }
            None => fail(self.unknown_procedure(name)),
        }
    }

    /// "unknown procedure `orbt`", with a suggestion among the defined ones.
    fn unknown_procedure(&self, name: &Ident) -> Diagnostic {
        let diagnostic = Diagnostic::error(name.span, format!("unknown procedure `{}`", name.name))
            .with_code("unknown-procedure")
            .with_label("no such procedure");
        if let Some(value) = self.env.lookup(name.name) {
            let kind = value.kind_name();
            return diagnostic.with_note(format!("`{}` is {kind}, not a procedure", name.name));
        }
        with_suggestion(diagnostic, &name.name, self.procs.keys().map(|k| &**k))
    }

    /// The recursion-limit error, with the chain of active calls.
    fn too_deep(&self, name: &Ident, span: Span) -> Box<EvalError> {
        let limit = self.limits.max_call_depth;
        let diagnostic = Diagnostic::error(span, format!("recursion deeper than {limit} calls"))
            .with_code("recursion-too-deep")
            .with_label("this call goes too deep")
            .with_help(format!(
                "check that the recursion stops (an `if` whose condition becomes false), or raise the limit ({})",
                self.limits.raised_with.how("calls")
            ));
        // The callers add themselves as the error unwinds (see `in_call`).
        Box::new(EvalError { diagnostic, chain: Some(vec![(name.name, span)]) })
    }
}

/// Marks an error raised inside a call with the place of the call (the
/// innermost few distinct places only: a deep recursion would otherwise list
/// them all), and
/// adds the call to a recursion error's chain.
fn in_call(mut error: Box<EvalError>, name: Name, span: Span) -> Box<EvalError> {
    if let Some(chain) = &mut error.chain {
        chain.push((name, span));
    }
    let diagnostic = &mut error.diagnostic;
    let shown = span == diagnostic.span || diagnostic.related.iter().any(|(s, _)| *s == span);
    if !shown && diagnostic.related.len() < CALLS_SHOWN {
        diagnostic.related.push((span, with_names_shortened(format!("in this call of `{name}`"))));
    }
    error
}
