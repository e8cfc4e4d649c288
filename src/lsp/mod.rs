//! `graftal lsp`: a language server (LSP 3.17 over stdio) for every
//! notation graftal reads. A thin layer over the library calls the CLI
//! makes: each open document is compiled as `graftal check` compiles it
//! ([`driver::compile`]) on open and on every change, and its diagnostics
//! are published; hover, definitions and the outline read the compiled
//! system. Nothing is derived on a keystroke: `check`'s derivation limits
//! (E0301, E0302) are left to `graftal check`.

mod features;
mod position;
mod publish;
mod uri;

use crate::driver::{self, Compiled};
use crate::source::SourceFile;
use lsp_server::{Connection, ErrorCode, Message, Notification, Request, RequestId, Response};
use lsp_types::notification::{
    DidChangeTextDocument, DidCloseTextDocument, DidOpenTextDocument, Notification as _,
    PublishDiagnostics,
};
use lsp_types::{
    CompletionOptions, HoverProviderCapability, OneOf, PublishDiagnosticsParams,
    ServerCapabilities, TextDocumentSyncCapability, TextDocumentSyncKind, Uri,
};
use std::collections::HashMap;
use std::io::Write;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// An open document: its URI and what compiling its text gave.
pub struct Document {
    pub uri: Uri,
    pub compiled: Compiled,
}

impl Document {
    /// Compiles `text` under the path `uri` names, so that the notation
    /// comes from its extension and cpfg's side files are read beside it.
    fn new(uri: Uri, text: String) -> Self {
        let file = SourceFile::new(uri::to_path(&uri), text);
        Document {
            uri,
            compiled: driver::compile(file),
        }
    }
}

/// What the server knows: the open documents by URI.
#[derive(Default)]
struct Server {
    docs: HashMap<String, Document>,
}

/// Serves the protocol on standard input and `stdout` until `exit`. The
/// caller holds the standard output (the CLI locks it once), so the server
/// runs on a thread of its own and this thread writes what it sends.
pub fn run_stdio(stdout: &mut dyn Write) -> Result<(), String> {
    let (server_end, client_end) = Connection::memory();
    let server = std::thread::spawn(move || serve(&server_end));
    let to_server = client_end.sender;
    // Not joined: it may be blocked reading a client that never closes.
    std::thread::spawn(move || {
        let mut stdin = std::io::BufReader::new(std::io::stdin());
        while let Ok(Some(msg)) = Message::read(&mut stdin) {
            let exit = matches!(&msg, Message::Notification(n) if n.method == "exit");
            if to_server.send(msg).is_err() || exit {
                break;
            }
        }
    });
    let mut written = Ok(());
    for msg in &client_end.receiver {
        if written.is_ok() {
            written = msg.write(&mut &mut *stdout).map_err(|e| e.to_string());
        }
    }
    server
        .join()
        .map_err(|_| "the server stopped".to_string())??;
    written
}

/// What the server can do, as `initialize` answers.
fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Kind(TextDocumentSyncKind::FULL)),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        document_symbol_provider: Some(OneOf::Left(true)),
        completion_provider: Some(CompletionOptions::default()),
        ..Default::default()
    }
}

/// Answers `initialize`, then serves `connection` until `shutdown` and
/// `exit` (or until the client goes away).
pub fn serve(connection: &Connection) -> Result<(), String> {
    let caps = serde_json::to_value(capabilities()).map_err(|e| e.to_string())?;
    connection.initialize(caps).map_err(|e| e.to_string())?;
    let mut server = Server::default();
    for msg in &connection.receiver {
        match msg {
            Message::Request(req) => {
                if connection
                    .handle_shutdown(&req)
                    .map_err(|e| e.to_string())?
                {
                    return Ok(());
                }
                let response = guarded(req.id.clone(), || server.answer(&req));
                send(connection, Message::Response(response));
            }
            Message::Notification(n) => {
                // A panic while compiling loses that document's diagnostics,
                // not the server.
                let published = catch_unwind(AssertUnwindSafe(|| server.notified(&n)));
                for note in published.unwrap_or_default() {
                    send(connection, Message::Notification(note));
                }
            }
            Message::Response(_) => {}
        }
    }
    Ok(())
}

fn send(connection: &Connection, msg: Message) {
    // The client is gone when this fails; the receiving loop then ends.
    let _ = connection.sender.send(msg);
}

/// The response `answer` gives for request `id`, or an error response when
/// it panics: one bad request does not end the server.
fn guarded(id: RequestId, answer: impl FnOnce() -> Response) -> Response {
    catch_unwind(AssertUnwindSafe(answer)).unwrap_or_else(|panic| {
        let why = panic
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        Response::new_err(
            id,
            ErrorCode::InternalError as i32,
            format!("graftal lsp: internal error while answering: {why}"),
        )
    })
}

impl Server {
    /// Takes in a notification; the diagnostics to publish because of it.
    fn notified(&mut self, n: &Notification) -> Vec<Notification> {
        let (uri, text) = match n.method.as_str() {
            DidOpenTextDocument::METHOD => {
                let Ok(p) = parse::<lsp_types::DidOpenTextDocumentParams>(&n.params) else {
                    return Vec::new();
                };
                (p.text_document.uri, p.text_document.text)
            }
            DidChangeTextDocument::METHOD => {
                let Ok(p) = parse::<lsp_types::DidChangeTextDocumentParams>(&n.params) else {
                    return Vec::new();
                };
                // Full sync: the last change holds the whole text.
                let Some(change) = p.content_changes.into_iter().last() else {
                    return Vec::new();
                };
                (p.text_document.uri, change.text)
            }
            DidCloseTextDocument::METHOD => {
                if let Ok(p) = parse::<lsp_types::DidCloseTextDocumentParams>(&n.params) {
                    self.docs.remove(p.text_document.uri.as_str());
                    return vec![diagnostics_note(p.text_document.uri, Vec::new())];
                }
                return Vec::new();
            }
            _ => return Vec::new(),
        };
        let doc = Document::new(uri.clone(), text);
        let c = &doc.compiled;
        let notes = publish::by_file(&c.diagnostics.0, &c.file, &uri)
            .into_iter()
            .map(|(u, ds)| diagnostics_note(u, ds))
            .collect();
        self.docs.insert(uri.as_str().to_string(), doc);
        notes
    }

    /// The response to request `req`.
    fn answer(&self, req: &Request) -> Response {
        match features::answer(&self.docs, &req.method, &req.params) {
            Ok(Some(value)) => Response::new_ok(req.id.clone(), value),
            Ok(None) => Response::new_err(
                req.id.clone(),
                ErrorCode::MethodNotFound as i32,
                format!("graftal lsp does not answer `{}`", req.method),
            ),
            Err(e) => Response::new_err(req.id.clone(), ErrorCode::InvalidParams as i32, e),
        }
    }
}

fn diagnostics_note(uri: Uri, diagnostics: Vec<lsp_types::Diagnostic>) -> Notification {
    Notification::new(
        PublishDiagnostics::METHOD.to_string(),
        PublishDiagnosticsParams {
            uri,
            diagnostics,
            version: None,
        },
    )
}

/// Request or notification parameters as `T`.
fn parse<T: serde::de::DeserializeOwned>(params: &serde_json::Value) -> Result<T, String> {
    serde_json::from_value(params.clone()).map_err(|e| format!("invalid parameters: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panicking_answer_is_an_error_response() {
        let r = guarded(RequestId::from(7), || panic!("boom"));
        let e = r.error.expect("an error");
        assert_eq!(e.code, ErrorCode::InternalError as i32);
        assert!(e.message.contains("boom"), "{}", e.message);
        assert_eq!(r.id, RequestId::from(7));
    }
}
