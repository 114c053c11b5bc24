//! Short descriptions of the global objects (`sphere`, `group of 3
//! objects`, `translated box`), read off the syntax of their `object`
//! definitions, for `:env` and for the confirmation after an input.

use std::collections::HashMap;

use crate::lang::ast::{InstrKind, Item, Obj, ObjKind, Program};
use crate::lang::walk::{bound_name, same_level};

/// What each global object was defined as, when that is certain.
#[derive(Debug, Clone, Default)]
pub(crate) struct ObjectDescriptions {
    by_name: HashMap<String, String>,
}

impl ObjectDescriptions {
    /// Records the top-level `object` definitions of `program`. A name
    /// defined inside a top-level `if` loses its description: which branch
    /// ran is not known here.
    pub(crate) fn record(&mut self, program: &Program) {
        for item in &program.items {
            let Item::Instr(instr) = item else { continue };
            match &instr.kind {
                InstrKind::Object(name, obj) => {
                    let what = self.describe(obj);
                    self.by_name.insert(name.name.to_string(), what);
                }
                InstrKind::If(..) => {
                    for name in same_level(std::iter::once(instr)).filter_map(bound_name) {
                        self.by_name.remove(&**name);
                    }
                }
                InstrKind::Let(name, _) => {
                    self.by_name.remove(&*name.name);
                }
                InstrKind::Call(..) | InstrKind::Put(_) | InstrKind::Print(_) => {}
            }
        }
    }

    /// What the object `name` is, if known.
    pub(crate) fn get(&self, name: &str) -> Option<&str> {
        self.by_name.get(name).map(String::as_str)
    }

    /// A short description of what an object expression builds. Nested
    /// transformations are read in a loop, so any depth of them is fine.
    pub(crate) fn describe(&self, obj: &Obj) -> String {
        let mut description = String::new();
        let mut obj = obj;
        loop {
            let (word, inner) = match &obj.kind {
                ObjKind::Translate(inner, _) => ("translated ", inner),
                ObjKind::Rotate(inner, _) => ("rotated ", inner),
                ObjKind::Scale(inner, _) => ("scaled ", inner),
                ObjKind::Var(name) => return description + self.get(name).unwrap_or("object"),
                ObjKind::Sphere { .. } => return description + "sphere",
                ObjKind::Plane { .. } => return description + "plane",
                ObjKind::Box { .. } => return description + "box",
                ObjKind::Group(members) if members.len() == 1 => return description + "group of 1 object",
                ObjKind::Group(members) => return format!("{description}group of {} objects", members.len()),
            };
            description.push_str(word);
            obj = inner;
        }
    }
}
