//! The cpfg dialect of `.l`: the L-system files of the Virtual Laboratory's
//! cpfg (Prusinkiewicz, Hanan, Mech and others; manual in
//! `../shared/reference/cpfg-manual.txt`).
//!
//! Reading a cpfg object: [`preprocess`] (the C preprocessor pass cpfg runs
//! over the `.l` file, with a map back to the original text) -> `lexer`
//! (logos, cpfg's two modes) -> `parser` (chumsky, one item per line,
//! recovering) -> `ast` -> `lower` (the IR, with its parametric part
//! [`crate::ir::parametric`]). The files beside the `.l` come in through
//! [`view`] (the `.v` view file: angle, widths, colours, surfaces,
//! functions), [`func`] (`.func`, `.fset`) and [`surface`] (`.s`).

pub mod ast;
pub mod func;
pub mod lexer;
pub mod lower;
pub mod parser;
pub mod preprocess;
pub mod surface;
pub mod view;

pub use lower::Lowered;

use crate::diagnostics::Diagnostics;

/// Parses and lowers a preprocessed cpfg text.
pub fn read(src: &str, diags: &mut Diagnostics) -> Lowered {
    let ast = parser::parse(src, diags);
    lower::lower(&ast, diags)
}

/// Reads a cpfg `.l` file.
pub fn read_file(file: &crate::source::SourceFile, diags: &mut Diagnostics) -> Lowered {
    read(&file.text, diags)
}

/// Reads a cpfg text that must be free of errors (for tests).
///
/// # Panics
/// When the text has errors; the message lists them.
pub fn read_ok(src: &str) -> crate::ir::System {
    let mut d = Diagnostics::default();
    let l = read(src, &mut d);
    assert!(!d.has_errors(), "{d:#?}");
    l.system
}
