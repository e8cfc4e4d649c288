//! The names a file declares besides its symbols (STL rules, LinF
//! rotations and declared names, cpfg macros, Fractint entries, as its
//! front end finds them: [`Front::declarations`]) and the places each is
//! used. Each front end answers for its own notation; this module matches
//! on none.

use crate::front::declared::is_name_char;
use crate::front::{Declaration, Front};
use crate::ir::Span;
use std::collections::HashMap;

/// The declarations of a file, and each place one of them is used (the
/// index of the declaration, the span of the use).
#[derive(Default)]
pub struct Names {
    /// What hovering one shows is its `about` (Markdown).
    pub decls: Vec<Declaration>,
    uses: Vec<(usize, Span)>,
}

impl Names {
    /// The declaration named at byte `at` (or just before it, where a
    /// cursor after a name stands), by its index, and where it is named
    /// there.
    pub(super) fn at(&self, at: usize) -> Option<(usize, &Span)> {
        let hit = |s: &Span| s.start <= at && at <= s.end;
        let declared = self.decls.iter().enumerate().map(|(i, d)| (i, &d.span));
        let used = self.uses.iter().map(|(i, s)| (*i, s));
        declared.chain(used).find(|(_, s)| hit(s))
    }

    /// The declaration of `i` and every use of it.
    pub(super) fn places(&self, i: usize) -> impl Iterator<Item = &Span> {
        let decl = self.decls.get(i).map(|d| &d.span);
        decl.into_iter()
            .chain(self.uses.iter().filter(move |u| u.0 == i).map(|u| &u.1))
    }
}

/// The names `text`, read by `front`, declares and uses.
pub(super) fn find(front: &dyn Front, text: &str) -> Names {
    // Names in comments are neither declared nor used.
    let comments = front.comment_spans(text);
    let in_comment = |s: &Span| {
        let k = comments.partition_point(|c| c.end <= s.start);
        comments.get(k).is_some_and(|c| c.start <= s.start)
    };
    let decls: Vec<Declaration> = (front.declarations(text).into_iter())
        .filter(|d| !in_comment(&d.span))
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
fn first_by_name(decls: &[Declaration]) -> HashMap<&str, usize> {
    (decls.iter().enumerate().rev())
        .map(|(i, d)| (d.name.as_str(), i))
        .collect()
}

/// Every word of `text` (a run of letters, digits and `_`) outside
/// comments that is a declared name, other than the declarations
/// themselves.
fn uses(
    text: &str,
    decls: &[Declaration],
    in_comment: &dyn Fn(&Span) -> bool,
) -> Vec<(usize, Span)> {
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
    use crate::front::DeclarationKind;

    #[test]
    fn cpfg_macros_and_their_uses() {
        let text = "#define N 5\n# define LEAF(a) [+F(a)]\n#definex 1\nA --> LEAF(N)\n";
        let names = find(crate::front::by_name("cpfg").unwrap(), text);
        let found: Vec<_> = names.decls.iter().map(|d| d.name.as_str()).collect();
        assert_eq!(found, ["N", "LEAF"]);
        assert_eq!(names.decls[1].kind, DeclarationKind::Function);
        assert!(names.decls[0].about.contains("`#define N 5`"));
        let n_at = text.rfind('N').unwrap();
        assert_eq!(names.at(n_at), Some((0, &(n_at..n_at + 1))));
        assert_eq!(names.places(0).count(), 2);
    }
}
