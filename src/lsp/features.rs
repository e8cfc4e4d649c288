//! The requests about a document: hover, definition, references, the
//! outline, completion and formatting, answered from what compiling it
//! gave (its system, the places of its productions and symbols) without
//! deriving.

use super::names::{self, Names};
use super::position::{offset, range};
use super::publish::explanation;
use super::{edits, json, parse, uri, Document};
use crate::common::vocabulary::{self, TurtleSet};
use crate::front::declared::word_at;
use crate::front::FunctionSite;
use crate::ir::{Angle, Axis, Rotation, Span, SymbolId, System, TurtleOp};
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

/// A place where a symbol is written: in a production's predecessor (a
/// definition) or anywhere else (the axiom, a successor).
pub struct Occurrence {
    span: Span,
    symbol: SymbolId,
    defines: bool,
}

/// The names `doc` declares besides its symbols, found once per compile.
fn names(doc: &Document) -> &Names {
    let c = &doc.compiled;
    doc.names.get_or_init(|| names::find(c.front, &c.file.text))
}

/// Every place a symbol of `doc`'s system is written, found once per
/// compile (the first request after it) and kept with the document.
fn occurrences(doc: &Document) -> &[Occurrence] {
    doc.occurrences.get_or_init(|| find_occurrences(doc))
}

/// Every place a symbol of `doc`'s system is written, as the span table
/// records it; predecessors are found in their production's text.
fn find_occurrences(doc: &Document) -> Vec<Occurrence> {
    let c = &doc.compiled;
    // A file with errors: the symbols of the parts that parse.
    let Some(sys) = c.system_or_recovered() else {
        return Vec::new();
    };
    let spans = &c.spans;
    let mut out: Vec<Occurrence> = (sys.axiom.0.iter().zip(&spans.axiom))
        .map(|(&symbol, span)| Occurrence {
            span: span.clone(),
            symbol,
            defines: false,
        })
        .collect();
    for (i, p) in sys.productions.iter().enumerate() {
        if let Some(span) = predecessor_span(sys, &c.file.text, spans.productions.get(i), p) {
            out.push(Occurrence {
                span,
                symbol: p.predecessor[0],
                defines: true,
            });
        }
        let per_alt = spans.successors.get(i).map(Vec::as_slice).unwrap_or(&[]);
        for (alt, alt_spans) in p.alternatives.iter().zip(per_alt) {
            for (&symbol, span) in alt.successor.0.iter().zip(alt_spans) {
                out.push(Occurrence {
                    span: span.clone(),
                    symbol,
                    defines: false,
                });
            }
        }
    }
    out
}

/// Where production `p`'s (first) predecessor symbol is written in its
/// production's span: after the left context's `<` when it has one.
fn predecessor_span(
    sys: &System,
    text: &str,
    production: Option<&Span>,
    p: &crate::ir::Production,
) -> Option<Span> {
    let span = production?;
    let line = text.get(span.clone())?;
    let name = sys.symbols.name(*p.predecessor.first()?);
    if name.is_empty() {
        return None;
    }
    let from = if p.left.is_empty() {
        0
    } else {
        line.find('<').map_or(0, |i| i + 1)
    };
    let at = span.start + from + line[from..].find(name)?;
    Some(at..at + name.len())
}

/// The symbol written at byte `at` (or just before it, where a cursor
/// after a symbol stands).
fn symbol_at(occ: &[Occurrence], at: usize) -> Option<SymbolId> {
    let hit = |o: &&Occurrence| o.span.start <= at && at < o.span.end;
    let before = |o: &&Occurrence| o.span.end == at && at > 0;
    (occ.iter().find(hit))
        .or_else(|| occ.iter().find(before))
        .map(|o| o.symbol)
}

/// The user function a source calls at `at` (a cpfg `func(NAME, x)` or
/// `func(k, x)`, when `at` is on its `NAME` or `k`), as its front end
/// finds it.
fn user_function_at(doc: &Document, at: usize) -> Option<&FunctionSite> {
    let c = &doc.compiled;
    let word = c.front.user_function_called_at(&c.file.text, at)?;
    let path = std::path::Path::new(&c.file.name);
    let sites = doc.functions.get_or_init(|| c.front.user_functions(path));
    match word.parse::<usize>() {
        Ok(k) => sites.iter().find(|s| s.number == k),
        Err(_) => sites.iter().find(|s| s.name.as_deref() == Some(word)),
    }
}

/// Where user function `f` is declared: `Location[]` as JSON.
fn function_location(f: &FunctionSite) -> String {
    let Some(uri) = uri::from_path(&f.path.to_string_lossy()) else {
        return "[]".into();
    };
    let file = SourceFile::new(f.path.to_string_lossy().into_owned(), f.text.clone());
    json::locations(&uri, std::iter::once(range(&file, &f.span)))
}

/// The most control points a hover lists.
const HOVER_POINTS: usize = 12;

/// A user function's hover: its name, number, file, samples and points.
fn function_text(f: &FunctionSite) -> String {
    let name = f.name.as_deref().unwrap_or("(unnamed)");
    let file = f
        .path
        .file_name()
        .map_or("?".into(), |n| n.to_string_lossy());
    let points = &f.points;
    let shown: Vec<String> = (points.iter().take(HOVER_POINTS))
        // Read as single precision, as cpfg reads them: shown so, as written.
        .map(|[x, y]| format!("({}, {})", *x as f32, *y as f32))
        .collect();
    let more = points.len().saturating_sub(HOVER_POINTS);
    let more = if more > 0 {
        format!(", … and {more} more")
    } else {
        String::new()
    };
    format!(
        "cpfg user function `{name}` (function {} of `{file}`)\n\nsamples: {}; {} points: {}{more}",
        f.number,
        f.samples,
        points.len(),
        shown.join(", ")
    )
}

/// The productions of the symbol at `at` and the declaration of the name
/// there (`definitions`), or every place either is written: `Location[]`
/// as JSON.
fn locations(doc: &Document, at: usize, definitions: bool) -> String {
    if let Some(f) = user_function_at(doc, at).filter(|_| definitions) {
        return function_location(f);
    }
    let occ = occurrences(doc);
    let symbol = symbol_at(occ, at);
    let names = names(doc);
    let decl = names.at(at);
    let named: Vec<&Span> = match decl {
        Some(i) if definitions => names.decls.get(i).map(|d| &d.span).into_iter().collect(),
        Some(i) => names.places(i).collect(),
        None => Vec::new(),
    };
    let mut spans: Vec<&Span> = occ
        .iter()
        .filter(|o| symbol.is_some() && Some(o.symbol) == symbol && (o.defines || !definitions))
        .map(|o| &o.span)
        .collect();
    // A LinF name is both declared (`lines F`) and a symbol: each place once.
    spans.extend(named);
    spans.sort_by_key(|s| (s.start, s.end));
    spans.dedup();
    let file = &doc.compiled.file;
    json::locations(&doc.uri, spans.into_iter().map(|s| range(file, s)))
}

/// What hovering at `at` shows: the explanation of the diagnostics there,
/// and what the symbol there does and which productions rewrite it.
fn hover(doc: &Document, at: usize) -> Option<Hover> {
    let c = &doc.compiled;
    let mut parts: Vec<String> = (c.diagnostics.iter())
        .filter(|d| d.side.is_none())
        .filter(|d| {
            d.span
                .as_ref()
                .is_some_and(|s| s.start <= at && at <= s.end)
        })
        .filter_map(|d| explanation(d.code.0))
        .collect();
    // A code written in the text (a comment that names it, say).
    let word = word_at(&c.file.text, at).filter(|w| !w.is_empty() && w.len() == 5);
    let code = word.and_then(|w| explanation(w).filter(|e| !parts.contains(e)));
    parts.extend(code);
    let names = names(doc);
    if let Some(i) = names.at(at) {
        parts.extend(names.decls.get(i).map(|d| d.about.clone()));
    }
    parts.extend(user_function_at(doc, at).map(function_text));
    if let (Some(sys), Some(symbol)) = (c.system_or_recovered(), symbol_at(occurrences(doc), at)) {
        parts.push(symbol_text(doc, sys, symbol));
    }
    if parts.is_empty() {
        return None;
    }
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent {
            kind: MarkupKind::Markdown,
            value: parts.join("\n\n---\n\n"),
        }),
        range: None,
    })
}

/// The most productions a hover lists.
const HOVER_PRODUCTIONS: usize = 10;

/// A symbol's hover: what the turtle does for it, and the productions that
/// rewrite it (their lines).
fn symbol_text(doc: &Document, sys: &System, symbol: SymbolId) -> String {
    let name = sys.symbols.name(symbol);
    let does = sys.op(symbol).map_or_else(
        || "nothing to the turtle".to_string(),
        |op| what_it_does(&sys.rotations, op),
    );
    let mut text = format!("`{name}`: {does}");
    let file = &doc.compiled.file;
    let rewriting: Vec<_> = (sys.productions.iter().enumerate())
        .filter(|(_, p)| p.predecessor.contains(&symbol))
        .filter_map(|(i, _)| doc.compiled.spans.productions.get(i))
        .collect();
    if rewriting.is_empty() {
        text.push_str("\n\nNo production rewrites it.");
    } else {
        text.push_str("\n\nRewritten by:\n");
        for span in rewriting.iter().take(HOVER_PRODUCTIONS) {
            let line = file.line_index(span.start);
            let shown = crate::diagnostics::shortened(
                file.text.get((*span).clone()).unwrap_or("").trim(),
                120,
            );
            text.push_str(&format!("- line {}: `{shown}`\n", line + 1));
        }
        if rewriting.len() > HOVER_PRODUCTIONS {
            let more = rewriting.len() - HOVER_PRODUCTIONS;
            text.push_str(&format!("- … and {more} more\n"));
        }
    }
    text
}

/// What `op` does to the turtle, in words.
fn what_it_does(rotations: &[Rotation], op: TurtleOp) -> String {
    match op {
        TurtleOp::Forward { draw: true } => "moves one step forward, drawing a line".into(),
        TurtleOp::Forward { draw: false } => "moves one step forward without drawing".into(),
        TurtleOp::Rotate { axis, angle } => {
            let about = match axis {
                Axis::Heading => "rolls about its heading H",
                Axis::Left => "pitches about its left axis L",
                Axis::Up => "turns about its up axis U",
            };
            format!("{about} by {}", angle_text(angle))
        }
        TurtleOp::Frenet { rotation, negate } => {
            let r = rotations.get(rotation.0 as usize);
            let name = r.map_or("?", |r| r.name.as_str());
            let sign = if negate { "the inverse of " } else { "" };
            format!("applies {sign}the rotation `{name}` (torsion, then curvature)")
        }
        TurtleOp::TurnAround => "turns around (180° about U)".into(),
        TurtleOp::Push => "starts a branch: pushes the turtle's state".into(),
        TurtleOp::Pop => "ends a branch: pops the turtle's state".into(),
        TurtleOp::PolygonBegin => "starts a filled polygon".into(),
        TurtleOp::PolygonEnd => "closes and fills the polygon".into(),
        TurtleOp::DecrementWidth => "decrements the line width".into(),
        TurtleOp::NextColour => "takes the next colour".into(),
        TurtleOp::PreviousColour => "goes back to the previous colour".into(),
        TurtleOp::SwapTurns => "exchanges positive and negative turns".into(),
        TurtleOp::ScaleLength(x) => format!("multiplies the step length by {x}"),
        other => format!("{other:?}"),
    }
}

fn angle_text(angle: Angle) -> String {
    match angle {
        Angle::Delta(1.0) => "the angle increment δ".into(),
        Angle::Delta(f) => format!("{f} × the angle increment δ"),
        Angle::Radians(r) => format!("{}°", r.to_degrees()),
        Angle::Uniform { lo, hi } => format!(
            "a random angle in [{}°, {}°]",
            lo.to_degrees(),
            hi.to_degrees()
        ),
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
        if c.library.is_none() || d.kind != SymbolKind::MODULE {
            out.push((d.name.clone(), d.kind, range(file, &d.span)));
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
                SymbolKind::FUNCTION => CompletionItemKind::FUNCTION,
                SymbolKind::MODULE => CompletionItemKind::MODULE,
                SymbolKind::CONSTANT => CompletionItemKind::CONSTANT,
                _ => CompletionItemKind::VARIABLE,
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
