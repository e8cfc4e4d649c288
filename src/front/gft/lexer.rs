//! The `.gft` lexer (logos).
//!
//! Tokens are coarse: a word (`F-F+F`) is a run of tokens whose texts the
//! lowering splits again by the longest declared name (docs/gft.md §2), so
//! the lexer need not know which names a file declares. Comments are
//! `/* … */`; line breaks are tokens, since `.gft` is line-oriented.

use crate::diagnostics::Diagnostics;
use crate::front::comments::unterminated_comment;
use crate::ir::Span;
use logos::Logos;
use std::fmt;

#[derive(Clone, Debug, Default, PartialEq)]
pub enum LexError {
    #[default]
    InvalidCharacter,
    UnterminatedComment,
}

#[derive(Logos, Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[logos(error = LexError)]
#[logos(skip r"[ \t\f\x0b\u{a0}\u{3000}\u{feff}]+")]
pub enum Token<'src> {
    #[regex(r"[\r\n]+")]
    Newline,
    #[token("/*", block_comment)]
    Comment,
    #[token("->")]
    Arrow,
    /// `` `any text` ``: a symbol with exactly that name.
    #[regex(r"`[^`\r\n]*`")]
    Quoted(&'src str),
    #[regex(r#""[^"\r\n]*""#)]
    Str(&'src str),
    #[regex(r"#[0-9a-fA-F]{6}")]
    Colour(&'src str),
    #[regex(r"[0-9]+(\.[0-9]*)?([eE][+-]?[0-9]+)?")]
    #[regex(r"\.[0-9]+([eE][+-]?[0-9]+)?")]
    Number(&'src str),
    #[regex(r"[A-Za-z_][A-Za-z0-9_]*")]
    Ident(&'src str),
    #[token("<=")]
    #[token(">=")]
    #[token("==")]
    #[token("!=")]
    #[token("&&")]
    #[token("||")]
    Op2(&'src str),
    /// Any other printable character.
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

impl<'src> Token<'src> {
    /// The token's text as written (a newline as `\n`).
    pub fn text(&self) -> &'src str {
        match self {
            Token::Newline => "\n",
            Token::Comment => "",
            Token::Arrow => "->",
            Token::Quoted(s)
            | Token::Str(s)
            | Token::Colour(s)
            | Token::Number(s)
            | Token::Ident(s)
            | Token::Op2(s)
            | Token::Char(s) => s,
        }
    }

    /// Whether the token is the one-character punctuation `c`.
    pub fn is(&self, c: &str) -> bool {
        matches!(self, Token::Char(s) if *s == c)
    }
}

impl fmt::Display for Token<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Token::Newline => f.write_str("end of line"),
            Token::Comment => f.write_str("comment"),
            t => write!(f, "`{}`", t.text()),
        }
    }
}

/// Lexes `src` into tokens with their byte spans. Comments are dropped and
/// runs of line breaks are one [`Token::Newline`]; lexing errors become
/// diagnostics and their characters are dropped.
pub fn lex<'src>(src: &'src str, diags: &mut Diagnostics) -> Vec<(Token<'src>, Span)> {
    let mut out: Vec<(Token<'src>, Span)> = Vec::new();
    let mut lexer = Token::lexer(src);
    while let Some(result) = lexer.next() {
        let span = lexer.span();
        match result {
            Ok(Token::Comment) => {}
            Ok(Token::Newline) if out.last().is_some_and(|t| t.0 == Token::Newline) => {}
            Ok(tok) => out.push((tok, span)),
            Err(LexError::UnterminatedComment) => diags.push(unterminated_comment(src, span.start)),
            Err(LexError::InvalidCharacter) => diags.push_invalid_character(src, span),
        }
    }
    out
}

/// The spans of `src`'s comments in order (an unterminated one runs to the
/// end): `graftal fmt` carries them across, since the IR has no place for
/// them.
pub fn comment_spans(src: &str) -> Vec<Span> {
    let mut lexer = Token::lexer(src);
    let mut out = Vec::new();
    while let Some(result) = lexer.next() {
        if matches!(
            result,
            Ok(Token::Comment) | Err(LexError::UnterminatedComment)
        ) {
            out.push(lexer.span());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::codes;

    fn texts(src: &str) -> Vec<&str> {
        let mut d = Diagnostics::default();
        lex(src, &mut d).iter().map(|t| t.0.text()).collect()
    }

    #[test]
    fn comments_vanish_and_arrows_are_one_token() {
        assert_eq!(
            texts("A(x)->F /* c\n */ `<`<=.5e1 #00ff00"),
            ["A", "(", "x", ")", "->", "F", "`<`", "<=", ".5e1", "#00ff00"]
        );
    }

    #[test]
    fn comment_spans_skip_quoted_text() {
        let src = "F `/*` /* a */ G\n/* b";
        let texts: Vec<&str> = comment_spans(src).into_iter().map(|s| &src[s]).collect();
        assert_eq!(texts, ["/* a */", "/* b"]);
    }

    #[test]
    fn an_open_comment_is_reported() {
        let mut d = Diagnostics::default();
        lex("F /* open", &mut d);
        assert_eq!(
            d.iter().next().map(|d| d.code),
            Some(codes::UNTERMINATED_COMMENT)
        );
    }
}
