//! Short descriptions of the global objects (`sphere`, `group of 3
//! objects`, `translated box`), read off the syntax of their `object`
//! definitions, for `:env` and for the confirmation after an input.

use std::collections::HashMap;

use crate::lang::ast::{InstrKind, Item, Obj, ObjKind, Program};

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
                InstrKind::If(..) => self.forget_names_bound_in(&instr.kind),
                InstrKind::Let(name, _) => {
                    self.by_name.remove(&*name.name);
                }
                InstrKind::Call(..) | InstrKind::Put(_) => {}
            }
        }
    }

    /// What the object `name` is, if known.
    pub(crate) fn get(&self, name: &str) -> Option<&str> {
        self.by_name.get(name).map(String::as_str)
    }

    /// A short description of what an object expression builds.
    pub(crate) fn describe(&self, obj: &Obj) -> String {
        match &obj.kind {
            ObjKind::Var(name) => self.get(name).unwrap_or("object").to_string(),
            ObjKind::Sphere { .. } => "sphere".to_string(),
            ObjKind::Plane { .. } => "plane".to_string(),
            ObjKind::Box { .. } => "box".to_string(),
            ObjKind::Translate(inner, _) => format!("translated {}", self.describe(inner)),
            ObjKind::Rotate(inner, _) => format!("rotated {}", self.describe(inner)),
            ObjKind::Scale(inner, _) => format!("scaled {}", self.describe(inner)),
            ObjKind::Group(members) if members.len() == 1 => "group of 1 object".to_string(),
            ObjKind::Group(members) => format!("group of {} objects", members.len()),
        }
    }

    fn forget_names_bound_in(&mut self, kind: &InstrKind) {
        match kind {
            InstrKind::Object(name, _) | InstrKind::Let(name, _) => {
                self.by_name.remove(&*name.name);
            }
            InstrKind::If(_, then, otherwise) => {
                for instr in then.iter().chain(otherwise.iter().flatten()) {
                    self.forget_names_bound_in(&instr.kind);
                }
            }
            InstrKind::Call(..) | InstrKind::Put(_) => {}
        }
    }
}
