//! `rayrepl lsp`: a Language Server Protocol server on standard input and
//! output, one more front-end of the language: editors get, while the
//! learner types, the diagnostics the command line gives (with their
//! related places, help and code), quick fixes for the help that proposes
//! an edit, the help pages of the words, what a name is and where it is
//! bound, its references and renames, completion, signatures, colour
//! swatches, formatting and the outline of the file.
//!
//! The protocol is rust-analyzer's `lsp-server` (the framing and the
//! message loop) with `lsp-types` (the messages). Documents are kept as the
//! client edits them (incremental sync) and analysed again at each change:
//! a parse, an evaluation at `time` 0 stopped after
//! [`analysis::EVALUATION_BUDGET`], and the checks of the scene.

mod analysis;
mod features;
mod picture;
mod text;
mod typing;

use std::collections::HashMap;

use lsp_server::{Connection, ErrorCode, Message, Notification, Request, Response};
use lsp_types::notification::{
    DidChangeTextDocument, DidCloseTextDocument, DidOpenTextDocument, Notification as _, PublishDiagnostics,
};
use lsp_types::request::{
    CodeActionRequest, ColorPresentationRequest, Completion, DocumentColor, DocumentSymbolRequest, ExecuteCommand,
    Formatting, GotoDefinition, HoverRequest, PrepareRenameRequest, References, Rename, Request as _,
    SignatureHelpRequest,
};
use lsp_types::{
    CodeActionKind, CodeActionProviderCapability, HoverProviderCapability, InitializeResult, OneOf,
    PublishDiagnosticsParams, RenameOptions, ServerCapabilities, ServerInfo, TextDocumentSyncCapability,
    TextDocumentSyncKind, Uri, WorkDoneProgressOptions,
};
use serde_json::Value;

use crate::ide::names::Vocabulary;
use analysis::Analysis;

/// An open document: its text as the client last sent it, and its
/// analysis. (Documents are found by their URI's text: `Uri` caches parts
/// of itself, so it is no map key.)
struct Document {
    text: String,
    version: i32,
    analysis: Analysis,
    /// The global names of the last version that parsed, for completion
    /// while the text being typed does not.
    last_names: Vocabulary,
}

impl Document {
    fn new(uri: &Uri, text: String, version: i32, last_names: Option<Vocabulary>) -> Document {
        let analysis = Analysis::of(&display_name(uri), &text);
        let last_names = match &analysis.program {
            Some(program) => Vocabulary::of_program(program, &analysis.names, None),
            None => last_names.unwrap_or_default(),
        };
        Document { text, version, analysis, last_names }
    }

    /// The names defined at `position`: with a procedure's parameters and
    /// locals inside it.
    fn names_at(&self, position: lsp_types::Position) -> Vocabulary {
        match &self.analysis.program {
            Some(program) => {
                Vocabulary::of_program(program, &self.analysis.names, Some(text::offset(&self.text, position)))
            }
            None => self.last_names.clone(),
        }
    }
}

/// What the client said it can do, as far as the answers depend on it.
struct Client {
    /// Completions may be snippets, with placeholders to fill.
    snippets: bool,
}

/// Serves the protocol on standard input and output until the client
/// says `exit` (or closes the connection).
pub fn serve_stdio() -> Result<(), String> {
    let (connection, threads) = Connection::stdio();
    serve(&connection)?;
    drop(connection);
    threads.join().map_err(|error| format!("the connection failed: {error}"))
}

/// Serves the protocol on `connection`: the handshake, then each message.
fn serve(connection: &Connection) -> Result<(), String> {
    let failed = |error: lsp_server::ProtocolError| format!("the client broke the protocol: {error}");
    let (id, params) = connection.initialize_start().map_err(failed)?;
    let params: lsp_types::InitializeParams = serde_json::from_value(params).unwrap_or_default();
    let completion = params.capabilities.text_document.and_then(|document| document.completion?.completion_item);
    let client = Client { snippets: completion.and_then(|item| item.snippet_support).unwrap_or(false) };
    let result = InitializeResult {
        capabilities: capabilities(),
        server_info: Some(ServerInfo {
            name: "rayrepl".to_string(),
            version: Some(env!("CARGO_PKG_VERSION").to_string()),
        }),
    };
    connection.initialize_finish(id, to_json(result)).map_err(failed)?;
    let mut documents: HashMap<String, Document> = HashMap::new();
    for message in &connection.receiver {
        match message {
            Message::Request(request) => {
                if connection.handle_shutdown(&request).map_err(failed)? {
                    return Ok(());
                }
                let response = answer(&documents, &client, request);
                send(connection, response.into())?;
            }
            Message::Notification(notification) => {
                if let Some(uri) = follow(&mut documents, notification) {
                    publish(connection, &uri, documents.get(uri.as_str()))?;
                }
            }
            Message::Response(_) => {}
        }
    }
    Ok(())
}

/// What the server offers, as the handshake tells the client.
fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Kind(TextDocumentSyncKind::INCREMENTAL)),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        rename_provider: Some(OneOf::Right(RenameOptions {
            prepare_provider: Some(true),
            work_done_progress_options: WorkDoneProgressOptions::default(),
        })),
        document_symbol_provider: Some(OneOf::Left(true)),
        color_provider: Some(lsp_types::ColorProviderCapability::Simple(true)),
        document_formatting_provider: Some(OneOf::Left(true)),
        execute_command_provider: Some(lsp_types::ExecuteCommandOptions {
            commands: vec![picture::RENDER.to_string()],
            ..Default::default()
        }),
        completion_provider: Some(lsp_types::CompletionOptions {
            trigger_characters: Some(vec![" ".to_string(), "(".to_string(), ",".to_string()]),
            ..Default::default()
        }),
        signature_help_provider: Some(lsp_types::SignatureHelpOptions {
            trigger_characters: Some(vec!["(".to_string(), ",".to_string()]),
            ..Default::default()
        }),
        code_action_provider: Some(CodeActionProviderCapability::Options(lsp_types::CodeActionOptions {
            code_action_kinds: Some(vec![CodeActionKind::QUICKFIX]),
            ..Default::default()
        })),
        ..ServerCapabilities::default()
    }
}

/// Keeps `documents` as a notification changes them; the document whose
/// diagnostics must be published again, if any.
fn follow(documents: &mut HashMap<String, Document>, notification: Notification) -> Option<Uri> {
    match notification.method.as_str() {
        DidOpenTextDocument::METHOD => {
            let params: lsp_types::DidOpenTextDocumentParams =
                notification.extract(DidOpenTextDocument::METHOD).ok()?;
            let document = params.text_document;
            documents.insert(
                document.uri.as_str().to_string(),
                Document::new(&document.uri, document.text, document.version, None),
            );
            Some(document.uri)
        }
        DidChangeTextDocument::METHOD => {
            let params: lsp_types::DidChangeTextDocumentParams =
                notification.extract(DidChangeTextDocument::METHOD).ok()?;
            let uri = params.text_document.uri;
            let document = documents.get_mut(uri.as_str())?;
            for change in params.content_changes {
                text::apply(&mut document.text, change);
            }
            let text = std::mem::take(&mut document.text);
            let last_names = std::mem::take(&mut document.last_names);
            *document = Document::new(&uri, text, params.text_document.version, Some(last_names));
            Some(uri)
        }
        DidCloseTextDocument::METHOD => {
            let params: lsp_types::DidCloseTextDocumentParams =
                notification.extract(DidCloseTextDocument::METHOD).ok()?;
            documents.remove(params.text_document.uri.as_str());
            Some(params.text_document.uri)
        }
        _ => None,
    }
}

/// Sends the diagnostics of `document` (none once it is closed).
fn publish(connection: &Connection, uri: &Uri, document: Option<&Document>) -> Result<(), String> {
    let diagnostics = document.map(|document| features::diagnostics(uri, &document.analysis)).unwrap_or_default();
    let params = PublishDiagnosticsParams { uri: uri.clone(), diagnostics, version: document.map(|d| d.version) };
    send(connection, Notification::new(PublishDiagnostics::METHOD.to_string(), params).into())
}

fn send(connection: &Connection, message: Message) -> Result<(), String> {
    connection.sender.send(message).map_err(|_| "the client closed the connection".to_string())
}

/// The answer to `request`, about one of `documents`.
fn answer(documents: &HashMap<String, Document>, client: &Client, request: Request) -> Response {
    let id = request.id.clone();
    let result = match request.method.as_str() {
        HoverRequest::METHOD => handle::<HoverRequest>(documents, request, |doc, params| {
            let at = &params.text_document_position_params;
            Ok(features::hover(&doc.text, &doc.analysis, &doc.names_at(at.position), at.position))
        }),
        GotoDefinition::METHOD => handle::<GotoDefinition>(documents, request, |doc, params| {
            let at = &params.text_document_position_params;
            Ok(features::definition(&at.text_document.uri, &doc.text, &doc.analysis, at.position))
        }),
        References::METHOD => handle::<References>(documents, request, |doc, params| {
            let at = &params.text_document_position;
            Ok(features::references(&at.text_document.uri, &doc.text, &doc.analysis, at.position))
        }),
        PrepareRenameRequest::METHOD => handle::<PrepareRenameRequest>(documents, request, |doc, params| {
            Ok(features::prepare_rename(&doc.text, &doc.analysis, params.position))
        }),
        Rename::METHOD => handle::<Rename>(documents, request, |doc, params| {
            let at = &params.text_document_position;
            features::rename(&at.text_document.uri, &doc.text, &doc.analysis, at.position, &params.new_name).map(Some)
        }),
        Completion::METHOD => handle::<Completion>(documents, request, |doc, params| {
            let at = params.text_document_position.position;
            Ok(Some(typing::complete(&doc.text, at, &doc.names_at(at), client.snippets)))
        }),
        SignatureHelpRequest::METHOD => handle::<SignatureHelpRequest>(documents, request, |doc, params| {
            let at = params.text_document_position_params.position;
            Ok(typing::signature(&doc.text, at, &doc.names_at(at)))
        }),
        DocumentColor::METHOD => {
            handle::<DocumentColor>(documents, request, |doc, _| Ok(features::colours(&doc.analysis)))
        }
        ColorPresentationRequest::METHOD => handle::<ColorPresentationRequest>(documents, request, |_, params| {
            Ok(features::colour_written(params.color))
        }),
        Formatting::METHOD => {
            handle::<Formatting>(documents, request, |doc, _| features::formatting(&doc.text, &doc.analysis).map(Some))
        }
        DocumentSymbolRequest::METHOD => {
            handle::<DocumentSymbolRequest>(documents, request, |doc, _| Ok(features::symbols(&doc.analysis)))
        }
        CodeActionRequest::METHOD => handle::<CodeActionRequest>(documents, request, |doc, params| {
            Ok(Some(features::quick_fixes(&params.text_document.uri, &doc.analysis, params.range)))
        }),
        ExecuteCommand::METHOD => request
            .extract::<lsp_types::ExecuteCommandParams>(ExecuteCommand::METHOD)
            .map_err(|error| format!("{error:?}"))
            .and_then(|(_, params)| execute(documents, &params)),
        _ => {
            let message = format!("unknown request `{}`", request.method);
            return Response::new_err(id, ErrorCode::MethodNotFound as i32, message);
        }
    };
    match result {
        Ok(value) => Response::new_ok(id, value),
        Err(message) => Response::new_err(id, ErrorCode::InvalidParams as i32, message),
    }
}

/// Runs a command: `rayrepl.render` with the document's URI, and the
/// render's options or nothing.
fn execute(documents: &HashMap<String, Document>, params: &lsp_types::ExecuteCommandParams) -> Result<Value, String> {
    if params.command != picture::RENDER {
        return Err(format!("unknown command `{}`: the one command is `{}`", params.command, picture::RENDER));
    }
    let uri = params.arguments.first().and_then(Value::as_str).ok_or("the render needs the document's URI first")?;
    let document = documents.get(uri).ok_or_else(|| format!("`{uri}` is not open"))?;
    picture::render_command(&document.analysis, params.arguments.get(1))
}

/// Reads the parameters of request `R`, finds its document and answers
/// with `work` (`null` for a document that is not open); a request that
/// cannot be done says why.
fn handle<R>(
    documents: &HashMap<String, Document>,
    request: Request,
    work: impl FnOnce(&Document, &R::Params) -> Result<R::Result, String>,
) -> Result<Value, String>
where
    R: lsp_types::request::Request,
    R::Params: DocumentParams,
{
    let (_, params) = request.extract::<R::Params>(R::METHOD).map_err(|error| format!("{error:?}"))?;
    match documents.get(params.uri().as_str()) {
        Some(document) => work(document, &params).map(to_json),
        None => Ok(Value::Null),
    }
}

/// The parameters of a request about one document.
trait DocumentParams {
    fn uri(&self) -> &Uri;
}

macro_rules! document_params {
    ($($params:ty => |$p:ident| $uri:expr;)*) => {
        $(impl DocumentParams for $params {
            fn uri(&self) -> &Uri {
                let $p = self;
                &$uri
            }
        })*
    };
}

document_params! {
    lsp_types::HoverParams => |p| p.text_document_position_params.text_document.uri;
    lsp_types::GotoDefinitionParams => |p| p.text_document_position_params.text_document.uri;
    lsp_types::ReferenceParams => |p| p.text_document_position.text_document.uri;
    lsp_types::TextDocumentPositionParams => |p| p.text_document.uri;
    lsp_types::DocumentSymbolParams => |p| p.text_document.uri;
    lsp_types::CodeActionParams => |p| p.text_document.uri;
    lsp_types::RenameParams => |p| p.text_document_position.text_document.uri;
    lsp_types::CompletionParams => |p| p.text_document_position.text_document.uri;
    lsp_types::DocumentColorParams => |p| p.text_document.uri;
    lsp_types::DocumentFormattingParams => |p| p.text_document.uri;
    lsp_types::ColorPresentationParams => |p| p.text_document.uri;
    lsp_types::SignatureHelpParams => |p| p.text_document_position_params.text_document.uri;
}

fn to_json(value: impl serde::Serialize) -> Value {
    serde_json::to_value(value).expect("protocol messages are JSON")
}

/// The name diagnostics give a document: its file's path (decoded from the
/// URI, as fluent-uri, the URI type of lsp-types, decodes it), or its URI.
fn display_name(uri: &Uri) -> String {
    match uri.scheme().map(|scheme| scheme.as_str()) {
        Some("file") => uri.path().as_estr().decode().into_string_lossy().into_owned(),
        _ => uri.as_str().to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_is_named_by_its_decoded_path() {
        let uri = |text: &str| text.parse::<Uri>().expect("a URI");
        assert_eq!(display_name(&uri("file:///tmp/my%20scene%C3%A9.ray")), "/tmp/my sceneé.ray");
        assert_eq!(display_name(&uri("untitled:Untitled-1")), "untitled:Untitled-1");
    }
}
