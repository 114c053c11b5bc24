//! The tokens of the `.ray` language (SPEC 1): what the lexer makes and the
//! grammar reads. How each keyword is spelt is in the words table
//! ([`super::words`]), which also says how a token is written.

use super::name::Name;

/// One token of the `.ray` language.
#[derive(Debug, Clone, PartialEq)]
pub enum Token {
    /// A number literal: `3`, `0.75`, `.5`, `1e3`.
    Number(f64),
    /// A name that is not a keyword.
    Ident(Name),
    /// `ambient`
    Ambient,
    /// `angle`
    Angle,
    /// `box`
    Box,
    /// `by`
    By,
    /// `camera`
    Camera,
    /// `center`
    Center,
    /// `color`
    Color,
    /// `cos`
    Cos,
    /// `distance`
    Distance,
    /// `else`
    Else,
    /// `end`
    End,
    /// `group`
    Group,
    /// `if`
    If,
    /// `intensity`
    Intensity,
    /// `kd`
    Kd,
    /// `ks`
    Ks,
    /// `length`
    Length,
    /// `let`
    Let,
    /// `light`
    Light,
    /// `object`
    Object,
    /// `phong`
    Phong,
    /// `pi`
    Pi,
    /// `plane`
    Plane,
    /// `print` (an extension of this project: not in SPEC 1)
    Print,
    /// `proc`
    Proc,
    /// `put`
    Put,
    /// `radius`
    Radius,
    /// `rotate`
    Rotate,
    /// `rotation`
    Rotation,
    /// `scale`
    Scale,
    /// `shift`
    Shift,
    /// `sin`
    Sin,
    /// `sphere`
    Sphere,
    /// `sqrt`
    Sqrt,
    /// `then`
    Then,
    /// `translate`
    Translate,
    /// `vector`
    Vector,
    /// `+`
    Plus,
    /// `-`
    Minus,
    /// `*`
    Star,
    /// `/`
    Slash,
    /// `(`
    LParen,
    /// `)`
    RParen,
    /// `,`
    Comma,
    /// `=`
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
    /// `&`
    And,
    /// `|`
    Or,
    /// `!`
    Bang,
}
