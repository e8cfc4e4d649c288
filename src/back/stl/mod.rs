//! The STL emitter.
//!
//! [`write`]: an STL system (its lowered structure) written out as a
//! Branch-Expansion Description, the paper's BED text files.
//! [`from_productions`]: a pfg or LinF system written as STL rules whose
//! expansion is the word the source derives in the given number of steps.
//!
//! What is written: the settings (`ANGLE`, `B`, `L`, `GROWTH`, `LEVELS`),
//! every rule with its body expanded to drawing components (macros and
//! `[I n X]` written out, which draws the same), the seed with every
//! branching term explicit (`~` for failed branches, trailing empty entries
//! left out, `R{}` for a term of a rule with branches and no entries, the
//! bare name for a rule without branches), and the layout. An Outline
//! Description's grown tree is such a seed, and since it has no growth point
//! left, reading the BED back draws exactly the same stems (and the layout
//! under them).

use super::walk::{
    distinct_colours, dropped, fractint_only, nesting_of, no_chance, no_length_factor, no_polygons,
    no_scale, no_widths, spell_each, turn_text, turning, write_word, Does, Sym, Symbols, Turning,
};
use super::{
    hash_comment, number, numbered, opening, single_symbol_rules, Emitter, Kind, Names, Rules,
};
use crate::common::stl_words::RESERVED;
use crate::ir::{
    Axis, BranchEntry, BranchTerm, SeedItem, Shape, Structure, SymbolId, System, Word, MAX_NESTING,
};
use std::collections::HashMap;
use std::fmt::Write;

/// The Stl emitter in the registry.
pub struct Stl;

impl super::Back for Stl {
    fn name(&self) -> &'static str {
        "stl"
    }
    fn extension(&self) -> &'static str {
        "stl"
    }
    fn write(&self, e: &mut super::Emitter<'_>) -> String {
        from_productions(e)
    }
    fn write_structure(&self, sys: &crate::ir::System) -> Option<String> {
        Some(write(sys).unwrap_or_default())
    }
}

/// Writes `sys` (which must come from the STL front end) as a BED; `None`
/// for a system without STL structure.
pub fn write(sys: &System) -> Option<String> {
    let st = sys.structure.as_ref()?;
    // Components are written together unless a rule name could swallow
    // them (a name made only of F, L and R).
    let spaced = st
        .rules
        .iter()
        .any(|r| r.name.chars().all(|c| matches!(c, 'F' | 'L' | 'R')));
    let mut out = String::new();
    out.push_str("# Branch-Expansion Description written by graftal\n");
    let _ = writeln!(out, "ANGLE {}", super::degrees(sys.settings.delta));
    let _ = writeln!(
        out,
        "B = {} ({})",
        st.stems.broadness.0, st.stems.broadness.1
    );
    let _ = writeln!(out, "L = {} ({})", st.stems.length.0, st.stems.length.1);
    let _ = writeln!(
        out,
        "GROWTH {}",
        match st.constraint.strategy {
            crate::ir::Growth::BreadthFirst => "BFS",
            crate::ir::Growth::DepthFirst => "DFS",
        }
    );
    let _ = writeln!(out, "LEVELS {}", st.constraint.levels);
    for r in &st.rules {
        let _ = writeln!(out, "{} = {}", r.name, word(sys, &r.body, spaced));
    }
    out.push_str("SEED\n");
    let mut line = String::new();
    for item in &st.seed {
        if !line.is_empty() {
            line.push(' ');
        }
        match item {
            SeedItem::Word(w) => line.push_str(&word(sys, w, spaced)),
            SeedItem::Term(t) => term(sys, st, t, &mut line),
        }
    }
    out.push_str(line.trim());
    out.push_str("\nENDSEED\n");
    if !st.constraint.outline.is_empty() {
        out.push_str("LAYOUT\n");
        for s in &st.constraint.outline {
            out.push_str(&shape(s));
            out.push('\n');
        }
        out.push_str("ENDLAYOUT\n");
    }
    Some(out)
}

fn word(sys: &System, w: &Word, spaced: bool) -> String {
    let names =
        w.0.iter()
            .map(|&s: &SymbolId| sys.symbols.name(s))
            .filter(|n| !n.is_empty());
    if spaced {
        names.collect::<Vec<_>>().join(" ")
    } else {
        names.collect()
    }
}

fn has_branches(sys: &System, body: &Word) -> bool {
    let _ = sys;
    body.0.contains(&SymbolId::OPEN)
}

/// Writes `t` and its entries (by recursion, as deep as the terms nest:
/// the STL front end, which alone makes them, keeps that within
/// [`MAX_NESTING`]).
fn term(sys: &System, st: &Structure, t: &BranchTerm, out: &mut String) {
    let Some(rule) = st.rules.get(t.rule.0 as usize) else {
        return;
    };
    out.push_str(&rule.name);
    let keep = t
        .entries
        .iter()
        .rposition(|e| *e != BranchEntry::Empty)
        .map_or(0, |i| i + 1);
    if keep == 0 && !has_branches(sys, &rule.body) {
        return;
    }
    out.push('{');
    for (i, e) in t.entries[..keep].iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        match e {
            BranchEntry::Empty => {}
            BranchEntry::Failed => out.push('~'),
            BranchEntry::Term(c) => term(sys, st, c, out),
        }
    }
    out.push('}');
}

fn colour(c: crate::ir::Rgb) -> String {
    match crate::ir::colours::delphi().iter().find(|(_, v)| *v == c) {
        Some((n, _)) => n.to_string(),
        None => format!("$00{:02X}{:02X}{:02X}", c.2, c.1, c.0),
    }
}

fn shape(s: &Shape) -> String {
    match s {
        Shape::Rectangle {
            colour: c,
            x,
            y,
            w,
            h,
        } => {
            format!("({}) Rectangle ({x}, {y}), {w}, {h}", colour(*c))
        }
        Shape::Ellipse {
            colour: c,
            x,
            y,
            w,
            h,
        } => {
            format!("({}) Ellipse ({x}, {y}), {w}, {h}", colour(*c))
        }
        Shape::RoundRect {
            colour: c,
            x,
            y,
            w,
            h,
            corner,
        } => format!("({}) RoundRect ({x}, {y}), {w}, {h}, {corner}", colour(*c)),
        Shape::Polygon { colour: c, points } => {
            let pts: Vec<String> = points.iter().map(|(x, y)| format!("({x}, {y})")).collect();
            format!("({}) Polygon {}", colour(*c), pts.join(", "))
        }
    }
}

/// How many components the STL reader expands at most.
const MAX_COMPONENTS: u64 = crate::ir::Structure::MAX_EXPANSION as u64;

/// How STL takes the turns of a system.
const TURNING: Turning = Turning {
    target: "STL",
    fixed: "STL turns by a fixed angle",
    middle_in_degrees: false,
    plane: true,
};

/// A pfg or LinF system as STL. STL has no derivation: the steps are
/// written into the rules. Symbol `s` after `k` steps is the macro `Sk`,
/// whose body is `s`'s successor with each symbol after `k − 1` steps; a
/// symbol nothing rewrites (or any symbol after 0 steps) is its drawing
/// components (`F`, `L`/`R` repeated to make the angle, brackets), or
/// nothing. When only the drawing symbol is rewritten, the macro is the
/// paper's self-resemblance count `[I n X]`. STL draws in the plane with
/// stems only: moves without drawing, 3D turns, colours, widths and
/// length factors are problems, as are contexts and random choices.
pub fn from_productions(e: &mut super::Emitter<'_>) -> String {
    let sys = e.sys;
    let rules = single_symbol_rules(e, "STL");
    let syms = Symbols::of(sys);
    let n = turning(e, &syms.plain, &TURNING);
    let distinct = distinct_colours(sys);
    let comps = spell_each(e, syms.plain.iter().copied(), |e, sym| {
        Some(components(e, sym, n, distinct))
    })
    .into_iter()
    .map(|(sym, text)| (sym.id, text))
    .collect();
    // A guarded occurrence is its base.
    for &(s, g) in &syms.guarded {
        no_chance(e, s, g, "STL has no chance");
    }
    no_scale(e, "STL pictures fill the frame");

    let steps = e.steps;
    let sizes = Sizes::new(sys, &rules, &comps);
    let mut x = Expansion {
        sys,
        rules: &rules,
        comps,
        sizes,
        names: Names::new(&RESERVED),
        stems: HashMap::new(),
        defined: HashMap::new(),
        stack: Vec::new(),
    };
    let resembling = x.self_resembling(steps);
    // Without a self-resemblance count, each step is a rule holding the
    // rules of the step before: a chain as long as the steps, which the
    // STL reader (like every reader) follows at most MAX_NESTING deep.
    if resembling.is_none() && steps > MAX_NESTING as u64 && x.rewrites_from_axiom() {
        e.problem(
            Kind::TooDeep,
            None,
            format!(
                "after {steps} steps the rules nest {steps} deep, one rule per step; STL reads rules through rules at most {MAX_NESTING} deep"
            ),
            format!("translate with at most {MAX_NESTING} steps (`-n`)"),
        );
        return text(e, n, &rules, &[], "");
    }
    if x.total(steps) > MAX_COMPONENTS {
        e.problem(
            Kind::TooLarge,
            None,
            format!(
                "after {steps} steps the word has more than {MAX_COMPONENTS} drawing components, the most STL expands"
            ),
            "translate with fewer steps (`-n`)",
        );
    }
    let (out_rules, seed) = if let Some(d) = resembling {
        x.self_resemblance(d, steps)
    } else if x.total(steps) <= MAX_COMPONENTS {
        x.macros(steps)
    } else {
        (Vec::new(), String::new())
    };
    let bodies = out_rules
        .iter()
        .map(|(_, name, body)| (name.as_str(), body));
    too_deep_to_read(e, bodies.chain([("the seed", &seed)]));
    text(e, n, &rules, &out_rules, &seed)
}

/// Reports the first of `bodies` (what a rule or the seed holds) whose
/// brackets nest deeper than STL reads (past [`MAX_NESTING`]).
pub fn too_deep_to_read<'b>(
    e: &mut Emitter<'_>,
    bodies: impl Iterator<Item = (&'b str, &'b String)>,
) {
    let deep = bodies
        .map(|(name, body)| (name, nesting_of(body)))
        .find(|&(_, depth)| depth > MAX_NESTING);
    if let Some((name, depth)) = deep {
        e.problem(
            Kind::TooDeep,
            None,
            format!("`{name}` nests {depth} deep written out; STL reads brackets and braces at most {MAX_NESTING} deep"),
            "translate to a notation that reads branches to any depth (pfg, LinF)",
        );
    }
}

/// The drawing components STL writes for a symbol, with the angle factor
/// `n` and the count of the file's distinct colours.
fn components(e: &mut Emitter<'_>, sym: &Sym, n: u64, distinct: usize) -> String {
    let sys = e.sys;
    let name = &sym.name;
    let span = sym.span.clone();
    match sym.does {
        Does::Nothing | Does::Stem | Does::Cpfg => String::new(),
        Does::Forward { draw: true } => "F".into(),
        Does::Forward { draw: false } => {
            e.problem(
                Kind::Move,
                span,
                format!("`{name}` moves without drawing: every STL stem is drawn"),
                "the move is drawn as a stem",
            );
            "F".into()
        }
        Does::Turn(op) => turn_text(e, sym.id, op, n, None, |axis, positive| {
            (axis == Axis::Up).then_some(if positive { 'R' } else { 'L' })
        }),
        Does::Push => "[".into(),
        Does::Pop => "]".into(),
        Does::Colour { .. } if sys.colours.is_empty() || distinct > 1 => dropped(
            e,
            sym,
            Kind::Attribute,
            format!("the colour symbol `{name}`: STL stems have no colours"),
            "it is dropped",
        ),
        Does::Colour { .. } => String::new(),
        Does::Thinner => no_widths(e, sym, "STL sets widths per level only"),
        Does::Polygon { .. } => no_polygons(e, sym, "STL", "as stems"),
        Does::Swap => dropped(
            e,
            sym,
            Kind::Swap,
            format!("`{name}` exchanges left and right: STL has no such component"),
            "it is dropped",
        ),
        Does::Length(x) => no_length_factor(e, sym, x, "STL stem lengths change per level only"),
        Does::Fractint => fractint_only(e, sym, "STL"),
    }
}

/// One rule as written: the steps it stands for, its name, its body.
type Macro = (u64, String, String);

/// How many drawing components each rewritten symbol has after 0, 1, 2, …
/// steps, worked out level by level from the level before (not by
/// recursion: a translation may ask for any number of steps), and capped
/// just past [`MAX_COMPONENTS`] (a sum of capped counts is past the cap
/// exactly when the true sum is).
struct Sizes {
    /// The rewritten symbols (each a guarded occurrence's base), numbered.
    heads: HashMap<SymbolId, usize>,
    /// Per head: the components its successor writes itself, and the heads
    /// in it with how often each occurs.
    recipes: Vec<(u64, Vec<(usize, u64)>)>,
    /// The counts of the heads after 0, 1, … steps, kept up to
    /// [`MAX_NESTING`] steps (as many as the macros of a translation use).
    levels: Vec<Vec<u64>>,
    /// Whether the last level kept is the last there is: the level after
    /// it is the same, and so every one after.
    settled: bool,
}

/// Just past the most components STL expands: counts stop here.
const CAP: u64 = MAX_COMPONENTS + 1;

impl Sizes {
    fn new(sys: &System, rules: &Rules, comps: &HashMap<SymbolId, String>) -> Self {
        let base = |s: SymbolId| sys.symbols.info(s).guard.map_or(s, |g| g.base);
        let own = |s: SymbolId| comps.get(&s).map_or(0, |c| c.len() as u64);
        let heads: HashMap<SymbolId, usize> = rules
            .heads()
            .into_iter()
            .enumerate()
            .map(|(i, (s, _))| (s, i))
            .collect();
        let mut recipes = vec![(0, Vec::new()); heads.len()];
        let mut first = vec![0; heads.len()];
        for (&h, &i) in &heads {
            first[i] = own(h);
            let mut uses: HashMap<usize, u64> = HashMap::new();
            let mut written = 0u64;
            for &t in rules.successor(sys, h).unwrap_or_default() {
                match heads.get(&base(t)) {
                    Some(&j) => *uses.entry(j).or_default() += 1,
                    None => written = written.saturating_add(own(base(t))),
                }
            }
            let mut uses: Vec<(usize, u64)> = uses.into_iter().collect();
            uses.sort_unstable();
            recipes[i] = (written.min(CAP), uses);
        }
        Sizes {
            heads,
            recipes,
            levels: vec![first],
            settled: false,
        }
    }

    /// The counts one step after `counts`, into `next`.
    fn step(&self, counts: &[u64], next: &mut Vec<u64>) {
        next.clear();
        next.extend(self.recipes.iter().map(|(written, uses)| {
            uses.iter()
                .fold(*written, |sum, &(j, n)| {
                    sum.saturating_add(counts[j].saturating_mul(n))
                })
                .min(CAP)
        }));
    }

    /// The count of head `h` after `k` steps.
    fn count(&mut self, h: usize, k: u64) -> u64 {
        let mut next = Vec::new();
        while !self.settled && (self.levels.len() as u64) <= k.min(MAX_NESTING as u64) {
            let last = &self.levels[self.levels.len() - 1];
            self.step(last, &mut next);
            self.settled = next == *last;
            if !self.settled {
                self.levels.push(std::mem::take(&mut next));
            }
        }
        let last = &self.levels[self.levels.len() - 1];
        match self.levels.get(k as usize) {
            Some(level) => level[h],
            None if self.settled => last[h],
            // Past the levels kept: on from the last, without keeping them,
            // until the counts settle (growth reaches the cap; a translation
            // that asks for more steps than kept has one rewritten symbol,
            // whose count only grows).
            None => {
                let mut counts = last.clone();
                for _ in self.levels.len() as u64 - 1..k {
                    self.step(&counts, &mut next);
                    if next == counts {
                        break;
                    }
                    std::mem::swap(&mut counts, &mut next);
                }
                counts[h]
            }
        }
    }
}

/// The derived word as STL rules: each symbol's drawing components, and
/// the macros defined so far.
struct Expansion<'a> {
    sys: &'a System,
    rules: &'a Rules,
    comps: HashMap<SymbolId, String>,
    sizes: Sizes,
    names: Names,
    /// The stem of each symbol's macro names.
    stems: HashMap<SymbolId, String>,
    /// The macro of each symbol after k steps, and those still to write.
    defined: HashMap<(SymbolId, u64), String>,
    stack: Vec<(SymbolId, u64)>,
}

impl<'a> Expansion<'a> {
    /// The symbol a guarded occurrence stands for.
    fn base(&self, s: SymbolId) -> SymbolId {
        self.sys.symbols.info(s).guard.map_or(s, |g| g.base)
    }

    fn successor(&self, s: SymbolId) -> Option<&'a [SymbolId]> {
        self.rules.successor(self.sys, s)
    }

    /// The components `s` writes itself.
    fn comp(&self, s: SymbolId) -> Option<&String> {
        self.comps.get(&s).filter(|c| !c.is_empty())
    }

    /// The number of components of `s` after `k` steps (capped just past
    /// [`MAX_COMPONENTS`]).
    fn size(&mut self, s: SymbolId, k: u64) -> u64 {
        let b = self.base(s);
        match self.sizes.heads.get(&b) {
            Some(&h) => self.sizes.count(h, k),
            None => self.comps.get(&b).map_or(0, |c| c.len() as u64),
        }
    }

    /// The number of components of the axiom after `steps` steps (capped
    /// just past [`MAX_COMPONENTS`]).
    fn total(&mut self, steps: u64) -> u64 {
        let mut total: u64 = 0;
        for &s in &self.sys.axiom.0 {
            total = total.saturating_add(self.size(s, steps)).min(CAP);
        }
        total
    }

    /// Whether the axiom holds a symbol that is rewritten.
    fn rewrites_from_axiom(&self) -> bool {
        let axiom = &self.sys.axiom.0;
        axiom
            .iter()
            .any(|&s| self.successor(self.base(s)).is_some())
    }

    /// The symbol whose successor is the paper's self-resemblance count
    /// `[I n X]`: the only rewritten symbol, which draws, when its
    /// successor draws and has no guarded symbol.
    fn self_resembling(&self, steps: u64) -> Option<SymbolId> {
        let heads = self.rules.heads();
        let [(d, _)] = heads[..] else {
            return None;
        };
        let ok = self.comps.get(&d).map(String::as_str) == Some("F")
            && steps >= 1
            && self.successor(d).is_some_and(|w| {
                w.iter().all(|&t| self.sys.symbols.info(t).guard.is_none())
                    && w.iter().any(|t| self.comp(*t).is_some())
            });
        ok.then_some(d)
    }

    /// The one rule `[I steps X]` for `d`, and the seed.
    fn self_resemblance(&mut self, d: SymbolId, steps: u64) -> (Vec<Macro>, String) {
        let body = write_word(
            self.successor(d).unwrap_or_default(),
            |t| Some(self.comps.get(&t).cloned().unwrap_or_default()),
            |t| t.concat(),
        );
        let name = self
            .names
            .take([
                "Plant".to_string(),
                "Plant1".to_string(),
                "Plant2".to_string(),
            ])
            .unwrap_or_else(|| "Plant".into());
        let mut seed = Vec::new();
        for &s in &self.sys.axiom.0 {
            let s = self.base(s);
            if s == d {
                seed.push(name.clone());
            } else if let Some(c) = self.comp(s) {
                seed.push(c.clone());
            }
        }
        (
            vec![(steps, name, format!("[I {steps} {body}]"))],
            join(&seed),
        )
    }

    /// A macro for each symbol after each number of steps the axiom needs,
    /// and the seed.
    fn macros(&mut self, steps: u64) -> (Vec<Macro>, String) {
        let axiom = &self.sys.axiom.0;
        let seed = write_word(axiom, |s| self.token(s, steps), |t| join(&t));
        let mut made: Vec<Macro> = Vec::new();
        while let Some((s, k)) = self.stack.pop() {
            let succ = self.successor(s).unwrap_or_default();
            let body = write_word(succ, |t| self.token(t, k - 1), |t| join(&t));
            let name = self.token(s, k).unwrap_or_default();
            made.push((k, name, body));
        }
        made.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.cmp(&b.1)));
        (made, seed)
    }

    /// What `s` after `k` steps is written as: its components, or the
    /// macro for it (defined, to be written, when new); `None` for
    /// nothing.
    fn token(&mut self, s: SymbolId, k: u64) -> Option<String> {
        let s = self.base(s);
        if k == 0 || self.successor(s).is_none() {
            return self.comp(s).cloned();
        }
        if self.size(s, k) == 0 {
            return None;
        }
        if let Some(n) = self.defined.get(&(s, k)) {
            return Some(n.clone());
        }
        let stem = self.stem(s);
        let first = format!("{stem}{k}");
        let name = self
            .names
            .take(std::iter::once(first).chain(numbered(&format!("{stem}{k}_"), 1..1000)))
            .unwrap_or_default();
        self.defined.insert((s, k), name.clone());
        self.stack.push((s, k));
        Some(name)
    }

    /// The stem of `s`'s macro names: its name where that is an STL name
    /// that cannot be read as components, reserved on first use.
    fn stem(&mut self, s: SymbolId) -> String {
        if let Some(stem) = self.stems.get(&s) {
            return stem.clone();
        }
        let n = self.sys.symbols.name(s);
        let ok = n.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
            && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        let stem = if ok {
            n.to_string()
        } else {
            format!("S{}", s.0)
        };
        let stem = if stem
            .chars()
            .all(|c| matches!(c, 'F' | 'L' | 'R' | 'B' | 'I'))
        {
            format!("{stem}x")
        } else {
            stem
        };
        self.names.reserve(&stem);
        self.stems.insert(s, stem.clone());
        stem
    }
}

/// The file: the opening comment, the settings, the rules, the seed.
fn text(e: &mut Emitter<'_>, n: u64, rules: &Rules, out_rules: &[Macro], seed: &str) -> String {
    let sys = e.sys;
    let mut out = hash_comment(&opening(e));
    let _ = writeln!(
        out,
        "# {} derivation steps are written into the rules.",
        e.steps
    );
    // STL has no angle factor: the exact degrees, and the factor in a
    // comment when the degrees are not a short number.
    let degrees = crate::number::turn_fraction_degrees(n);
    if degrees.len() > 8 {
        let _ = writeln!(out, "ANGLE {degrees} # 360/{n}");
    } else {
        let _ = writeln!(out, "ANGLE {degrees}");
    }
    let _ = writeln!(out, "B = {} (0)", number(sys.settings.width));
    let _ = writeln!(out, "L = {} (0)", number(sys.settings.step));
    for (_, name, body) in out_rules {
        let _ = writeln!(out, "{name} = {body}");
    }
    out.push_str("SEED\n");
    if !seed.is_empty() {
        out.push_str(seed);
        out.push('\n');
    }
    out.push_str("ENDSEED\n");
    e.exact_axiom(seed);
    for (_, i) in rules.heads() {
        e.exact_production(i, "written into the rules, one per step");
    }
    out
}

/// STL tokens joined: components together, rule names spaced.
fn join(toks: &[String]) -> String {
    let comp = |t: &str| t.chars().all(|c| matches!(c, 'F' | 'L' | 'R' | '[' | ']'));
    let mut out = String::new();
    let mut prev_comp = true;
    for t in toks {
        let c = comp(t);
        let together =
            out.is_empty() || out.ends_with('[') || t.starts_with(']') || (c && prev_comp);
        if !together {
            out.push(' ');
        }
        out.push_str(t);
        prev_comp = c;
    }
    out
}
