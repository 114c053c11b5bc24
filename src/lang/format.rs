//! Formatting a `.ray` program in the house style of the bundled scenarios
//! (`rayrepl fmt`; a language server or a web page can call [`format`] too).
//!
//! The formatter reads the lexer's tokens and their byte spans; the
//! comments, which the lexer skips, are what follows the last token of a
//! line from a `#` on (no token holds a `#`, and a comment runs to the end
//! of its line). It changes only blanks: the tokens, so the program and its
//! scene, are those of the text it was given. The rules:
//!
//! - **The lines are the author's.** A line end between two tokens stays
//!   and none is added: lines are never joined or split (a one-line
//!   `put sphere ... end` stays on one line, and the scenarios' shapes
//!   written over three lines stay on three). A run of blank lines becomes
//!   one; blank lines at the start and at the end go; the text ends with
//!   one `\n`, also when it was written with `\r\n`.
//! - **Indentation follows the constructs `end` closes**, two spaces a
//!   level: a line inside a `proc`, an `if`, the camera, a light, a shape, a
//!   transformation or a group is two columns right of the construct; a line
//!   that starts with `end`, `else`, `then` or `by` is at the construct's
//!   own column. A construct's column is its line's, except for the object
//!   right after `put` or `object NAME =`, whose column is its own, so that
//!   the lines of a long object hang under its first word:
//!
//!   ```text
//!   put sphere center 0, 0, 0 radius 1
//!         kd 0.8 ks 0.3 phong 50 color 220, 40, 40
//!       end
//!   ```
//!
//!   A line after one that ends with a `,` starts under the first item of
//!   that list (the arguments of a call, the parameters of a procedure, a
//!   triple, a colour, the values of a `print`), as
//!   `tests/cases/valid/comments_everywhere.ray` writes them; a line after
//!   one that ends with an operator, `(` or `put` (an expression or an
//!   instruction cut in two) is two columns further right than the lines
//!   around it. Indentation stops growing at column [`MAX_INDENT`], so that
//!   a program nested thousands deep does not become gigabytes of spaces.
//! - **One space between tokens**, except none before `,` and `)`, after
//!   `(`, after a unary `-` or `!` (`-pi / 4`, `!(i < 8)`), and between a
//!   name or `sin`, `cos`, `sqrt` and its `(` (`sin(a)`, `row(n - 1)`). Two
//!   minus signs keep a space (`- -x`). A run of spaces after a `,` is kept:
//!   it aligns arguments in columns (`menger(x,     y, z - t, t, d)` in
//!   `scenarios/menger.ray`).
//! - **Comments stay where they are, word for word** (blanks at their end
//!   removed). A comment on its own line is indented as a line of code
//!   would be there. A comment after code keeps its column, so comments
//!   lined up in a column stay lined up, unless the code now reaches it:
//!   then it comes one space after the code.
//! - A byte-order mark at the start stays; blanks at the start of a line
//!   (tabs included) become the indentation, those at its end go.

use std::ops::Range;

use super::diagnostic::Diagnostic;
use super::lexer::{BYTE_ORDER_MARK, Lexer, WordToken};
use super::parser::parse_items;
use super::source::SourceId;
use super::token::Token;
use super::words::Word;

/// The column past which lines are indented no further.
pub const MAX_INDENT: usize = 200;

/// The columns one level of nesting indents.
const INDENT_STEP: usize = 2;

/// `text` formatted by the rules of this module's documentation, or the
/// diagnostic of the lexer or the parser when it is not a program (its
/// items may come in any order, as in a session's script: the order of a
/// file is not the formatter's business). Its spans point into `text`,
/// named `source`.
pub fn format(source: SourceId, text: &str) -> Result<String, Diagnostic> {
    parse_items(source, text)?;
    let mut lexer = Lexer::new(source, text);
    let mut tokens = Vec::new();
    while let Some(token) = lexer.next_word() {
        tokens.push(token.map_err(|diagnostic| *diagnostic)?);
    }
    let body_start = if text.starts_with(BYTE_ORDER_MARK) { BYTE_ORDER_MARK.len_utf8() } else { 0 };
    let mut layout = Layout::new(text, &tokens);
    let mut formatted = String::with_capacity(text.len() + text.len() / 8);
    if body_start > 0 {
        formatted.push(BYTE_ORDER_MARK);
    }
    let mut blank_pending = false;
    for line in source_lines(text, body_start, &tokens) {
        if line.tokens.is_empty() && line.comment.is_none() {
            blank_pending = formatted.len() > body_start;
            continue;
        }
        if blank_pending {
            formatted.push('\n');
            blank_pending = false;
        }
        layout.line(&mut formatted, &line);
        formatted.push('\n');
    }
    Ok(formatted)
}

/// One line of the text given: the tokens on it, and the comment that ends it.
#[derive(Debug)]
struct SourceLine<'a> {
    /// The indices of its tokens.
    tokens: Range<usize>,
    /// Its comment, if it has one.
    comment: Option<Comment<'a>>,
}

/// A comment, from its `#` to the end of its line, without the blanks that end it.
#[derive(Debug)]
struct Comment<'a> {
    text: &'a str,
    /// The characters before its `#` on its line.
    column: usize,
}

/// The lines of `text` from byte `body_start` on, each with its tokens (of
/// `tokens`, the tokens of `text`) and its comment. Lines end at `\n` only,
/// as for the lexer, which reads a lone `\r` as a blank.
fn source_lines<'a>(text: &'a str, body_start: usize, tokens: &[WordToken]) -> Vec<SourceLine<'a>> {
    let mut lines = Vec::new();
    let mut next_token = 0;
    let mut start = body_start;
    for line in text[body_start..].split('\n') {
        let end = start + line.len();
        let first = next_token;
        while tokens.get(next_token).is_some_and(|((token_start, _, _), _)| *token_start < end) {
            next_token += 1;
        }
        let code_end = if next_token > first { tokens[next_token - 1].0.2 } else { start };
        let comment = text[code_end..end].find('#').map(|at| Comment {
            text: text[code_end + at..end].trim_end(),
            column: text[start..code_end + at].chars().count(),
        });
        lines.push(SourceLine { tokens: first..next_token, comment });
        start = end + 1;
    }
    lines
}

/// Lays out the lines of a program one after the other, knowing the
/// constructs and the lists open at each.
struct Layout<'a> {
    text: &'a str,
    tokens: &'a [WordToken],
    /// The column of each construct open, innermost last.
    frames: Vec<usize>,
    /// The column of the first token inside each `(` open, innermost last.
    parentheses: Vec<usize>,
    /// The column of the first token after the last word that starts a
    /// list of expressions separated by commas outside parentheses
    /// (`center`, `color`, `print`...).
    word_list: Option<usize>,
    /// The last token laid out.
    last_token: Option<usize>,
}

impl<'a> Layout<'a> {
    /// A layout of `tokens`, the tokens of `text`, before its first line.
    fn new(text: &'a str, tokens: &'a [WordToken]) -> Layout<'a> {
        Layout { text, tokens, frames: Vec::new(), parentheses: Vec::new(), word_list: None, last_token: None }
    }

    /// Writes `line`, formatted, to `out` (without its line end).
    fn line(&mut self, out: &mut String, line: &SourceLine) {
        let row_start = out.len();
        if line.tokens.is_empty() {
            push_spaces(out, self.inner_indent());
        } else {
            self.code(out, line.tokens.clone());
        }
        if let Some(comment) = &line.comment {
            if !line.tokens.is_empty() {
                let code_width = out.len() - row_start;
                push_spaces(out, comment.column.max(code_width + 1) - code_width);
            }
            out.push_str(comment.text);
        }
    }

    /// Writes the tokens `range`, a line's, indented and spaced, and
    /// follows the constructs and the lists they open and close.
    fn code(&mut self, out: &mut String, range: Range<usize>) {
        let row_start = out.len();
        let indent = match self.tokens[range.start].0.1 {
            Token::End | Token::Else | Token::By | Token::Then => self.frames.last().copied().unwrap_or(0),
            _ => self.inner_indent(),
        }
        .min(MAX_INDENT);
        push_spaces(out, indent);
        let mut anchor = indent;
        for index in range.clone() {
            if index > range.start {
                self.space_before(out, index);
            }
            let column = out.len() - row_start;
            match self.last_token.map(|before| &self.tokens[before].0.1) {
                Some(Token::LParen) => self.parentheses.push(column),
                Some(
                    Token::Center
                    | Token::Length
                    | Token::Vector
                    | Token::Rotation
                    | Token::By
                    | Token::Color
                    | Token::Print,
                ) => {
                    self.word_list = Some(column);
                }
                _ => {}
            }
            let ((start, token, end), word) = &self.tokens[index];
            out.push_str(&self.text[*start..*end]);
            match token {
                Token::End => {
                    self.frames.pop();
                }
                Token::RParen => {
                    self.parentheses.pop();
                }
                _ if word.is_some_and(Word::opens) => {
                    if self.hangs(index) {
                        anchor = column;
                    }
                    self.frames.push(anchor);
                }
                _ => {}
            }
            self.last_token = Some(index);
        }
    }

    /// The indentation of a line that does not start with `end`, `else`,
    /// `by` or `then`: inside the innermost construct; after a `,` that
    /// ends a line, under the first item of its list (the arguments of a
    /// call, the parameters of a procedure, a triple, a colour, the values
    /// of a `print`); further right when the line before leaves an
    /// expression or an instruction unfinished otherwise.
    fn inner_indent(&self) -> usize {
        let inside = self.frames.last().map_or(0, |column| column + INDENT_STEP);
        let indent = match self.last_token.map(|index| &self.tokens[index].0.1) {
            Some(Token::Comma) => self.parentheses.last().copied().or(self.word_list).unwrap_or(inside + INDENT_STEP),
            Some(
                Token::Plus
                | Token::Minus
                | Token::Star
                | Token::Slash
                | Token::LParen
                | Token::Eq
                | Token::Ne
                | Token::Lt
                | Token::Le
                | Token::Gt
                | Token::Ge
                | Token::And
                | Token::Or
                | Token::Bang
                | Token::Put,
            ) => inside + INDENT_STEP,
            _ => inside,
        };
        indent.min(MAX_INDENT)
    }

    /// Whether the construct token `index` opens is the object of a `put`
    /// or of an `object NAME =`, whose lines hang under its first word.
    fn hangs(&self, index: usize) -> bool {
        let before = |back: usize| index.checked_sub(back).map(|at| &self.tokens[at].0.1);
        matches!(before(1), Some(Token::Put))
            || matches!((before(3), before(1)), (Some(Token::Object), Some(Token::Eq)))
    }

    /// Writes the blanks between token `index` and the one before it on its line.
    fn space_before(&self, out: &mut String, index: usize) {
        let (_, previous, previous_end) = &self.tokens[index - 1].0;
        let (start, next, _) = &self.tokens[index].0;
        let gap = &self.text[*previous_end..*start];
        if *previous == Token::Comma && gap.len() > 1 && gap.bytes().all(|byte| byte == b' ') {
            out.push_str(gap);
            return;
        }
        let spaced = match (previous, next) {
            (_, Token::RParen | Token::Comma) | (Token::LParen, _) | (Token::Bang, _) => false,
            (Token::Ident(_) | Token::Sin | Token::Cos | Token::Sqrt, Token::LParen) => false,
            (Token::Minus, Token::Minus) => true,
            (Token::Minus, _) => !self.is_unary(index - 1),
            _ => true,
        };
        if spaced {
            out.push(' ');
        }
    }

    /// Whether the `-` at token `index` is a unary minus: no operand ends
    /// right before it.
    fn is_unary(&self, index: usize) -> bool {
        let operand_before = index.checked_sub(1).is_some_and(|before| {
            matches!(self.tokens[before].0.1, Token::Number(_) | Token::Ident(_) | Token::Pi | Token::RParen)
        });
        !operand_before
    }
}

/// Writes `count` spaces.
fn push_spaces(out: &mut String, count: usize) {
    out.extend(std::iter::repeat_n(' ', count));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn formatted(text: &str) -> String {
        format(SourceId(0), text).expect("a program")
    }

    /// Checks that `text` formats as `expected`, and `expected` as itself.
    fn formats_as(text: &str, expected: &str) {
        assert_eq!(formatted(text), expected, "formatting:\n{text}");
        assert_eq!(formatted(expected), expected, "formatting again:\n{expected}");
    }

    #[test]
    fn a_formatted_program_is_left_as_it_is() {
        let text = "camera distance 8 angle 1 end\nambient 0.2\n";
        assert_eq!(formatted(text), text);
    }

    #[test]
    fn spaces_around_operators_commas_and_parentheses() {
        formats_as(
            "let  x=1+2*-3\nlet y = ( x-1 )/sqrt (x)\nball( x ,y,-(x) )\n",
            "let x = 1 + 2 * -3\nlet y = (x - 1) / sqrt(x)\nball(x, y, -(x))\n",
        );
    }

    #[test]
    fn conditions_are_spaced_and_negations_are_not() {
        formats_as("if ! ( a<b ) & a!=1|b>=2 then\nend\n", "if !(a < b) & a != 1 | b >= 2 then\nend\n");
    }

    #[test]
    fn two_minus_signs_keep_a_space() {
        formats_as("let x = 2 - -3 * - -1\n", "let x = 2 - -3 * - -1\n");
    }

    #[test]
    fn a_procedure_and_an_if_indent_their_bodies() {
        formats_as(
            "proc row (n)\nif n > 0 then\nball(n)\nrow(n - 1)\nelse\nball(0)\nend\nend\nrow(3)\n",
            "proc row(n)\n  if n > 0 then\n    ball(n)\n    row(n - 1)\n  else\n    ball(0)\n  end\nend\nrow(3)\n",
        );
    }

    #[test]
    fn an_else_if_chain_closes_with_its_ends() {
        formats_as(
            "if a < 1 then\nball(1)\nelse if a < 2 then\nball(2)\nend end\n",
            "if a < 1 then\n  ball(1)\nelse if a < 2 then\n  ball(2)\nend end\n",
        );
    }

    #[test]
    fn a_shape_put_over_several_lines_hangs_under_its_first_word() {
        formats_as(
            "proc ball(x)\nput sphere center x, 0, 0 radius 1\nkd 0.8 ks 0.3 phong 50 color 220, 40, 40\nend\nend\n",
            "proc ball(x)\n  put sphere center x, 0, 0 radius 1\n        kd 0.8 ks 0.3 phong 50 color 220, 40, 40\n      end\nend\n",
        );
    }

    #[test]
    fn transformations_over_several_lines_nest_with_their_by() {
        formats_as(
            "put rotate\ntranslate\nbox center 0, 0, 0 length 1, 1, 1\nkd 1 ks 0 phong 1 color 1, 2, 3\nend\nby 1, 0, 0\nend\nby tilt, 0, 0\nend\n",
            "put rotate\n      translate\n        box center 0, 0, 0 length 1, 1, 1\n          kd 1 ks 0 phong 1 color 1, 2, 3\n        end\n      by 1, 0, 0\n      end\n    by tilt, 0, 0\n    end\n",
        );
    }

    #[test]
    fn an_object_on_the_line_of_its_transformation_indents_from_the_line() {
        formats_as(
            "put translate sphere center 0, 0, 0 radius 1\nkd 1 ks 0 phong 1 color 1, 2, 3\nend by 0, 1, 0 end\n",
            "put translate sphere center 0, 0, 0 radius 1\n      kd 1 ks 0 phong 1 color 1, 2, 3\n    end by 0, 1, 0 end\n",
        );
    }

    #[test]
    fn the_members_of_a_named_group_hang_under_group() {
        formats_as(
            "object pair = group\n a\n      scale a by 2 end\n end\n",
            "object pair = group\n                a\n                scale a by 2 end\n              end\n",
        );
    }

    #[test]
    fn the_camera_and_a_light_over_several_lines() {
        formats_as(
            "camera\ndistance 8\nangle 1\nend\nlight vector 0, 0, 0\nintensity 1 end\n",
            "camera\n  distance 8\n  angle 1\nend\nlight vector 0, 0, 0\n  intensity 1 end\n",
        );
    }

    #[test]
    fn a_line_cut_after_an_operator_or_a_comma_is_indented_further() {
        formats_as(
            "proc f(a)\nlet x = a +\n2\nf(1,\n2)\nend\n",
            "proc f(a)\n  let x = a +\n    2\n  f(1,\n    2)\nend\n",
        );
    }

    #[test]
    fn a_list_cut_after_a_comma_goes_on_under_its_first_item() {
        formats_as(
            "light vector 0,\n0,\n0 intensity 1 end\nproc p(a,\nb)\nput sphere center a, b, 0 radius 1 kd 1 ks 0 phong 1 color 255,\n0, 0\nend\nend\np(1,\n2)\nprint a,\nb\n",
            "light vector 0,\n             0,\n             0 intensity 1 end\nproc p(a,\n       b)\n  put sphere center a, b, 0 radius 1 kd 1 ks 0 phong 1 color 255,\n                                                             0, 0\n      end\nend\np(1,\n  2)\nprint a,\n      b\n",
        );
    }

    #[test]
    fn then_on_its_own_line_is_under_its_if() {
        formats_as("if\n1 < 2 &\n2 < 3\nthen\nput a\nend\n", "if\n  1 < 2 &\n    2 < 3\nthen\n  put a\nend\n");
    }

    #[test]
    fn comments_on_their_own_line_are_indented_as_code() {
        formats_as(
            "# top\nproc f()\n# first\nput a\n        # last\nend\n",
            "# top\nproc f()\n  # first\n  put a\n  # last\nend\n",
        );
    }

    #[test]
    fn comments_after_code_keep_their_column_or_follow_the_code() {
        formats_as(
            "let a = 1       # one\nlet bb=2        # two\nlet c = 1 + 2 + 3# three  \n",
            "let a = 1       # one\nlet bb = 2      # two\nlet c = 1 + 2 + 3 # three\n",
        );
    }

    #[test]
    fn comments_keep_their_words() {
        formats_as("let a = 1 #  (x , y )  +-\n", "let a = 1 #  (x , y )  +-\n");
    }

    #[test]
    fn blank_lines_are_kept_one_at_a_time() {
        formats_as("\n\nlet a = 1\n\n\n\nlet b = 2\n# c\n\n\n", "let a = 1\n\nlet b = 2\n# c\n");
    }

    #[test]
    fn aligned_arguments_stay_aligned() {
        formats_as("f(x - t, y, z)\nf(x,     y, z)\n", "f(x - t, y, z)\nf(x,     y, z)\n");
    }

    #[test]
    fn tabs_line_ends_and_trailing_blanks() {
        formats_as("proc f()\r\n\tput a  \r\nend", "proc f()\n  put a\nend\n");
    }

    #[test]
    fn a_lone_carriage_return_is_a_blank_as_for_the_lexer() {
        // The lexer reads `# a\rlet x = 1` as one comment: it stays one.
        formats_as("let y = 2 # a\rlet x = 1\n", "let y = 2 # a\rlet x = 1\n");
        formats_as("let y =\r2\n", "let y = 2\n");
    }

    #[test]
    fn a_byte_order_mark_stays() {
        formats_as("\u{feff}\nlet  a = 1\n", "\u{feff}let a = 1\n");
    }

    #[test]
    fn words_that_touch_are_separated() {
        formats_as(
            "camera distance 8 angle 1end\nif a < 2then end\n",
            "camera distance 8 angle 1 end\nif a < 2 then end\n",
        );
    }

    #[test]
    fn nothing_formats_as_nothing() {
        formats_as("", "");
        formats_as("\n\n  \n", "");
        formats_as("  # only a comment", "# only a comment\n");
    }

    #[test]
    fn indentation_stops_growing() {
        let depth = MAX_INDENT;
        let text = format!("{}put a\n{}", "if 1 < 2 then\n".repeat(depth), "end\n".repeat(depth));
        let lines: Vec<String> = formatted(&text).lines().map(str::to_string).collect();
        assert_eq!(lines[depth], format!("{}put a", " ".repeat(MAX_INDENT)));
        assert_eq!(lines[depth + 1], format!("{}end", " ".repeat(MAX_INDENT)));
        assert_eq!(formatted(&formatted(&text)), formatted(&text));
    }

    #[test]
    fn a_text_that_is_not_a_program_gets_its_diagnostic() {
        let error = format(SourceId(0), "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 1, 2, 3\nput box")
            .expect_err("not a program");
        assert_eq!(error.message, "expected `end` to close this `sphere`");
        let error = format(SourceId(0), "let x = 1;").expect_err("not a program");
        assert_eq!(error.message, "unexpected character `;`");
    }
}
