//! Numeric expressions and conditions (SPEC 3).
//!
//! Every operation checks that its result is finite, so a division by zero or
//! the square root of a negative number is reported where it happens instead
//! of turning into NaN pixels. Nested expressions grow the native stack on
//! demand, so `1+(1+(1+...))` a hundred thousand levels deep still evaluates.

use std::f64::consts::PI;

use super::Interpreter;
use super::errors::{EvalResult, fail, with_suggestion, wrong_kind};
use super::stack::grow;
use super::value::{Kind, Num};
use crate::lang::ast::{BinOp, CmpOp, Cond, CondKind, Expr, ExprKind, Func};
use crate::lang::diagnostic::Diagnostic;
use crate::lang::name::Name;
use crate::lang::number::Number;
use crate::lang::source::Span;

impl Interpreter {
    /// Evaluates a numeric expression.
    pub(crate) fn eval_expr(&mut self, expr: &Expr) -> EvalResult<Num> {
        match &expr.kind {
            ExprKind::Number(value) if value.is_finite() => Ok(Num::constant(*value)),
            ExprKind::Number(_) => {
                fail(Diagnostic::error(expr.span, "this number is too large").with_code("number-too-large"))
            }
            ExprKind::Pi => Ok(Num::constant(PI)),
            ExprKind::Var(name) => self.number_variable(*name, expr.span),
            _ => grow(|| expr.span, || self.eval_compound(expr)),
        }
    }

    /// Evaluates an expression with operands.
    fn eval_compound(&mut self, expr: &Expr) -> EvalResult<Num> {
        match &expr.kind {
            ExprKind::Neg(inner) => {
                let n = self.eval_expr(inner)?;
                Ok(Num { value: -n.value, tainted: n.tainted })
            }
            ExprKind::Binary(op, left, right) => {
                let a = self.eval_expr(left)?;
                let b = self.eval_expr(right)?;
                let value = binary(*op, a.value, b.value, expr.span)?;
                Ok(Num { value, tainted: a.tainted | b.tainted })
            }
            ExprKind::Call(func, argument) => {
                let n = self.eval_expr(argument)?;
                let value = function(*func, n.value, expr.span)?;
                Ok(Num { value, tainted: n.tainted })
            }
            ExprKind::Number(_) | ExprKind::Pi | ExprKind::Var(_) => self.eval_expr(expr),
        }
    }

    /// The number a variable holds, or an error naming what is wrong with it.
    fn number_variable(&mut self, name: Name, span: Span) -> EvalResult<Num> {
        match self.env.lookup(name) {
            Some(value) => match value.kind {
                // Only `time` can hold one (see `Interpreter::new`).
                Kind::Number(number) if !number.is_finite() => fail(
                    Diagnostic::error(span, format!("`{name}` is {number} here, not a finite number"))
                        .with_code("overflow")
                        .with_label("not a finite number"),
                ),
                Kind::Number(number) => {
                    let tainted = value.tainted;
                    self.scene.time_use.read |= tainted;
                    Ok(Num { value: number, tainted })
                }
                Kind::Object(_) => fail(wrong_kind(span, &name, "an object", "a number")),
            },
            None => fail(self.unknown_variable(name, span)),
        }
    }

    /// "unknown variable `x`", with a suggestion among the visible names.
    pub(crate) fn unknown_variable(&self, name: Name, span: Span) -> Diagnostic {
        let diagnostic = Diagnostic::error(span, format!("unknown variable `{name}`"))
            .with_code("unknown-variable")
            .with_label("not defined here");
        if self.procs.contains_key(&name) {
            return diagnostic.with_note(format!("`{name}` is a procedure; procedures are called as instructions"));
        }
        with_suggestion(diagnostic, &name, self.env.visible_names())
    }

    /// Evaluates a condition: its truth and whether it depends on `time`.
    /// `&` and `|` stop early when their left side decides.
    pub(crate) fn eval_cond(&mut self, cond: &Cond) -> EvalResult<(bool, bool)> {
        match &cond.kind {
            CondKind::Compare(op, left, right) => {
                let a = self.eval_expr(left)?;
                let b = self.eval_expr(right)?;
                Ok((compare(*op, a.value, b.value), a.tainted | b.tainted))
            }
            _ => grow(|| cond.span, || self.eval_connective(cond)),
        }
    }

    /// Evaluates `!`, `&` and `|`.
    fn eval_connective(&mut self, cond: &Cond) -> EvalResult<(bool, bool)> {
        match &cond.kind {
            CondKind::Not(inner) => {
                let (value, tainted) = self.eval_cond(inner)?;
                Ok((!value, tainted))
            }
            CondKind::And(left, right) => {
                let (a, a_tainted) = self.eval_cond(left)?;
                if !a {
                    return Ok((false, a_tainted));
                }
                let (b, b_tainted) = self.eval_cond(right)?;
                Ok((b, a_tainted | b_tainted))
            }
            CondKind::Or(left, right) => {
                let (a, a_tainted) = self.eval_cond(left)?;
                if a {
                    return Ok((true, a_tainted));
                }
                let (b, b_tainted) = self.eval_cond(right)?;
                Ok((b, a_tainted | b_tainted))
            }
            CondKind::Compare(..) => self.eval_cond(cond),
        }
    }
}

/// `a op b`, or an error at `span` if the result is not a finite number.
#[inline]
fn binary(op: BinOp, a: f64, b: f64, span: Span) -> EvalResult<f64> {
    let value = match op {
        BinOp::Add => a + b,
        BinOp::Sub => a - b,
        BinOp::Mul => a * b,
        BinOp::Div if b == 0.0 => return division_by_zero(span),
        BinOp::Div => a / b,
    };
    finite(value, span)
}

/// The division-by-zero error (out of line: the hot path only tests for it).
#[cold]
#[inline(never)]
fn division_by_zero<T>(span: Span) -> EvalResult<T> {
    fail(Diagnostic::error(span, "division by zero").with_code("division-by-zero").with_label("the divisor is 0"))
}

/// `sin`, `cos` or `sqrt` of `x`.
fn function(func: Func, x: f64, span: Span) -> EvalResult<f64> {
    match func {
        Func::Sin => Ok(x.sin()),
        Func::Cos => Ok(x.cos()),
        Func::Sqrt if x < 0.0 => fail(
            Diagnostic::error(span, format!("square root of a negative number ({})", Number(x)))
                .with_code("negative-square-root")
                .with_label("the argument is negative"),
        ),
        Func::Sqrt => Ok(x.sqrt()),
    }
}

/// `value` if finite, else an overflow error at `span`.
#[inline]
fn finite(value: f64, span: Span) -> EvalResult<f64> {
    if value.is_finite() { Ok(value) } else { overflow(span) }
}

/// The overflow error (out of line).
#[cold]
#[inline(never)]
fn overflow<T>(span: Span) -> EvalResult<T> {
    fail(
        Diagnostic::error(span, "this operation overflows: its result is too large to be a number")
            .with_code("overflow")
            .with_label("not a finite number"),
    )
}

/// `a op b` for a comparison; `=` is exact float equality (SPEC 3).
#[allow(clippy::float_cmp)]
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
