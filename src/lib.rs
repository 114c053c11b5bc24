//! rayrepl: an interpreter and ray tracer for the `.ray` scene language.
//!
//! The pipeline, one module per arrow: text → tokens → AST with spans
//! ([`lang::parser`]) → evaluation ([`lang::eval`]) → a scene of flat
//! primitives ([`scene`]), checked for the mistakes that spoil a picture
//! ([`lint`]) → BVH ([`render::bvh`]) → rays and shading ([`render`]) →
//! image file ([`output`]) or terminal preview ([`repl`]). [`explain`] tells
//! why a pixel has its colour.

pub mod animation;
#[cfg(feature = "terminal")]
pub mod app;
#[cfg(feature = "terminal")]
pub mod cli;
pub mod clock;
pub mod compare;
mod data_dir;
pub mod explain;
#[cfg(feature = "terminal")]
mod job;
#[cfg(feature = "jupyter")]
pub mod jupyter;
pub mod lang;
pub mod lint;
#[cfg(feature = "lsp")]
pub mod lsp;
pub mod output;
pub mod playback;
pub mod pov;
pub mod presentation;
pub mod process;
pub mod render;
pub mod scene;
pub mod session;
pub mod settings;
#[cfg(test)]
mod source_tree;
#[cfg(feature = "terminal")]
pub mod terminal;
mod warned;
