//! What the session has defined, for `:env`, for completion and for the
//! confirmations printed after each input: global numbers (with their values),
//! global objects (with what they are) and procedures (with their parameters).
//!
//! It is read off the syntax trees of the inputs that succeeded. That is
//! exact because only top-level `let`, `object` and `if` bind globals (a
//! procedure never changes a global, SPEC 3), and an input is only recorded
//! after the interpreter accepted it, so every value computed here is one the
//! interpreter computed too.

use std::collections::BTreeMap;
use std::f64::consts::PI;

use crate::lang::ast::{
    BinOp, CmpOp, Cond, CondKind, Expr, ExprKind, Func, Instr, InstrKind, Item, Obj, ObjKind,
    Program,
};

/// The global names and procedures defined so far.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Defined {
    /// Global numbers; the value is `None` when it depends on a branch of an
    /// `if` this summary cannot decide.
    numbers: BTreeMap<String, Option<f64>>,
    /// Global objects, with a short description (`sphere`, `group of 3 objects`).
    objects: BTreeMap<String, String>,
    /// Procedures and their parameter names.
    procedures: BTreeMap<String, Vec<String>>,
}

impl Defined {
    /// What is defined before any input: only `time`.
    pub fn new(time: f64) -> Defined {
        let mut defined = Defined::default();
        defined.numbers.insert("time".to_string(), Some(time));
        defined
    }

    /// Adds what `program`'s top-level items define.
    pub fn record(&mut self, program: &Program) {
        for item in &program.items {
            match item {
                Item::Proc(proc_def) => {
                    let params = proc_def.params.iter().map(|p| p.name.to_string()).collect();
                    self.procedures
                        .insert(proc_def.name.name.to_string(), params);
                }
                Item::Instr(instr) => self.record_instr(instr, true),
                Item::Camera(_) | Item::Ambient(_) | Item::Light(_) => {}
            }
        }
    }

    /// Global numbers and their values (`None` when unknown), by name.
    pub fn numbers(&self) -> impl Iterator<Item = (&str, Option<f64>)> {
        self.numbers
            .iter()
            .map(|(name, value)| (name.as_str(), *value))
    }

    /// Global objects and what they are, by name.
    pub fn objects(&self) -> impl Iterator<Item = (&str, &str)> {
        self.objects
            .iter()
            .map(|(name, what)| (name.as_str(), what.as_str()))
    }

    /// Procedures and their parameters, by name.
    pub fn procedures(&self) -> impl Iterator<Item = (&str, &[String])> {
        self.procedures
            .iter()
            .map(|(name, params)| (name.as_str(), params.as_slice()))
    }

    /// The value of the global number `name`, if it is one and is known.
    pub fn number(&self, name: &str) -> Option<f64> {
        self.numbers.get(name).copied().flatten()
    }

    /// What the global object `name` is, if it is one.
    pub fn object(&self, name: &str) -> Option<&str> {
        self.objects.get(name).map(String::as_str)
    }

    /// The parameters of procedure `name`, if it is one.
    pub fn procedure(&self, name: &str) -> Option<&[String]> {
        self.procedures.get(name).map(Vec::as_slice)
    }

    /// The value of `expr` with the globals known so far, if it can be told.
    pub fn value(&self, expr: &Expr) -> Option<f64> {
        let value = match &expr.kind {
            ExprKind::Number(n) => *n,
            ExprKind::Var(name) => self.number(name)?,
            ExprKind::Pi => PI,
            ExprKind::Neg(inner) => -self.value(inner)?,
            ExprKind::Binary(op, a, b) => binary(*op, self.value(a)?, self.value(b)?),
            ExprKind::Call(func, inner) => call(*func, self.value(inner)?),
        };
        value.is_finite().then_some(value)
    }

    /// `sure` is false inside a branch of an `if` whose condition is unknown:
    /// the names it binds are recorded, their values are not.
    fn record_instr(&mut self, instr: &Instr, sure: bool) {
        match &instr.kind {
            InstrKind::Let(name, value) => {
                let value = if sure { self.value(value) } else { None };
                self.objects.remove(&*name.name);
                self.numbers.insert(name.name.to_string(), value);
            }
            InstrKind::Object(name, obj) => {
                let what = self.describe(obj);
                self.numbers.remove(&*name.name);
                self.objects.insert(name.name.to_string(), what);
            }
            InstrKind::If(cond, then, otherwise) => {
                self.record_if(cond, then, otherwise.as_deref(), sure)
            }
            InstrKind::Call(..) | InstrKind::Put(_) => {}
        }
    }

    fn record_if(&mut self, cond: &Cond, then: &[Instr], otherwise: Option<&[Instr]>, sure: bool) {
        let decided = if sure { self.truth(cond) } else { None };
        let branches: Vec<&[Instr]> = match decided {
            Some(true) => vec![then],
            Some(false) => otherwise.into_iter().collect(),
            None => std::iter::once(then).chain(otherwise).collect(),
        };
        for branch in branches {
            for instr in branch {
                self.record_instr(instr, decided.is_some());
            }
        }
    }

    fn truth(&self, cond: &Cond) -> Option<bool> {
        Some(match &cond.kind {
            CondKind::Or(a, b) => self.truth(a)? || self.truth(b)?,
            CondKind::And(a, b) => self.truth(a)? && self.truth(b)?,
            CondKind::Not(inner) => !self.truth(inner)?,
            CondKind::Compare(op, a, b) => compare(*op, self.value(a)?, self.value(b)?),
        })
    }

    /// A short description of what an object expression builds.
    pub fn describe(&self, obj: &Obj) -> String {
        match &obj.kind {
            ObjKind::Var(name) => self.object(name).unwrap_or("object").to_string(),
            ObjKind::Sphere { .. } => "sphere".to_string(),
            ObjKind::Plane { .. } => "plane".to_string(),
            ObjKind::Box { .. } => "box".to_string(),
            ObjKind::Translate(inner, _) => format!("translated {}", self.describe(inner)),
            ObjKind::Rotate(inner, _) => format!("rotated {}", self.describe(inner)),
            ObjKind::Scale(inner, _) => format!("scaled {}", self.describe(inner)),
            ObjKind::Group(members) => match members.len() {
                1 => "group of 1 object".to_string(),
                n => format!("group of {n} objects"),
            },
        }
    }
}

fn binary(op: BinOp, a: f64, b: f64) -> f64 {
    match op {
        BinOp::Add => a + b,
        BinOp::Sub => a - b,
        BinOp::Mul => a * b,
        BinOp::Div => a / b,
    }
}

fn call(func: Func, x: f64) -> f64 {
    match func {
        Func::Sin => x.sin(),
        Func::Cos => x.cos(),
        Func::Sqrt => x.sqrt(),
    }
}

fn compare(op: CmpOp, a: f64, b: f64) -> bool {
    match op {
        CmpOp::Eq => a == b,
        CmpOp::Ne => a != b,
        CmpOp::Lt => a < b,
        CmpOp::Le => a <= b,
        CmpOp::Gt => a > b,
        CmpOp::Ge => a >= b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::source::Span;
    use crate::repl::facts::tests::{let_item, num, var};

    fn times(a: Expr, b: Expr) -> Expr {
        Expr {
            kind: ExprKind::Binary(BinOp::Mul, Box::new(a), Box::new(b)),
            span: Span::default(),
        }
    }

    #[test]
    fn lets_are_evaluated_in_order_with_time() {
        let mut defined = Defined::new(3.0);
        defined.record(&Program {
            items: vec![
                let_item("r", num(2.0)),
                let_item("s", times(var("r"), var("time"))),
            ],
        });
        assert_eq!(defined.number("s"), Some(6.0));
        assert_eq!(defined.number("time"), Some(3.0));
        defined.record(&Program {
            items: vec![let_item("r", var("unknown"))],
        });
        assert_eq!(
            defined.numbers().find(|(n, _)| *n == "r"),
            Some(("r", None))
        );
    }

    #[test]
    fn a_non_finite_value_is_unknown() {
        let defined = Defined::new(0.0);
        let div = Expr {
            kind: ExprKind::Binary(BinOp::Div, Box::new(num(1.0)), Box::new(num(0.0))),
            span: Span::default(),
        };
        assert_eq!(defined.value(&div), None);
    }
}
