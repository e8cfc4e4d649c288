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
/// and `!`.
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
        let atom = choice((
            select! { Token::Number(v) => ExprKind::Num(v) },
            select! { Token::Str(s) => ExprKind::Str(s) },
            name()
                .then(args)
                .map(|((n, span), a)| ExprKind::Call(n, span, a)),
            name()
                .then(subscripts)
                .map(|((n, _), s)| ExprKind::Index(n, s)),
            name().map(|(n, _)| ExprKind::Name(n)),
            just(Token::Amp)
                .ignore_then(name())
                .map(|(n, _)| ExprKind::Address(n)),
        ))
        .map_with(|kind, e| Expr {
            kind,
            span: range(e.span()),
        })
        .or(expr
            .clone()
            .delimited_by(just(Token::LParen), just(Token::RParen))
            .map_with(|inner: Expr, e| Expr {
                span: range(e.span()),
                ..inner
            }))
        .labelled("an expression")
        .boxed();
        let unary = select! { Token::Minus => UnOp::Neg, Token::Not => UnOp::Not }
            .map_with(|op, e| (op, range(e.span())))
            .repeated()
            .foldr(atom, |(op, span), rhs: Expr| Expr {
                span: span.start..rhs.span.end,
                kind: ExprKind::Unary(op, Box::new(rhs)),
            })
            .boxed();
        let binary = |lhs: Expr, (op, rhs): (BinOp, Expr)| Expr {
            span: lhs.span.start..rhs.span.end,
            kind: ExprKind::Binary(op, Box::new(lhs), Box::new(rhs)),
        };
        let pow = unary
            .clone()
            .foldl(just(Token::Caret).to(BinOp::Pow).then(unary).repeated(), binary).boxed();
        let product = pow.clone().foldl(
            select! { Token::Star => BinOp::Mul, Token::Slash => BinOp::Div, Token::Percent => BinOp::Rem }
                .then(pow)
                .repeated(),
            binary,
        ).boxed();
        let sum = product.clone().foldl(
            select! { Token::Plus => BinOp::Add, Token::Minus => BinOp::Sub }
                .then(product)
                .repeated(),
            binary,
        ).boxed();
        let compare = sum.clone().foldl(
            select! { Token::Lt => BinOp::Lt, Token::Le => BinOp::Le, Token::Gt => BinOp::Gt, Token::Ge => BinOp::Ge }
                .then(sum)
                .repeated(),
            binary,
        ).boxed();
        let equality = compare.clone().foldl(
            select! { Token::EqEq => BinOp::Eq, Token::Ne => BinOp::Ne }
                .then(compare)
                .repeated(),
            binary,
        ).boxed();
        let and = equality.clone().foldl(
            just(Token::And).to(BinOp::And).then(equality).repeated(),
            binary,
        ).boxed();
        let or = and
            .clone()
            .foldl(just(Token::Or).to(BinOp::Or).then(and).repeated(), binary);
        or.then(
            just(Token::Question)
                .ignore_then(expr.clone())
                .then_ignore(just(Token::Colon))
                .then(expr)
                .or_not(),
        )
        .map(|(c, rest)| match rest {
            None => c,
            Some((a, b)) => Expr {
                span: c.span.start..b.span.end,
                kind: ExprKind::Cond(Box::new(c), Box::new(a), Box::new(b)),
            },
        })
        .boxed()
    })
    .boxed()
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
        let stmt = choice((
            if_stmt.boxed(),
            while_stmt.boxed(),
            do_stmt.boxed(),
            assign.boxed(),
            eval.boxed(),
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

/// Parses a preprocessed cpfg text. Never fails: each malformed item is
/// reported and skipped.
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
    let parser = item();
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
                .with_help("replace `->` with `-->`"),
            );
            continue;
        }
        let end = line.last().map_or(0, |(_, s)| s.end);
        let eoi = SimpleSpan::from(end..end);
        let (out, errors) = parser
            .parse(line.as_slice().map(eoi, |(t, s)| (t, s)))
            .into_output_errors();
        match out {
            Some(item) if errors.is_empty() => file.items.push(item),
            _ => {
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
        let mut d = Diagnostics::default();
        let f = parse(src, &mut d);
        assert!(d.is_empty(), "{d:#?}");
        f
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
