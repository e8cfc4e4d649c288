//! Brackets and colour steps in a string: each `]` closes a `[`, each `}`
//! a `{`, and what is left open is reported.

use super::Cx;
use crate::diagnostics::{codes, Diagnostic};
use crate::ir::Span;

/// The brackets of a string not yet closed, and at each bracket depth the
/// `{` not yet closed by `}`.
pub(super) struct Nesting {
    pub(super) open: Vec<Span>,
    pub(super) colours: Vec<Vec<Span>>,
}

impl Nesting {
    pub(super) fn new() -> Self {
        Nesting {
            open: Vec::new(),
            colours: vec![Vec::new()],
        }
    }

    pub(super) fn open(&mut self, span: &Span) {
        self.open.push(span.clone());
        self.colours.push(Vec::new());
    }

    pub(super) fn close(&mut self, cx: &mut Cx<'_>, span: &Span) {
        if self.open.pop().is_some() {
            self.colours.pop();
            return;
        }
        cx.report(codes::LINF_UNBALANCED, |_| {
            Diagnostic::at(
                codes::LINF_UNBALANCED,
                span.clone(),
                "`]` without a matching `[`",
            )
            .with_label("nothing to close")
            .with_help("remove this `]` or add the `[` that opens the branch")
        });
    }

    pub(super) fn next_colour(&mut self, span: &Span) {
        self.colours
            .last_mut()
            .expect("never empty")
            .push(span.clone());
    }

    pub(super) fn previous_colour(&mut self, cx: &mut Cx<'_>, span: &Span) {
        if self
            .colours
            .last_mut()
            .expect("never empty")
            .pop()
            .is_some()
        {
            return;
        }
        cx.report(codes::LINF_COLOUR_BALANCE, |_| {
            Diagnostic::at(
                codes::LINF_COLOUR_BALANCE,
                span.clone(),
                "`}` without a `{` before it in this string",
            )
            .with_label("goes back to a colour chosen outside this string")
            .with_help("`}` returns to the previous colour; pair it with a `{`")
        });
    }

    /// Reports every `[` never closed, and the first `{` never closed
    /// outside a branch (a branch restores the colour).
    pub(super) fn check_closed(self, cx: &mut Cx<'_>) {
        for span in self.open {
            cx.report(codes::LINF_UNBALANCED, |_| {
                Diagnostic::at(codes::LINF_UNBALANCED, span, "`[` is never closed")
                    .with_label("this branch has no `]`")
                    .with_help("add `]` where the branch ends")
            });
        }
        if let Some(unclosed) = self.colours.first().and_then(|c| c.first()) {
            cx.diags.push(
                Diagnostic::at(
                    codes::LINF_COLOUR_BALANCE,
                    unclosed.clone(),
                    "`{` is never closed by `}` in this string",
                )
                .with_label("the colour stays changed after this string")
                .with_help(
                    "close it with `}`, or put it inside a branch `[…]`, which restores the colour",
                ),
            );
        }
    }
}
