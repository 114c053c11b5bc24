"""The Pygments lexer of `.ray` files, installed as a package and found the
way nbconvert and Sphinx find it, checked against rayrepl's own reading:
every scenario and valid test case lexes without an `Error` token, each
word of the words table gets its class's token type and no other name
does, the invalid cases that rayrepl's lexer rejects have their first
`Error` where `rayrepl --check` puts the error, and a few lines have every
token written out.
"""

import inspect
import pathlib
import re
import unittest

import pygments
import pygments.lexers
from pygments.formatters import HtmlFormatter
from pygments.token import Comment, Error, Keyword, Name, Number, Operator, Punctuation, Text, Whitespace

ROOT = pathlib.Path(__file__).resolve().parents[3]
FOLDERS = ["scenarios", "tests/cases/valid", "tests/cases/warnings"]


def table_words():
    """The words of the language, read from the table itself (not from the
    lexer, which is what is tested): the keyword(...) and opener(...) rows,
    and the predefined names (`time`)."""
    table = (ROOT / "src/lang/words.rs").read_text(encoding="utf-8")
    rows = re.finditer(r'\b(?:keyword|opener)\("([a-z]+)"|text: "([a-z]+)", kind: Kind::Predefined', table)
    return {row[1] or row[2] for row in rows}


def lex(text):
    """The tokens of `text` as the installed lexer `ray` reads them, blanks left out."""
    lexer = pygments.lexers.get_lexer_by_name("ray")
    return [(token, value) for token, value in lexer.get_tokens(text) if token is not Whitespace]


def ray_files(folders):
    """The `.ray` files of `folders`, in order."""
    return sorted(path for folder in folders for path in (ROOT / folder).glob("*.ray"))


class Lookup(unittest.TestCase):
    """Pygments finds the lexer by the names nbconvert, Sphinx and pygmentize use."""

    def test_by_name_filename_and_mimetype(self):
        lexer = pygments.lexers.get_lexer_by_name("ray")
        self.assertEqual(type(lexer).__module__, "rayrepl_pygments.lexer", "found through the package's entry point")
        self.assertEqual(lexer.name, "Ray")
        self.assertIs(pygments.lexers.find_lexer_class_for_filename("x.ray"), type(lexer))
        self.assertIs(type(pygments.lexers.get_lexer_for_mimetype("text/x-ray")), type(lexer))

    def test_html_has_a_class_per_token_type(self):
        # As nbconvert and Sphinx write it: a type below a standard one has the standard class too.
        html = pygments.highlight("translate sphere", pygments.lexers.get_lexer_by_name("ray"), HtmlFormatter())
        self.assertIn('<span class="kt kt-Transformation">translate</span>', html)
        self.assertIn('<span class="kt">sphere</span>', html)

    def test_the_installed_lexer_is_the_committed_one(self):
        lexer = pygments.lexers.get_lexer_by_name("ray")
        installed = pathlib.Path(inspect.getsourcefile(type(lexer)))
        committed = ROOT / "editors/pygments/rayrepl_pygments/lexer.py"
        self.assertEqual(installed.read_text(encoding="utf-8"), committed.read_text(encoding="utf-8"))


class Files(unittest.TestCase):
    """Every scenario and valid test case, as rayrepl reads it."""

    def test_valid_files_have_no_error_and_words_their_types(self):
        words = table_words()
        self.assertGreater(len(words), 30, "the words read from src/lang/words.rs")
        files = ray_files(FOLDERS)
        self.assertGreater(len(files), 40, "the scenarios and valid cases")
        for path in files:
            text = path.read_text(encoding="utf-8")
            tokens = lex(text)
            where = path.relative_to(ROOT)
            with self.subTest(file=str(where)):
                errors = [value for token, value in tokens if token in Error]
                self.assertEqual(errors, [], f"{where}: Error tokens")
                for token, value in tokens:
                    if token in Comment or token in Number or token in Operator or token in Punctuation:
                        continue
                    # A word of the table is a keyword, a builtin or an attribute, never a plain name.
                    plain = token is Name or token is Name.Function
                    self.assertEqual(plain, value not in words, f"{where}: `{value}` is {token}")

    def test_every_word_of_the_table_alone(self):
        for word in sorted(table_words()):
            with self.subTest(word=word):
                [(token, value)] = lex(word)
                self.assertEqual(value, word)
                self.assertTrue(token in Keyword or token in Name.Builtin or token in Name.Attribute, token)

    def test_rejected_characters_are_errors_where_rayrepl_says(self):
        # The invalid cases whose first error is the lexer's, as the snapshots of `rayrepl --check` give it.
        lexing_error = re.compile(
            r"^error: (?:unexpected character|invisible character|`(?://|/\*)` does not start a comment).*\n"
            r" --> (\S+\.ray):(\d+):(\d+)$",
            re.MULTILINE,
        )
        found = 0
        for snapshot in sorted((ROOT / "tests/snapshots/file").glob("*.snap")):
            match = lexing_error.search(snapshot.read_text(encoding="utf-8"))
            if not match:
                continue
            found += 1
            path, line, column = match[1], int(match[2]), int(match[3])
            text = (ROOT / path).read_text(encoding="utf-8")
            lexer = pygments.lexers.get_lexer_by_name("ray")
            offset = 0
            for token, value in lexer.get_tokens(text):
                if token in Error:
                    break
                offset += len(value)
            before = text.removeprefix("\ufeff")[:offset]
            where = (before.count("\n") + 1, offset - (before.rfind("\n") + 1) + 1)
            with self.subTest(file=path):
                self.assertEqual(where, (line, column), f"{path}: the first Error token")
        self.assertGreaterEqual(found, 10, "the snapshots of lexing errors")


# Lines with every token (blanks left out) written out.
KNOWN_LINES = [
    (
        "proc branch(x, l) # a branch",
        [
            (Keyword, "proc"), (Name.Function, "branch"), (Punctuation, "("), (Name, "x"), (Punctuation, ","),
            (Name, "l"), (Punctuation, ")"), (Comment.Single, "# a branch"),
        ],
    ),
    (
        "let r = sqrt(2.5e-1) * time - pi <= .5 + 1e3 / 7E+1",
        [
            (Keyword.Reserved, "let"), (Name, "r"), (Operator, "="), (Name.Builtin, "sqrt"), (Punctuation, "("),
            (Number.Float, "2.5e-1"), (Punctuation, ")"), (Operator, "*"), (Name.Builtin.Pseudo, "time"),
            (Operator, "-"), (Keyword.Constant, "pi"), (Operator, "<="), (Number.Float, ".5"), (Operator, "+"),
            (Number.Float, "1e3"), (Operator, "/"), (Number.Float, "7E+1"),
        ],
    ),
    (
        "put translate sphere center 0,0,0 radius 1 kd 1 ks 0.5 phong 2 color 9,9,9 end by 1,2,3 end",
        [
            (Keyword.Reserved, "put"), (Keyword.Type.Transformation, "translate"), (Keyword.Type, "sphere"),
            (Name.Attribute, "center"), (Number.Integer, "0"), (Punctuation, ","), (Number.Integer, "0"),
            (Punctuation, ","), (Number.Integer, "0"), (Name.Attribute, "radius"), (Number.Integer, "1"),
            (Name.Attribute.Texture, "kd"), (Number.Integer, "1"), (Name.Attribute.Texture, "ks"),
            (Number.Float, "0.5"), (Name.Attribute.Texture, "phong"), (Number.Integer, "2"),
            (Name.Attribute.Texture, "color"), (Number.Integer, "9"), (Punctuation, ","), (Number.Integer, "9"),
            (Punctuation, ","), (Number.Integer, "9"), (Keyword, "end"), (Name.Attribute, "by"),
            (Number.Integer, "1"), (Punctuation, ","), (Number.Integer, "2"), (Punctuation, ","),
            (Number.Integer, "3"), (Keyword, "end"),
        ],
    ),
    (
        "if spheres != 2end | !x & 2e then camera distance 1 angle 1 end else ambient 1 end",
        [
            (Keyword, "if"), (Name, "spheres"), (Operator, "!="), (Number.Integer, "2"), (Keyword, "end"),
            (Operator, "|"), (Operator, "!"), (Name, "x"), (Operator, "&"), (Number.Integer, "2"), (Name, "e"),
            (Keyword, "then"), (Keyword.Declaration, "camera"), (Name.Attribute, "distance"), (Number.Integer, "1"),
            (Name.Attribute, "angle"), (Number.Integer, "1"), (Keyword, "end"), (Keyword, "else"),
            (Keyword.Declaration, "ambient"), (Number.Integer, "1"), (Keyword, "end"),
        ],
    ),
    (
        "x2end colour tan (1) // no $ 5. sphère",
        [
            (Name, "x2end"), (Name, "colour"), (Name.Function, "tan"), (Punctuation, "("), (Number.Integer, "1"),
            (Punctuation, ")"), (Error, "//"), (Name, "no"), (Error, "$"), (Number.Integer, "5"), (Error, "."),
            (Name, "sph"), (Error, "è"), (Name, "re"),
        ],
    ),
    (
        # A notebook's cell holds commands: each is its whole line.
        "  :save out 1.png",
        [(Keyword.Pseudo, ":save"), (Text, " out 1.png")],
    ),
    (
        "let\u00a0x = 1\u2212y;",
        [
            (Keyword.Reserved, "let"), (Error, "\u00a0"), (Name, "x"), (Operator, "="), (Number.Integer, "1"),
            (Error, "\u2212"), (Name, "y"), (Error, ";"),
        ],
    ),
]


class KnownLines(unittest.TestCase):
    """Lines with every token's type written out."""

    def test_known_lines(self):
        for line, expected in KNOWN_LINES:
            with self.subTest(line=line):
                self.assertEqual(lex(line + "\n"), expected)


if __name__ == "__main__":
    unittest.main()
