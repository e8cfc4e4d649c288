//! Branching terms and the seed: reading `R{e1, …}` against the rule's
//! branches, and expanding terms and the seed into the events the growth
//! walk and the level word read.

use super::names::Piece;
use super::{opener, Ctx, Ev, Part, State, Term, TermEntry, MAX_EXPANSION};
use crate::diagnostics::{codes, Diagnostic};
use crate::front::stl::ast::{Elem, Entries, Entry, Str};
use crate::front::stl::growth::{branches, Comp};
use crate::ir::Span;

impl Ctx<'_> {
    /// A branching term for rule `r` written at `span` with `entries`.
    pub(super) fn term(
        &mut self,
        r: usize,
        span: &Span,
        entries: Option<&Entries>,
        od: bool,
    ) -> Option<Term> {
        if self.state[r] == State::Busy {
            let from = self.stack.iter().position(|&x| x == r).unwrap_or(0);
            let path: Vec<&str> = self.stack[from..]
                .iter()
                .chain(std::iter::once(&r))
                .map(|&x| self.rules[x].name.as_str())
                .collect();
            let path = path.join(" -> ");
            let def = self.rules[r].name_span.clone();
            self.diags.push(
                Diagnostic::at(
                    codes::STL_CYCLE,
                    span.clone(),
                    format!("rule `{}` is defined through itself: {path}", self.rules[r].name),
                )
                .with_label("uses the rule being defined")
                .with_secondary(def, "defined here")
                .with_help("a rule is a macro and cannot use itself; grow it from a SEED with a LAYOUT, or write `[I n R]`"),
            );
            return None;
        }
        if self.state[r] == State::New {
            // Expanding the rule's body is one level deeper. (Every rule is
            // resolved before the seed is read, so only a rule used through
            // a rule gets here unresolved.)
            self.deeper(span, |c| c.resolve(r))?;
        } else {
            self.resolve(r)?;
        }
        let nb = branches(&self.full[r]).len();
        let Some(entries) = entries else {
            return Some(Term {
                rule: r,
                entries: Vec::new(),
                growth: od && nb > 0,
            });
        };
        if nb == 0 {
            let def = self.rules[r].span.clone();
            self.diags.push(
                Diagnostic::at(
                    codes::STL_NO_BRANCHES,
                    span.start..entries.span.end,
                    format!("`{}` has no branches to extend", self.rules[r].name),
                )
                .with_label("a branching term on a rule without branches")
                .with_secondary(def, "this rule has no top-level `[...]`")
                .with_help(format!("write `{}` without `{{…}}`", self.rules[r].name)),
            );
            return None;
        }
        let mut ok = true;
        if entries.list.len() > nb {
            let extra = entries.list[nb].span();
            let def = self.rules[r].span.clone();
            self.diags.push(
                Diagnostic::at(
                    codes::STL_TOO_MANY_ENTRIES,
                    extra,
                    format!(
                        "`{}` has {nb} branch{}, but {} entries are given",
                        self.rules[r].name,
                        if nb == 1 { "" } else { "es" },
                        entries.list.len()
                    ),
                )
                .with_label(format!("entry {} has no branch to extend", nb + 1))
                .with_secondary(
                    def,
                    format!(
                        "`{}` is defined here with {nb} top-level branch{}",
                        self.rules[r].name,
                        if nb == 1 { "" } else { "es" }
                    ),
                )
                .with_help(format!("give at most {nb} entries, one per branch")),
            );
            ok = false;
        }
        let mut list = Vec::new();
        for e in &entries.list {
            match e {
                Entry::Empty(_) => list.push(TermEntry::Empty),
                Entry::Failed(_) => list.push(TermEntry::Failed),
                Entry::Term {
                    name,
                    name_span,
                    entries,
                } => {
                    let Some(k) = self.rule_named(name, name_span) else {
                        ok = false;
                        continue;
                    };
                    let term =
                        self.deeper(name_span, |c| c.term(k, name_span, entries.as_ref(), od));
                    match term {
                        Some(t) => list.push(TermEntry::Term(t)),
                        None => ok = false,
                    }
                }
            }
        }
        ok.then_some(Term {
            rule: r,
            entries: list,
            growth: false,
        })
    }

    /// Expands a term into events; `level` is the term's level (None in a
    /// macro: no level events).
    pub(super) fn expand_term(&mut self, t: &Term, level: Option<u32>, out: &mut Vec<Ev>) {
        if self.too_large {
            return;
        }
        let full = self.full[t.rule].clone();
        let br = branches(&full);
        if let Some(l) = level {
            out.push(Ev::Level(l));
        }
        if t.growth {
            out.push(Ev::Growth(usize::MAX));
        } else {
            let mut i = 0;
            // The branches in order of their `[`: the next one to meet.
            let mut k = 0;
            while i < full.len() {
                if k < br.len() && br[k].0 == i {
                    let close = br[k].1;
                    match t.entries.get(k) {
                        Some(TermEntry::Failed) => {}
                        Some(TermEntry::Term(child)) => {
                            out.extend(full[i..close].iter().map(|&c| Ev::Component(c)));
                            // Terms nest no deeper than the braces and the
                            // growth that made them, both within the limit.
                            self.expand_term(child, level.map(|l| l + 1), out);
                            if let Some(l) = level {
                                out.push(Ev::Level(l));
                            }
                            out.push(Ev::Component(Comp::Close));
                        }
                        _ => out.extend(full[i..=close].iter().map(|&c| Ev::Component(c))),
                    }
                    i = close + 1;
                    k += 1;
                } else {
                    out.push(Ev::Component(full[i]));
                    i += 1;
                }
                if out.len() > MAX_EXPANSION {
                    let span = self.rules[t.rule].name_span.clone();
                    self.room(out.len(), 1, &span);
                    return;
                }
            }
        }
    }

    /// The seed's parts; `od` marks growth points.
    pub(super) fn seed(&mut self, s: &Str, od: bool, parts: &mut Vec<Part>) -> bool {
        let mut ok = true;
        let push = |parts: &mut Vec<Part>, c: Comp| match parts.last_mut() {
            Some(Part::Comps(v)) => v.push(c),
            _ => parts.push(Part::Comps(vec![c])),
        };
        for e in &s.elems {
            match e {
                Elem::Turn { left, .. } => {
                    push(parts, if *left { Comp::Plus } else { Comp::Minus })
                }
                Elem::Branch { body, span } => {
                    push(parts, Comp::Open);
                    ok &= self
                        .deeper(&opener(span), |c| Some(c.seed(body, od, parts)))
                        .unwrap_or(false);
                    push(parts, Comp::Close);
                }
                Elem::Resemble { .. } => {
                    let one = Str {
                        elems: vec![e.clone()],
                        span: s.span.clone(),
                    };
                    match self.expand(&one) {
                        Some(cs) => cs.into_iter().for_each(|c| push(parts, c)),
                        None => ok = false,
                    }
                }
                Elem::Name {
                    text,
                    span,
                    entries,
                } => {
                    ok &= self.each_piece(text, span, entries.as_ref(), |c, piece| match piece {
                        Piece::C(comp) => {
                            push(parts, comp);
                            true
                        }
                        Piece::Rule(r, rspan, ents) => match c.term(r, &rspan, ents, od) {
                            Some(t) => {
                                parts.push(Part::Term(t));
                                true
                            }
                            None => false,
                        },
                    });
                }
            }
        }
        ok
    }

    pub(super) fn seed_events(&mut self, parts: &[Part]) -> Vec<Ev> {
        let mut out = vec![Ev::Level(0)];
        for p in parts {
            match p {
                Part::Comps(cs) => out.extend(cs.iter().map(|&c| Ev::Component(c))),
                Part::Term(t) => {
                    self.expand_term(t, Some(1), &mut out);
                    out.push(Ev::Level(0));
                }
            }
            if self.too_large {
                break;
            }
        }
        out
    }
}
