//! `graftal fmt`: a `.gft` file rewritten in the layout the emitter
//! (`src/back/gft`) writes, its comments kept.
//!
//! The file is read with the `.gft` front end and written again by the
//! emitter, so the layout is the emitter's by construction and formatting
//! twice changes nothing. The IR has no place for comments: each is
//! attached to the source item it precedes (or trails, on that item's
//! line) and put back at the emitted item that comes from the same source
//! item, items being matched by what they are ([`Key`]: a setting by its
//! keyword, a symbol's operation by its name, a production by its index).
//! The result is read back and must be the same system, so `fmt` never
//! changes a model: where the reader does not yet read what the emitter
//! writes, the file is left alone.

use crate::diagnostics::Diagnostics;
use crate::driver::{self, Compiled};
use crate::front::gft::ast::{Block, GraphLine, Item};
use crate::front::gft::{lexer, parser};
use crate::front::Front;
use crate::ir::Span;
use crate::source::SourceFile;
use std::collections::HashMap;

/// What formatting a file came to.
pub enum Outcome {
    /// The file in the canonical layout (it may equal the input).
    Formatted(String),
    /// The file has errors (in `Formatting::compiled`): not formatted.
    HasErrors,
    /// The canonical layout would not read back as the same system (the
    /// reader lags behind the emitter): not formatted. Says why.
    NotSame(String),
}

/// The file as read, and the outcome.
pub struct Formatting {
    pub compiled: Compiled,
    pub outcome: Outcome,
}

/// The notation `graftal fmt` formats.
const FORMATTED: &str = "gft";

/// Whether `graftal fmt` formats files that `front` reads (`.gft` files).
pub fn formats(front: &dyn Front) -> bool {
    front.name() == FORMATTED
}

/// Formats a `.gft` file (whatever its name: it is read as `.gft`).
pub fn format(file: SourceFile) -> Formatting {
    let compiled = driver::compile_as(file, None, crate::front::by_name(FORMATTED));
    let outcome = outcome(&compiled);
    Formatting { compiled, outcome }
}

/// The outcome of formatting `compiled`, a `.gft` file read already (the
/// language server's open document).
pub fn outcome(compiled: &Compiled) -> Outcome {
    match &compiled.system {
        None => Outcome::HasErrors,
        Some(sys) => {
            let text = with_comments(&compiled.file.text, &crate::back::gft::write(sys, None));
            // Most often only the blanks change: then the file, which read
            // as `sys`, says that the layout reads back as it, at a small
            // part of the cost of reading it again.
            if same_tokens(&compiled.file.text, &text) {
                return Outcome::Formatted(text);
            }
            match reads_back_as(&text, sys) {
                Ok(()) => Outcome::Formatted(text),
                Err(why) => Outcome::NotSame(why),
            }
        }
    }
}

/// Whether `a` and `b` lex without errors to the same tokens, each
/// touching the one before it or not alike (comments, blanks and runs of
/// line breaks aside). The parser sees nothing else of a text (it asks
/// whether pieces of a word touch; a line break is none), so `b` then
/// reads as the same system as `a`.
fn same_tokens(a: &str, b: &str) -> bool {
    use lexer::Token::Newline;
    let mut diags = Diagnostics::default();
    let (ta, tb) = (lexer::lex(a, &mut diags), lexer::lex(b, &mut diags));
    let glued = |ts: &[(lexer::Token, Span)], i: usize| {
        i > 0 && ts[i - 1].1.end == ts[i].1.start && ts[i - 1].0 != Newline && ts[i].0 != Newline
    };
    diags.is_empty()
        && ta.len() == tb.len()
        && (0..ta.len()).all(|i| ta[i].0 == tb[i].0 && glued(&ta, i) == glued(&tb, i))
}

/// `Ok` when `text` reads without errors as the same system as `sys`.
fn reads_back_as(text: &str, sys: &crate::ir::System) -> Result<(), String> {
    let mut diags = Diagnostics::default();
    let again = crate::front::gft::read(text, &mut diags);
    if let Some(e) = diags.iter().find(|d| d.is_error()) {
        return Err(format!(
            "the layout the emitter writes does not read back ({}: {})",
            e.code, e.message
        ));
    }
    again
        .system
        .same_as(sys)
        .map_err(|d| format!("the layout the emitter writes reads back differently: {d}"))
}

/// What an item is, the same in the source and in the emitted file.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum Key {
    /// A keyword item: by its name, with its first argument for items
    /// that name something ([`NAMED`]) and else by how many items of that
    /// keyword come before it.
    Keyword(String, String),
    /// `NAME = OPERATION`.
    Define(String),
    /// A production by its index, at top level (`""`) or in a block.
    Production(String, usize),
    /// A line of a `graph` block: its kind, the symbol (or transform) it
    /// is of, and how many lines of that kind and symbol come before it.
    Graph(&'static str, String, usize),
}

/// Keywords whose first argument names what the item declares.
const NAMED: &[&str] = &[
    "rotation", "array", "function", "silent", "rule", "surface", "contour", "material",
];

/// The items of `text` with their keys and where they start, in order;
/// a block's productions follow their block item.
fn items(text: &str) -> Vec<(Key, usize)> {
    let file = parser::parse(text, &mut Diagnostics::default());
    let mut out = Vec::new();
    let mut seen: HashMap<&str, usize> = HashMap::new();
    let mut productions = 0;
    for item in &file.items {
        match item {
            Item::Keyword(k) => {
                let count = seen.entry(k.name.as_str()).or_default();
                let which = match k.args.first() {
                    Some(a) if NAMED.contains(&k.name.as_str()) => a.text().to_string(),
                    _ => count.to_string(),
                };
                *count += 1;
                out.push((Key::Keyword(k.name.clone(), which), k.line.start));
                let productions = match &k.block {
                    Some(Block::Productions(ps)) => Some(ps),
                    Some(Block::Lsystem { productions, .. }) => Some(productions),
                    _ => None,
                };
                if let Some(ps) = productions {
                    for (i, p) in ps.iter().enumerate() {
                        out.push((Key::Production(k.name.clone(), i), p.span.start));
                    }
                }
                if let Some(Block::Graph(lines)) = &k.block {
                    graph_items(lines, &mut out);
                }
            }
            Item::Define { name, span, .. } => out.push((Key::Define(name.clone()), span.start)),
            Item::Production(p) => {
                out.push((Key::Production(String::new(), productions), p.span.start));
                productions += 1;
            }
        }
    }
    out.sort_by_key(|(_, at)| *at);
    out
}

/// The keys of a `graph` block's lines.
fn graph_items(lines: &[GraphLine], out: &mut Vec<(Key, usize)>) {
    let mut seen: HashMap<(&'static str, String), usize> = HashMap::new();
    for line in lines {
        let (kind, name) = match line {
            GraphLine::Transform { name, .. } => ("transform", name.text.clone()),
            GraphLine::Axiom { .. } => ("axiom", String::new()),
            GraphLine::Symbol { names, .. } => ("symbol", names[0].text.clone()),
            GraphLine::Rule { symbol, .. } => ("rule", symbol.text.clone()),
            GraphLine::Geometry { symbol, .. } => ("geometry", symbol.text.clone()),
            GraphLine::Alternative { symbol, .. } => ("alternative", symbol.text.clone()),
            GraphLine::Unread { .. } => continue,
        };
        let count = seen.entry((kind, name.clone())).or_default();
        out.push((Key::Graph(kind, name, *count), line.span().start));
        *count += 1;
    }
}

/// Where a comment goes back: at the start of the file (one before every
/// item: the file's heading), before an emitted item, at the end of its
/// first line, or at the end of the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Place {
    Start,
    Before(usize),
    After(usize),
    End,
}

/// Whether code (not only comments and blanks) precedes comment `k` on
/// its line: then the comment trails that code.
fn trails_code(src: &str, comments: &[Span], k: usize) -> bool {
    let start = comments[k].start;
    let line_start = src[..start].rfind('\n').map_or(0, |i| i + 1);
    let mut at = line_start;
    // Comments are in order and apart: those on this line are a tail.
    let on_line = comments[..k].partition_point(|c| c.end <= line_start);
    for c in &comments[on_line..k] {
        if !src[at..c.start.max(at)].trim().is_empty() {
            return true;
        }
        at = at.max(c.end);
    }
    !src[at.min(start)..start].trim().is_empty()
}

/// Where each comment of `src` goes in the emitted file, whose items are
/// `emitted`: by the key of the source item it trails or precedes; when
/// the emitted file has no such item, before the next source item that
/// it has, else at the end.
fn places(src: &str, comments: &[Span], emitted: &[(Key, usize)]) -> Vec<Place> {
    let source = items(src);
    // Looked up by key, not searched for: a file of ten thousand commented
    // items took seconds.
    let mut emitted_at: HashMap<&Key, usize> = HashMap::new();
    for (e, (key, _)) in emitted.iter().enumerate() {
        emitted_at.entry(key).or_insert(e);
    }
    let found = |i: usize| emitted_at.get(&source[i].0).copied();
    // For each source item, the first emitted one at or after it.
    let mut next_found = vec![None; source.len() + 1];
    for i in (0..source.len()).rev() {
        next_found[i] = found(i).or(next_found[i + 1]);
    }
    let leading = |from: usize| next_found[from].map_or(Place::End, Place::Before);
    (0..comments.len())
        .map(|k| {
            let c = &comments[k];
            let next = source.partition_point(|(_, at)| *at < c.start);
            if next > 0 && trails_code(src, comments, k) {
                if let Some(e) = found(next - 1) {
                    return Place::After(e);
                }
            }
            if next == 0 {
                return Place::Start;
            }
            leading(next)
        })
        .collect()
}

/// The emitted text with `src`'s comments put back.
fn with_comments(src: &str, emitted: &str) -> String {
    let comments = lexer::comment_spans(src);
    if comments.is_empty() {
        return emitted.to_string();
    }
    let targets = items(emitted);
    // The comments of each place, in order, gathered once.
    let mut by_place: HashMap<Place, Vec<&str>> = HashMap::new();
    for (c, p) in comments.iter().zip(places(src, &comments, &targets)) {
        by_place.entry(p).or_default().push(&src[c.clone()]);
    }
    let text = |p: Place| {
        by_place
            .get(&p)
            .map_or(&[][..], Vec::as_slice)
            .iter()
            .copied()
    };
    let mut out = String::new();
    for c in text(Place::Start) {
        out.push_str(c);
        out.push('\n');
    }
    let mut copied = 0;
    for (e, (_, at)) in targets.iter().enumerate() {
        let line_start = emitted[..*at].rfind('\n').map_or(0, |i| i + 1);
        let line_end = emitted[*at..].find('\n').map_or(emitted.len(), |i| at + i);
        out.push_str(&emitted[copied..line_start]);
        let indent = &emitted[line_start..*at];
        for c in text(Place::Before(e)) {
            out.push_str(indent);
            out.push_str(c);
            out.push('\n');
        }
        out.push_str(&emitted[line_start..line_end]);
        for c in text(Place::After(e)) {
            out.push(' ');
            out.push_str(c);
        }
        copied = line_end;
    }
    out.push_str(&emitted[copied..]);
    for c in text(Place::End) {
        if !out.is_empty() && !out.ends_with('\n') {
            out.push('\n');
        }
        out.push_str(c);
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fmt(src: &str) -> String {
        match format(SourceFile::new("t.gft", src)).outcome {
            Outcome::Formatted(t) => t,
            Outcome::HasErrors => panic!("errors in\n{src}"),
            Outcome::NotSame(why) => panic!("{why}"),
        }
    }

    #[test]
    fn a_comment_stays_before_its_item() {
        let out = fmt("/* island */\nsteps 2\naxiom F-F-F-F\n/* the rule */\nF -> F+F\n");
        assert!(out.starts_with("/* island */\nsteps 2\n"), "{out}");
        assert!(out.contains("/* the rule */\nF -> F+F\n"), "{out}");
    }

    #[test]
    fn a_trailing_comment_stays_on_its_line() {
        let out = fmt("axiom F /* start */\nF -> FF /* doubles */\n");
        assert!(out.contains("axiom F /* start */\n"), "{out}");
        assert!(out.contains("F -> FF /* doubles */\n"), "{out}");
    }

    #[test]
    fn a_comment_of_an_item_the_emitter_drops_moves_to_the_next() {
        let out = fmt("axiom F\n/* pfg's turtle */\nturtle pfg\n/* end */");
        assert!(out.ends_with("/* end */\n"), "{out}");
        assert!(out.contains("/* pfg's turtle */\n"), "{out}");
    }

    #[test]
    fn texts_of_the_same_tokens_glued_alike_are_told_apart_from_others() {
        assert!(same_tokens("F  ->  F+F /* c */\n\n", "F -> F+F\n"));
        assert!(same_tokens("F -> F\r\nG -> G", "F -> F\nG -> G"));
        assert!(!same_tokens("F -> F+F\n", "F -> F + F\n"), "glued apart");
        assert!(!same_tokens("F -> FF\n", "F -> F F\n"), "another token");
        assert!(
            !same_tokens("F -> F\n", "F -> F\n$"),
            "a character that does not lex"
        );
    }

    #[test]
    fn a_comment_after_code_is_told_from_one_after_a_comment() {
        let src = "/* a */ /* b */ F\n";
        let cs = lexer::comment_spans(src);
        assert!(!trails_code(src, &cs, 0));
        assert!(!trails_code(src, &cs, 1));
        let src = "F /* a */\n";
        assert!(trails_code(src, &lexer::comment_spans(src), 0));
    }
}
