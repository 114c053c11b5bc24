//! Environments (SPEC 3): the globals, and one frame of locals per active
//! procedure call.
//!
//! Locals of all active calls live in one stack; a call's frame is a slice of
//! it. Lookups search only the current frame (a procedure never sees its
//! caller's locals), then the globals. Frames are short, so a linear search
//! beats hashing, and nothing is allocated per call beyond the stack's growth.

use std::collections::HashMap;

use super::value::{Kind, Value};
use crate::lang::fast_hash::FastHash;
use crate::lang::name::Name;

/// A map keyed by names, with the fast hasher.
pub(crate) type NameMap<V> = HashMap<Name, V, FastHash>;

/// Where the current frame lies in the locals stack, saved across a call.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    base: usize,
    top: usize,
    in_call: bool,
}

/// The globals and the stack of locals.
#[derive(Debug, Clone, Default)]
pub(crate) struct Env {
    /// Top-level `let`s and `object`s, and `time`.
    pub globals: NameMap<Value>,
    /// Parameters and locals of every active call, innermost last.
    locals: Vec<(Name, Value)>,
    /// The current frame is `locals[base..top]`. Arguments of a call being
    /// prepared sit above `top`, invisible until the call starts.
    base: usize,
    top: usize,
    /// Whether a procedure is running (so `let` binds a local).
    in_call: bool,
    /// What each global held before each change since [`Env::begin`],
    /// oldest first, so that a failed input is taken back in time
    /// proportional to what it changed, not to all the globals.
    undo: Vec<(Name, Option<Value>)>,
    /// Primitives held by global objects, kept up to date on every change.
    object_primitives: usize,
}

impl Env {
    /// The value `name` holds here: a local of the current call, else a global.
    pub fn lookup(&self, name: Name) -> Option<&Value> {
        self.frame_locals().iter().rev().find(|(n, _)| *n == name).map(|(_, v)| v).or_else(|| self.globals.get(&name))
    }

    /// Binds `name`: a local inside a procedure call, a global at top level.
    pub fn bind(&mut self, name: Name, value: Value) {
        if !self.in_call {
            let before = self.replace_global(name, Some(value));
            self.undo.push((name, before));
            return;
        }
        let (base, top) = (self.base, self.top);
        match self.locals[base..top].iter_mut().find(|(n, _)| *n == name) {
            Some(slot) => slot.1 = value,
            None => {
                self.locals.push((name, value));
                self.top += 1;
            }
        }
    }

    /// Marks the variable `name` of the current scope (the call's locals, or
    /// the globals at top level) as depending on `time`, if it exists.
    pub fn taint(&mut self, name: Name) {
        if !self.in_call {
            if let Some(value) = self.globals.get(&name).filter(|value| !value.tainted) {
                let tainted = Value { tainted: true, ..value.clone() };
                self.bind(name, tainted);
            }
            return;
        }
        let slot = self.locals[self.base..self.top].iter_mut().find(|(n, _)| *n == name);
        if let Some((_, value)) = slot {
            value.tainted = true;
        }
    }

    /// Starts recording the changes to the globals that [`Env::rollback`] undoes.
    pub fn begin(&mut self) {
        self.undo.clear();
    }

    /// Gives every global changed since [`Env::begin`] its value from then.
    pub fn rollback(&mut self) {
        while let Some((name, before)) = self.undo.pop() {
            self.replace_global(name, before);
        }
    }

    /// How many primitives the global objects hold.
    pub fn object_primitives(&self) -> usize {
        self.object_primitives
    }

    /// Sets (or with `None` removes) a global; returns what it held.
    fn replace_global(&mut self, name: Name, value: Option<Value>) -> Option<Value> {
        let size = |value: Option<&Value>| match value.map(|v| &v.kind) {
            Some(Kind::Object(primitives)) => primitives.len(),
            _ => 0,
        };
        self.object_primitives += size(value.as_ref());
        let before = match value {
            Some(value) => self.globals.insert(name, value),
            None => self.globals.remove(&name),
        };
        self.object_primitives -= size(before.as_ref());
        before
    }

    /// Starts preparing a call: returns the caller's frame, to give back to
    /// [`Env::leave`]. Arguments are then added with [`Env::push_argument`].
    pub fn prepare_call(&self) -> Frame {
        Frame { base: self.base, top: self.top, in_call: self.in_call }
    }

    /// Adds one argument of the call being prepared, bound to its parameter.
    /// It stays invisible until [`Env::enter`], so the other arguments are
    /// still evaluated in the caller's frame.
    pub fn push_argument(&mut self, param: Name, value: Value) {
        self.locals.push((param, value));
    }

    /// Makes the pushed arguments the current frame.
    pub fn enter(&mut self, caller: Frame) {
        self.base = caller.top;
        self.top = self.locals.len();
        self.in_call = true;
    }

    /// Ends a call: drops its locals and returns to the caller's frame.
    pub fn leave(&mut self, caller: Frame) {
        self.locals.truncate(caller.top);
        self.base = caller.base;
        self.top = caller.top;
        self.in_call = caller.in_call;
    }

    /// Back to top level with no locals (after an error, whatever the depth).
    pub fn reset_locals(&mut self) {
        self.locals.clear();
        self.base = 0;
        self.top = 0;
        self.in_call = false;
    }

    /// Every name visible here, for "did you mean" suggestions.
    pub fn visible_names(&self) -> impl Iterator<Item = &str> {
        self.frame_locals().iter().map(|(n, _)| &**n).chain(self.globals.keys().map(|n| &**n))
    }

    fn frame_locals(&self) -> &[(Name, Value)] {
        &self.locals[self.base..self.top]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn number(env: &Env, name: &str) -> Option<f64> {
        match env.lookup(name.into())?.kind {
            Kind::Number(v) => Some(v),
            Kind::Object(_) => None,
        }
    }

    #[test]
    fn frames_hide_caller_locals_but_show_globals() {
        let mut env = Env::default();
        let x: Name = "x".into();
        let y: Name = "y".into();
        env.bind(x, Value::number(1.0, false));
        let top = env.prepare_call();
        env.push_argument(y, Value::number(2.0, false));
        env.enter(top);
        env.bind(x, Value::number(3.0, false));
        assert_eq!(number(&env, "x"), Some(3.0));
        let inner = env.prepare_call();
        env.enter(inner);
        assert_eq!(number(&env, "x"), Some(1.0), "the callee sees the global, not its caller's local");
        assert_eq!(number(&env, "y"), None);
        env.leave(inner);
        assert_eq!(number(&env, "y"), Some(2.0));
        env.leave(top);
        assert_eq!(number(&env, "x"), Some(1.0));
        assert_eq!(number(&env, "y"), None);
    }

    #[test]
    fn rollback_gives_back_the_globals_of_begin() {
        let mut env = Env::default();
        let (x, y): (Name, Name) = ("x".into(), "y".into());
        env.bind(x, Value::number(1.0, false));
        env.begin();
        env.bind(x, Value::number(2.0, false));
        env.bind(y, Value::number(3.0, false));
        env.taint(x);
        env.rollback();
        assert_eq!(number(&env, "x"), Some(1.0));
        assert!(!env.lookup(x).expect("x is bound").tainted);
        assert_eq!(number(&env, "y"), None);
    }

    #[test]
    fn the_hasher_tells_names_apart() {
        let mut map: NameMap<u32> = NameMap::default();
        for (i, name) in ["a", "b", "ab", "ba", "abcdefgh", "abcdefghi"].iter().enumerate() {
            map.insert((*name).into(), i as u32);
        }
        assert_eq!(map.len(), 6);
        assert_eq!(map.get(&Name::new("abcdefghi")), Some(&5));
    }
}
