//! The entries a Fractint library declares, for the language server: each
//! with its first lines.

use crate::diagnostics::Diagnostics;
use crate::front::{Declaration, DeclarationKind};

/// The entries `text` declares.
pub fn entries(text: &str) -> Vec<Declaration> {
    let file = super::parser::parse(text, &mut Diagnostics::default());
    (file.entries.into_iter())
        .filter(|e| !e.name.is_empty())
        .map(|e| {
            let lines = (e.span.end - e.span.start).min(300);
            let shown = text.get(e.span.start..e.span.start + lines).unwrap_or("");
            Declaration {
                about: format!("Fractint entry `{}`\n\n```\n{shown}\n```", e.name),
                name: e.name,
                span: e.name_span,
                kind: DeclarationKind::Module,
            }
        })
        .collect()
}
