//! The pfg lexer (logos).
//!
//! pfg symbols are single characters, and almost every character can be a
//! symbol, so the lexer is fine-grained: letters and digits come in runs
//! (header keywords, numbers), the structural marks `<`, `>`, `:`, `*`, `-->`
//! are tokens of their own, and any other character is a one-character
//! [`Token::Char`]. The parser decides, by position, whether a `<` or a digit
//! run is structure or symbols. Spaces and `/* … */` comments are skipped;
//! line breaks are tokens, since pfg is line-oriented: one [`Token::Newline`]
//! for a run of them, blank lines and comments between included, so that
//! blank lines cost nothing (eight million of them took the parser 3.8 s
//! and 1.4 GB, one empty line each).

use crate::diagnostics::Diagnostics;
use crate::front::comments::unterminated_comment;
use crate::ir::Span;
use logos::Logos;
use std::fmt;

/// What went wrong while lexing.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum LexError {
    #[default]
    InvalidCharacter,
    UnterminatedComment,
}

#[derive(Logos, Clone, Copy, Debug, PartialEq, Eq)]
#[logos(error = LexError)]
#[logos(skip r"[ \t\f\x0b\u{a0}\u{1680}\u{2000}-\u{200b}\u{202f}\u{205f}\u{3000}\u{feff}]+")]
pub enum Token<'src> {
    /// LF, CR LF, or a lone CR (old Mac files).
    /// A run of line breaks; [`lex`] gives it the span of the first.
    #[regex(r"[\r\n]+")]
    Newline,
    #[token("/*", block_comment)]
    Comment,
    #[token("-->")]
    Arrow,
    /// `->`, `=>`, `==>`, `→`, `—>`: arrows people write for `-->`.
    #[token("->")]
    #[token("=>")]
    #[token("==>")]
    #[token("→")]
    #[token("—>")]
    #[token("--->")]
    BadArrow(&'src str),
    #[token("<")]
    Lt,
    #[token(">")]
    Gt,
    #[token(":")]
    Colon,
    #[token("*")]
    Star,
    #[regex(r"[A-Za-z_]+")]
    Word(&'src str),
    #[regex(r"[0-9]+(\.[0-9]+)?")]
    Number(&'src str),
    /// Any other printable character: a symbol.
    #[regex(r"[^\s\x00-\x1f\x7f-\u{9f}\u{200b}\u{feff}]", priority = 0)]
    Char(&'src str),
}

fn block_comment<'s>(lex: &mut logos::Lexer<'s, Token<'s>>) -> Result<(), LexError> {
    if crate::front::skip_block_comment(lex) {
        Ok(())
    } else {
        Err(LexError::UnterminatedComment)
    }
}

impl fmt::Display for Token<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Token::Newline => f.write_str("end of line"),
            Token::Comment => f.write_str("comment"),
            Token::Arrow => f.write_str("`-->`"),
            Token::BadArrow(s) | Token::Word(s) | Token::Number(s) | Token::Char(s) => {
                write!(f, "`{s}`")
            }
            Token::Lt => f.write_str("`<`"),
            Token::Gt => f.write_str("`>`"),
            Token::Colon => f.write_str("`:`"),
            Token::Star => f.write_str("`*`"),
        }
    }
}

/// Lexes `src` into tokens with their byte spans. Comments are dropped;
/// lexing errors become diagnostics and their characters are dropped, so
/// the parser sees only valid tokens.
pub fn lex<'src>(src: &'src str, diags: &mut Diagnostics) -> Vec<(Token<'src>, Span)> {
    let mut out: Vec<(Token<'src>, Span)> = Vec::new();
    let mut lexer = Token::lexer(src);
    while let Some(result) = lexer.next() {
        let span = lexer.span();
        match result {
            Ok(Token::Comment) => {}
            Ok(Token::Newline) if out.last().is_some_and(|t| t.0 == Token::Newline) => {}
            Ok(Token::Newline) => {
                let first = if src[span.clone()].starts_with("\r\n") {
                    2
                } else {
                    1
                };
                out.push((Token::Newline, span.start..span.start + first));
            }
            Ok(tok) => out.push((tok, span)),
            Err(LexError::UnterminatedComment) => diags.push(unterminated_comment(src, span.start)),
            Err(LexError::InvalidCharacter) => diags.push_invalid_character(src, span),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::codes;

    fn kinds(src: &str) -> Vec<Token<'_>> {
        let mut d = Diagnostics::default();
        let toks = lex(src, &mut d);
        assert!(d.is_empty(), "{d:?}");
        toks.into_iter().map(|(t, _)| t).collect()
    }

    #[test]
    fn arrow_wins_over_minus_and_greater() {
        assert_eq!(
            kinds("F-->F-F"),
            vec![
                Token::Word("F"),
                Token::Arrow,
                Token::Word("F"),
                Token::Char("-"),
                Token::Word("F")
            ]
        );
    }

    #[test]
    fn comments_and_carriage_returns_are_skipped() {
        assert_eq!(
            kinds("axiom: /* x\ny */ F1\r\n"),
            vec![
                Token::Word("axiom"),
                Token::Colon,
                Token::Word("F"),
                Token::Number("1"),
                Token::Newline
            ]
        );
    }

    #[test]
    fn every_line_ending_and_unicode_space_separates() {
        let newlines = |src: &str| kinds(src).iter().filter(|t| **t == Token::Newline).count();
        assert_eq!(newlines("a\nb\r\nc\rd"), 3);
        // Blank lines, spaces and comments between line breaks: one token,
        // spanning the first break.
        let mut d = Diagnostics::default();
        let toks = lex("a\r\n\n  \n/* c */\r\n\nb", &mut d);
        let spans: Vec<_> = toks.iter().map(|t| t.1.clone()).collect();
        assert_eq!(spans, [0..1, 1..3, 17..18]);
        assert_eq!(kinds("F\u{a0}F\u{3000}F").len(), 3);
    }

    #[test]
    fn hash_and_unicode_are_symbols() {
        assert_eq!(kinds("#é"), vec![Token::Char("#"), Token::Char("é")]);
    }

    #[test]
    fn a_run_of_invalid_characters_is_one_diagnostic() {
        let mut d = Diagnostics::default();
        let src = format!("F{}F\u{7}", "\u{7}".repeat(1000));
        let toks = lex(&src, &mut d);
        assert_eq!(toks.len(), 2);
        assert_eq!(d.len(), 2);
        assert_eq!(d.0[0].span, Some(1..1001));
        assert_eq!(d.0[1].span, Some(1002..1003));
    }

    #[test]
    fn bad_input_is_reported_not_fatal() {
        let mut d = Diagnostics::default();
        let toks = lex("F\u{7}F /* open", &mut d);
        assert_eq!(toks.len(), 2);
        let codes: Vec<_> = d.iter().map(|d| d.code).collect();
        assert_eq!(
            codes,
            vec![codes::INVALID_CHARACTER, codes::UNTERMINATED_COMMENT]
        );
        assert_eq!(d.0[0].span, Some(1..2));
    }
}
