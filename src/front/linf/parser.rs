//! The LinF parser (chumsky 0.12 over logos tokens).
//!
//! A file is a run of blocks; a block runs from its keyword to the next
//! keyword. Inside a block the parser reads the block's items (names,
//! rotations, rules, colours, a string) and, when an item is malformed,
//! reports it and skips to the next place an item can start, so that every
//! error of a file is reported in one run and the parser never fails. Checks
//! that need the whole file (declared names, values of expressions, balance
//! of brackets) are lowering's ([`super::lower`]).

use super::ast::{
    BinOp, Block, BlockBody, ColourDecl, Component, Directive, Expr, ExprKind, File, Item, Name,
    RotationDecl, Rule,
};
use super::lexer::{lex, BlockKind, Token};
use crate::diagnostics::{codes, nearest, Diagnostic, Diagnostics};
use crate::front::depth::{cut_too_deep, parenthesized, too_deep, Nest};
use crate::front::repeats::Repeats;
use crate::ir::Span;
use chumsky::input::ValueInput;
use chumsky::prelude::*;

type Extra<'t, 's> = extra::Err<Rich<'t, Token<'s>>>;

/// A rule as the parser meets it: a proper rule, or `+ = …`, a rule for a
/// reserved symbol (reported by [`parse`]).
#[derive(Clone, Debug)]
enum RawRule {
    Rule(Rule),
    Reserved { token: String, span: Span },
}

/// A block's contents before the checks of [`parse`]. `None` items are
/// malformed ones the parser skipped (and reported).
#[derive(Clone, Debug)]
enum RawBody {
    Names(Vec<Option<Name>>),
    Angles(Vec<Option<RotationDecl>>),
    /// The string, then any `name = …` rules written in the axiom block.
    Axiom(Vec<Option<Item>>, Vec<Rule>),
    Rules(Vec<Option<RawRule>>),
    Colors(Vec<Option<ColourDecl>>),
}

fn range(s: SimpleSpan) -> Span {
    s.into_range()
}

fn not_keyword(t: &Token<'_>) -> bool {
    !matches!(t, Token::Keyword(_))
}

/// One or more tokens that are not keywords, stopping before `stop` (always
/// taking the first): what recovery skips after a malformed item.
fn junk<'t, 's: 't, I>(
    stop: impl Parser<'t, I, (), Extra<'t, 's>> + Clone,
) -> impl Parser<'t, I, (), Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let other = any().filter(not_keyword);
    other
        .ignored()
        .then(other.and_is(stop.not()).repeated())
        .ignored()
}

/// Arithmetic over `atom`: unary signs, `*` `/`, then `+` `-`. With
/// `tight_signs`, a sign that looks like a prefix (`[0 -pi]`) is not taken
/// as a binary operator, so two expressions can stand side by side.
fn arithmetic<'t, 's: 't, I>(
    atom: impl Parser<'t, I, Expr, Extra<'t, 's>> + Clone,
    tight_signs: bool,
) -> impl Parser<'t, I, Expr, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let unary = select! { Token::Minus(_) => true, Token::Plus(_) => false }
        .map_with(|minus, e| (minus, range(e.span())))
        .repeated()
        .foldr(atom, |(minus, at), rhs: Expr| {
            let span = at.start..rhs.span.end;
            if minus {
                Expr::operation(ExprKind::Neg(Box::new(rhs)), span, at)
            } else if rhs.is_cut() {
                rhs
            } else {
                Expr { span, ..rhs }
            }
        });
    let binary = |lhs: Expr, ((op, at), rhs): ((BinOp, Span), Expr)| {
        let span = lhs.span.start..rhs.span.end;
        Expr::operation(ExprKind::Binary(op, Box::new(lhs), Box::new(rhs)), span, at)
    };
    let product = unary.clone().foldl(
        select! { Token::Star => BinOp::Mul, Token::Slash => BinOp::Div }
            .map_with(|op, e| (op, range(e.span())))
            .then(unary)
            .repeated(),
        binary,
    );
    let sum_op = select! {
        Token::Plus(prefix) if !(tight_signs && prefix) => BinOp::Add,
        Token::Minus(prefix) if !(tight_signs && prefix) => BinOp::Sub,
    }
    .map_with(|op, e| (op, range(e.span())));
    product
        .clone()
        .foldl(sum_op.then(product).repeated(), binary)
        .labelled("an expression")
}

/// A block as the parser returns it: kind, keyword span, contents, and the
/// tokens after the contents that no item could take.
type RawBlock<'s> = (BlockKind, Span, RawBody, Vec<(Token<'s>, SimpleSpan)>);

/// A file: the tokens before the first block (reported by `parse`), then
/// the blocks.
fn file_parser<'t, 's: 't, I>(
) -> impl Parser<'t, I, (Vec<(Token<'s>, SimpleSpan)>, Vec<RawBlock<'s>>), Extra<'t, 's>>
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    stray_tokens()
        .then(block().repeated().collect::<Vec<_>>())
        .then_ignore(end())
}

/// Tokens up to the next keyword, with their spans.
fn stray_tokens<'t, 's: 't, I>(
) -> impl Parser<'t, I, Vec<(Token<'s>, SimpleSpan)>, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    any()
        .filter(not_keyword)
        .map_with(|t, e| (t, e.span()))
        .repeated()
        .collect::<Vec<_>>()
}

/// A block: its keyword, the items its kind holds, then whatever no item
/// could take (reported by `parse`).
fn block<'t, 's: 't, I>() -> impl Parser<'t, I, RawBlock<'s>, Extra<'t, 's>>
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let keyword =
        |kind: BlockKind| just(Token::Keyword(kind)).map_with(move |_, e| (kind, range(e.span())));
    choice((
        keyword(BlockKind::Lines).then(names_body()),
        keyword(BlockKind::Blanks).then(names_body()),
        keyword(BlockKind::Angles).then(angles_body()),
        keyword(BlockKind::Axiom).then(axiom_body()),
        keyword(BlockKind::Rules).then(rules_body()),
        keyword(BlockKind::Colors).then(colors_body()),
    ))
    .then(stray_tokens())
    .map(|(((kind, span), body), leftover)| (kind, span, body, leftover))
}

/// The items of a block, each `None` when it is malformed: reported, then
/// skipped up to where `start` says the next item can start.
fn items<'t, 's: 't, I, T>(
    item: impl Parser<'t, I, T, Extra<'t, 's>> + Clone,
    start: impl Parser<'t, I, (), Extra<'t, 's>> + Clone,
) -> impl Parser<'t, I, Vec<Option<T>>, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    item.map(Some)
        .recover_with(via_parser(junk(start).map(|_| None)))
        .repeated()
        .collect::<Vec<_>>()
}

fn name<'t, 's: 't, I>() -> impl Parser<'t, I, Name, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    select! { Token::Name(s) => s }.map_with(|s, e| Name {
        text: s.to_string(),
        span: range(e.span()),
    })
}

/// A number's value and span.
fn number<'t, 's: 't, I>() -> impl Parser<'t, I, (f64, Span), Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    select! { Token::Number(s) => s }
        .map_with(|s: &str, e| (s.parse::<f64>().unwrap_or(f64::NAN), range(e.span())))
}

/// An arithmetic expression.
fn expression<'t, 's: 't, I>() -> impl Parser<'t, I, Expr, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    recursive(|expr| arithmetic(operand(expr).labelled("a number"), false))
}

/// What arithmetic is made of: a number, a name, or `expr` in parentheses.
fn operand<'t, 's: 't, I>(
    expr: impl Parser<'t, I, Expr, Extra<'t, 's>> + Clone,
) -> impl Parser<'t, I, Expr, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    choice((
        number().map(|(v, span)| Expr::leaf(ExprKind::Number(v), span)),
        name().map(|n| Expr::leaf(ExprKind::Name(n.text), n.span)),
        just(Token::TooDeep).map_with(|_, e| Expr::cut(range(e.span()))),
        expr.delimited_by(just(Token::LParen), just(Token::RParen))
            .map_with(|inner: Expr, e| parenthesized(inner, range(e.span()))),
    ))
}

/// A names block (`lines`, `blanks`): names; anything else is skipped to
/// the next name.
fn names_body<'t, 's: 't, I>() -> impl Parser<'t, I, RawBody, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    items(name(), select! { Token::Name(_) => () }).map(RawBody::Names)
}

/// The `angles` block: rotations, each starting with `(` or `name =`.
fn angles_body<'t, 's: 't, I>() -> impl Parser<'t, I, RawBody, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let rotation_start = just(Token::LParen)
        .ignored()
        .or(name().then(just(Token::Eq)).ignored());
    items(rotation(), rotation_start).map(RawBody::Angles)
}

/// A group `(…)` or `[…]` skipped whole, groups inside it included: how
/// recovery passes over a malformed rotation or colour. Any closer ends
/// the innermost group, as the depth limit counts them, and
/// [`close_value_groups`] has closed every group before its block ends:
/// so the skip never fails and never leaves its block, and each token is
/// skipped at most once (reading to the end of the file for each unclosed
/// `(` made a file of `angles (` blocks take seconds).
fn skipped_group<'t, 's: 't, I>() -> impl Parser<'t, I, (), Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    recursive(|group| {
        let inside = any().filter(|t: &Token| {
            !matches!(
                t,
                Token::Keyword(_)
                    | Token::LParen
                    | Token::RParen
                    | Token::LBracket
                    | Token::RBracket
            )
        });
        just(Token::LParen)
            .or(just(Token::LBracket))
            .ignore_then(group.or(inside.ignored()).repeated())
            .then_ignore(just(Token::RParen).or(just(Token::RBracket)))
            .ignored()
    })
}

/// A rotation `(torsion, curvature)`, named `t = (…)` or not.
fn rotation<'t, 's: 't, I>() -> impl Parser<'t, I, RotationDecl, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    name()
        .then_ignore(just(Token::Eq))
        .or_not()
        .then(
            component()
                .separated_by(just(Token::Comma))
                .collect::<Vec<_>>()
                .map(Some)
                .delimited_by(just(Token::LParen), just(Token::RParen))
                // A malformed pair is reported and skipped to its `)`, and
                // the name stays declared (no cascade at its uses).
                .recover_with(via_parser(skipped_group().map(|_| None)))
                .map_with(|c, e| (c, range(e.span())))
                .labelled("a rotation `(torsion, curvature)`"),
        )
        .map(|(name, (components, span))| RotationDecl {
            name,
            recovered: components.is_none(),
            components: components.unwrap_or_default(),
            span,
        })
}

/// A component of a rotation: an interval `[lo hi]` or one expression.
fn component<'t, 's: 't, I>() -> impl Parser<'t, I, Component, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let expr = expression();
    // A sign before the high end starts it: `[0 -pi]`.
    let low_end = arithmetic(operand(expr.clone()), true);
    let interval = low_end
        .then_ignore(just(Token::Comma).or_not())
        .then(expr.clone())
        .delimited_by(just(Token::LBracket), just(Token::RBracket))
        .map_with(|(lo, hi), e| Component::Interval {
            lo,
            hi,
            span: range(e.span()),
        })
        .labelled("an interval `[lo hi]`");
    interval.or(expr.map(Component::Value))
}

/// Whether a token can stand in a string.
fn is_string_token(t: &Token<'_>) -> bool {
    matches!(
        t,
        Token::Name(_)
            | Token::Plus(_)
            | Token::Minus(_)
            | Token::Number(_)
            | Token::Question
            | Token::At
            | Token::LBracket
            | Token::RBracket
            | Token::LBrace
            | Token::RBrace
            | Token::Bang
    )
}

/// A token that can stand in a string.
fn string_token<'t, 's: 't, I>() -> impl Parser<'t, I, Token<'s>, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    any().filter(is_string_token)
}

/// The symbol a string token at `span` stands for.
fn string_symbol(t: Token<'_>, span: Span) -> Item {
    match t {
        Token::Name(s) => Item::Name(Name {
            text: s.to_string(),
            span,
        }),
        Token::Plus(_) => Item::Sign { minus: false, span },
        Token::Minus(_) => Item::Sign { minus: true, span },
        Token::Number(s) => Item::Number {
            value: s.parse().unwrap_or(f64::NAN),
            text: s.to_string(),
            span,
        },
        Token::Question => Item::Question(span),
        Token::At => Item::At(span),
        Token::LBracket => Item::Open(span),
        Token::RBracket => Item::Close(span),
        Token::LBrace => Item::NextColour(span),
        Token::RBrace => Item::PreviousColour(span),
        _ => Item::Swap(span),
    }
}

/// A symbol of a string. A token followed by `=` starts the next rule.
fn string_item<'t, 's: 't, I>() -> impl Parser<'t, I, Item, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    string_token()
        .and_is(any().then(just(Token::Eq)).not())
        .map_with(|t: Token, e| string_symbol(t, range(e.span())))
        .labelled("a symbol")
}

/// The symbols of a string, up to a token that cannot stand in one or one
/// followed by `=` (which starts the next rule). They are read in a loop:
/// per symbol, the lookahead of [`string_item`] costs more than the rest
/// of reading a file (a string of a million symbols took half a second).
/// [`string_item`] then fails where the loop stopped, so that an error
/// there expects a symbol, as it would after a string read item by item.
fn string<'t, 's: 't, I>() -> impl Parser<'t, I, Vec<Item>, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let run = custom(|inp| {
        let mut items = Vec::new();
        loop {
            let start = inp.cursor();
            match inp.peek() {
                Some(t) if is_string_token(&t) => {
                    let before = inp.save();
                    inp.skip();
                    if inp.peek() == Some(Token::Eq) {
                        inp.rewind(before);
                        break;
                    }
                    items.push(string_symbol(t, range(inp.span_since(&start))));
                }
                _ => break,
            }
        }
        Ok(items)
    });
    run.then(string_item().repeated().collect::<Vec<_>>())
        .map(|(mut run, rest)| {
            run.extend(rest);
            run
        })
}

/// A rule `name = string`.
fn rule<'t, 's: 't, I>() -> impl Parser<'t, I, Rule, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    name()
        .then_ignore(just(Token::Eq))
        .then(string())
        .map(|(head, body): (Name, Vec<Item>)| {
            let end = body.last().map_or(head.span.end + 1, |i| i.span().end);
            Rule {
                span: head.span.start..end,
                head,
                body,
            }
        })
}

/// The `axiom` block: a string. A `name = …` in it is a rule written
/// without the `rules` keyword: parsed as a rule, reported by `parse`.
fn axiom_body<'t, 's: 't, I>() -> impl Parser<'t, I, RawBody, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let start = string_token()
        .ignored()
        .or(name().then(just(Token::Eq)).ignored());
    let symbols = string_item().then(string()).map(|(first, mut rest)| {
        rest.insert(0, first);
        rest
    });
    items(rule().map(Err).or(symbols.map(Ok)), start).map(|all| {
        let mut symbols = Vec::new();
        let mut rules = Vec::new();
        for part in all.into_iter().flatten() {
            match part {
                Ok(run) => symbols.extend(run.into_iter().map(Some)),
                Err(rule) => rules.push(rule),
            }
        }
        RawBody::Axiom(symbols, rules)
    })
}

/// The `rules` block: rules, each starting with a token and `=`.
fn rules_body<'t, 's: 't, I>() -> impl Parser<'t, I, RawBody, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    // Only a token that can head a rule starts one: a run of stray `=`
    // is one mistake.
    let rule_start = string_token().then(just(Token::Eq)).ignored();
    items(rule().map(RawRule::Rule).or(reserved_rule()), rule_start).map(RawBody::Rules)
}

/// A rule for a reserved symbol, `+ = …` (reported by `parse`).
fn reserved_rule<'t, 's: 't, I>() -> impl Parser<'t, I, RawRule, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    any()
        .filter(|t: &Token| {
            matches!(
                t,
                Token::Plus(_)
                    | Token::Minus(_)
                    | Token::LBracket
                    | Token::RBracket
                    | Token::LBrace
                    | Token::RBrace
                    | Token::Bang
                    | Token::Question
                    | Token::At
            )
        })
        .map_with(|t: Token, e| RawRule::Reserved {
            token: t.to_string(),
            span: range(e.span()),
        })
        .then_ignore(just(Token::Eq))
        .then(string())
        .map(|(r, _)| r)
}

/// The `colors` block: colours, each starting with `(` or `label:`.
fn colors_body<'t, 's: 't, I>() -> impl Parser<'t, I, RawBody, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let colour_start = just(Token::LParen)
        .ignored()
        .or(number().then(just(Token::Colon)).ignored());
    // A malformed colour is reported and skipped to its `)`.
    let colour = colour()
        .map(Some)
        .recover_with(via_parser(skipped_group().map(|_| None)));
    items(colour, colour_start).map(|c| RawBody::Colors(c.into_iter().flatten().collect()))
}

/// A colour `(r, g, b)`, with an optional label `n:`.
fn colour<'t, 's: 't, I>() -> impl Parser<'t, I, ColourDecl, Extra<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    number()
        .then_ignore(just(Token::Colon))
        .or_not()
        .then(
            expression()
                .separated_by(just(Token::Comma))
                .collect::<Vec<_>>()
                .delimited_by(just(Token::LParen), just(Token::RParen))
                .map_with(|c, e| (c, range(e.span())))
                .labelled("a colour `(r, g, b)`"),
        )
        .map(|(label, (components, span))| ColourDecl {
            label,
            components,
            span,
        })
}

/// Parses LinF source text into an AST. Never fails: problems are pushed to
/// `diags` and malformed items are left out of the AST.
pub fn parse(src: &str, diags: &mut Diagnostics) -> File {
    let mut lexed = lex(src, diags);
    respell_keywords(src, &mut lexed.tokens, diags);
    let tokens = close_value_groups(cut_nesting(lexed.tokens), diags);
    let eoi = SimpleSpan::from(src.len()..src.len());
    let (out, errors) = file_parser()
        .parse(tokens.as_slice().map(eoi, |(t, s, _)| (t, s)))
        .into_output_errors();
    report_syntax_errors(src, errors, diags);
    let mut file = File {
        blocks: Vec::new(),
        directives: lexed
            .directives
            .into_iter()
            .map(|d| Directive {
                text: d.text.to_string(),
                span: d.span,
            })
            .collect(),
    };
    let Some((preamble, blocks)) = out else {
        return file;
    };
    if let (Some(first), Some(last)) = (preamble.first(), preamble.last()) {
        diags.push(text_before_first_block(first.0, first.1.start..last.1.end));
    }
    for (kind, keyword, body, leftover) in blocks {
        if let (Some(first), Some(last)) = (leftover.first(), leftover.last()) {
            diags.push(
                Diagnostic::at(
                    codes::SYNTAX,
                    first.1.start..last.1.end,
                    format!("unexpected {} in the `{}` block", first.0, kind.keyword()),
                )
                .with_label("not part of any item")
                .with_help(block_help(kind)),
            );
        }
        let body = match body {
            RawBody::Names(names) => BlockBody::Names(names.into_iter().flatten().collect()),
            RawBody::Angles(r) => {
                let mut r: Vec<RotationDecl> = r.into_iter().flatten().collect();
                for rotation in &mut r {
                    let exprs = rotation.components.iter_mut().flat_map(|c| match c {
                        Component::Value(e) => vec![e],
                        Component::Interval { lo, hi, .. } => vec![lo, hi],
                    });
                    report_cuts(exprs, diags);
                }
                BlockBody::Angles(r)
            }
            RawBody::Colors(c) => {
                let mut c: Vec<ColourDecl> = c.into_iter().flatten().collect();
                for colour in &mut c {
                    report_cuts(colour.components.iter_mut(), diags);
                }
                BlockBody::Colors(c)
            }
            RawBody::Axiom(items, rules) => {
                for r in &rules {
                    diags.push(
                        Diagnostic::at(
                            codes::LINF_RULE_IN_AXIOM,
                            r.head.span.start..r.head.span.end,
                            format!("a rule for `{}` in the axiom block", r.head.text),
                        )
                        .with_label("the axiom ends before this rule")
                        .with_secondary(keyword.clone(), "the axiom block starts here")
                        .with_help("start the rules with the keyword `rules`"),
                    );
                }
                BlockBody::Axiom(items.into_iter().flatten().collect())
            }
            RawBody::Rules(rules) => {
                let mut out = Vec::new();
                for r in rules.into_iter().flatten() {
                    match r {
                        RawRule::Rule(r) => out.push(r),
                        RawRule::Reserved { token, span } => diags.push(
                            Diagnostic::at(
                                codes::LINF_RESERVED_RULE,
                                span,
                                format!("a rule for the reserved symbol {token}"),
                            )
                            .with_label("reserved: its meaning is fixed")
                            .with_help(
                                "only names can have rules; `[ ] @ ? + - { } !` are LinF's reserved symbols",
                            ),
                        ),
                    }
                }
                BlockBody::Rules(out)
            }
        };
        file.blocks.push(Block {
            kind,
            keyword,
            body,
        });
    }
    file
}

/// Reports the parser's errors, each mistake once (recovery may meet one
/// twice), and a mistake repeated along a line a few times, then counted
/// ([`Repeats`]).
fn report_syntax_errors(src: &str, mut errors: Vec<Rich<'_, Token<'_>>>, diags: &mut Diagnostics) {
    errors.sort_by_key(|e| e.span().start);
    let mut seen = std::collections::HashSet::new();
    let mut repeats = Repeats::default();
    let mut last = 0;
    for err in errors {
        let span = range(*err.span());
        if !seen.insert((span.start, span.end)) {
            continue;
        }
        if src[last..span.start].contains('\n') {
            repeats.end_item(diags, "on this line");
        }
        last = span.start;
        let code = match err.found() {
            Some(Token::TooDeep) => codes::NESTED_TOO_DEEPLY,
            Some(_) => codes::SYNTAX,
            None => codes::UNEXPECTED_EOF,
        };
        repeats.report(diags, code, || match err.found() {
            Some(Token::TooDeep) => too_deep(span, DEPTH_HELP),
            _ => syntax_error(&err),
        });
    }
    repeats.end_item(diags, "on this line");
}

/// How to keep a LinF value within the depth limit.
const DEPTH_HELP: &str = "write the value with fewer parentheses and operations, or as a number";

/// `tokens` with what the `angles` and `colors` blocks nest past the depth
/// limit cut out (see [`cut_too_deep`]): the expression parser and the
/// recovery of a malformed rotation recurse into parentheses and brackets,
/// which nest only there (a string's brackets are branches, read without
/// recursion).
fn cut_nesting<'s>(tokens: Vec<(Token<'s>, Span)>) -> Vec<Tagged<'s>> {
    let mut in_values = false;
    let tagged: Vec<Tagged<'s>> = tokens
        .into_iter()
        .map(|(t, s)| {
            let nest = match t {
                Token::Keyword(k) => {
                    in_values = matches!(k, BlockKind::Angles | BlockKind::Colors);
                    Nest::Reset
                }
                Token::LParen | Token::LBracket if in_values => Nest::Open,
                Token::RParen | Token::RBracket if in_values => Nest::Close,
                _ => Nest::Other,
            };
            (t, SimpleSpan::from(s), nest)
        })
        .collect();
    let filler = |&(_, s, _): &Tagged<'s>| vec![(Token::TooDeep, s, Nest::Other)];
    let closer = |&(t, s, _): &Tagged<'s>| (closer_of(t), s, Nest::Close);
    cut_too_deep(&tagged, |t| t.2, filler, closer).unwrap_or(tagged)
}

/// A token with what it does to the nesting of values (see
/// [`cut_nesting`]).
type Tagged<'s> = (Token<'s>, SimpleSpan, Nest);

/// The closer of the group `opener` opens.
fn closer_of(opener: Token<'_>) -> Token<'_> {
    if opener == Token::LBracket {
        Token::RBracket
    } else {
        Token::RParen
    }
}

/// `tokens` with every group `(…)` or `[…]` of an `angles` or `colors`
/// block closed before the block ends: a group still open at the next
/// keyword (or the end of the file) is reported, once per block at the
/// outermost, and closed there, so that the rotation or colour reads as
/// far as it goes and the recovery of a malformed one ([`skipped_group`])
/// stays within its block. As for the depth limit, any closer closes the
/// innermost group.
fn close_value_groups<'s>(tokens: Vec<Tagged<'s>>, diags: &mut Diagnostics) -> Vec<Tagged<'s>> {
    // Each block that ends with groups open: where it ends (its next
    // keyword, or the end), its kind, and the openers.
    let mut unclosed: Vec<(usize, BlockKind, Vec<usize>)> = Vec::new();
    let mut block = None;
    let mut open: Vec<usize> = Vec::new();
    for (i, (t, _, nest)) in tokens.iter().enumerate() {
        match nest {
            Nest::Open => open.push(i),
            Nest::Close => {
                open.pop();
            }
            _ => {}
        }
        if let Token::Keyword(k) = t {
            if let (Some(b), false) = (block, open.is_empty()) {
                unclosed.push((i, b, std::mem::take(&mut open)));
            }
            block = Some(*k);
        }
    }
    if let (Some(b), false) = (block, open.is_empty()) {
        unclosed.push((tokens.len(), b, open));
    }
    if unclosed.is_empty() {
        return tokens;
    }
    let mut out =
        Vec::with_capacity(tokens.len() + unclosed.iter().map(|u| u.2.len()).sum::<usize>());
    let mut from = 0;
    for (end, block, openers) in unclosed {
        out.extend_from_slice(&tokens[from..end]);
        from = end;
        let (opener, at, _) = tokens[openers[0]];
        let block_end = out.last().map_or(at.end, |t| t.1.end);
        let ends = match tokens.get(end) {
            Some((keyword, _, _)) => {
                format!("the `{}` block ends before the {keyword}", block.keyword())
            }
            None => "the file ends here".to_string(),
        };
        diags.push(
            Diagnostic::at(codes::SYNTAX, range(at), format!("unclosed {opener}"))
                .with_label("never closed")
                .with_secondary(block_end..block_end, ends)
                .with_help(format!("close it with {}", closer_of(opener))),
        );
        let here = SimpleSpan::from(block_end..block_end);
        out.extend(
            openers
                .iter()
                .rev()
                .map(|&k| (closer_of(tokens[k].0), here, Nest::Close)),
        );
    }
    out.extend_from_slice(&tokens[from..]);
    out
}

/// Reports the first cut among `exprs` (the values of one rotation or
/// colour, see [`Expr::operation`]) and replaces each with 0, so that
/// lowering reads them without further complaint. A cut is carried up to
/// the root of its expression.
fn report_cuts<'a>(exprs: impl Iterator<Item = &'a mut Expr>, diags: &mut Diagnostics) {
    let mut reported = false;
    for e in exprs.filter(|e| e.is_cut()) {
        if !std::mem::replace(&mut reported, true) {
            diags.push(too_deep(e.span.clone(), DEPTH_HELP));
        }
        *e = Expr::leaf(ExprKind::Number(0.0), e.span.clone());
    }
}

/// What a block holds, for help lines.
fn block_help(kind: BlockKind) -> &'static str {
    match kind {
        BlockKind::Lines | BlockKind::Blanks => "this block holds names separated by spaces",
        BlockKind::Angles => {
            "this block holds rotations `(torsion, curvature)`, named `t = (…, …)` or not"
        }
        BlockKind::Axiom => "this block holds one string of symbols",
        BlockKind::Rules => "this block holds rules `name = string`",
        BlockKind::Colors => "this block holds colours `(r, g, b)`",
    }
}

/// Reads a name that starts a line, is close to a block keyword and is
/// followed by `(` (as `angles (0, pi/2)` is) as that keyword, and reports
/// it once: else the block is not read and every name it declares is
/// reported as undeclared. No block holds a name followed by `(`, so a
/// correct file is never read otherwise.
fn respell_keywords<'a>(src: &str, tokens: &mut [(Token<'a>, Span)], diags: &mut Diagnostics) {
    let keywords: Vec<&str> = BlockKind::ALL.iter().map(|k| k.keyword()).collect();
    for i in 0..tokens.len() {
        let (Token::Name(n), span) = &tokens[i] else {
            continue;
        };
        let starts_line = i == 0 || src[tokens[i - 1].1.end..span.start].contains(['\n', '\r']);
        let paren_follows = matches!(tokens.get(i + 1), Some((Token::LParen, _)));
        let near = nearest(n, &keywords);
        let Some(kind) = BlockKind::ALL
            .iter()
            .find(|k| near.first() == Some(&k.keyword()))
        else {
            continue;
        };
        if !starts_line || !paren_follows {
            continue;
        }
        diags.push(
            Diagnostic::at(
                codes::LINF_MISSPELT_KEYWORD,
                span.clone(),
                format!("`{n}` is not a block keyword"),
            )
            .with_label(format!("read as `{}`", kind.keyword()))
            .with_help(format!("did you mean `{}`?", kind.keyword())),
        );
        tokens[i].0 = Token::Keyword(*kind);
    }
}

fn text_before_first_block(first: Token<'_>, span: Span) -> Diagnostic {
    let d = Diagnostic::at(
        codes::LINF_OUTSIDE_BLOCK,
        span,
        "text before the first block",
    )
    .with_label("not inside any block");
    let keywords: Vec<&str> = BlockKind::ALL.iter().map(|k| k.keyword()).collect();
    match first {
        Token::Name(n) if !nearest(n, &keywords).is_empty() => d.with_help(format!(
            "did you mean the block keyword `{}`?",
            nearest(n, &keywords)[0]
        )),
        _ => d.with_help(
            "a LinF file is made of blocks, each starting with its keyword: lines, blanks, angles, axiom, rules, colors",
        ),
    }
}

fn syntax_error(err: &Rich<'_, Token<'_>>) -> Diagnostic {
    crate::front::syntax_error(err, |tok| match tok {
        Token::Eq => Some("a rule is `name = string`; each rule starts with its name"),
        Token::Colon => Some("`:` only labels a colour: `0: (0, 0, 0)`"),
        Token::LParen | Token::RParen => {
            Some("parentheses belong in rotations `(torsion, curvature)` and colours `(r, g, b)`")
        }
        Token::Name(_) => Some("write `*` between a number and a name: `2*pi`"),
        _ => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_ok(src: &str) -> File {
        crate::front::parse::parse_clean(parse, src)
    }

    fn errors(src: &str) -> Vec<(crate::diagnostics::Code, Span)> {
        let mut d = Diagnostics::default();
        parse(src, &mut d);
        d.iter()
            .map(|d| (d.code, d.span.clone().unwrap_or(0..0)))
            .collect()
    }

    #[test]
    fn the_six_blocks_in_any_order() {
        let f = parse_ok(
            "rules f = f+f--f+f i = [0.5?j]\ncolors (0,0,0) 1: (40, 40, 40)\naxiom f\n\
             angles (0, pi/3) t = (pi/2, pi/6) w = (0, [0 2*pi])\nblanks b\nlines f g\n",
        );
        let kinds: Vec<BlockKind> = f.blocks.iter().map(|b| b.kind).collect();
        use BlockKind::*;
        assert_eq!(kinds, [Rules, Colors, Axiom, Angles, Blanks, Lines]);
        let BlockBody::Rules(rules) = &f.blocks[0].body else {
            panic!()
        };
        assert_eq!(rules.len(), 2);
        assert_eq!(rules[0].body.len(), 8);
        assert_eq!(rules[1].head.text, "i");
        let BlockBody::Angles(angles) = &f.blocks[3].body else {
            panic!()
        };
        assert_eq!(angles.len(), 3);
        assert!(angles[0].name.is_none());
        assert!(matches!(
            angles[2].components[1],
            Component::Interval { .. }
        ));
        let BlockBody::Colors(colours) = &f.blocks[1].body else {
            panic!()
        };
        assert_eq!(colours[1].label.as_ref().map(|l| l.0), Some(1.0));
    }

    #[test]
    fn intervals_split_side_by_side_expressions() {
        let f = parse_ok("angles (0, [0 -pi/2]) t = ([0-1 1], [-pi, pi])");
        let BlockBody::Angles(a) = &f.blocks[0].body else {
            panic!()
        };
        let Component::Interval { lo, hi, .. } = &a[0].components[1] else {
            panic!()
        };
        assert_eq!(lo.kind, ExprKind::Number(0.0));
        let hi = super::super::lower::eval(hi).unwrap();
        assert!((hi + std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        let Component::Interval { lo, .. } = &a[1].components[0] else {
            panic!()
        };
        assert!(matches!(lo.kind, ExprKind::Binary(BinOp::Sub, _, _)));
    }

    #[test]
    fn every_malformed_item_is_reported_and_the_rest_kept() {
        let src = "angles t = (pi, ) u = (0, 1)\nrules f = f(f) g = g\ncolors (1, 2, 3) x (4,5,6)";
        let mut d = Diagnostics::default();
        let f = parse(src, &mut d);
        assert_eq!(d.len(), 3, "{d:#?}");
        let BlockBody::Angles(a) = &f.blocks[0].body else {
            panic!()
        };
        // The malformed pair keeps its name (so its uses are not reported
        // again) and is marked as recovered.
        assert_eq!(a.len(), 2, "{a:?}");
        assert!(a[0].recovered && a[0].name.as_ref().unwrap().text == "t");
        assert!(!a[1].recovered && a[1].name.as_ref().unwrap().text == "u");
        let BlockBody::Rules(r) = &f.blocks[1].body else {
            panic!()
        };
        assert_eq!(r.len(), 2);
        let BlockBody::Colors(c) = &f.blocks[2].body else {
            panic!()
        };
        assert_eq!(c.len(), 2);
    }

    #[test]
    fn an_unclosed_group_is_closed_at_the_end_of_its_block() {
        // Reported once, at the outermost `(`; the rotation reads as far as
        // it goes, and the blocks after it read as usual.
        let src = "angles (0, (pi/2\naxiom f\nlines f\nangles t = ([0 1\n";
        let mut d = Diagnostics::default();
        let f = parse(src, &mut d);
        let found: Vec<_> = d
            .iter()
            .map(|d| (d.code, d.span.clone().unwrap()))
            .collect();
        assert_eq!(
            found,
            [(codes::SYNTAX, 7..8), (codes::SYNTAX, 44..45)],
            "{d:#?}"
        );
        assert_eq!(d.0[0].message, "unclosed `(`");
        assert_eq!(d.0[1].message, "unclosed `(`");
        assert!(d.0[0].labels[0]
            .message
            .contains("before the keyword `axiom`"));
        assert!(d.0[1].labels[0].message.contains("the file ends here"));
        let kinds: Vec<BlockKind> = f.blocks.iter().map(|b| b.kind).collect();
        use BlockKind::*;
        assert_eq!(kinds, [Angles, Axiom, Lines, Angles]);
        let BlockBody::Angles(a) = &f.blocks[0].body else {
            panic!()
        };
        assert_eq!(a.len(), 1);
        assert_eq!(a[0].components.len(), 2);
        let BlockBody::Angles(a) = &f.blocks[3].body else {
            panic!()
        };
        assert!(matches!(a[0].components[..], [Component::Interval { .. }]));
    }

    #[test]
    fn a_malformed_group_is_skipped_to_its_closer_within_its_block() {
        // Recovery skips the whole group, brackets inside and mismatched
        // closers included, and never the next block.
        let src = "angles t = (0 [1 2) 3) u = (0, 1)\ncolors (1 (2] 3) (4, 5, 6)\naxiom f";
        let mut d = Diagnostics::default();
        let f = parse(src, &mut d);
        assert_eq!(d.len(), 2, "{d:#?}");
        let BlockBody::Angles(a) = &f.blocks[0].body else {
            panic!()
        };
        let names: Vec<_> = a
            .iter()
            .map(|r| r.name.as_ref().unwrap().text.as_str())
            .collect();
        assert_eq!(names, ["t", "u"]);
        assert!(a[0].recovered && !a[1].recovered);
        let BlockBody::Colors(c) = &f.blocks[1].body else {
            panic!()
        };
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].components.len(), 3);
        assert_eq!(f.blocks.len(), 3);
    }

    #[test]
    fn a_mistake_repeated_along_a_line_is_reported_three_times() {
        let src = format!("rules f = f{}\ng = g) h = h)\n", ") f = f".repeat(1000));
        let e = errors(&src);
        // Three on the first line (the third says how many more), two on
        // the next.
        assert_eq!(e.len(), 5, "{e:?}");
        let mut d = Diagnostics::default();
        parse(&src, &mut d);
        assert_eq!(
            d.0[2].notes,
            ["997 more E0003 diagnostics on this line are not shown one by one"]
        );
        // A run of stray `=` is one mistake.
        assert_eq!(errors(&format!("rules {}", "= ".repeat(1000))).len(), 1);
    }

    #[test]
    fn reserved_heads_rules_in_the_axiom_and_stray_text() {
        let e = errors("lnes f\nrules + = f\naxiom f g = f");
        let codes: Vec<_> = e.iter().map(|(c, _)| *c).collect();
        assert_eq!(
            codes,
            [
                codes::LINF_OUTSIDE_BLOCK,
                codes::LINF_RESERVED_RULE,
                codes::LINF_RULE_IN_AXIOM
            ]
        );
        assert_eq!(e[0].1, 0..6);
        assert_eq!(e[1].1, 13..14);
    }
}
