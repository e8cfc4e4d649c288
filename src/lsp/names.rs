//! The names a file declares besides its symbols: STL rules, LinF
//! rotations and declared names, cpfg macros (object-like and
//! function-like), Fractint entries; and the places each is used. Found
//! from the front end's syntax tree (a parse, no lowering or derivation)
//! or, for cpfg's `#define`s, from the lines that declare them.

use crate::diagnostics::Diagnostics;
use crate::front;
use crate::ir::Span;
use lsp_types::SymbolKind;
use std::collections::HashMap;

/// A declared name: where it is written in its declaration, what kind of
/// thing it is, and what hovering it shows (Markdown).
pub struct Decl {
    pub name: String,
    pub span: Span,
    pub kind: SymbolKind,
    pub about: String,
}

/// The declarations of a file, and each place one of them is used (the
/// index of the declaration, the span of the use).
#[derive(Default)]
pub struct Names {
    pub decls: Vec<Decl>,
    pub uses: Vec<(usize, Span)>,
}

impl Names {
    /// The declaration named at byte `at` (or just before it, where a
    /// cursor after a name stands), by its index.
    pub fn at(&self, at: usize) -> Option<usize> {
        let hit = |s: &Span| s.start <= at && at <= s.end;
        (self.decls.iter().position(|d| hit(&d.span)))
            .or_else(|| self.uses.iter().find(|(_, s)| hit(s)).map(|u| u.0))
    }

    /// The declaration of `i` and every use of it.
    pub fn places(&self, i: usize) -> impl Iterator<Item = &Span> {
        let decl = self.decls.get(i).map(|d| &d.span);
        decl.into_iter()
            .chain(self.uses.iter().filter(move |u| u.0 == i).map(|u| &u.1))
    }
}

/// The names `text`, read as `notation`, declares and uses.
pub fn find(notation: &str, text: &str) -> Names {
    let decls = match notation {
        "stl" => stl_rules(text),
        "linf" => linf_names(text),
        "cpfg" => cpfg_macros(text),
        "fractint" => fractint_entries(text),
        _ => Vec::new(),
    };
    // Names in comments are neither declared nor used.
    let comments = comment_spans(notation, text);
    let in_comment = |s: &Span| {
        let k = comments.partition_point(|c| c.end <= s.start);
        comments.get(k).is_some_and(|c| c.start <= s.start)
    };
    let decls: Vec<Decl> = decls.into_iter().filter(|d| !in_comment(&d.span)).collect();
    let uses = match notation {
        // Read from the syntax tree, split as lowering splits `FR1`.
        "stl" => {
            let file = front::stl::parser::parse(text, &mut Diagnostics::default());
            let by_name = first_by_name(&decls);
            (front::stl::lower::rule_uses(&file).into_iter())
                .filter_map(|(name, span)| Some((*by_name.get(name.as_str())?, span)))
                .collect()
        }
        _ => uses(text, &decls, &in_comment),
    };
    Names { decls, uses }
}

/// The spans of `text`'s comments, in order, as `notation`'s lexer finds
/// them.
pub fn comment_spans(notation: &str, text: &str) -> Vec<Span> {
    match notation {
        "cpfg" => front::cpfg::lexer::comment_spans(text),
        "fractint" => front::fractint::lexer::comment_spans(text),
        _ => (front::by_name(notation).into_iter())
            .flat_map(|f| f.comments(text))
            .map(|(span, _)| span)
            .collect(),
    }
}

/// Each name's first declaration, by index.
fn first_by_name(decls: &[Decl]) -> HashMap<&str, usize> {
    (decls.iter().enumerate().rev())
        .map(|(i, d)| (d.name.as_str(), i))
        .collect()
}

/// `text[span]`, cut to a line's worth for a hover.
fn quoted(text: &str, span: &Span) -> String {
    crate::diagnostics::shortened(text.get(span.clone()).unwrap_or("").trim(), 200).into_owned()
}

/// STL's rules: each with its body and the self-resemblance counts
/// (`[I n X]`) written in it.
fn stl_rules(text: &str) -> Vec<Decl> {
    use front::stl::ast::{Elem, Item, Str};
    fn counts(s: &Str, out: &mut Vec<f64>) {
        for e in &s.elems {
            match e {
                Elem::Resemble { count, body, .. } => {
                    out.push(count.value);
                    counts(body, out);
                }
                Elem::Branch { body, .. } => counts(body, out),
                _ => {}
            }
        }
    }
    let file = front::stl::parser::parse(text, &mut Diagnostics::default());
    let mut out = Vec::new();
    for item in &file.items {
        if let Item::Rule {
            name,
            name_span,
            body,
            ..
        } = item
        {
            let mut found = Vec::new();
            counts(body, &mut found);
            let resemblance = match found.as_slice() {
                [] => "no self-resemblance (`[I n …]`)".to_string(),
                ns => {
                    let ns: Vec<String> = ns.iter().map(|n| n.to_string()).collect();
                    format!("self-resemblance count {}", ns.join(", "))
                }
            };
            out.push(Decl {
                name: name.clone(),
                span: name_span.clone(),
                kind: SymbolKind::FUNCTION,
                about: format!(
                    "STL rule `{name}` = `{}`\n\n{resemblance}",
                    quoted(text, &body.span)
                ),
            });
        }
    }
    out
}

/// LinF's named rotations (with their pair) and the names its `lines` and
/// `blanks` blocks declare.
fn linf_names(text: &str) -> Vec<Decl> {
    use front::linf::ast::BlockBody;
    let file = front::linf::parser::parse(text, &mut Diagnostics::default());
    let mut out = Vec::new();
    for block in &file.blocks {
        match &block.body {
            BlockBody::Angles(rotations) => {
                for r in rotations {
                    let Some(name) = &r.name else { continue };
                    out.push(Decl {
                        name: name.text.clone(),
                        span: name.span.clone(),
                        kind: SymbolKind::CONSTANT,
                        about: format!(
                            "LinF rotation `{}` = `{}` (torsion, curvature)",
                            name.text,
                            quoted(text, &r.span)
                        ),
                    });
                }
            }
            BlockBody::Names(names) => {
                let block_name = text.get(block.keyword.clone()).unwrap_or("lines");
                for n in names {
                    out.push(Decl {
                        name: n.text.clone(),
                        span: n.span.clone(),
                        kind: SymbolKind::VARIABLE,
                        about: format!("`{}`: declared in `{block_name}`", n.text),
                    });
                }
            }
            _ => {}
        }
    }
    out
}

/// cpfg's `#define NAME body` and `#define NAME(args) body` lines: macros
/// and the functions written as macros, with their expansion.
fn cpfg_macros(text: &str) -> Vec<Decl> {
    let mut out = Vec::new();
    let mut at = 0;
    for line in text.split_inclusive('\n') {
        let start = at;
        at += line.len();
        let trimmed = line.trim_start();
        let Some(rest) = trimmed.strip_prefix('#') else {
            continue;
        };
        let Some(rest) = rest.trim_start().strip_prefix("define") else {
            continue;
        };
        let name_from = line.len() - rest.trim_start().len();
        let name_len = rest.trim_start().find(|c: char| !is_name_char(c));
        let name_len = name_len.unwrap_or(rest.trim_start().len());
        if name_len == 0 || name_from == line.len() - rest.len() {
            continue; // no name, or `#defineX`
        }
        let span = start + name_from..start + name_from + name_len;
        let name = text[span.clone()].to_string();
        let after = &line[name_from + name_len..];
        let (kind, what) = if after.starts_with('(') {
            (SymbolKind::FUNCTION, "function-like macro")
        } else {
            (SymbolKind::CONSTANT, "macro")
        };
        let definition = quoted(line, &(name_from..line.len()));
        out.push(Decl {
            about: format!("cpfg {what} `{name}`: expands as `#define {definition}`"),
            name,
            span,
            kind,
        });
    }
    out
}

/// A Fractint library's entries, each with its first lines.
fn fractint_entries(text: &str) -> Vec<Decl> {
    let file = front::fractint::parser::parse(text, &mut Diagnostics::default());
    (file.entries.into_iter())
        .filter(|e| !e.name.is_empty())
        .map(|e| {
            let lines = (e.span.end - e.span.start).min(300);
            let shown = text.get(e.span.start..e.span.start + lines).unwrap_or("");
            Decl {
                about: format!("Fractint entry `{}`\n\n```\n{shown}\n```", e.name),
                name: e.name,
                span: e.name_span,
                kind: SymbolKind::MODULE,
            }
        })
        .collect()
}

fn is_name_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// Every word of `text` (a run of letters, digits and `_`) outside
/// comments that is a declared name, other than the declarations
/// themselves.
fn uses(text: &str, decls: &[Decl], in_comment: &dyn Fn(&Span) -> bool) -> Vec<(usize, Span)> {
    let by_name = first_by_name(decls);
    if by_name.is_empty() {
        return Vec::new();
    }
    let mut out = Vec::new();
    let mut word_start = None;
    for (i, c) in text.char_indices().chain([(text.len(), ' ')]) {
        match (is_name_char(c), word_start) {
            (true, None) => word_start = Some(i),
            (false, Some(s)) => {
                word_start = None;
                if let Some(&d) = by_name.get(&text[s..i]) {
                    if decls[d].span.start != s && !in_comment(&(s..i)) {
                        out.push((d, s..i));
                    }
                }
            }
            _ => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpfg_macros_and_their_uses() {
        let text = "#define N 5\n# define LEAF(a) [+F(a)]\n#definex 1\nA --> LEAF(N)\n";
        let names = find("cpfg", text);
        let found: Vec<_> = names.decls.iter().map(|d| d.name.as_str()).collect();
        assert_eq!(found, ["N", "LEAF"]);
        assert_eq!(names.decls[1].kind, SymbolKind::FUNCTION);
        assert!(names.decls[0].about.contains("`#define N 5`"));
        let n_at = text.rfind('N').unwrap();
        assert_eq!(names.at(n_at), Some(0));
        assert_eq!(names.places(0).count(), 2);
    }
}
