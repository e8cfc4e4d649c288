//! The names a file declares besides its symbols (STL rules, LinF
//! rotations and declared names, cpfg macros, Fractint entries, as its
//! front end finds them: [`Front::declarations`]) and the places each is
//! used. Each front end answers for its own notation; this module matches
//! on none.

use crate::front::declared::is_name_char;
use crate::front::{Declaration, DeclarationKind, Front};
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

impl From<Declaration> for Decl {
    fn from(d: Declaration) -> Self {
        Decl {
            name: d.name,
            span: d.span,
            kind: match d.kind {
                DeclarationKind::Function => SymbolKind::FUNCTION,
                DeclarationKind::Constant => SymbolKind::CONSTANT,
                DeclarationKind::Variable => SymbolKind::VARIABLE,
                DeclarationKind::Module => SymbolKind::MODULE,
            },
            about: d.about,
        }
    }
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

/// The names `text`, read by `front`, declares and uses.
pub fn find(front: &dyn Front, text: &str) -> Names {
    // Names in comments are neither declared nor used.
    let comments = front.comment_spans(text);
    let in_comment = |s: &Span| {
        let k = comments.partition_point(|c| c.end <= s.start);
        comments.get(k).is_some_and(|c| c.start <= s.start)
    };
    let decls: Vec<Decl> = (front.declarations(text).into_iter())
        .filter(|d| !in_comment(&d.span))
        .map(Decl::from)
        .collect();
    let uses = match front.declared_name_uses(text) {
        // Read from the syntax tree (split as lowering splits `FR1`).
        Some(found) => {
            let by_name = first_by_name(&decls);
            (found.into_iter())
                .filter_map(|(name, span)| Some((*by_name.get(name.as_str())?, span)))
                .collect()
        }
        None => uses(text, &decls, &in_comment),
    };
    Names { decls, uses }
}

/// Each name's first declaration, by index.
fn first_by_name(decls: &[Decl]) -> HashMap<&str, usize> {
    (decls.iter().enumerate().rev())
        .map(|(i, d)| (d.name.as_str(), i))
        .collect()
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
        let names = find(crate::front::by_name("cpfg").unwrap(), text);
        let found: Vec<_> = names.decls.iter().map(|d| d.name.as_str()).collect();
        assert_eq!(found, ["N", "LEAF"]);
        assert_eq!(names.decls[1].kind, SymbolKind::FUNCTION);
        assert!(names.decls[0].about.contains("`#define N 5`"));
        let n_at = text.rfind('N').unwrap();
        assert_eq!(names.at(n_at), Some(0));
        assert_eq!(names.places(0).count(), 2);
    }
}
