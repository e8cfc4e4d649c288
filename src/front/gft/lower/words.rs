//! Words: splitting runs of names into declared symbols (the longest
//! first), balancing brackets, and reporting misspelt names.

use super::{err, Cx, Locals};
use crate::common::vocabulary;
use crate::common::vocabulary::TurtleSet;
use crate::diagnostics::codes;
use crate::front::gft::ast;
use crate::front::gft::ast::Piece;
use crate::front::repeats::push_lazily;
use crate::ir::program::Expr;
use crate::ir::{Span, SymbolId, Word};

impl Cx<'_> {
    /// A word's modules, their parameter expressions (empty when none has
    /// any) and spans. Unbalanced brackets are read as written (W0901).
    pub(super) fn word(
        &mut self,
        w: &ast::Word,
        locals: &mut Locals,
    ) -> (Word, Vec<Vec<Expr>>, Vec<Span>) {
        let (word, args, spans) = self.word_unbalanced(w, locals);
        self.balance(w, word.symbols(), &spans);
        (word, args, spans)
    }

    /// A word's modules, parameter expressions and spans, its brackets
    /// unchecked (an STL seed's words open branches that its terms fill).
    pub(super) fn word_unbalanced(
        &mut self,
        w: &ast::Word,
        locals: &mut Locals,
    ) -> (Word, Vec<Vec<Expr>>, Vec<Span>) {
        let mut ids: Vec<SymbolId> = Vec::new();
        let mut spans: Vec<Span> = Vec::new();
        let mut args: Vec<Vec<Expr>> = Vec::new();
        let mut guard: Option<f64> = None;
        for piece in &w.pieces {
            match piece {
                Piece::Guard(p, _) => guard = Some(*p),
                Piece::Args(list, span) => {
                    if ids.is_empty() {
                        self.diags.push(err(
                            codes::SYNTAX,
                            span,
                            "parameters without a module",
                            "no symbol before `(`",
                            "write the symbol first: `F(1)`",
                        ));
                        continue;
                    }
                    args.resize(ids.len(), Vec::new());
                    let e: Vec<Expr> = list.iter().map(|e| self.expr(e, locals)).collect();
                    *args.last_mut().expect("one per module") = e;
                }
                Piece::Quoted(name, span) => {
                    let id = self.symbol(name, span, guard.take());
                    ids.push(id);
                    spans.push(span.clone());
                }
                Piece::Text(text, span) => {
                    self.misspelt_name(text, span);
                    for (name, s) in self.split(text, span.start) {
                        let id = self.symbol(&name, &s, guard.take());
                        ids.push(id);
                        spans.push(s);
                    }
                }
            }
        }
        // The parameters are expressions beside the word, as cpfg's reader
        // keeps them: the word itself holds symbols only.
        let word = Word::from(ids.clone());
        let has_args = args.iter().any(|a| !a.is_empty());
        if has_args {
            args.resize(ids.len(), Vec::new());
        } else {
            args.clear();
        }
        (word, args, spans)
    }

    /// Warns of a `]` without `[` and an unclosed `[` (W0901): cpfg and
    /// Fractint words may be so, and the IR holds them as written.
    fn balance(&mut self, w: &ast::Word, ids: &[SymbolId], spans: &[Span]) {
        let mut depth = 0i64;
        for (id, s) in ids.iter().zip(spans) {
            depth += i64::from(*id == SymbolId::OPEN) - i64::from(*id == SymbolId::CLOSE);
            if depth < 0 {
                self.diags.push(err(
                    codes::GFT_UNBALANCED_BRACKETS,
                    s,
                    "`]` without `[`",
                    "closes no branch",
                    "remove it unless another word opens its branch",
                ));
                depth = 0;
            }
        }
        if depth > 0 {
            self.diags.push(err(
                codes::GFT_UNBALANCED_BRACKETS,
                &w.span,
                "unclosed `[`",
                "a branch is not closed",
                "close it with `]` unless another word closes it",
            ));
        }
    }

    pub(super) fn symbol(&mut self, name: &str, span: &Span, guard: Option<f64>) -> SymbolId {
        let id = self.declare_use(name, span);
        match guard {
            Some(p) => {
                let g = self.sys.symbols.intern_guarded(p, id);
                let n = self.sys.symbols.len();
                if self.sys.interpretation.len() < n {
                    self.sys.interpretation.resize(n, None);
                }
                g
            }
            None => id,
        }
    }

    fn declare_use(&mut self, name: &str, span: &Span) -> SymbolId {
        let id = self.sys.intern(name);
        self.spans.symbols.entry(id).or_insert_with(|| span.clone());
        if self.set == TurtleSet::Fractint && self.sys.op(id).is_none() {
            let n = (std::f64::consts::TAU / self.sys.settings.delta).round();
            if let Some(op) = vocabulary::fractint_op(name, n.clamp(0.0, u32::MAX as f64) as u32) {
                self.sys.set_interpretation(id, op);
            }
        }
        id
    }

    /// Warns (W0903) of a run of three or more letters that no declared
    /// name matches, so that it is read one letter a module, when it is
    /// near a name the file declares (`symbol apex`, then `apx`).
    fn misspelt_name(&mut self, text: &str, span: &Span) {
        if text.len() < 3 || !text.chars().all(|c| c.is_ascii_alphabetic()) {
            return;
        }
        if self.names.longest_prefix(text) > 0 {
            return;
        }
        let own: Vec<&str> = (self.names.names.iter())
            .map(String::as_str)
            .filter(|n| !self.set.names().contains(n))
            .collect();
        if own.is_empty() {
            return;
        }
        if let Some(near) = self.suggester.nearest(text, &own).first() {
            let near = near.to_string();
            push_lazily(self.diags, codes::GFT_UNDECLARED_NAME, || {
                err(
                    codes::GFT_UNDECLARED_NAME,
                    span,
                    format!(
                        "`{text}` is no declared name: it is read as {} modules",
                        text.len()
                    ),
                    "one module per letter",
                    &format!("did you mean `{near}`?"),
                )
            });
        }
    }

    /// Splits symbol text by the longest declared name (one character
    /// otherwise; a Fractint command with its number).
    pub(super) fn split(&self, text: &str, at: usize) -> Vec<(String, Span)> {
        let mut out = Vec::new();
        let mut i = 0;
        while i < text.len() {
            let rest = &text[i..];
            let mut len = self.names.longest_prefix(rest);
            let c = rest.chars().next().expect("not empty");
            if len == 0 && self.set == TurtleSet::Fractint && vocabulary::fractint_takes_number(c) {
                len = c.len_utf8()
                    + rest[c.len_utf8()..]
                        .find(|d: char| !(d.is_ascii_digit() || matches!(d, '.' | 'q' | 'i')))
                        .unwrap_or(rest.len() - c.len_utf8());
            }
            let len = len.max(c.len_utf8());
            out.push((rest[..len].to_string(), at + i..at + i + len));
            i += len;
        }
        out
    }
}
