//! The answers of the server, from a document's [`Analysis`]: diagnostics,
//! quick fixes, hovers, definitions, references, renames, the outline and
//! the colour swatches, the formatting.
//! Each turns the language's places (spans) into the protocol's ranges.

use std::collections::HashMap;

use lsp_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, Color, ColorInformation, ColorPresentation,
    DiagnosticRelatedInformation, DiagnosticSeverity, DocumentSymbol, DocumentSymbolResponse, GotoDefinitionResponse,
    Hover, HoverContents, Location, MarkupContent, MarkupKind, NumberOrString, Position, PrepareRenameResponse, Range,
    SymbolKind, TextEdit, Uri, WorkspaceEdit,
};

use super::analysis::{Analysis, EVALUATION_BUDGET, Evaluation};
use super::text::{end, offset, range};
use crate::ide::hover::{Pages, Subject, hover as hovered};
use crate::ide::names::Vocabulary;
use crate::ide::scanner::is_word_char;
use crate::lang::ast::{Expr, ExprKind, InstrKind, Item};
use crate::lang::format::format;
use crate::lang::names::{Binding, Namespace, Occurrence, Scope};
use crate::lang::number::format_number;
use crate::lang::walk::{same_level, textures};
use crate::lang::{Diagnostic, Severity, SourceId, Span, words};

/// The diagnostics of the document at `uri`, as the protocol gives them.
pub(crate) fn diagnostics(uri: &Uri, analysis: &Analysis) -> Vec<lsp_types::Diagnostic> {
    let mut shown: Vec<lsp_types::Diagnostic> =
        analysis.diagnostics.iter().map(|diagnostic| to_protocol(uri, analysis, diagnostic)).collect();
    if matches!(analysis.evaluation, Evaluation::TooLong) {
        shown.push(lsp_types::Diagnostic {
            range: Range::default(),
            severity: Some(DiagnosticSeverity::INFORMATION),
            code: Some(NumberOrString::String("evaluation-too-long".to_string())),
            source: Some("rayrepl".to_string()),
            message: format!(
                "the scene was not evaluated to its end: it ran for more than {} s and was stopped \
                 (a runaway recursion?), so its errors and warnings after that point are not shown",
                EVALUATION_BUDGET.as_secs()
            ),
            ..lsp_types::Diagnostic::default()
        });
    }
    shown
}

/// One diagnostic as the protocol gives it: the message with its label,
/// notes and help under it, its code, its related places.
fn to_protocol(uri: &Uri, analysis: &Analysis, diagnostic: &Diagnostic) -> lsp_types::Diagnostic {
    let sources = &analysis.sources;
    let mut message = diagnostic.message.clone();
    for line in diagnostic.label.iter() {
        message.push_str(&format!("\n{line}"));
    }
    for note in &diagnostic.notes {
        message.push_str(&format!("\nnote: {}", note.display(sources, diagnostic.span.source)));
    }
    if let Some(help) = &diagnostic.help {
        message.push_str(&format!("\nhelp: {help}"));
    }
    let related = diagnostic.related.iter().map(|(span, text)| DiagnosticRelatedInformation {
        location: Location { uri: uri.clone(), range: range(*span, sources) },
        message: text.clone(),
    });
    lsp_types::Diagnostic {
        range: range(diagnostic.span, sources),
        severity: Some(match diagnostic.severity {
            Severity::Error => DiagnosticSeverity::ERROR,
            Severity::Warning => DiagnosticSeverity::WARNING,
        }),
        code: Some(NumberOrString::String(diagnostic.code.to_string())),
        source: Some("rayrepl".to_string()),
        message,
        related_information: Some(related.collect()).filter(|related: &Vec<_>| !related.is_empty()),
        ..lsp_types::Diagnostic::default()
    }
}

/// The quick fixes for the diagnostics at `wanted` whose help proposes an
/// edit (a misspelt word, capitals, a decimal comma, ...).
pub(crate) fn quick_fixes(uri: &Uri, analysis: &Analysis, wanted: Range) -> Vec<CodeActionOrCommand> {
    let sources = &analysis.sources;
    let overlaps = |other: Range| other.start <= wanted.end && wanted.start <= other.end;
    let fixable = analysis.diagnostics.iter().filter(|diagnostic| !diagnostic.replacements.is_empty());
    // Asked at the diagnostic or at what the fix changes (the misspelt
    // word, where the caret points at the word after it).
    let asked = |diagnostic: &&Diagnostic| {
        let mut spans = std::iter::once(diagnostic.span).chain(diagnostic.replacements.iter().map(|r| r.span));
        spans.any(|span| overlaps(range(span, sources)))
    };
    fixable
        .filter(asked)
        .map(|diagnostic| {
            let edits = diagnostic
                .replacements
                .iter()
                .map(|replacement| TextEdit {
                    range: range(replacement.span, sources),
                    new_text: replacement.text.clone(),
                })
                .collect();
            let title = diagnostic.help.clone().unwrap_or_else(|| format!("fix: {}", diagnostic.message));
            CodeActionOrCommand::CodeAction(CodeAction {
                title,
                kind: Some(CodeActionKind::QUICKFIX),
                diagnostics: Some(vec![to_protocol(uri, analysis, diagnostic)]),
                edit: Some(WorkspaceEdit {
                    changes: Some(HashMap::from([(uri.clone(), edits)])),
                    ..WorkspaceEdit::default()
                }),
                is_preferred: Some(true),
                ..CodeAction::default()
            })
        })
        .collect()
}

/// What the word at `position` is ([`crate::ide::hover`], `names` being
/// the names defined there): a procedure's signature and where it is
/// defined, what a name holds, or the help page of a word of the language.
pub(crate) fn hover(text: &str, analysis: &Analysis, names: &Vocabulary, position: Position) -> Option<Hover> {
    let at = offset(text, position);
    let hover = hovered(text, at, names, Pages::OfWords)?;
    let markdown = match hover.subject {
        Subject::Name => {
            let occurrence = analysis.names.at(at)?;
            if analysis.names.bindings_for(occurrence).is_empty() {
                return None;
            }
            describe(analysis, occurrence)
        }
        Subject::Page(page) => help_markdown(page.text),
    };
    let span = Span::new(SourceId::default(), hover.range.start, hover.range.end);
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent { kind: MarkupKind::Markdown, value: markdown }),
        range: Some(range(span, &analysis.sources)),
    })
}

/// What the name at `occurrence` is, in Markdown.
fn describe(analysis: &Analysis, occurrence: &Occurrence) -> String {
    let names = &analysis.names;
    let symbol = &names.symbols[occurrence.symbol];
    let name = &symbol.name;
    let bindings = names.bindings_for(occurrence);
    let lines: Vec<String> = bindings.iter().map(|binding| line_of(analysis, binding.span).to_string()).collect();
    let at_lines = match lines.as_slice() {
        [one] => format!("line {one}"),
        several => format!("lines {}", several.join(", ")),
    };
    let program = analysis.program.as_ref();
    let procedure_of = |scope: Scope| match (scope, program) {
        (Scope::Procedure(index), Some(program)) => match &program.items[index] {
            Item::Proc(procedure) => Some(procedure.clone()),
            _ => None,
        },
        _ => None,
    };
    if symbol.namespace == Namespace::Procedure {
        let definition = program.and_then(|program| {
            program.items.iter().find_map(|item| match item {
                Item::Proc(procedure) if Some(procedure.name.span) == bindings.first().map(|b| b.span) => {
                    Some(procedure)
                }
                _ => None,
            })
        });
        let params = definition.map(|procedure| procedure.params.iter().map(|p| &*p.name).collect::<Vec<_>>());
        let signature = format!("proc {name}({})", params.unwrap_or_default().join(", "));
        return format!("```ray\n{signature}\n```\nprocedure, defined at {at_lines}");
    }
    let kind = match bindings.last().and_then(|binding| binding.binding) {
        Some(Binding::Object) => "object",
        Some(Binding::Parameter) => "parameter",
        _ => "number",
    };
    let mut text = match symbol.scope {
        Scope::Procedure(_) => {
            let owner = procedure_of(symbol.scope).map(|procedure| format!(" of `{}`", procedure.name.name));
            let role = if kind == "parameter" { "parameter".to_string() } else { format!("local {kind}") };
            format!("`{name}`: {role}{}, bound at {at_lines}", owner.unwrap_or_default())
        }
        Scope::Global => format!("`{name}`: global {kind}, bound at {at_lines}"),
    };
    if let (Scope::Global, Some(interpreter)) = (symbol.scope, analysis.interpreter()) {
        if let Some(value) = interpreter.global_number(name) {
            text.push_str(&format!("\n\nat the end of the program (time 0): `{name} = {}`", format_number(value)));
        } else if let Some(primitives) = interpreter.global_object(name) {
            let count = primitives.len();
            let parts = if count == 1 { "1 part".to_string() } else { format!("{count} parts") };
            text.push_str(&format!("\n\nat the end of the program (time 0): an object of {parts}"));
        }
    }
    text
}

/// The line, from 1, of `span`.
fn line_of(analysis: &Analysis, span: Span) -> usize {
    analysis.sources.get(span.source).line_col(span.start as usize).0
}

/// A help page in Markdown: its first line (the form of the word) and its
/// examples as `.ray` code, the rest as text.
fn help_markdown(page: &str) -> String {
    let mut lines = page.lines();
    let mut markdown = format!("```ray\n{}\n```\n", lines.next().unwrap_or_default());
    let mut in_example = false;
    for line in lines {
        let code = line.starts_with("  ") && in_example;
        match (code, line.trim_end().ends_with(':') && !line.starts_with(' ')) {
            (_, true) => {
                markdown.push_str(&format!("\n{line}\n```ray\n"));
                in_example = true;
            }
            (true, _) => markdown.push_str(&format!("{}\n", &line[2..])),
            (false, _) => markdown.push_str(&format!("{}\n", line.trim())),
        }
    }
    if in_example {
        markdown.push_str("```\n");
    }
    markdown
}

/// Where the name at `position` is bound.
pub(crate) fn definition(
    uri: &Uri,
    text: &str,
    analysis: &Analysis,
    position: Position,
) -> Option<GotoDefinitionResponse> {
    let occurrence = analysis.names.at(offset(text, position))?;
    let locations: Vec<Location> = analysis
        .names
        .bindings_for(occurrence)
        .into_iter()
        .map(|binding| Location { uri: uri.clone(), range: range(binding.span, &analysis.sources) })
        .collect();
    (!locations.is_empty()).then_some(GotoDefinitionResponse::Array(locations))
}

/// Every place the name at `position` is written, as the same variable,
/// object or procedure.
pub(crate) fn references(uri: &Uri, text: &str, analysis: &Analysis, position: Position) -> Option<Vec<Location>> {
    let occurrence = analysis.names.at(offset(text, position))?;
    let all = analysis.names.occurrences_of(occurrence.symbol);
    Some(all.map(|other| Location { uri: uri.clone(), range: range(other.span, &analysis.sources) }).collect())
}

/// The name a rename at `position` would change.
pub(crate) fn prepare_rename(text: &str, analysis: &Analysis, position: Position) -> Option<PrepareRenameResponse> {
    let occurrence = renamable(analysis, offset(text, position)).ok()?;
    let placeholder = analysis.names.symbols[occurrence.symbol].name.to_string();
    Some(PrepareRenameResponse::RangeWithPlaceholder { range: range(occurrence.span, &analysis.sources), placeholder })
}

/// The edits that rename the name at `position` to `new_name` everywhere
/// it means the same thing, or why it cannot be renamed.
pub(crate) fn rename(
    uri: &Uri,
    text: &str,
    analysis: &Analysis,
    position: Position,
    new_name: &str,
) -> Result<WorkspaceEdit, String> {
    let occurrence = renamable(analysis, offset(text, position))?;
    let names = &analysis.names;
    let symbol = &names.symbols[occurrence.symbol];
    let mut characters = new_name.chars();
    let is_name =
        characters.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_') && characters.all(is_word_char);
    if !is_name {
        return Err(format!(
            "`{new_name}` is not a name: a name is letters, digits and `_`, not starting with a digit"
        ));
    }
    if words::keyword_token(new_name).is_some() || new_name == "time" {
        return Err(format!("`{new_name}` is a word of the language, not a name of yours"));
    }
    let taken = names
        .symbols
        .iter()
        .any(|other| &*other.name == new_name && other.namespace == symbol.namespace && other.scope == symbol.scope);
    if taken {
        return Err(format!("`{new_name}` is already a name here: the rename would join two of them"));
    }
    let edits = names
        .occurrences_of(occurrence.symbol)
        .map(|other| TextEdit { range: range(other.span, &analysis.sources), new_text: new_name.to_string() })
        .collect();
    Ok(WorkspaceEdit { changes: Some(HashMap::from([(uri.clone(), edits)])), ..WorkspaceEdit::default() })
}

/// The occurrence at `offset`, if it is a name of the program (not one the
/// language predefines, such as `time`).
fn renamable(analysis: &Analysis, offset: usize) -> Result<&Occurrence, String> {
    let occurrence = analysis.names.at(offset).ok_or("there is no name here to rename")?;
    let bound = analysis.names.occurrences_of(occurrence.symbol).any(|other| other.binding.is_some());
    if bound {
        Ok(occurrence)
    } else {
        Err(format!("`{}` is not bound in this file", analysis.names.symbols[occurrence.symbol].name))
    }
}

/// The outline: the camera, the ambient light, the lights, the procedures
/// (with their parameters and locals) and the names bound at top level.
pub(crate) fn symbols(analysis: &Analysis) -> Option<DocumentSymbolResponse> {
    let program = analysis.program.as_ref()?;
    let sources = &analysis.sources;
    let symbol = |name: String, detail: Option<String>, kind: SymbolKind, whole: Span, name_span: Span| {
        #[allow(deprecated)] // `deprecated` is a required field of the type, replaced by `tags`.
        DocumentSymbol {
            name,
            detail,
            kind,
            tags: None,
            deprecated: None,
            range: range(whole, sources),
            selection_range: range(name_span, sources),
            children: None,
        }
    };
    let bound = |instrs: &mut dyn DoubleEndedIterator<Item = &crate::lang::ast::Instr>| -> Vec<DocumentSymbol> {
        same_level(instrs)
            .filter_map(|instr| match &instr.kind {
                InstrKind::Let(name, _) => Some(symbol(
                    name.name.to_string(),
                    Some("number".into()),
                    SymbolKind::VARIABLE,
                    instr.span,
                    name.span,
                )),
                InstrKind::Object(name, _) => Some(symbol(
                    name.name.to_string(),
                    Some("object".into()),
                    SymbolKind::OBJECT,
                    instr.span,
                    name.span,
                )),
                _ => None,
            })
            .collect()
    };
    let mut outline = Vec::new();
    let mut lights = 0;
    for item in &program.items {
        match item {
            Item::Camera(camera) => {
                outline.push(symbol("camera".into(), None, SymbolKind::PROPERTY, camera.span, camera.span));
            }
            Item::Ambient(ambient) => {
                outline.push(symbol("ambient".into(), None, SymbolKind::PROPERTY, ambient.span, ambient.span));
            }
            Item::Light(light) => {
                lights += 1;
                outline.push(symbol(format!("light {lights}"), None, SymbolKind::PROPERTY, light.span, light.span));
            }
            Item::Proc(procedure) => {
                let params: Vec<&str> = procedure.params.iter().map(|param| &*param.name).collect();
                let detail = Some(format!("({})", params.join(", ")));
                let mut entry = symbol(
                    procedure.name.name.to_string(),
                    detail,
                    SymbolKind::FUNCTION,
                    procedure.span,
                    procedure.name.span,
                );
                let mut children: Vec<DocumentSymbol> = procedure
                    .params
                    .iter()
                    .map(|param| {
                        symbol(
                            param.name.to_string(),
                            Some("parameter".into()),
                            SymbolKind::VARIABLE,
                            param.span,
                            param.span,
                        )
                    })
                    .collect();
                children.extend(bound(&mut procedure.body.iter()));
                entry.children = Some(children).filter(|children| !children.is_empty());
                outline.push(entry);
            }
            Item::Instr(instr) => outline.extend(bound(&mut std::iter::once(instr))),
        }
    }
    Some(DocumentSymbolResponse::Nested(outline))
}

/// A swatch for every `color r, g, b` whose three parts are numbers (the
/// language's 0..255, shown clamped).
pub(crate) fn colours(analysis: &Analysis) -> Vec<ColorInformation> {
    let Some(program) = &analysis.program else { return Vec::new() };
    let channel = |part: &Expr| match part.kind {
        ExprKind::Number(value) => Some((value / 255.0).clamp(0.0, 1.0) as f32),
        _ => None,
    };
    textures(program)
        .into_iter()
        .filter_map(|texture| {
            let [red, green, blue] = &texture.color.parts;
            let color = Color { red: channel(red)?, green: channel(green)?, blue: channel(blue)?, alpha: 1.0 };
            Some(ColorInformation { range: range(texture.color.span, &analysis.sources), color })
        })
        .collect()
}

/// How a colour picked in a swatch is written: its three parts in 0..255.
pub(crate) fn colour_written(color: Color) -> Vec<ColorPresentation> {
    let part = |channel: f32| format_number((f64::from(channel) * 255.0).round().clamp(0.0, 255.0));
    let label = format!("{}, {}, {}", part(color.red), part(color.green), part(color.blue));
    vec![ColorPresentation { label, text_edit: None, additional_text_edits: None }]
}

/// The edit that formats the whole document as `rayrepl fmt` does (none if
/// it is formatted), or why it cannot be: the text does not parse.
pub(crate) fn formatting(text: &str, analysis: &Analysis) -> Result<Vec<TextEdit>, String> {
    let formatted = format(SourceId::default(), text).map_err(|error| {
        let line = line_of(analysis, error.span);
        format!("the file cannot be formatted until it parses: line {line}: {}", error.message)
    })?;
    if formatted == text {
        return Ok(Vec::new());
    }
    let whole = Range { start: Position::default(), end: end(text) };
    Ok(vec![TextEdit { range: whole, new_text: formatted }])
}
