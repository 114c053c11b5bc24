//! The names in scope at a place, one model for every front-end: a
//! session's globals (from its interpreter) and a document's names at a
//! place (from its syntax), for completion, signatures and hovers.

use crate::lang::Interpreter;
use crate::lang::ast::{Item, Program};
use crate::lang::names::{Binding, Names, Namespace, Scope};

/// The names defined where something is typed or asked about.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Vocabulary {
    /// Numbers and objects.
    pub variables: Vec<String>,
    /// Which of them are objects.
    pub objects: Vec<String>,
    /// Procedures with their parameters.
    pub procedures: Vec<(String, Vec<String>)>,
}

impl Vocabulary {
    /// The global names and procedures `interpreter` holds after what it ran
    /// (`time` among the numbers).
    pub fn of_interpreter(interpreter: &Interpreter) -> Vocabulary {
        let globals = interpreter.global_names();
        let objects = globals.iter().filter(|name| interpreter.global_object(name).is_some());
        let procedures = interpreter.procedure_names().into_iter().filter_map(|name| {
            let params = interpreter.procedure(&name)?.params.iter().map(|param| param.name.to_string()).collect();
            Some((name.to_string(), params))
        });
        Vocabulary {
            objects: objects.map(|name| name.to_string()).collect(),
            variables: globals.iter().map(|name| name.to_string()).collect(),
            procedures: procedures.collect(),
        }
    }

    /// The names `program` (whose names are `names`) binds that are seen at
    /// byte `at`: the globals, the procedures with their parameters and,
    /// inside a procedure, its parameters and locals. With no place, the
    /// globals and procedures only.
    pub fn of_program(program: &Program, names: &Names, at: Option<usize>) -> Vocabulary {
        let inside = at.and_then(|offset| procedure_at(program, offset));
        // Whether each symbol is bound, and as an object: one pass over the occurrences.
        let mut bound = vec![(false, false); names.symbols.len()];
        for occurrence in &names.occurrences {
            let (any, object) = &mut bound[occurrence.symbol];
            *any |= occurrence.binding.is_some();
            *object |= occurrence.binding == Some(Binding::Object);
        }
        let mut vocabulary = Vocabulary::default();
        for (symbol, (any, object)) in names.symbols.iter().zip(bound) {
            let visible = symbol.scope == Scope::Global || Some(symbol.scope) == inside.map(Scope::Procedure);
            if symbol.namespace != Namespace::Value || !visible || !any {
                continue;
            }
            vocabulary.variables.push(symbol.name.to_string());
            if object {
                vocabulary.objects.push(symbol.name.to_string());
            }
        }
        let procedures = program.items.iter().filter_map(|item| match item {
            Item::Proc(procedure) => Some((
                procedure.name.name.to_string(),
                procedure.params.iter().map(|param| param.name.to_string()).collect(),
            )),
            _ => None,
        });
        vocabulary.procedures = procedures.collect();
        vocabulary
    }

    /// Whether `name` is one of its numbers, objects or procedures.
    pub fn defines(&self, name: &str) -> bool {
        self.variables.iter().any(|variable| variable == name)
            || self.procedures.iter().any(|(procedure, _)| procedure == name)
    }
}

/// The procedure of `program` whose definition holds byte `offset`, as the
/// index of its item.
fn procedure_at(program: &Program, offset: usize) -> Option<usize> {
    program.items.iter().position(|item| {
        matches!(item, Item::Proc(procedure) if (procedure.span.start as usize) < offset && offset <= procedure.span.end as usize)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::{Limits, SourceId, parse_items};

    const PROGRAM: &str = "let size = 1
object ball = sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 9, 9, 9 end
proc ring(n)
  let step = n
end
";

    #[test]
    fn a_procedures_locals_are_seen_inside_it_only() {
        let program = parse_items(SourceId::default(), PROGRAM).expect("parses");
        let names = Names::of(&program);
        let outside = Vocabulary::of_program(&program, &names, None);
        assert_eq!(outside.variables, ["size", "ball"]);
        assert_eq!(outside.objects, ["ball"]);
        assert_eq!(outside.procedures, [("ring".to_string(), vec!["n".to_string()])]);
        let inside = Vocabulary::of_program(&program, &names, PROGRAM.find("step"));
        assert_eq!(inside.variables, ["size", "ball", "n", "step"]);
        assert!(inside.defines("ring") && inside.defines("step") && !outside.defines("step"));
    }

    #[test]
    fn an_interpreters_globals_include_time() {
        let program = parse_items(SourceId::default(), "let size = 1\nproc ring(n)\nend\n").expect("parses");
        let mut interpreter = Interpreter::new(0.0, Limits::default());
        interpreter.run(&program).expect("runs");
        let vocabulary = Vocabulary::of_interpreter(&interpreter);
        assert_eq!(vocabulary.variables, ["size", "time"]);
        assert!(vocabulary.objects.is_empty());
        assert!(vocabulary.defines("ring") && vocabulary.defines("time") && !vocabulary.defines("sphere"));
    }
}
