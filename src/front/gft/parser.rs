//! The `.gft` parser: logical lines (docs/gft.md §1) split by hand, then
//! each line read as an item; expressions and statements are chumsky 0.12
//! parsers. An error in one line is reported and reading goes on with the
//! next, so every error of a file is reported in one run.

use super::ast::{
    Alternative, Arg, Block, Expr, ExprKind, File, Item, Keyword, Piece, Production, Stmt, Word,
};
use super::lexer::{lex, Token};
/// The keywords, as the language server lists them.
pub use crate::common::gft_words::KEYWORDS;
use crate::common::gft_words::{is_keyword, takes_block};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::front::parse::push_syntax_errors;
use crate::front::repeats::push_lazily;
use crate::front::suggest::Suggester;
use crate::ir::{Span, MAX_NESTING};
use chumsky::input::ValueInput;
use chumsky::prelude::*;

type Tok<'s> = (Token<'s>, Span);
type Extra<'t, 's> = extra::Err<Rich<'t, Token<'s>>>;

/// Block items whose block holds lines of values, not productions or
/// statements.
const VALUE_BLOCKS: &[&str] = &["outline", "surface", "contour", "backdrop"];

/// Keywords whose value is an expression (`angle 360/7`).
const EXPRESSION_KEYWORDS: &[&str] = &[
    "steps",
    "angle",
    "length",
    "scale",
    "width",
    "width-factor",
    "width-step",
    "colour",
    "colour-step",
    "seed",
    "label",
];
/// Keywords followed by a word.
const WORD_KEYWORDS: &[&str] = &["axiom", "ignore", "consider", "cut"];

/// Parses `.gft` text. Never fails: problems go to `diags` and their
/// lines are left out.
pub fn parse(src: &str, diags: &mut Diagnostics) -> File {
    let tokens = lex(src, diags);
    let mut file = File::default();
    for line in logical_lines(&tokens, diags) {
        if let Some(item) = item(line, diags) {
            file.items.push(item);
        }
    }
    file
}

/// The keyword a line starts with: identifiers joined by `-` with nothing
/// between (`width-factor`), and how many tokens it takes.
fn keyword_at(line: &[Tok<'_>]) -> Option<(String, Span, usize)> {
    let (Token::Ident(first), span) = line.first()? else {
        return None;
    };
    let (mut name, mut end, mut n) = (first.to_string(), span.end, 1);
    while let [(dash, d), (Token::Ident(next), s), ..] = &line[n..] {
        if !dash.is("-") || d.start != end || s.start != d.end {
            break;
        }
        name.push('-');
        name.push_str(next);
        end = s.end;
        n += 2;
    }
    Some((name, span.start..end, n))
}

/// Splits the tokens into logical lines: a line break ends a line unless
/// it is inside `( )`, inside the `{ }` of a block item, or the next line
/// starts with `->`. A line nested deeper than [`MAX_NESTING`] is reported
/// and left out.
fn logical_lines<'a, 's>(tokens: &'a [Tok<'s>], diags: &mut Diagnostics) -> Vec<&'a [Tok<'s>]> {
    let mut lines = Vec::new();
    let (mut start, mut parens, mut braces, mut too_deep) = (0, 0usize, 0usize, false);
    // Whether the line that starts at `start` is a block item, found once
    // per line (a line of a million `a-a-…` would otherwise be quadratic).
    let block_at = |start: usize| keyword_at(&tokens[start..]).is_some_and(|k| takes_block(&k.0));
    let mut block = block_at(0);
    for (i, (t, span)) in tokens.iter().enumerate() {
        match t {
            Token::Char("(") => parens += 1,
            Token::Char(")") => parens = parens.saturating_sub(1),
            Token::Char("{") if block => braces += 1,
            Token::Char("}") if block => braces = braces.saturating_sub(1),
            _ => {}
        }
        if parens + braces > MAX_NESTING && !too_deep {
            too_deep = true;
            diags.push(
                Diagnostic::at(codes::NESTED_TOO_DEEPLY, span.clone(), "nested too deeply")
                    .with_label(format!("more than {MAX_NESTING} levels deep"))
                    .with_help("graftal reads at most 256 nested parentheses or braces"),
            );
        }
        let continues =
            parens > 0 || braces > 0 || matches!(tokens.get(i + 1), Some((Token::Arrow, _)));
        if *t == Token::Newline && !continues {
            if i > start && !too_deep {
                lines.push(&tokens[start..i]);
            }
            (start, parens, braces, too_deep) = (i + 1, 0, 0, false);
            block = start < tokens.len() && block_at(start);
        }
    }
    if start < tokens.len() && !too_deep {
        lines.push(&tokens[start..]);
    }
    lines
}

/// Index of the first token at nesting depth 0 (of `( ) [ ] { }`)
/// satisfying `pred`.
fn top_level(line: &[Tok<'_>], pred: impl Fn(&Token<'_>) -> bool) -> Option<usize> {
    let mut depth = 0i64;
    for (i, (t, _)) in line.iter().enumerate() {
        match t {
            Token::Char("(") => depth += 1,
            Token::Char(")") => depth -= 1,
            _ if depth == 0 && pred(t) => return Some(i),
            _ => {}
        }
    }
    None
}

fn span_of(toks: &[Tok<'_>]) -> Span {
    match (toks.first(), toks.last()) {
        (Some(a), Some(b)) => a.1.start..b.1.end,
        _ => 0..0,
    }
}

fn item(line: &[Tok<'_>], diags: &mut Diagnostics) -> Option<Item> {
    let keyword = keyword_at(line);
    let block = keyword.as_ref().is_some_and(|k| takes_block(&k.0));
    if !block && top_level(line, |t| *t == Token::Arrow).is_some() {
        return production(line, diags).map(Item::Production);
    }
    if let Some((name, span, n)) = &keyword {
        if is_keyword(name) {
            return keyword_item(name, span, &line[*n..], line, diags).map(Item::Keyword);
        }
    }
    if let Some(eq) = top_level(line, |t| t.is("=")) {
        let name: String = line[..eq].iter().map(|t| t.0.text()).collect();
        let name = name.trim_matches('`').to_string();
        let rest = &line[eq + 1..];
        if !name.is_empty() && !rest.is_empty() {
            return Some(Item::Define {
                name,
                span: span_of(&line[..eq]),
                op: args(rest),
                op_span: span_of(rest),
            });
        }
    }
    unknown_line(line, keyword, diags);
    None
}

fn unknown_line(line: &[Tok<'_>], keyword: Option<(String, Span, usize)>, diags: &mut Diagnostics) {
    let Some((name, span, _)) = keyword else {
        let span = span_of(line);
        push_lazily(diags, codes::GFT_UNKNOWN_LINE, || {
            Diagnostic::at(codes::GFT_UNKNOWN_LINE, span, "not an item")
                .with_label("neither a keyword, `NAME = OPERATION` nor a production")
                .with_help("a production needs `->`: `F -> F+F`")
        });
        return;
    };
    let mut d = Diagnostic::at(
        codes::GFT_UNKNOWN_KEYWORD,
        span,
        format!("unknown keyword `{name}`"),
    )
    .with_label("not a keyword");
    let keywords: Vec<&str> = KEYWORDS.iter().map(|(k, _)| *k).collect();
    let near = Suggester::default().nearest(&name, &keywords);
    // Among equally near keywords, one that starts like the name (`widht`:
    // `width`, not `light`).
    let first = near.iter().find(|k| k.get(..1) == name.get(..1));
    d = match first.or(near.first()) {
        Some(k) => d.suggesting(k),
        None => d.with_help("a production needs `->`: `F -> F+F`"),
    };
    push_lazily(diags, codes::GFT_UNKNOWN_KEYWORD, || d);
}

/// The arguments of a keyword line as written.
pub fn args(toks: &[Tok<'_>]) -> Vec<Arg> {
    toks.iter()
        .map(|(t, s)| match t {
            Token::Number(n) => match n.parse() {
                Ok(v) => Arg::Number(v, n.to_string(), s.clone()),
                Err(_) => Arg::Word(n.to_string(), s.clone()),
            },
            Token::Ident(w) => Arg::Word(w.to_string(), s.clone()),
            Token::Colour(c) => Arg::Colour(c.to_string(), s.clone()),
            Token::Quoted(q) => Arg::Quoted(q.trim_matches('`').to_string(), s.clone()),
            t => Arg::Punct(t.text().to_string(), s.clone()),
        })
        .collect()
}

fn keyword_item(
    name: &str,
    span: &Span,
    rest: &[Tok<'_>],
    line: &[Tok<'_>],
    diags: &mut Diagnostics,
) -> Option<Keyword> {
    let mut kw = Keyword {
        name: name.to_string(),
        span: span.clone(),
        args: Vec::new(),
        block: None,
        value: None,
        word: None,
        line: span_of(line),
    };
    if !takes_block(name) {
        kw.args = args(rest);
        if EXPRESSION_KEYWORDS.contains(&name) && !structure_seed(name, rest) {
            let unit = rest
                .last()
                .is_some_and(|t| matches!(t.0, Token::Ident("rad" | "deg")));
            let value = &rest[..rest.len() - usize::from(unit)];
            kw.value = expression(value, diags);
        }
        if WORD_KEYWORDS.contains(&name) {
            kw.word = Some(word(rest, diags));
        }
        return Some(kw);
    }
    let open = rest.iter().position(|t| t.0.is("{"));
    let close = rest.iter().rposition(|t| t.0.is("}"));
    let (Some(open), Some(close)) = (open, close) else {
        diags.push(
            Diagnostic::at(codes::GFT_UNBALANCED, span.clone(), "block without braces")
                .with_label(format!("`{name}` takes a block `{{ … }}`"))
                .with_help(format!("write `{name} {{ … }}`")),
        );
        return None;
    };
    kw.args = args(&rest[..open]);
    let inner = &rest[open + 1..close.max(open + 1)];
    kw.block = Some(if name == "graph" {
        if let (Some(first), Some(last)) = (kw.args.first(), kw.args.last()) {
            let span = first.span().start..last.span().end;
            diags.push(
                Diagnostic::at(codes::GRAPH_BAD_LINE, span, "text before the graph's `{`")
                    .with_label("nothing goes between `graph` and `{`")
                    .with_help("write `graph {` and the graph's lines below it"),
            );
        }
        Block::Graph(super::graph::block(inner, diags))
    } else if VALUE_BLOCKS.contains(&name) {
        let lines = inner.split(|t| t.0 == Token::Newline);
        Block::Lines(lines.filter(|l| !l.is_empty()).map(args).collect())
    } else if matches!(name, "decomposition" | "homomorphism") {
        let mut ps = Vec::new();
        for l in inner.split(|t| t.0 == Token::Newline) {
            if !l.is_empty() {
                ps.extend(production(l, diags));
            }
        }
        Block::Productions(ps)
    } else if name == "sub-lsystem" {
        lsystem_block(inner, diags)
    } else {
        Block::Statements(statements(inner, diags))
    });
    Some(kw)
}

/// The lines of `sub-lsystem N { … }`: productions, and an `ignore` or
/// `consider` line (a line without `->` that starts with either).
fn lsystem_block(inner: &[Tok<'_>], diags: &mut Diagnostics) -> Block {
    let mut productions = Vec::new();
    let mut context = None;
    for l in inner.split(|t| t.0 == Token::Newline) {
        match l {
            [] => {}
            [(Token::Ident(k @ ("ignore" | "consider")), _), rest @ ..]
                if top_level(l, |t| *t == Token::Arrow).is_none() =>
            {
                context = Some((k.to_string(), word(rest, diags)));
            }
            _ => productions.extend(production(l, diags)),
        }
    }
    Block::Lsystem {
        productions,
        context,
    }
}

/// Whether a `seed` line is an STL seed (docs/gft.md §8), not the file's
/// random seed (§4), which is one whole number.
pub fn structure_seed(name: &str, rest: &[Tok<'_>]) -> bool {
    name == "seed" && !matches!(rest, [(Token::Number(_), _)])
}

/// A production line: `[left <] pred [> right] [: [{…}] cond [{…}]] -> succ [: weight] …`.
fn production(line: &[Tok<'_>], diags: &mut Diagnostics) -> Option<Production> {
    let first_arrow = top_level(line, |t| *t == Token::Arrow)?;
    if let Some(d) = long_arrow(line, first_arrow) {
        diags.push(d);
        return None;
    }
    let head = &line[..first_arrow];
    let (lhs, cond) = match top_level(head, |t| t.is(":")) {
        Some(c) => (&head[..c], Some(&head[c + 1..])),
        None => (head, None),
    };
    let lt = top_level(lhs, |t| t.is("<"));
    let gt = top_level(lhs, |t| t.is(">"));
    let (left, mid) = match lt {
        Some(i) => (Some(&lhs[..i]), &lhs[i + 1..]),
        None => (None, lhs),
    };
    let (pred, right) = match gt.map(|g| g.saturating_sub(lt.map_or(0, |l| l + 1))) {
        Some(g) if g < mid.len() => (&mid[..g], Some(&mid[g + 1..])),
        _ => (mid, None),
    };
    if pred.is_empty() {
        diags.push(
            Diagnostic::at(
                codes::MISSING_PREDECESSOR,
                line[first_arrow].1.clone(),
                "missing predecessor",
            )
            .with_label("nothing to rewrite before `->`")
            .with_help("write the symbol this production rewrites: `F -> F+F`"),
        );
        return None;
    }
    let mut p = Production {
        left: left.map(|w| word(w, diags)),
        predecessor: word(pred, diags),
        right: right.map(|w| word(w, diags)),
        before: Vec::new(),
        condition: None,
        after: Vec::new(),
        alternatives: Vec::new(),
        span: span_of(line),
    };
    if let Some(cond) = cond {
        condition(cond, &mut p, diags);
    }
    let mut rest = &line[first_arrow + 1..];
    loop {
        let next = top_level(rest, |t| *t == Token::Arrow).unwrap_or(rest.len());
        let alt = &rest[..next];
        let alt: Vec<Tok<'_>> = alt
            .iter()
            .filter(|t| t.0 != Token::Newline)
            .cloned()
            .collect();
        let (succ, weight) = match top_level(&alt, |t| t.is(":")) {
            Some(c) => (&alt[..c], Some(expression(&alt[c + 1..], diags)?)),
            None => (&alt[..], None),
        };
        p.alternatives.push(Alternative {
            successor: word(succ, diags),
            weight,
        });
        if next == rest.len() {
            break;
        }
        rest = &rest[next + 1..];
    }
    Some(p)
}

/// `[{ statements }] condition [{ statements }]`; the condition may be `*` (none).
fn condition(toks: &[Tok<'_>], p: &mut Production, diags: &mut Diagnostics) {
    let mut toks = toks;
    if toks.first().is_some_and(|t| t.0.is("{")) {
        let close = matching(toks, 0, "{", "}");
        p.before = statements(&toks[1..close], diags);
        toks = toks.get(close + 1..).unwrap_or_default();
    }
    if let Some(open) = toks.iter().position(|t| t.0.is("{")) {
        let close = matching(toks, open, "{", "}");
        p.after = statements(&toks[open + 1..close], diags);
        if close + 1 < toks.len() {
            let span = span_of(&toks[close + 1..]);
            diags.push(
                Diagnostic::at(codes::SYNTAX, span, "text after the statements")
                    .with_label("nothing may follow the statements after the condition")
                    .with_help("write `: {before} condition {after} -> successor`"),
            );
        }
        toks = &toks[..open];
    }
    // cpfg's `*` stands for "no condition" where statements follow it.
    let star = toks.len() == 1 && toks[0].0.is("*");
    if !toks.is_empty() && !star {
        p.condition = expression(toks, diags);
    }
}

/// A word: symbol text, quoted names, guards `p?` and parameter lists.
pub fn word(toks: &[Tok<'_>], diags: &mut Diagnostics) -> Word {
    let mut w = Word {
        pieces: Vec::new(),
        span: span_of(toks),
    };
    let mut i = 0;
    while i < toks.len() {
        let (t, span) = &toks[i];
        match t {
            Token::Newline => {}
            Token::Quoted(q) => w
                .pieces
                .push(Piece::Quoted(q.trim_matches('`').to_string(), span.clone())),
            Token::Number(n)
                if toks
                    .get(i + 1)
                    .is_some_and(|t| t.0.is("?") && t.1.start == span.end) =>
            {
                let p = n.parse().unwrap_or(f64::NAN);
                w.pieces.push(Piece::Guard(p, span.start..span.end + 1));
                i += 1;
            }
            Token::Char("(") => {
                let close = matching(toks, i, "(", ")");
                let inner = &toks[i + 1..close.min(toks.len())];
                let before = diags.len();
                let args = arguments(inner, diags);
                // Parameters cut short mid-expression are reported as such
                // (E0007); a `(` left open after whole ones, here.
                if close >= toks.len() && diags.len() == before {
                    diags.push(unclosed(span, toks));
                }
                w.pieces.push(Piece::Args(
                    args,
                    span.start..toks[close.min(toks.len() - 1)].1.end,
                ));
                i = close;
            }
            Token::Str(_) | Token::Char(":" | "<" | ">" | "=" | "?" | ")") => {
                push_lazily(diags, codes::SYNTAX, || {
                    Diagnostic::at(codes::SYNTAX, span.clone(), format!("unexpected {t}"))
                        .with_label("not a symbol")
                        .with_help("a symbol with this name is written in backquotes: `` `<` ``")
                });
            }
            // Text written without space between its tokens is one piece,
            // split later by the longest declared name (`+b`, `.5@`).
            t => match w.pieces.last_mut() {
                Some(Piece::Text(text, at)) if at.end == span.start => {
                    text.push_str(t.text());
                    at.end = span.end;
                }
                _ => w
                    .pieces
                    .push(Piece::Text(t.text().to_string(), span.clone())),
            },
        }
        i += 1;
    }
    w
}

/// pfg's arrow `-->`, which `.gft` reads as a `-` ending the predecessor
/// and then `->`: refused when the `-` touches the arrow at `arrow`.
fn long_arrow(line: &[Tok<'_>], arrow: usize) -> Option<Diagnostic> {
    let (dash, at) = (&line[arrow.checked_sub(1)?], &line[arrow].1);
    if !dash.0.is("-") || dash.1.end != at.start {
        return None;
    }
    let span = dash.1.start..at.end;
    Some(
        Diagnostic::at(
            codes::GFT_LONG_ARROW,
            span.clone(),
            "`-->` is not `.gft`'s arrow",
        )
        .with_label("reads as a `-` then `->`")
        .with_note("pfg and cpfg write `-->`; a production for `-` writes a space before `->`")
        .with_fix(span, "->".into(), "write `->`".into()),
    )
}

/// The error for the `(` at `open` that nothing in `toks` closes.
fn unclosed(open: &Span, toks: &[Tok<'_>]) -> Diagnostic {
    let end = toks.last().map_or(open.end, |t| t.1.end);
    Diagnostic::at(codes::GFT_UNCLOSED, open.clone(), "`(` is never closed")
        .with_label("these parameters have no `)`")
        .with_secondary(end..end, "the item ends here")
        .with_help("close the parameters with `)`")
}

/// The index of the `close` that closes the `open` at `at` (or the end).
fn matching(toks: &[Tok<'_>], at: usize, open: &str, close: &str) -> usize {
    let mut depth = 0;
    for (k, (t, _)) in toks.iter().enumerate().skip(at) {
        if t.is(open) {
            depth += 1;
        } else if t.is(close) {
            depth -= 1;
            if depth == 0 {
                return k;
            }
        }
    }
    toks.len()
}

fn input<'s>(toks: &[Tok<'s>]) -> Vec<(Token<'s>, SimpleSpan)> {
    toks.iter()
        .filter(|t| t.0 != Token::Newline)
        .map(|(t, s)| (*t, SimpleSpan::from(s.clone())))
        .collect()
}

fn report(errors: Vec<Rich<'_, Token<'_>>>, diags: &mut Diagnostics) {
    push_syntax_errors(diags, errors, |_| None);
}

/// One expression filling `toks`.
pub fn expression(toks: &[Tok<'_>], diags: &mut Diagnostics) -> Option<Expr> {
    let toks = input(toks);
    let eoi = SimpleSpan::from(toks.last().map_or(0..0, |t| t.1.end..t.1.end));
    let (e, errors) = expr_parser()
        .then_ignore(end())
        .parse(toks.as_slice().map(eoi, |(t, s)| (t, s)))
        .into_output_errors();
    report(errors, diags);
    e
}

/// Expressions separated by commas.
fn arguments(toks: &[Tok<'_>], diags: &mut Diagnostics) -> Vec<Expr> {
    let toks = input(toks);
    let eoi = SimpleSpan::from(toks.last().map_or(0..0, |t| t.1.end..t.1.end));
    let (e, errors) = expr_parser()
        .separated_by(just(Token::Char(",")))
        .collect::<Vec<_>>()
        .then_ignore(end())
        .parse(toks.as_slice().map(eoi, |(t, s)| (t, s)))
        .into_output_errors();
    report(errors, diags);
    e.unwrap_or_default()
}

/// Statements `x = e; a[i] = e; e; if (c) {…} else {…} while (c) {…} do {…} while (c);`.
fn statements(toks: &[Tok<'_>], diags: &mut Diagnostics) -> Vec<Stmt> {
    let toks = input(toks);
    let eoi = SimpleSpan::from(toks.last().map_or(0..0, |t| t.1.end..t.1.end));
    let (s, errors) = stmt_parser()
        .repeated()
        .collect::<Vec<_>>()
        .then_ignore(end())
        .parse(toks.as_slice().map(eoi, |(t, s)| (t, s)))
        .into_output_errors();
    report(errors, diags);
    s.unwrap_or_default()
}

fn ch<'t, 's: 't, I>(c: &'static str) -> impl Parser<'t, I, Token<'s>, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    just(Token::Char(c))
}

fn stmt_parser<'t, 's: 't, I>() -> impl Parser<'t, I, Stmt, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    recursive(|stmt| {
        let block = stmt
            .clone()
            .repeated()
            .collect::<Vec<_>>()
            .delimited_by(ch("{"), ch("}"));
        let cond = expr_parser().delimited_by(ch("("), ch(")"));
        let kw = |k: &'static str| just(Token::Ident(k));
        let if_ = kw("if")
            .ignore_then(cond.clone())
            .then(block.clone())
            .then(kw("else").ignore_then(block.clone()).or_not())
            .map(|((c, a), b)| Stmt::If(c, a, b.unwrap_or_default()));
        let while_ = kw("while")
            .ignore_then(cond.clone())
            .then(block.clone())
            .map(|(c, b)| Stmt::While(c, b));
        let do_ = kw("do")
            .ignore_then(block)
            .then_ignore(kw("while"))
            .then(cond)
            .then_ignore(ch(";"))
            .map(|(b, c)| Stmt::Do(b, c));
        let name = select! { Token::Ident(n) => n.to_string() };
        let assign = name
            .then(
                expr_parser()
                    .delimited_by(ch("["), ch("]"))
                    .repeated()
                    .collect::<Vec<_>>(),
            )
            .then_ignore(ch("="))
            .then(expr_parser())
            .then_ignore(ch(";"))
            .map_with(|((name, index), value), e| Stmt::Assign {
                name,
                index,
                value,
                span: {
                    let span: SimpleSpan = e.span();
                    span.into_range()
                },
            });
        let expr_stmt = expr_parser().then_ignore(ch(";")).map(Stmt::Expr);
        choice((if_, while_, do_, assign, expr_stmt)).boxed()
    })
}

/// Binary operators from the loosest to the tightest.
const LEVELS: &[&[&str]] = &[
    &["||"],
    &["&&"],
    &["==", "!="],
    &["<", "<=", ">", ">="],
    &["+", "-"],
    &["*", "/", "%"],
    &["^"],
];

fn fold(first: Expr, rest: Vec<(String, Expr)>) -> Expr {
    // Precedence climbing over a flat list (`^` right-associative).
    let mut operands = vec![first];
    let mut ops: Vec<String> = Vec::new();
    let level = |op: &str| LEVELS.iter().position(|l| l.contains(&op)).unwrap_or(0);
    let reduce = |operands: &mut Vec<Expr>, op: String| {
        let b = operands.pop().expect("two operands");
        let a = operands.pop().expect("two operands");
        let span = a.span.start..b.span.end;
        operands.push(Expr {
            kind: ExprKind::Binary(op, Box::new(a), Box::new(b)),
            span,
        });
    };
    for (op, e) in rest {
        while let Some(top) = ops.last() {
            let (lt, lo) = (level(top), level(&op));
            if lt > lo || (lt == lo && op != "^") {
                let top = ops.pop().expect("an operator");
                reduce(&mut operands, top);
            } else {
                break;
            }
        }
        ops.push(op);
        operands.push(e);
    }
    while let Some(op) = ops.pop() {
        reduce(&mut operands, op);
    }
    operands.pop().expect("an operand")
}

pub fn expr_parser<'t, 's: 't, I>() -> impl Parser<'t, I, Expr, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    recursive(|expr| {
        let leaf = |kind: ExprKind, span: SimpleSpan| Expr {
            kind,
            span: span.into_range(),
        };
        let list = expr
            .clone()
            .separated_by(ch(","))
            .collect::<Vec<_>>()
            .delimited_by(ch("("), ch(")"));
        let subscripts = expr
            .clone()
            .delimited_by(ch("["), ch("]"))
            .repeated()
            .at_least(1)
            .collect::<Vec<_>>();
        let name = select! { Token::Ident(n) => n.to_string() };
        let atom = choice((
            select! { Token::Number(n) => n }
                .try_map(|n: &str, span| {
                    n.parse::<f64>()
                        .map_err(|_| Rich::custom(span, "bad number"))
                })
                .map_with(move |v, e| leaf(ExprKind::Num(v), e.span())),
            select! { Token::Str(s) => s.trim_matches('"').to_string() }
                .map_with(move |s, e| leaf(ExprKind::Str(s), e.span())),
            name.then(list)
                .map_with(move |(n, a), e| leaf(ExprKind::Call(n, a), e.span())),
            name.then(subscripts)
                .map_with(move |(n, s), e| leaf(ExprKind::Element(n, s), e.span())),
            name.map_with(move |n, e| leaf(ExprKind::Name(n), e.span())),
            expr.clone().delimited_by(ch("("), ch(")")),
        ))
        .labelled("an expression");
        let unary = select! { Token::Char("-") => "-", Token::Char("!") => "!" }
            .map_with(|op, e| {
                let span: SimpleSpan = e.span();
                (op, span.into_range())
            })
            .repeated()
            .foldr(atom, |(op, at): (&'static str, Span), rhs: Expr| {
                let span = at.start..rhs.span.end;
                Expr {
                    kind: ExprKind::Unary(op, Box::new(rhs)),
                    span,
                }
            });
        let operator = select! {
            Token::Op2(o) => o.to_string(),
            Token::Char(c) if matches!(c, "+" | "-" | "*" | "/" | "%" | "^" | "<" | ">") => c.to_string(),
        };
        let operations = unary
            .clone()
            .then(operator.then(unary).repeated().collect::<Vec<_>>())
            .map(|(first, rest)| fold(first, rest));
        operations
            .then(
                ch("?")
                    .ignore_then(expr.clone())
                    .then_ignore(ch(":"))
                    .then(expr)
                    .or_not(),
            )
            .map(|(c, rest)| match rest {
                None => c,
                Some((a, b)) => {
                    let span = c.span.start..b.span.end;
                    Expr {
                        kind: ExprKind::Cond(Box::new(c), Box::new(a), Box::new(b)),
                        span,
                    }
                }
            })
            .boxed()
    })
}
