//! Where the parts of an evaluated scene come from in the program.
//!
//! The scene itself holds no source positions: the renderer reads it, and
//! its data stay as small as they are. [`Origins`] sits beside it, built by
//! the same evaluation, for the warnings about the scene (`crate::lint`):
//! the camera, the ambient light and each light by their expressions, each
//! primitive by the `put` that made it, each `object` definition by its name
//! and whether it was ever used, the angles of turns that look like degrees. When asked (to explain a pixel), it also
//! records the procedure calls that led to each `put` ([`PutCalls`]).

use std::collections::HashMap;
use std::ops::Range;

use crate::lang::fast_hash::FastHash;
use crate::lang::name::Name;
use crate::lang::source::Span;

/// Where the parts of a scene come from, indexed like the scene's parts.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Origins {
    /// The `camera` item's expressions; `None` while the session's default
    /// camera is used.
    pub camera: Option<CameraOrigin>,
    /// The `ambient` expression; `None` while the session's default is used.
    pub ambient: Option<Span>,
    /// Each light's origin, in the order of [`crate::scene::Scene::lights`].
    pub lights: Vec<LightOrigin>,
    /// The `put` of each of [`crate::scene::Scene::primitives`].
    pub primitives: PutSpans,
    /// The `put` of each of [`crate::scene::Scene::timed_primitives`].
    pub timed_primitives: PutSpans,
    /// Every `object` instruction that ran.
    pub objects: ObjectDefinitions,
    /// The angles of turns that look like degrees, each place once (the
    /// first [`DEGREES_KEPT`]), in the order they ran; none that depend on `time`.
    pub degrees: Vec<DegreesOrigin>,
    /// Whether an `if` chose its branch by `time` (directly or through a
    /// procedure's argument): at another time other objects may be put.
    pub branched_on_time: bool,
    /// The calls that led to each primitive's `put`, when recorded
    /// ([`crate::lang::Interpreter::recording_calls`]).
    pub calls: Option<PutCalls>,
}

impl Origins {
    /// Records that `angle`, written at `span`, turns `turned` and looks like
    /// degrees, unless that place is already recorded or enough are.
    #[cold]
    pub(crate) fn record_degrees(&mut self, span: Span, angle: f64, turned: Turned) {
        if self.degrees.len() < DEGREES_KEPT && self.degrees.iter().all(|d| d.span != span) {
            self.degrees.push(DegreesOrigin { span, angle, turned });
        }
    }

    /// Records that the primitives `range`, appended last to the static
    /// (or, with `timed`, the timed) primitives, come from the `put` at `span`.
    #[inline]
    pub(crate) fn record_put(&mut self, timed: bool, range: Range<usize>, span: Span) {
        if let Some(calls) = &mut self.calls
            && !range.is_empty()
        {
            calls.record(timed, range.start);
        }
        let puts = if timed { &mut self.timed_primitives } else { &mut self.primitives };
        puts.record(range, span);
    }

    /// Forgets the primitives from index `primitives` (static) and `timed`
    /// (timed) on: a failed run took them back.
    pub(crate) fn truncate_primitives(&mut self, primitives: usize, timed: usize) {
        self.primitives.truncate(primitives);
        self.timed_primitives.truncate(timed);
        if let Some(calls) = &mut self.calls {
            calls.truncate(primitives, timed);
        }
    }

    /// The `put` that made primitive `index` of
    /// [`crate::scene::Scene::all_primitives`], of which the first
    /// `static_count` are static.
    pub fn put_of(&self, index: usize, static_count: usize) -> Option<Span> {
        match index.checked_sub(static_count) {
            None => self.primitives.span_of(index),
            Some(timed) => self.timed_primitives.span_of(timed),
        }
    }

    /// The calls that led to the `put` of primitive `index` of
    /// [`crate::scene::Scene::all_primitives`] (the first `static_count`
    /// static), innermost first; empty when not recorded.
    pub fn calls_of(&self, index: usize, static_count: usize) -> Vec<&Call> {
        let Some(calls) = &self.calls else { return Vec::new() };
        let innermost = match index.checked_sub(static_count) {
            None => PutCalls::call_at(&calls.primitives, index),
            Some(timed) => PutCalls::call_at(&calls.timed_primitives, timed),
        };
        std::iter::successors(innermost.map(|call| &calls.calls[call as usize]), |call| {
            call.caller.map(|caller| &calls.calls[caller as usize])
        })
        .collect()
    }
}

/// One procedure call that ran.
#[derive(Debug, Clone, PartialEq)]
pub struct Call {
    /// The procedure called.
    pub procedure: Name,
    /// Its parameters, each with the value it was given.
    pub arguments: Vec<(Name, f64)>,
    /// The call instruction.
    pub span: Span,
    /// The call whose body made this call (index in [`PutCalls`]'s
    /// calls), if any.
    pub caller: Option<u32>,
}

/// The calls that led to each `put`: every call that ran, and for each
/// primitive (in runs, as in [`PutSpans`]) the innermost call active at
/// its `put`. A frame per call: recorded only when asked.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PutCalls {
    calls: Vec<Call>,
    /// The innermost active call.
    current: Option<u32>,
    /// (first primitive, innermost call), by first primitive.
    primitives: Vec<(usize, Option<u32>)>,
    /// The same for the timed primitives.
    timed_primitives: Vec<(usize, Option<u32>)>,
}

impl PutCalls {
    /// A call of `procedure` at `span` with `arguments` starts.
    pub(crate) fn enter(&mut self, procedure: Name, arguments: Vec<(Name, f64)>, span: Span) {
        let caller = self.current;
        self.current = Some(saturating_u32(self.calls.len()));
        self.calls.push(Call { procedure, arguments, span, caller });
    }

    /// The innermost call returns.
    pub(crate) fn leave(&mut self) {
        self.current = self.current.and_then(|call| self.calls[call as usize].caller);
    }

    /// No call is active (a run ended, maybe by an error inside calls).
    pub(crate) fn end_run(&mut self) {
        self.current = None;
    }

    /// The primitives appended from index `start` on (to the timed ones
    /// with `timed`) come from a `put` inside the current call.
    fn record(&mut self, timed: bool, start: usize) {
        let runs = if timed { &mut self.timed_primitives } else { &mut self.primitives };
        if runs.last().is_none_or(|&(_, call)| call != self.current) {
            runs.push((start, self.current));
        }
    }

    /// Forgets the primitives from index `primitives` (static) and `timed` on.
    fn truncate(&mut self, primitives: usize, timed: usize) {
        for (runs, len) in [(&mut self.primitives, primitives), (&mut self.timed_primitives, timed)] {
            let kept = runs.partition_point(|&(start, _)| start < len);
            runs.truncate(kept);
        }
    }

    /// The innermost call at the `put` of primitive `index` of `runs`.
    fn call_at(runs: &[(usize, Option<u32>)], index: usize) -> Option<u32> {
        let run = runs.partition_point(|&(start, _)| start <= index).checked_sub(1)?;
        runs[run].1
    }
}

/// The expressions of a `camera` item.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CameraOrigin {
    /// The whole item.
    pub item: Span,
    /// The `distance` expression.
    pub distance: Span,
    /// The `angle` expression.
    pub angle: Span,
}

/// How many places of angles that look like degrees [`Origins`] keeps: a
/// warning about each is enough to see the mistake.
pub const DEGREES_KEPT: usize = 16;

/// An angle of a turn that looks like degrees
/// ([`crate::lang::degrees::turn_looks_like_degrees`]), where it was written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DegreesOrigin {
    /// The angle's expression.
    pub span: Span,
    /// Its value.
    pub angle: f64,
    /// What it turns.
    pub turned: Turned,
}

/// What an angle turns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Turned {
    /// A `light`'s `vector` (or `rotation`).
    Light,
    /// A `plane`'s `rotation`.
    Plane,
    /// `rotate ... by`.
    Object,
}

/// The expressions of a `light` item.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LightOrigin {
    /// The whole item.
    pub item: Span,
    /// The `intensity` expression.
    pub intensity: Span,
}

/// The `put` that made each primitive of a list, stored as runs: a `put` of
/// a group, or the same `put` run again and again by a procedure, is one
/// run of consecutive primitives. A run is two `u32`s (its first primitive
/// and its `put` among the distinct ones), so even a scene where every
/// primitive comes from another `put` than the one before costs 8 bytes a
/// primitive, against about 180 for the primitive itself.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PutSpans {
    /// (first primitive, index in `puts`), by first primitive.
    runs: Vec<(u32, u32)>,
    /// The distinct `put` instructions.
    puts: Vec<Span>,
    /// Index of each span in `puts`.
    index: HashMap<Span, u32, FastHash>,
}

impl PutSpans {
    /// Records that the primitives `range` (appended last) come from the `put` at `span`.
    #[inline]
    pub(crate) fn record(&mut self, range: Range<usize>, span: Span) {
        let last = self.runs.last().map(|&(_, put)| put);
        if range.is_empty() || last.is_some_and(|put| self.puts[put as usize] == span) {
            // Nothing new, or more of the last run (no hashing: the usual case).
            return;
        }
        // Two `put`s taking turns (a procedure that puts a branch, then a
        // leaf) need no hashing either.
        let before_last = self.runs.len().checked_sub(2).map(|i| self.runs[i].1);
        let put = match before_last.filter(|&put| self.puts[put as usize] == span) {
            Some(put) => put,
            None => {
                let next = self.puts.len() as u32;
                let put = *self.index.entry(span).or_insert(next);
                if put == next {
                    self.puts.push(span);
                }
                put
            }
        };
        self.runs.push((saturating_u32(range.start), put));
    }

    /// Forgets the primitives from index `len` on (a failed run took them
    /// back), and the `put`s that only they came from: distinct `put`s are
    /// numbered in the order they first ran, so those are the last ones.
    pub(crate) fn truncate(&mut self, len: usize) {
        let kept = self.runs.partition_point(|&(start, _)| (start as usize) < len);
        if kept == self.runs.len() {
            return;
        }
        self.runs.truncate(kept);
        let used = self.runs.iter().map(|&(_, put)| put as usize + 1).max().unwrap_or(0);
        forget_from(&mut self.index, used, self.puts[used..].iter().copied());
        self.puts.truncate(used);
    }

    /// The `put` that made primitive `index`, if it was recorded.
    pub fn span_of(&self, index: usize) -> Option<Span> {
        let run = self.runs.partition_point(|&(start, _)| start as usize <= index).checked_sub(1)?;
        Some(self.puts[self.runs[run].1 as usize])
    }
}

/// Forgets the entries of `index` numbered `from` on, whose keys are
/// `keys`: one by one when they are few, in one pass over the map when
/// they are many (a stopped `:load` of a million `put`s gives them back
/// in a fifth of the time, `BENCHMARKS.md`).
fn forget_from(index: &mut HashMap<Span, u32, FastHash>, from: usize, keys: impl ExactSizeIterator<Item = Span>) {
    if keys.len() < index.len() / 4 {
        for key in keys {
            index.remove(&key);
        }
    } else {
        index.retain(|_, number| (*number as usize) < from);
    }
}

/// `n`, or `u32::MAX` past it: beyond 4 billion primitives (far more than
/// memory holds) the last run simply covers the rest.
fn saturating_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// One `object` instruction that ran.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectDefinition {
    /// The name it binds, where it is written.
    pub name: Name,
    /// The name's span in the `object` instruction.
    pub span: Span,
    /// Whether an object it bound was ever named in a `put` or in another
    /// object (a procedure that defines a local object on every call has
    /// one definition, used if any call used it).
    pub used: bool,
}

/// The `object` instructions that ran, each once however often it ran.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObjectDefinitions {
    list: Vec<ObjectDefinition>,
    /// Index in `list` by the span of the name.
    index: HashMap<Span, u32, FastHash>,
    /// How many are not used (yet).
    unused: usize,
    /// How many definitions there were at [`ObjectDefinitions::begin`].
    begun_with: usize,
    /// The definitions from before that mark that the current run marked
    /// used, so that a failed run is taken back in time proportional to what
    /// it did, not to all the definitions.
    marked: Vec<u32>,
}

impl ObjectDefinitions {
    /// The number that stands for the definition of `name` at `span`, added
    /// the first time it runs.
    pub(crate) fn define(&mut self, name: Name, span: Span) -> u32 {
        let next = self.list.len() as u32;
        let id = *self.index.entry(span).or_insert(next);
        if id == next {
            self.list.push(ObjectDefinition { name, span, used: false });
            self.unused += 1;
        }
        id
    }

    /// Marks definition `id` as used.
    pub(crate) fn mark_used(&mut self, id: u32) {
        if let Some(definition) = self.list.get_mut(id as usize)
            && !definition.used
        {
            definition.used = true;
            self.unused -= 1;
            if (id as usize) < self.begun_with {
                self.marked.push(id);
            }
        }
    }

    /// Starts recording what [`ObjectDefinitions::rollback`] undoes.
    pub(crate) fn begin(&mut self) {
        self.begun_with = self.list.len();
        self.marked.clear();
    }

    /// Forgets the definitions added, and the marks made, since
    /// [`ObjectDefinitions::begin`].
    pub(crate) fn rollback(&mut self) {
        for id in self.marked.drain(..) {
            self.list[id as usize].used = false;
            self.unused += 1;
        }
        let added = &self.list[self.begun_with..];
        self.unused -= added.iter().filter(|definition| !definition.used).count();
        forget_from(&mut self.index, self.begun_with, added.iter().map(|definition| definition.span));
        self.list.truncate(self.begun_with);
    }

    /// Whether some definition is not used (yet).
    pub(crate) fn has_unused(&self) -> bool {
        self.unused > 0
    }

    /// Every definition that ran, in the order they first ran.
    pub fn iter(&self) -> impl Iterator<Item = &ObjectDefinition> {
        self.list.iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::source::SourceId;

    fn span(start: usize) -> Span {
        Span::new(SourceId(0), start, start + 3)
    }

    #[test]
    fn rollback_forgets_the_definitions_and_marks_of_the_run() {
        let name: Name = "ball".into();
        let mut objects = ObjectDefinitions::default();
        let kept = objects.define(name, span(0));
        let before = objects.clone();
        objects.begin();
        objects.mark_used(kept);
        let added = objects.define(name, span(40));
        objects.mark_used(added);
        objects.define(name, span(80));
        objects.rollback();
        assert_eq!(objects.iter().collect::<Vec<_>>(), before.iter().collect::<Vec<_>>());
        assert!(objects.has_unused());
        assert_eq!(objects.define(name, span(40)), 1, "a forgotten definition is new again");
    }

    #[test]
    fn rollback_of_many_definitions_leaves_those_from_before() {
        let name: Name = "ball".into();
        let mut objects = ObjectDefinitions::default();
        objects.define(name, span(0));
        let before = objects.clone();
        objects.begin();
        for i in 1..40 {
            objects.define(name, span(10 * i));
        }
        objects.rollback();
        assert_eq!(objects.index, before.index);
        assert_eq!(objects.iter().collect::<Vec<_>>(), before.iter().collect::<Vec<_>>());
    }

    #[test]
    fn runs_merge_and_find_the_put_of_each_primitive() {
        let mut puts = PutSpans::default();
        puts.record(0..2, span(10));
        puts.record(2..3, span(10));
        puts.record(3..3, span(20));
        puts.record(3..5, span(30));
        puts.record(5..6, span(10));
        assert_eq!(puts.runs.len(), 3, "the second put of span 10 continues the first run");
        assert_eq!(puts.puts.len(), 2, "an empty put records nothing");
        let found: Vec<_> = (0..7).map(|i| puts.span_of(i).map(|s| s.start)).collect();
        assert_eq!(found, [10, 10, 10, 30, 30, 10, 10].map(Some));
        puts.truncate(3);
        assert_eq!(puts.span_of(4).map(|s| s.start), Some(10));
        assert_eq!(PutSpans::default().span_of(0), None);
    }

    /// A few puts taken back are removed from the index one by one, many
    /// in one pass over it: either way the index is the one the kept puts
    /// alone make.
    #[test]
    fn truncating_forgets_the_puts_of_the_primitives_taken_back_few_or_many() {
        let mut puts = PutSpans::default();
        for i in 0..20 {
            puts.record(i..i + 1, span(10 * i));
        }
        for kept in [19, 4, 0] {
            puts.truncate(kept);
            let mut alone = PutSpans::default();
            (0..kept).for_each(|i| alone.record(i..i + 1, span(10 * i)));
            assert_eq!(puts, alone, "{kept} kept");
        }
    }

    #[test]
    fn a_definition_that_runs_again_is_the_same_one() {
        let mut objects = ObjectDefinitions::default();
        let name: Name = "ball".into();
        let first = objects.define(name, span(0));
        assert_eq!(objects.define(name, span(0)), first);
        let second = objects.define(name, span(40));
        assert!(objects.has_unused());
        objects.mark_used(second);
        objects.mark_used(second);
        assert!(objects.has_unused(), "the first is still unused");
        let used: Vec<_> = objects.iter().map(|d| (d.span.start, d.used)).collect();
        assert_eq!(used, [(0, false), (40, true)]);
    }
}
