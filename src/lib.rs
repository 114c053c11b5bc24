//! rayrepl: an interpreter and ray tracer for the `.ray` scene language.
//!
//! The pipeline, one module per arrow: text → tokens → AST with spans
//! ([`lang::parser`]) → evaluation ([`lang::eval`]) → a scene of flat
//! primitives ([`scene`]), checked for the mistakes that spoil a picture
//! ([`lint`]) → BVH ([`render::bvh`]) → rays and shading ([`render`]) →
//! image file ([`output`]) or terminal preview ([`repl`]). [`explain`] tells
//! why a pixel has its colour.

pub mod animation;
pub mod app;
pub mod cli;
pub mod clock;
pub mod explain;
pub mod failure;
mod job;
pub mod lang;
pub mod lint;
pub mod output;
pub mod playback;
mod pov;
mod progress;
pub mod render;
pub mod repl;
pub mod scene;
mod settings;
#[cfg(test)]
mod source_tree;
mod watch;
