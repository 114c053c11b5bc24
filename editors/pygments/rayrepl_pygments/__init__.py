"""Pygments support for rayrepl's `.ray` scene language: the lexer `ray`."""

from .lexer import RayLexer

__all__ = ["RayLexer"]
