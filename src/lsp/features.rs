//! The requests about a document: hover, definition, references, the
//! outline, completion and formatting, answered from what compiling it
//! gave (its system, the places of its productions and symbols) without
//! deriving. What a hover says and where a symbol is defined are the
//! library's ([`crate::driver::explain`]); this face turns them into the
//! protocol's positions.

use super::position::{offset, range};
use super::{edits, json, parse, uri, Document};
use crate::common::vocabulary::{self, TurtleSet};
use crate::driver::explain::{DeclarationKind, FunctionSite};
use crate::driver::{what_it_does, Names};
use crate::source::SourceFile;
use lsp_types::request::{
    Completion, DocumentSymbolRequest, Formatting, GotoDefinition, HoverRequest, References,
    Request as _,
};
use lsp_types::{
    CompletionItem, CompletionItemKind, Hover, HoverContents, MarkupContent, MarkupKind,
    SymbolKind, TextDocumentPositionParams,
};
use serde_json::Value;
use std::collections::{HashMap, HashSet};

/// The answer to request `method` with `params`: `Ok(None)` for a method
/// the server does not answer; JSON `null` when there is nothing to say.
pub fn answer(
    docs: &HashMap<String, Document>,
    method: &str,
    params: &Value,
) -> Result<Option<String>, String> {
    let at = |p: &TextDocumentPositionParams| {
        let doc = docs.get(p.text_document.uri.as_str());
        doc.map(|d| (d, offset(&d.compiled.file, p.position)))
    };
    let value = match method {
        HoverRequest::METHOD => {
            let p: lsp_types::HoverParams = parse(params)?;
            let hover = at(&p.text_document_position_params).and_then(|(d, o)| hover(d, o));
            serde_json::to_string(&hover)
        }
        GotoDefinition::METHOD => {
            let p: lsp_types::GotoDefinitionParams = parse(params)?;
            let found = at(&p.text_document_position_params)
                .map_or_else(|| "[]".into(), |(d, o)| locations(d, o, true));
            Ok(found)
        }
        References::METHOD => {
            let p: lsp_types::ReferenceParams = parse(params)?;
            let found = at(&p.text_document_position)
                .map_or_else(|| "[]".into(), |(d, o)| locations(d, o, false));
            Ok(found)
        }
        DocumentSymbolRequest::METHOD => {
            let p: lsp_types::DocumentSymbolParams = parse(params)?;
            let doc = docs.get(p.text_document.uri.as_str());
            Ok(doc.map_or_else(|| "[]".into(), outline))
        }
        Completion::METHOD => {
            let p: lsp_types::CompletionParams = parse(params)?;
            let doc = docs.get(p.text_document_position.text_document.uri.as_str());
            serde_json::to_string(&doc.map(completions).unwrap_or_default())
        }
        Formatting::METHOD => {
            let p: lsp_types::DocumentFormattingParams = parse(params)?;
            let doc = docs.get(p.text_document.uri.as_str());
            serde_json::to_string(&doc.map(edits::formatted).unwrap_or_default())
        }
        _ => return Ok(None),
    };
    value.map(Some).map_err(|e| e.to_string())
}

/// Where user function `f` is declared: `Location[]` as JSON.
fn function_location(f: &FunctionSite) -> String {
    let Some(uri) = uri::from_path(&f.path.to_string_lossy()) else {
        return "[]".into();
    };
    let file = SourceFile::new(f.path.to_string_lossy().into_owned(), f.text.clone());
    json::locations(&uri, std::iter::once(range(&file, &f.span)))
}

/// The definitions of what is written at `at` (a user function's, in its
/// own file), or every place it is written: `Location[]` as JSON.
fn locations(doc: &Document, at: usize, definitions: bool) -> String {
    let c = &doc.compiled;
    let known = &doc.known;
    if let Some(f) = known.user_function_at(c, at).filter(|_| definitions) {
        return function_location(f);
    }
    let spans = if definitions {
        known.definitions(c, at)
    } else {
        known.references(c, at)
    };
    json::locations(&doc.uri, spans.iter().map(|s| range(&c.file, s)))
}

/// What hovering at `at` shows, as the library says it.
fn hover(doc: &Document, at: usize) -> Option<Hover> {
    let said = doc.known.hover(&doc.compiled, at)?;
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent {
            kind: MarkupKind::Markdown,
            value: said.markdown,
        }),
        range: said.span.map(|s| range(&doc.compiled.file, &s)),
    })
}

/// The names `doc` declares besides its symbols.
fn names(doc: &Document) -> &Names {
    doc.known.names(&doc.compiled)
}

/// How the outline and completion show a declared name.
fn symbol_kind(kind: DeclarationKind) -> SymbolKind {
    match kind {
        DeclarationKind::Function => SymbolKind::FUNCTION,
        DeclarationKind::Constant => SymbolKind::CONSTANT,
        DeclarationKind::Variable => SymbolKind::VARIABLE,
        DeclarationKind::Module => SymbolKind::MODULE,
    }
}

/// The outline: the settings, a library's entries, the names declared
/// (rules, rotations, macros) and each production under its predecessor's
/// name, in the order written: `DocumentSymbol[]` as JSON.
fn outline(doc: &Document) -> String {
    let c = &doc.compiled;
    let file = &c.file;
    let mut out = settings(doc);
    for d in &names(doc).decls {
        // A library's entries come from the library, whole.
        if c.library.is_none() || d.kind != DeclarationKind::Module {
            out.push((d.name.clone(), symbol_kind(d.kind), range(file, &d.span)));
        }
    }
    if let Some(lib) = &c.library {
        for e in &lib.entries {
            let name = if e.name.is_empty() {
                "(entry)".into()
            } else {
                e.name.clone()
            };
            out.push((name, SymbolKind::MODULE, range(file, &e.span)));
        }
    }
    if let Some(sys) = c.system_or_recovered() {
        for (p, span) in sys.productions.iter().zip(&c.spans.productions) {
            let name: String = (p.predecessor.iter())
                .map(|&s| sys.symbols.name(s))
                .collect::<Vec<_>>()
                .join(" ");
            let name = if name.trim().is_empty() {
                "(production)".into()
            } else {
                name
            };
            out.push((name, SymbolKind::FUNCTION, range(file, span)));
        }
    }
    out.sort_by_key(|o| (o.2.start.line, o.2.start.character));
    json::outline(out.into_iter())
}

/// The lines that start with one of the notation's keywords (`angle
/// factor: 4`, `ANGLE 30`, `axiom F`), as outline entries.
fn settings(doc: &Document) -> Vec<(String, SymbolKind, lsp_types::Range)> {
    let file = &doc.compiled.file;
    let keys: Vec<String> = (doc.compiled.front.keywords().into_iter())
        .map(|k| k.trim_end_matches(':').to_lowercase())
        .collect();
    let mut out = Vec::new();
    let mut at = 0;
    for line in file.text.split_inclusive('\n') {
        let start = at + line.len() - line.trim_start().len();
        at += line.len();
        let written = line.trim();
        let head = written.get(..written.len().min(24)).unwrap_or(written);
        let head = head.to_lowercase();
        let is_key = keys.iter().any(|k| {
            head.starts_with(k.as_str())
                && !(head[k.len()..].chars().next()).is_some_and(|c| c.is_alphanumeric())
        });
        if is_key {
            let shown = crate::diagnostics::shortened(written, 60).into_owned();
            out.push((
                shown,
                SymbolKind::PROPERTY,
                range(file, &(start..start + written.len())),
            ));
        }
    }
    out
}

/// The turtle set of `doc`'s notation (the `.gft` default is no set).
fn turtle_set(doc: &Document) -> TurtleSet {
    TurtleSet::from_name(doc.compiled.front.name()).unwrap_or(TurtleSet::None)
}

/// Completion: the notation's keywords, its turtle symbols with what they
/// do, and the symbols the document writes.
fn completions(doc: &Document) -> Vec<CompletionItem> {
    let item = |label: &str, kind, detail: String| CompletionItem {
        label: label.to_string(),
        kind: Some(kind),
        detail: Some(detail),
        ..Default::default()
    };
    let notation = doc.compiled.front.name();
    let mut out: Vec<CompletionItem> = (doc.compiled.front.keywords().into_iter())
        .map(|k| {
            item(
                k,
                CompletionItemKind::KEYWORD,
                format!("{notation} keyword"),
            )
        })
        .collect();
    let set = turtle_set(doc);
    let rotations = (doc.compiled.system_or_recovered()).map_or(&[][..], |s| &s.rotations);
    for &name in set.names() {
        if let Some(op) = vocabulary::op(set, name) {
            out.push(item(
                name,
                CompletionItemKind::OPERATOR,
                what_it_does(rotations, op),
            ));
        }
    }
    // Each label once: a file may declare ten thousand names.
    let mut seen: HashSet<String> = out.iter().map(|i| i.label.clone()).collect();
    for d in &names(doc).decls {
        if seen.insert(d.name.clone()) {
            let kind = match d.kind {
                DeclarationKind::Function => CompletionItemKind::FUNCTION,
                DeclarationKind::Module => CompletionItemKind::MODULE,
                DeclarationKind::Constant => CompletionItemKind::CONSTANT,
                DeclarationKind::Variable => CompletionItemKind::VARIABLE,
            };
            let first_line = d.about.lines().next().unwrap_or("").to_string();
            out.push(item(&d.name, kind, first_line));
        }
    }
    if let Some(sys) = doc.compiled.system_or_recovered() {
        for (id, info) in sys.symbols.iter() {
            if !info.name.is_empty() && seen.insert(info.name.clone()) {
                let does = sys.op(id).map_or("a symbol of this file".into(), |op| {
                    what_it_does(rotations, op)
                });
                out.push(item(&info.name, CompletionItemKind::VARIABLE, does));
            }
        }
    }
    out
}
