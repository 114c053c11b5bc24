//! Facts read off a program's syntax tree without running it: whether it
//! reads `time`, whether it sets the camera or the ambient light.

use crate::lang::ast::{
    Cond, CondKind, Expr, ExprKind, Instr, InstrKind, Item, Obj, ObjKind, Program, Texture, Triple,
};

/// Whether any expression of `program` (procedure bodies included) reads the
/// variable `time`. Such inputs must be evaluated again when time changes;
/// the others give the same result at any time.
pub(crate) fn reads_time(program: &Program) -> bool {
    program.items.iter().any(item_reads_time)
}

/// Whether `program` has a top-level `camera` item.
pub(crate) fn sets_camera(program: &Program) -> bool {
    program
        .items
        .iter()
        .any(|item| matches!(item, Item::Camera(_)))
}

/// Whether `program` has a top-level `ambient` item.
pub(crate) fn sets_ambient(program: &Program) -> bool {
    program
        .items
        .iter()
        .any(|item| matches!(item, Item::Ambient(_)))
}

fn item_reads_time(item: &Item) -> bool {
    match item {
        Item::Camera(camera) => expr_reads_time(&camera.distance) || expr_reads_time(&camera.angle),
        Item::Ambient(intensity) => expr_reads_time(intensity),
        Item::Light(light) => {
            triple_reads_time(&light.rotation) || expr_reads_time(&light.intensity)
        }
        Item::Proc(proc_def) => instrs_read_time(&proc_def.body),
        Item::Instr(instr) => instr_reads_time(instr),
    }
}

fn instrs_read_time(instrs: &[Instr]) -> bool {
    instrs.iter().any(instr_reads_time)
}

fn instr_reads_time(instr: &Instr) -> bool {
    match &instr.kind {
        InstrKind::Let(_, value) => expr_reads_time(value),
        InstrKind::Object(_, obj) | InstrKind::Put(obj) => obj_reads_time(obj),
        InstrKind::Call(_, args) => args.iter().any(expr_reads_time),
        InstrKind::If(cond, then, otherwise) => {
            cond_reads_time(cond)
                || instrs_read_time(then)
                || otherwise.as_deref().is_some_and(instrs_read_time)
        }
    }
}

fn obj_reads_time(obj: &Obj) -> bool {
    match &obj.kind {
        ObjKind::Var(_) => false,
        ObjKind::Sphere {
            center,
            radius,
            texture,
        } => triple_reads_time(center) || expr_reads_time(radius) || texture_reads_time(texture),
        ObjKind::Plane {
            rotation,
            shift,
            texture,
        } => triple_reads_time(rotation) || expr_reads_time(shift) || texture_reads_time(texture),
        ObjKind::Box {
            center,
            length,
            texture,
        } => triple_reads_time(center) || triple_reads_time(length) || texture_reads_time(texture),
        ObjKind::Translate(inner, by) | ObjKind::Rotate(inner, by) => {
            obj_reads_time(inner) || triple_reads_time(by)
        }
        ObjKind::Scale(inner, by) => obj_reads_time(inner) || expr_reads_time(by),
        ObjKind::Group(members) => members.iter().any(obj_reads_time),
    }
}

fn texture_reads_time(texture: &Texture) -> bool {
    expr_reads_time(&texture.kd)
        || expr_reads_time(&texture.ks)
        || expr_reads_time(&texture.phong)
        || triple_reads_time(&texture.color)
}

fn triple_reads_time(triple: &Triple) -> bool {
    triple.parts.iter().any(expr_reads_time)
}

fn cond_reads_time(cond: &Cond) -> bool {
    match &cond.kind {
        CondKind::Or(a, b) | CondKind::And(a, b) => cond_reads_time(a) || cond_reads_time(b),
        CondKind::Not(inner) => cond_reads_time(inner),
        CondKind::Compare(_, a, b) => expr_reads_time(a) || expr_reads_time(b),
    }
}

fn expr_reads_time(expr: &Expr) -> bool {
    match &expr.kind {
        ExprKind::Var(name) => &**name == "time",
        ExprKind::Number(_) | ExprKind::Pi => false,
        ExprKind::Neg(inner) | ExprKind::Call(_, inner) => expr_reads_time(inner),
        ExprKind::Binary(_, a, b) => expr_reads_time(a) || expr_reads_time(b),
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::lang::ast::{BinOp, Ident};
    use crate::lang::source::Span;

    /// A number literal.
    pub(crate) fn num(value: f64) -> Expr {
        Expr {
            kind: ExprKind::Number(value),
            span: Span::default(),
        }
    }

    /// A variable reference.
    pub(crate) fn var(name: &str) -> Expr {
        Expr {
            kind: ExprKind::Var(name.into()),
            span: Span::default(),
        }
    }

    /// A top-level `let`.
    pub(crate) fn let_item(name: &str, value: Expr) -> Item {
        let ident = Ident {
            name: name.into(),
            span: Span::default(),
        };
        Item::Instr(Instr {
            kind: InstrKind::Let(ident, value),
            span: Span::default(),
        })
    }

    #[test]
    fn time_is_found_inside_expressions() {
        let sum = Expr {
            kind: ExprKind::Binary(BinOp::Add, Box::new(num(1.0)), Box::new(var("time"))),
            span: Span::default(),
        };
        assert!(reads_time(&Program {
            items: vec![let_item("x", sum)]
        }));
        assert!(!reads_time(&Program {
            items: vec![let_item("time", var("x"))]
        }));
        assert!(!sets_camera(&Program {
            items: vec![let_item("x", num(1.0))]
        }));
    }
}
