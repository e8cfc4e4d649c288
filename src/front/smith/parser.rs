//! The Smith parser (chumsky 0.12 over logos tokens): each line is
//! `key: value` or empty. A line chumsky rejects (no key, no `:`) is a
//! syntax error, and the parser recovers at the next line, so every error
//! of a file is reported in one run.

use super::ast::{Entry, File};
use super::lexer::{lex, Token};
use crate::diagnostics::Diagnostics;
use crate::front::parse::push_syntax_errors;
use chumsky::input::ValueInput;
use chumsky::prelude::*;

type Tok<'src> = (Token<'src>, SimpleSpan);

/// One line as chumsky sees it: the key and the value's tokens.
type RawLine<'src> = (Tok<'src>, Vec<Tok<'src>>);

fn line_parser<'tokens, 'src: 'tokens, I>(
) -> impl Parser<'tokens, I, Vec<Option<RawLine<'src>>>, extra::Err<Rich<'tokens, Token<'src>>>>
where
    I: ValueInput<'tokens, Token = Token<'src>, Span = SimpleSpan>,
{
    let key = select! { Token::Key(k) => Token::Key(k) }
        .map_with(|t, e| (t, e.span()))
        .labelled("a key");
    let value_tok = select! { Token::Key(k) => Token::Key(k), Token::Text(t) => Token::Text(t) }
        .map_with(|t, e| (t, e.span()));
    let end_of_line = just(Token::Newline).ignored().or(end()).rewind();
    let line = key
        .then_ignore(just(Token::Colon).labelled("`:`"))
        .then(value_tok.repeated().collect::<Vec<_>>())
        .then_ignore(end_of_line.labelled("end of line"))
        .map(Some)
        .recover_with(via_parser(
            any()
                .filter(|t: &Token| *t != Token::Newline)
                .repeated()
                .at_least(1)
                .to(None),
        ));
    line.or_not()
        .map(Option::flatten)
        .separated_by(just(Token::Newline))
        .collect::<Vec<_>>()
        .then_ignore(end())
}

/// Parses Smith source text into an AST. Never fails: problems are pushed
/// to `diags`.
pub fn parse(src: &str, diags: &mut Diagnostics) -> File {
    let tokens: Vec<Tok<'_>> = lex(src, diags)
        .into_iter()
        .map(|(t, s)| (t, SimpleSpan::from(s)))
        .collect();
    let eoi = SimpleSpan::from(src.len()..src.len());
    let (lines, errors) = line_parser()
        .parse(tokens.as_slice().map(eoi, |(t, s)| (t, s)))
        .into_output_errors();
    push_syntax_errors(diags, errors, |_| {
        Some("each line is `key: value`, as in `rules: 0.1[1].1.1.0.11.1.0`")
    });
    let mut file = File::default();
    for ((key, key_span), value) in lines.unwrap_or_default().into_iter().flatten() {
        let Token::Key(key) = key else { continue };
        let value_span = match (value.first(), value.last()) {
            (Some(a), Some(b)) => a.1.start..b.1.end,
            _ => key_span.end + 1..key_span.end + 1,
        };
        let value_span = value_span.start.min(src.len())..value_span.end.min(src.len());
        file.entries.push(Entry {
            key: key.to_ascii_lowercase(),
            key_span: key_span.into_range(),
            value: src[value_span.clone()].to_string(),
            value_span,
        });
    }
    file
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::codes;

    #[test]
    fn lines_become_entries_and_a_bad_line_is_one_error() {
        let mut d = Diagnostics::default();
        let f = parse("rules: 0.1.0\n\n: x\naxiom: 1 1\n", &mut d);
        let keys: Vec<_> = f.entries.iter().map(|e| e.key.as_str()).collect();
        assert_eq!(keys, ["rules", "axiom"]);
        assert_eq!(f.entries[1].value, "1 1");
        assert_eq!(d.len(), 1);
        assert_eq!(d.0[0].code, codes::SYNTAX);
    }
}
