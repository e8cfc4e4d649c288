//! The Smith lexer (logos): keys, `:`, values, comments, line breaks.
//!
//! A value is everything after the `:` up to the end of the line or a `#`
//! comment; the lowering reads it character by character, so that every
//! mistake in a rule string gets the span of its own character.

use crate::diagnostics::Diagnostics;
use crate::ir::Span;
use logos::Logos;
use std::fmt;

#[derive(Logos, Clone, Copy, Debug, PartialEq, Eq)]
#[logos(skip r"[ \t\f\u{a0}\u{feff}]+")]
pub enum Token<'src> {
    /// A run of line breaks.
    #[regex(r"[\r\n]+")]
    Newline,
    #[regex(r"#[^\r\n]*", allow_greedy = true)]
    Comment,
    #[token(":")]
    Colon,
    /// A key: letters, digits, `-` and `_`, starting with a letter.
    #[regex(r"[A-Za-z][A-Za-z0-9_-]*")]
    Key(&'src str),
    /// Anything else up to a space, `:`, `#` or line break: part of a value.
    #[regex(r"[^\sA-Za-z:#\x00-\x1f\x7f][^\s:#\x00-\x1f\x7f]*", priority = 0)]
    Text(&'src str),
}

impl fmt::Display for Token<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Token::Newline => f.write_str("end of line"),
            Token::Comment => f.write_str("comment"),
            Token::Colon => f.write_str("`:`"),
            Token::Key(s) | Token::Text(s) => write!(f, "`{s}`"),
        }
    }
}

/// Lexes `src` into tokens with their byte spans; comments are dropped,
/// invalid characters reported and dropped.
pub fn lex<'src>(src: &'src str, diags: &mut Diagnostics) -> Vec<(Token<'src>, Span)> {
    let mut out = Vec::new();
    let mut lexer = Token::lexer(src);
    while let Some(result) = lexer.next() {
        let span = lexer.span();
        match result {
            Ok(Token::Comment) => {}
            Ok(tok) => out.push((tok, span)),
            Err(()) => diags.push_invalid_character(src, span),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rule_line_is_key_colon_text() {
        let mut d = Diagnostics::default();
        let toks: Vec<_> = lex("rules: 0.1[1].1 # c\n", &mut d)
            .into_iter()
            .map(|t| t.0)
            .collect();
        assert_eq!(
            toks,
            [
                Token::Key("rules"),
                Token::Colon,
                Token::Text("0.1[1].1"),
                Token::Newline
            ]
        );
    }
}
