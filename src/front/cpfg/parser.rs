//! The cpfg parser (chumsky 0.12 over the tokens of [`super::lexer`]).
//!
//! A cpfg file is a sequence of items, each ending at an end of line (the
//! lexer already joined continuation lines and statement blocks). Each item
//! is parsed on its own: a malformed one is reported and left out, and the
//! next one is read as usual, so every error of a file is reported in one
//! run and the parser never fails. Meaning (names, symbols, values) is
//! checked by [`super::lower`].

use super::ast::{
    ArrayDef, BlockKind, Expr, ExprKind, File, Item, Module, Production, Section, Stmt,
};
use super::lexer::{lex, Keyword, Token};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::front::depth::{cut_too_deep, parenthesized, too_deep, Nest};
use crate::front::syntax_error;
use crate::ir::program::{BinOp, UnOp};
use crate::ir::Span;
use chumsky::input::ValueInput;
use chumsky::prelude::*;

type Extra<'t> = extra::Err<Rich<'t, Token>>;

/// A type-erased parser: the pieces below are built once and shared, which
/// keeps compile times and parser types small.
type P<'t, I, O> = Boxed<'t, 't, I, O, Extra<'t>>;

fn range(s: SimpleSpan) -> Span {
    s.into_range()
}

fn name<'t, I>() -> impl Parser<'t, I, (String, Span), Extra<'t>> + Clone
where
    I: ValueInput<'t, Token = Token, Span = SimpleSpan>,
{
    select! { Token::Name(n) => n }
        .map_with(|n, e| (n, range(e.span())))
        .labelled("a name")
}

fn word<'t, I>(w: &'static str) -> impl Parser<'t, I, (), Extra<'t>> + Clone
where
    I: ValueInput<'t, Token = Token, Span = SimpleSpan>,
{
    any()
        .filter(move |t: &Token| matches!(t, Token::Name(n) if n == w))
        .ignored()
        .labelled(w)
}

/// C expressions with cpfg's precedences (lowest first): `?:`, `||`, `&&`,
/// `== !=`, `< <= > >=`, `+ -`, `* / %`, `^` (left-associative), unary `-`
/// and `!`. The binary operators are read as one flat run and put into a
/// tree by [`by_precedence`]: a parenthesis then costs one level of the
/// parser's recursion rather than one per precedence level, which keeps
/// nesting up to [`crate::ir::MAX_NESTING`] within a small stack. Trees are
/// built by [`Expr::leaf`] and [`Expr::operation`], which cut them at the
/// limit.
pub fn expr_parser<'t, I>() -> P<'t, I, Expr>
where
    I: ValueInput<'t, Token = Token, Span = SimpleSpan>,
{
    recursive(|expr| {
        let args = expr
            .clone()
            .separated_by(just(Token::Comma))
            .collect::<Vec<_>>()
            .delimited_by(just(Token::LParen), just(Token::RParen));
        let subscripts = expr
            .clone()
            .separated_by(just(Token::Comma))
            .at_least(1)
            .collect::<Vec<_>>()
            .delimited_by(just(Token::LBracket), just(Token::RBracket))
            .repeated()
            .at_least(1)
            .collect::<Vec<Vec<Expr>>>()
            .map(|v| v.into_iter().flatten().collect::<Vec<_>>());
        let leaf = |kind, e: &mut chumsky::input::MapExtra<'t, '_, I, Extra<'t>>| {
            Expr::leaf(kind, range(e.span()))
        };
        let atom = choice((
            select! { Token::Number(v) => ExprKind::Num(v) }.map_with(leaf),
            select! { Token::Str(s) => ExprKind::Str(s) }.map_with(leaf),
            name().then(args).map_with(|((n, span), a), e| {
                Expr::operation(ExprKind::Call(n, span.clone(), a), range(e.span()), span)
            }),
            name()
                .then(subscripts.clone())
                .map_with(|((n, span), s), e| {
                    Expr::operation(ExprKind::Index(n, s), range(e.span()), span)
                }),
            name().map(|(n, span)| Expr::leaf(ExprKind::Name(n), span)),
            just(Token::TooDeep).map_with(|_, e| Expr::cut(range(e.span()))),
            // `&x` and `&x[i]`, as `fscanf` takes them: the call reads
            // nothing (W0822), so only the name is kept.
            just(Token::Amp)
                .ignore_then(name())
                .then_ignore(subscripts.clone().or_not())
                .map_with(move |(n, _), e| leaf(ExprKind::Address(n), e)),
        ))
        .or(expr
            .clone()
            .delimited_by(just(Token::LParen), just(Token::RParen))
            .map_with(|inner: Expr, e| parenthesized(inner, range(e.span()))))
        .labelled("an expression");
        let unary = select! { Token::Minus => UnOp::Neg, Token::Not => UnOp::Not }
            .map_with(|op, e| (op, range(e.span())))
            .repeated()
            .foldr(atom, |(op, at), rhs: Expr| {
                let span = at.start..rhs.span.end;
                Expr::operation(ExprKind::Unary(op, Box::new(rhs)), span, at)
            });
        let operator = choice((
            just(Token::Caret).to(BinOp::Pow),
            select! {
                Token::Star => BinOp::Mul,
                Token::Slash => BinOp::Div,
                Token::Percent => BinOp::Rem,
                Token::Plus => BinOp::Add,
                Token::Minus => BinOp::Sub,
                Token::Lt => BinOp::Lt,
                Token::Le => BinOp::Le,
                Token::Gt => BinOp::Gt,
                Token::Ge => BinOp::Ge,
                Token::EqEq => BinOp::Eq,
                Token::Ne => BinOp::Ne,
            },
            just(Token::And).to(BinOp::And),
            just(Token::Or).to(BinOp::Or),
        ))
        .map_with(|op, e| (op, range(e.span())));
        let operations = unary
            .clone()
            .then(operator.then(unary).repeated().collect::<Vec<_>>())
            .map(|(first, rest)| by_precedence(first, rest));
        let question = just(Token::Question).map_with(|_, e| range(e.span()));
        operations
            .then(
                question
                    .then(expr.clone())
                    .then_ignore(just(Token::Colon))
                    .then(expr)
                    .or_not(),
            )
            .map(|(c, rest)| match rest {
                None => c,
                Some(((at, a), b)) => {
                    let span = c.span.start..b.span.end;
                    Expr::operation(
                        ExprKind::Cond(Box::new(c), Box::new(a), Box::new(b)),
                        span,
                        at,
                    )
                }
            })
            .boxed()
    })
    .boxed()
}

/// How tightly a binary operator binds (the tightest highest).
fn precedence(op: BinOp) -> u8 {
    match op {
        BinOp::Pow => 7,
        BinOp::Mul | BinOp::Div | BinOp::Rem => 6,
        BinOp::Add | BinOp::Sub => 5,
        BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => 4,
        BinOp::Eq | BinOp::Ne => 3,
        BinOp::And => 2,
        BinOp::Or => 1,
    }
}

/// `first op operand op operand …` as a tree, every operator
/// left-associative and the tighter ones first: operator-precedence
/// parsing with a stack of left operands waiting for their right one, so
/// that a chain of any length is built without recursion.
fn by_precedence(first: Expr, rest: Vec<((BinOp, Span), Expr)>) -> Expr {
    let binary = |op, at, l: Expr, r: Expr| {
        let span = l.span.start..r.span.end;
        Expr::operation(ExprKind::Binary(op, Box::new(l), Box::new(r)), span, at)
    };
    let mut waiting: Vec<(Expr, BinOp, Span)> = Vec::new();
    let mut current = first;
    for ((op, at), operand) in rest {
        while waiting
            .last()
            .is_some_and(|(_, top, _)| precedence(*top) >= precedence(op))
        {
            if let Some((l, top, top_at)) = waiting.pop() {
                current = binary(top, top_at, l, current);
            }
        }
        waiting.push((current, op, at));
        current = operand;
    }
    while let Some((l, top, at)) = waiting.pop() {
        current = binary(top, at, l, current);
    }
    current
}

/// A block of statements `{ … }`.
pub fn block_parser<'t, I>(expr: P<'t, I, Expr>) -> P<'t, I, Vec<Stmt>>
where
    I: ValueInput<'t, Token = Token, Span = SimpleSpan>,
{
    recursive(move |block| {
        let block = block.boxed();
        let cond = expr
            .clone()
            .delimited_by(just(Token::LParen), just(Token::RParen));
        let if_stmt = word("if")
            .ignore_then(cond.clone())
            .then(block.clone())
            .then(word("else").ignore_then(block.clone()).or_not())
            .map(|((c, t), e)| Stmt::If(c, t, e.unwrap_or_default()));
        let while_stmt = word("while")
            .ignore_then(cond.clone())
            .then(block.clone())
            .map(|(c, b)| Stmt::While(c, b));
        let do_stmt = word("do")
            .ignore_then(block.clone())
            .then_ignore(word("while"))
            .then(cond)
            .then_ignore(just(Token::Semi).or_not())
            .map(|(b, c)| Stmt::Do(b, c));
        let assign = expr
            .clone()
            .then_ignore(just(Token::Assign))
            .then(expr.clone())
            .then_ignore(just(Token::Semi))
            .map(|(target, value)| Stmt::Assign { target, value });
        let eval = expr.then_ignore(just(Token::Semi)).map(Stmt::Eval);
        // The marker for a block nested past the depth limit.
        let cut = just(Token::TooDeep).map_with(|_, e| Stmt::Eval(Expr::cut(range(e.span()))));
        let stmt = choice((
            if_stmt.boxed(),
            while_stmt.boxed(),
            do_stmt.boxed(),
            assign.boxed(),
            eval.boxed(),
            cut.boxed(),
        ));
        stmt.repeated()
            .collect::<Vec<_>>()
            .delimited_by(just(Token::LBrace), just(Token::RBrace))
            .labelled("a block `{ … }`")
            .boxed()
    })
    .boxed()
}

/// Modules with parameters: `F(1)A[+B]`.
fn modules<'t, I>(expr: P<'t, I, Expr>, at_least: usize) -> P<'t, I, Vec<Module>>
where
    I: ValueInput<'t, Token = Token, Span = SimpleSpan>,
{
    let args = expr
        .separated_by(just(Token::Comma))
        .collect::<Vec<_>>()
        .delimited_by(just(Token::LParen), just(Token::RParen));
    select! { Token::Symbol(s) => s }
        .map_with(|s, e| (s, range(e.span())))
        .then(args.or_not())
        .map_with(|((name, span), args), e| Module {
            name,
            span: span.start..range(e.span()).end,
            args: args.unwrap_or_default(),
        })
        .repeated()
        .at_least(at_least)
        .collect::<Vec<_>>()
        .labelled("modules")
        .boxed()
}

fn production<'t, I>(
    expr: P<'t, I, Expr>,
    block: P<'t, I, Vec<Stmt>>,
    mods: P<'t, I, Vec<Module>>,
) -> P<'t, I, Production>
where
    I: ValueInput<'t, Token = Token, Span = SimpleSpan>,
{
    let context = mods.clone().or(just(Token::Null).to(Vec::new()));
    let left = context
        .clone()
        .then_ignore(just(Token::LSep))
        .or_not()
        .map(Option::unwrap_or_default);
    let right = just(Token::RSep)
        .ignore_then(context)
        .or_not()
        .map(Option::unwrap_or_default);
    let condition = just(Token::Star).to(None).or(expr.clone().map(Some));
    let statements = just(Token::Colon)
        .ignore_then(block.clone().or_not())
        .then(condition.or_not().map(Option::flatten))
        .then(block.or_not())
        .or_not();
    let successor = just(Token::Null).to(Vec::new()).or(mods.clone());
    let probability = just(Token::Colon).ignore_then(expr).or_not();
    left.then(mods.labelled("a predecessor"))
        .then(right)
        .then(statements)
        .then_ignore(just(Token::Arrow))
        .then(successor.labelled("a successor (or `*`)"))
        .then(probability)
        .map_with(|(((((left, pred), right), stmts), succ), prob), e| {
            let ((before, condition), after) = stmts.unwrap_or(((None, None), None));
            Production {
                left,
                predecessor: pred,
                right,
                before: before.unwrap_or_default(),
                condition,
                after: after.unwrap_or_default(),
                successor: succ,
                probability: prob,
                span: range(e.span()),
            }
        })
        .boxed()
}

fn array_defs<'t, I>(expr: P<'t, I, Expr>) -> P<'t, I, Vec<ArrayDef>>
where
    I: ValueInput<'t, Token = Token, Span = SimpleSpan>,
{
    let dims = expr
        .clone()
        .separated_by(just(Token::Comma))
        .at_least(1)
        .collect::<Vec<_>>()
        .delimited_by(just(Token::LBracket), just(Token::RBracket))
        .repeated()
        .at_least(1)
        .collect::<Vec<Vec<Expr>>>()
        .map(|v| v.into_iter().flatten().collect::<Vec<_>>());
    let init = just(Token::Assign).ignore_then(
        expr.separated_by(just(Token::Comma))
            .allow_trailing()
            .collect::<Vec<_>>()
            .delimited_by(just(Token::LBrace), just(Token::RBrace)),
    );
    let def = name()
        .then(dims)
        .then(init.or_not())
        .map(|(((name, span), dims), init)| ArrayDef {
            name,
            span,
            dims,
            init: init.unwrap_or_default(),
        });
    word("array")
        .ignore_then(def.separated_by(just(Token::Comma)).collect::<Vec<_>>())
        .then_ignore(just(Token::Semi))
        .repeated()
        .collect::<Vec<Vec<ArrayDef>>>()
        .map(|v| v.into_iter().flatten().collect())
        .delimited_by(just(Token::LBrace), just(Token::RBrace))
        .boxed()
}

/// A production alone: the item a line starting with a module is. The
/// keyword items of [`item`] all fail at such a line's first token, and
/// trying them (each failure merged into the expected tokens) cost more
/// than reading the production; what they would expect there never shows,
/// since the production reads past that token.
fn production_item<'t, I>() -> P<'t, I, Item>
where
    I: ValueInput<'t, Token = Token, Span = SimpleSpan>,
{
    let expr = expr_parser();
    let block_p = block_parser(expr.clone());
    let mods = modules(expr.clone(), 1);
    production(expr, block_p, mods)
        .map(|p| Item::Production(Box::new(p)))
        .then_ignore(end())
        .boxed()
}

/// One item (a logical line).
fn item<'t, I>() -> P<'t, I, Item>
where
    I: ValueInput<'t, Token = Token, Span = SimpleSpan>,
{
    let expr = expr_parser();
    let block_p = block_parser(expr.clone());
    let mods = modules(expr.clone(), 1);
    let kw = |k: Keyword| just(Token::Keyword(k)).map_with(|_, e| range(e.span()));
    let symbols = select! { Token::Symbol(s) => s }
        .map_with(|s, e| (s, range(e.span())))
        .repeated()
        .collect::<Vec<_>>();
    let section = |k: Keyword, s: Section| {
        kw(k)
            .then_ignore(
                just(Token::Keyword(Keyword::Warnings))
                    .or(just(Token::Keyword(Keyword::NoWarnings)))
                    .or_not(),
            )
            .map(move |span| Item::Section(s, span))
            .boxed()
    };
    let block = |k: Keyword, b: BlockKind| {
        kw(k)
            .then(block_p.clone())
            .then_ignore(just(Token::Semi).or_not())
            .map(move |(span, stmts)| Item::Block(b, stmts, span))
            .boxed()
    };
    choice((
        kw(Keyword::Lsystem)
            .then(
                any()
                    .filter(|t: &Token| !matches!(t, Token::Eol))
                    .repeated()
                    .collect::<Vec<_>>(),
            )
            .map(|(span, toks)| Item::Lsystem {
                label: toks
                    .iter()
                    .map(|t| match t {
                        Token::Symbol(s) | Token::Name(s) => s.clone(),
                        Token::Number(v) => v.to_string(),
                        _ => String::new(),
                    })
                    .collect(),
                span,
            })
            .boxed(),
        kw(Keyword::Seed)
            .then(expr.clone())
            .map(|(s, e)| Item::Seed(e, s))
            .boxed(),
        kw(Keyword::DerivationLength)
            .then(expr.clone())
            .map(|(s, e)| Item::DerivationLength(e, s))
            .boxed(),
        kw(Keyword::MaximumDepth)
            .then(expr.clone())
            .map(|(s, e)| Item::MaximumDepth(e, s))
            .boxed(),
        kw(Keyword::Ignore)
            .ignore_then(symbols)
            .map(Item::Ignore)
            .boxed(),
        kw(Keyword::Consider)
            .ignore_then(symbols)
            .map(Item::Consider)
            .boxed(),
        kw(Keyword::Axiom)
            .then(mods.clone().labelled("the axiom's modules"))
            .map(|(s, m)| Item::Axiom(m, s))
            .boxed(),
        kw(Keyword::Define)
            .ignore_then(array_defs(expr.clone()))
            .map(Item::Define)
            .boxed(),
        kw(Keyword::Ring).map(Item::Ring).boxed(),
        block(Keyword::Start, BlockKind::Start),
        block(Keyword::StartEach, BlockKind::StartEach),
        block(Keyword::EndEach, BlockKind::EndEach),
        block(Keyword::End, BlockKind::End),
        section(Keyword::Homomorphism, Section::Homomorphism),
        section(Keyword::Decomposition, Section::Decomposition),
        kw(Keyword::EndLsystem).map(Item::EndLsystem).boxed(),
        production(expr, block_p, mods)
            .map(|p| Item::Production(Box::new(p)))
            .boxed(),
    ))
    .then_ignore(end())
    .boxed()
}

/// Help for a token met where it does not belong.
fn help_for(t: &Token) -> Option<&'static str> {
    match t {
        Token::Symbol(s) if s == "=" => Some("cpfg productions are written `pred --> succ`"),
        Token::Keyword(Keyword::Warnings) => {
            Some("`warnings` follows `homomorphism` or `decomposition` on the same line")
        }
        Token::RParen => Some("a `)` here closes nothing: check the parentheses before it"),
        _ => None,
    }
}

/// How to keep a cpfg item within the depth limit.
const DEPTH_HELP: &str =
    "compute part of it apart, in a statement `{ x = …; }` or a `#define`, and use the result";

/// What a token does to the nesting the parser descends into.
fn nesting(t: &Token) -> Nest {
    match t {
        Token::LParen | Token::LBracket | Token::LBrace => Nest::Open,
        Token::RParen | Token::RBracket | Token::RBrace => Nest::Close,
        Token::Question => Nest::Question,
        Token::Colon => Nest::Else,
        Token::Comma | Token::Semi | Token::Arrow => Nest::Separator,
        _ => Nest::Other,
    }
}

/// What the parser reads in place of what `opener` holds past the depth
/// limit: a marker, and for a `?` its two branches.
fn filler((t, s): &(Token, SimpleSpan)) -> Vec<(Token, SimpleSpan)> {
    match t {
        Token::Question => vec![
            (Token::TooDeep, *s),
            (Token::Colon, *s),
            (Token::TooDeep, *s),
        ],
        _ => vec![(Token::TooDeep, *s)],
    }
}

/// The closer of the group `opener` opens.
fn closer(opener: &Token) -> Token {
    match opener {
        Token::LBracket => Token::RBracket,
        Token::LBrace => Token::RBrace,
        _ => Token::RParen,
    }
}

/// Replaces each cut in `item` (see [`Expr::operation`]) with 0, so that
/// lowering reads the item without further complaint, and says where the
/// first one was. A cut is carried up to the root of its expression, so
/// only the roots are looked at.
fn take_cuts(item: &mut Item) -> Option<Span> {
    let mut roots: Vec<&mut Expr> = Vec::new();
    match item {
        Item::Seed(e, _) | Item::DerivationLength(e, _) | Item::MaximumDepth(e, _) => roots.push(e),
        Item::Axiom(mods, _) => module_roots(mods, &mut roots),
        Item::Define(defs) => {
            for d in defs {
                roots.extend(d.dims.iter_mut().chain(&mut d.init));
            }
        }
        Item::Block(_, stmts, _) => statement_roots(stmts, &mut roots),
        Item::Production(p) => {
            let p = &mut **p;
            for mods in [&mut p.left, &mut p.predecessor, &mut p.right] {
                module_roots(mods, &mut roots);
            }
            statement_roots(&mut p.before, &mut roots);
            roots.extend(&mut p.condition);
            statement_roots(&mut p.after, &mut roots);
            module_roots(&mut p.successor, &mut roots);
            roots.extend(&mut p.probability);
        }
        Item::Lsystem { .. }
        | Item::Ignore(_)
        | Item::Consider(_)
        | Item::Ring(_)
        | Item::Section(..)
        | Item::EndLsystem(_) => {}
    }
    let mut first = None;
    for e in roots.into_iter().filter(|e| e.is_cut()) {
        first.get_or_insert(e.span.clone());
        *e = Expr::leaf(ExprKind::Num(0.0), e.span.clone());
    }
    first
}

fn module_roots<'a>(mods: &'a mut [Module], out: &mut Vec<&'a mut Expr>) {
    out.extend(mods.iter_mut().flat_map(|m| &mut m.args));
}

/// The expressions of `stmts` and of the blocks inside them (as deep as
/// the braces, which the limit bounds).
fn statement_roots<'a>(stmts: &'a mut [Stmt], out: &mut Vec<&'a mut Expr>) {
    for s in stmts {
        match s {
            Stmt::Assign { target, value } => out.extend([target, value]),
            Stmt::Eval(e) => out.push(e),
            Stmt::If(c, then, otherwise) => {
                out.push(c);
                statement_roots(then, out);
                statement_roots(otherwise, out);
            }
            Stmt::While(c, body) => {
                out.push(c);
                statement_roots(body, out);
            }
            Stmt::Do(body, c) => {
                statement_roots(body, out);
                out.push(c);
            }
        }
    }
}

/// Parses a preprocessed cpfg text. Never fails: each malformed item is
/// reported and skipped. An item nested past [`crate::ir::MAX_NESTING`]
/// gets one E0013, at the first place past it, and is read with that part
/// left out.
/// A line that does not parse and reads as a misspelt item keyword
/// (`derivaton length: 10`): one to three words, then `:`, and a keyword
/// near them. The same did-you-mean as pfg's headers, at the words.
fn misspelt_item(src: &str, line: &[(Token, SimpleSpan)]) -> Option<Diagnostic> {
    if line.iter().any(|(t, _)| *t == Token::Arrow) {
        return None;
    }
    let start = line.first()?.1.start;
    let text = src.get(start..line.last()?.1.end)?;
    let key = text[..text.find(':')?].trim_end();
    let words: Vec<&str> = key.split_whitespace().collect();
    let is_word = |w: &&str| w.chars().all(|c| c.is_ascii_alphabetic());
    if words.is_empty() || words.len() > 3 || !words.iter().all(is_word) {
        return None;
    }
    let known: Vec<&str> = (Keyword::ALL.iter())
        .map(|k| k.text().trim_end_matches(':'))
        .collect();
    let lower = key.to_ascii_lowercase();
    let near = *crate::diagnostics::nearest(&lower, &known).first()?;
    Some(
        Diagnostic::at(
            codes::UNKNOWN_HEADER,
            start..start + key.len(),
            format!("unknown item `{key}:`"),
        )
        .with_label("not a cpfg keyword")
        .suggesting(near),
    )
}

pub fn parse(src: &str, diags: &mut Diagnostics) -> File {
    let lexed = lex(src, diags);
    let mut file = File::default();
    let mut lines: Vec<Vec<(Token, SimpleSpan)>> = vec![Vec::new()];
    for (t, s) in lexed.tokens {
        if t == Token::Eol {
            lines.push(Vec::new());
        } else if let Some(line) = lines.last_mut() {
            line.push((t, SimpleSpan::from(s)));
        }
    }
    // The parser recurses into brackets: it is not shown what lies past
    // the depth limit, only a marker it reads as a cut.
    for line in &mut lines {
        let end = line.last().map_or(0, |(_, s)| s.end);
        let closer = |(t, _): &(Token, SimpleSpan)| (closer(t), SimpleSpan::from(end..end));
        if let Some(cut) = cut_too_deep(line, |(t, _)| nesting(t), filler, closer) {
            *line = cut;
        }
    }
    let parser = item();
    let production_parser = production_item();
    for line in lines.iter().filter(|l| !l.is_empty()) {
        if let Some((_, s)) = line.iter().find(|(t, _)| *t == Token::ObjectArrow) {
            diags.push(
                Diagnostic::at(
                    codes::CPFG_UNSUPPORTED,
                    range(*s),
                    "object productions `-o>` are not supported",
                )
                .with_label("an object production")
                .with_help("write the production with `-->`"),
            );
            continue;
        }
        // `->` (a `-` module then `>`) where `-->` was meant.
        let arrow = line.windows(2).find(|w| {
            w[0].0 == Token::Symbol("-".into())
                && w[1].0 == Token::RSep
                && w[0].1.end == w[1].1.start
        });
        if let (Some(w), false) = (arrow, line.iter().any(|(t, _)| *t == Token::Arrow)) {
            diags.push(
                Diagnostic::at(
                    codes::MALFORMED_ARROW,
                    w[0].1.start..w[1].1.end,
                    "malformed arrow `->`",
                )
                .with_label("cpfg writes the arrow as `-->`")
                .with_fix(
                    w[0].1.start..w[1].1.end,
                    "-->".into(),
                    "replace `->` with `-->`".into(),
                ),
            );
            continue;
        }
        let end = line.last().map_or(0, |(_, s)| s.end);
        let eoi = SimpleSpan::from(end..end);
        let parser = match line.first() {
            Some((Token::Symbol(_), _)) => &production_parser,
            _ => &parser,
        };
        let (out, errors) = parser
            .parse(line.as_slice().map(eoi, |(t, s)| (t, s)))
            .into_output_errors();
        let cut = || line.iter().find(|(t, _)| *t == Token::TooDeep);
        match out {
            Some(mut item) if errors.is_empty() => {
                if let Some(at) = take_cuts(&mut item) {
                    diags.push(too_deep(at, DEPTH_HELP));
                }
                file.items.push(item);
            }
            // A part nested too deeply comes first, whatever else is wrong.
            _ if cut().is_some() => {
                let at = cut().map_or(end..end, |(_, s)| range(*s));
                diags.push(too_deep(at, DEPTH_HELP));
            }
            _ => {
                if let Some(d) = misspelt_item(src, line) {
                    diags.push(d);
                    continue;
                }
                if let Some(err) = errors.first() {
                    let mut d = syntax_error(err, help_for);
                    if err.found().is_none() {
                        // The item ends early: say so at its end.
                        d = Diagnostic::at(
                            codes::SYNTAX,
                            d.span.clone().unwrap_or(end..end),
                            "this item ends too early",
                        )
                        .with_label("the line ends here")
                        .with_help(
                            d.help
                                .clone()
                                .unwrap_or_else(|| "complete the item".to_string()),
                        );
                    }
                    diags.push(d);
                }
            }
        }
    }
    file
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_ok(src: &str) -> File {
        crate::front::parse::parse_clean(parse, src)
    }

    #[test]
    fn reads_a_parametric_production_with_statements() {
        let f = parse_ok(
            "Lsystem: 1\nderivation length: 3\naxiom: A(1)\nB(a) < A(x) > C : {y=x*2;} y<10 && !0 {z=y;} --> A(z)[+F(x^2)]\nendlsystem\n",
        );
        assert_eq!(f.items.len(), 5);
        let Item::Production(p) = &f.items[3] else {
            panic!("{:?}", f.items[3])
        };
        assert_eq!(p.left.len(), 1);
        assert_eq!(p.right[0].name, "C");
        assert_eq!(p.before.len(), 1);
        assert!(p.condition.is_some());
        assert_eq!(p.after.len(), 1);
        assert_eq!(p.successor.len(), 5);
        assert_eq!(p.successor[2].name, "+");
        assert_eq!(p.successor[3].args.len(), 1);
    }

    #[test]
    fn precedence_follows_cpfg() {
        let f = parse_ok("axiom: A(1+2*3^2>4?5:6)\n");
        let Item::Axiom(m, _) = &f.items[0] else {
            panic!()
        };
        let ExprKind::Cond(c, _, _) = &m[0].args[0].kind else {
            panic!("{:?}", m[0].args[0])
        };
        let ExprKind::Binary(BinOp::Gt, l, _) = &c.kind else {
            panic!()
        };
        assert!(matches!(l.kind, ExprKind::Binary(BinOp::Add, _, _)));
    }

    #[test]
    fn a_bad_item_is_reported_and_the_next_still_read() {
        let mut d = Diagnostics::default();
        let f = parse("axiom: A\nA -> B\nB --> C\n", &mut d);
        assert_eq!(d.len(), 1, "{d:#?}");
        assert_eq!(f.items.len(), 2);
    }

    #[test]
    fn blocks_and_arrays() {
        let f = parse_ok(
            "Start: {i=0; if (i<1) {i=2;} else {i=3;} while (i>0) {i=i-1;}}\ndefine: { array a[2] = {1,2}; array b[2][3]; }\n",
        );
        assert!(matches!(&f.items[0], Item::Block(BlockKind::Start, s, _) if s.len() == 3));
        assert!(matches!(&f.items[1], Item::Define(a) if a.len() == 2 && a[1].dims.len() == 2));
    }
}
