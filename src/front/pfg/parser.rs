//! The pfg parser (chumsky 0.12 over logos tokens).
//!
//! pfg is line-oriented: each line is a header (`key: value`), a production
//! (`lc < pred > rc --> succ : weight`) or empty. The chumsky grammar is
//! deliberately permissive about the *shape* of a production (any run of
//! symbols and `<` `>` before the arrow), so that the checks that follow
//! ([`build`]) can say precisely what is wrong — a missing arrow, a `>` before
//! a `<` — with a code and a help line, instead of a generic "unexpected
//! token". Whatever chumsky itself rejects (a second arrow, a stray `:`) is
//! reported as a syntax error and the parser recovers at the next line, so
//! every error of a file is reported in one run and the parser never fails.

use super::ast::{File, Header, Item, Production, Symbols};
use super::lexer::{lex, Token};
use crate::diagnostics::{codes, nearest, Diagnostic, Diagnostics};
use crate::front::parse::push_syntax_errors;
use crate::front::repeats::push_lazily;
use crate::ir::Span;
use chumsky::input::ValueInput;
use chumsky::prelude::*;

/// The header keywords of the Appendix A listing, in the listing's order.
pub const HEADERS: [&str; 5] = [
    "derivation length",
    "angle factor",
    "scale factor",
    "axiom",
    "ignore",
];

type Tok<'src> = (Token<'src>, SimpleSpan);

/// One line as chumsky sees it.
#[derive(Clone, Debug)]
enum RawLine<'src> {
    Header {
        key: Vec<Tok<'src>>,
        value: Vec<Tok<'src>>,
    },
    Rule {
        lhs: Vec<Tok<'src>>,
        arrow: Option<Tok<'src>>,
        rhs: Vec<Tok<'src>>,
        weight: Option<(SimpleSpan, Vec<Tok<'src>>)>,
    },
}

fn line_parser<'tokens, 'src: 'tokens, I>(
) -> impl Parser<'tokens, I, Vec<Option<RawLine<'src>>>, extra::Err<Rich<'tokens, Token<'src>>>>
where
    I: ValueInput<'tokens, Token = Token<'src>, Span = SimpleSpan>,
{
    let word = select! { Token::Word(w) => Token::Word(w) }.map_with(|t, e| (t, e.span()));
    let colon = just(Token::Colon).map_with(|t, e| (t, e.span()));
    let not_newline = any()
        .filter(|t: &Token| *t != Token::Newline)
        .map_with(|t, e| (t, e.span()));
    let lhs_tok = any()
        .filter(|t: &Token| {
            matches!(
                t,
                Token::Word(_)
                    | Token::Number(_)
                    | Token::Char(_)
                    | Token::Star
                    | Token::Lt
                    | Token::Gt
            )
        })
        .map_with(|t, e| (t, e.span()));
    let rhs_tok = any()
        .filter(|t: &Token| {
            matches!(
                t,
                Token::Word(_)
                    | Token::Number(_)
                    | Token::Char(_)
                    | Token::Star
                    | Token::Lt
                    | Token::Gt
                    | Token::BadArrow(_)
            )
        })
        .map_with(|t, e| (t, e.span()))
        .labelled("a symbol");
    let arrow = select! { Token::Arrow => Token::Arrow, Token::BadArrow(s) => Token::BadArrow(s) }
        .map_with(|t, e| (t, e.span()))
        .labelled("`-->`");

    let header = word
        .repeated()
        .at_least(1)
        .collect::<Vec<_>>()
        .then_ignore(colon)
        .then(not_newline.repeated().collect::<Vec<_>>())
        .map(|(key, value)| RawLine::Header { key, value });

    let weight = colon.map(|(_, s)| s).then(
        not_newline
            .repeated()
            .collect::<Vec<_>>()
            .labelled("a weight"),
    );

    let rule = lhs_tok
        .repeated()
        .collect::<Vec<_>>()
        .then(arrow.or_not())
        .then(rhs_tok.repeated().collect::<Vec<_>>())
        .then(weight.or_not())
        .map(|(((lhs, arrow), rhs), weight)| RawLine::Rule {
            lhs,
            arrow,
            rhs,
            weight,
        });

    let end_of_line = just(Token::Newline).ignored().or(end()).rewind();
    let line = header
        .or(rule)
        .then_ignore(end_of_line.labelled("end of line"))
        .map(Some)
        .recover_with(via_parser(
            any()
                .filter(|t: &Token| *t != Token::Newline)
                .repeated()
                .to(None),
        ));

    line.separated_by(just(Token::Newline))
        .collect::<Vec<_>>()
        .then_ignore(end())
}

/// Parses pfg source text into an AST. Never fails: problems are pushed to
/// `diags` and the lines they are on are left out of the AST.
pub fn parse(src: &str, diags: &mut Diagnostics) -> File {
    let tokens: Vec<Tok<'_>> = lex(src, diags)
        .into_iter()
        .map(|(t, s)| (t, SimpleSpan::from(s)))
        .collect();
    let eoi = SimpleSpan::from(src.len()..src.len());
    let (lines, errors) = line_parser()
        .parse(tokens.as_slice().map(eoi, |(t, s)| (t, s)))
        .into_output_errors();
    push_syntax_errors(diags, errors, help_for);
    let mut file = File::default();
    for line in lines.unwrap_or_default().into_iter().flatten() {
        if let Some(item) = build(line, src, diags) {
            file.items.push(item);
        }
    }
    file
}

/// A hint for an unexpected token.
fn help_for(tok: &Token<'_>) -> Option<&'static str> {
    match tok {
        Token::Arrow => {
            Some("a production has exactly one `-->`; put each production on its own line")
        }
        Token::Colon => {
            Some("`:` starts a header (`axiom: F`) or, after the successor, a weight (`: 0.5`)")
        }
        _ => None,
    }
}

fn range(s: SimpleSpan) -> Span {
    s.into_range()
}

/// The characters of the tokens as one-character symbols with their spans.
/// With `star_empty` (production parts, as the listing's `enter`), a string
/// starting with `*` is the empty string; header values are read as written.
fn symbols(toks: &[Tok<'_>], src: &str, star_empty: bool) -> Symbols {
    let mut chars = Vec::new();
    for (_, span) in toks {
        let text = &src[range(*span)];
        for (off, c) in text.char_indices() {
            let start = span.start + off;
            chars.push((c.to_string(), start..start + c.len_utf8()));
        }
    }
    let span = match (toks.first(), toks.last()) {
        (Some(a), Some(b)) => a.1.start..b.1.end,
        _ => 0..0,
    };
    let star = star_empty && toks.first().is_some_and(|t| t.0 == Token::Star);
    if star {
        chars.clear();
    }
    Symbols { chars, star, span }
}

fn line_span(toks: &[&[Tok<'_>]]) -> Span {
    let start = toks
        .iter()
        .filter_map(|t| t.first())
        .map(|t| t.1.start)
        .min();
    let end = toks.iter().filter_map(|t| t.last()).map(|t| t.1.end).max();
    match (start, end) {
        (Some(s), Some(e)) => s..e,
        _ => 0..0,
    }
}

/// Turns one permissive line into an AST item, checking the shape of
/// productions.
fn build(line: RawLine<'_>, src: &str, diags: &mut Diagnostics) -> Option<Item> {
    match line {
        RawLine::Header { key, value } => {
            let key_span = line_span(&[&key]);
            let words: Vec<&str> = key
                .iter()
                .map(|(t, _)| match t {
                    Token::Word(w) => *w,
                    _ => "",
                })
                .collect();
            let value = symbols(&value, src, false);
            let end = if value.chars.is_empty() {
                key_span.end + 1
            } else {
                value.span.end
            };
            Some(Item::Header(Header {
                key: words.join(" "),
                key_span: key_span.clone(),
                value,
                span: key_span.start..end,
            }))
        }
        RawLine::Rule {
            lhs,
            arrow,
            rhs,
            weight,
        } => {
            let weight_toks: &[Tok<'_>] = weight.as_ref().map_or(&[], |(_, w)| w.as_slice());
            let arrow_toks: Vec<Tok<'_>> = arrow.iter().cloned().collect();
            let mut all = line_span(&[&lhs, &arrow_toks, &rhs, weight_toks]);
            if let Some((colon, _)) = &weight {
                all.start = all.start.min(colon.start);
                all.end = all.end.max(colon.end);
            }
            if lhs.is_empty() && arrow.is_none() && rhs.is_empty() && weight.is_none() {
                return None;
            }
            build_rule(&lhs, arrow, &rhs, weight.as_ref(), all, src, diags).map(Item::Production)
        }
    }
}

fn build_rule(
    lhs: &[Tok<'_>],
    arrow: Option<Tok<'_>>,
    rhs: &[Tok<'_>],
    weight: Option<&(SimpleSpan, Vec<Tok<'_>>)>,
    span: Span,
    src: &str,
    diags: &mut Diagnostics,
) -> Option<Production> {
    let errors_before = diags.len();
    let (parts, seps) = split_at_separators(lhs);
    let Some(arrow) = arrow else {
        push_lazily(diags, codes::MISSING_ARROW, || {
            missing_arrow(lhs, span, src)
        });
        return None;
    };
    if let Token::BadArrow(s) = arrow.0 {
        diags.push(
            Diagnostic::at(
                codes::MALFORMED_ARROW,
                range(arrow.1),
                format!("malformed arrow `{s}`"),
            )
            .with_label("pfg writes the arrow as `-->`")
            // A fix, not help alone: an editor offers it.
            .with_fix(
                range(arrow.1),
                "-->".into(),
                format!("replace `{s}` with `-->`"),
            ),
        );
    }
    let (left, pred, right) = contexts(&parts, &seps, diags)?;
    check_separator_sides(&parts, &seps, diags);
    // The listing's `enter` reads any string starting with `*` as empty.
    for part in [left, Some(pred), right, Some(rhs)].into_iter().flatten() {
        check_text_after_star(part, diags);
    }
    let pred_sym = symbols(pred, src, true);
    check_predecessor(pred, &pred_sym, seps.is_empty(), arrow, diags);
    let successor = symbols(rhs, src, true);
    if rhs.is_empty() {
        diags.push(missing_successor(arrow, src));
    }
    let weight = weight.and_then(|(colon, toks)| read_weight(*colon, toks, src, diags));
    if diags.0[errors_before..].iter().any(Diagnostic::is_error) {
        return None;
    }
    Some(Production {
        left: left.map(|l| symbols(l, src, true)),
        predecessor: pred_sym,
        right: right.map(|r| symbols(r, src, true)),
        successor,
        weight,
        arrow: range(arrow.1),
        span,
    })
}

/// The left-hand side split at its `<` and `>`: the parts, and the
/// separators between them.
fn split_at_separators<'a, 's>(lhs: &'a [Tok<'s>]) -> (Vec<&'a [Tok<'s>]>, Vec<Tok<'s>>) {
    let mut parts: Vec<&[Tok<'_>]> = Vec::new();
    let mut seps: Vec<Tok<'_>> = Vec::new();
    let mut start = 0;
    for (i, tok) in lhs.iter().enumerate() {
        if matches!(tok.0, Token::Lt | Token::Gt) {
            parts.push(&lhs[start..i]);
            seps.push(*tok);
            start = i + 1;
        }
    }
    parts.push(&lhs[start..]);
    (parts, seps)
}

/// A line without `-->`: perhaps a header missing its colon.
fn missing_arrow(lhs: &[Tok<'_>], span: Span, src: &str) -> Diagnostic {
    let at = if lhs.is_empty() {
        span
    } else {
        line_span(&[lhs])
    };
    let d = Diagnostic::at(codes::MISSING_ARROW, at.end..at.end, "missing `-->`")
        .with_label("expected `-->` here")
        .with_secondary(at, "this line is neither a header nor a production");
    let first: String = lhs
        .first()
        .map(|t| src[range(t.1)].to_string())
        .unwrap_or_default();
    let hint = nearest(&first, &HEADERS);
    match hint.first() {
        Some(h) if !first.is_empty() && first.len() > 1 => {
            d.with_help(format!("if this is a header, write it as `{h}: …`"))
        }
        _ => d.with_help("a production is written `predecessor --> successor`"),
    }
}

/// The left context, predecessor and right context (`left < pred > right`),
/// or `None` when the separators are out of order (reported).
type Contexts<'a, 's> = (Option<&'a [Tok<'s>]>, &'a [Tok<'s>], Option<&'a [Tok<'s>]>);

fn contexts<'a, 's>(
    parts: &[&'a [Tok<'s>]],
    seps: &[Tok<'s>],
    diags: &mut Diagnostics,
) -> Option<Contexts<'a, 's>> {
    Some(match seps {
        [] => (None, parts[0], None),
        [(Token::Lt, _)] => (Some(parts[0]), parts[1], None),
        [(Token::Gt, _)] => (None, parts[0], Some(parts[1])),
        [(Token::Lt, _), (Token::Gt, _)] => (Some(parts[0]), parts[1], Some(parts[2])),
        _ => {
            let (msg, bad) = misplaced(seps);
            diags.push(
                Diagnostic::at(codes::MISPLACED_CONTEXT, range(bad.1), msg)
                    .with_label("misplaced here")
                    .with_help("write `left < predecessor > right --> successor`; each of `<` and `>` at most once, `<` first"),
            );
            return None;
        }
    })
}

/// Reports a `<` or `>` with nothing on one side.
fn check_separator_sides(parts: &[&[Tok<'_>]], seps: &[Tok<'_>], diags: &mut Diagnostics) {
    for (i, sep) in seps.iter().enumerate() {
        let (before, after) = (parts[i], parts[i + 1]);
        let which = if sep.0 == Token::Lt { "<" } else { ">" };
        if before.is_empty() || after.is_empty() {
            let side = if before.is_empty() { "before" } else { "after" };
            let ctx_missing = (sep.0 == Token::Lt && before.is_empty())
                || (sep.0 == Token::Gt && after.is_empty());
            let help = if ctx_missing {
                "write `*` for an empty context, or leave out the separator"
            } else {
                "a production needs a predecessor between `<` and `>`"
            };
            diags.push(
                Diagnostic::at(
                    codes::MISPLACED_CONTEXT,
                    range(sep.1),
                    format!("nothing {side} `{which}`"),
                )
                .with_label(format!("`{which}` needs something {side} it"))
                .with_help(help),
            );
        }
    }
}

/// Reports text after a `*` that makes a string empty (it is not read).
fn check_text_after_star(part: &[Tok<'_>], diags: &mut Diagnostics) {
    if part.len() > 1 && part[0].0 == Token::Star {
        let rest = part[1].1.start..part[part.len() - 1].1.end;
        diags.push(
            Diagnostic::at(codes::TEXT_AFTER_STAR, rest, "text after `*` is ignored")
                .with_label("not read")
                .with_secondary(range(part[0].1), "`*` makes this string empty")
                .with_note("the Appendix A listing reads any string that starts with `*` as the empty string")
                .with_help("write `*` alone for an empty string, or remove the `*`"),
        );
    }
}

/// Reports a predecessor that is missing (with no context separator
/// either) or is `*`.
fn check_predecessor(
    pred: &[Tok<'_>],
    pred_sym: &Symbols,
    no_separators: bool,
    arrow: Tok<'_>,
    diags: &mut Diagnostics,
) {
    if pred.is_empty() && no_separators {
        diags.push(
            Diagnostic::at(
                codes::MISSING_PREDECESSOR,
                range(arrow.1),
                "missing predecessor",
            )
            .with_label("nothing before the arrow")
            .with_help("write the symbols this production replaces before `-->`"),
        );
    } else if pred_sym.star {
        diags.push(
            Diagnostic::at(
                codes::MISSING_PREDECESSOR,
                pred_sym.span.clone(),
                "`*` cannot be a predecessor",
            )
            .with_label("the predecessor must be at least one symbol")
            .with_note("`*` stands for an empty context or successor"),
        );
    }
}

/// Nothing after the arrow: the end of the file, or a missing successor.
fn missing_successor(arrow: Tok<'_>, src: &str) -> Diagnostic {
    let at = range(arrow.1);
    let at_eof = src[at.end..].trim().is_empty();
    let d = if at_eof {
        Diagnostic::at(
            codes::UNEXPECTED_EOF,
            at.end..at.end,
            "unexpected end of file",
        )
        .with_label("the file ends before the successor")
    } else {
        Diagnostic::at(codes::MISSING_SUCCESSOR, at, "missing successor")
            .with_label("nothing after the arrow")
    };
    d.with_help("write the successor, or `*` for the empty one")
}

/// The weight after the `:` at `colon`, which must be a positive finite
/// number; otherwise it is reported and `None`.
fn read_weight(
    colon: SimpleSpan,
    toks: &[Tok<'_>],
    src: &str,
    diags: &mut Diagnostics,
) -> Option<(f64, Span)> {
    let text: String = match (toks.first(), toks.last()) {
        (Some(a), Some(b)) => src[a.1.start..b.1.end].to_string(),
        _ => String::new(),
    };
    let wspan = if toks.is_empty() {
        range(colon)
    } else {
        line_span(&[toks])
    };
    match text.parse::<f64>() {
        Ok(w) if w > 0.0 && w.is_finite() => Some((w, wspan)),
        Ok(w) if w <= 0.0 => {
            diags.push(
                Diagnostic::at(
                    codes::BAD_PROBABILITY,
                    wspan,
                    format!("probability `{text}` is not positive"),
                )
                .with_label("must be greater than zero")
                .with_help("weights are relative: e.g. `: 0.33`, or `: 1` for each of equally likely productions"),
            );
            None
        }
        _ => {
            diags.push(
                Diagnostic::at(
                    codes::BAD_PROBABILITY,
                    wspan,
                    if text.is_empty() {
                        "missing probability after `:`".to_string()
                    } else if text.parse::<f64>().is_ok() {
                        format!("probability `{text}` is not a finite number")
                    } else {
                        format!("probability `{text}` is not a number")
                    },
                )
                .with_label("expected a positive number")
                .with_help("write the weight as a decimal number, e.g. `F --> F[+F]F : 0.33`"),
            );
            None
        }
    }
}

/// The message for a bad sequence of separators and the separator to blame.
fn misplaced<'a>(seps: &'a [Tok<'a>]) -> (String, &'a Tok<'a>) {
    let mut seen_lt = false;
    let mut seen_gt = false;
    for sep in seps {
        match sep.0 {
            Token::Lt if seen_lt => return ("more than one `<`".into(), sep),
            Token::Lt if seen_gt => return ("`<` after `>`".into(), sep),
            Token::Lt => seen_lt = true,
            _ if seen_gt => return ("more than one `>`".into(), sep),
            _ => seen_gt = true,
        }
    }
    ("misplaced context separator".into(), &seps[0])
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
    fn parses_headers_and_all_production_forms() {
        let f = parse_ok(
            "derivation length: 30\naxiom: F1F1F1\n0 < 0 > 1 --> 1[+F1F1]\n* < + > * --> -\nb < a --> b\nF > G --> H\nF --> F[+F]F : 0.33\n",
        );
        assert_eq!(f.items.len(), 7);
        let Item::Production(p) = &f.items[2] else {
            panic!()
        };
        assert_eq!(p.left.as_ref().unwrap().text(), "0");
        assert_eq!(p.predecessor.text(), "0");
        assert_eq!(p.right.as_ref().unwrap().text(), "1");
        assert_eq!(p.successor.text(), "1[+F1F1]");
        let Item::Production(p) = &f.items[3] else {
            panic!()
        };
        assert!(p.left.as_ref().unwrap().star && p.right.as_ref().unwrap().star);
        let Item::Production(p) = &f.items[6] else {
            panic!()
        };
        assert_eq!(p.weight.as_ref().unwrap().0, 0.33);
    }

    #[test]
    fn symbol_spans_point_at_each_character() {
        let f = parse_ok("axiom: Fé+F");
        let Item::Header(h) = &f.items[0] else {
            panic!()
        };
        let spans: Vec<_> = h.value.chars.iter().map(|(_, s)| s.clone()).collect();
        assert_eq!(spans, vec![7..8, 8..10, 10..11, 11..12]);
    }

    #[test]
    fn shape_errors_have_their_own_codes() {
        assert_eq!(codes_of("F F+F\n"), vec!["E0004"]);
        assert_eq!(codes_of("F -> F+F\n"), vec!["E0005"]);
        assert_eq!(codes_of("a > b < c --> d\n"), vec!["E0006"]);
        assert_eq!(codes_of("< a --> b\n"), vec!["E0006"]);
        assert_eq!(codes_of("--> F\n"), vec!["E0009"]);
        assert_eq!(codes_of("F -->\nG --> H\n"), vec!["E0008"]);
        assert_eq!(codes_of("F -->"), vec!["E0007"]);
        assert_eq!(codes_of("F --> G : 0\n"), vec!["E0204"]);
        assert_eq!(codes_of("F --> G : inf\n"), vec!["E0204"]);
        assert_eq!(codes_of("F --> G : nan\n"), vec!["E0204"]);
        assert_eq!(codes_of("F --> G --> H\n"), vec!["E0003"]);
    }

    #[test]
    fn recovers_and_reports_every_bad_line() {
        let mut d = Diagnostics::default();
        let f = parse("F -> G\nA --> B\nF F\nC --> D --> E\nX --> Y\n", &mut d);
        let codes: Vec<_> = d.iter().map(|d| d.code.0).collect();
        assert_eq!(codes, vec!["E0003", "E0005", "E0004"]);
        // The good lines survive.
        assert_eq!(f.items.len(), 2);
    }
}
