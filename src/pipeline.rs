//! The one road from a program to a picture, which every front-end takes:
//! a program evaluated and its scene checked ([`evaluation`]: the batch
//! renderer, the session, the language server and the grader), then the
//! scene, or a rectangle of it, rendered ([`picture`]: a still picture for
//! every front-end; an animation's frames go through
//! [`crate::animation`], which reuses what did not change between them).
//!
//! Where front-ends differ on purpose, the difference is a named parameter
//! of the road ([`Evaluation`]'s fields, a [`crate::render::Region`] and a
//! size), not a road of their own, so that they give the same warnings and
//! the same bytes by construction.

pub mod evaluation;
pub mod picture;

pub use evaluation::{Evaluated, Evaluation, Lint};
pub use picture::{PictureError, Rendered, render_picture};
