//! Questions about a program's tree that need no evaluation: which
//! instructions run at one level, which names an expression reads. Trees
//! may be nested to any depth, so these walk from a list on the heap
//! rather than by recursion.

use super::ast::{Expr, ExprKind, Instr, InstrKind, Item, ObjKind, Program, Texture};
use super::name::Name;

/// The instructions `instrs` run at their own level: each of them and,
/// inside an `if`, those of both branches, to any depth, in source order.
/// A procedure's body is another level: a call is listed, not entered.
pub fn same_level<'a>(instrs: impl DoubleEndedIterator<Item = &'a Instr>) -> impl Iterator<Item = &'a Instr> {
    let mut pending: Vec<&Instr> = instrs.rev().collect();
    std::iter::from_fn(move || {
        let instr = pending.pop()?;
        if let InstrKind::If(_, then, otherwise) = &instr.kind {
            pending.extend(otherwise.iter().flatten().rev());
            pending.extend(then.iter().rev());
        }
        Some(instr)
    })
}

/// The name an instruction binds (`let x = ...`, `object x = ...`), if any.
pub fn bound_name(instr: &Instr) -> Option<&Name> {
    match &instr.kind {
        InstrKind::Let(name, _) | InstrKind::Object(name, _) => Some(&name.name),
        InstrKind::Call(..) | InstrKind::Put(_) | InstrKind::If(..) | InstrKind::Print(_) => None,
    }
}

/// The procedure an instruction calls, if it is a call.
pub fn called_name(instr: &Instr) -> Option<&Name> {
    match &instr.kind {
        InstrKind::Call(name, _) => Some(&name.name),
        _ => None,
    }
}

/// The variables `exprs` read, in source order, with repetitions.
pub fn variables<'a>(exprs: impl DoubleEndedIterator<Item = &'a Expr>) -> Vec<&'a Name> {
    let mut pending: Vec<&Expr> = exprs.rev().collect();
    let mut names = Vec::new();
    while let Some(expr) = pending.pop() {
        match &expr.kind {
            ExprKind::Var(name) => names.push(name),
            ExprKind::Neg(inner) | ExprKind::Call(_, inner) => pending.push(inner),
            ExprKind::Binary(_, left, right) => pending.extend([&**right, &**left]),
            ExprKind::Number(_) | ExprKind::Pi => {}
        }
    }
    names
}

/// The textures of every sphere, plane and box written in `program`, in
/// procedures too, in source order.
pub fn textures(program: &Program) -> Vec<&Texture> {
    let bodies = program.items.iter().flat_map(|item| match item {
        Item::Proc(procedure) => procedure.body.as_slice(),
        Item::Instr(instr) => std::slice::from_ref(instr),
        Item::Camera(_) | Item::Ambient(_) | Item::Light(_) => &[],
    });
    let mut objects: Vec<_> = same_level(bodies.collect::<Vec<_>>().into_iter())
        .filter_map(|instr| match &instr.kind {
            InstrKind::Put(object) | InstrKind::Object(_, object) => Some(&**object),
            _ => None,
        })
        .collect();
    objects.reverse();
    let mut textures = Vec::new();
    while let Some(object) = objects.pop() {
        match &object.kind {
            ObjKind::Sphere { texture, .. } | ObjKind::Plane { texture, .. } | ObjKind::Box { texture, .. } => {
                textures.push(texture);
            }
            ObjKind::Translate(inner, _) | ObjKind::Rotate(inner, _) | ObjKind::Scale(inner, _) => objects.push(inner),
            ObjKind::Group(members) => objects.extend(members.iter().rev()),
            ObjKind::Var(_) => {}
        }
    }
    textures
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::ast::{Item, Program};
    use crate::lang::{SourceId, parse_items};

    fn program(text: &str) -> Program {
        parse_items(SourceId::default(), text).expect("the program parses")
    }

    fn instrs(program: &Program) -> impl DoubleEndedIterator<Item = &Instr> {
        program.items.iter().filter_map(|item| match item {
            Item::Instr(instr) => Some(instr),
            _ => None,
        })
    }

    #[test]
    fn one_level_goes_into_ifs_but_not_into_calls() {
        let program = program("let a = 1 if a < 2 then let b = 2 if b < 3 then p() end else let c = 3 end q()");
        let bound: Vec<&str> = same_level(instrs(&program)).filter_map(bound_name).map(|n| &**n).collect();
        assert_eq!(bound, ["a", "b", "c"]);
        let called: Vec<&str> = same_level(instrs(&program)).filter_map(called_name).map(|n| &**n).collect();
        assert_eq!(called, ["p", "q"]);
    }

    #[test]
    fn textures_are_found_in_procedures_groups_and_ifs() {
        let texture = |n: u32| format!("kd 1 ks 0 phong 1 color {n}, 0, 0 end");
        let text = format!(
            "proc p() if 1 < 2 then put group sphere center 0, 0, 0 radius 1 {} box center 0, 0, 0 length 1, 1, 1 {} end end end\n\
             object o = translate plane rotation 0, 0, 0 shift 0 {} by 1, 0, 0 end",
            texture(1),
            texture(2),
            texture(3)
        );
        let program = program(&text);
        let reds: Vec<f64> = textures(&program)
            .iter()
            .map(|texture| match texture.color.parts[0].kind {
                ExprKind::Number(red) => red,
                _ => panic!("a number"),
            })
            .collect();
        assert_eq!(reds, [1.0, 2.0, 3.0]);
    }

    #[test]
    fn variables_are_listed_in_source_order() {
        let program = program("let x = -a * sin(b + time) / (c - a)");
        let Some(Item::Instr(Instr { kind: InstrKind::Let(_, value), .. })) = program.items.first() else {
            panic!("a let");
        };
        let names: Vec<&str> = variables(std::iter::once(value)).into_iter().map(|n| &**n).collect();
        assert_eq!(names, ["a", "b", "time", "c", "a"]);
    }
}
