//! The requests that answer with edits: quick fixes (the replacement a
//! diagnostic suggests, [`crate::diagnostics::Fix`]) and formatting
//! (`.gft`, as `graftal fmt` writes it).

use super::position::{position, range};
use super::publish::convert;
use super::{uri, Document};
use crate::format::{outcome, Outcome};
use crate::source::SourceFile;
use lsp_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, Range, TextEdit, Uri, WorkspaceEdit,
};
use std::collections::HashMap;

/// The most quick fixes one request lists: a selection of the whole of a
/// file with thousands of mistakes would otherwise list thousands.
const MAX_FIXES: usize = 100;

/// The quick fixes for the file at `uri` that touch `asked`: of the
/// diagnostics that know their fix, those of the open document at `uri`
/// and those other open documents report on it (a cpfg view file, an
/// `#include`d file). Each writes the replacement over the span it names.
pub fn quick_fixes(
    docs: &HashMap<String, Document>,
    uri: &Uri,
    asked: Range,
) -> Vec<CodeActionOrCommand> {
    let touches = |r: &Range| r.start <= asked.end && asked.start <= r.end;
    // The document itself first, then the others in a stable order.
    let mut order: Vec<&Document> = docs.values().collect();
    order.sort_by_key(|d| (d.uri != *uri, d.uri.as_str().to_string()));
    let mut out = Vec::new();
    for doc in order {
        let c = &doc.compiled;
        let mut side_files: HashMap<&str, Option<SourceFile>> = HashMap::new();
        for (d, fix) in c
            .diagnostics
            .iter()
            .filter_map(|d| Some((d, d.fix.as_ref()?)))
        {
            let file = match &d.side {
                None if doc.uri == *uri => &c.file,
                None => continue,
                Some(s) => {
                    let found = side_files.entry(&s.name).or_insert_with(|| {
                        let here = uri::from_path(&s.name).is_some_and(|u| u == *uri);
                        here.then(|| SourceFile::new(s.name.clone(), s.text.clone()))
                    });
                    let Some(file) = found.as_ref() else { continue };
                    file
                }
            };
            let at = range(file, &fix.span);
            if !touches(&at) {
                continue;
            }
            let was = file.text.get(fix.span.clone()).unwrap_or("");
            out.push(CodeActionOrCommand::CodeAction(CodeAction {
                title: format!("Replace `{was}` with `{}`", fix.replacement),
                kind: Some(CodeActionKind::QUICKFIX),
                diagnostics: Some(vec![convert(d, file, uri)]),
                edit: Some(whole_edit(
                    uri,
                    vec![TextEdit::new(at, fix.replacement.clone())],
                )),
                is_preferred: Some(true),
                ..Default::default()
            }));
            if out.len() == MAX_FIXES {
                return out;
            }
        }
    }
    out
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
    if !crate::format::formats(c.front) {
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
