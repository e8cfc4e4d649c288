//! The rules an STL file declares, for the language server: each with its
//! body and the self-resemblance counts (`[I n X]`) written in it; and
//! where each is used, as lowering splits `FR1` into `F R1`.

use super::ast::{Elem, Item, Str};
use crate::diagnostics::Diagnostics;
use crate::front::declared::quoted;
use crate::front::{Declaration, DeclarationKind};
use crate::ir::Span;

/// The rules `text` declares.
pub fn rules(text: &str) -> Vec<Declaration> {
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
    let file = super::parser::parse(text, &mut Diagnostics::default());
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
            out.push(Declaration {
                name: name.clone(),
                span: name_span.clone(),
                kind: DeclarationKind::Function,
                about: format!(
                    "STL rule `{name}` = `{}`\n\n{resemblance}",
                    quoted(text, &body.span)
                ),
            });
        }
    }
    out
}

/// Each use of a rule in `text`, read from the syntax tree.
pub fn rule_uses(text: &str) -> Vec<(String, Span)> {
    let file = super::parser::parse(text, &mut Diagnostics::default());
    super::lower::rule_uses(&file)
}
