//! The process layer: what a running rayrepl process does around its work,
//! whatever its front-end. How it stops a job without leaving ([`cancel`]),
//! what stops it from outside ([`interruption`]: the signal that asked,
//! the writes that may block), how it hears the signals ([`signals`], with
//! the `signals` cargo feature, which every front-end's feature enables),
//! and how it speaks of its own failures on standard error ([`failure`]).

pub(crate) mod cancel;
pub mod failure;
pub(crate) mod interruption;
#[cfg(feature = "signals")]
pub mod signals;
