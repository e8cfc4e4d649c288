//! The LinF lexer (logos).
//!
//! LinF is free-form: line breaks are spaces, `#` starts a comment that runs
//! to the end of the line. Block keywords (`lines`, `blanks`, `angles`,
//! `axiom`, `rules`, `colors`) are reserved words; every other run of
//! letters, digits and `_` that starts with a letter or `_` is a name, which
//! lowering splits into declared names (`fgf` is `f g f` when `f` and `g`
//! are declared). Numbers are decimals (`2`, `0.5`, `.5`, `1e-3`).
//!
//! A sign `+` or `-` is one token whatever its role (a rotation in a string,
//! an operator in an expression). It records whether it *looks like a
//! prefix sign*: whitespace (or an opening mark) before it and none after,
//! as the `-` in `[0 -pi]`. The interval parser uses that to tell two
//! expressions written side by side from one subtraction.
//!
//! A comment that starts with `#:` is a *directive* that graftal reads and
//! cFLC, for which it is a comment, ignores (see `grammar/linf.ebnf`).

use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::ir::Span;
use logos::Logos;
use std::fmt;

/// The six blocks of a LinF program.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum BlockKind {
    Lines,
    Blanks,
    Angles,
    Axiom,
    Rules,
    Colors,
}

impl BlockKind {
    pub const ALL: [BlockKind; 6] = [
        BlockKind::Lines,
        BlockKind::Blanks,
        BlockKind::Angles,
        BlockKind::Axiom,
        BlockKind::Rules,
        BlockKind::Colors,
    ];

    pub fn keyword(self) -> &'static str {
        match self {
            BlockKind::Lines => "lines",
            BlockKind::Blanks => "blanks",
            BlockKind::Angles => "angles",
            BlockKind::Axiom => "axiom",
            BlockKind::Rules => "rules",
            BlockKind::Colors => "colors",
        }
    }
}

#[derive(Logos, Clone, Copy, Debug, PartialEq)]
#[logos(skip r"[ \t\r\n\f\x0b\u{a0}\u{1680}\u{2000}-\u{200b}\u{202f}\u{205f}\u{3000}\u{feff}]+")]
pub enum Token<'src> {
    /// `# …` to the end of the line (dropped by [`lex`], except directives).
    #[regex(r"#[^\r\n]*", allow_greedy = true)]
    Comment(&'src str),
    #[token("lines", |_| BlockKind::Lines)]
    #[token("blanks", |_| BlockKind::Blanks)]
    #[token("angles", |_| BlockKind::Angles)]
    #[token("axiom", |_| BlockKind::Axiom)]
    #[token("rules", |_| BlockKind::Rules)]
    #[token("colors", |_| BlockKind::Colors)]
    Keyword(BlockKind),
    #[regex(r"[A-Za-z_][A-Za-z0-9_]*")]
    Name(&'src str),
    #[regex(r"([0-9]+(\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?")]
    Number(&'src str),
    #[token("+", prefix_like)]
    Plus(bool),
    #[token("-", prefix_like)]
    Minus(bool),
    #[token("*")]
    Star,
    #[token("/")]
    Slash,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token("[")]
    LBracket,
    #[token("]")]
    RBracket,
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[token(",")]
    Comma,
    #[token("=")]
    Eq,
    #[token(":")]
    Colon,
    #[token("?")]
    Question,
    #[token("@")]
    At,
    #[token("!")]
    Bang,
    /// Not lexed: what the parser is given in place of a part nested past
    /// the depth limit ([`crate::front::depth::cut_too_deep`]).
    TooDeep,
}

/// Whether the sign just lexed looks like a prefix sign: preceded by
/// whitespace, an opening mark or the start of the text, and followed by
/// something other than whitespace.
fn prefix_like<'s>(lex: &mut logos::Lexer<'s, Token<'s>>) -> bool {
    let src = lex.source();
    let span = lex.span();
    let before = src[..span.start].chars().next_back();
    let after = src[span.end..].chars().next();
    let open_before = before.is_none_or(|c| c.is_whitespace() || matches!(c, '(' | '[' | ','));
    let tight_after = after.is_some_and(|c| !c.is_whitespace());
    open_before && tight_after
}

impl Token<'_> {
    /// Whether this token is `+` or `-`.
    pub fn is_sign(&self) -> bool {
        matches!(self, Token::Plus(_) | Token::Minus(_))
    }
}

impl fmt::Display for Token<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = match self {
            Token::Comment(_) => "comment",
            Token::Keyword(k) => return write!(f, "keyword `{}`", k.keyword()),
            Token::Name(s) => return write!(f, "name `{s}`"),
            Token::Number(s) => return write!(f, "number `{s}`"),
            Token::Plus(_) => "`+`",
            Token::Minus(_) => "`-`",
            Token::Star => "`*`",
            Token::Slash => "`/`",
            Token::LParen => "`(`",
            Token::RParen => "`)`",
            Token::LBracket => "`[`",
            Token::RBracket => "`]`",
            Token::LBrace => "`{`",
            Token::RBrace => "`}`",
            Token::Comma => "`,`",
            Token::Eq => "`=`",
            Token::Colon => "`:`",
            Token::Question => "`?`",
            Token::At => "`@`",
            Token::Bang => "`!`",
            Token::TooDeep => "a part nested too deeply",
        };
        f.write_str(s)
    }
}

/// A `#: key value` directive comment.
#[derive(Clone, Debug, PartialEq)]
pub struct Directive<'src> {
    /// The text after `#:`.
    pub text: &'src str,
    /// The span of that text.
    pub span: Span,
}

/// The tokens of a file (comments dropped), and its directives.
pub struct Lexed<'src> {
    pub tokens: Vec<(Token<'src>, Span)>,
    pub directives: Vec<Directive<'src>>,
}

/// Lexes `src`. Invalid characters become diagnostics (E0001, a run of
/// them reported once) and are dropped, so the parser sees valid tokens.
pub fn lex<'src>(src: &'src str, diags: &mut Diagnostics) -> Lexed<'src> {
    let mut tokens = Vec::new();
    let mut directives = Vec::new();
    let mut lexer = Token::lexer(src);
    while let Some(result) = lexer.next() {
        let span = lexer.span();
        match result {
            Ok(Token::Comment(text)) => {
                if let Some(rest) = text.strip_prefix("#:") {
                    directives.push(Directive {
                        text: rest,
                        span: span.start + 2..span.end,
                    });
                }
            }
            Ok(tok) => tokens.push((tok, span)),
            Err(()) if arrow_for_eq(src, &tokens, &span) => {
                // Read as `=`, so the rule is read and the next line too.
                let minus = tokens.pop().map_or(span.clone(), |(_, s)| s);
                diags.push(
                    Diagnostic::at(
                        codes::MALFORMED_ARROW,
                        minus.start..span.end,
                        "LinF writes `=`, not `->`",
                    )
                    .with_label("read as `=`")
                    .with_fix(
                        minus.start..span.end,
                        "=".into(),
                        "write the rule as `name = string`".into(),
                    ),
                );
                tokens.push((Token::Eq, minus.start..span.end));
            }
            Err(()) => diags.push_invalid_character(src, span),
        }
    }
    Lexed { tokens, directives }
}

/// Whether the invalid character at `span` is the `>` of `->` (a `-`
/// token just before it), the arrow of other notations.
fn arrow_for_eq(src: &str, tokens: &[(Token<'_>, Span)], span: &Span) -> bool {
    &src[span.clone()] == ">"
        && matches!(tokens.last(), Some((Token::Minus(_), s)) if s.end == span.start)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<Token<'_>> {
        let mut d = Diagnostics::default();
        let toks = lex(src, &mut d).tokens;
        assert!(d.is_empty(), "{d:?}");
        toks.into_iter().map(|(t, _)| t).collect()
    }

    #[test]
    fn keywords_names_and_numbers() {
        assert_eq!(
            kinds("lines f linesx\naxiom .5?j 2.@ 1e-3"),
            vec![
                Token::Keyword(BlockKind::Lines),
                Token::Name("f"),
                Token::Name("linesx"),
                Token::Keyword(BlockKind::Axiom),
                Token::Number(".5"),
                Token::Question,
                Token::Name("j"),
                Token::Number("2."),
                Token::At,
                Token::Number("1e-3"),
            ]
        );
    }

    #[test]
    fn signs_know_whether_they_look_like_prefixes() {
        assert_eq!(
            kinds("[0 -pi] a - b a-b -x"),
            vec![
                Token::LBracket,
                Token::Number("0"),
                Token::Minus(true),
                Token::Name("pi"),
                Token::RBracket,
                Token::Name("a"),
                Token::Minus(false),
                Token::Name("b"),
                Token::Name("a"),
                Token::Minus(false),
                Token::Name("b"),
                Token::Minus(true),
                Token::Name("x"),
            ]
        );
    }

    #[test]
    fn comments_are_dropped_and_directives_kept() {
        let mut d = Diagnostics::default();
        let src = "# a comment\n#: steps 4\naxiom f # more\n";
        let l = lex(src, &mut d);
        assert_eq!(l.tokens.len(), 2);
        assert_eq!(l.directives.len(), 1);
        assert_eq!(l.directives[0].text, " steps 4");
        assert_eq!(&src[l.directives[0].span.clone()], " steps 4");
    }

    #[test]
    fn invalid_characters_are_reported_once_per_run() {
        let mut d = Diagnostics::default();
        let l = lex("axiom f\u{7}\u{7}f $", &mut d);
        assert_eq!(l.tokens.len(), 3);
        assert_eq!(d.len(), 2);
        assert_eq!(d.0[0].span, Some(7..9));
    }
}
