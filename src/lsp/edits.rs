//! The requests that answer with edits: quick fixes (the replacement a
//! diagnostic suggests, [`crate::diagnostics::Fix`]), as code actions or
//! as commands that ask the client for the edit, and formatting (`.gft`,
//! as `graftal fmt` writes it).

use super::position::{position, range};
use super::publish::convert;
use super::{uri, Document};
use crate::format::{outcome, Outcome};
use crate::source::SourceFile;
use lsp_types::{
    ApplyWorkspaceEditParams, CodeAction, CodeActionKind, CodeActionOrCommand, Command,
    ExecuteCommandParams, NumberOrString, Range, TextEdit, Uri, WorkspaceEdit,
};
use std::collections::HashMap;

/// The most quick fixes one request lists: a selection of the whole of a
/// file with thousands of mistakes would otherwise list thousands.
const MAX_FIXES: usize = 100;

/// The command that stands for a quick fix with a client that takes no
/// code action literals (no `codeActionLiteralSupport`): its one argument
/// is the `workspace/applyEdit` request the server sends when it runs.
pub const APPLY_FIX: &str = "graftal.applyFix";

/// The quick fixes for the file at `uri` asked for over `asked`, with the
/// client's `listed` diagnostics: of the diagnostics that know their fix,
/// those of the open document at `uri` and those other open documents
/// report on it (a cpfg view file, an `#include`d file). Each writes the
/// replacement over the span it names. `literal`: as code actions, else as
/// [`APPLY_FIX`] commands.
pub fn quick_fixes(
    docs: &HashMap<String, Document>,
    uri: &Uri,
    asked: Range,
    listed: &[lsp_types::Diagnostic],
    literal: bool,
) -> Vec<CodeActionOrCommand> {
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
            let place = d.span.as_ref().map_or(at, |s| range(file, s));
            let wanted = touches(&at, &asked) || touches(&place, &asked);
            if !(wanted || is_listed(d.code.0, place, listed)) {
                continue;
            }
            let was = file.text.get(fix.span.clone()).unwrap_or("");
            let title = format!("Replace `{was}` with `{}`", fix.replacement);
            let edit = whole_edit(uri, vec![TextEdit::new(at, fix.replacement.clone())]);
            out.push(action(title, convert(d, file, uri), edit, literal));
            if out.len() == MAX_FIXES {
                return out;
            }
        }
    }
    out
}

/// Whether ranges `a` and `b` overlap or meet (a cursor at either end of
/// a range touches it).
fn touches(a: &Range, b: &Range) -> bool {
    a.start <= b.end && b.start <= a.end
}

/// Whether the client lists the diagnostic `code` at `place` among those
/// it asks about. A client asks over the cursor's place and lists the
/// diagnostics of its line (Neovim), which the place may not touch.
fn is_listed(code: &str, place: Range, listed: &[lsp_types::Diagnostic]) -> bool {
    let code = Some(NumberOrString::String(code.to_string()));
    (listed.iter()).any(|l| l.range == place && l.code == code)
}

/// The quick fix `title` that makes `edit`, fixing `d`: a code action, or
/// the [`APPLY_FIX`] command that asks the client to make it.
fn action(
    title: String,
    d: lsp_types::Diagnostic,
    edit: WorkspaceEdit,
    literal: bool,
) -> CodeActionOrCommand {
    if !literal {
        let apply = ApplyWorkspaceEditParams {
            label: Some(title.clone()),
            edit,
        };
        let arguments = serde_json::to_value(apply).ok().map(|a| vec![a]);
        return CodeActionOrCommand::Command(Command {
            title,
            command: APPLY_FIX.to_string(),
            arguments,
        });
    }
    CodeActionOrCommand::CodeAction(CodeAction {
        title,
        kind: Some(CodeActionKind::QUICKFIX),
        diagnostics: Some(vec![d]),
        edit: Some(edit),
        is_preferred: Some(true),
        ..Default::default()
    })
}

/// The `workspace/applyEdit` request's parameters that running the
/// command `p` (an [`APPLY_FIX`] of [`quick_fixes`]) sends.
pub fn command_edit(p: &ExecuteCommandParams) -> Result<ApplyWorkspaceEditParams, String> {
    if p.command != APPLY_FIX {
        return Err(format!("graftal lsp has no command `{}`", p.command));
    }
    match p.arguments.as_slice() {
        [edit] => serde_json::from_value(edit.clone())
            .map_err(|e| format!("`{APPLY_FIX}` takes a workspace edit: {e}")),
        _ => Err(format!(
            "`{APPLY_FIX}` takes one argument, a workspace edit"
        )),
    }
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
