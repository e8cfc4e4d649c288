//! The entries a Fractint library declares, for the language server: each
//! with its first lines.

use crate::diagnostics::Diagnostics;
use crate::front::Declaration;

/// The entries `text` declares.
pub fn entries(text: &str) -> Vec<Declaration> {
    let file = super::parser::parse(text, &mut Diagnostics::default());
    crate::front::library::declarations(text, file.entries, "Fractint entry")
}
