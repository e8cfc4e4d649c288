//! Rules as macros: declaring them, resolving each one's expansion, unit
//! and self-resemblance count, and expanding strings through them.

use super::names::Piece;
use super::{opener, Ctx, Ev, RuleSrc, State};
use crate::diagnostics::{codes, Diagnostic};
use crate::front::stl::ast::{Elem, Num, Str};
use crate::front::stl::growth::Comp;
use crate::front::stl::parser::RESERVED;
use crate::ir::Span;

impl Ctx<'_> {
    /// Resolves rule `r` (its expansion, unit and count); `None` if it has
    /// errors (already reported).
    pub(super) fn resolve(&mut self, r: usize) -> Option<()> {
        match self.state[r] {
            State::Done => return Some(()),
            State::Failed | State::Busy => return None,
            State::New => {}
        }
        self.state[r] = State::Busy;
        self.stack.push(r);
        self.repeats.begin_item();
        let body = self.rules[r].body.clone();
        let ok = if let [Elem::Resemble {
            count,
            body: x,
            span,
        }] = body.elems.as_slice()
        {
            let n = self.count(count);
            let unit = self.expand(x);
            match (n, unit) {
                (Some(n), Some(unit)) => {
                    self.unit_ref[r] = match x.elems.as_slice() {
                        [Elem::Name {
                            text,
                            entries: None,
                            ..
                        }] => self.by_name.get(text).copied(),
                        _ => None,
                    };
                    let full = self.rewrite(&unit, n, span);
                    self.count[r] = Some(n);
                    self.unit[r] = unit;
                    match full {
                        Some(f) => {
                            self.full[r] = f;
                            true
                        }
                        None => false,
                    }
                }
                _ => false,
            }
        } else {
            match self.expand(&body) {
                Some(f) => {
                    self.unit[r] = f.clone();
                    self.full[r] = f;
                    true
                }
                None => false,
            }
        };
        self.repeats.end_item(self.diags, "in this rule");
        self.stack.pop();
        self.state[r] = if ok { State::Done } else { State::Failed };
        ok.then_some(())
    }

    /// A count of `[I n X]`.
    pub(super) fn count(&mut self, n: &Num) -> Option<u32> {
        if n.value < 0.0 || n.value.fract() != 0.0 || !n.value.is_finite() {
            self.diags.push(
                Diagnostic::at(
                    codes::STL_NEGATIVE,
                    n.span.clone(),
                    format!(
                        "the self-resemblance count must be a whole number of 0 or more, not {}",
                        n.value
                    ),
                )
                .with_label("not a count")
                .with_help("write the number of rewritings, e.g. `[I 3 R1]`"),
            );
            return None;
        }
        Some(n.value.min(u32::MAX as f64) as u32)
    }

    /// What F becomes after `n` rewritings `F -> unit`.
    fn rewrite(&mut self, unit: &[Comp], n: u32, span: &Span) -> Option<Vec<Comp>> {
        let fs = unit.iter().filter(|c| **c == Comp::F).count();
        if n == 0 {
            return Some(vec![Comp::F]);
        }
        if fs == 1 {
            // F -> A F B: n rewritings give A^n F B^n, built directly.
            let at = unit.iter().position(|c| *c == Comp::F).unwrap_or(0);
            let (a, b) = (&unit[..at], &unit[at + 1..]);
            let len = (n as usize)
                .saturating_mul(unit.len() - 1)
                .saturating_add(1);
            if !self.room(0, len, span) {
                return None;
            }
            let mut out = Vec::with_capacity(len);
            for _ in 0..n {
                out.extend_from_slice(a);
            }
            out.push(Comp::F);
            for _ in 0..n {
                out.extend_from_slice(b);
            }
            return Some(out);
        }
        let mut cur = vec![Comp::F];
        for _ in 0..n {
            let f = cur.iter().filter(|c| **c == Comp::F).count();
            if f == 0 {
                break;
            }
            let new_len = (cur.len() - f).saturating_add(f.saturating_mul(unit.len()));
            if !self.room(0, new_len, span) {
                return None;
            }
            let mut next = Vec::with_capacity(new_len);
            for &c in &cur {
                if c == Comp::F {
                    next.extend_from_slice(unit);
                } else {
                    next.push(c);
                }
            }
            cur = next;
        }
        Some(cur)
    }

    /// The macro expansion of a string (no levels).
    pub(super) fn expand(&mut self, s: &Str) -> Option<Vec<Comp>> {
        let mut out = Vec::new();
        let mut ok = true;
        for e in &s.elems {
            match e {
                Elem::Turn { left, .. } => out.push(if *left { Comp::Plus } else { Comp::Minus }),
                Elem::Branch { body, span } => match self.deeper(&opener(span), |c| c.expand(body))
                {
                    Some(b) if self.room(out.len(), b.len() + 2, span) => {
                        out.push(Comp::Open);
                        out.extend(b);
                        out.push(Comp::Close);
                    }
                    _ => ok = false,
                },
                Elem::Resemble { count, body, span } => {
                    let x = self.deeper(&opener(span), |c| c.expand(body));
                    let n = self.count(count);
                    match (x, n) {
                        (Some(x), Some(n)) => match self.rewrite(&x, n, span) {
                            Some(f) if self.room(out.len(), f.len(), span) => out.extend(f),
                            _ => ok = false,
                        },
                        _ => ok = false,
                    }
                }
                Elem::Name {
                    text,
                    span,
                    entries,
                } => {
                    ok &= self.each_piece(text, span, entries.as_ref(), |c, piece| match piece {
                        Piece::C(comp) => {
                            out.push(comp);
                            true
                        }
                        Piece::Rule(r, rspan, None) => {
                            // A macro: the rule's expansion.
                            if c.term(r, &rspan, None, false).is_none()
                                || !c.room(out.len(), c.full[r].len(), &rspan)
                            {
                                return false;
                            }
                            out.extend_from_slice(&c.full[r]);
                            true
                        }
                        Piece::Rule(r, rspan, ents) => {
                            let Some(t) = c.term(r, &rspan, ents, false) else {
                                return false;
                            };
                            let mut evs = Vec::new();
                            c.expand_term(&t, None, &mut evs);
                            if !c.room(out.len(), evs.len(), &rspan) {
                                return false;
                            }
                            out.extend(evs.into_iter().filter_map(|e| match e {
                                Ev::Component(c) => Some(c),
                                _ => None,
                            }));
                            true
                        }
                    });
                }
            }
        }
        ok.then_some(out)
    }

    pub(super) fn no_branches_component(&mut self, span: &Span, c: Comp) {
        self.report(codes::STL_NO_BRANCHES, |_| {
            Diagnostic::at(
                codes::STL_NO_BRANCHES,
                span.clone(),
                format!("branching entries after the drawing component `{c:?}`"),
            )
            .with_label("only a rule with branches takes `{…}`")
            .with_help("write the entries after a rule name: `R1{R2, ~}`")
        });
    }

    /// Declares a rule (resolved later, once all rules are known); false if
    /// its name is reserved or taken.
    pub(super) fn declare_rule(
        &mut self,
        name: &str,
        name_span: &Span,
        body: &Str,
        span: &Span,
    ) -> bool {
        if RESERVED.contains(&name) || name == "DFS" {
            self.diags.push(
                Diagnostic::at(codes::STL_RESERVED_NAME, name_span.clone(), format!("`{name}` cannot name a rule"))
                    .with_label("reserved")
                    .with_help("F, L, R draw, B and L are the stem parameters, I counts rewritings; name rules R1, R2, …"),
            );
            return false;
        }
        if let Some(&first) = self.by_name.get(name) {
            let fs = self.rules[first].name_span.clone();
            self.diags.push(
                Diagnostic::at(
                    codes::STL_DUPLICATE,
                    name_span.clone(),
                    format!("rule `{name}` is defined twice"),
                )
                .with_label("defined again here")
                .with_secondary(fs, "first defined here")
                .with_help("give this rule another name"),
            );
            return false;
        }
        self.by_name.insert(name.to_string(), self.rules.len());
        self.name_index = None;
        self.max_name = self.max_name.max(name.len());
        self.rules.push(RuleSrc {
            name: name.to_string(),
            name_span: name_span.clone(),
            span: span.clone(),
            body: body.clone(),
        });
        true
    }

    /// Resolves every declared rule; false if any has errors.
    pub(super) fn resolve_rules(&mut self) -> bool {
        let n = self.rules.len();
        self.state = vec![State::New; n];
        self.full = vec![Vec::new(); n];
        self.unit = vec![Vec::new(); n];
        self.count = vec![None; n];
        self.unit_ref = vec![None; n];
        let mut ok = true;
        for r in 0..n {
            if self.resolve(r).is_none() {
                ok = false;
            }
        }
        ok
    }
}
