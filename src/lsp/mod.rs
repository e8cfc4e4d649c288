//! `graftal lsp`: a language server (LSP 3.17 over stdio) for every
//! notation graftal reads. A thin layer over the library calls the CLI
//! makes: each open document is compiled as `graftal check` compiles it
//! ([`driver::compile`]) on open and on every change, and its diagnostics
//! are published; hover, definitions and the outline read the compiled
//! system (of a file with errors, what was read of the parts that parse),
//! as [`driver::explain`] says them.
//! Nothing is derived on a keystroke: `check`'s derivation limits
//! (E0301, E0302) are left to `graftal check`.

mod edits;
mod features;
mod json;
mod position;
mod publish;
mod uri;

use crate::driver::{self, Compiled, Knowledge};
use crate::source::SourceFile;
use lsp_server::{ErrorCode, Message, Notification, Request, RequestId};
use lsp_types::notification::{
    DidChangeTextDocument, DidCloseTextDocument, DidOpenTextDocument, Notification as _,
    PublishDiagnostics,
};
use lsp_types::request::{ApplyWorkspaceEdit, CodeActionRequest, ExecuteCommand, Request as _};
use lsp_types::{
    CodeActionProviderCapability, CompletionOptions, ExecuteCommandOptions,
    HoverProviderCapability, OneOf, PublishDiagnosticsParams, ServerCapabilities,
    TextDocumentSyncCapability, TextDocumentSyncKind, Uri,
};
use serde_json::json;
use std::collections::HashMap;
use std::io::Write;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc::{channel, Receiver};

/// An open document: its URI and what compiling its text gave.
pub struct Document {
    pub uri: Uri,
    pub compiled: Compiled,
    /// Where its symbols and names are written, the user functions beside
    /// it: each found by the first request that needs it, once per compile.
    known: Knowledge,
}

impl Document {
    /// Compiles `text` under the path `uri` names, so that the notation
    /// comes from its extension and cpfg's side files are read beside it.
    fn new(uri: Uri, text: String) -> Self {
        let file = SourceFile::new(uri::to_path(&uri), text);
        Document {
            uri,
            compiled: driver::compile(file),
            known: Knowledge::default(),
        }
    }
}

/// What the server knows: the open documents by URI, and what the client
/// said it can take.
#[derive(Default)]
struct Server {
    docs: HashMap<String, Document>,
    /// Whether the client takes code actions (`codeActionLiteralSupport`);
    /// one that does not takes commands.
    literal_actions: bool,
    /// The requests to the client that answering a request made, written
    /// before its response.
    requests: Vec<String>,
    /// How many requests the server has sent the client: each one's id.
    sent: u64,
}

/// Serves the protocol on standard input and `stdout` until `exit`. A
/// thread reads standard input; this one answers and writes, serializing
/// each result straight from its protocol type: a result of ten thousand
/// locations built as a `serde_json::Value` tree first took a second.
pub fn run_stdio(stdout: &mut dyn Write) -> Result<(), String> {
    let (to_server, incoming) = channel();
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
    match serve(&incoming, stdout) {
        Ok(true) => Ok(()),
        Ok(false) => Err("`exit` without `shutdown` first".to_string()),
        Err(e) => Err(e.to_string()),
    }
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
        code_action_provider: Some(CodeActionProviderCapability::Simple(true)),
        document_formatting_provider: Some(OneOf::Left(true)),
        execute_command_provider: Some(ExecuteCommandOptions {
            commands: vec![edits::APPLY_FIX.to_string()],
            ..Default::default()
        }),
        ..Default::default()
    }
}

/// Where the conversation stands (LSP 3.17's lifecycle).
#[derive(PartialEq)]
enum Stage {
    /// Before `initialize`: requests are refused.
    Starting,
    Running,
    /// After `shutdown`: only `exit` is expected.
    ShutDown,
}

/// Serves the messages of `incoming`, writing to `out`, until `exit` (or
/// until the client goes away). `Ok(true)` when `shutdown` came first: LSP
/// asks for exit status 0 then, and 1 otherwise.
pub fn serve(incoming: &Receiver<Message>, out: &mut dyn Write) -> std::io::Result<bool> {
    let mut server = Server::default();
    let mut stage = Stage::Starting;
    for msg in incoming {
        match msg {
            Message::Request(req) => {
                let refused = match (&stage, req.method.as_str()) {
                    (Stage::Starting, "initialize") => {
                        stage = Stage::Running;
                        server.literal_actions = takes_literal_actions(&req.params);
                        let init = json!({ "capabilities": capabilities() });
                        write_body(out, &result_body(&req.id, &init.to_string()))?;
                        continue;
                    }
                    (Stage::Starting, _) => Some((
                        ErrorCode::ServerNotInitialized,
                        "graftal lsp: `initialize` first",
                    )),
                    (Stage::ShutDown, _) => Some((
                        ErrorCode::InvalidRequest,
                        "graftal lsp: shut down; only `exit` is expected",
                    )),
                    (Stage::Running, "shutdown") => {
                        stage = Stage::ShutDown;
                        write_body(out, &result_body(&req.id, "null"))?;
                        continue;
                    }
                    (Stage::Running, _) => None,
                };
                let body = match refused {
                    Some((code, why)) => error_body(req.id, code as i32, why.to_string()),
                    None => match guarded(|| server.answer(&req)) {
                        Ok(result) => result_body(&req.id, &result),
                        Err((code, why)) => error_body(req.id, code, why),
                    },
                };
                for request in std::mem::take(&mut server.requests) {
                    write_body(out, &request)?;
                }
                write_body(out, &body)?;
            }
            Message::Notification(n) if n.method == "exit" => return Ok(stage == Stage::ShutDown),
            Message::Notification(n) if stage == Stage::Running => {
                // A panic while compiling loses that document's diagnostics,
                // not the server.
                let published = catch_unwind(AssertUnwindSafe(|| server.notified(&n)));
                for body in published.unwrap_or_default() {
                    write_body(out, &body)?;
                }
            }
            Message::Notification(_) | Message::Response(_) => {}
        }
    }
    Ok(stage == Stage::ShutDown)
}

/// Writes one message: its header, then `body`.
fn write_body(out: &mut dyn Write, body: &str) -> std::io::Result<()> {
    write!(out, "Content-Length: {}\r\n\r\n", body.len())?;
    out.write_all(body.as_bytes())?;
    out.flush()
}

/// The response to request `id` whose result is the JSON text `result`.
fn result_body(id: &RequestId, result: &str) -> String {
    let id = serde_json::to_string(id).unwrap_or_else(|_| "null".into());
    format!(r#"{{"jsonrpc":"2.0","id":{id},"result":{result}}}"#)
}

/// The error response to request `id`.
fn error_body(id: RequestId, code: i32, message: String) -> String {
    let error = json!({ "code": code, "message": message });
    json!({ "jsonrpc": "2.0", "id": id, "error": error }).to_string()
}

/// The notification `method` with `params`, as a message body.
fn notification_body(method: &str, params: &impl serde::Serialize) -> String {
    let params = serde_json::to_string(params).unwrap_or_else(|_| "null".into());
    format!(r#"{{"jsonrpc":"2.0","method":"{method}","params":{params}}}"#)
}

/// The request `method` with `params` and id `id`, as a message body.
fn request_body(id: &RequestId, method: &str, params: &impl serde::Serialize) -> String {
    let id = serde_json::to_string(id).unwrap_or_else(|_| "null".into());
    let params = serde_json::to_string(params).unwrap_or_else(|_| "null".into());
    format!(r#"{{"jsonrpc":"2.0","id":{id},"method":"{method}","params":{params}}}"#)
}

/// What `answer` gives, or an internal error when it panics: one bad
/// request does not end the server.
fn guarded(answer: impl FnOnce() -> Answer) -> Answer {
    catch_unwind(AssertUnwindSafe(answer)).unwrap_or_else(|panic| {
        let why = panic
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        Err((
            ErrorCode::InternalError as i32,
            format!("graftal lsp: internal error while answering: {why}"),
        ))
    })
}

/// A request's result as JSON text, or an error code and message.
type Answer = Result<String, (i32, String)>;

impl Server {
    /// Takes in a notification; the diagnostics to publish because of it.
    fn notified(&mut self, n: &Notification) -> Vec<String> {
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
    fn answer(&mut self, req: &Request) -> Answer {
        let answered = match req.method.as_str() {
            CodeActionRequest::METHOD => self.code_actions(&req.params),
            ExecuteCommand::METHOD => self.execute(&req.params),
            method => features::answer(&self.docs, method, &req.params),
        };
        match answered {
            Ok(Some(result)) => Ok(result),
            Ok(None) => Err((
                ErrorCode::MethodNotFound as i32,
                format!("graftal lsp does not answer `{}`", req.method),
            )),
            Err(e) => Err((ErrorCode::InvalidParams as i32, e)),
        }
    }

    /// The quick fixes asked for by `params`, as the client takes them.
    fn code_actions(&self, params: &serde_json::Value) -> Result<Option<String>, String> {
        let p: lsp_types::CodeActionParams = parse(params)?;
        let fixes = edits::quick_fixes(
            &self.docs,
            &p.text_document.uri,
            p.range,
            &p.context.diagnostics,
            self.literal_actions,
        );
        serde_json::to_string(&fixes)
            .map(Some)
            .map_err(|e| e.to_string())
    }

    /// Runs the command `params` names (a quick fix's): the edit is asked
    /// of the client with `workspace/applyEdit`, and the answer is `null`.
    fn execute(&mut self, params: &serde_json::Value) -> Result<Option<String>, String> {
        let p: lsp_types::ExecuteCommandParams = parse(params)?;
        let edit = edits::command_edit(&p)?;
        self.sent = self.sent.wrapping_add(1);
        let id = RequestId::from(format!("graftal-{}", self.sent));
        self.requests
            .push(request_body(&id, ApplyWorkspaceEdit::METHOD, &edit));
        Ok(Some("null".into()))
    }
}

/// Whether the client's capabilities (`initialize`'s `params`) say it
/// takes code action literals rather than commands (LSP 3.8 and later).
fn takes_literal_actions(params: &serde_json::Value) -> bool {
    let at = "/capabilities/textDocument/codeAction/codeActionLiteralSupport";
    params.pointer(at).is_some_and(|v| v.is_object())
}

/// The `publishDiagnostics` notification for `uri`, as a message body.
fn diagnostics_note(uri: Uri, diagnostics: Vec<lsp_types::Diagnostic>) -> String {
    let params = PublishDiagnosticsParams {
        uri,
        diagnostics,
        version: None,
    };
    notification_body(PublishDiagnostics::METHOD, &params)
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
        let (code, message) = guarded(|| panic!("boom")).expect_err("an error");
        assert_eq!(code, ErrorCode::InternalError as i32);
        assert!(message.contains("boom"), "{message}");
    }

    /// The bodies `serve` writes for `messages` (given as JSON).
    fn served(messages: &[serde_json::Value]) -> Vec<serde_json::Value> {
        let (tx, rx) = channel();
        for m in messages {
            tx.send(serde_json::from_value(m.clone()).unwrap()).unwrap();
        }
        drop(tx);
        let mut out = Vec::new();
        let shut_down = serve(&rx, &mut out).unwrap();
        let asked = messages.iter().any(|m| m["method"] == "shutdown");
        assert_eq!(shut_down, asked, "exit status 0 only after `shutdown`");
        let text = String::from_utf8(out).unwrap();
        (text.split("Content-Length: ").skip(1))
            .map(|m| serde_json::from_str(m.split_once("\r\n\r\n").unwrap().1).unwrap())
            .collect()
    }

    #[test]
    fn exit_without_shutdown_is_not_a_clean_end() {
        let req = |id: i32, method: &str| json!({ "id": id, "method": method, "params": null });
        // `served` asserts what `serve` says of the end.
        let out = served(&[
            req(1, "initialize"),
            json!({ "method": "exit", "params": null }),
        ]);
        assert_eq!(out.len(), 1);
    }

    #[test]
    fn requests_before_initialize_and_after_shutdown_are_refused() {
        let req = |id: i32, method: &str| json!({ "id": id, "method": method, "params": null });
        let out = served(&[
            req(1, "textDocument/hover"),
            req(2, "initialize"),
            req(3, "shutdown"),
            req(4, "textDocument/hover"),
            json!({ "method": "exit", "params": null }),
            req(5, "textDocument/hover"),
        ]);
        assert_eq!(out.len(), 4, "nothing is answered after `exit`: {out:?}");
        let code = ErrorCode::ServerNotInitialized as i32;
        assert_eq!(out[0]["error"]["code"], code);
        assert_eq!(out[1]["result"]["capabilities"]["hoverProvider"], true);
        assert_eq!(out[2]["id"], 3);
        assert_eq!(out[2]["result"], serde_json::Value::Null);
        assert_eq!(out[3]["error"]["code"], ErrorCode::InvalidRequest as i32);
    }
}
