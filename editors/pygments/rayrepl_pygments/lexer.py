"""The Pygments lexer of rayrepl's `.ray` scene language.

Generated from the words table (src/lang/words.rs) by tools/generate/src/pygments.rs:
do not edit; cargo run -p generate -- write makes it again.
"""

from pygments.lexer import RegexLexer, bygroups, words
from pygments.token import Comment, Error, Keyword, Name, Number, Operator, Punctuation, Text, Whitespace

__all__ = ["RayLexer"]

# What a name is made of, as rayrepl's lexer reads it.
NAME = r"[A-Za-z_][A-Za-z0-9_]*"
# After a word: not more of a name (`spheres` is a name, not `sphere`).
WORD_END = r"(?![A-Za-z0-9_])"
# The blanks rayrepl's lexer skips; it rejects any other space.
BLANK = r"[ \t\r\n\x0b\x0c]"


class RayLexer(RegexLexer):
    """Scenes for rayrepl, a ray tracer with its own small language."""

    name = "Ray"
    aliases = ["ray"]
    filenames = ["*.ray"]
    mimetypes = ["text/x-ray"]

    # Tried in this order at each place: a command's line first (a cell
    # of a notebook holds commands), a keyword before a name, `proc f`
    # before `proc`, a whole integer before a number with a point.
    tokens = {
        "root": [
            (r"^([ \t]*)(:[A-Za-z_]+)([^\n]*)", bygroups(Whitespace, Keyword.Pseudo, Text)),
            (BLANK + r"+", Whitespace),
            (r"#.*", Comment.Single),
            (r"(proc)(" + BLANK + r"+)(" + NAME + r")", bygroups(Keyword, Whitespace, Name.Function)),
            (words(["camera", "ambient", "light"], suffix=WORD_END), Keyword.Declaration),
            (words(["distance", "angle", "vector", "rotation", "intensity", "center", "radius", "shift", "length", "by"], suffix=WORD_END), Name.Attribute),
            (words(["proc", "if", "then", "else", "end"], suffix=WORD_END), Keyword),
            (words(["let", "object", "put", "print"], suffix=WORD_END), Keyword.Reserved),
            (words(["sphere", "plane", "box"], suffix=WORD_END), Keyword.Type),
            (words(["kd", "ks", "phong", "color"], suffix=WORD_END), Name.Attribute.Texture),
            (words(["translate", "rotate", "scale", "group"], suffix=WORD_END), Keyword.Type.Transformation),
            (words(["sin", "cos", "sqrt"], suffix=WORD_END), Name.Builtin),
            (words(["pi"], suffix=WORD_END), Keyword.Constant),
            (words(["time"], suffix=WORD_END), Name.Builtin.Pseudo),
            (NAME + r"(?=" + BLANK + r"*\()", Name.Function),
            (NAME, Name),
            (r"[0-9]+(?!\.[0-9]|[eE][+-]?[0-9])", Number.Integer),
            (r"(?:[0-9]+(?:\.[0-9]+)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?", Number.Float),
            (r"//|/\*", Error),
            (r"!=|<=|>=|=|<|>|\+|-|\*|/|&|\||!", Operator),
            (r",|\(|\)", Punctuation),
            (r".", Error),
        ],
    }
