//! From lalrpop's syntax errors to messages a learner can act on.
//!
//! lalrpop reports the unexpected token and the list of grammar terminals it
//! would have accepted. This module reads the tokens before the error again to
//! know what is still open (`proc`, `sphere`, `(`...), groups the expected
//! terminals into categories ("an expression", "an object", "`end` to close
//! the `sphere` opened at line 12"), and recognises the usual mistakes (a
//! missing comma in a triple, a texture out of order, a misspelt keyword).

use lalrpop_util::ParseError;

use super::opens_construct;
use super::order::{ItemOrder, Phase, line_number};
use crate::lang::diagnostic::Diagnostic;
use crate::lang::lexer::{self, Lexer, Token};
use crate::lang::source::{SourceId, Span};
use crate::lang::suggest;

/// The error type of the generated parser.
pub(super) type GrammarError = ParseError<usize, Token, Box<Diagnostic>>;

/// The terminals that can start an expression.
const EXPRESSION_STARTS: [&str; 8] = ["NUMBER", "NAME", "(", "-", "pi", "sin", "cos", "sqrt"];
/// The terminals that can start an object expression.
const OBJECT_STARTS: [&str; 8] = ["sphere", "plane", "box", "translate", "rotate", "scale", "group", "NAME"];
/// The terminals that can start an instruction.
const INSTRUCTION_STARTS: [&str; 6] = ["let", "object", "put", "if", "print", "NAME"];
/// The keywords that start the items other than instructions.
const DEFINITION_STARTS: [&str; 4] = ["camera", "ambient", "light", "proc"];
/// The comparison operators.
const COMPARISONS: [&str; 6] = ["=", "!=", "<", "<=", ">", ">="];
/// Operators that may continue an expression or a condition; they are
/// always expected after one, so they are left out of messages.
const CONTINUATIONS: [&str; 6] = ["+", "-", "*", "/", "&", "|"];
/// The keywords of a texture, in their required order.
const TEXTURE: [&str; 4] = ["kd", "ks", "phong", "color"];
/// How a texture is written.
const TEXTURE_SHAPE: &str = "`kd ... ks ... phong ... color r, g, b`";

/// Turns an error of the generated parser into a diagnostic.
pub(super) fn syntax_error(
    source: SourceId,
    text: &str,
    line_offset: usize,
    order: &ItemOrder<'_>,
    error: GrammarError,
) -> Diagnostic {
    let place = Place { source, text, line_offset };
    match error {
        ParseError::User { error } => *error,
        ParseError::UnrecognizedEof { location, expected } => {
            let context = Context::scan(place, usize::MAX);
            end_of_file_error(place, &context, &Expected::new(expected), location)
        }
        ParseError::UnrecognizedToken { token: (start, token, end), expected } => {
            let context = Context::scan(place, start);
            let found = Found { token, span: Span::new(source, start, end) };
            token_error(place, &context, &Expected::new(expected), order, &found)
        }
        ParseError::ExtraToken { token: (start, _, end) } => {
            let span = Span::new(source, start, end);
            Diagnostic::error(span, format!("unexpected `{}`", place.slice(span)))
        }
        // Only lalrpop's own lexer reports invalid tokens; ours reports
        // unexpected characters as user errors.
        ParseError::InvalidToken { location } => {
            Diagnostic::error(last_character(place, location), "unexpected character")
        }
    }
}

/// The text being parsed and how to name positions in it.
#[derive(Debug, Clone, Copy)]
struct Place<'t> {
    source: SourceId,
    text: &'t str,
    line_offset: usize,
}

impl Place<'_> {
    /// The source text of `span`.
    fn slice(&self, span: Span) -> &str {
        self.text.get(span.start as usize..span.end as usize).unwrap_or("")
    }

    /// The line, as the user sees it, where `span` starts.
    fn line(&self, span: Span) -> usize {
        line_number(self.text, span.start as usize, self.line_offset)
    }
}

/// The token the parser did not expect.
struct Found {
    token: Token,
    span: Span,
}

/// What the tokens before an error leave open.
#[derive(Debug, Default)]
struct Context {
    /// Constructs opened and not yet closed by `end`, innermost last.
    openers: Vec<(Token, Span)>,
    /// Parentheses opened and not yet closed, innermost last, each with the
    /// token before it (`sqrt` in `sqrt(`).
    parens: Vec<(Span, Option<Token>)>,
    /// The last token before the error, and the one before it.
    previous: Option<(Token, Span)>,
    before_previous: Option<(Token, Span)>,
    /// The name of the triple being read, if any ("the centre").
    triple: Option<&'static str>,
}

impl Context {
    /// Reads the tokens of `place` that start before byte `limit`.
    fn scan(place: Place<'_>, limit: usize) -> Context {
        let mut context = Context::default();
        for token in Lexer::new(place.source, place.text) {
            let Ok((start, token, end)) = token else {
                break;
            };
            if start >= limit {
                break;
            }
            context.read(token, Span::new(place.source, start, end));
        }
        context
    }

    /// Takes one token into account.
    fn read(&mut self, token: Token, span: Span) {
        if opens_construct(&token) {
            self.openers.push((token.clone(), span));
        }
        match token {
            Token::End => {
                self.openers.pop();
            }
            Token::LParen => {
                let before = self.previous.as_ref().map(|(token, _)| token.clone());
                self.parens.push((span, before));
            }
            Token::RParen => {
                self.parens.pop();
            }
            _ => {}
        }
        if token.is_keyword() && !matches!(token, Token::Pi | Token::Sin | Token::Cos | Token::Sqrt) {
            self.triple = self.triple_after(&token);
        }
        self.before_previous = self.previous.take();
        self.previous = Some((token, span));
    }

    /// The name of the triple that follows `keyword`, if one does.
    fn triple_after(&self, keyword: &Token) -> Option<&'static str> {
        match keyword {
            Token::Center => Some("the centre"),
            Token::Length => Some("the lengths"),
            Token::Rotation | Token::Vector => Some("the rotation"),
            Token::Color => Some("the colour"),
            Token::By => match self.openers.last() {
                Some((Token::Translate, _)) => Some("the vector"),
                Some((Token::Rotate, _)) => Some("the rotation"),
                _ => None,
            },
            _ => None,
        }
    }

    /// The innermost open construct.
    fn innermost(&self) -> Option<&(Token, Span)> {
        self.openers.last()
    }
}

/// The terminals lalrpop would have accepted, as plain names (`end`, `NUMBER`).
struct Expected {
    names: Vec<String>,
}

impl Expected {
    /// Strips the quotes lalrpop puts around keywords and symbols.
    fn new(raw: Vec<String>) -> Expected {
        let names = raw
            .into_iter()
            .map(|name| match name.strip_prefix('"').and_then(|n| n.strip_suffix('"')) {
                Some(inner) => inner.to_string(),
                None => name,
            })
            .collect();
        Expected { names }
    }

    /// Whether `name` was expected.
    fn has(&self, name: &str) -> bool {
        self.names.iter().any(|n| n == name)
    }

    /// Whether any of `names` was expected.
    fn has_any(&self, names: &[&str]) -> bool {
        names.iter().any(|name| self.has(name))
    }

    /// The expected names, without the operators that merely could have
    /// continued what came before (unless nothing else is expected).
    fn essential(&self) -> Vec<&str> {
        let starts_expression = self.has("NUMBER");
        let essential: Vec<&str> = self
            .names
            .iter()
            .map(String::as_str)
            .filter(|name| !CONTINUATIONS.contains(name) || (starts_expression && *name == "-"))
            .collect();
        if essential.is_empty() { self.names.iter().map(String::as_str).collect() } else { essential }
    }

    /// The expected keywords, for "did you mean ...?".
    fn keywords(&self) -> impl Iterator<Item = &str> {
        self.names.iter().map(String::as_str).filter(|name| lexer::keyword(name).is_some())
    }
}

/// The error when the text ends too early.
fn end_of_file_error(place: Place<'_>, context: &Context, expected: &Expected, location: usize) -> Diagnostic {
    let span = last_character(place, location);
    if let Some((opener, opened)) = context.innermost().filter(|_| expected.has("end")) {
        let name = opener.to_string();
        let line = place.line(*opened);
        return Diagnostic::error(
            span,
            format!("unexpected end of file: the `{name}` opened at line {line} is not closed with `end`"),
        )
        .with_label("the file ends here")
        .with_related(*opened, format!("this `{name}` needs an `end`"));
    }
    let what = describe(place, context, &expected.essential());
    let message = match &context.previous {
        Some((_, previous)) => {
            format!("unexpected end of file: expected {what} after `{}`", place.slice(*previous))
        }
        None => format!("unexpected end of file: expected {what}"),
    };
    Diagnostic::error(span, message).with_label("the file ends here")
}

/// The span of the character that ends at byte `location` (the end of the
/// last token), or an empty span at 0 for an empty text.
fn last_character(place: Place<'_>, location: usize) -> Span {
    let before = place.text.get(..location).unwrap_or(place.text);
    match before.chars().next_back() {
        Some(last) => Span::new(place.source, before.len() - last.len_utf8(), before.len()),
        None => Span::new(place.source, 0, 0),
    }
}

/// The error at a token the parser did not expect.
fn token_error(
    place: Place<'_>,
    context: &Context,
    expected: &Expected,
    order: &ItemOrder<'_>,
    found: &Found,
) -> Diagnostic {
    let diagnostic = token_message(place, context, expected, order, found);
    let diagnostic = add_spelling_help(diagnostic, place, context, expected, found);
    if diagnostic.help.is_some() {
        return diagnostic;
    }
    match common_mistake(place, context, expected, found) {
        Some(help) => diagnostic.with_help(help),
        None => diagnostic,
    }
}

/// A hint for mistakes learners often make, recognised from the unexpected
/// token and what comes before it.
fn common_mistake(place: Place<'_>, context: &Context, expected: &Expected, found: &Found) -> Option<String> {
    let previous = context.previous.as_ref().map(|(token, _)| token);
    match (&found.token, previous) {
        (Token::Eq, Some(Token::Eq)) => Some("a comparison is written with a single `=`".to_string()),
        (Token::LParen, Some(Token::Number(_) | Token::RParen)) if expected.has("*") => {
            Some("to multiply, write `*`, like `2 * (x + 1)`".to_string())
        }
        (Token::Eq, Some(keyword)) if keyword.is_keyword() && expected.has("NUMBER") => {
            Some(format!("write the value right after `{keyword}`, without `=`"))
        }
        (Token::Comma, _) => match context.parens.last() {
            Some((_, Some(function @ (Token::Sin | Token::Cos | Token::Sqrt)))) => {
                Some(format!("`{function}` takes a single number"))
            }
            Some(_) if context.triple.is_some() => {
                Some("write the three parts without parentheses, like `0, 0, 1`".to_string())
            }
            _ => None,
        },
        (token, _) if token.is_keyword() && expects_only_a_name(expected) => {
            Some(format!("`{}` is a reserved word of the language; choose another name", place.slice(found.span)))
        }
        _ => None,
    }
}

/// The message (and label and related spans) for an unexpected token,
/// before any spelling help.
fn token_message(
    place: Place<'_>,
    context: &Context,
    expected: &Expected,
    order: &ItemOrder<'_>,
    found: &Found,
) -> Diagnostic {
    let span = found.span;
    let found_text = place.slice(span);
    let unexpected = format!("unexpected `{found_text}`");
    let innermost = context.innermost();
    if found.token == Token::End && innermost.is_none() {
        return Diagnostic::error(span, "unexpected `end`: nothing is open here")
            .with_label("this `end` closes nothing");
    }
    if found.token == Token::Else && !matches!(innermost, Some((Token::If, _))) {
        return Diagnostic::error(span, "unexpected `else`: it belongs between `if ... then` and `end`")
            .with_label("this `else` has no `if`");
    }
    if order.is_file() && order.phase() == Phase::Start && context.previous.is_none() {
        return Diagnostic::error(span, "a scenario file must start with `camera ... end`")
            .with_label("expected `camera` here")
            .with_help("begin the file with, for example, `camera distance 10 angle 1 end` then `ambient 0.2`");
    }
    if TEXTURE.contains(&found_text) && expected.has_any(&TEXTURE) {
        return Diagnostic::error(span, format!("the texture must be {TEXTURE_SHAPE} in this order"))
            .with_label("out of order");
    }
    if expected.has("let") && OBJECT_STARTS[..7].contains(&found_text) {
        return Diagnostic::error(span, format!("expected an instruction, found the object `{found_text}`"))
            .with_label("an object is not an instruction")
            .with_help("write `put` before it to add it to the scene, or `object name =` to give it a name");
    }
    let essential = expected.essential();
    match essential.as_slice() {
        [","] if context.triple.is_some() => {
            let triple = context.triple.unwrap_or("the triple");
            return Diagnostic::error(span, format!("expected `,` between the parts of {triple}"))
                .with_label("expected `,` before this");
        }
        ["then"] => {
            return Diagnostic::error(span, "expected `then` after the condition of `if`")
                .with_label("expected `then` before this");
        }
        [")"] => {
            if let Some((paren, _)) = context.parens.last() {
                return Diagnostic::error(span, "expected `)` to close the parenthesis")
                    .with_label("expected `)` before this")
                    .with_related(*paren, "the parenthesis opened here");
            }
        }
        _ => {}
    }
    let what = describe(place, context, &essential);
    let closes = essential.contains(&"end") && innermost.is_some();
    let message = match &context.previous {
        Some((_, previous)) if !closes => {
            format!("expected {what} after `{}`", place.slice(*previous))
        }
        _ => format!("expected {what}"),
    };
    let diagnostic = Diagnostic::error(span, message).with_label(unexpected);
    match innermost {
        Some((opener, opened)) if closes => diagnostic.with_related(*opened, format!("the `{opener}` opened here")),
        _ => diagnostic,
    }
}

/// Adds "did you mean `sphere`?" when a name near the error looks like a
/// misspelt keyword.
fn add_spelling_help(
    diagnostic: Diagnostic,
    place: Place<'_>,
    context: &Context,
    expected: &Expected,
    found: &Found,
) -> Diagnostic {
    if let Token::Ident(name) = &found.token {
        let suggestion = suggest::closest(name, expected.keywords())
            .or_else(|| suggest::closest(name, lexer::keyword_names()).filter(|_| name.len() >= 3));
        if let Some(keyword) = suggestion {
            return diagnostic.with_help(format!("did you mean `{keyword}`?"));
        }
    }
    let earlier = [&context.previous, &context.before_previous];
    for (token, span) in earlier.into_iter().flatten() {
        let Token::Ident(name) = token else { continue };
        if name.len() < 3 {
            continue;
        }
        if let Some(keyword) = suggest::closest(name, lexer::keyword_names()) {
            return diagnostic
                .with_related(*span, format!("`{}` is not a keyword, so it is read as a name", place.slice(*span)))
                .with_help(format!("did you mean `{keyword}`?"));
        }
    }
    diagnostic
}

/// Whether the parser wanted a new name there (after `let`, `object`,
/// `proc`, or in a parameter list).
fn expects_only_a_name(expected: &Expected) -> bool {
    matches!(expected.essential().as_slice(), ["NAME"] | ["NAME", ")"] | [")", "NAME"])
}

/// Describes the expected terminals in words: "an expression (...)",
/// "`end` to close the `sphere` opened at line 12", joined with "or".
fn describe(place: Place<'_>, context: &Context, essential: &[&str]) -> String {
    let mut left: Vec<&str> = essential.to_vec();
    let mut phrases: Vec<String> = Vec::new();
    let mut take = |left: &mut Vec<&str>, names: &[&str], phrase: &str| {
        left.retain(|name| !names.contains(name));
        phrases.push(phrase.to_string());
    };
    if left.contains(&"!") {
        take(&mut left, &EXPRESSION_STARTS, "a condition (like `x < 1`)");
        left.retain(|name| *name != "!");
    } else if left.contains(&"NUMBER") {
        take(&mut left, &EXPRESSION_STARTS, "an expression (a number, a name, `(`...)");
    }
    if left.contains(&"sphere") {
        take(&mut left, &OBJECT_STARTS, "an object (`sphere`, `plane`, `box`, a name...)");
    }
    if left.contains(&"let") {
        take(&mut left, &INSTRUCTION_STARTS, "an instruction (`let`, `object`, `put`, `if` or a procedure call)");
        left.retain(|name| !DEFINITION_STARTS.contains(name));
    }
    if left.contains(&"<") {
        take(&mut left, &COMPARISONS, "a comparison (`=`, `<`, `>`, `<=`, `>=` or `!=`)");
    }
    if left.contains(&"kd") {
        take(&mut left, &["kd"], &format!("the texture {TEXTURE_SHAPE}"));
    }
    let mut end = None;
    for name in left {
        match name {
            "NAME" => phrases.push("a name".to_string()),
            "NUMBER" => phrases.push("a number".to_string()),
            "end" => end = Some(end_phrase(place, context)),
            other => phrases.push(format!("`{other}`")),
        }
    }
    phrases.extend(end);
    join_with_or(&phrases)
}

/// "`end`", and what it would close if something is open.
fn end_phrase(place: Place<'_>, context: &Context) -> String {
    match context.innermost() {
        Some((opener, opened)) => format!("`end` to close the `{opener}` opened at line {}", place.line(*opened)),
        None => "`end`".to_string(),
    }
}

/// "a", "a or b", "a, b or c".
fn join_with_or(phrases: &[String]) -> String {
    match phrases {
        [] => "something else".to_string(),
        [only] => only.clone(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}
