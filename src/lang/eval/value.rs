//! The values a name can hold: numbers and objects, each with a taint bit
//! telling whether it depends on `time`.

use std::rc::Rc;

use crate::scene::Primitive;

/// What a name holds (SPEC 3: one namespace for numbers and objects).
#[derive(Debug, Clone)]
pub(crate) enum Kind {
    /// A number.
    Number(f64),
    /// An object: its primitives, already transformed into world space.
    /// Shared, so binding, passing and grouping never deep-copy until a `put`
    /// or a transformation needs the primitives themselves.
    Object(Rc<[Primitive]>),
}

/// A value with its dependence on `time`.
#[derive(Debug, Clone)]
pub(crate) struct Value {
    /// The number or the object.
    pub kind: Kind,
    /// Whether it was computed from `time` (directly, or in a condition or
    /// procedure argument that depends on it).
    pub tainted: bool,
    /// For an object, the `object` instruction that bound it (its number in
    /// [`super::origins::ObjectDefinitions`]), to find the definitions never
    /// used; 0 for a number. It takes what would be padding: a value stays
    /// three words.
    pub definition: u32,
}

impl Value {
    /// A number value.
    pub fn number(value: f64, tainted: bool) -> Value {
        Value { kind: Kind::Number(value), tainted, definition: 0 }
    }

    /// An object value bound by the `object` instruction numbered `definition`.
    pub fn object(primitives: Rc<[Primitive]>, tainted: bool, definition: u32) -> Value {
        Value { kind: Kind::Object(primitives), tainted, definition }
    }

    /// "a number" or "an object", for error messages.
    pub fn kind_name(&self) -> &'static str {
        match self.kind {
            Kind::Number(_) => "a number",
            Kind::Object(_) => "an object",
        }
    }
}

/// The result of a numeric expression: its value and whether it depends on `time`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Num {
    /// The value, always finite.
    pub value: f64,
    /// Whether it depends on `time`.
    pub tainted: bool,
}

impl Num {
    /// A value that does not depend on `time`.
    pub fn constant(value: f64) -> Num {
        Num { value, tainted: false }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_is_three_words() {
        assert_eq!(size_of::<Value>(), 3 * size_of::<usize>());
    }
}
