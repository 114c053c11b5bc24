//! Compact S-expressions of AST shapes, to compare parses with expectations:
//! `1 - 2 * x` is `(- 1 (* 2 x))`.

use rayrepl::lang::ast::{Cond, CondKind, Expr, ExprKind};

/// The S-expression of an expression.
pub fn expr(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Number(n) => format!("{n}"),
        ExprKind::Var(name) => name.to_string(),
        ExprKind::Pi => "pi".to_string(),
        ExprKind::Neg(inner) => format!("(neg {})", expr(inner)),
        ExprKind::Binary(op, a, b) => format!("({} {} {})", op.symbol(), expr(a), expr(b)),
        ExprKind::Call(f, arg) => format!("({} {})", f.name(), expr(arg)),
    }
}

/// The S-expression of a condition.
pub fn cond(c: &Cond) -> String {
    match &c.kind {
        CondKind::Or(a, b) => format!("(or {} {})", cond(a), cond(b)),
        CondKind::And(a, b) => format!("(and {} {})", cond(a), cond(b)),
        CondKind::Not(inner) => format!("(not {})", cond(inner)),
        CondKind::Compare(op, a, b) => format!("({} {} {})", op.symbol(), expr(a), expr(b)),
    }
}
