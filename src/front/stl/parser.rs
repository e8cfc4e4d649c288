//! The STL parser (logos tokens, then precise checks).
//!
//! Two passes, as in the pfg front end:
//!
//! 1. [`raw_items`] cuts the token stream into *raw items*: `SEED …
//!    ENDSEED` and `LAYOUT … ENDLAYOUT` blocks (which may span lines; a
//!    block whose end keyword is missing runs to the end of the file) and
//!    single lines (settings and rule definitions). It accepts every token
//!    sequence, so it never fails, and it is one scan (a parser combinator
//!    here cost more per token than everything else together).
//! 2. [`build`] reads each raw item by recursive descent and says precisely
//!    what is wrong (an unclosed `[`, a shape without its colour, …) with a
//!    code, a span and a help line; after an error it recovers at the next
//!    token that can start something, so every error of a file is reported
//!    in one run. Nesting deeper than [`MAX_NESTING`] (graftal's one depth
//!    limit) is an error (E0013, once per item), so no input can exhaust
//!    the stack. A mistake repeated along a line is reported a few times,
//!    then counted ([`Repeats`]).

use super::ast::{Arg, ColourAst, Elem, Entries, Entry, File, Item, Num, ShapeAst, Str};
use super::lexer::{lex, Token};
use crate::diagnostics::{codes, nearest, Code, Diagnostic, Diagnostics};
use crate::front::depth::too_deep;
use crate::front::repeats::Repeats;
use crate::ir::Span;

/// The statement keywords (upper case, as the paper writes them).
pub const KEYWORDS: [&str; 7] = ["ANGLE", "B", "L", "GROWTH", "LEVELS", "SEED", "LAYOUT"];

pub use crate::common::stl_words::RESERVED;

/// The deepest nesting of `[ ]` and `{ }` read: the one depth limit.
pub const MAX_NESTING: usize = crate::ir::MAX_NESTING;

type Tok<'src> = (Token<'src>, Span);

/// An item as the first pass cuts it from the tokens.
#[derive(Clone, Debug)]
enum Raw<'t, 'src> {
    Line(&'t [Tok<'src>]),
    Block {
        seed: bool,
        open: Span,
        body: &'t [Tok<'src>],
        close: Option<Span>,
    },
}

/// Cuts the tokens into raw items: a `SEED` or `LAYOUT` that starts an
/// item runs to its end keyword (or the end of the file); anything else
/// runs to the end of its line. Every token sequence is accepted. The
/// items are slices of `tokens`: nothing is copied per token.
fn raw_items<'t, 'src>(tokens: &'t [Tok<'src>]) -> Vec<Raw<'t, 'src>> {
    let mut items = Vec::new();
    let mut i = 0;
    while let Some((t, span)) = tokens.get(i) {
        let end_keyword = match t {
            Token::Newline => {
                i += 1;
                continue;
            }
            Token::Ident("SEED") => Some("ENDSEED"),
            Token::Ident("LAYOUT") => Some("ENDLAYOUT"),
            _ => None,
        };
        let rest = &tokens[i + 1..];
        let Some(end_keyword) = end_keyword else {
            let len = tokens[i..]
                .iter()
                .position(|t| t.0 == Token::Newline)
                .unwrap_or(tokens.len() - i);
            items.push(Raw::Line(&tokens[i..i + len]));
            i += len;
            continue;
        };
        let body_len = rest
            .iter()
            .position(|t| t.0 == Token::Ident(end_keyword))
            .unwrap_or(rest.len());
        items.push(Raw::Block {
            seed: end_keyword == "ENDSEED",
            open: span.clone(),
            body: &rest[..body_len],
            close: rest.get(body_len).map(|t| t.1.clone()),
        });
        i += 1 + body_len + 1;
    }
    items
}

/// Parses STL source text into an AST. Never fails: problems are pushed to
/// `diags` and what they affect is left out of the AST.
pub fn parse(src: &str, diags: &mut Diagnostics) -> File {
    let tokens = lex(src, diags);
    let mut file = File::default();
    for raw in raw_items(&tokens) {
        build(raw, src, diags, &mut file);
    }
    file
}

/// A cursor over the tokens of one raw item.
struct Cursor<'a, 'src> {
    toks: &'a [Tok<'src>],
    pos: usize,
    diags: &'a mut Diagnostics,
    /// Where the item ends (for "expected … here" at the end).
    end: usize,
    /// Set when nesting went too deep: the rest of the item is skipped and
    /// the enclosing brackets are not reported again.
    aborted: bool,
    /// What the current line reported: a mistake repeated along a line
    /// (`SEED F(1)F(1)…`) is reported a few times, then counted.
    repeats: Repeats,
}

impl<'src> Cursor<'_, 'src> {
    fn peek(&self) -> Option<Token<'src>> {
        self.toks.get(self.pos).map(|t| t.0)
    }
    fn peek_at(&self, k: usize) -> Option<Token<'src>> {
        self.toks.get(self.pos + k).map(|t| t.0)
    }
    fn span(&self) -> Span {
        self.toks
            .get(self.pos)
            .map_or(self.end..self.end, |t| t.1.clone())
    }
    fn bump(&mut self) -> (Token<'src>, Span) {
        let t = self.toks[self.pos].clone();
        self.pos += 1;
        if t.0 == Token::Newline {
            self.end_line();
        }
        t
    }
    /// Reports what `build` makes, a diagnostic of `code` on the current
    /// line, unless the line has reported enough of that code already.
    fn report(&mut self, code: Code, build: impl FnOnce() -> Diagnostic) {
        self.repeats.report(self.diags, code, build);
    }
    /// Ends a line: says how many repeated diagnostics it did not show.
    fn end_line(&mut self) {
        self.repeats.end_item(self.diags, "on this line");
    }
    fn at_end(&self) -> bool {
        self.pos >= self.toks.len()
    }
    fn unexpected(&mut self, expected: &str, help: &str) {
        let span = self.span();
        let found = self.peek();
        self.report(codes::SYNTAX, || {
            let d = match found {
                Some(t) => Diagnostic::at(codes::SYNTAX, span, format!("unexpected {t}")),
                None => Diagnostic::at(codes::SYNTAX, span, "unexpected end of line"),
            };
            d.with_label(format!("expected {expected}")).with_help(help)
        });
    }

    /// A number, with an optional leading `-`.
    fn number(&mut self) -> Option<Num> {
        let start = self.span().start;
        let neg = if self.peek() == Some(Token::Minus)
            && matches!(self.peek_at(1), Some(Token::Number(_)))
        {
            self.bump();
            true
        } else {
            false
        };
        match self.peek() {
            Some(Token::Number(n)) => {
                let (_, s) = self.bump();
                let v: f64 = n.parse().unwrap_or(f64::NAN);
                Some(Num {
                    value: if neg { -v } else { v },
                    span: start..s.end,
                })
            }
            _ => None,
        }
    }

    /// A number; without one, reports that a number was expected.
    fn expect_number(&mut self, help: &str) -> Option<Num> {
        let n = self.number();
        if n.is_none() {
            self.unexpected("a number", help);
        }
        n
    }

    /// A string of elements up to (not including) a token `stop` accepts,
    /// or the end. `depth` counts the brackets and braces around it.
    fn string(&mut self, stop: fn(&Token) -> bool, depth: usize) -> Str {
        let start = self.span().start;
        let mut elems = Vec::new();
        while let Some(t) = self.peek() {
            if stop(&t) {
                break;
            }
            match t {
                Token::Newline => {
                    self.bump();
                }
                Token::Ident(name) => {
                    let (_, span) = self.bump();
                    let entries = if self.peek() == Some(Token::LBrace) {
                        self.entries(depth)
                    } else {
                        None
                    };
                    elems.push(Elem::Name {
                        text: name.to_string(),
                        span,
                        entries,
                    });
                }
                Token::Plus | Token::Minus => {
                    let (_, span) = self.bump();
                    elems.push(Elem::Turn {
                        left: t == Token::Plus,
                        span,
                    });
                }
                Token::Open => {
                    if depth >= MAX_NESTING {
                        self.too_deep();
                        return Str {
                            elems,
                            span: start..self.end,
                        };
                    }
                    if let Some(e) = self.bracket(depth) {
                        elems.push(e);
                    }
                }
                Token::Close => {
                    let (_, span) = self.bump();
                    self.report(codes::STL_UNBALANCED, || {
                        Diagnostic::at(codes::STL_UNBALANCED, span, "unmatched `]`")
                            .with_label("no `[` opens this branch")
                            .with_help("remove this `]` or add the `[` that opens the branch")
                    });
                }
                Token::LBrace => {
                    let span = self.span();
                    self.report(codes::SYNTAX, || {
                        Diagnostic::at(codes::SYNTAX, span, "unexpected `{`")
                            .with_label("a branching `{…}` must follow a rule name")
                            .with_help("write the rule before its entries: `R1{R2, ~, R1}`")
                    });
                    let _ = self.entries(depth);
                }
                _ => {
                    self.unexpected(
                        "a drawing component, a rule name or `[`",
                        "a string holds F L R + - [ ], rule names, `[I n X]` and branching terms `R{…}`",
                    );
                    self.bump();
                }
            }
        }
        let end = self
            .toks
            .get(self.pos.saturating_sub(1))
            .map_or(start, |t| t.1.end)
            .max(start);
        Str {
            elems,
            span: start..end,
        }
    }

    fn too_deep(&mut self) {
        let span = self.span();
        self.diags.push(too_deep(
            span,
            "split the string into rules: a rule's name stands for its whole body",
        ));
        // Skip the rest of the item.
        self.pos = self.toks.len();
        self.aborted = true;
    }

    /// `[ … ]` or `[I n X]`, the cursor at `[`.
    fn bracket(&mut self, depth: usize) -> Option<Elem> {
        let (_, open) = self.bump();
        let resemble = matches!(self.peek(), Some(Token::Ident("I")))
            && matches!(self.peek_at(1), Some(Token::Number(_)) | Some(Token::Minus));
        let count = if resemble {
            self.bump();
            self.number()
        } else {
            None
        };
        if resemble && count.is_none() {
            self.unexpected("a count", "a self-resemblance count is written `[I 3 R1]`");
        }
        let body = self.string(|t| *t == Token::Close, depth + 1);
        let end = match self.peek() {
            Some(Token::Close) => self.bump().1.end,
            _ if self.aborted => return None,
            _ => {
                let end = self.end;
                self.report(codes::STL_UNBALANCED, || {
                    Diagnostic::at(codes::STL_UNBALANCED, open.clone(), "unclosed `[`")
                        .with_label("this branch is never closed")
                        .with_secondary(end..end, "the string ends here")
                        .with_help("close the branch with `]`")
                });
                return None;
            }
        };
        let span = open.start..end;
        if resemble {
            let count = count?;
            if body.elems.is_empty() {
                self.report(codes::SYNTAX, || {
                    Diagnostic::at(codes::SYNTAX, span, "`[I n]` without a rule")
                        .with_label("nothing to repeat")
                        .with_help(
                            "write the rule or string to rewrite: `[I 3 R1]` or `[I 2 F[+F]]`",
                        )
                });
                return None;
            }
            Some(Elem::Resemble { count, body, span })
        } else {
            Some(Elem::Branch { body, span })
        }
    }

    /// `{ e1, …, em }`, the cursor at `{`; `depth` counts the brackets and
    /// braces around it.
    fn entries(&mut self, depth: usize) -> Option<Entries> {
        if depth >= MAX_NESTING {
            self.too_deep();
            return None;
        }
        let (_, open) = self.bump();
        let mut list = Vec::new();
        let mut sep = open.clone();
        if self.peek() == Some(Token::RBrace) {
            let close = self.bump().1;
            return Some(Entries {
                list,
                span: open.start..close.end,
            });
        }
        loop {
            while self.peek() == Some(Token::Newline) {
                self.bump();
            }
            match self.peek() {
                Some(Token::Comma) | Some(Token::RBrace) => list.push(Entry::Empty(sep.clone())),
                Some(Token::Tilde) => list.push(Entry::Failed(self.bump().1)),
                Some(Token::Ident(name)) => {
                    let (_, name_span) = self.bump();
                    let entries = if self.peek() == Some(Token::LBrace) {
                        self.entries(depth + 1)
                    } else {
                        None
                    };
                    list.push(Entry::Term {
                        name: name.to_string(),
                        name_span,
                        entries,
                    });
                }
                None => {}
                Some(_) => {
                    self.unexpected(
                        "a rule name, `~` or `,`",
                        "an entry is a rule (with its own optional `{…}`), `~` for a failed branch, or nothing",
                    );
                    // Skip to the next comma or brace at this level.
                    while let Some(t) = self.peek() {
                        if matches!(t, Token::Comma | Token::RBrace | Token::Newline) {
                            break;
                        }
                        self.bump();
                    }
                }
            }
            while self.peek() == Some(Token::Newline) {
                self.bump();
            }
            match self.peek() {
                Some(Token::Comma) => sep = self.bump().1,
                Some(Token::RBrace) => {
                    let close = self.bump().1;
                    return Some(Entries {
                        list,
                        span: open.start..close.end,
                    });
                }
                _ if self.aborted => return None,
                _ => {
                    let here = self.span();
                    self.report(codes::STL_UNBALANCED, || {
                        Diagnostic::at(codes::STL_UNBALANCED, open.clone(), "unclosed `{`")
                            .with_label("these branching entries are never closed")
                            .with_secondary(here, "expected `,` or `}` here")
                            .with_help("separate entries with `,` and close them with `}`")
                    });
                    return None;
                }
            }
        }
    }
}

/// Reads one raw item into the AST.
fn build(raw: Raw<'_, '_>, src: &str, diags: &mut Diagnostics, file: &mut File) {
    match raw {
        Raw::Block {
            seed,
            open,
            body,
            close,
        } => {
            let (open_kw, close_kw) = if seed {
                ("SEED", "ENDSEED")
            } else {
                ("LAYOUT", "ENDLAYOUT")
            };
            let end = close.as_ref().map_or(src.len(), |c| c.end);
            if close.is_none() {
                diags.push(
                    Diagnostic::at(
                        codes::STL_UNTERMINATED,
                        open.clone(),
                        format!("unterminated `{open_kw}`"),
                    )
                    .with_label(format!("this `{open_kw}` has no `{close_kw}`"))
                    .with_secondary(src.len()..src.len(), "the file ends here")
                    .with_help(format!("end the block with `{close_kw}` on its own line")),
                );
            }
            let body_end = body.last().map_or(open.end, |t| t.1.end);
            let mut cur = Cursor {
                toks: body,
                pos: 0,
                diags,
                end: body_end,
                aborted: false,
                repeats: Repeats::default(),
            };
            let span = open.start..end;
            if seed {
                let body = cur.string(|_| false, 0);
                file.items.push(Item::Seed { body, span });
            } else {
                let mut shapes = Vec::new();
                while !cur.at_end() {
                    if cur.peek() == Some(Token::Newline) {
                        cur.bump();
                        continue;
                    }
                    if let Some(s) = shape(&mut cur) {
                        shapes.push(s);
                    }
                    // Skip what is left of the line.
                    while !cur.at_end() && cur.peek() != Some(Token::Newline) {
                        cur.bump();
                    }
                }
                file.items.push(Item::Layout { shapes, span });
            }
            cur.end_line();
        }
        Raw::Line(toks) => {
            let end = toks.last().map_or(0, |t| t.1.end);
            let mut cur = Cursor {
                toks,
                pos: 0,
                diags,
                end,
                aborted: false,
                repeats: Repeats::default(),
            };
            if let Some(item) = line(&mut cur) {
                file.items.push(item);
            }
            cur.end_line();
        }
    }
}

/// A setting or a rule definition.
fn line(cur: &mut Cursor<'_, '_>) -> Option<Item> {
    let start = cur.span().start;
    let end = cur.end;
    let span = start..end;
    let Some(Token::Ident(first)) = cur.peek() else {
        cur.unexpected(
            "a setting or a rule",
            "a line is a setting (`ANGLE 30`, `B = 8 (1)`, `GROWTH BFS`, `LEVELS 12`), a rule `R1 = …`, or a `SEED`/`LAYOUT` block",
        );
        return None;
    };
    let (_, first_span) = cur.bump();
    match first {
        "ANGLE" | "LEVELS" => number_setting(cur, first, span),
        "GROWTH" => growth(cur, span),
        _ if cur.peek() == Some(Token::Eq) => {
            cur.bump();
            if first == "B" || first == "L" {
                return parameter(cur, first, span);
            }
            let body = cur.string(|_| false, 0);
            Some(Item::Rule {
                name: first.to_string(),
                name_span: first_span,
                body,
                span,
            })
        }
        _ => {
            cur.diags.push(not_a_line(first, first_span));
            None
        }
    }
}

/// Reports anything left on a line after its setting.
fn line_end(cur: &mut Cursor<'_, '_>) {
    if !cur.at_end() {
        cur.unexpected(
            "the end of the line",
            "put one setting or rule on each line",
        );
    }
}

/// `ANGLE a` or `LEVELS n`, after the keyword.
fn number_setting(cur: &mut Cursor<'_, '_>, keyword: &str, span: Span) -> Option<Item> {
    let example = if keyword == "ANGLE" { "30" } else { "12" };
    let value = cur.expect_number(&format!("write e.g. `{keyword} {example}`"))?;
    line_end(cur);
    Some(if keyword == "ANGLE" {
        Item::Angle { value, span }
    } else {
        Item::Levels { value, span }
    })
}

/// `GROWTH BFS` or `GROWTH DFS`, after the keyword.
fn growth(cur: &mut Cursor<'_, '_>, span: Span) -> Option<Item> {
    let depth_first = match cur.peek() {
        Some(Token::Ident("BFS")) => false,
        Some(Token::Ident("DFS")) => true,
        Some(Token::Ident(other)) => {
            let s = cur.span();
            let near = nearest(other, &["BFS", "DFS"]);
            let help = match near.first() {
                Some(n) => format!("did you mean `{n}`?"),
                None => "write `GROWTH BFS` (breadth first) or `GROWTH DFS` (depth first)".into(),
            };
            cur.report(codes::SYNTAX, || {
                Diagnostic::at(
                    codes::SYNTAX,
                    s,
                    format!("unknown growth strategy `{other}`"),
                )
                .with_label("expected `BFS` or `DFS`")
                .with_help(help)
            });
            return None;
        }
        _ => {
            cur.unexpected(
                "`BFS` or `DFS`",
                "write `GROWTH BFS` (breadth first) or `GROWTH DFS` (depth first)",
            );
            return None;
        }
    };
    cur.bump();
    line_end(cur);
    Some(Item::Growth { depth_first, span })
}

/// `B = value (decrement)` or `L = …`, after the `=`; the decrement is
/// optional.
fn parameter(cur: &mut Cursor<'_, '_>, name: &str, span: Span) -> Option<Item> {
    let example = if name == "B" { "8" } else { "40" };
    let value = cur.expect_number(&format!(
        "write `{name} = {example} (1)`: the value and its decrement per level"
    ))?;
    let decrement = if cur.peek() == Some(Token::LParen) {
        cur.bump();
        let d = cur.expect_number("the decrement per level is a number in parentheses: `(1)`")?;
        if cur.peek() != Some(Token::RParen) {
            cur.unexpected("`)`", "close the decrement with `)`");
            return None;
        }
        cur.bump();
        Some(d)
    } else {
        None
    };
    line_end(cur);
    Some(Item::Param {
        param: if name == "B" { 'B' } else { 'L' },
        value,
        decrement,
        span,
    })
}

/// The error for a line that starts with a word that is neither a setting
/// nor a rule name: a stray block end, a misspelt keyword, or other text.
fn not_a_line(first: &str, first_span: Span) -> Diagnostic {
    let keywords: Vec<&str> = KEYWORDS
        .iter()
        .copied()
        .chain(["ENDSEED", "ENDLAYOUT"])
        .collect();
    let near = nearest(first, &keywords);
    if matches!(first, "ENDSEED" | "ENDLAYOUT") {
        Diagnostic::at(
            codes::SYNTAX,
            first_span,
            format!("`{first}` without its opening keyword"),
        )
        .with_label("no block to end")
        .with_help(format!("start the block with `{}`", &first[3..]))
    } else if let Some(k) = near
        .first()
        .filter(|_| first.chars().all(|c| c.is_ascii_uppercase()))
    {
        Diagnostic::at(
            codes::STL_UNKNOWN_KEYWORD,
            first_span,
            format!("unknown keyword `{first}`"),
        )
        .with_label("not an STL keyword")
        .with_help(format!("did you mean `{k}`?"))
    } else {
        Diagnostic::at(
            codes::STL_UNKNOWN_KEYWORD,
            first_span,
            format!("`{first}` is not a setting or a rule definition"),
        )
        .with_label("expected a keyword or `NAME =`")
        .with_help("define a rule with `R1 = [F][+F]`; the seed goes between `SEED` and `ENDSEED`")
    }
}

/// One layout shape: `(colour) Kind arg, arg, …`.
fn shape(cur: &mut Cursor<'_, '_>) -> Option<ShapeAst> {
    let start = cur.span().start;
    let help = "a shape is `(colour) Kind arguments`, e.g. `(clGreen) Ellipse (-150,0), 300, 400`";
    if cur.peek() != Some(Token::LParen) {
        cur.unexpected("`(` and a colour", help);
        return None;
    }
    cur.bump();
    let colour = match cur.peek() {
        Some(Token::Ident(n)) => ColourAst::Name(n.to_string(), cur.bump().1),
        Some(Token::Hex(h)) => ColourAst::Hex(h.to_string(), cur.bump().1),
        _ => {
            cur.unexpected("a colour name or `$00BBGGRR`", help);
            return None;
        }
    };
    if cur.peek() != Some(Token::RParen) {
        cur.unexpected("`)`", help);
        return None;
    }
    cur.bump();
    let (kind, kind_span) = match cur.peek() {
        Some(Token::Ident(k)) => (k.to_string(), cur.bump().1),
        _ => {
            cur.unexpected("a shape: Rectangle, RoundRect, Ellipse or Polygon", help);
            return None;
        }
    };
    let mut args = Vec::new();
    loop {
        if cur.at_end() || cur.peek() == Some(Token::Newline) {
            break;
        }
        let a = if cur.peek() == Some(Token::LParen) {
            let s = cur.bump().1;
            let x = cur.number();
            let comma = cur.peek() == Some(Token::Comma);
            if comma {
                cur.bump();
            }
            let y = cur.number();
            match (x, comma, y, cur.peek()) {
                (Some(x), true, Some(y), Some(Token::RParen)) => {
                    let e = cur.bump().1;
                    Arg::Point(x, y, s.start..e.end)
                }
                _ => {
                    cur.unexpected(
                        "a point `(x, y)`",
                        "a point is two numbers in parentheses: `(-150, 0)`",
                    );
                    return None;
                }
            }
        } else if let Some(n) = cur.number() {
            Arg::Num(n)
        } else {
            cur.unexpected("a number or a point `(x, y)`", help);
            return None;
        };
        args.push(a);
        match cur.peek() {
            Some(Token::Comma) => {
                cur.bump();
            }
            None | Some(Token::Newline) => break,
            _ => {
                cur.unexpected(
                    "`,` or the end of the line",
                    "separate a shape's arguments with `,`",
                );
                return None;
            }
        }
    }
    let end = args.last().map_or(kind_span.end, |a| a.span().end);
    Some(ShapeAst {
        colour,
        kind,
        kind_span,
        args,
        span: start..end,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_ok(src: &str) -> File {
        crate::front::parse::parse_clean(parse, src)
    }

    fn codes_of(src: &str) -> Vec<&'static str> {
        crate::front::parse::parse_codes(parse, src)
    }

    #[test]
    fn parses_settings_rules_seed_and_layout() {
        let f = parse_ok(
            "ANGLE 30\nB = 8 (1)\nL = 40\nGROWTH DFS\nLEVELS 5\nR1 = [F][+F][-F]\nR3 = [I 3 R1]\nSEED\nF R1{R1, R2{,}, ~}\nENDSEED\nLAYOUT\n(clGreen) Ellipse (-150,0), 300, 400\n($00FF00) Polygon (0,0), (1,0), (0,1)\nENDLAYOUT\n",
        );
        assert_eq!(f.items.len(), 9);
        let Item::Seed { body, .. } = &f.items[7] else {
            panic!()
        };
        let Elem::Name {
            entries: Some(e), ..
        } = &body.elems[1]
        else {
            panic!()
        };
        assert_eq!(e.list.len(), 3);
        assert!(matches!(e.list[2], Entry::Failed(_)));
        let Item::Layout { shapes, .. } = &f.items[8] else {
            panic!()
        };
        assert_eq!(shapes.len(), 2);
        assert_eq!(shapes[1].args.len(), 3);
        let Item::Rule { body, .. } = &f.items[6] else {
            panic!()
        };
        assert!(matches!(body.elems[0], Elem::Resemble { .. }));
    }

    #[test]
    fn seeds_span_lines_and_empty_entries_count() {
        let f = parse_ok("SEED\nR1{R1{,},\n ,}\nENDSEED");
        let Item::Seed { body, .. } = &f.items[0] else {
            panic!()
        };
        let Elem::Name {
            entries: Some(e), ..
        } = &body.elems[0]
        else {
            panic!()
        };
        assert_eq!(e.list.len(), 3);
        let Entry::Term {
            entries: Some(inner),
            ..
        } = &e.list[0]
        else {
            panic!()
        };
        assert_eq!(inner.list.len(), 2);
    }

    #[test]
    fn errors_are_reported_and_parsing_goes_on() {
        assert_eq!(codes_of("SEED\nF[F\n"), vec!["E0504", "E0516"]);
        assert_eq!(
            codes_of("SEED F] ENDSEED\nANGEL 30\nR1 = F{\n"),
            vec!["E0516", "E0512", "E0516"]
        );
        assert_eq!(
            codes_of("LAYOUT\nEllipse (0,0), 1, 2\nENDLAYOUT"),
            vec!["E0003"]
        );
    }

    #[test]
    fn deep_nesting_is_one_error_not_a_crash() {
        let src = format!("SEED\n{}F{}\nENDSEED", "[".repeat(5000), "]".repeat(5000));
        assert_eq!(codes_of(&src), ["E0013"]);
        let src = format!("SEED\n{}\nENDSEED", "R1{".repeat(5000));
        assert_eq!(codes_of(&src), ["E0013"]);
    }

    #[test]
    fn brackets_and_braces_nest_to_the_same_limit() {
        for (open, close) in [("[", "]"), ("R1{", "}")] {
            let at = |n: usize| format!("SEED\n{}F{}\nENDSEED", open.repeat(n), close.repeat(n));
            assert_eq!(codes_of(&at(MAX_NESTING)), Vec::<&str>::new(), "{open}");
            assert_eq!(codes_of(&at(MAX_NESTING + 1)), ["E0013"], "{open}");
        }
    }
}
