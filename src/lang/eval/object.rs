//! Object expressions (SPEC 3 and 4): building primitives and baking the
//! transformations into them.
//!
//! An object expression is evaluated by appending its primitives to a buffer
//! (the scene itself for a `put`), then transforming that tail of the buffer
//! in place: no intermediate object is allocated.

use glam::{DMat3, DVec3};

use super::Interpreter;
use super::errors::{EvalResult, fail, wrong_kind};
use super::origins::Turned;
use super::stack::grow;
use super::value::{Kind, Num};
use crate::lang::ast::{Expr, Obj, ObjKind, Texture, Triple};
use crate::lang::degrees::turn_looks_like_degrees;
use crate::lang::diagnostic::Diagnostic;
use crate::lang::name::Name;
use crate::lang::number::Number;
use crate::lang::source::Span;
use crate::scene::transform::{rotated_up, rotation_matrix};
use crate::scene::{Material, Primitive, Shape};

impl Interpreter {
    /// Appends the primitives of `obj` to `out`; returns whether they depend on `time`.
    pub(crate) fn emit_obj(&mut self, obj: &Obj, out: &mut Vec<Primitive>) -> EvalResult<bool> {
        match &obj.kind {
            ObjKind::Var(name) => self.emit_variable(*name, obj.span, out),
            ObjKind::Sphere { center, radius, texture } => {
                let (center, c) = self.eval_triple(center)?;
                let r = self.eval_expr(radius)?;
                positive(r.value, radius.span, "a sphere's radius")?;
                let (material, m) = self.eval_texture(texture)?;
                self.make_room(1, obj.span, out)?;
                out.push(Primitive { shape: Shape::Sphere { center, radius: r.value }, material });
                Ok(c | r.tainted | m)
            }
            ObjKind::Plane { rotation, shift, texture } => {
                let (angles, a) = self.eval_angles(rotation, Turned::Plane)?;
                let d = self.eval_expr(shift)?;
                let (material, m) = self.eval_texture(texture)?;
                self.make_room(1, obj.span, out)?;
                let normal = rotated_up(&self.rotation(angles));
                out.push(Primitive { shape: Shape::Plane { normal, shift: d.value }, material });
                Ok(a | d.tainted | m)
            }
            ObjKind::Box { center, length, texture } => {
                let (center, c) = self.eval_triple(center)?;
                let (size, s) = self.eval_triple(length)?;
                for (value, part) in size.to_array().into_iter().zip(&length.parts) {
                    positive(value, part.span, "a box's length")?;
                }
                let (material, m) = self.eval_texture(texture)?;
                self.make_room(1, obj.span, out)?;
                let shape = Shape::Box { center, half: size * 0.5, axes: DMat3::IDENTITY };
                out.push(Primitive { shape, material });
                Ok(c | s | m)
            }
            _ => grow(|| obj.span, || self.emit_compound(obj, out)),
        }
    }

    /// Appends the primitives of a transformation or a group.
    fn emit_compound(&mut self, obj: &Obj, out: &mut Vec<Primitive>) -> EvalResult<bool> {
        let start = out.len();
        match &obj.kind {
            ObjKind::Translate(inner, by) => {
                let inner_tainted = self.emit_obj(inner, out)?;
                let (v, t) = self.eval_triple(by)?;
                transform(&mut out[start..], obj.span, |p| p.translate(v))?;
                Ok(inner_tainted | t)
            }
            ObjKind::Rotate(inner, by) => {
                let inner_tainted = self.emit_obj(inner, out)?;
                let (angles, t) = self.eval_angles(by, Turned::Object)?;
                let r = self.rotation(angles);
                transform(&mut out[start..], obj.span, |p| p.rotate(&r))?;
                Ok(inner_tainted | t)
            }
            ObjKind::Scale(inner, by) => {
                let inner_tainted = self.emit_obj(inner, out)?;
                let k = self.eval_expr(by)?;
                if k.value == 0.0 {
                    return fail(
                        Diagnostic::error(by.span, "cannot scale by 0")
                            .with_code("scale-by-zero")
                            .with_label("this is 0")
                            .with_note("a scale of 0 would shrink the object to a single point"),
                    );
                }
                transform(&mut out[start..], obj.span, |p| p.scale(k.value))?;
                Ok(inner_tainted | k.tainted)
            }
            ObjKind::Group(members) => {
                let mut tainted = false;
                for member in members {
                    tainted |= self.emit_obj(member, out)?;
                }
                Ok(tainted)
            }
            ObjKind::Var(_) | ObjKind::Sphere { .. } | ObjKind::Plane { .. } | ObjKind::Box { .. } => {
                self.emit_obj(obj, out)
            }
        }
    }

    /// Appends a copy of the primitives an `object` variable holds.
    fn emit_variable(&mut self, name: Name, span: Span, out: &mut Vec<Primitive>) -> EvalResult<bool> {
        let (primitives, tainted, definition) = match self.env.lookup(name) {
            Some(value) => match &value.kind {
                Kind::Object(primitives) => (primitives.clone(), value.tainted, value.definition),
                Kind::Number(_) => return fail(wrong_kind(span, &name, "a number", "an object")),
            },
            None => return fail(self.unknown_variable(name, span)),
        };
        self.scene.time_use.read |= tainted;
        self.origins.objects.mark_used(definition);
        self.make_room(primitives.len(), span, out)?;
        out.extend_from_slice(&primitives);
        Ok(tainted)
    }

    /// Counts `n` new primitives against [`super::Limits::max_primitives`],
    /// and makes room for them in `out`: running out of memory is an error
    /// at the construct that needed it, not an abort.
    fn make_room(&mut self, n: usize, span: Span, out: &mut Vec<Primitive>) -> EvalResult<()> {
        let total = self.created.saturating_add(n);
        if total > self.limits.max_primitives {
            return fail(
                Diagnostic::error(
                    span,
                    format!(
                        "this makes more than {} primitives, the most a scene may have",
                        self.limits.max_primitives
                    ),
                )
                .with_code("too-many-primitives")
                .with_label(format!("{n} more here"))
                .with_help(format!(
                    "make fewer objects, or raise the limit ({})",
                    self.limits.raised_with.how("primitives")
                )),
            );
        }
        if out.try_reserve(n).is_err() {
            return fail(not_enough_memory(span, total));
        }
        self.created = total;
        Ok(())
    }

    /// The rotation matrix of SPEC 4 for these angles. The last one is kept:
    /// a procedure that puts many objects usually turns them all alike, and
    /// six sines and cosines per object would cost more than the rest of it.
    pub(crate) fn rotation(&mut self, angles: DVec3) -> DMat3 {
        if self.last_rotation.0 != angles {
            self.last_rotation = (angles, rotation_matrix(angles.x, angles.y, angles.z));
        }
        self.last_rotation.1
    }

    /// Evaluates three expressions into a vector.
    pub(crate) fn eval_triple(&mut self, triple: &Triple) -> EvalResult<(DVec3, bool)> {
        let [a, b, c] = &triple.parts;
        let (x, y, z) = (self.eval_expr(a)?, self.eval_expr(b)?, self.eval_expr(c)?);
        Ok((DVec3::new(x.value, y.value, z.value), x.tainted | y.tainted | z.tainted))
    }

    /// [`Interpreter::eval_triple`] for the angles of a turn, noting in the
    /// origins those that look like degrees (unless they depend on `time`:
    /// other frames may differ).
    pub(crate) fn eval_angles(&mut self, triple: &Triple, turned: Turned) -> EvalResult<(DVec3, bool)> {
        let mut angles = [0.0; 3];
        let mut tainted = false;
        for (angle, part) in angles.iter_mut().zip(&triple.parts) {
            let n = self.eval_expr(part)?;
            if turn_looks_like_degrees(n.value) && !n.tainted {
                self.origins.record_degrees(part.span, n.value, turned);
            }
            *angle = n.value;
            tainted |= n.tainted;
        }
        Ok((DVec3::from_array(angles), tainted))
    }

    /// Evaluates a texture into a material: colour / 255, coefficients clamped
    /// with a warning, the Phong exponent checked.
    fn eval_texture(&mut self, texture: &Texture) -> EvalResult<(Material, bool)> {
        let kd = self.eval_coefficient(&texture.kd, "kd")?;
        let ks = self.eval_coefficient(&texture.ks, "ks")?;
        let phong = self.eval_expr(&texture.phong)?;
        positive(phong.value, texture.phong.span, "`phong`")?;
        let mut color = [0.0; 3];
        let mut tainted = kd.tainted | ks.tainted | phong.tainted;
        for (slot, part) in color.iter_mut().zip(&texture.color.parts) {
            let component = self.eval_color_component(part)?;
            *slot = component.value / 255.0;
            tainted |= component.tainted;
        }
        let material = Material { color: DVec3::from_array(color), kd: kd.value, ks: ks.value, phong: phong.value };
        Ok((material, tainted))
    }

    /// A `kd` or `ks`, clamped to 0..1 with a warning.
    fn eval_coefficient(&mut self, expr: &Expr, name: &str) -> EvalResult<Num> {
        let n = self.eval_expr(expr)?;
        let clamped = n.value.clamp(0.0, 1.0);
        if clamped != n.value {
            self.warn(
                Diagnostic::warning(
                    expr.span,
                    format!("`{name}` should be between 0 and 1, but it is {}; {clamped} is used", n.value),
                )
                .with_code("clamped-coefficient"),
            );
        }
        Ok(Num { value: clamped, ..n })
    }

    /// A colour component, clamped to 0..255 with a warning.
    fn eval_color_component(&mut self, expr: &Expr) -> EvalResult<Num> {
        let n = self.eval_expr(expr)?;
        let clamped = n.value.clamp(0.0, 255.0);
        if clamped != n.value {
            self.warn(
                Diagnostic::warning(
                    expr.span,
                    format!("a colour component should be between 0 and 255, but it is {}; {clamped} is used", n.value),
                )
                .with_code("clamped-colour"),
            );
        }
        Ok(Num { value: clamped, ..n })
    }
}

/// An error unless `value > 0`: radii, box lengths and Phong exponents.
#[inline]
fn positive(value: f64, span: Span, what: &str) -> EvalResult<()> {
    if value > 0.0 { Ok(()) } else { not_positive(value, span, what) }
}

/// The error for a size or exponent that is not positive (out of line).
#[cold]
#[inline(never)]
fn not_positive(value: f64, span: Span, what: &str) -> EvalResult<()> {
    fail(
        Diagnostic::error(span, format!("{what} must be positive, but it is {}", Number(value)))
            .with_code("not-positive")
            .with_label("not greater than 0"),
    )
}

/// Applies `f` to every primitive, then checks that none left the range of
/// finite numbers (a translation by 1e308, twice, would).
fn transform(primitives: &mut [Primitive], span: Span, f: impl Fn(&mut Primitive)) -> EvalResult<()> {
    for primitive in primitives.iter_mut() {
        f(primitive);
    }
    if primitives.iter().all(|p| p.shape.is_finite()) {
        Ok(())
    } else {
        fail(
            Diagnostic::error(span, "this transformation moves the object out of range")
                .with_code("out-of-range")
                .with_label("coordinates are no longer finite numbers"),
        )
    }
}

/// The error when the memory for `total` primitives cannot be had (at
/// about 180 bytes each while the program runs, docs/language.md section 10).
#[cold]
fn not_enough_memory(span: Span, total: usize) -> Diagnostic {
    Diagnostic::error(span, format!("not enough memory for {total} primitives"))
        .with_code("out-of-memory")
        .with_label("no memory for these")
        .with_help("make fewer objects, or run rayrepl where it may use more memory")
}
