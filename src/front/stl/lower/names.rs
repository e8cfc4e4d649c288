//! Rule names in runs: splitting `FR1` into the longest declared rule
//! names and drawing components, and where a file uses its rules.

use super::Ctx;
use crate::diagnostics::{codes, Diagnostic};
use crate::front::name_list;
use crate::front::names::LongestNames;
use crate::front::stl::ast::{Elem, Entries, Entry, File, Item, Str};
use crate::front::stl::growth::Comp;
use crate::front::stl::parser::RESERVED;
use crate::ir::Span;
use std::collections::HashMap;

/// A piece of a name run as lowering reads it: a drawing component, or a
/// rule written at a span with the branching entries that follow it (only
/// the run's last piece has them).
pub(super) enum Piece<'e> {
    C(Comp),
    Rule(usize, Span, Option<&'e Entries>),
}

/// A piece of an identifier run (`FR1`): a drawing component, a rule (by
/// its index in `by_name`), or neither.
enum RunPiece {
    Comp(Comp),
    Rule(usize),
    Unknown,
}

/// Splits identifier run `text` into the longest rule names of `by_name`
/// (`index` indexes them) and drawing components, each with its byte range
/// in `text`; an unknown piece (up to the next capital) ends it.
fn split_run(
    text: &str,
    by_name: &HashMap<String, usize>,
    index: &LongestNames,
) -> Vec<(RunPiece, std::ops::Range<usize>)> {
    let longest_at = index.longest_at(text);
    let mut out = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < text.len() {
        let n = longest_at[i];
        let longest = (n > 0)
            .then(|| by_name.get(&text[i..i + n]).map(|&r| (r, n)))
            .flatten();
        if let Some((r, n)) = longest {
            out.push((RunPiece::Rule(r), i..i + n));
            i += n;
            continue;
        }
        let next_digit = bytes
            .get(i + 1)
            .is_some_and(|b| b.is_ascii_digit() || *b == b'_');
        let comp = match bytes[i] {
            b'F' if !next_digit => Some(Comp::F),
            b'L' if !next_digit => Some(Comp::L),
            b'R' if !next_digit => Some(Comp::R),
            _ => None,
        };
        if let Some(c) = comp {
            out.push((RunPiece::Comp(c), i..i + 1));
            i += 1;
            continue;
        }
        let mut j = i + 1;
        while j < text.len() && !bytes[j].is_ascii_uppercase() {
            j += 1;
        }
        out.push((RunPiece::Unknown, i..j));
        break;
    }
    out
}

/// Where `file` uses its rules, by name and span, as lowering reads them:
/// the names in the rules' bodies and the seed, split from runs such as
/// `FR1` by the longest rule name, and the names of branching terms.
pub fn rule_uses(file: &File) -> Vec<(String, Span)> {
    type Uses = Vec<(String, Span)>;
    fn entries(es: &Entries, out: &mut Uses) {
        for e in &es.list {
            if let Entry::Term {
                name,
                name_span,
                entries: inner,
            } = e
            {
                out.push((name.clone(), name_span.clone()));
                inner.iter().for_each(|i| entries(i, out));
            }
        }
    }
    fn walk(s: &Str, split: &dyn Fn(&str, &Span, &mut Uses), out: &mut Uses) {
        for e in &s.elems {
            match e {
                Elem::Name {
                    text,
                    span,
                    entries: es,
                } => {
                    split(text, span, out);
                    es.iter().for_each(|es| entries(es, out));
                }
                Elem::Branch { body, .. } | Elem::Resemble { body, .. } => walk(body, split, out),
                Elem::Turn { .. } => {}
            }
        }
    }
    let mut by_name = HashMap::new();
    for item in &file.items {
        if let Item::Rule { name, .. } = item {
            if RESERVED.contains(&name.as_str()) || name == "DFS" {
                continue;
            }
            let next = by_name.len();
            by_name.entry(name.clone()).or_insert(next);
        }
    }
    let index = LongestNames::new(by_name.keys().map(String::as_str));
    let split = |text: &str, span: &Span, out: &mut Uses| {
        for (piece, at) in split_run(text, &by_name, &index) {
            if let RunPiece::Rule(_) = piece {
                out.push((
                    text[at.clone()].to_string(),
                    span.start + at.start..span.start + at.end,
                ));
            }
        }
    };
    let mut out = Vec::new();
    for item in &file.items {
        if let Item::Rule { body, .. } | Item::Seed { body, .. } = item {
            walk(body, &split, &mut out);
        }
    }
    out
}

impl Ctx<'_> {
    /// Walks the name run `text` written at `span` (the walk the rules'
    /// bodies and the seed share): each piece in order goes to `each`, the
    /// last with `entries`; a drawing component given entries is reported
    /// and still passed on. False if a piece is unknown (reported, and the
    /// walk stops there) or reported a problem, or `each` returned false.
    pub(super) fn each_piece<'e>(
        &mut self,
        text: &str,
        span: &Span,
        entries: Option<&'e Entries>,
        mut each: impl FnMut(&mut Self, Piece<'e>) -> bool,
    ) -> bool {
        let index = self
            .name_index
            .get_or_insert_with(|| LongestNames::new(self.by_name.keys().map(String::as_str)));
        let mut pieces = Vec::new();
        for (piece, at) in split_run(text, &self.by_name, index) {
            let in_file = span.start + at.start..span.start + at.end;
            match piece {
                RunPiece::Comp(c) => pieces.push(Piece::C(c)),
                RunPiece::Rule(r) => pieces.push(Piece::Rule(r, in_file, None)),
                RunPiece::Unknown => {
                    self.unknown_in_run(&text[at], in_file);
                    return false;
                }
            }
        }
        let last = pieces.len().saturating_sub(1);
        let mut ok = true;
        for (i, piece) in pieces.into_iter().enumerate() {
            let piece = match piece {
                Piece::C(c) if i == last && entries.is_some() => {
                    self.no_branches_component(span, c);
                    ok = false;
                    Piece::C(c)
                }
                Piece::Rule(r, at, _) if i == last => Piece::Rule(r, at, entries),
                piece => piece,
            };
            ok &= each(self, piece);
        }
        ok
    }

    /// Reports `bad`, a piece of a run that is no rule and no component.
    fn unknown_in_run(&mut self, bad: &str, at: Span) {
        self.report(codes::STL_UNKNOWN_RULE, |c| {
                let otherwise = if c.rules.is_empty() {
                    format!(
                        "define it as a rule, e.g. `{bad} = [F][+F]`; drawing components are F, L, R, +, -"
                    )
                } else {
                    format!(
                        "the rules are {}; drawing components are F, L, R, +, -",
                        name_list(c.rules.iter().map(|r| r.name.as_str()), true)
                    )
                };
                let d = Diagnostic::at(
                    codes::STL_UNKNOWN_RULE,
                    at.clone(),
                    format!("unknown rule `{bad}`"),
                )
                .with_label("not a rule or a drawing component");
                c.did_you_mean(d, bad, otherwise)
            });
    }

    /// The rule called `name` (an entry names exactly one rule).
    pub(super) fn rule_named(&mut self, name: &str, span: &Span) -> Option<usize> {
        if let Some(&r) = self.by_name.get(name) {
            return Some(r);
        }
        self.report(codes::STL_UNKNOWN_RULE, |c| {
            let otherwise = "an entry is a rule name, `~` (failed) or nothing".to_string();
            let d = Diagnostic::at(
                codes::STL_UNKNOWN_RULE,
                span.clone(),
                format!("unknown rule `{name}`"),
            )
            .with_label("no rule of this name");
            c.did_you_mean(d, name, otherwise)
        });
        None
    }
}
