//! Helpers shared by the integration tests.

// Each test crate compiles this module and uses only some of it.
#![allow(dead_code)]

pub mod cases;
pub mod interrupt;
pub mod limited;
pub mod programs;
pub mod scenes;
pub mod sexpr;
