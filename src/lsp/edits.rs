//! The requests that answer with edits: quick fixes (the replacement a
//! diagnostic suggests, [`crate::diagnostics::Fix`]) and formatting
//! (`.gft`, as `graftal fmt` writes it).

use super::position::{position, range};
use super::publish::convert;
use super::Document;
use crate::format::{outcome, Outcome};
use lsp_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, Range, TextEdit, Uri, WorkspaceEdit,
};
use std::collections::HashMap;

/// The most quick fixes one request lists: a selection of the whole of a
/// file with thousands of mistakes would otherwise list thousands.
const MAX_FIXES: usize = 100;

/// The quick fixes of the diagnostics of `doc` that touch `asked` and
/// know their fix: each writes the replacement over the span it names.
pub fn quick_fixes(doc: &Document, asked: Range) -> Vec<CodeActionOrCommand> {
    let c = &doc.compiled;
    let touches = |r: &Range| r.start <= asked.end && asked.start <= r.end;
    (c.diagnostics.iter())
        .filter(|d| d.side.is_none())
        .filter_map(|d| Some((d, d.fix.as_ref()?)))
        .filter(|(_, fix)| touches(&range(&c.file, &fix.span)))
        .take(MAX_FIXES)
        .map(|(d, fix)| {
            let edit = TextEdit::new(range(&c.file, &fix.span), fix.replacement.clone());
            let was = c.file.text.get(fix.span.clone()).unwrap_or("");
            CodeActionOrCommand::CodeAction(CodeAction {
                title: format!("Replace `{was}` with `{}`", fix.replacement),
                kind: Some(CodeActionKind::QUICKFIX),
                diagnostics: Some(vec![convert(d, &c.file, &doc.uri)]),
                edit: Some(whole_edit(&doc.uri, vec![edit])),
                is_preferred: Some(true),
                ..Default::default()
            })
        })
        .collect()
}

/// `edits` of the document at `uri`, as a workspace edit.
fn whole_edit(uri: &Uri, edits: Vec<TextEdit>) -> WorkspaceEdit {
    WorkspaceEdit {
        changes: Some(HashMap::from([(uri.clone(), edits)])),
        ..Default::default()
    }
}

/// The edits that make a `.gft` document what `graftal fmt` writes: one
/// that replaces the whole text, or none when it is already so, is not
/// `.gft`, or does not read (its diagnostics say why).
pub fn formatted(doc: &Document) -> Vec<TextEdit> {
    let c = &doc.compiled;
    if c.front.name() != "gft" {
        return Vec::new();
    }
    match outcome(c) {
        Outcome::Formatted(text) if text != c.file.text => {
            let end = position(&c.file, c.file.text.len());
            let whole = Range::new(lsp_types::Position::new(0, 0), end);
            vec![TextEdit::new(whole, text)]
        }
        _ => Vec::new(),
    }
}
