//! Similarity transformations (SPEC 4): rotations, translations and scalings,
//! applied to primitives.
