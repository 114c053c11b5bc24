//! rayrepl: an interpreter and ray tracer for the `.ray` scene language.
//!
//! The pipeline, one module per arrow: text → tokens → AST with spans
//! ([`lang::parser`]) → evaluation ([`lang::eval`]) → a scene of flat
//! primitives ([`scene`]), checked for the mistakes that spoil a picture
//! ([`lint`]) → BVH ([`render::bvh`]) → rays and shading ([`render`]) →
//! image file ([`output`]). [`pipeline`] is the one road from a program to a
//! picture that every front-end takes; [`session`] keeps a program across
//! inputs and hands what it shows, pictures included, to a front-end, which
//! previews them where it can (the terminal's previews are in `terminal`,
//! the notebook's and the page's pictures are PNG bytes). [`explain`] tells
//! why a pixel has its colour; [`ide`] answers what editors of the language
//! ask (completion, help, hovers), for the session and the language server.
//! ARCHITECTURE.md gives the layers and the rules between them.

pub mod animation;
#[cfg(feature = "terminal")]
pub mod app;
#[cfg(feature = "terminal")]
pub mod cli;
pub mod clock;
pub mod compare;
mod data_dir;
pub mod explain;
pub mod ide;
#[cfg(feature = "terminal")]
mod job;
#[cfg(feature = "jupyter")]
pub mod jupyter;
pub mod lang;
mod lessons;
pub mod lint;
#[cfg(feature = "lsp")]
pub mod lsp;
pub mod output;
pub mod pipeline;
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
