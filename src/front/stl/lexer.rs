//! The STL lexer (logos).
//!
//! Identifiers are runs of letters, digits and `_` starting with a letter:
//! keywords (`ANGLE`, `SEED`, …), rule names (`R1`) and strings of drawing
//! components written together (`FLFRRFLF`, `FR1`) all lex as
//! [`Token::Ident`]; lowering splits a run into components and rule names
//! once every rule is known. `#` starts a comment to the end of the line;
//! line breaks are tokens, since settings and rules end at the end of a
//! line.

use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::ir::Span;
use logos::Logos;
use std::fmt;

#[derive(Logos, Clone, Copy, Debug, PartialEq, Eq)]
#[logos(skip r"[ \t\f\x0b\u{a0}\u{1680}\u{2000}-\u{200b}\u{202f}\u{205f}\u{3000}\u{feff}]+")]
#[logos(skip(r"#[^\r\n]*", allow_greedy = true))]
pub enum Token<'src> {
    /// LF, CR LF, or a lone CR.
    #[regex(r"\r\n|\n|\r")]
    Newline,
    #[regex(r"[A-Za-z][A-Za-z0-9_]*")]
    Ident(&'src str),
    #[regex(r"[0-9]+(\.[0-9]*)?|\.[0-9]+")]
    Number(&'src str),
    /// A Delphi colour literal `$00BBGGRR` (any run of hex digits).
    #[regex(r"\$[0-9A-Za-z]*")]
    Hex(&'src str),
    #[token("[")]
    Open,
    #[token("]")]
    Close,
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token(",")]
    Comma,
    #[token("=")]
    Eq,
    #[token("+")]
    Plus,
    #[token("-")]
    Minus,
    #[token("~")]
    Tilde,
}

impl fmt::Display for Token<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Token::Newline => f.write_str("end of line"),
            Token::Ident(s) | Token::Number(s) | Token::Hex(s) => write!(f, "`{s}`"),
            Token::Open => f.write_str("`[`"),
            Token::Close => f.write_str("`]`"),
            Token::LBrace => f.write_str("`{`"),
            Token::RBrace => f.write_str("`}`"),
            Token::LParen => f.write_str("`(`"),
            Token::RParen => f.write_str("`)`"),
            Token::Comma => f.write_str("`,`"),
            Token::Eq => f.write_str("`=`"),
            Token::Plus => f.write_str("`+`"),
            Token::Minus => f.write_str("`-`"),
            Token::Tilde => f.write_str("`~`"),
        }
    }
}

/// Lexes `src` into tokens with their byte spans. Invalid characters become
/// diagnostics (a run of them is one) and are dropped.
pub fn lex<'src>(src: &'src str, diags: &mut Diagnostics) -> Vec<(Token<'src>, Span)> {
    let mut out = Vec::new();
    let mut lexer = Token::lexer(src);
    let mut bad: Option<Span> = None;
    let flush = |bad: &mut Option<Span>, diags: &mut Diagnostics| {
        if let Some(span) = bad.take() {
            let text = &src[span.clone()];
            let ch = text.chars().next().unwrap_or('\0');
            let msg = if text.chars().count() > 1 {
                "invalid characters".to_string()
            } else {
                format!(
                    "invalid character `{}` (U+{:04X})",
                    ch.escape_debug(),
                    ch as u32
                )
            };
            diags.push(
                Diagnostic::at(codes::INVALID_CHARACTER, span, msg)
                    .with_label("not part of STL")
                    .with_help(
                        "STL uses F L R + - [ ] for drawing, names, numbers, `{ , ~ }` for branching and `#` for comments",
                    ),
            );
        }
    };
    while let Some(result) = lexer.next() {
        let span = lexer.span();
        match result {
            Ok(tok) => {
                flush(&mut bad, diags);
                out.push((tok, span));
            }
            Err(()) => match &mut bad {
                Some(b) if b.end == span.start => b.end = span.end,
                _ => {
                    flush(&mut bad, diags);
                    bad = Some(span);
                }
            },
        }
    }
    flush(&mut bad, diags);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<Token<'_>> {
        let mut d = Diagnostics::default();
        let toks = lex(src, &mut d);
        assert!(d.is_empty(), "{d:?}");
        toks.into_iter().map(|(t, _)| t).collect()
    }

    #[test]
    fn runs_of_letters_are_one_identifier_and_comments_are_skipped() {
        assert_eq!(
            kinds("R1 = FLF[+F] # a comment\n"),
            vec![
                Token::Ident("R1"),
                Token::Eq,
                Token::Ident("FLF"),
                Token::Open,
                Token::Plus,
                Token::Ident("F"),
                Token::Close,
                Token::Newline
            ]
        );
    }

    #[test]
    fn colours_numbers_and_branching_marks() {
        assert_eq!(
            kinds("($0000FF) 1.5 R{~,}"),
            vec![
                Token::LParen,
                Token::Hex("$0000FF"),
                Token::RParen,
                Token::Number("1.5"),
                Token::Ident("R"),
                Token::LBrace,
                Token::Tilde,
                Token::Comma,
                Token::RBrace
            ]
        );
    }

    #[test]
    fn a_run_of_invalid_characters_is_one_diagnostic() {
        let mut d = Diagnostics::default();
        let toks = lex("F\u{7}\u{7}@F", &mut d);
        assert_eq!(toks.len(), 2);
        assert_eq!(d.len(), 1);
        assert_eq!(d.0[0].span, Some(1..4));
    }
}
