//! The answers that help while a line is being typed: completion (the
//! editor services' rules of what may come where, [`completion::complete`])
//! and the signature of the procedure or function being called. The text
//! being typed rarely parses, so the names come from the last version of
//! the document that did ([`Vocabulary`]).

use lsp_types::{
    CompletionItem, CompletionItemKind, CompletionResponse, CompletionTextEdit, InsertTextFormat, ParameterInformation,
    ParameterLabel, Position, Range, SignatureHelp, SignatureInformation, TextEdit,
};

use super::text::offset;
use crate::ide::completion::{self, CandidateKind};
use crate::ide::names::Vocabulary;
use crate::ide::scanner::word_start;
use crate::lang::words::{self, Role};

/// The completions at `position` of `text`, with the names of `vocabulary`.
/// With `snippets`, a procedure's parameters are placeholders to fill.
pub(crate) fn complete(text: &str, position: Position, vocabulary: &Vocabulary, snippets: bool) -> CompletionResponse {
    let at = offset(text, position);
    let (start, candidates) = completion::complete(&text[..at], false, vocabulary);
    let typed =
        Range { start: Position { character: position.character - (at - start) as u32, ..position }, end: position };
    let items = candidates.into_iter().map(|candidate| {
        let word = words::lookup(candidate.replacement.trim_end_matches([' ', '(']));
        let (kind, detail) = match candidate.kind {
            CandidateKind::Keyword => (CompletionItemKind::KEYWORD, word.map(|word| word.about.to_string())),
            CandidateKind::Function => (CompletionItemKind::FUNCTION, word.map(|word| word.about.to_string())),
            CandidateKind::Number => (CompletionItemKind::VARIABLE, Some("number".to_string())),
            CandidateKind::Object => (CompletionItemKind::STRUCT, Some("object".to_string())),
            CandidateKind::Procedure => (CompletionItemKind::FUNCTION, Some(format!("proc {}", candidate.display))),
            // A program file holds no commands.
            CandidateKind::Command => (CompletionItemKind::KEYWORD, None),
        };
        let params = vocabulary.procedures.iter().find(|(name, _)| candidate.replacement == format!("{name}("));
        let (new_text, format) = match params {
            Some((name, params)) if snippets => {
                let holes: Vec<String> =
                    params.iter().enumerate().map(|(at, param)| format!("${{{}:{param}}}", at + 1)).collect();
                (format!("{name}({})$0", holes.join(", ")), InsertTextFormat::SNIPPET)
            }
            _ => (candidate.replacement, InsertTextFormat::PLAIN_TEXT),
        };
        CompletionItem {
            label: candidate.display,
            kind: Some(kind),
            detail,
            insert_text_format: Some(format),
            text_edit: Some(CompletionTextEdit::Edit(TextEdit { range: typed, new_text })),
            ..CompletionItem::default()
        }
    });
    CompletionResponse::Array(items.collect())
}

/// The signature of the call whose parentheses hold `position`: a
/// procedure of `vocabulary` or a function of the language, with the
/// parameter being typed.
pub(crate) fn signature(text: &str, position: Position, vocabulary: &Vocabulary) -> Option<SignatureHelp> {
    let before = &text[..offset(text, position)];
    let (open, commas) = open_call(before)?;
    let name = &before[word_start(&before[..open])..open];
    let params: Vec<String> = match vocabulary.procedures.iter().find(|(procedure, _)| procedure == name) {
        Some((_, params)) => params.clone(),
        None if words::lookup(name).and_then(words::Word::role) == Some(Role::Function) => vec!["x".to_string()],
        None => return None,
    };
    let keyword = if words::lookup(name).is_some() { "" } else { "proc " };
    let label = format!("{keyword}{name}({})", params.join(", "));
    let mut at = keyword.len() + name.len() + 1;
    let parameters = params.iter().map(|param| {
        let range = [at as u32, (at + param.len()) as u32];
        at += param.len() + 2;
        ParameterInformation { label: ParameterLabel::LabelOffsets(range), documentation: None }
    });
    let signature = SignatureInformation {
        label,
        documentation: None,
        parameters: Some(parameters.collect()),
        active_parameter: Some(commas as u32),
    };
    Some(SignatureHelp {
        signatures: vec![signature],
        active_signature: Some(0),
        active_parameter: Some(commas as u32),
    })
}

/// The `(` of the innermost call left open at the end of `before`, and how
/// many of its arguments are already complete (commas at its level).
fn open_call(before: &str) -> Option<(usize, usize)> {
    let mut depth = 0;
    let mut commas = 0;
    for (at, c) in before.char_indices().rev() {
        match c {
            ')' => depth += 1,
            '(' if depth == 0 => return Some((at, commas)),
            '(' => depth -= 1,
            ',' if depth == 0 => commas += 1,
            // A call's arguments stay on one line of an instruction.
            '\n' => return None,
            _ => {}
        }
    }
    None
}
