//! From lalrpop's syntax errors to messages a learner can act on.
//!
//! lalrpop reports the unexpected token and the list of grammar terminals it
//! would have accepted. This module takes what the tokens before it left
//! open from the [`Context`] recorded while parsing, groups the expected
//! terminals into categories of the words table ("an expression", "an
//! object", "`end` to close this `sphere`"), and recognises the usual
//! mistakes (a missing comma in a triple, a missing texture part, a decimal
//! comma, a misspelt keyword). Messages carry no line numbers: positions are
//! spans, turned into lines when the diagnostic is shown.

use lalrpop_util::ParseError;

use super::context::{Blame, Context, Misclosed, Open};
use super::order::start_error;
use crate::lang::diagnostic::Diagnostic;
use crate::lang::lexer::Lexer;
use crate::lang::source::{SourceId, Span};
use crate::lang::suggest;
use crate::lang::token::Token;
use crate::lang::words::{self, Role};

/// The error type of the generated parser.
pub(super) type GrammarError = ParseError<usize, Token, Box<Diagnostic>>;

/// What is being parsed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Mode {
    /// A whole file, which starts with the camera.
    File,
    /// An input of the session, or a file loaded into it: any items.
    Session,
}

/// The comparison operators.
const COMPARISONS: [&str; 6] = ["=", "!=", "<", "<=", ">", ">="];
/// Operators that may continue an expression or a condition; they are
/// always expected after one, so they are left out of messages.
const CONTINUATIONS: [&str; 6] = ["+", "-", "*", "/", "&", "|"];
/// How a texture is written.
const TEXTURE_SHAPE: &str = "`kd ... ks ... phong ... color r, g, b`";

/// Turns an error of the generated parser into a diagnostic; `context`
/// tells what the tokens before the error left open.
pub(super) fn syntax_error(
    source: SourceId,
    text: &str,
    mode: Mode,
    context: &Context,
    error: GrammarError,
) -> Diagnostic {
    let place = Place { source, text };
    match error {
        ParseError::User { error } => *error,
        ParseError::UnrecognizedEof { location, expected } => {
            end_of_file_error(place, context, &Expected::new(expected), location)
        }
        ParseError::UnrecognizedToken { token: (start, token, end), expected } => {
            let found = Found { token, span: Span::new(source, start, end) };
            token_error(place, mode, context, &Expected::new(expected), &found)
        }
        ParseError::ExtraToken { token: (start, _, end) } => {
            let span = Span::new(source, start, end);
            Diagnostic::error(span, format!("unexpected `{}`", place.slice(span))).with_code("unexpected-token")
        }
        // Only lalrpop's own lexer reports invalid tokens; ours reports
        // unexpected characters as user errors.
        ParseError::InvalidToken { location } => {
            Diagnostic::error(last_character(place, location), "unexpected character").with_code("unexpected-character")
        }
    }
}

/// The text being parsed.
#[derive(Debug, Clone, Copy)]
struct Place<'t> {
    source: SourceId,
    text: &'t str,
}

impl Place<'_> {
    /// The source text of `span`.
    fn slice(&self, span: Span) -> &str {
        self.text.get(span.start as usize..span.end as usize).unwrap_or("")
    }

    /// The token at `span`, read again from the text: the context keeps
    /// only where the last tokens are.
    fn token(&self, span: Option<Span>) -> Option<(Token, Span)> {
        let span = span?;
        let (_, token, _) = Lexer::new(self.source, self.slice(span)).next()?.ok()?;
        Some((token, span))
    }

    /// The token before the one the parser stopped at.
    fn previous(&self, context: &Context) -> Option<(Token, Span)> {
        self.token(context.previous())
    }

    /// How to name an open construct: "`proc ring`", "`sphere`".
    fn construct(&self, open: &Open) -> String {
        match open.name {
            Some(name) => format!("`{} {}`", open.word.text, self.slice(name)),
            None => format!("`{}`", open.word.text),
        }
    }
}

/// The token the parser did not expect.
struct Found {
    token: Token,
    span: Span,
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
        self.names.iter().map(String::as_str).filter(|name| words::keyword_token(name).is_some())
    }
}

/// The role of the keyword `name` in the grammar, if it is one.
fn role(name: &str) -> Option<Role> {
    words::lookup(name).and_then(|word| word.role())
}

/// Whether the terminal `name` can start an expression.
fn starts_expression(name: &str) -> bool {
    matches!(name, "NUMBER" | "NAME" | "(" | "-") || matches!(role(name), Some(Role::Function | Role::Constant))
}

/// Whether the terminal `name` can start an object expression.
fn starts_object(name: &str) -> bool {
    name == "NAME" || matches!(role(name), Some(Role::Shape | Role::Transformation))
}

/// Whether the terminal `name` can start an instruction.
fn starts_instruction(name: &str) -> bool {
    name == "NAME" || role(name) == Some(Role::Instruction)
}

/// The error when the text ends too early.
fn end_of_file_error(place: Place<'_>, context: &Context, expected: &Expected, location: usize) -> Diagnostic {
    // Just after the last token: the caret says "here, more was needed".
    let end = location.min(place.text.len());
    let span = Span::new(place.source, end, end);
    if expected.has("end")
        && let Some(blame) = context.blame()
    {
        return unclosed_error(place, blame, span, None);
    }
    let what = describe(place, context, &expected.essential());
    let message = match context.previous() {
        Some(previous) => {
            format!("unexpected end of file: expected {what} after `{}`", place.slice(previous))
        }
        None => format!("unexpected end of file: expected {what}"),
    };
    let diagnostic =
        Diagnostic::error(span, message).with_code("unexpected-end-of-file").with_label("the file ends here");
    match (colour_help(place, context, place.text.len()), colour_fix(place, context, place.text.len())) {
        (Some(help), Some((span, numbers))) => diagnostic.with_help(help).with_replacement(span, numbers),
        _ => diagnostic,
    }
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

/// The error for a construct that lacks its `end`, found at `at`: the
/// unexpected token `found`, or the end of the file when `None`.
fn unclosed_error(place: Place<'_>, blame: Blame<'_>, at: Span, found: Option<&Found>) -> Diagnostic {
    let prefix = if found.is_some() { "" } else { "unexpected end of file: " };
    let (open, diagnostic) = match blame {
        Blame::Unclosed(open) => {
            let construct = place.construct(open);
            let label = match found {
                Some(found) => format!("unexpected `{}`", place.slice(found.span)),
                None => "the file ends here".to_string(),
            };
            let diagnostic = Diagnostic::error(at, format!("{prefix}expected `end` to close this {construct}"))
                .with_code("unclosed-block")
                .with_label(label)
                .with_related(open.span, format!("this {construct} is not closed"));
            (open, diagnostic)
        }
        Blame::Misclosed(misclosed) => (&misclosed.construct, misclosed_error(place, misclosed, at, found, prefix)),
    };
    match else_if_help(open) {
        Some((help, related)) => {
            let diagnostic = diagnostic.with_help(help);
            let diagnostic = match related {
                Some(span) => diagnostic.with_related(span, "this `if` needs its own `end`"),
                None => diagnostic,
            };
            // The quick fix: the outer `if`'s `end` right after the inner one's.
            match open.else_if_end.filter(|_| !open.after_else) {
                Some(end) => diagnostic.with_replacement(Span { start: end.end, ..end }, " end"),
                None => diagnostic,
            }
        }
        None => diagnostic,
    }
}

/// The error for a construct closed by an `end` that lines up with an
/// outer one: says which `end` went astray and what was read differently.
fn misclosed_error(
    place: Place<'_>,
    misclosed: &Misclosed,
    at: Span,
    found: Option<&Found>,
    prefix: &str,
) -> Diagnostic {
    let construct = place.construct(&misclosed.construct);
    let outer = place.construct(&misclosed.meant_for);
    let label = match found {
        Some(_) => format!("{outer} is still open here"),
        None => format!("the file ends here, with {outer} still open"),
    };
    let diagnostic = Diagnostic::error(at, format!("{prefix}expected `end` to close this {construct}"))
        .with_code("unclosed-block")
        .with_label(label)
        .with_related(misclosed.construct.span, format!("this {construct} is not closed"))
        .with_related(misclosed.end, format!("this `end`, lined up with {outer}, closed the {construct}"));
    let body_end = misclosed.construct.dedent.filter(|_| misclosed.construct.body_indented == Some(true));
    let diagnostic = match body_end {
        Some(body_end) => diagnostic
            .with_related(body_end, format!("the {construct}'s body seems to end before this line"))
            .with_note(format!(
                "so the lines from there to that `end` were read as the body of the {construct}, \
                 and the lines after it as the body of {outer}"
            )),
        None => diagnostic.with_note(format!("so the lines after that `end` were read as the body of {outer}")),
    };
    diagnostic.with_help(format!("add an `end` lined up with the {construct} where its body ends"))
}

/// The help for an `if` written as `else if`, which needs an `end` of its
/// own, and the inner `if` to point at, if `open` is one of the two.
fn else_if_help(open: &Open) -> Option<(&'static str, Option<Span>)> {
    let help = "`else if` starts a second `if` inside the `else`, and each `if` needs its own `end`: \
                `if a then ... else if b then ... end end`";
    if open.after_else {
        return Some((help, None));
    }
    open.else_if.map(|inner| (help, Some(inner)))
}

/// The error at a token the parser did not expect.
fn token_error(place: Place<'_>, mode: Mode, context: &Context, expected: &Expected, found: &Found) -> Diagnostic {
    let diagnostic = token_message(place, mode, context, expected, found);
    if diagnostic.help.is_some() {
        return diagnostic;
    }
    if let Some(help) = common_mistake(place, context, expected, found) {
        let until = found.span.start as usize;
        let colour =
            colour_fix(place, context, until).filter(|_| colour_help(place, context, until) == Some(help.clone()));
        let diagnostic = diagnostic.with_help(help);
        let fix = decimal_comma(place, context, found).or(colour);
        return match fix {
            Some((span, text)) => diagnostic.with_replacement(span, text),
            None => diagnostic,
        };
    }
    let Some(spelling) = spelling_help(place, context, expected, found) else { return diagnostic };
    let diagnostic = match spelling.related {
        Some((span, text)) => diagnostic.with_related(span, text),
        None => diagnostic,
    };
    spelling.replacements.into_iter().fold(diagnostic.with_help(spelling.help), |diagnostic, (span, keyword)| {
        diagnostic.with_replacement(span, keyword)
    })
}

/// A hint for mistakes learners often make, recognised from the unexpected
/// token and what comes before it.
fn common_mistake(place: Place<'_>, context: &Context, expected: &Expected, found: &Found) -> Option<String> {
    let previous = place.previous(context);
    if let Some(help) = decimal_comma_help(place, context, found) {
        return Some(help);
    }
    match (&found.token, previous) {
        (Token::Eq, Some((Token::Eq, _))) => Some("a comparison is written with a single `=`".to_string()),
        (Token::LParen, Some((Token::Number(_) | Token::RParen, _))) if expected.has("*") => {
            Some("to multiply, write `*`, like `2 * (x + 1)`".to_string())
        }
        (Token::Eq, Some((keyword, _))) if keyword.is_keyword() && expected.has("NUMBER") => {
            Some(format!("write the value right after `{keyword}`, without `=`"))
        }
        (Token::Comma, _) => match context.parens.last() {
            Some((_, Some(function))) if function.role() == Some(Role::Function) => {
                Some(format!("`{}` takes a single number", function.text))
            }
            Some(_) if context.triple.is_some() => {
                Some("write the three parts without parentheses, like `0, 0, 1`".to_string())
            }
            _ => None,
        },
        (token, _) if token.is_keyword() && expects_only_a_name(expected) => {
            let word = place.slice(found.span);
            let about = words::lookup(word).map(|w| format!(" ({})", w.about)).unwrap_or_default();
            Some(format!("`{word}` is a reserved word of the language{about}; choose another name"))
        }
        _ => colour_help(place, context, found.span.start as usize),
    }
}

/// "decimal numbers are written with a point", when `found` is a comma
/// between digits, as in `0,5`.
fn decimal_comma_help(place: Place<'_>, context: &Context, found: &Found) -> Option<String> {
    decimal_comma(place, context, found)
        .map(|(_, number)| format!("decimal numbers are written with a point: `{number}`"))
}

/// The number written with a point, and the span of the number written
/// with a comma (`0,5`), when `found` is a comma between digits.
fn decimal_comma(place: Place<'_>, context: &Context, found: &Found) -> Option<(Span, String)> {
    let (Token::Number(_), number) = place.previous(context)? else { return None };
    if found.token != Token::Comma || number.end != found.span.start {
        return None;
    }
    let fraction: String = place.text[found.span.end as usize..].chars().take_while(char::is_ascii_digit).collect();
    let span = Span { end: found.span.end + fraction.len() as u32, ..number };
    (!fraction.is_empty()).then(|| (span, format!("{}.{fraction}", place.slice(number))))
}

/// "colours are three numbers", when a `#ff0000` colour (read as a comment)
/// follows `color` in the text before byte `until`.
fn colour_help(place: Place<'_>, context: &Context, until: usize) -> Option<String> {
    let (_, numbers) = colour_fix(place, context, until)?;
    Some(format!("`#` starts a comment; colours are three numbers from 0 to 255: `color {numbers}`"))
}

/// The span of a `#ff0000` colour (read as a comment) that follows `color`
/// in the text before byte `until`, and its three numbers (`255, 0, 0`).
fn colour_fix(place: Place<'_>, context: &Context, until: usize) -> Option<(Span, String)> {
    let (Token::Color, color) = place.previous(context)? else { return None };
    let after = place.text.get(color.end as usize..until)?;
    let hash = after.find('#').filter(|&at| after[..at].trim().is_empty())?;
    let digits: String = after[hash + 1..].chars().take_while(char::is_ascii_alphanumeric).collect();
    let six_digits: String = match digits.len() {
        6 => digits.clone(),
        3 => digits.chars().flat_map(|digit| [digit, digit]).collect(),
        _ => return None,
    };
    let [_, red, green, blue] = u32::from_str_radix(&six_digits, 16).ok()?.to_be_bytes();
    let start = color.end + hash as u32;
    let span = Span { start, end: start + 1 + digits.len() as u32, ..color };
    Some((span, format!("{red}, {green}, {blue}")))
}

/// The message (and label and related spans) for an unexpected token,
/// before any spelling help.
fn token_message(place: Place<'_>, mode: Mode, context: &Context, expected: &Expected, found: &Found) -> Diagnostic {
    let span = found.span;
    let found_text = place.slice(span);
    let unexpected = format!("unexpected `{found_text}`");
    let innermost = context.open.last();
    if found.token == Token::End && innermost.is_none() {
        return Diagnostic::error(span, "unexpected `end`: nothing is open here")
            .with_code("unmatched-end")
            .with_label("this `end` closes nothing");
    }
    if found.token == Token::Else && innermost.is_none_or(|open| open.word.text != "if") {
        return Diagnostic::error(span, "unexpected `else`: it belongs between `if ... then` and `end`")
            .with_code("unmatched-else")
            .with_label("this `else` has no `if`");
    }
    if mode == Mode::File && context.previous().is_none() {
        return start_error(span);
    }
    if let Some(diagnostic) = texture_error(place, expected, found) {
        return diagnostic;
    }
    if let (Token::LParen, Some((Token::Ident(name), name_span))) = (&found.token, place.previous(context))
        && expected.has("*")
    {
        return Diagnostic::error(name_span, format!("unknown function `{name}`"))
            .with_code("unknown-function")
            .with_label("not a function of the language")
            .with_help(words::hint_for_function(&name));
    }
    if expected.has("let") && found.token.is_keyword() && starts_object(found_text) {
        return Diagnostic::error(span, format!("expected an instruction, found the object `{found_text}`"))
            .with_code("object-as-instruction")
            .with_label("an object is not an instruction")
            .with_help("write `put` before it to add it to the scene, or `object name =` to give it a name");
    }
    let essential = expected.essential();
    match essential.as_slice() {
        [","] if context.triple.is_some() => {
            let triple = context.triple.unwrap_or("the triple");
            return Diagnostic::error(span, format!("expected `,` between the parts of {triple}"))
                .with_code("missing-comma")
                .with_label("expected `,` before this");
        }
        ["then"] => {
            return Diagnostic::error(span, "expected `then` after the condition of `if`")
                .with_code("missing-then")
                .with_label("expected `then` before this");
        }
        [")"] => {
            if let Some((paren, _)) = context.parens.last() {
                return Diagnostic::error(span, "expected `)` to close the parenthesis")
                    .with_code("unclosed-parenthesis")
                    .with_label("expected `)` before this")
                    .with_related(*paren, "the parenthesis opened here");
            }
        }
        ["end"] => {
            if let Some(blame) = context.blame() {
                return unclosed_error(place, blame, span, Some(found));
            }
        }
        _ => {}
    }
    if essential.contains(&"end")
        && let Some(blame @ Blame::Misclosed(_)) = context.blame()
    {
        return unclosed_error(place, blame, span, Some(found));
    }
    let what = describe(place, context, &essential);
    let closes = essential.contains(&"end") && innermost.is_some();
    let message = match context.previous() {
        Some(previous) if !closes => {
            format!("expected {what} after `{}`", place.slice(previous))
        }
        _ => format!("expected {what}"),
    };
    let diagnostic = Diagnostic::error(span, message).with_code("unexpected-token").with_label(unexpected);
    match innermost {
        Some(open) if closes => {
            diagnostic.with_related(open.span, format!("this {} is not closed", place.construct(open)))
        }
        _ => diagnostic,
    }
}

/// The error for a texture whose parts are missing or out of order, when a
/// part of it is expected and `found` is another part, or `end`.
fn texture_error(place: Place<'_>, expected: &Expected, found: &Found) -> Option<Diagnostic> {
    let texture: Vec<&str> = words::with_role(Role::Texture).collect();
    let wanted = texture.iter().position(|part| expected.has(part))?;
    let found_text = place.slice(found.span);
    let missing = match texture.iter().position(|part| *part == found_text) {
        Some(given) => given > wanted,
        None => found.token == Token::End && wanted > 0,
    };
    if missing {
        let part = texture[wanted];
        return Some(
            Diagnostic::error(found.span, format!("missing `{part}`: a texture is {TEXTURE_SHAPE}, in this order"))
                .with_code("texture-part-missing")
                .with_label(format!("expected `{part}` before this")),
        );
    }
    texture.contains(&found_text).then(|| {
        Diagnostic::error(found.span, format!("the texture must be {TEXTURE_SHAPE} in this order"))
            .with_code("texture-out-of-order")
            .with_label("out of order")
    })
}

/// A help about the spelling of a name: its text, the place to point at
/// (when the name is not the error spot), and the keywords it proposes in
/// place of names.
struct SpellingHelp {
    help: String,
    related: Option<(Span, String)>,
    replacements: Vec<(Span, String)>,
}

/// The help for names near the error that the words table knows (a keyword
/// in capitals, a word of the French course) or that look like a misspelt
/// keyword, and the place to point at when the name is not the error spot.
fn spelling_help(place: Place<'_>, context: &Context, expected: &Expected, found: &Found) -> Option<SpellingHelp> {
    let earlier = [place.token(context.before_previous()), place.previous(context)];
    let names: Vec<(&str, Span)> = earlier
        .into_iter()
        .flatten()
        .chain([(found.token.clone(), found.span)])
        .filter(|(token, _)| matches!(token, Token::Ident(_)))
        .map(|(_, span)| (place.slice(span), span))
        .collect();
    let in_capitals: Vec<(Span, String)> =
        names.iter().filter_map(|(name, span)| Some((*span, words::in_lower_case(name)?.to_string()))).collect();
    if !in_capitals.is_empty() {
        let keywords: Vec<String> = in_capitals.iter().map(|(_, keyword)| format!("`{keyword}`")).collect();
        let help = format!("keywords are written in lower case: {}", keywords.join(", "));
        return Some(SpellingHelp { help, related: None, replacements: in_capitals });
    }
    let not_a_keyword = |name: &str, span: Span| {
        (span != found.span).then(|| (span, format!("`{name}` is not a keyword, so it is read as a name")))
    };
    for (name, span) in names.iter().rev() {
        if let Some(hint) = words::hint_for_name(name) {
            let replacements =
                words::keyword_meant(name).map(|keyword| (*span, keyword.to_string())).into_iter().collect();
            return Some(SpellingHelp { help: hint, related: not_a_keyword(name, *span), replacements });
        }
    }
    if let Token::Ident(name) = &found.token {
        let suggestion = suggest::closest(name, expected.keywords())
            .or_else(|| suggest::closest(name, words::keyword_names()).filter(|_| name.len() >= 3));
        if let Some(keyword) = suggestion {
            let help = format!("did you mean `{keyword}`?");
            return Some(SpellingHelp { help, related: None, replacements: vec![(found.span, keyword.to_string())] });
        }
    }
    for (name, span) in names.iter().rev().filter(|(_, span)| *span != found.span) {
        if name.len() < 3 {
            continue;
        }
        if let Some(keyword) = suggest::closest(name, words::keyword_names()) {
            let help = format!("did you mean `{keyword}`?");
            return Some(SpellingHelp {
                help,
                related: not_a_keyword(name, *span),
                replacements: vec![(*span, keyword.to_string())],
            });
        }
    }
    None
}

/// Whether the parser wanted a new name there (after `let`, `object`,
/// `proc`, or in a parameter list).
fn expects_only_a_name(expected: &Expected) -> bool {
    matches!(expected.essential().as_slice(), ["NAME"] | ["NAME", ")"] | [")", "NAME"])
}

/// Describes the expected terminals in words: "an expression (...)",
/// "`end` to close this `sphere`", joined with "or".
fn describe(place: Place<'_>, context: &Context, essential: &[&str]) -> String {
    let mut left: Vec<&str> = essential.to_vec();
    let mut phrases: Vec<String> = Vec::new();
    let mut take = |left: &mut Vec<&str>, belongs: &dyn Fn(&str) -> bool, phrase: &str| {
        left.retain(|name| !belongs(name));
        phrases.push(phrase.to_string());
    };
    if left.contains(&"!") {
        take(&mut left, &|name| starts_expression(name) || name == "!", "a condition (like `x < 1`)");
    } else if left.contains(&"NUMBER") {
        take(&mut left, &starts_expression, "an expression (a number, a name, `(`...)");
    }
    if left.contains(&"sphere") {
        take(&mut left, &starts_object, "an object (`sphere`, `plane`, `box`, a name...)");
    }
    if left.contains(&"let") {
        let instruction_or_definition = |name: &str| starts_instruction(name) || role(name) == Some(Role::Definition);
        take(
            &mut left,
            &instruction_or_definition,
            "an instruction (`let`, `object`, `put`, `if` or a procedure call)",
        );
    }
    if left.contains(&"<") {
        take(&mut left, &|name| COMPARISONS.contains(&name), "a comparison (`=`, `<`, `>`, `<=`, `>=` or `!=`)");
    }
    if left.contains(&"kd") {
        take(&mut left, &|name| name == "kd", &format!("the texture {TEXTURE_SHAPE}"));
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
    match context.open.last() {
        Some(open) => format!("`end` to close this {}", place.construct(open)),
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
