//! The names of programs, interned: each distinct name is stored once, for
//! the life of the process, and a [`Name`] is a pointer to it.
//!
//! Why interned names: a syntax tree whose names are plain pointers can be
//! moved to another thread (a `:load` is parsed on a thread Ctrl-C abandons,
//! and the tree of an input that Ctrl-C stopped is freed on one), and a name
//! is copied without a count (the parameters bound at every call of a
//! procedure), compared and hashed as one word. What it costs: a name once
//! seen is kept to the end, its length and about 80 bytes, once however
//! often it is written; the limits on a session's inputs and on their
//! lines bound how many there can be (`docs/language.md`, "Names").

use std::collections::HashMap;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::ops::Deref;
use std::sync::{LazyLock, Mutex, PoisonError};

use super::fast_hash::FastHash;

/// A name of a program (a variable, an object, a procedure, a parameter),
/// interned: two `Name`s are equal exactly when their texts are.
#[derive(Clone, Copy)]
pub struct Name(&'static Interned);

/// What a [`Name`] points to.
struct Interned {
    text: &'static str,
    /// The names interned before this one: what a name hashes as (its
    /// address would leave the low bits of a hash, which pick the bucket,
    /// the same for every name).
    number: u32,
}

/// Every name interned so far, by its text.
static NAMES: LazyLock<Mutex<HashMap<&'static str, Name, FastHash>>> = LazyLock::new(Mutex::default);

impl Name {
    /// The name whose text is `text`, interned on its first use.
    pub fn new(text: &str) -> Name {
        let mut names = NAMES.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(&name) = names.get(text) {
            return name;
        }
        let text: &'static str = Box::leak(text.into());
        let number = names.len() as u32;
        let name = Name(Box::leak(Box::new(Interned { text, number })));
        names.insert(text, name);
        name
    }

    /// The name whose text is `text` if it was ever interned: what a lookup
    /// by text uses, so that asking for a name never seen keeps nothing.
    pub fn find(text: &str) -> Option<Name> {
        NAMES.lock().unwrap_or_else(PoisonError::into_inner).get(text).copied()
    }

    /// The name's text.
    pub fn as_str(self) -> &'static str {
        self.0.text
    }
}

impl Deref for Name {
    type Target = str;

    fn deref(&self) -> &str {
        self.0.text
    }
}

impl From<&str> for Name {
    fn from(text: &str) -> Name {
        Name::new(text)
    }
}

impl PartialEq for Name {
    fn eq(&self, other: &Name) -> bool {
        std::ptr::eq(self.0, other.0)
    }
}

impl Eq for Name {}

impl Hash for Name {
    fn hash<H: Hasher>(&self, state: &mut H) {
        state.write_u32(self.0.number);
    }
}

/// Names sort by their texts.
impl Ord for Name {
    fn cmp(&self, other: &Name) -> std::cmp::Ordering {
        self.0.text.cmp(other.0.text)
    }
}

impl PartialOrd for Name {
    fn partial_cmp(&self, other: &Name) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl fmt::Display for Name {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0.text)
    }
}

/// Shown as its text is, quoted.
impl fmt::Debug for Name {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.0.text, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_name_is_interned_once_and_equal_by_its_text() {
        let (ball, again) = (Name::new("ball_of_names_test"), Name::new(&String::from("ball_of_names_test")));
        assert_eq!(ball, again);
        assert!(std::ptr::eq(ball.as_str(), again.as_str()));
        assert_ne!(ball, Name::new("ball_of_names_test2"));
        assert_eq!(ball.as_str(), "ball_of_names_test");
        assert_eq!(format!("{ball} {ball:?}"), "ball_of_names_test \"ball_of_names_test\"");
    }

    #[test]
    fn finding_a_name_never_interned_keeps_nothing() {
        assert_eq!(Name::find("never_interned_by_any_test"), None);
        assert_eq!(Name::find("never_interned_by_any_test"), None);
        let name = Name::new("interned_by_this_test");
        assert_eq!(Name::find("interned_by_this_test"), Some(name));
    }

    #[test]
    fn names_sort_by_their_texts() {
        let mut names = [Name::new("b_sorted"), Name::new("a_sorted"), Name::new("c_sorted")];
        names.sort();
        assert_eq!(names.map(Name::as_str), ["a_sorted", "b_sorted", "c_sorted"]);
    }

    #[test]
    fn a_syntax_tree_can_move_between_threads() {
        fn sendable<T: Send + Sync>() {}
        sendable::<crate::lang::ast::Program>();
    }
}
