//! Translation: a system in the IR written out in a notation, exactly
//! where the target can express it and honestly where not.
//!
//! `graftal translate FILE --to pfg|linf|stl|gft` is source -> IR -> emitter.
//! One emitter per target notation, each listed in [`BACKS`]:
//!
//! * [`pfg`] writes the 1988 format of the Appendix A listing;
//! * [`linf`] writes LinF blocks in the paper's order;
//! * [`stl`] writes STL: a Branch-Expansion Description for an STL source,
//!   and, for a pfg or LinF source, rules whose expansion is the derived
//!   word (one macro per symbol and step, `[I n X]` where that is exact);
//! * [`gft`] writes graftal's own notation: every field of the IR, never
//!   refused ([`Back::write_everything`]).
//!
//! An STL source is first turned into a bracketed production system by
//! [`from_stl`]: each branching term becomes a symbol whose production is
//! its rule's body with the term's entries at the branch ends, and stem
//! levels become length factors. The pfg and LinF emitters then write that
//! system like any other.
//!
//! The pfg, LinF and STL emitters walk a system alike ([`walk`]): the symbols that
//! occur and what each does to the turtle, the turns as repeated turn
//! symbols, words written symbol by symbol, and what a target drops
//! reported in the same words; a target that rewrites one symbol by one
//! rule takes the system's [`Rules`].
//!
//! Each of them reports what its target cannot express as a [`Problem`]:
//! the kind of construct (each kind has an error code `E06xx` and, for
//! `--lossy`, a warning code `W06xx`), the source span, what the construct
//! is and what `--lossy` does with it. Without `--lossy` any problem means
//! nothing is written; with it, each problem is one warning. A translation
//! without problems is exact: the translated file, evaluated with the same
//! steps and seed, draws the same segments (tests/it/translate.rs checks this
//! over the standard library and over random systems).
//!
//! Everything the emitters decide is also recorded as a [`Mapped`] entry
//! (construct, source span, status, what it became), which `translate
//! --format json` prints.

pub mod from_stl;
pub mod gft;
pub mod linf;
pub mod pfg;
pub mod stl;
pub mod walk;

use crate::diagnostics::codes::{self, Code};
use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::ir::{Angle, Axis, Production, Span, SpanTable, SymbolId, System, TurtleOp};
use serde::Serialize;
use std::collections::{HashMap, HashSet};

/// Every notation graftal writes.
pub static BACKS: &[&dyn Back] = &[&pfg::Pfg, &linf::Linf, &stl::Stl, &gft::Gft];

/// A notation graftal writes.
pub trait Back: Sync {
    /// The name as the command line spells it (`pfg`, `linf`, `stl`, `gft`).
    fn name(&self) -> &'static str;
    /// The extension of its files, without the dot.
    fn extension(&self) -> &'static str;
    /// Writes the system's productions, reporting to `e` what cannot be
    /// said exactly.
    fn write(&self, e: &mut Emitter<'_>) -> String;
    /// Writes a system with a growth structure (named rules and branching
    /// terms) as that structure, when the notation has one; `None` makes
    /// the structure productions first.
    fn write_structure(&self, _sys: &System) -> Option<String> {
        None
    }
    /// How many branching terms a structure may have before its
    /// productions are spelled out without a symbol per term (pfg's
    /// alphabet is about 80 characters).
    fn term_symbols(&self) -> Option<usize> {
        None
    }
    /// The whole system, every field of it, when the notation can say
    /// everything the IR holds (`.gft`); `steps` replaces the system's
    /// derivation length. `None`: the notation goes through [`translate`]'s
    /// checks and [`Back::write`].
    fn write_everything(&self, _sys: &System, _steps: Option<u64>) -> Option<String> {
        None
    }
}

impl std::fmt::Debug for dyn Back {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The emitter registered as `name`.
pub fn by_name(name: &str) -> Option<&'static dyn Back> {
    BACKS.iter().copied().find(|b| b.name() == name)
}

/// What an emitter knows of the source besides the system: its
/// notation's name, its comments, and the angle increment it states.
#[derive(Clone, Debug, Default)]
pub struct Origin {
    /// The source notation as people write its name (`LinF`).
    pub title: &'static str,
    /// (span, text) of each comment that can be carried over.
    pub comments: Vec<(Span, String)>,
    /// The turn divided into whole increments as the source states it,
    /// kept by a translation when it fits.
    pub angle_divisions: Option<u64>,
}

/// What to translate to.
#[derive(Clone, Debug)]
pub struct Request {
    pub target: &'static dyn Back,
    /// Approximate what the target cannot express, with a warning each.
    pub lossy: bool,
    /// Steps (the file's derivation length when `None`): written as the
    /// target's derivation length, or baked into STL rules.
    pub steps: Option<u64>,
}

/// How a construct was carried over.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Written so that it means exactly the same.
    Exact,
    /// Changed (`--lossy`): see the note.
    Approximated,
    /// The target cannot express it and `--lossy` was not given.
    Impossible,
}

/// One construct of the source and what it became.
#[derive(Clone, Debug, Serialize)]
pub struct Mapped {
    /// What the construct is, e.g. "production `F --> F+F`".
    pub construct: String,
    /// Where it is in the source (byte range), when known.
    pub span: Option<Span>,
    pub status: Status,
    /// What it became in the target's text (empty when dropped).
    pub target: String,
    pub note: Option<String>,
}

/// The kinds of construct a target may be unable to express.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    Context,
    Stochastic,
    Guard,
    Interval,
    ThreeD,
    Angle,
    Length,
    Attribute,
    Swap,
    Layout,
    Rule,
    Move,
    TooLarge,
    /// Nesting the target's readers refuse (past [`crate::ir::MAX_NESTING`]).
    TooDeep,
}

impl Kind {
    /// The error code, and the warning code used under `--lossy` (none
    /// when the construct cannot be approximated at all).
    pub fn codes(self) -> (Code, Option<Code>) {
        use codes::*;
        match self {
            Kind::Context => (TR_CONTEXT, Some(TR_CONTEXT_APPROX)),
            Kind::Stochastic => (TR_STOCHASTIC, Some(TR_STOCHASTIC_APPROX)),
            Kind::Guard => (TR_GUARD, Some(TR_GUARD_APPROX)),
            Kind::Interval => (TR_INTERVAL, Some(TR_INTERVAL_APPROX)),
            Kind::ThreeD => (TR_3D, Some(TR_3D_APPROX)),
            Kind::Angle => (TR_ANGLE, Some(TR_ANGLE_APPROX)),
            Kind::Length => (TR_LENGTH, Some(TR_LENGTH_APPROX)),
            Kind::Attribute => (TR_ATTRIBUTE, Some(TR_ATTRIBUTE_APPROX)),
            Kind::Swap => (TR_SWAP, Some(TR_SWAP_APPROX)),
            Kind::Layout => (TR_LAYOUT, Some(TR_LAYOUT_APPROX)),
            Kind::Rule => (TR_RULE, Some(TR_RULE_APPROX)),
            Kind::Move => (TR_MOVE, Some(TR_MOVE_APPROX)),
            Kind::TooLarge => (TR_TOO_LARGE, None),
            Kind::TooDeep => (NESTED_TOO_DEEPLY, None),
        }
    }
}

/// Something the target cannot express.
#[derive(Clone, Debug)]
pub struct Problem {
    pub kind: Kind,
    pub span: Option<Span>,
    /// The construct, e.g. "the context of `a < b --> c`".
    pub what: String,
    /// What `--lossy` does with it.
    pub change: String,
}

/// The result of a translation.
#[derive(Clone, Debug)]
pub struct Translation {
    /// The translated file; `None` when the target cannot express the
    /// source and `--lossy` was not given.
    pub text: Option<String>,
    pub mapping: Vec<Mapped>,
    /// Source symbol name -> how the target writes it, where they differ.
    pub names: Vec<(String, String)>,
    /// One error per problem (or one warning under `--lossy`).
    pub diagnostics: Diagnostics,
}

impl Translation {
    /// Whether the translation is written and means exactly the source.
    pub fn is_exact(&self) -> bool {
        self.text.is_some() && self.diagnostics.is_empty()
    }
}

/// What the emitters share: the source, the problems found, the mapping.
pub struct Emitter<'a> {
    pub sys: &'a System,
    pub spans: &'a SpanTable,
    /// The source text (for comments) and what is known of its notation.
    pub source: &'a str,
    pub origin: &'a Origin,
    pub lossy: bool,
    pub steps: u64,
    problems: Vec<Problem>,
    seen: HashSet<(Kind, String)>,
    pub mapping: Vec<Mapped>,
    pub names: Vec<(String, String)>,
    /// How the source writes what a symbol made for the translation
    /// stands for (an STL length factor: the `L = …` line), so that
    /// messages about it speak the source's syntax.
    pub written: HashMap<SymbolId, String>,
}

impl<'a> Emitter<'a> {
    pub fn new(
        sys: &'a System,
        spans: &'a SpanTable,
        source: &'a str,
        origin: &'a Origin,
        req: &Request,
    ) -> Self {
        Emitter {
            sys,
            spans,
            source,
            origin,
            lossy: req.lossy,
            steps: req.steps.or(sys.settings.steps).unwrap_or(0),
            problems: Vec::new(),
            seen: HashSet::new(),
            mapping: Vec::new(),
            names: Vec::new(),
            written: HashMap::new(),
        }
    }

    /// Reports a construct the target cannot express (once per kind and
    /// description).
    pub fn problem(
        &mut self,
        kind: Kind,
        span: Option<Span>,
        what: impl Into<String>,
        change: impl Into<String>,
    ) {
        let what = what.into();
        if !self.seen.insert((kind, what.clone())) {
            return;
        }
        let change = change.into();
        let lossy = self.lossy && kind.codes().1.is_some();
        self.mapping.push(Mapped {
            construct: what.clone(),
            span: span.clone(),
            status: if lossy {
                Status::Approximated
            } else {
                Status::Impossible
            },
            target: String::new(),
            note: Some(change.clone()),
        });
        self.problems.push(Problem {
            kind,
            span,
            what,
            change,
        });
    }

    /// Records a construct carried over exactly.
    pub fn exact(&mut self, construct: impl Into<String>, span: Option<Span>, target: &str) {
        self.mapping.push(Mapped {
            construct: construct.into(),
            span,
            status: Status::Exact,
            target: target.to_string(),
            note: None,
        });
    }

    /// Records production `i` carried over exactly as `target`.
    pub fn exact_production(&mut self, i: usize, target: &str) {
        let text = self.production_text(i);
        self.exact(
            format!("production `{text}`"),
            self.production_span(i),
            target,
        );
    }

    /// Records the axiom carried over exactly as `target`.
    pub fn exact_axiom(&mut self, target: &str) {
        self.exact("the axiom", self.spans.axiom.first().cloned(), target);
    }

    /// The comment attached to the item at `span` (see [`attached`]).
    pub fn attached_to(&self, span: Option<&Span>) -> Option<Attached> {
        span.and_then(|s| attached(&self.origin.comments, self.source, s))
    }

    /// Where symbol `id` is first written in the source.
    pub fn symbol_span(&self, id: SymbolId) -> Option<Span> {
        self.spans.symbols.get(&id).cloned()
    }

    /// The source span of production `i`.
    pub fn production_span(&self, i: usize) -> Option<Span> {
        self.spans.productions.get(i).cloned()
    }

    /// Production `i` as the source would write it, for messages.
    pub fn production_text(&self, i: usize) -> String {
        if let Some(s) = self.production_span(i) {
            if let Some(t) = self.source.get(s) {
                let t = t.split_whitespace().collect::<Vec<_>>().join(" ");
                if !t.is_empty() {
                    return t;
                }
            }
        }
        let p = &self.sys.productions[i];
        let name = |w: &[SymbolId]| -> String {
            w.iter()
                .map(|&s| self.sys.symbols.name(s))
                .collect::<Vec<_>>()
                .join(" ")
        };
        let succ = p
            .alternatives
            .first()
            .map(|a| name(&a.successor.0))
            .unwrap_or_default();
        format!("{} -> {}", name(&p.predecessor), succ)
    }

    /// The symbol's name as the source writes it.
    pub fn name(&self, id: SymbolId) -> &str {
        self.sys.symbols.name(id)
    }

    /// Records that the source's `from` is written `to`.
    pub fn rename(&mut self, from: &str, to: &str) {
        if from != to && !from.is_empty() {
            self.names.push((from.to_string(), to.to_string()));
        }
    }

    /// Turns the problems into diagnostics and decides whether the text is
    /// written.
    pub fn finish(self, text: String) -> Translation {
        let mut diags = Diagnostics::default();
        let mut blocked = false;
        for p in &self.problems {
            let (error, warning) = p.kind.codes();
            let d = match (self.lossy, warning) {
                (true, Some(w)) => {
                    let d = match &p.span {
                        Some(s) => {
                            Diagnostic::at(w, s.clone(), format!("{}: {}", p.what, p.change))
                        }
                        None => Diagnostic::global(w, format!("{}: {}", p.what, p.change)),
                    };
                    d.with_label("approximated")
                }
                _ => {
                    blocked = true;
                    let d = match &p.span {
                        Some(s) => Diagnostic::at(error, s.clone(), p.what.clone()),
                        None => Diagnostic::global(error, p.what.clone()),
                    };
                    let d = d.with_label("the target cannot express this");
                    if warning.is_some() {
                        d.with_help(format!("with `--lossy`: {}", p.change))
                    } else {
                        d.with_help(p.change.clone())
                    }
                }
            };
            diags.push(d);
        }
        diags.sort();
        Translation {
            text: if blocked { None } else { Some(text) },
            mapping: self.mapping,
            names: self.names,
            diagnostics: diags,
        }
    }
}

/// Translates `sys` (read from `source`, with `spans`) to `req.target`.
pub fn translate(
    sys: &System,
    spans: &SpanTable,
    source: &str,
    origin: &Origin,
    req: &Request,
) -> Translation {
    if let Some(text) = req.target.write_everything(sys, req.steps) {
        let mut e = Emitter::new(sys, spans, source, origin, req);
        e.exact("the whole system", None, "");
        return e.finish(text);
    }
    if sys.graph.is_some() {
        // Written without its graph, the system would draw nothing of it.
        let what = "an object-instancing graph cannot be written in";
        return refused(
            crate::diagnostics::codes::TR_GRAPH,
            format!("{what} {}", req.target.name()),
            "graftal writes graphs in its own notation only: `--to gft`",
        );
    }
    if sys.rewrites_modules() {
        return refused(
            crate::diagnostics::codes::TR_PARAMETRIC,
            "parametric cpfg L-systems cannot be translated yet".into(),
            "graftal translates pfg, LinF and STL systems, and Fractint entries",
        );
    }
    let target = req.target;
    if sys.structure.is_some() {
        if let Some(text) = target.write_structure(sys) {
            let mut e = Emitter::new(sys, spans, source, origin, req);
            e.exact("the STL file, as a Branch-Expansion Description", None, "");
            // Rules are written expanded: `[I n [F]]` is n brackets deep.
            if let Some(st) = &sys.structure {
                let bodies: Vec<(&str, String)> = (st.rules.iter())
                    .map(|r| (r.name.as_str(), r.body.display(&sys.symbols)))
                    .collect();
                stl::too_deep_to_read(&mut e, bodies.iter().map(|(n, b)| (*n, b)));
            }
            return e.finish(text);
        }
        return translate_structure(sys, source, origin, req);
    }
    let (plain, problems) = common_operations(sys, spans, target.name());
    let mut e = Emitter::new(&plain, spans, source, origin, req);
    for p in problems {
        e.problem(p.kind, p.span, p.what, p.change);
    }
    let text = target.write(&mut e);
    e.finish(text)
}

/// A translation not written, for the one reason `code` says.
fn refused(code: crate::diagnostics::Code, message: String, help: &str) -> Translation {
    let mut diagnostics = crate::diagnostics::Diagnostics::default();
    diagnostics.push(crate::diagnostics::Diagnostic::global(code, message).with_help(help));
    Translation {
        text: None,
        mapping: Vec::new(),
        names: Vec::new(),
        diagnostics,
    }
}

/// A system with a growth structure, for a target without one: the
/// structure as productions ([`from_stl`]), then the target's emitter.
fn translate_structure(sys: &System, source: &str, origin: &Origin, req: &Request) -> Translation {
    let explicit = req
        .target
        .term_symbols()
        .is_some_and(|n| from_stl::term_count(sys) > n);
    let (flat, problems) = from_stl::productions(sys, explicit);
    // Where things are: STL keeps no spans past lowering, so they
    // are found by the lines that define them.
    let mut where_ = SpanTable::default();
    let mut written = HashMap::new();
    for (id, info) in flat.symbols.iter() {
        let factor = matches!(flat.op(id), Some(TurtleOp::ScaleLength(_)));
        let line = if factor {
            line_starting(source, "L")
        } else {
            info.name
                .split('_')
                .next()
                .and_then(|rule| line_starting(source, rule))
        };
        if let Some(span) = line {
            if let (true, Some(text)) = (factor, source.get(span.clone())) {
                written.insert(id, text.to_string());
            }
            where_.symbols.insert(id, span);
        }
    }
    let mut req2 = req.clone();
    req2.steps = flat.settings.steps;
    let mut e = Emitter::new(&flat, &where_, source, origin, &req2);
    e.written = written;
    for p in problems {
        let span = p.span.or_else(|| match p.kind {
            Kind::Layout => line_starting(source, "LAYOUT"),
            Kind::Attribute => line_starting(source, "B"),
            _ => None,
        });
        e.problem(p.kind, span, p.what, p.change);
    }
    let text = req.target.write(&mut e);
    e.finish(text)
}

/// A system with the operations no target has (Fractint's) replaced by the
/// common ones where that means the same, and the problems where it does
/// not: the real heading (`\n /n D M`) is the frame's heading when the
/// system uses only one of the two; `|` is a plain turn unless `!` swaps
/// turns; colour indices (`Cn <n >n`) and an indexed palette that starts
/// past its first colour have no counterpart; strings with unbalanced
/// brackets are balanced. For a system with none of these, the same
/// system and no problem.
fn common_operations(sys: &System, spans: &SpanTable, to: &str) -> (System, Vec<Problem>) {
    let mut plain = sys.clone();
    let mut problems = Vec::new();
    let ops: Vec<(SymbolId, TurtleOp)> = (0..sys.symbols.len() as u32)
        .map(SymbolId)
        .filter_map(|s| sys.op(s).map(|op| (s, op)))
        .collect();
    let uses = |f: fn(&TurtleOp) -> bool| ops.iter().any(|(_, op)| f(op));
    let two_headings =
        uses(|op| {
            matches!(
                op,
                TurtleOp::Forward { .. }
                    | TurtleOp::Rotate { .. }
                    | TurtleOp::TurnAround
                    | TurtleOp::TurnUnswapped(_)
            )
        }) && uses(|op| matches!(op, TurtleOp::RotateReal(_) | TurtleOp::ForwardReal { .. }));
    let swaps = uses(|op| matches!(op, TurtleOp::SwapTurns));
    for (s, op) in ops {
        let name = sys.symbols.name(s);
        let span = spans.symbols.get(&s).cloned();
        let mut problem = |kind, what: String, change: &str| {
            problems.push(Problem {
                kind,
                span: span.clone(),
                what,
                change: change.to_string(),
            })
        };
        let new = match op {
            TurtleOp::RotateReal(_) | TurtleOp::ForwardReal { .. } => {
                if two_headings {
                    problem(
                        Kind::Angle,
                        format!("`{name}` uses Fractint's second heading (`\\n /n D M`) beside the first (`+ - | F G`): {to} has one heading"),
                        "the two headings are merged into one",
                    );
                }
                Some(match op {
                    TurtleOp::RotateReal(angle) => TurtleOp::Rotate {
                        axis: Axis::Up,
                        angle,
                    },
                    _ => TurtleOp::Forward {
                        draw: matches!(op, TurtleOp::ForwardReal { draw: true }),
                    },
                })
            }
            TurtleOp::TurnUnswapped(angle) => {
                if swaps {
                    problem(
                        Kind::Swap,
                        format!("`{name}` turns the same way after `!`: {to} has no such turn"),
                        "it is written as a turn that `!` reverses",
                    );
                }
                Some(TurtleOp::Rotate {
                    axis: Axis::Up,
                    angle,
                })
            }
            TurtleOp::SetColour(_) | TurtleOp::ShiftColour { .. } => {
                problem(
                    Kind::Attribute,
                    format!("the colour command `{name}` (sets a palette index): {to} has no colour indices"),
                    "it is dropped",
                );
                None
            }
            other => Some(other),
        };
        plain.interpretation[s.index()] = new;
    }
    // Fractint tolerates a string with unbalanced brackets (W0702); the
    // targets do not.
    let mut words: Vec<(&mut crate::ir::Word, Option<Span>)> =
        vec![(&mut plain.axiom, spans.axiom.first().cloned())];
    for (i, p) in plain.productions.iter_mut().enumerate() {
        let span = spans.productions.get(i).cloned();
        for a in &mut p.alternatives {
            words.push((&mut a.successor, span.clone()));
        }
    }
    for (word, span) in words {
        let mut depth = 0usize;
        let mut balanced = Vec::with_capacity(word.0.len());
        for &s in &word.0 {
            if s == SymbolId::CLOSE {
                if depth == 0 {
                    continue;
                }
                depth -= 1;
            } else if s == SymbolId::OPEN {
                depth += 1;
            }
            balanced.push(s);
        }
        balanced.extend(std::iter::repeat_n(SymbolId::CLOSE, depth));
        if balanced != word.0 {
            problems.push(Problem {
                kind: Kind::Rule,
                span,
                what: format!("a string with unbalanced brackets: {to} needs every `[` closed"),
                change: "unmatched `]` are dropped and missing `]` added at the end".into(),
            });
            word.0 = balanced;
        }
    }
    if plain.settings.colour != 0 {
        plain.colours.clear();
        plain.settings.colour = 0;
    }
    fold_leading_scale(&mut plain);
    (plain, problems)
}

/// Folds the length factors (LinF `10@ f`) that start the axiom and that
/// no production rewrites into the step length: they scale the whole
/// picture, which each target then says its own way (a length factor, STL's
/// `L`, `.gft`'s `length`) or reports (pfg's steps are 1 long), so that a
/// translation said to be exact keeps the coordinates.
fn fold_leading_scale(sys: &mut System) {
    let rewritten: HashSet<SymbolId> = (sys.productions.iter())
        .flat_map(|p| p.predecessor.iter().copied())
        .collect();
    let factor = |s: &SymbolId| match sys.op(*s) {
        Some(TurtleOp::ScaleLength(x)) if x > 0.0 && x.is_finite() && !rewritten.contains(s) => {
            Some(x)
        }
        _ => None,
    };
    let factors: Vec<f64> = sys.axiom.0.iter().map_while(factor).collect();
    let step = factors.iter().fold(sys.settings.step, |l, x| l * x);
    if step.is_finite() && step > 0.0 {
        sys.axiom.0.drain(..factors.len());
        sys.settings.step = step;
    }
}

/// The first line of `src` that starts with the word `word` (followed by
/// a blank, `=` or the end of the line), as a span without its blanks;
/// comments are not lines.
pub fn line_starting(src: &str, word: &str) -> Option<Span> {
    let mut offset = 0;
    for line in src.split_inclusive('\n') {
        let t = line.trim_start();
        let start = offset + (line.len() - t.len());
        offset += line.len();
        let Some(rest) = t.strip_prefix(word) else {
            continue;
        };
        if rest
            .chars()
            .next()
            .is_none_or(|c| c.is_whitespace() || c == '=')
        {
            let body = t.trim_end();
            return Some(start..start + body.len());
        }
    }
    None
}

// ---------------------------------------------------------------------
// Shared analysis
// ---------------------------------------------------------------------

/// The symbols that occur anywhere in the system (axiom, productions), in
/// symbol-table order.
pub fn occurring(sys: &System) -> Vec<SymbolId> {
    let mut seen = vec![false; sys.symbols.len()];
    let mut mark = |w: &[SymbolId]| {
        for &s in w {
            seen[s.index()] = true;
            if let Some(g) = sys.symbols.info(s).guard {
                seen[g.base.index()] = true;
            }
        }
    };
    mark(&sys.axiom.0);
    for p in &sys.productions {
        mark(&p.left);
        mark(&p.predecessor);
        mark(&p.right);
        for a in &p.alternatives {
            mark(&a.successor.0);
        }
    }
    (0..seen.len())
        .filter(|&i| seen[i])
        .map(|i| SymbolId(i as u32))
        .collect()
}

/// The alternative a deterministic target uses: the heaviest (the first
/// of equal weights).
pub fn heaviest(p: &Production) -> usize {
    let mut best = 0;
    for (i, a) in p.alternatives.iter().enumerate() {
        if a.weight > p.alternatives[best].weight {
            best = i;
        }
    }
    best
}

/// For targets that rewrite one symbol by one rule (LinF, STL): which
/// production rewrites each symbol.
#[derive(Clone, Debug, Default)]
pub struct Rules {
    by_symbol: HashMap<SymbolId, usize>,
}

impl Rules {
    /// The index of the production that rewrites `s`.
    pub fn get(&self, s: SymbolId) -> Option<usize> {
        self.by_symbol.get(&s).copied()
    }

    pub fn contains(&self, s: SymbolId) -> bool {
        self.by_symbol.contains_key(&s)
    }

    pub fn remove(&mut self, s: SymbolId) {
        self.by_symbol.remove(&s);
    }

    /// Each rewritten symbol with its production, in the productions'
    /// order.
    pub fn heads(&self) -> Vec<(SymbolId, usize)> {
        let mut heads: Vec<(SymbolId, usize)> =
            self.by_symbol.iter().map(|(&s, &i)| (s, i)).collect();
        heads.sort_by_key(|&(_, i)| i);
        heads
    }

    /// The successor `s` is rewritten to: the heaviest alternative's.
    pub fn successor<'s>(&self, sys: &'s System, s: SymbolId) -> Option<&'s [SymbolId]> {
        let p = &sys.productions[self.get(s)?];
        Some(&p.alternatives[heaviest(p)].successor.0)
    }
}

/// The [`Rules`] of a system for a target that rewrites one symbol by one
/// rule, reporting what such targets cannot express (contexts, several
/// predecessor symbols, random choice). Contexts dropped under `--lossy`
/// make the first production for a symbol apply everywhere; productions
/// after it never apply, in the source as in the target.
pub fn single_symbol_rules(e: &mut Emitter<'_>, target: &str) -> Rules {
    let mut rules: HashMap<SymbolId, usize> = HashMap::new();
    for (i, p) in e.sys.productions.iter().enumerate() {
        let text = e.production_text(i);
        let span = e.production_span(i);
        if p.predecessor.len() != 1 {
            e.problem(
                Kind::Rule,
                span,
                format!("the production `{text}` rewrites several symbols at once, which {target} cannot"),
                "the production is dropped",
            );
            continue;
        }
        let head = p.predecessor[0];
        if p.is_context_sensitive() {
            e.problem(
                Kind::Context,
                span.clone(),
                format!("the context of `{text}`: {target} rewrites without context"),
                "the context is dropped, so the production applies wherever its predecessor occurs",
            );
            if !e.lossy {
                continue;
            }
        }
        if rules.contains_key(&head) {
            e.mapping.push(Mapped {
                construct: format!("production `{text}`"),
                span,
                status: Status::Exact,
                target: String::new(),
                note: Some(
                    "never applies: an earlier production for the same symbol always does".into(),
                ),
            });
            continue;
        }
        if p.is_stochastic() {
            e.problem(
                Kind::Stochastic,
                span,
                format!("the random choice of `{text}`: {target} has no stochastic rules"),
                "the most likely successor is always used",
            );
        }
        rules.insert(head, i);
    }
    Rules { by_symbol: rules }
}

/// The rotations a turtle operation makes, each about one axis (radians),
/// in order; `None` when it is not a rotation.
pub enum Turns {
    Fixed(Vec<(Axis, f64)>),
    /// An interval angle: drawn at random when applied. The rotations are
    /// given with each interval's middle.
    Random(Vec<(Axis, f64)>),
}

/// Resolves an angle in radians for a system; `None` for intervals.
pub fn radians(sys: &System, a: Angle) -> Option<f64> {
    match a {
        Angle::Delta(k) => Some(k * sys.settings.delta),
        Angle::Radians(r) => Some(r),
        Angle::Uniform { .. } => None,
    }
}

fn middle(sys: &System, a: Angle) -> f64 {
    match a {
        Angle::Uniform { lo, hi } => (lo + hi) / 2.0,
        other => radians(sys, other).unwrap_or(0.0),
    }
}

/// The turns of `op`, as rotations about the turtle's axes.
pub fn turns(sys: &System, op: TurtleOp) -> Option<Turns> {
    match op {
        TurtleOp::Rotate { axis, angle } => {
            let t = vec![(axis, middle(sys, angle))];
            Some(match angle {
                Angle::Uniform { .. } => Turns::Random(t),
                _ => Turns::Fixed(t),
            })
        }
        TurtleOp::Frenet { rotation, negate } => {
            let r = sys.rotations.get(rotation.0 as usize)?;
            let sign = if negate { -1.0 } else { 1.0 };
            let mut t = Vec::new();
            let tor = middle(sys, r.torsion);
            let cur = middle(sys, r.curvature);
            if tor != 0.0 {
                t.push((Axis::Heading, -sign * tor));
            }
            if cur != 0.0 {
                t.push((Axis::Up, -sign * cur));
            }
            let random = matches!(r.torsion, Angle::Uniform { .. })
                || matches!(r.curvature, Angle::Uniform { .. });
            Some(if random {
                Turns::Random(t)
            } else {
                Turns::Fixed(t)
            })
        }
        TurtleOp::TurnAround => Some(Turns::Fixed(vec![(Axis::Up, std::f64::consts::PI)])),
        _ => None,
    }
}

/// The largest angle 2π/n (n at most 3600) of which every angle is a
/// whole multiple (within 1e-9 of a turn); `prefer` is tried first.
pub fn increment(angles: &[f64], prefer: Option<u64>) -> Option<u64> {
    let fits = |n: u64| {
        angles.iter().all(|&a| {
            let k = a * n as f64 / std::f64::consts::TAU;
            (k - k.round()).abs() < 1e-9 * n as f64
        })
    };
    if let Some(p) = prefer.filter(|&p| p >= 1 && fits(p)) {
        return Some(p);
    }
    (1..=3600).find(|&n| fits(n))
}

/// The first of `angles` (with the symbol that turns by it) that is not a
/// whole multiple of one angle together with those before it: where to
/// point when [`increment`] finds none.
pub fn odd_angle(angles: &[(SymbolId, f64)]) -> Option<SymbolId> {
    let mut seen = Vec::new();
    for &(s, a) in angles {
        seen.push(a);
        if increment(&seen, None).is_none() {
            return Some(s);
        }
    }
    None
}

/// The angle factor n (turns by multiples of 360/n degrees) for the
/// turns `by_symbol` (each symbol with an angle it turns by): the source's
/// own factor when it is pfg and fits, else the smallest that fits; when
/// none does, a problem at the first angle that breaks it, and 360.
pub fn angle_factor(e: &mut Emitter<'_>, by_symbol: &[(SymbolId, f64)], target: &str) -> u64 {
    let angles: Vec<f64> = by_symbol.iter().map(|x| x.1).collect();
    // With no turn to fit, the system's own increment, so that δ is kept.
    let own = || angles.is_empty().then(|| e.sys.settings.whole_divisions());
    let prefer =
        (e.origin.angle_divisions.map(|n| n.min(i64::MAX as u64))).or_else(|| own().flatten());
    if let Some(n) = increment(&angles, prefer) {
        return n;
    }
    let list: Vec<String> = angles
        .iter()
        .map(|a| crate::number::readable(a.to_degrees()))
        .collect();
    let odd = odd_angle(by_symbol);
    e.problem(
        Kind::Angle,
        odd.and_then(|s| e.symbol_span(s)),
        format!(
            "the angles ({} degrees) are not whole multiples of one angle, as {target} needs{}",
            list.join(", "),
            odd.map(|s| format!(": `{}` breaks it", e.name(s)))
                .unwrap_or_default()
        ),
        "every angle is rounded to a whole degree",
    );
    360
}

/// Whole multiples of 2π/n making up `a`, between −n/2 and n/2.
pub fn multiples(a: f64, n: u64) -> i64 {
    let n = n as f64;
    let mut k = (a * n / std::f64::consts::TAU).round().rem_euclid(n);
    if k * 2.0 > n {
        k -= n;
    }
    k as i64
}

/// The most times one turn symbol is repeated to make an angle.
pub const MAX_REPEAT: u64 = 3600;

/// `c` written `|k|` times for the turn of symbol `s`; a problem (and
/// nothing written) beyond [`MAX_REPEAT`].
pub fn repeated(e: &mut Emitter<'_>, s: SymbolId, c: char, k: i64) -> String {
    let n = k.unsigned_abs();
    if n > MAX_REPEAT {
        e.problem(
            Kind::Angle,
            e.symbol_span(s),
            format!(
                "the turn of `{}` would be {n} turn symbols (the angle increment is too small)",
                e.name(s)
            ),
            "the turn is dropped",
        );
        return String::new();
    }
    std::iter::repeat_n(c, n as usize).collect()
}

pub use crate::number::degrees;
/// `x` as a short decimal that reads back as the same `f64` (see
/// [`crate::number`]).
pub use crate::number::exact as number;

// ---------------------------------------------------------------------
// Names
// ---------------------------------------------------------------------

/// Allocates the target's names, avoiding reserved ones and each other.
pub struct Names {
    used: HashSet<String>,
}

impl Names {
    pub fn new(reserved: &[&str]) -> Self {
        Names {
            used: reserved.iter().map(|s| s.to_string()).collect(),
        }
    }

    pub fn is_free(&self, name: &str) -> bool {
        !self.used.contains(name)
    }

    /// Takes the first free name of `candidates`.
    pub fn take(&mut self, candidates: impl IntoIterator<Item = String>) -> Option<String> {
        for c in candidates {
            if !c.is_empty() && !self.used.contains(&c) {
                self.used.insert(c.clone());
                return Some(c);
            }
        }
        None
    }

    /// Reserves `name`.
    pub fn reserve(&mut self, name: &str) {
        self.used.insert(name.to_string());
    }
}

/// `base` followed by each number of `range`: names to try after the
/// wished ones.
pub fn numbered(base: &str, range: std::ops::Range<u32>) -> impl Iterator<Item = String> + '_ {
    range.map(move |i| format!("{base}{i}"))
}

// ---------------------------------------------------------------------
// Comments
// ---------------------------------------------------------------------

/// A comment's lines, trimmed and with common decoration removed.
pub fn comment_lines(text: &str) -> Vec<String> {
    // A lone CR ends a line too (it would end a LinF or STL comment).
    let text = text.replace("\r\n", "\n").replace('\r', "\n");
    let lines: Vec<String> = text
        .lines()
        .map(|l| l.trim_end().to_string())
        .collect::<Vec<_>>();
    let indent = lines
        .iter()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.len() - l.trim_start().len())
        .min()
        .unwrap_or(0);
    let mut out: Vec<String> = lines
        .iter()
        .map(|l| l.get(indent..).unwrap_or("").trim_end().to_string())
        .collect();
    while out.first().is_some_and(|l| l.trim().is_empty()) {
        out.remove(0);
    }
    while out.last().is_some_and(|l| l.trim().is_empty()) {
        out.pop();
    }
    out
}

/// The comment that opens the file (before anything else), if any.
pub fn file_comment(cs: &[(Span, String)], src: &str) -> Option<Vec<String>> {
    let mut lines = Vec::new();
    let mut pos = 0;
    for (span, text) in cs {
        if !src[pos..span.start].trim().is_empty() {
            break;
        }
        lines.extend(comment_lines(text));
        pos = span.end;
    }
    // A translation's own first line is not carried into the next one.
    if lines
        .first()
        .is_some_and(|l| l.starts_with("Translated by graftal from"))
    {
        lines.remove(0);
        lines = comment_lines(&lines.join("\n"));
    }
    (!lines.is_empty()).then_some(lines)
}

/// Where a comment stands relative to the item it is attached to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Attached {
    /// On the lines right above the item.
    Above(Vec<String>),
    /// On the item's (last) line, after it.
    After(String),
}

/// The comment attached to the item at `span`: on the same line after it,
/// else on the lines right above it (no blank line between), not counting
/// the file's opening comment.
pub fn attached(cs: &[(Span, String)], src: &str, span: &Span) -> Option<Attached> {
    let lines = attached_comment(cs, src, span)?;
    let line_end = src[span.end.min(src.len())..]
        .find('\n')
        .map_or(src.len(), |k| span.end + k);
    let trailing = cs
        .iter()
        .any(|(s, _)| s.start >= span.end && s.start <= line_end);
    Some(if trailing && lines.len() == 1 {
        Attached::After(lines[0].trim().to_string())
    } else {
        Attached::Above(lines)
    })
}

/// The lines of the comment [`attached`] to the item at `span`.
pub fn attached_comment(cs: &[(Span, String)], src: &str, span: &Span) -> Option<Vec<String>> {
    let opening_end = {
        let mut pos = 0;
        for (s, _) in cs {
            if !src[pos..s.start].trim().is_empty() {
                break;
            }
            pos = s.end;
        }
        pos
    };
    let line_end = src[span.end.min(src.len())..]
        .find('\n')
        .map_or(src.len(), |k| span.end + k);
    // Trailing: a comment starting on the item's last line.
    for (s, text) in cs {
        if s.start >= span.end && s.start <= line_end {
            let l = comment_lines(text);
            if !l.is_empty() {
                return Some(l);
            }
        }
    }
    // Leading: comments that end on the line before the item, chained up.
    let line_start = src[..span.start.min(src.len())]
        .rfind('\n')
        .map_or(0, |k| k + 1);
    let mut lines: Vec<String> = Vec::new();
    let mut boundary = line_start;
    for (s, text) in cs.iter().rev() {
        if s.end > boundary || s.start < opening_end {
            continue;
        }
        let between = &src[s.end..boundary];
        // Only blanks and at most one line break between the comment and
        // what follows it.
        if !between.trim().is_empty() || between.matches('\n').count() > 1 {
            break;
        }
        // The comment must start its line.
        let ls = src[..s.start].rfind('\n').map_or(0, |k| k + 1);
        if !src[ls..s.start].trim().is_empty() {
            break;
        }
        let mut l = comment_lines(text);
        l.append(&mut lines);
        lines = l;
        boundary = ls;
    }
    (!lines.is_empty()).then_some(lines)
}

/// The first line every translation starts with.
pub fn banner(e: &Emitter<'_>) -> String {
    format!("Translated by graftal from {}", e.origin.title)
}

/// The comment every translation opens with: the [`banner`], then, after
/// a blank line, the source's [`file_comment`].
pub fn opening(e: &Emitter<'_>) -> Vec<String> {
    let mut head = vec![banner(e)];
    if let Some(c) = file_comment(&e.origin.comments, e.source) {
        head.push(String::new());
        head.extend(c);
    }
    head
}

/// A comment line as LinF and STL write it: `#`, a blank, the text.
pub fn hash_line(l: &str) -> String {
    if l.is_empty() {
        "#".into()
    } else {
        format!("# {l}")
    }
}

/// Comment lines as LinF and STL write them, each ending its line.
pub fn hash_comment(lines: &[String]) -> String {
    lines.iter().map(|l| hash_line(l) + "\n").collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::Front;

    #[test]
    fn increment_finds_the_largest_common_angle() {
        let pi = std::f64::consts::PI;
        assert_eq!(increment(&[pi / 3.0], None), Some(6));
        assert_eq!(increment(&[pi / 3.0, pi / 2.0], None), Some(12));
        assert_eq!(increment(&[pi / 2.0], Some(8)), Some(8));
        assert_eq!(increment(&[1.0], None), None);
        assert_eq!(increment(&[], None), Some(1));
    }

    #[test]
    fn multiples_are_reduced_to_half_a_turn() {
        let pi = std::f64::consts::PI;
        assert_eq!(multiples(pi / 3.0, 6), 1);
        assert_eq!(multiples(-pi / 3.0, 6), -1);
        assert_eq!(multiples(5.0 * pi / 3.0, 6), -1);
        assert_eq!(multiples(pi, 4), 2);
    }

    #[test]
    fn comments_attach_to_the_item_after_them_or_on_their_line() {
        let src = "/* file */\naxiom: F\n/* doubles */\nF --> FF\nG --> G /* stays */\n\n/* far */\n\nH --> H\n";
        let at = |s: &str| {
            let k = src.find(s).unwrap();
            k..k + s.len()
        };
        let cs = crate::front::pfg::Pfg.comments(src);
        assert_eq!(file_comment(&cs, src), Some(vec!["file".into()]));
        assert_eq!(
            attached_comment(&cs, src, &at("F --> FF")),
            Some(vec!["doubles".into()])
        );
        assert_eq!(
            attached_comment(&cs, src, &at("G --> G")),
            Some(vec!["stays".into()])
        );
        assert_eq!(attached_comment(&cs, src, &at("H --> H")), None);
        let linf = "# top\nrules\n  # grows\n  f = ff  # twice\n";
        let k = linf.find("f = ff").unwrap();
        assert_eq!(
            attached_comment(&crate::front::linf::Linf.comments(linf), linf, &(k..k + 6)),
            Some(vec!["twice".into()])
        );
    }
}
