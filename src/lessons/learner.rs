//! What the checks read of a learner's state: a view that names no
//! session, so that the lessons sit beside the session rather than inside
//! it. The session's state gives it for the learner's inputs; an
//! [`super::lesson_scene::LessonScene`] gives it for a lesson's own programs (its goals,
//! the answers it is proved with).

use crate::lang::SourceMap;
use crate::lang::eval::Origins;
use crate::lang::name::Name;
use crate::scene::{Primitive, Scene};

/// The language's state a check looks at: the scene built, where its parts
/// come from, the texts they were written in, and the global names.
pub(crate) trait Learner {
    /// The scene built so far.
    fn scene(&self) -> &Scene;
    /// Where the scene's parts come from in the program.
    fn origins(&self) -> &Origins;
    /// The texts the programs were written in, to say where a part was made.
    fn sources(&self) -> &SourceMap;
    /// Whether a `camera` was given (otherwise the default one is used).
    fn has_camera(&self) -> bool;
    /// Whether an `ambient` was given (otherwise the default one is used).
    fn has_ambient(&self) -> bool;
    /// The global numbers and their values, by name.
    fn numbers(&self) -> Vec<(Name, f64)>;
    /// The names of the global objects.
    fn object_names(&self) -> Vec<Name>;
    /// The primitives of the global object `name`, if it is one.
    fn object(&self, name: &str) -> Option<&[Primitive]>;
    /// The procedures and how many parameters each takes, by name.
    fn procedures(&self) -> Vec<(Name, usize)>;
}
