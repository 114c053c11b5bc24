//! Where each name of a program is bound and used, by the scoping rules of
//! SPEC 3.4, without evaluating it: what an editor's "go to definition",
//! "find references" and "rename" need.
//!
//! Numbers and objects share one namespace, procedures have their own. A
//! name bound by `let` or `object` at top level is a global; inside a
//! procedure it is a local of that procedure from its binding on, and
//! hides the global of the same name, as a parameter does. A use inside a
//! procedure that no parameter or earlier local explains reads the globals
//! as they are when the procedure is called, so it may be bound by any of
//! the global bindings; a use at top level is bound by the latest one
//! before it.

use std::collections::HashMap;

use super::ast::{Cond, CondKind, Expr, ExprKind, Ident, Instr, InstrKind, Item, Obj, ObjKind, Program, Triple};
use super::name::Name;
use super::source::Span;

/// The namespace a name lives in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Namespace {
    /// Numbers and objects.
    Value,
    /// Procedures.
    Procedure,
}

/// Where a name is bound.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Scope {
    /// At top level.
    Global,
    /// Inside one procedure definition: the index of its item in the program.
    Procedure(usize),
}

/// One name in one scope: every occurrence of it is the same variable,
/// object or procedure, which a rename changes together.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Symbol {
    /// The name as written.
    pub name: Name,
    /// Its namespace.
    pub namespace: Namespace,
    /// Its scope.
    pub scope: Scope,
}

/// How an occurrence binds its name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Binding {
    /// `let NAME = ...`
    Number,
    /// `object NAME = ...`
    Object,
    /// A procedure's parameter.
    Parameter,
    /// `proc NAME(...)`
    Procedure,
}

/// One place a name is written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Occurrence {
    /// The name's own bytes.
    pub span: Span,
    /// Which of [`Names::symbols`] it is.
    pub symbol: usize,
    /// How it binds the name, or `None` for a use.
    pub binding: Option<Binding>,
    /// The scope it is written in (a use of a global inside a procedure is
    /// written in the procedure's scope).
    pub written_in: Scope,
    /// Where the binding takes effect, or where the use reads: a `let`
    /// binds at the end of its instruction, so `let x = x + 1` reads the
    /// earlier `x`.
    at: u32,
}

/// The names of a program: its symbols and their occurrences, in source order.
#[derive(Debug, Clone, Default)]
pub struct Names {
    /// Every symbol, in the order of its first occurrence.
    pub symbols: Vec<Symbol>,
    /// Every occurrence, ordered by where it starts.
    pub occurrences: Vec<Occurrence>,
}

/// A node still to visit, or a binding to record once the node before it
/// (the value of a `let`) has been visited.
enum Task<'a> {
    Instr(&'a Instr),
    Expr(&'a Expr),
    Cond(&'a Cond),
    Obj(&'a Obj),
    Bind(&'a Ident, Binding, u32),
}

/// The walk of a program, one scope at a time.
#[derive(Default)]
struct Collector {
    names: Names,
    index: HashMap<Symbol, usize>,
}

impl Collector {
    fn occurrence(&mut self, symbol: Symbol, span: Span, binding: Option<Binding>, written_in: Scope, at: u32) {
        let next = self.names.symbols.len();
        let index = *self.index.entry(symbol.clone()).or_insert(next);
        if index == next {
            self.names.symbols.push(symbol);
        }
        self.names.occurrences.push(Occurrence { span, symbol: index, binding, written_in, at });
    }

    /// Visits `tasks` (the last one first) in `scope`, whose parameters and
    /// locals bound so far are `locals`. Nesting costs no stack.
    fn visit<'a>(&mut self, mut tasks: Vec<Task<'a>>, scope: Scope, locals: &mut Vec<Name>) {
        let value_symbol = |name: &Name, locals: &[Name]| {
            let scope = if locals.contains(name) { scope } else { Scope::Global };
            Symbol { name: *name, namespace: Namespace::Value, scope }
        };
        while let Some(task) = tasks.pop() {
            match task {
                Task::Bind(ident, binding, at) => {
                    if scope != Scope::Global && !locals.contains(&ident.name) {
                        locals.push(ident.name);
                    }
                    let symbol = value_symbol(&ident.name, locals);
                    self.occurrence(symbol, ident.span, Some(binding), scope, at);
                }
                Task::Instr(instr) => {
                    let end = instr.span.end;
                    match &instr.kind {
                        InstrKind::Let(name, value) => {
                            tasks.extend([Task::Bind(name, Binding::Number, end), Task::Expr(value)]);
                        }
                        InstrKind::Object(name, value) => {
                            tasks.extend([Task::Bind(name, Binding::Object, end), Task::Obj(value)]);
                        }
                        InstrKind::Call(name, arguments) => {
                            let symbol =
                                Symbol { name: name.name, namespace: Namespace::Procedure, scope: Scope::Global };
                            self.occurrence(symbol, name.span, None, scope, name.span.start);
                            tasks.extend(arguments.iter().rev().map(Task::Expr));
                        }
                        InstrKind::Put(object) => tasks.push(Task::Obj(object)),
                        InstrKind::If(condition, then, otherwise) => {
                            tasks.extend(otherwise.iter().flatten().rev().map(Task::Instr));
                            tasks.extend(then.iter().rev().map(Task::Instr));
                            tasks.push(Task::Cond(condition));
                        }
                        InstrKind::Print(values) => tasks.extend(values.iter().rev().map(Task::Expr)),
                    }
                }
                Task::Expr(expr) => match &expr.kind {
                    ExprKind::Var(name) => {
                        let symbol = value_symbol(name, locals);
                        self.occurrence(symbol, expr.span, None, scope, expr.span.start);
                    }
                    ExprKind::Neg(inner) | ExprKind::Call(_, inner) => tasks.push(Task::Expr(inner)),
                    ExprKind::Binary(_, left, right) => tasks.extend([Task::Expr(right), Task::Expr(left)]),
                    ExprKind::Number(_) | ExprKind::Pi => {}
                },
                Task::Cond(condition) => match &condition.kind {
                    CondKind::Or(left, right) | CondKind::And(left, right) => {
                        tasks.extend([Task::Cond(right), Task::Cond(left)]);
                    }
                    CondKind::Not(inner) => tasks.push(Task::Cond(inner)),
                    CondKind::Compare(_, left, right) => tasks.extend([Task::Expr(right), Task::Expr(left)]),
                },
                Task::Obj(object) => match &object.kind {
                    ObjKind::Var(name) => {
                        let symbol = value_symbol(name, locals);
                        self.occurrence(symbol, object.span, None, scope, object.span.start);
                    }
                    ObjKind::Sphere { center, radius, texture } => {
                        tasks.extend(triple(&texture.color));
                        tasks.extend([&texture.phong, &texture.ks, &texture.kd, radius].map(Task::Expr));
                        tasks.extend(triple(center));
                    }
                    ObjKind::Plane { rotation, shift, texture } => {
                        tasks.extend(triple(&texture.color));
                        tasks.extend([&texture.phong, &texture.ks, &texture.kd, shift].map(Task::Expr));
                        tasks.extend(triple(rotation));
                    }
                    ObjKind::Box { center, length, texture } => {
                        tasks.extend(triple(&texture.color));
                        tasks.extend([&texture.phong, &texture.ks, &texture.kd].map(Task::Expr));
                        tasks.extend(triple(length));
                        tasks.extend(triple(center));
                    }
                    ObjKind::Translate(inner, by) | ObjKind::Rotate(inner, by) => {
                        tasks.extend(triple(by));
                        tasks.push(Task::Obj(inner));
                    }
                    ObjKind::Scale(inner, by) => tasks.extend([Task::Expr(by), Task::Obj(inner)]),
                    ObjKind::Group(members) => tasks.extend(members.iter().rev().map(Task::Obj)),
                },
            }
        }
    }
}

/// The three parts of `triple`, to visit in order (pushed last first).
fn triple(triple: &Triple) -> impl Iterator<Item = Task<'_>> {
    triple.parts.iter().rev().map(Task::Expr)
}

impl Names {
    /// The names of `program`.
    pub fn of(program: &Program) -> Names {
        let mut collector = Collector::default();
        for (index, item) in program.items.iter().enumerate() {
            let mut no_locals = Vec::new();
            match item {
                Item::Camera(camera) => collector.visit(
                    vec![Task::Expr(&camera.angle), Task::Expr(&camera.distance)],
                    Scope::Global,
                    &mut no_locals,
                ),
                Item::Ambient(ambient) => {
                    collector.visit(vec![Task::Expr(&ambient.intensity)], Scope::Global, &mut no_locals)
                }
                Item::Light(light) => {
                    let mut tasks = vec![Task::Expr(&light.intensity)];
                    tasks.extend(triple(&light.rotation));
                    collector.visit(tasks, Scope::Global, &mut no_locals);
                }
                Item::Instr(instr) => collector.visit(vec![Task::Instr(instr)], Scope::Global, &mut no_locals),
                Item::Proc(procedure) => {
                    let scope = Scope::Procedure(index);
                    let name = &procedure.name;
                    let symbol = Symbol { name: name.name, namespace: Namespace::Procedure, scope: Scope::Global };
                    collector.occurrence(symbol, name.span, Some(Binding::Procedure), Scope::Global, name.span.start);
                    let mut locals: Vec<Name> = Vec::new();
                    let mut tasks: Vec<Task> = procedure.body.iter().rev().map(Task::Instr).collect();
                    tasks.extend(
                        procedure
                            .params
                            .iter()
                            .rev()
                            .map(|param| Task::Bind(param, Binding::Parameter, param.span.start)),
                    );
                    collector.visit(tasks, scope, &mut locals);
                }
            }
        }
        let mut names = collector.names;
        names.occurrences.sort_by_key(|occurrence| occurrence.span.start);
        names
    }

    /// The occurrence whose name holds byte `offset` (or ends right at it,
    /// as a cursor after a name), if any.
    pub fn at(&self, offset: usize) -> Option<&Occurrence> {
        let offset = offset as u32;
        let after = self.occurrences.partition_point(|occurrence| occurrence.span.start <= offset);
        self.occurrences[..after].last().filter(|occurrence| offset <= occurrence.span.end)
    }

    /// Every occurrence of `symbol`, bindings and uses, in source order.
    pub fn occurrences_of(&self, symbol: usize) -> impl Iterator<Item = &Occurrence> {
        self.occurrences.iter().filter(move |occurrence| occurrence.symbol == symbol)
    }

    /// The bindings that may give `occurrence` its meaning: itself for a
    /// binding; for a use, the latest binding before it in its own scope,
    /// or every binding of the symbol where the order of evaluation decides
    /// (a global read inside a procedure, a procedure called).
    pub fn bindings_for<'a>(&'a self, occurrence: &'a Occurrence) -> Vec<&'a Occurrence> {
        if occurrence.binding.is_some() {
            return vec![occurrence];
        }
        let symbol = &self.symbols[occurrence.symbol];
        let bindings = self.occurrences_of(occurrence.symbol).filter(|other| other.binding.is_some());
        let in_order = symbol.namespace == Namespace::Value && symbol.scope == occurrence.written_in;
        if !in_order {
            return bindings.collect();
        }
        bindings.filter(|binding| binding.at <= occurrence.at).last().into_iter().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::{SourceId, parse_items};

    /// The names of `text`, and the spans of its occurrences as text.
    fn names(text: &str) -> Names {
        Names::of(&parse_items(SourceId::default(), text).expect("the program parses"))
    }

    /// The occurrence of the `nth` (0-based) `word` in `text`.
    fn nth<'a>(names: &'a Names, text: &str, word: &str, nth: usize) -> &'a Occurrence {
        let word_char = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
        let whole = |&(at, _): &(usize, &str)| {
            !word_char(text[..at].chars().next_back()) && !word_char(text[at + word.len()..].chars().next())
        };
        let offset = text.match_indices(word).filter(whole).nth(nth).expect("the word is there").0;
        names.at(offset).expect("an occurrence there")
    }

    fn bound_at(names: &Names, occurrence: &Occurrence) -> Vec<u32> {
        names.bindings_for(occurrence).iter().map(|binding| binding.span.start).collect()
    }

    #[test]
    fn a_local_hides_the_global_for_the_rest_of_the_call() {
        let text = "let size = 1\nproc p(x)\n  print size\n  let size = 2\n  print size, x\nend\nprint size";
        let names = names(text);
        let global = nth(&names, text, "size", 0).symbol;
        assert_eq!(nth(&names, text, "size", 1).symbol, global, "before the local: the global");
        let local = nth(&names, text, "size", 2).symbol;
        assert_ne!(local, global);
        assert_eq!(names.symbols[local].scope, Scope::Procedure(1));
        assert_eq!(nth(&names, text, "size", 3).symbol, local);
        assert_eq!(nth(&names, text, "size", 4).symbol, global);
        assert_eq!(names.occurrences_of(global).count(), 3);
        let x = nth(&names, text, "x", 1);
        assert_eq!(names.bindings_for(x)[0].binding, Some(Binding::Parameter));
    }

    #[test]
    fn a_use_at_top_level_is_bound_by_the_latest_binding_before_it() {
        let text = "let r = 1\nlet r = r + 1\nprint r\nproc p() print r end";
        let names = names(text);
        let [first, second] = [0, 1].map(|n| nth(&names, text, "r", n).span.start);
        assert_eq!(bound_at(&names, nth(&names, text, "r", 2)), [first], "the second let's value reads the first");
        assert_eq!(bound_at(&names, nth(&names, text, "r", 3)), [second]);
        assert_eq!(bound_at(&names, nth(&names, text, "r", 4)), [first, second], "inside a procedure: any of them");
    }

    #[test]
    fn procedures_objects_and_deep_nesting() {
        let text = "object ball = sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 1, 1, 1 end\n\
                    proc row(n) if n > 0 then put translate ball by n, 0, 0 end row(n - 1) end end\nrow(3)";
        let names = names(text);
        let row = nth(&names, text, "row", 0);
        assert_eq!(row.binding, Some(Binding::Procedure));
        assert_eq!(names.occurrences_of(row.symbol).count(), 3);
        assert_eq!(bound_at(&names, nth(&names, text, "row", 2)), [row.span.start]);
        assert_eq!(bound_at(&names, nth(&names, text, "ball", 1)), [nth(&names, text, "ball", 0).span.start]);
        let deep =
            format!("let x = {}a put {}s{}", "-".repeat(100_000), "group ".repeat(100_000), " end".repeat(100_000));
        let deep = parse_items(SourceId::default(), &deep).map(|program| Names::of(&program).occurrences.len());
        assert_eq!(deep.ok(), Some(3), "a, x and s");
    }
}
