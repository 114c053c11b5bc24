//! The interactive session (SPEC 7) and piped scripts.
