//! The pfg front end: the 1988 plant and fractal generator format of
//! Prusinkiewicz & Hanan (Appendix A), as `grammar/pfg.ebnf` states it
//! normatively.
//!
//! `lexer` (logos) -> `parser` (chumsky, recovering) -> `ast` -> `lower` (IR).

pub mod ast;
pub mod lexer;
pub mod lower;
pub mod parser;

pub use crate::ir::Lowered;
pub use lower::lower;
pub use parser::parse;

use crate::diagnostics::Diagnostics;
use crate::front::{block_comments, Confidence, Front, Read};
use crate::ir::{Span, System};
use crate::source::SourceFile;

/// The pfg notation in the registry.
pub struct Pfg;

impl Front for Pfg {
    fn keywords(&self) -> Vec<&'static str> {
        parser::HEADERS.to_vec()
    }
    fn name(&self) -> &'static str {
        "pfg"
    }
    fn title(&self) -> &'static str {
        "pfg"
    }
    fn extensions(&self) -> &'static [&'static str] {
        &["l"]
    }
    /// A `.l` file is pfg unless another dialect claims it; a line with a
    /// pfg header (`axiom:`, …) makes it likely (a Fractint reader would
    /// reject `axiom:` as an unknown keyword).
    fn detect(&self, text: &str) -> Confidence {
        let header = text
            .lines()
            .any(|line| pfg_header(line.split(';').next().unwrap_or("")));
        if header {
            Confidence::Likely
        } else {
            Confidence::Fallback
        }
    }
    fn read(&self, file: &SourceFile, _entry: Option<&str>, diags: &mut Diagnostics) -> Read {
        read(&file.text, diags).into()
    }
    fn comments(&self, src: &str) -> Vec<(Span, String)> {
        block_comments(src)
    }
    fn angle_divisions(&self, sys: &System) -> Option<u64> {
        (sys.settings.delta > 0.0).then(|| {
            (std::f64::consts::TAU / sys.settings.delta)
                .round()
                .min(i64::MAX as f64) as u64
        })
    }
}

/// A pfg header line: one of the Appendix A keywords and a colon.
fn pfg_header(line: &str) -> bool {
    let l = line.trim_start().to_ascii_lowercase();
    parser::HEADERS.iter().any(|h| {
        l.strip_prefix(h)
            .is_some_and(|r| r.trim_start().starts_with(':'))
    })
}

/// Parses and lowers pfg source text: the IR (usable only when `diags` got
/// no error) and its spans.
pub fn read(src: &str, diags: &mut Diagnostics) -> Lowered {
    let ast = parse(src, diags);
    lower(&ast, diags)
}

/// Reads a pfg text that must be free of errors (for tests and examples).
///
/// # Panics
/// When the text has errors; the message lists them.
pub fn read_ok(src: &str) -> crate::ir::System {
    crate::front::read_clean(|d| read(src, d))
}
