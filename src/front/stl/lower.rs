//! Lowering an STL AST to the IR: the paper's Language Analyzer.
//!
//! * **Rules are macros.** A rule name in a string stands for the rule's
//!   body. Names written together are split into the longest declared rule
//!   names and the components F, L, R (`FR1` is `F R1`). A rule that uses
//!   itself through macros is an error (E0509) with the path.
//! * **`[I n X]`** is what `F` becomes after n parallel rewritings by
//!   `F -> X` (`[I 0 X]` is `F`). A rule whose whole body is `[I n X]` has
//!   the self-resemblance count n: as a macro it is that expansion; in an
//!   outline it grows X for at most n levels.
//! * **Branching terms** `R{e1, …, em}` extend R's top-level branches (of
//!   R's expansion as a macro). A rule name without braces in a seed or an
//!   entry is the term with no entries (`R1{R1, R2, R1}` = `R1{R1{}, R2{},
//!   R1{}}`); a rule without branches is written without braces.
//! * **Levels.** The seed's own stems are level 0; the stems of a term at
//!   level k are level k + 1, and its entries' terms level k + 2, …; a stem
//!   at level k has broadness `B − k·ΔB` and length `L − k·ΔL` (a tenth of
//!   the first value where that would not be positive: W0501). Inside a
//!   rule's body (a macro) there are no levels.
//! * **Outline Descriptions.** A file with a LAYOUT is an OD: in its seed, a
//!   rule name without braces whose rule has branches is a *growth point*
//!   ([`super::growth`]); everything written explicitly (components, terms
//!   with braces) is drawn as written and occupies space before growth
//!   starts. The grown tree replaces each growth point by explicit terms,
//!   so the lowered seed is a BED: written out with its layout
//!   (`translate --to stl`) it reads back to exactly the same stems, since
//!   it has no growth points left.

use super::ast::{Arg, ColourAst, Elem, Entries, Entry, File, Item, Num, ShapeAst, Str};
use super::growth::{self, branches, Comp, Grown, Point, UnitGeom};
use super::layout::{self, Outline};
use super::parser::RESERVED;
use crate::common::vocabulary::{self, TurtleSet};
use crate::diagnostics::{codes, nearest, Code, Diagnostic, Diagnostics};
use crate::front::depth::too_deep;
use crate::front::name_list;
use crate::front::names::LongestNames;
use crate::front::repeats::Repeats;
use crate::front::suggest::Suggester;
use crate::ir::{
    BranchEntry, BranchTerm, Growth, GrowthConstraint, Rgb, SeedItem, Shape, Span, SpanTable,
    Stems, Structure, StructureRule, StructureRuleId, SymbolId, System, TurtleOp, Word,
    MAX_NESTING,
};
use crate::number::readable;
use std::collections::HashMap;

pub const DEFAULT_ANGLE: f64 = 30.0;
pub const DEFAULT_LEVELS: u32 = 12;
pub const DEFAULT_BROADNESS: f64 = 1.0;
pub const DEFAULT_LENGTH: f64 = 10.0;
/// The most levels an outline grows (`LEVELS`): the one depth limit, since
/// each level of the grown tree is a term nested in the one before.
pub const MAX_LEVELS: u32 = MAX_NESTING as u32;
/// The most drawing components an expansion may have.
const MAX_EXPANSION: usize = Structure::MAX_EXPANSION;

pub use crate::ir::Lowered;

/// A branching term during lowering.
#[derive(Clone, Debug)]
struct Term {
    rule: usize,
    entries: Vec<TermEntry>,
    /// A growth point of an outline (a rule with branches written bare).
    growth: bool,
}

#[derive(Clone, Debug)]
enum TermEntry {
    Empty,
    Failed,
    Term(Term),
}

#[derive(Clone, Debug)]
enum Part {
    Comps(Vec<Comp>),
    Term(Term),
}

/// The expanded seed as the growth walk reads it.
type Ev = growth::SeedEvent;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum State {
    New,
    Busy,
    Done,
    Failed,
}

struct RuleSrc {
    name: String,
    name_span: Span,
    span: Span,
    body: Str,
}

struct Ctx<'a> {
    diags: &'a mut Diagnostics,
    rules: Vec<RuleSrc>,
    by_name: HashMap<String, usize>,
    max_name: usize,
    state: Vec<State>,
    full: Vec<Vec<Comp>>,
    unit: Vec<Vec<Comp>>,
    count: Vec<Option<u32>>,
    /// For `[I n Rk]`: k.
    unit_ref: Vec<Option<usize>>,
    stack: Vec<usize>,
    /// Set once an expansion went past [`MAX_EXPANSION`] (reported once).
    too_large: bool,
    /// How deep the expansion under way is: brackets, braces and rules
    /// used through rules, each a level of recursion here.
    level: usize,
    /// Set once the expansion went past [`MAX_NESTING`] (reported once).
    too_deep: bool,
    /// What the rule or seed being read reported: a mistake repeated
    /// through it is reported a few times, then counted.
    repeats: Repeats,
    /// What suggestions for unknown rule names may still cost.
    suggester: Suggester,
    /// The rule names, for splitting runs of them; made when the first
    /// run is split, after every rule is declared.
    name_index: Option<LongestNames>,
    /// The rule each counted rule an outline grew grows by.
    grown_units: HashMap<usize, usize>,
}

enum Piece {
    C(Comp),
    Rule(usize, Span),
}

/// A piece of an identifier run (`FR1`): a drawing component, a rule (by
/// its index in `by_name`), or neither.
enum RunPiece {
    Comp(Comp),
    Rule(usize),
    Unknown,
}

/// Splits identifier run `text` into the longest rule names of `by_name`
/// (`index` indexes them) and drawing components, each with its byte range
/// in `text`; an unknown piece (up to the next capital) ends it.
fn split_run(
    text: &str,
    by_name: &HashMap<String, usize>,
    index: &LongestNames,
) -> Vec<(RunPiece, std::ops::Range<usize>)> {
    let longest_at = index.longest_at(text);
    let mut out = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < text.len() {
        let n = longest_at[i];
        let longest = (n > 0)
            .then(|| by_name.get(&text[i..i + n]).map(|&r| (r, n)))
            .flatten();
        if let Some((r, n)) = longest {
            out.push((RunPiece::Rule(r), i..i + n));
            i += n;
            continue;
        }
        let next_digit = bytes
            .get(i + 1)
            .is_some_and(|b| b.is_ascii_digit() || *b == b'_');
        let comp = match bytes[i] {
            b'F' if !next_digit => Some(Comp::F),
            b'L' if !next_digit => Some(Comp::L),
            b'R' if !next_digit => Some(Comp::R),
            _ => None,
        };
        if let Some(c) = comp {
            out.push((RunPiece::Comp(c), i..i + 1));
            i += 1;
            continue;
        }
        let mut j = i + 1;
        while j < text.len() && !bytes[j].is_ascii_uppercase() {
            j += 1;
        }
        out.push((RunPiece::Unknown, i..j));
        break;
    }
    out
}

/// Where `file` uses its rules, by name and span, as lowering reads them:
/// the names in the rules' bodies and the seed, split from runs such as
/// `FR1` by the longest rule name, and the names of branching terms.
pub fn rule_uses(file: &File) -> Vec<(String, Span)> {
    type Uses = Vec<(String, Span)>;
    fn entries(es: &Entries, out: &mut Uses) {
        for e in &es.list {
            if let Entry::Term {
                name,
                name_span,
                entries: inner,
            } = e
            {
                out.push((name.clone(), name_span.clone()));
                inner.iter().for_each(|i| entries(i, out));
            }
        }
    }
    fn walk(s: &Str, split: &dyn Fn(&str, &Span, &mut Uses), out: &mut Uses) {
        for e in &s.elems {
            match e {
                Elem::Name {
                    text,
                    span,
                    entries: es,
                } => {
                    split(text, span, out);
                    es.iter().for_each(|es| entries(es, out));
                }
                Elem::Branch { body, .. } | Elem::Resemble { body, .. } => walk(body, split, out),
                Elem::Turn { .. } => {}
            }
        }
    }
    let mut by_name = HashMap::new();
    for item in &file.items {
        if let Item::Rule { name, .. } = item {
            if RESERVED.contains(&name.as_str()) || name == "DFS" {
                continue;
            }
            let next = by_name.len();
            by_name.entry(name.clone()).or_insert(next);
        }
    }
    let index = LongestNames::new(by_name.keys().map(String::as_str));
    let split = |text: &str, span: &Span, out: &mut Uses| {
        for (piece, at) in split_run(text, &by_name, &index) {
            if let RunPiece::Rule(_) = piece {
                out.push((
                    text[at.clone()].to_string(),
                    span.start + at.start..span.start + at.end,
                ));
            }
        }
    };
    let mut out = Vec::new();
    for item in &file.items {
        if let Item::Rule { body, .. } | Item::Seed { body, .. } = item {
            walk(body, &split, &mut out);
        }
    }
    out
}

impl Ctx<'_> {
    /// Splits an identifier run into components and rule names.
    fn split(&mut self, text: &str, span: &Span) -> Option<Vec<Piece>> {
        let index = self
            .name_index
            .get_or_insert_with(|| LongestNames::new(self.by_name.keys().map(String::as_str)));
        let mut out = Vec::new();
        for (piece, at) in split_run(text, &self.by_name, index) {
            match piece {
                RunPiece::Comp(c) => out.push(Piece::C(c)),
                RunPiece::Rule(r) => {
                    out.push(Piece::Rule(r, span.start + at.start..span.start + at.end))
                }
                RunPiece::Unknown => {
                    self.unknown_in_run(
                        &text[at.clone()],
                        span.start + at.start..span.start + at.end,
                    );
                    return None;
                }
            }
        }
        Some(out)
    }

    /// Reports `bad`, a piece of a run that is no rule and no component.
    fn unknown_in_run(&mut self, bad: &str, at: Span) {
        self.report(codes::STL_UNKNOWN_RULE, |c| {
                let otherwise = if c.rules.is_empty() {
                    format!(
                        "define it as a rule, e.g. `{bad} = [F][+F]`; drawing components are F, L, R, +, -"
                    )
                } else {
                    format!(
                        "the rules are {}; drawing components are F, L, R, +, -",
                        name_list(c.rules.iter().map(|r| r.name.as_str()), true)
                    )
                };
                let d = Diagnostic::at(
                    codes::STL_UNKNOWN_RULE,
                    at.clone(),
                    format!("unknown rule `{bad}`"),
                )
                .with_label("not a rule or a drawing component");
                c.did_you_mean(d, bad, otherwise)
            });
    }

    /// Reports what `build` makes, a diagnostic of `code` found in the
    /// rule or seed being read, unless that has reported enough of the
    /// code already ([`Repeats`]).
    fn report(&mut self, code: Code, build: impl FnOnce(&mut Self) -> Diagnostic) {
        if self.repeats.admit(self.diags, code) {
            let d = build(self);
            self.repeats.push(self.diags, d);
        }
    }

    /// `d` (an unknown rule `name`) with the nearest rule name as its fix,
    /// when one is near and the file's budget for suggestions allows, or
    /// `otherwise` as its help.
    fn did_you_mean(&mut self, d: Diagnostic, name: &str, otherwise: String) -> Diagnostic {
        if !self
            .suggester
            .afford(name.len(), self.rules.len(), self.max_name)
        {
            return d.with_help(otherwise);
        }
        let names: Vec<&str> = self.rules.iter().map(|r| r.name.as_str()).collect();
        did_you_mean(d, name, &names, otherwise)
    }

    fn room(&mut self, have: usize, add: usize, span: &Span) -> bool {
        if have.saturating_add(add) <= MAX_EXPANSION {
            return true;
        }
        if !self.too_large {
            self.too_large = true;
            self.diags.push(
                Diagnostic::at(
                    codes::TOO_MANY_SYMBOLS,
                    span.clone(),
                    format!("this expands to more than {MAX_EXPANSION} drawing components"),
                )
                .with_label("expands too far")
                .with_help("use fewer rewritings in `[I n X]` or fewer nested rules"),
            );
        }
        false
    }

    /// `f` one level deeper (a bracket, a brace, a rule used through
    /// another, written at `span`); past [`MAX_NESTING`] levels, `None`
    /// instead, reported once. This bounds the recursion of expanding
    /// nested rules, which the parser's limit on each string does not: a
    /// chain of rules each using the next nests as deep as it is long.
    fn deeper<T>(&mut self, span: &Span, f: impl FnOnce(&mut Self) -> Option<T>) -> Option<T> {
        if self.level >= MAX_NESTING {
            if !std::mem::replace(&mut self.too_deep, true) {
                self.diags.push(too_deep(
                    span.clone(),
                    "use fewer rules through rules here: write some of them out in place",
                ));
            }
            return None;
        }
        self.level += 1;
        let out = f(self);
        self.level -= 1;
        out
    }

    /// Resolves rule `r` (its expansion, unit and count); `None` if it has
    /// errors (already reported).
    fn resolve(&mut self, r: usize) -> Option<()> {
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
    fn count(&mut self, n: &Num) -> Option<u32> {
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
    fn expand(&mut self, s: &Str) -> Option<Vec<Comp>> {
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
                    let Some(pieces) = self.split(text, span) else {
                        ok = false;
                        continue;
                    };
                    let last = pieces.len().saturating_sub(1);
                    for (i, p) in pieces.into_iter().enumerate() {
                        match p {
                            Piece::C(c) => {
                                if i == last && entries.is_some() {
                                    self.no_branches_component(span, c);
                                    ok = false;
                                }
                                out.push(c);
                            }
                            Piece::Rule(r, rspan) => {
                                let ents = if i == last { entries.as_ref() } else { None };
                                if ents.is_none() {
                                    // A macro: the rule's expansion.
                                    if self.term(r, &rspan, None, false).is_none()
                                        || !self.room(out.len(), self.full[r].len(), &rspan)
                                    {
                                        ok = false;
                                        continue;
                                    }
                                    out.extend_from_slice(&self.full[r]);
                                    continue;
                                }
                                let Some(t) = self.term(r, &rspan, ents, false) else {
                                    ok = false;
                                    continue;
                                };
                                let mut evs = Vec::new();
                                self.expand_term(&t, None, &mut evs);
                                if !self.room(out.len(), evs.len(), &rspan) {
                                    ok = false;
                                    continue;
                                }
                                out.extend(evs.into_iter().filter_map(|e| match e {
                                    Ev::Component(c) => Some(c),
                                    _ => None,
                                }));
                            }
                        }
                    }
                }
            }
        }
        ok.then_some(out)
    }

    fn no_branches_component(&mut self, span: &Span, c: Comp) {
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

    /// A branching term for rule `r` written at `span` with `entries`.
    fn term(&mut self, r: usize, span: &Span, entries: Option<&Entries>, od: bool) -> Option<Term> {
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

    /// The rule called `name` (an entry names exactly one rule).
    fn rule_named(&mut self, name: &str, span: &Span) -> Option<usize> {
        if let Some(&r) = self.by_name.get(name) {
            return Some(r);
        }
        self.report(codes::STL_UNKNOWN_RULE, |c| {
            let otherwise = "an entry is a rule name, `~` (failed) or nothing".to_string();
            let d = Diagnostic::at(
                codes::STL_UNKNOWN_RULE,
                span.clone(),
                format!("unknown rule `{name}`"),
            )
            .with_label("no rule of this name");
            c.did_you_mean(d, name, otherwise)
        });
        None
    }

    /// Expands a term into events; `level` is the term's level (None in a
    /// macro: no level events).
    fn expand_term(&mut self, t: &Term, level: Option<u32>, out: &mut Vec<Ev>) {
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
    fn seed(&mut self, s: &Str, od: bool, parts: &mut Vec<Part>) -> bool {
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
                    let Some(pieces) = self.split(text, span) else {
                        ok = false;
                        continue;
                    };
                    let last = pieces.len().saturating_sub(1);
                    for (i, p) in pieces.into_iter().enumerate() {
                        match p {
                            Piece::C(c) => {
                                if i == last && entries.is_some() {
                                    self.no_branches_component(span, c);
                                    ok = false;
                                }
                                push(parts, c);
                            }
                            Piece::Rule(r, rspan) => {
                                let ents = if i == last { entries.as_ref() } else { None };
                                match self.term(r, &rspan, ents, od) {
                                    Some(t) => parts.push(Part::Term(t)),
                                    None => ok = false,
                                }
                            }
                        }
                    }
                }
            }
        }
        ok
    }

    fn seed_events(&mut self, parts: &[Part]) -> Vec<Ev> {
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

/// The opening `[` of a bracket written at `span`.
fn opener(span: &Span) -> Span {
    span.start..span.start + 1
}

fn nonneg(diags: &mut Diagnostics, n: &Num, what: &str) -> Option<f64> {
    if !n.value.is_finite() || n.value < 0.0 {
        diags.push(
            Diagnostic::at(
                codes::STL_NEGATIVE,
                n.span.clone(),
                format!("{what} cannot be negative"),
            )
            .with_label(format!("{} is less than zero", n.value))
            .with_help("write a number of zero or more"),
        );
        return None;
    }
    Some(n.value)
}

/// `d` (an unknown `name`) with the nearest of `candidates` as its fix, or
/// `otherwise` as its help when none is near.
fn did_you_mean(
    d: Diagnostic,
    name: &str,
    candidates: &[&str],
    otherwise: impl Into<String>,
) -> Diagnostic {
    match nearest(name, candidates).first() {
        Some(near) => d.suggesting(near),
        None => d.with_help(otherwise.into()),
    }
}

/// The layout shapes: a shape's name, matched without regard to case.
const SHAPE_KINDS: [&str; 4] = ["Rectangle", "RoundRect", "Ellipse", "Polygon"];

/// A layout shape. The colour and the kind are both checked (and both
/// reported) before the arguments.
fn shape(diags: &mut Diagnostics, s: &ShapeAst) -> Option<Shape> {
    let colour = shape_colour(diags, &s.colour);
    let kind = shape_kind(diags, s)?;
    let colour = colour?;
    if kind == "Polygon" {
        return polygon(diags, s, colour);
    }
    sized_shape(diags, s, kind, colour)
}

/// A shape's colour: a Delphi colour name or `$00BBGGRR`.
fn shape_colour(diags: &mut Diagnostics, colour: &ColourAst) -> Option<Rgb> {
    match colour {
        ColourAst::Name(n, span) => {
            let c = layout::named_colour(n);
            if c.is_none() {
                unknown_colour_name(diags, n, span);
            }
            c
        }
        ColourAst::Hex(h, span) => {
            let c = layout::hex_colour(h);
            if c.is_none() {
                diags.push(
                    Diagnostic::at(
                        codes::STL_UNKNOWN_COLOUR,
                        span.clone(),
                        format!("`{h}` is not a colour"),
                    )
                    .with_label("expected `$00BBGGRR`")
                    .with_help(
                        "write up to eight hex digits with a zero top byte: `$0000FF00` is green",
                    ),
                );
            }
            c
        }
    }
}

fn unknown_colour_name(diags: &mut Diagnostics, n: &str, span: &Span) {
    let names: Vec<&str> = crate::ir::colours::delphi()
        .iter()
        .map(|(n, _)| *n)
        .collect();
    let d = Diagnostic::at(
        codes::STL_UNKNOWN_COLOUR,
        span.clone(),
        format!("unknown colour `{n}`"),
    )
    .with_label("not a Delphi colour name");
    diags.push(did_you_mean(
        d,
        n,
        &names,
        "use a Delphi colour name (clGreen, clOlive, …; `graftal explain E0506` lists them) or `$00BBGGRR`",
    ));
}

/// The shape's kind, spelled as in [`SHAPE_KINDS`].
fn shape_kind(diags: &mut Diagnostics, s: &ShapeAst) -> Option<&'static str> {
    if let Some(kind) = SHAPE_KINDS.iter().find(|k| k.eq_ignore_ascii_case(&s.kind)) {
        return Some(kind);
    }
    let d = Diagnostic::at(
        codes::STL_UNKNOWN_SHAPE,
        s.kind_span.clone(),
        format!("unknown shape `{}`", s.kind),
    )
    .with_label("not a layout shape");
    diags.push(did_you_mean(
        d,
        &s.kind,
        &SHAPE_KINDS,
        "the shapes are Rectangle, RoundRect, Ellipse and Polygon",
    ));
    None
}

/// How to write the arguments of a shape of `kind`.
fn shape_args_help(kind: &str) -> String {
    match kind {
        "Rectangle" | "Ellipse" => format!("write `{kind} (x, y), width, height`"),
        "RoundRect" => "write `RoundRect (x, y), width, height, corner`".to_string(),
        _ => "write `Polygon (x1, y1), (x2, y2), (x3, y3), …`".to_string(),
    }
}

/// A polygon: three points or more.
fn polygon(diags: &mut Diagnostics, s: &ShapeAst, colour: Rgb) -> Option<Shape> {
    let mut points = Vec::new();
    for a in &s.args {
        match a {
            Arg::Point(x, y, _) => points.push((x.value, y.value)),
            Arg::Num(n) => {
                diags.push(
                    Diagnostic::at(
                        codes::STL_SHAPE_ARGS,
                        n.span.clone(),
                        "a polygon takes points, not numbers",
                    )
                    .with_label("expected a point `(x, y)`")
                    .with_help(shape_args_help("Polygon")),
                );
                return None;
            }
        }
    }
    if points.len() < 3 {
        diags.push(
            Diagnostic::at(
                codes::STL_FEW_POINTS,
                s.span.clone(),
                format!(
                    "a polygon needs at least three points, this one has {}",
                    points.len()
                ),
            )
            .with_label("too few points")
            .with_help("add points: `(clGreen) Polygon (0,0), (100,0), (50,100)`"),
        );
        return None;
    }
    Some(Shape::Polygon { colour, points })
}

/// A Rectangle, Ellipse or RoundRect: a starting point, then its sizes
/// (width and height, and a RoundRect's corner), none negative.
fn sized_shape(diags: &mut Diagnostics, s: &ShapeAst, kind: &str, colour: Rgb) -> Option<Shape> {
    let ((x, y), nums) = start_and_sizes(diags, s, kind)?;
    let want = if kind == "RoundRect" { 4 } else { 3 };
    if nums.len() + 1 != want {
        diags.push(
            Diagnostic::at(
                codes::STL_SHAPE_ARGS,
                s.span.clone(),
                format!("{kind} takes {want} arguments, {} given", nums.len() + 1),
            )
            .with_label("wrong number of arguments")
            .with_help(shape_args_help(kind)),
        );
        return None;
    }
    let mut sizes = Vec::new();
    for n in &nums {
        sizes.push(nonneg(diags, n, "a size")?);
    }
    Some(match kind {
        "Rectangle" => Shape::Rectangle {
            colour,
            x,
            y,
            w: sizes[0],
            h: sizes[1],
        },
        "Ellipse" => Shape::Ellipse {
            colour,
            x,
            y,
            w: sizes[0],
            h: sizes[1],
        },
        _ => Shape::RoundRect {
            colour,
            x,
            y,
            w: sizes[0],
            h: sizes[1],
            corner: sizes[2],
        },
    })
}

/// A sized shape's arguments: the starting point and the numbers after it.
fn start_and_sizes<'s>(
    diags: &mut Diagnostics,
    s: &'s ShapeAst,
    kind: &str,
) -> Option<((f64, f64), Vec<&'s Num>)> {
    let (start, nums) = match s.args.split_first() {
        Some((Arg::Point(x, y, _), rest)) => (Some((x.value, y.value)), rest),
        _ => (None, &s.args[..]),
    };
    let nums: Option<Vec<&Num>> = nums
        .iter()
        .map(|a| match a {
            Arg::Num(n) => Some(n),
            _ => None,
        })
        .collect();
    let (Some(start), Some(nums)) = (start, nums) else {
        diags.push(
            Diagnostic::at(
                codes::STL_SHAPE_ARGS,
                s.span.clone(),
                format!("wrong arguments for {kind}"),
            )
            .with_label("expected a starting point, then sizes")
            .with_help(shape_args_help(kind)),
        );
        return None;
    };
    Some((start, nums))
}

/// The settings a file gives.
struct Settings {
    angle: f64,
    levels: u32,
    depth_first: bool,
    b: (f64, f64),
    l: (f64, f64),
    b_span: Option<Span>,
    l_span: Option<Span>,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            angle: DEFAULT_ANGLE,
            levels: DEFAULT_LEVELS,
            depth_first: false,
            b: (DEFAULT_BROADNESS, 0.0),
            l: (DEFAULT_LENGTH, 0.0),
            b_span: None,
            l_span: None,
        }
    }
}

/// What a file's items say besides its rules (which go into [`Ctx`]), read
/// in file order.
#[derive(Default)]
struct Header<'f> {
    st: Settings,
    /// Where each setting and the seed was first given: each is given once.
    seen: HashMap<&'static str, Span>,
    seed: Option<&'f Str>,
    shapes: Vec<Shape>,
    /// The first LAYOUT: the file is an Outline Description.
    layout_span: Option<Span>,
    /// No item had an error that keeps the file from being drawn.
    ok: bool,
}

impl<'f> Header<'f> {
    /// Reads the items of `file`, declaring its rules in `ctx`.
    fn read(ctx: &mut Ctx<'_>, file: &'f File) -> Self {
        let mut hd = Header {
            ok: true,
            ..Header::default()
        };
        for item in &file.items {
            hd.ok &= hd.item(ctx, item);
        }
        hd
    }

    /// Reads one item; false if it has an error that keeps the file from
    /// being drawn.
    fn item(&mut self, ctx: &mut Ctx<'_>, item: &'f Item) -> bool {
        match item {
            Item::Angle { value, span } => {
                if !self.first_given(ctx.diags, "ANGLE", span) {
                    return true;
                }
                if !value.value.is_finite() {
                    return false;
                }
                self.st.angle = value.value;
                true
            }
            Item::Levels { value, span } => {
                if !self.first_given(ctx.diags, "LEVELS", span) {
                    return true;
                }
                let Some(levels) = levels(ctx.diags, value) else {
                    return false;
                };
                self.st.levels = levels;
                true
            }
            Item::Growth { depth_first, span } => {
                if self.first_given(ctx.diags, "GROWTH", span) {
                    self.st.depth_first = *depth_first;
                }
                true
            }
            Item::Param {
                param,
                value,
                decrement,
                span,
            } => self.param(ctx.diags, *param, value, decrement.as_ref(), span),
            Item::Rule {
                name,
                name_span,
                body,
                span,
            } => ctx.declare_rule(name, name_span, body, span),
            Item::Seed { body, span } => {
                if !self.first_given(ctx.diags, "SEED", span) {
                    return false;
                }
                self.seed = Some(body);
                true
            }
            Item::Layout { shapes, span } => {
                self.layout_span.get_or_insert(span.clone());
                let mut ok = true;
                for s in shapes {
                    match shape(ctx.diags, s) {
                        Some(sh) => self.shapes.push(sh),
                        None => ok = false,
                    }
                }
                ok
            }
        }
    }

    /// Whether `key` is given at `span` for the first time; a second one is
    /// reported.
    fn first_given(&mut self, diags: &mut Diagnostics, key: &'static str, span: &Span) -> bool {
        let Some(first) = self.seen.get(key) else {
            self.seen.insert(key, span.clone());
            return true;
        };
        diags.push(
            Diagnostic::at(
                codes::STL_DUPLICATE,
                span.clone(),
                format!("`{key}` given twice"),
            )
            .with_label("given again here")
            .with_secondary(first.clone(), "first given here")
            .with_help("keep one of them"),
        );
        false
    }

    /// `B = value (decrement)` or `L = value (decrement)`.
    fn param(
        &mut self,
        diags: &mut Diagnostics,
        param: char,
        value: &Num,
        decrement: Option<&Num>,
        span: &Span,
    ) -> bool {
        let key = if param == 'B' { "B" } else { "L" };
        if !self.first_given(diags, key, span) {
            return true;
        }
        let what = if param == 'B' {
            "the broadness B"
        } else {
            "the length L"
        };
        let v = nonneg(diags, value, what);
        let d = match decrement {
            Some(d) => nonneg(diags, d, "a decrement per level"),
            None => Some(0.0),
        };
        if param == 'L' && v == Some(0.0) {
            diags.push(
                Diagnostic::at(
                    codes::STL_NEGATIVE,
                    value.span.clone(),
                    "the length L must be more than zero",
                )
                .with_label("stems of length 0 draw nothing")
                .with_help("write e.g. `L = 40 (4)`"),
            );
            return false;
        }
        let (Some(v), Some(d)) = (v, d) else {
            return false;
        };
        // The clamping warning points at the decrement, or at the whole
        // parameter when it has none.
        let dspan = decrement.map_or(span.clone(), |d| d.span.clone());
        if param == 'B' {
            self.st.b = (v, d);
            self.st.b_span = Some(dspan);
        } else {
            self.st.l = (v, d);
            self.st.l_span = Some(dspan);
        }
        true
    }
}

/// The value of `LEVELS`: a whole number up to [`MAX_LEVELS`].
fn levels(diags: &mut Diagnostics, value: &Num) -> Option<u32> {
    let v = value.value;
    if v < 0.0 || v.fract() != 0.0 || !v.is_finite() {
        diags.push(
            Diagnostic::at(
                codes::STL_NEGATIVE,
                value.span.clone(),
                format!("LEVELS must be a whole number of 0 or more, not {v}"),
            )
            .with_label("not a count")
            .with_help("write e.g. `LEVELS 12`"),
        );
        return None;
    }
    if v > MAX_LEVELS as f64 {
        diags.push(
            Diagnostic::at(
                codes::STL_TOO_DEEP,
                value.span.clone(),
                format!("LEVELS {v} is more than the {MAX_LEVELS} graftal grows"),
            )
            .with_label("too many levels")
            .with_help(format!("use at most `LEVELS {MAX_LEVELS}`")),
        );
        return None;
    }
    Some(v as u32)
}

impl<'a> Ctx<'a> {
    fn new(diags: &'a mut Diagnostics) -> Self {
        Ctx {
            diags,
            rules: Vec::new(),
            by_name: HashMap::new(),
            max_name: 0,
            state: Vec::new(),
            full: Vec::new(),
            unit: Vec::new(),
            count: Vec::new(),
            unit_ref: Vec::new(),
            stack: Vec::new(),
            too_large: false,
            level: 0,
            too_deep: false,
            repeats: Repeats::default(),
            suggester: Suggester::default(),
            name_index: None,
            grown_units: HashMap::new(),
        }
    }
}

impl Ctx<'_> {
    /// Declares a rule (resolved later, once all rules are known); false if
    /// its name is reserved or taken.
    fn declare_rule(&mut self, name: &str, name_span: &Span, body: &Str, span: &Span) -> bool {
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
    fn resolve_rules(&mut self) -> bool {
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

    /// The rules in the IR: each one's expansion and count.
    fn ir_rules(&self, comp_ids: &ComponentIds) -> Vec<StructureRule> {
        self.rules
            .iter()
            .enumerate()
            .map(|(r, src)| StructureRule {
                name: src.name.clone(),
                body: ir_word(&self.full[r], comp_ids),
                resemblance: self.count[r],
                unit: (self.grown_units.get(&r)).map(|&u| StructureRuleId(u as u32)),
            })
            .collect()
    }
}

/// Lowers a parsed STL file.
pub fn lower(file: &File, src_len: usize, diags: &mut Diagnostics) -> Lowered {
    let mut ctx = Ctx::new(diags);
    let hd = Header::read(&mut ctx, file);
    let resolved = ctx.resolve_rules();
    let mut ok = hd.ok && resolved;
    let mut parts = Vec::new();
    match hd.seed {
        Some(body) => {
            ctx.repeats.begin_item();
            ok &= ctx.seed(body, hd.layout_span.is_some(), &mut parts);
            ctx.repeats.end_item(ctx.diags, "in the seed");
        }
        None => {
            ctx.diags.push(
                Diagnostic::at(codes::STL_MISSING_SEED, src_len..src_len, "missing SEED")
                    .with_label("the file ends without a seed")
                    .with_help("add the seed to draw: `SEED`, e.g. `F R1`, then `ENDSEED`"),
            );
            ok = false;
        }
    }
    let st = &hd.st;
    let mut system = System::new();
    system.settings.delta = st.angle.to_radians();
    system.settings.step = st.l.0;
    system.settings.width = st.b.0.min(Structure::MAX_DRAWN_WIDTH);
    let mut structure = new_structure(st, hd.shapes.clone());
    let comp_ids = intern_components(&mut system);
    // Nothing is grown or expanded in a file with errors (a parse error
    // may have dropped part of the seed or the layout).
    if !ok || ctx.too_large || ctx.diags.has_errors() {
        return finish(system, structure);
    }

    // Growth (an outline) or the seed as written (a BED).
    let max_level = st.levels.saturating_add(2).max(64);
    let (bw, _) = Structure::per_level(st.b.0, st.b.1, max_level);
    let (lw, _) = Structure::per_level(st.l.0, st.l.1, max_level);
    if let Some(layout_span) = &hd.layout_span {
        // The seed as planted, before growth replaces its growth points.
        structure.planted = parts.iter().map(|p| ir_seed_item(p, &comp_ids)).collect();
        if !grow_outline(&mut ctx, &mut parts, st, &hd.shapes, &bw, &lw) {
            no_growth(ctx.diags, layout_span);
        }
    }
    let events = ctx.seed_events(&parts);
    if ctx.too_large {
        return finish(system, structure);
    }
    let (word, max_seen) = level_word(&mut system, &events, &comp_ids, st, &bw, &lw);
    warn_clamped(ctx.diags, st, max_seen);
    structure.rules = ctx.ir_rules(&comp_ids);
    structure.seed = parts.iter().map(|p| ir_seed_item(p, &comp_ids)).collect();
    system.axiom = Word::from(word);
    finish(system, structure)
}

/// The structure before the rules and the seed go in.
fn new_structure(st: &Settings, layout: Vec<Shape>) -> Structure {
    Structure {
        rules: Vec::new(),
        seed: Vec::new(),
        planted: Vec::new(),
        constraint: GrowthConstraint {
            outline: layout,
            strategy: if st.depth_first {
                Growth::DepthFirst
            } else {
                Growth::BreadthFirst
            },
            levels: st.levels,
        },
        stems: Stems {
            broadness: st.b,
            length: st.l,
        },
    }
}

/// The lowered system with its structure (an STL file has no span table).
fn finish(mut system: System, structure: Structure) -> Lowered {
    system.structure = Some(structure);
    Lowered {
        system,
        spans: SpanTable::default(),
    }
}

fn no_growth(diags: &mut Diagnostics, layout_span: &Span) {
    diags.push(
        Diagnostic::at(
            codes::STL_NO_GROWTH,
            layout_span.clone(),
            "this layout has nothing to grow",
        )
        .with_label("an Outline Description grows the seed's rules")
        .with_help("name a rule with branches in the seed, without `{…}`, e.g. `F R1`"),
    );
}

/// The word of the expanded seed, with a silent stem-level marker wherever
/// the level changes; and the deepest level marked.
fn level_word(
    system: &mut System,
    events: &[Ev],
    comp_ids: &ComponentIds,
    st: &Settings,
    bw: &[f64],
    lw: &[f64],
) -> (Vec<SymbolId>, u32) {
    let mut word = Vec::with_capacity(events.len());
    let mut max_seen = 0u32;
    let mut markers: HashMap<u32, SymbolId> = HashMap::new();
    let mut last_level = None;
    for e in events {
        match *e {
            Ev::Component(c) => word.push(comp_ids[c as usize]),
            Ev::Level(k) if last_level != Some(k) => {
                last_level = Some(k);
                max_seen = max_seen.max(k);
                let id = *markers
                    .entry(k)
                    .or_insert_with(|| level_marker(system, st, bw, lw, k));
                // A marker right before another marker is dead: replace it.
                if let Some(&prev) = word.last() {
                    if markers.values().any(|&m| m == prev) {
                        word.pop();
                    }
                }
                word.push(id);
            }
            Ev::Level(_) | Ev::Growth(_) => {}
        }
    }
    (word, max_seen)
}

/// A new silent symbol that sets the stem of level `k`.
fn level_marker(system: &mut System, st: &Settings, bw: &[f64], lw: &[f64], k: u32) -> SymbolId {
    let id = system.intern_silent(&format!("stl-level-{k}"));
    system.set_interpretation(
        id,
        TurtleOp::Stem {
            width: at_level(bw, st.b, k).min(Structure::MAX_DRAWN_WIDTH),
            length: at_level(lw, st.l, k),
        },
    );
    id
}

/// The value at level `k` of a table of `Structure::per_level(base, dec, …)`, computed
/// when `k` is past its end.
fn at_level(table: &[f64], (base, dec): (f64, f64), k: u32) -> f64 {
    let kk = k as usize;
    table
        .get(kk)
        .copied()
        .unwrap_or_else(|| Structure::per_level(base, dec, k).0[kk])
}

/// Warns where a decrement makes B or L non-positive. Only levels with
/// stems count: `max_seen` is the deepest.
fn warn_clamped(diags: &mut Diagnostics, st: &Settings, max_seen: u32) {
    for (which, (base, dec), span) in [
        ("B", st.b, st.b_span.clone()),
        ("L", st.l, st.l_span.clone()),
    ] {
        let (_, first) = Structure::per_level(base, dec, max_seen);
        if let (Some(k), Some(span)) = (first, span) {
            let what = if which == "B" { "broadness" } else { "length" };
            diags.push(
                Diagnostic::at(
                    codes::STL_CLAMPED,
                    span,
                    format!(
                        "the stem {what} {which} reaches {} at level {k}; clamped to {}",
                        readable(base - dec * k as f64),
                        readable(base * 0.1)
                    ),
                )
                .with_label(format!("this decrement makes {which} non-positive"))
                .with_note(format!("the tree has {max_seen} levels"))
                .with_help(format!(
                    "use a smaller decrement, e.g. `({})`",
                    fmt_num(base / (max_seen as f64 + 1.0))
                )),
            );
        }
    }
}

/// Components as a word of the IR.
fn ir_word(cs: &[Comp], comp_ids: &ComponentIds) -> Word {
    Word::from(cs.iter().map(|&c| comp_ids[c as usize]).collect::<Vec<_>>())
}

fn ir_seed_item(p: &Part, comp_ids: &ComponentIds) -> SeedItem {
    match p {
        Part::Comps(cs) => SeedItem::Word(ir_word(cs, comp_ids)),
        Part::Term(t) => SeedItem::Term(ir_term(t)),
    }
}

fn fmt_num(x: f64) -> String {
    let s = format!("{x:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn ir_term(t: &Term) -> BranchTerm {
    BranchTerm {
        rule: StructureRuleId(t.rule as u32),
        entries: t
            .entries
            .iter()
            .map(|e| match e {
                TermEntry::Empty => BranchEntry::Empty,
                TermEntry::Failed => BranchEntry::Failed,
                TermEntry::Term(c) => BranchEntry::Term(ir_term(c)),
            })
            .collect(),
        grows: t.growth,
    }
}

/// The drawing components as symbols, indexed by `Comp as usize`.
type ComponentIds = [SymbolId; 7];

/// Interns the drawing components with their turtle meaning.
fn intern_components(sys: &mut System) -> ComponentIds {
    let mut ids = [crate::ir::SymbolId::OPEN; 7];
    for (c, name) in [
        (Comp::F, "F"),
        (Comp::L, "L"),
        (Comp::R, "R"),
        (Comp::Plus, "+"),
        (Comp::Minus, "-"),
    ] {
        let Some(op) = vocabulary::op(TurtleSet::Stl, name) else {
            continue;
        };
        let id = sys.intern(name);
        sys.set_interpretation(id, op);
        ids[c as usize] = id;
    }
    ids[Comp::Open as usize] = crate::ir::SymbolId::OPEN;
    ids[Comp::Close as usize] = crate::ir::SymbolId::CLOSE;
    ids
}

/// Grows the outline: replaces each growth point of `parts` by the grown
/// terms (adding a rule `NAME_unit` for each counted rule `[I n string]`
/// grown). Returns whether there was any growth point.
fn grow_outline(
    ctx: &mut Ctx<'_>,
    parts: &mut [Part],
    st: &Settings,
    shapes: &[Shape],
    bw: &[f64],
    lw: &[f64],
) -> bool {
    let events = ctx.seed_events(parts);
    let mut growth_points: Vec<(usize, usize)> = Vec::new();
    collect_growth(parts, &mut growth_points);
    if growth_points.is_empty() {
        return false;
    }
    let growth_terms: Vec<usize> = growth_points.iter().map(|&(r, _)| r).collect();
    let unit_of = ctx.unit_rules(&growth_terms);
    // Each growth point grows its unit rule for as many levels as its
    // rule's count allows, or LEVELS; and no deeper than the depth limit,
    // counted from the seed (each level is a term nested in the one
    // before, and the code that reads terms recurses).
    let growing: Vec<(usize, u32)> = growth_points
        .iter()
        .map(|&(r, depth)| {
            let room = (MAX_NESTING + 1).saturating_sub(depth) as u32;
            let levels = ctx.count[r].unwrap_or(st.levels).min(room);
            (unit_of[r].unwrap_or(r), levels)
        })
        .collect();
    let defaults = (st.l.0, st.b.0);
    let (stems, points) =
        growth::walk_seed(&events, &growing, st.angle.to_radians(), defaults, bw, lw);
    let delta = st.angle.to_radians();
    let units: Vec<UnitGeom> = ctx.full.iter().map(|c| UnitGeom::new(c, delta)).collect();
    let params = growth::Params {
        delta,
        depth_first: st.depth_first,
        broadness: bw.to_vec(),
        length: lw.to_vec(),
        max_stems: growth::MAX_STEMS,
    };
    let outline = Outline::new(shapes);
    let bounds = layout::bounds(shapes).unwrap_or([0.0, 0.0, 1.0, 1.0]);
    // Growth points with no budget (`[I 0 X]`) grow nothing.
    let out = growth::grow(&units, &outline, bounds, &params, &stems, &points);
    if out.truncated {
        ctx.diags.push(
            Diagnostic::global(
                codes::STL_TOO_DEEP,
                format!("growth stopped at {} stems", growth::MAX_STEMS),
            )
            .with_help("use fewer LEVELS, a larger broadness B or a smaller layout"),
        );
    }
    // Replace the growth points by the grown terms.
    let mut next = 0;
    fill_growth(parts, &out.nodes, &points, &mut next);
    true
}

impl Ctx<'_> {
    /// The unit rule each rule of `growth_terms` grows by: the rule itself,
    /// the rule named in `[I n Rk]`, or a new rule holding the string of
    /// `[I n string]`. Indexed by rule.
    fn unit_rules(&mut self, growth_terms: &[usize]) -> Vec<Option<usize>> {
        let mut unit_of: Vec<Option<usize>> = vec![None; self.rules.len()];
        for &r in growth_terms {
            if unit_of[r].is_some() {
                continue;
            }
            let unit = match (self.count[r], self.unit_ref[r]) {
                (None, _) => r,
                (Some(_), Some(k)) => k,
                (Some(_), None) => self.add_unit_rule(r),
            };
            if self.count[r].is_some() {
                self.grown_units.insert(r, unit);
            }
            unit_of[r] = Some(unit);
        }
        unit_of
    }

    /// Adds the rule `NAME_unit` holding the string of rule `r`'s
    /// `[I n string]`, a rule of its own so the grown terms can name it.
    fn add_unit_rule(&mut self, r: usize) -> usize {
        let mut name = format!("{}_unit", self.rules[r].name);
        while self.by_name.contains_key(&name) {
            name.push('_');
        }
        let unit = self.unit[r].clone();
        let id = self.rules.len();
        self.rules.push(RuleSrc {
            name: name.clone(),
            name_span: self.rules[r].name_span.clone(),
            span: self.rules[r].span.clone(),
            body: Str::default(),
        });
        self.by_name.insert(name, id);
        self.state.push(State::Done);
        self.full.push(unit.clone());
        self.unit.push(unit);
        self.count.push(None);
        self.unit_ref.push(None);
        id
    }
}

/// The growth points of `parts`, in order: each one's rule and how deep
/// its term is (1 for a term of the seed).
fn collect_growth(parts: &[Part], out: &mut Vec<(usize, usize)>) {
    fn term(t: &Term, depth: usize, out: &mut Vec<(usize, usize)>) {
        if t.growth {
            out.push((t.rule, depth));
        }
        for e in &t.entries {
            if let TermEntry::Term(c) = e {
                term(c, depth + 1, out);
            }
        }
    }
    for p in parts {
        if let Part::Term(t) = p {
            term(t, 1, out);
        }
    }
}

fn fill_growth(parts: &mut [Part], nodes: &[growth::Node], points: &[Point], next: &mut usize) {
    fn node_term(nodes: &[growth::Node], i: usize) -> Term {
        Term {
            rule: nodes[i].rule,
            entries: nodes[i]
                .entries
                .iter()
                .map(|e| match *e {
                    Grown::Empty => TermEntry::Empty,
                    Grown::Failed => TermEntry::Failed,
                    Grown::Node(c) => TermEntry::Term(node_term(nodes, c)),
                })
                .collect(),
            growth: false,
        }
    }
    fn term(t: &mut Term, nodes: &[growth::Node], points: &[Point], next: &mut usize) {
        if t.growth {
            if *next < points.len() {
                *t = node_term(nodes, *next);
            }
            *next += 1;
            return;
        }
        for e in &mut t.entries {
            if let TermEntry::Term(c) = e {
                term(c, nodes, points, next);
            }
        }
    }
    for p in parts {
        if let Part::Term(t) = p {
            term(t, nodes, points, next);
        }
    }
}
