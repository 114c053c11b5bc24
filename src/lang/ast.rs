//! The abstract syntax tree of the `.ray` language (SPEC section 2).
//!
//! Every node carries the [`Span`] of the source text it came from, so that
//! evaluation errors can point at the exact construct.
//!
//! The recursive nodes (expressions, conditions, objects, instructions) are
//! dropped without recursion: a program nested 100,000 levels deep would
//! otherwise overflow the stack of whichever thread lets go of it last. A
//! node without children of its own type (a number, a sphere, a `put`) is
//! dropped as it is, without that walk: most of a large file's nodes are
//! such leaves, and skipping the walk for them frees the tree of 100 MB of
//! spheres a fifth faster (`BENCHMARKS.md`).

use std::sync::Arc;

use super::name::Name;
use super::source::Span;

/// A name as written in the source, with its position.
#[derive(Debug, Clone, PartialEq)]
pub struct Ident {
    /// The name itself.
    pub name: Name,
    /// Where it was written.
    pub span: Span,
}

/// A numeric expression.
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    /// What kind of expression this is.
    pub kind: ExprKind,
    /// The whole expression's source range.
    pub span: Span,
}

/// The kinds of numeric expression.
#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    /// A literal such as `3` or `0.75`.
    Number(f64),
    /// A variable reference (a `let` or a parameter; `time` is predefined).
    Var(Name),
    /// The constant `pi`.
    Pi,
    /// Unary minus.
    Neg(Box<Expr>),
    /// A binary arithmetic operation.
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// `sin(e)`, `cos(e)` or `sqrt(e)`.
    Call(Func, Box<Expr>),
}

/// Binary arithmetic operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
}

impl BinOp {
    /// The operator as written: `+`, `-`, `*` or `/`.
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
        }
    }
}

/// The built-in numeric functions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Func {
    /// `sin`
    Sin,
    /// `cos`
    Cos,
    /// `sqrt`
    Sqrt,
}

impl Func {
    /// The function's name: `sin`, `cos` or `sqrt`.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Sqrt => "sqrt",
        }
    }
}

/// A condition of an `if`.
#[derive(Debug, Clone, PartialEq)]
pub struct Cond {
    /// What kind of condition this is.
    pub kind: CondKind,
    /// The whole condition's source range.
    pub span: Span,
}

/// The kinds of condition.
#[derive(Debug, Clone, PartialEq)]
pub enum CondKind {
    /// `a | b`
    Or(Box<Cond>, Box<Cond>),
    /// `a & b`
    And(Box<Cond>, Box<Cond>),
    /// `!a`
    Not(Box<Cond>),
    /// A comparison of two numbers.
    Compare(CmpOp, Expr, Expr),
}

/// Comparison operators: `=` and `<` from SPEC 2, the others an allowed extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CmpOp {
    /// `=` (exact float equality)
    Eq,
    /// `!=`
    Ne,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
}

impl CmpOp {
    /// The operator as written: `=`, `!=`, `<`, `<=`, `>` or `>=`.
    pub fn symbol(self) -> &'static str {
        match self {
            CmpOp::Eq => "=",
            CmpOp::Ne => "!=",
            CmpOp::Lt => "<",
            CmpOp::Le => "<=",
            CmpOp::Gt => ">",
            CmpOp::Ge => ">=",
        }
    }
}

/// Three expressions separated by commas: a point, a vector, a rotation or a colour.
#[derive(Debug, Clone, PartialEq)]
pub struct Triple {
    /// The three components, in order.
    pub parts: [Expr; 3],
    /// The source range of all three.
    pub span: Span,
}

/// `kd e ks e phong e color r, g, b`.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// Diffuse coefficient.
    pub kd: Expr,
    /// Specular (and reflection) coefficient.
    pub ks: Expr,
    /// Phong exponent.
    pub phong: Expr,
    /// Colour, components 0..255 in the language.
    pub color: Triple,
    /// The whole texture's source range.
    pub span: Span,
}

/// An object expression.
#[derive(Debug, Clone, PartialEq)]
pub struct Obj {
    /// What kind of object expression this is.
    pub kind: ObjKind,
    /// The whole object expression's source range.
    pub span: Span,
}

/// The kinds of object expression.
#[derive(Debug, Clone, PartialEq)]
pub enum ObjKind {
    /// A variable bound by `object`.
    Var(Name),
    /// `sphere center c radius r texture end`
    Sphere {
        /// Centre.
        center: Triple,
        /// Radius.
        radius: Expr,
        /// Surface texture.
        texture: Texture,
    },
    /// `plane rotation r shift d texture end`
    Plane {
        /// Rotation applied to the up normal (0, 1, 0).
        rotation: Triple,
        /// Signed distance from the origin along the normal.
        shift: Expr,
        /// Surface texture.
        texture: Texture,
    },
    /// `box center c length l texture end`
    Box {
        /// Centre.
        center: Triple,
        /// Full sizes along x, y, z.
        length: Triple,
        /// Surface texture.
        texture: Texture,
    },
    /// `translate o by v end`
    Translate(Box<Obj>, Triple),
    /// `rotate o by r end`
    Rotate(Box<Obj>, Triple),
    /// `scale o by k end`
    Scale(Box<Obj>, Expr),
    /// `group o* end`
    Group(Vec<Obj>),
}

/// An instruction (SPEC 2 `instruction`).
#[derive(Debug, Clone, PartialEq)]
pub struct Instr {
    /// What kind of instruction this is.
    pub kind: InstrKind,
    /// The whole instruction's source range.
    pub span: Span,
}

/// The kinds of instruction.
#[derive(Debug, Clone, PartialEq)]
pub enum InstrKind {
    /// `let x = e`
    Let(Ident, Expr),
    /// `object x = o` (boxed: an `Obj` is large, and a program is mostly
    /// small instructions; this keeps `Instr` and `Item` small)
    Object(Ident, Box<Obj>),
    /// `p(e, ...)`
    Call(Ident, Vec<Expr>),
    /// `put o` (boxed, as in `Object`)
    Put(Box<Obj>),
    /// `if c then ... [else ...] end`
    If(Cond, Vec<Instr>, Option<Vec<Instr>>),
    /// `print e, ...`: an extension of this project, writes the values on
    /// standard error (see `docs/language.md`, section 12).
    Print(Vec<Expr>),
}

/// `camera distance d angle a end`
#[derive(Debug, Clone, PartialEq)]
pub struct CameraDef {
    /// Distance of the eye from the origin, on +z.
    pub distance: Expr,
    /// Horizontal field of view, radians.
    pub angle: Expr,
    /// Source range of the whole definition.
    pub span: Span,
}

/// `ambient i`
#[derive(Debug, Clone, PartialEq)]
pub struct AmbientDef {
    /// Intensity of the light that reaches every surface, 0..1.
    pub intensity: Expr,
    /// Source range of the whole definition.
    pub span: Span,
}

/// `light vector r intensity i end` (or `light rotation ...`).
#[derive(Debug, Clone, PartialEq)]
pub struct LightDef {
    /// Rotation applied to the up direction (0, 1, 0).
    pub rotation: Triple,
    /// Intensity, 0..1.
    pub intensity: Expr,
    /// Source range of the whole definition.
    pub span: Span,
}

/// `proc name(params) body end`
#[derive(Debug, Clone, PartialEq)]
pub struct ProcDef {
    /// The procedure's name.
    pub name: Ident,
    /// Formal parameters, in order.
    pub params: Vec<Ident>,
    /// The instructions run at each call.
    pub body: Vec<Instr>,
    /// Source range of the whole definition.
    pub span: Span,
}

/// One top-level item. A file is a sequence of items in the order of SPEC 2;
/// the interactive session accepts them in any order (SPEC 7).
#[derive(Debug, Clone, PartialEq)]
pub enum Item {
    /// A camera definition (replaces any earlier one).
    Camera(CameraDef),
    /// `ambient e` (replaces any earlier one).
    Ambient(AmbientDef),
    /// A directional light (adds one).
    Light(LightDef),
    /// A procedure definition.
    Proc(Arc<ProcDef>),
    /// An instruction run at top level.
    Instr(Instr),
}

impl Item {
    /// Where the whole item is.
    pub fn span(&self) -> Span {
        match self {
            Item::Camera(def) => def.span,
            Item::Ambient(def) => def.span,
            Item::Light(def) => def.span,
            Item::Proc(def) => def.span,
            Item::Instr(instr) => instr.span,
        }
    }
}

/// A parsed program: a whole file or one input of the session.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Program {
    /// The items, in source order.
    pub items: Vec<Item>,
}

/// A tree node that can hand over its children of the same type, leaving
/// itself a leaf: what dropping a tree without recursion needs.
trait Subtrees: Sized {
    /// Moves this node's children of its own type into `into`.
    fn take_subtrees(&mut self, into: &mut Vec<Self>);
}

/// Drops the subtrees of `node` from a list on the heap, one level at a
/// time, so the depth of the tree costs no stack.
fn drop_subtrees<T: Subtrees>(node: &mut T) {
    let mut pending = Vec::new();
    node.take_subtrees(&mut pending);
    while let Some(mut subtree) = pending.pop() {
        subtree.take_subtrees(&mut pending);
    }
}

impl Subtrees for Expr {
    fn take_subtrees(&mut self, into: &mut Vec<Expr>) {
        match std::mem::replace(&mut self.kind, ExprKind::Pi) {
            ExprKind::Neg(inner) | ExprKind::Call(_, inner) => into.push(*inner),
            ExprKind::Binary(_, left, right) => into.extend([*left, *right]),
            ExprKind::Number(_) | ExprKind::Var(_) | ExprKind::Pi => {}
        }
    }
}

impl Drop for Expr {
    fn drop(&mut self) {
        if !matches!(self.kind, ExprKind::Number(_) | ExprKind::Var(_) | ExprKind::Pi) {
            drop_subtrees(self);
        }
    }
}

impl Subtrees for Cond {
    fn take_subtrees(&mut self, into: &mut Vec<Cond>) {
        let leaf_expr = || Expr { kind: ExprKind::Pi, span: self.span };
        let leaf = CondKind::Compare(CmpOp::Eq, leaf_expr(), leaf_expr());
        match std::mem::replace(&mut self.kind, leaf) {
            CondKind::Not(inner) => into.push(*inner),
            CondKind::And(left, right) | CondKind::Or(left, right) => into.extend([*left, *right]),
            CondKind::Compare(..) => {}
        }
    }
}

impl Drop for Cond {
    fn drop(&mut self) {
        if !matches!(self.kind, CondKind::Compare(..)) {
            drop_subtrees(self);
        }
    }
}

impl Subtrees for Obj {
    fn take_subtrees(&mut self, into: &mut Vec<Obj>) {
        match std::mem::replace(&mut self.kind, ObjKind::Group(Vec::new())) {
            ObjKind::Translate(inner, _) | ObjKind::Rotate(inner, _) | ObjKind::Scale(inner, _) => into.push(*inner),
            ObjKind::Group(mut members) => into.append(&mut members),
            ObjKind::Var(_) | ObjKind::Sphere { .. } | ObjKind::Plane { .. } | ObjKind::Box { .. } => {}
        }
    }
}

impl Drop for Obj {
    fn drop(&mut self) {
        if !matches!(self.kind, ObjKind::Var(_) | ObjKind::Sphere { .. } | ObjKind::Plane { .. } | ObjKind::Box { .. })
        {
            drop_subtrees(self);
        }
    }
}

impl Subtrees for Instr {
    fn take_subtrees(&mut self, into: &mut Vec<Instr>) {
        if let InstrKind::If(_, then, otherwise) = &mut self.kind {
            into.append(then);
            into.extend(otherwise.take().into_iter().flatten());
        }
    }
}

impl Drop for Instr {
    fn drop(&mut self) {
        if matches!(self.kind, InstrKind::If(..)) {
            drop_subtrees(self);
        }
    }
}
