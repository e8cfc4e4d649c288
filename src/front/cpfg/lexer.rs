//! The cpfg lexer (logos, two modes), after cpfg's own `lsys_input.l`.
//!
//! cpfg reads a file in two modes. In *symbol* mode (module names, contexts,
//! successors) every character other than `< > : *` and blanks is a module
//! symbol of its own: `FA(1)` is `F` then `A(1)`. A `(` after a symbol, a
//! `:`, and the keywords that take a value switch to *expression* mode, where
//! names, numbers, strings and C operators are read; the `)` closing the
//! parameter list, `-->` and the end of a line switch back.
//!
//! Lines: a line break ends an item (a production, a header line) unless the
//! next line starts with a tab (cpfg's continuation rule) or it falls inside
//! the braces of a statement block. The turtle commands written with a
//! prefix (`@O`, `@Gs`, `?P`, `~l`) are joined into one symbol here.
//!
//! Keywords are recognised in both modes, spelt as cpfg's lexer spells
//! them: the first letter of each word in either case, the rest in lower
//! case, the colon right after (`Lsystem:`, `axiom:`, `Endlsystem`). So
//! `AXIOM :` is a run of module symbols, as in cpfg.

use crate::diagnostics::Diagnostics;
use crate::ir::Span;
use logos::Logos;
use std::fmt;

/// The keywords of a cpfg L-system file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Keyword {
    Lsystem,
    Seed,
    DerivationLength,
    MaximumDepth,
    Consider,
    Ignore,
    Axiom,
    Define,
    Ring,
    Start,
    End,
    StartEach,
    EndEach,
    Homomorphism,
    Decomposition,
    NoWarnings,
    Warnings,
    EndLsystem,
}

impl Keyword {
    /// Every keyword, in the order a file usually writes them.
    pub const ALL: [Keyword; 18] = [
        Keyword::Lsystem,
        Keyword::Seed,
        Keyword::DerivationLength,
        Keyword::MaximumDepth,
        Keyword::Consider,
        Keyword::Ignore,
        Keyword::Axiom,
        Keyword::Define,
        Keyword::Ring,
        Keyword::Start,
        Keyword::End,
        Keyword::StartEach,
        Keyword::EndEach,
        Keyword::Homomorphism,
        Keyword::Decomposition,
        Keyword::NoWarnings,
        Keyword::Warnings,
        Keyword::EndLsystem,
    ];

    pub fn text(self) -> &'static str {
        match self {
            Keyword::Lsystem => "lsystem:",
            Keyword::Seed => "seed:",
            Keyword::DerivationLength => "derivation length:",
            Keyword::MaximumDepth => "maximum depth:",
            Keyword::Consider => "consider:",
            Keyword::Ignore => "ignore:",
            Keyword::Axiom => "axiom:",
            Keyword::Define => "define:",
            Keyword::Ring => "ring lsystem",
            Keyword::Start => "start:",
            Keyword::End => "end:",
            Keyword::StartEach => "starteach:",
            Keyword::EndEach => "endeach:",
            Keyword::Homomorphism => "homomorphism",
            Keyword::Decomposition => "decomposition",
            Keyword::NoWarnings => "no warnings",
            Keyword::Warnings => "warnings",
            Keyword::EndLsystem => "endlsystem",
        }
    }

    /// Whether expression mode follows the keyword.
    fn takes_expression(self) -> bool {
        matches!(
            self,
            Keyword::Seed
                | Keyword::DerivationLength
                | Keyword::MaximumDepth
                | Keyword::Define
                | Keyword::Start
                | Keyword::End
                | Keyword::StartEach
                | Keyword::EndEach
        )
    }
}

/// The tokens the parser sees.
#[derive(Clone, Debug, PartialEq)]
pub enum Token {
    Keyword(Keyword),
    /// The end of an item.
    Eol,
    /// A module symbol (one character, or a prefixed turtle command).
    Symbol(String),
    /// `*`: an empty successor, context or condition.
    Null,
    Arrow,
    /// `-o>`, cpfg's object production (not supported).
    ObjectArrow,
    /// `<` in symbol mode: a left-context separator.
    LSep,
    /// `>` in symbol mode: a right-context separator.
    RSep,
    Colon,
    LParen,
    RParen,
    LBrace,
    RBrace,
    LBracket,
    RBracket,
    Comma,
    Semi,
    Question,
    Assign,
    Amp,
    Not,
    Or,
    And,
    EqEq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    Plus,
    Minus,
    Star,
    Slash,
    Percent,
    Caret,
    Name(String),
    Number(f64),
    Str(String),
    /// Not lexed: what the parser is given in place of a part nested past
    /// the depth limit ([`crate::front::depth::cut_too_deep`]).
    TooDeep,
}

impl fmt::Display for Token {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = match self {
            Token::Keyword(k) => return write!(f, "`{}`", k.text()),
            Token::Eol => "end of line",
            Token::Symbol(s) => return write!(f, "module `{s}`"),
            Token::Name(s) => return write!(f, "name `{s}`"),
            Token::Number(v) => return write!(f, "number `{v}`"),
            Token::Str(_) => "string",
            Token::Null => "`*`",
            Token::Arrow => "`-->`",
            Token::ObjectArrow => "`-o>`",
            Token::LSep | Token::Lt => "`<`",
            Token::RSep | Token::Gt => "`>`",
            Token::Colon => "`:`",
            Token::LParen => "`(`",
            Token::RParen => "`)`",
            Token::LBrace => "`{`",
            Token::RBrace => "`}`",
            Token::LBracket => "`[`",
            Token::RBracket => "`]`",
            Token::Comma => "`,`",
            Token::Semi => "`;`",
            Token::Question => "`?`",
            Token::Assign => "`=`",
            Token::Amp => "`&`",
            Token::Not => "`!`",
            Token::Or => "`||`",
            Token::And => "`&&`",
            Token::EqEq => "`==`",
            Token::Ne => "`!=`",
            Token::Le => "`<=`",
            Token::Ge => "`>=`",
            Token::Plus => "`+`",
            Token::Minus => "`-`",
            Token::Star => "`*`",
            Token::Slash => "`/`",
            Token::Percent => "`%`",
            Token::Caret => "`^`",
            Token::TooDeep => "a part nested too deeply",
        };
        f.write_str(s)
    }
}

/// cpfg's comments, as the modes' tokens skip them; an unclosed `/*`
/// runs to the end.
#[derive(Logos, Clone, Copy, Debug, PartialEq)]
enum CommentTok {
    #[regex(r"/\*([^*]|\*+[^*/])*\*+/")]
    #[regex(r"//[^\n]*", allow_greedy = true)]
    Closed,
    #[token("/*")]
    Open,
}

/// The spans of `src`'s comments.
pub fn comment_spans(src: &str) -> Vec<Span> {
    let mut out = Vec::new();
    for (tok, span) in CommentTok::lexer(src).spanned() {
        match tok {
            Ok(CommentTok::Closed) => out.push(span),
            Ok(CommentTok::Open) => {
                out.push(span.start..src.len());
                break;
            }
            Err(()) => {}
        }
    }
    out
}

/// A token enum for one mode: the tokens shared by both modes (blanks, line
/// breaks, comments, keywords), then the mode's own.
macro_rules! mode_tokens {
    ($name:ident { $($own:tt)* }) => {
        #[derive(Logos, Clone, Debug, PartialEq)]
        enum $name {
        #[regex(r"[ \t\r\f]+", logos::skip)]
        #[regex(r"/\*([^*]|\*+[^*/])*\*+/", logos::skip)]
        #[regex(r"//[^\n]*", logos::skip, allow_greedy = true)]
        _Skip,
        /// A comment with no end.
        #[token("/*")]
        OpenComment,
        /// A line break followed by a tab: the item goes on.
        #[regex(r"\n\t")]
        Continuation,
        #[token("\n")]
        Newline,
        #[regex(r"[Ll]system:", |_| Keyword::Lsystem)]
        #[regex(r"[Ss]eed:", |_| Keyword::Seed)]
        #[regex(r"[Dd]erivation ?[Ll]ength:", |_| Keyword::DerivationLength)]
        #[regex(r"[Mm]aximum [Dd]epth:", |_| Keyword::MaximumDepth)]
        #[regex(r"[Cc]onsider:", |_| Keyword::Consider)]
        #[regex(r"[Ii]gnore:", |_| Keyword::Ignore)]
        #[regex(r"[Aa]xiom:", |_| Keyword::Axiom)]
        #[regex(r"[Dd]efine:", |_| Keyword::Define)]
        #[regex(r"[Rr]ing [Ll]system", |_| Keyword::Ring)]
        #[regex(r"[Ss]tart:", |_| Keyword::Start)]
        #[regex(r"[Ee]nd:", |_| Keyword::End)]
        #[regex(r"[Ss]tart ?[Ee]ach:", |_| Keyword::StartEach)]
        #[regex(r"[Ee]nd ?[Ee]ach:", |_| Keyword::EndEach)]
        #[regex(r"[Hh]omomorphism:?", |_| Keyword::Homomorphism)]
        #[regex(r"[Dd]ecomposition:?", |_| Keyword::Decomposition)]
        #[token("no warnings", |_| Keyword::NoWarnings)]
        #[token("warnings", |_| Keyword::Warnings)]
        #[regex(r"[Ee]nd[Ll]system", |_| Keyword::EndLsystem)]
        Keyword(Keyword),
        $($own)*
        }
    };
}

mode_tokens!(SymTok {
    #[token("*")]
    Null,
    #[token(":")]
    Colon,
    #[token("-->")]
    Arrow,
    #[token("-o>")]
    ObjectArrow,
    #[token("<")]
    LSep,
    #[token(">")]
    RSep,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[regex(r"[^<>:*() \t\r\f\n]")]
    Symbol,
});

mode_tokens!(ExprTok {
    #[token("-->")]
    Arrow,
    #[token("-o>")]
    ObjectArrow,
    #[token("=")]
    Assign,
    #[token("&")]
    Amp,
    #[token("+")]
    Plus,
    #[token("-")]
    Minus,
    #[token("*")]
    Star,
    #[token("/")]
    Slash,
    #[token("%")]
    Percent,
    #[token("^")]
    Caret,
    #[token(";")]
    Semi,
    #[token(",")]
    Comma,
    #[token("?")]
    Question,
    #[token(":")]
    Colon,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token("[")]
    LBracket,
    #[token("]")]
    RBracket,
    #[token("<")]
    Lt,
    #[token(">")]
    Gt,
    #[token("<>")]
    #[token("!=")]
    Ne,
    #[token("==")]
    EqEq,
    #[token("<=")]
    Le,
    #[token(">=")]
    Ge,
    #[token("!")]
    Not,
    #[token("&&")]
    And,
    #[token("||")]
    Or,
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[regex(r"[A-Za-z_][A-Za-z0-9_]*")]
    Name,
    #[regex(r"([0-9]+(\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?")]
    Number,
    #[regex(r#""[^"\n]*""#)]
    Str,
});

/// Two-letter turtle commands after `@` (cpfg reads `@Gs` as `@`, `G`, `s`
/// and looks ahead when drawing; graftal joins them into one symbol).
const AT_PAIRS: [&str; 19] = [
    "Gs", "Gc", "Ge", "Gt", "Gr", "Di", "Dd", "Tx", "Ts", "Ti", "Td", "Tp", "Tf", "PS", "PC", "PD",
    "bo", "bc", "mc",
];

/// The symbol that starts at `start` in symbol mode: one character, or a
/// prefixed command. Returns its text's length in bytes.
fn symbol_len(src: &str, start: usize) -> usize {
    let rest = &src[start..];
    let mut chars = rest.chars();
    let first = chars.next().unwrap_or(' ');
    let second = chars.next();
    let blank = |c: Option<char>| c.is_none_or(|c| c.is_whitespace() || "<>:*()".contains(c));
    match first {
        '@' if !blank(second) => {
            let pair = rest.get(1..3).unwrap_or("");
            if AT_PAIRS.contains(&pair) {
                3
            } else {
                1 + second.map_or(0, char::len_utf8)
            }
        }
        '?' if matches!(second, Some('P' | 'H' | 'L' | 'U' | 'E')) => 2,
        '~' if !blank(second) => 1 + second.map_or(0, char::len_utf8),
        c => c.len_utf8(),
    }
}

/// The tokens of a (preprocessed) cpfg text.
pub struct Lexed {
    pub tokens: Vec<(Token, Span)>,
}

/// Lexes `src`, switching modes as cpfg does. Characters that fit no token
/// are reported (E0001) and dropped.
pub fn lex(src: &str, diags: &mut Diagnostics) -> Lexed {
    let mut tokens: Vec<(Token, Span)> = Vec::new();
    let mut mode = Mode::default();
    let mut pos = 0;
    while pos < src.len() {
        let next = if mode.expression {
            next_raw::<ExprTok>(src, pos)
                .map(|(t, span)| (t.map(|t| mode.expression_step(t, &src[span.clone()])), span))
        } else {
            next_raw::<SymTok>(src, pos).map(|(t, span)| (t.map(|t| mode.symbol_step(t)), span))
        };
        let Some((step, span)) = next else {
            break;
        };
        pos = span.end;
        match step {
            Err(()) => diags.push_invalid_character(src, span),
            Ok(Step::Skip) => {}
            Ok(Step::Emit(token)) => tokens.push((token, span)),
            Ok(Step::Symbol) => {
                // A prefixed command is longer than the character read.
                let span = span.start..span.start + symbol_len(src, span.start);
                pos = span.end;
                tokens.push((Token::Symbol(src[span.clone()].to_string()), span));
            }
            Ok(Step::Unterminated) => {
                push_unterminated(diags, span);
                break;
            }
        }
    }
    Lexed { tokens }
}

/// The next token of one mode's lexer at byte `pos`, with its span in `src`.
fn next_raw<'s, T>(src: &'s str, pos: usize) -> Option<(Result<T, T::Error>, Span)>
where
    T: Logos<'s, Source = str>,
    T::Extras: Default,
{
    let mut lx = T::lexer(&src[pos..]);
    let t = lx.next()?;
    Some((t, pos + lx.span().start..pos + lx.span().end))
}

/// What a token read in either mode gives the parser.
enum Step {
    Emit(Token),
    /// A module symbol, perhaps the start of a prefixed command.
    Symbol,
    /// Nothing: blanks, comments, continuations, line breaks inside braces.
    Skip,
    /// A comment that is never closed: the rest of the text is comment.
    Unterminated,
}

/// The lexer's mode and the nesting that decides when it changes.
#[derive(Default)]
struct Mode {
    expression: bool,
    /// Parenthesis nesting in expression mode (0 ends a parameter list).
    nesting: i32,
    /// Statement-brace depth: line breaks inside braces do not end an item.
    braces: i32,
}

impl Mode {
    fn expression_step(&mut self, t: ExprTok, text: &str) -> Step {
        let token = match t {
            ExprTok::_Skip | ExprTok::Continuation => return Step::Skip,
            ExprTok::OpenComment => return Step::Unterminated,
            ExprTok::Newline => return self.line_break(),
            ExprTok::Keyword(k) => return self.keyword(k),
            ExprTok::Arrow => {
                self.expression = false;
                Token::Arrow
            }
            ExprTok::ObjectArrow => {
                self.expression = false;
                Token::ObjectArrow
            }
            ExprTok::Assign => Token::Assign,
            ExprTok::Amp => Token::Amp,
            ExprTok::Plus => Token::Plus,
            ExprTok::Minus => Token::Minus,
            ExprTok::Star => Token::Star,
            ExprTok::Slash => Token::Slash,
            ExprTok::Percent => Token::Percent,
            ExprTok::Caret => Token::Caret,
            ExprTok::Semi => Token::Semi,
            ExprTok::Comma => Token::Comma,
            ExprTok::Question => Token::Question,
            ExprTok::Colon => Token::Colon,
            ExprTok::LParen => {
                self.nesting += 1;
                Token::LParen
            }
            ExprTok::RParen => {
                self.nesting -= 1;
                if self.nesting <= 0 && self.braces == 0 {
                    self.nesting = 0;
                    self.expression = false;
                }
                Token::RParen
            }
            ExprTok::LBracket => Token::LBracket,
            ExprTok::RBracket => Token::RBracket,
            ExprTok::Lt => Token::Lt,
            ExprTok::Gt => Token::Gt,
            ExprTok::Ne => Token::Ne,
            ExprTok::EqEq => Token::EqEq,
            ExprTok::Le => Token::Le,
            ExprTok::Ge => Token::Ge,
            ExprTok::Not => Token::Not,
            ExprTok::And => Token::And,
            ExprTok::Or => Token::Or,
            ExprTok::LBrace => {
                self.braces += 1;
                Token::LBrace
            }
            ExprTok::RBrace => {
                self.braces = (self.braces - 1).max(0);
                Token::RBrace
            }
            ExprTok::Name => Token::Name(text.to_string()),
            ExprTok::Number => Token::Number(text.parse().unwrap_or(f64::NAN)),
            ExprTok::Str => Token::Str(text[1..text.len() - 1].to_string()),
        };
        Step::Emit(token)
    }

    fn symbol_step(&mut self, t: SymTok) -> Step {
        let token = match t {
            SymTok::_Skip | SymTok::Continuation => return Step::Skip,
            SymTok::OpenComment => return Step::Unterminated,
            SymTok::Newline => return self.line_break(),
            SymTok::Keyword(k) => return self.keyword(k),
            SymTok::Symbol => return Step::Symbol,
            SymTok::Null => Token::Null,
            // A condition or a parameter list follows.
            SymTok::Colon => {
                self.open_expression();
                Token::Colon
            }
            SymTok::LParen => {
                self.open_expression();
                Token::LParen
            }
            SymTok::Arrow => Token::Arrow,
            SymTok::ObjectArrow => Token::ObjectArrow,
            SymTok::LSep => Token::LSep,
            SymTok::RSep => Token::RSep,
            SymTok::RParen => Token::RParen,
        };
        Step::Emit(token)
    }

    /// A line break ends the item, back in symbol mode, unless it is inside
    /// the braces of a statement block.
    fn line_break(&mut self) -> Step {
        if self.braces > 0 {
            return Step::Skip;
        }
        self.expression = false;
        self.nesting = 0;
        Step::Emit(Token::Eol)
    }

    /// Expression mode, inside one level of parentheses (or after a `:`).
    fn open_expression(&mut self) {
        self.expression = true;
        self.nesting = 1;
    }

    fn keyword(&mut self, k: Keyword) -> Step {
        self.expression = k.takes_expression();
        self.nesting = 0;
        Step::Emit(Token::Keyword(k))
    }
}

fn push_unterminated(diags: &mut Diagnostics, span: Span) {
    diags.push(
        crate::diagnostics::Diagnostic::at(
            crate::diagnostics::codes::UNTERMINATED_COMMENT,
            span,
            "this comment is never closed",
        )
        .with_label("the comment starts here")
        .with_help("close it with `*/`"),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(src: &str) -> Vec<Token> {
        let mut d = Diagnostics::default();
        let l = lex(src, &mut d);
        assert!(d.is_empty(), "{d:?}");
        l.tokens.into_iter().map(|(t, _)| t).collect()
    }

    fn sym(s: &str) -> Token {
        Token::Symbol(s.into())
    }

    #[test]
    fn symbols_are_single_characters_and_parameters_are_expressions() {
        assert_eq!(
            toks("A(x) --> FA(x+1)@O(2)~l?P(a,b)\n"),
            vec![
                sym("A"),
                Token::LParen,
                Token::Name("x".into()),
                Token::RParen,
                Token::Arrow,
                sym("F"),
                sym("A"),
                Token::LParen,
                Token::Name("x".into()),
                Token::Plus,
                Token::Number(1.0),
                Token::RParen,
                sym("@O"),
                Token::LParen,
                Token::Number(2.0),
                Token::RParen,
                sym("~l"),
                sym("?P"),
                Token::LParen,
                Token::Name("a".into()),
                Token::Comma,
                Token::Name("b".into()),
                Token::RParen,
                Token::Eol,
            ]
        );
    }

    #[test]
    fn tabs_continue_lines_and_braces_hold_them_open() {
        let t = toks("A : {x=1;\ny=2;} x<2 -->\n\tB\nC --> *\n");
        let eols = t.iter().filter(|t| **t == Token::Eol).count();
        assert_eq!(eols, 2, "{t:?}");
        assert!(t.contains(&Token::Lt));
        assert!(t.contains(&Token::Null));
    }

    #[test]
    fn keywords_in_any_case_and_context_separators() {
        let t = toks("Lsystem: 1\nAxiom: A\nB < A > C --> D\nEndlsystem\n");
        assert_eq!(t[0], Token::Keyword(Keyword::Lsystem));
        assert!(t.contains(&Token::Keyword(Keyword::Axiom)));
        assert!(t.contains(&Token::LSep) && t.contains(&Token::RSep));
        assert!(t.contains(&Token::Keyword(Keyword::EndLsystem)));
    }

    #[test]
    fn two_letter_commands_are_joined() {
        let t = toks("axiom: @Gs@Gc(2)@Ge@v@#(1)\n");
        assert!(t.contains(&sym("@Gs")) && t.contains(&sym("@Gc")) && t.contains(&sym("@v")));
        assert!(t.contains(&sym("@#")));
    }
}
