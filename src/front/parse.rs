//! Reporting what a chumsky parser could not read, as every notation's
//! parser does: each syntax error a diagnostic (E0003, or E0007 at the end
//! of the file), built only while the file has not repeated it too often.

use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::front::repeats::push_lazily;
use chumsky::error::Rich;

/// Pushes each of a parser's `errors` to `diags` as [`syntax_error`] makes
/// it with `help`. A file may repeat a mistake on every line: past the most
/// kept, the diagnostics are counted without being built.
pub fn push_syntax_errors<'a, T: std::fmt::Display + 'a>(
    diags: &mut Diagnostics,
    errors: impl IntoIterator<Item = Rich<'a, T>>,
    help: impl Fn(&T) -> Option<&'static str>,
) {
    for err in errors {
        let code = match err.found() {
            Some(_) => codes::SYNTAX,
            None => codes::UNEXPECTED_EOF,
        };
        push_lazily(diags, code, || syntax_error(&err, &help));
    }
}

/// A parser's syntax error as a diagnostic: at the end of input E0007
/// "unexpected end of file", else E0003 "unexpected TOKEN" labelled with the
/// tokens that were expected there. `help` may add a hint for the token
/// found.
pub fn syntax_error<T: std::fmt::Display>(
    err: &Rich<'_, T>,
    help: impl Fn(&T) -> Option<&'static str>,
) -> Diagnostic {
    let span = err.span().into_range();
    let expected: Vec<String> = err
        .expected()
        .map(|e| e.to_string().trim_matches('\'').to_string())
        .filter(|e| e != "something else")
        .collect();
    let expected = match expected.len() {
        0 => None,
        _ => Some(expected.join(", ")),
    };
    match err.found() {
        None => {
            let d = Diagnostic::at(codes::UNEXPECTED_EOF, span, "unexpected end of file")
                .with_label("the file ends here");
            match expected {
                Some(e) => d.with_help(format!("expected {e}")),
                None => d,
            }
        }
        Some(tok) => {
            let d = Diagnostic::at(codes::SYNTAX, span, format!("unexpected {tok}"));
            let d = match &expected {
                Some(e) => d.with_label(format!("expected {e}")),
                None => d.with_label("not expected here"),
            };
            match help(tok) {
                Some(h) => d.with_help(h),
                None => d,
            }
        }
    }
}

/// What `parse` makes of `src`, which must read without a diagnostic (the
/// parsers' tests).
#[cfg(test)]
pub(crate) fn parse_clean<F>(parse: impl FnOnce(&str, &mut Diagnostics) -> F, src: &str) -> F {
    let mut d = Diagnostics::default();
    let f = parse(src, &mut d);
    assert!(d.is_empty(), "{d:#?}");
    f
}

/// The codes of what `parse` reports reading `src` (the parsers' tests).
#[cfg(test)]
pub(crate) fn parse_codes<F>(
    parse: impl FnOnce(&str, &mut Diagnostics) -> F,
    src: &str,
) -> Vec<&'static str> {
    let mut d = Diagnostics::default();
    parse(src, &mut d);
    d.iter().map(|d| d.code.0).collect()
}
