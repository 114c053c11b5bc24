//! Helpers shared by the integration tests.

pub mod cases;
pub mod interrupt;
pub mod limited;
pub mod programs;
pub mod scenes;
pub mod sexpr;
