//! The names a LinF file declares, for the language server: its named
//! rotations (with their pair) and the names its `lines` and `blanks`
//! blocks declare.

use super::ast::BlockBody;
use crate::diagnostics::Diagnostics;
use crate::front::declared::quoted;
use crate::front::{Declaration, DeclarationKind};

/// The names `text` declares.
pub fn names(text: &str) -> Vec<Declaration> {
    let file = super::parser::parse(text, &mut Diagnostics::default());
    let mut out = Vec::new();
    for block in &file.blocks {
        match &block.body {
            BlockBody::Angles(rotations) => {
                for r in rotations {
                    let Some(name) = &r.name else { continue };
                    out.push(Declaration {
                        name: name.text.clone(),
                        span: name.span.clone(),
                        kind: DeclarationKind::Constant,
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
                    out.push(Declaration {
                        name: n.text.clone(),
                        span: n.span.clone(),
                        kind: DeclarationKind::Variable,
                        about: format!("`{}`: declared in `{block_name}`", n.text),
                    });
                }
            }
            _ => {}
        }
    }
    out
}
