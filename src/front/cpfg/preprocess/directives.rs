//! Reading a directive line and reporting the ones that cannot be read:
//! unknown directives, malformed ones, tokens after them.

use super::output::Out;
use super::tokens::{span_of, strip_ws, tokenize, Kind, Tok};
use super::{Cond, Directive, Pp};
use crate::diagnostics::{codes, nearest, Diagnostic};
use std::ops::Range;

impl Pp<'_> {
    /// Reads the directive whose `#` is at `hash` and whose logical line ends
    /// at `end`. In skipped text (not `active`) only the conditionals are
    /// followed.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn directive(
        &mut self,
        clean: &str,
        hash: usize,
        end: usize,
        conds: &mut Vec<Cond>,
        out: &mut Out,
        active: bool,
        main: bool,
    ) {
        let toks = tokenize(&clean[hash + 1..end], hash + 1, true);
        let mut it = toks.iter().filter(|t| t.kind != Kind::Ws).peekable();
        let line_span = hash..clean[..end].trim_end().len().max(hash + 1);
        let Some(name_tok) = it.next() else {
            return; // the null directive `#`
        };
        let name = &*name_tok.text;
        let name_span = name_tok.origin.clone();
        // The tokens after the directive's name.
        let rest: Vec<Tok> = {
            let idx = toks
                .iter()
                .position(|t| std::ptr::eq(t, name_tok))
                .unwrap_or(0);
            toks[idx + 1..].to_vec()
        };
        let rest_span = span_of(&strip_ws(rest.clone())).unwrap_or(name_span.end..name_span.end);
        let dir = Directive {
            name,
            rest,
            rest_span,
            name_span,
            line_span,
        };
        match name {
            "if" | "ifdef" | "ifndef" => {
                let value = active && self.condition(&dir);
                conds.push(Cond {
                    active: active && value,
                    taken: value,
                    parent: active,
                    seen_else: false,
                    span: dir.line_span,
                });
            }
            "elif" | "else" | "endif" => self.next_group(dir, conds),
            _ if !active => {} // other directives of skipped text are not read
            "define" => self.define(dir.rest, dir.line_span, main),
            "undef" => {
                if let Some(m) = self.macro_operand(&dir) {
                    self.macros.remove(&*m);
                }
            }
            "include" => self.include_directive(dir.rest, dir.line_span, out),
            "error" => {
                let msg = clean[dir.rest_span.clone()].trim().to_string();
                self.diags.push(
                    Diagnostic::at(
                        codes::CPFG_ERROR_DIRECTIVE,
                        dir.line_span,
                        format!("#error {msg}"),
                    )
                    .with_label("the file stops itself here"),
                );
            }
            "pragma" | "line" | "warning" | "ident" | "sccs" => {}
            _ => self.unknown_directive(name_tok, hash),
        }
    }

    /// A `#` line that is no directive cpfg's preprocessor knows.
    fn unknown_directive(&mut self, name_tok: &Tok, hash: usize) {
        let name = &*name_tok.text;
        let known = [
            "define", "undef", "include", "if", "ifdef", "ifndef", "elif", "else", "endif",
            "error", "pragma", "line",
        ];
        let mut d = Diagnostic::at(
            codes::CPFG_UNKNOWN_DIRECTIVE,
            hash..name_tok.origin.end,
            format!("unknown preprocessor directive `#{name}`"),
        )
        .with_label("not a directive");
        let suggestion = if name_tok.kind == Kind::Ident {
            nearest(name, &known).first().copied()
        } else {
            None
        };
        if let Some(n) = suggestion {
            d = d.suggesting(format!("#{n}"));
        } else {
            d = d.with_help(
                "a line cannot start with `#` in cpfg (the preprocessor reads it as a directive); \
                 put something before the module, e.g. `* < #(w)` as a context",
            );
        }
        self.diags.push(d);
    }

    pub(super) fn bad_directive(&mut self, span: Range<usize>, msg: String) {
        self.diags
            .push(Diagnostic::at(codes::CPFG_BAD_DIRECTIVE, span, msg).with_label("here"));
    }

    pub(super) fn extra_tokens(&mut self, words: &[Tok], name: &str) {
        if let Some(s) = span_of(&strip_ws(words.to_vec())) {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_EXTRA_TOKENS,
                    s,
                    format!("extra text after `#{name}` is ignored"),
                )
                .with_label("ignored"),
            );
        }
    }
}
