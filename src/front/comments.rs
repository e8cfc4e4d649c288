//! Comments as the front ends share them: skipping and stripping `/* … */`
//! comments, listing block and `#` line comments for the emitters that
//! carry them over (the IR has no place for them), and the diagnostic for a
//! block comment never closed.

use crate::diagnostics::{codes, Diagnostic};
use crate::ir::Span;

/// The diagnostic for a `/*` at `start` of `src` that is never closed: the
/// rest of the file is comment (pfg's and `.gft`'s lexers).
pub(crate) fn unterminated_comment(src: &str, start: usize) -> Diagnostic {
    Diagnostic::at(
        codes::UNTERMINATED_COMMENT,
        start..start + 2,
        "unterminated comment",
    )
    .with_label("this comment is never closed")
    .with_secondary(src.len()..src.len(), "the file ends here")
    .with_help("close the comment with `*/`")
}

/// Text with `/* … */` comments removed (an unclosed one runs to the end).
pub(crate) fn strip_block_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(k) = rest.find("/*") {
        out.push_str(&rest[..k]);
        match rest[k + 2..].find("*/") {
            Some(e) => rest = &rest[k + 2 + e + 2..],
            None => rest = "",
        }
    }
    out.push_str(rest);
    out
}

/// A logos callback's part for a `/*` just read: skips to past the `*/`
/// and says whether there was one (an unclosed comment takes the rest).
pub(crate) fn skip_block_comment<'s, T>(lex: &mut logos::Lexer<'s, T>) -> bool
where
    T: logos::Logos<'s, Source = str>,
{
    match lex.remainder().find("*/") {
        Some(end) => {
            lex.bump(end + 2);
            true
        }
        None => {
            lex.bump(lex.remainder().len());
            false
        }
    }
}

/// `/* … */` comments of `src` with their spans (an unclosed one runs to
/// the end).
pub(crate) fn block_comments(src: &str) -> Vec<(Span, String)> {
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(k) = src[i..].find("/*") {
        let start = i + k;
        let (end, body_end) = match src[start + 2..].find("*/") {
            Some(e) => (start + 2 + e + 2, start + 2 + e),
            None => (src.len(), src.len()),
        };
        out.push((start..end, src[start + 2..body_end].to_string()));
        i = end;
    }
    out
}

/// `#` comments to the end of the line of `src` with their spans, except
/// lines whose comment starts with one of `directives` (LinF's `#:`).
pub(crate) fn line_comments(src: &str, directive: Option<char>) -> Vec<(Span, String)> {
    let mut out = Vec::new();
    let mut offset = 0;
    for line in src.split_inclusive('\n') {
        if let Some(k) = line.find('#') {
            let body = line[k + 1..].trim_end_matches(['\n', '\r']);
            if !directive.is_some_and(|d| body.starts_with(d)) {
                out.push((offset + k..offset + line.len(), body.to_string()));
            }
        }
        offset += line.len();
    }
    out
}
