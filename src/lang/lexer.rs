//! Turning source text into tokens with spans.
