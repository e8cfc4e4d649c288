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

use crate::ir::{BranchEntry, BranchTerm, SeedItem, Shape, Structure, SymbolId, System, Word};
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
    let _ = writeln!(out, "ANGLE {}", sys.settings.angle);
    let _ = writeln!(out, "B = {} ({})", st.broadness.0, st.broadness.1);
    let _ = writeln!(out, "L = {} ({})", st.length.0, st.length.1);
    let _ = writeln!(
        out,
        "GROWTH {}",
        match st.growth {
            crate::ir::Growth::BreadthFirst => "BFS",
            crate::ir::Growth::DepthFirst => "DFS",
        }
    );
    let _ = writeln!(out, "LEVELS {}", st.levels);
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
    if !st.layout.is_empty() {
        out.push_str("LAYOUT\n");
        for s in &st.layout {
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
    match crate::stdlib::delphi_colours()
        .iter()
        .find(|(_, v)| *v == c)
    {
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
const MAX_COMPONENTS: u64 = crate::front::stl::lower::MAX_EXPANSION as u64;

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
    use super::{heaviest, multiples, number, occurring, single_symbol_rules, turns};
    use super::{Kind, Turns};
    use crate::ir::{Axis, TurtleOp};
    use std::collections::HashMap;

    let sys = e.sys;
    let rules = single_symbol_rules(e, "STL");
    let occ = occurring(sys);
    let plain = |s: SymbolId| sys.symbols.info(s).guard.is_none();

    // The turning angle.
    let mut by_symbol = Vec::new();
    for &s in occ.iter().filter(|&&s| plain(s)) {
        let Some(op) = sys.op(s) else { continue };
        let t = match turns(sys, op) {
            Some(Turns::Fixed(t)) => t,
            Some(Turns::Random(t)) => {
                e.problem(
                    Kind::Interval,
                    e.symbol_span(s),
                    format!(
                        "the interval angle of `{}`: STL turns by a fixed angle",
                        e.name(s)
                    ),
                    "the middle of the interval is used",
                );
                t
            }
            None => continue,
        };
        for (axis, a) in t {
            if axis == Axis::Up {
                by_symbol.push((s, a.abs()));
            } else {
                e.problem(
                    Kind::ThreeD,
                    e.symbol_span(s),
                    format!("`{}` rotates out of the plane: STL draws in 2D", e.name(s)),
                    "the rotation out of the plane is dropped",
                );
            }
        }
    }
    let n = super::angle_factor(e, &by_symbol, "STL");

    // Components of each symbol.
    let distinct_colours = {
        let mut c = sys.colours.clone();
        c.dedup();
        c.len()
    };
    let mut comps: HashMap<SymbolId, String> = HashMap::new();
    for &s in occ.iter().filter(|&&s| plain(s)) {
        let name = e.name(s).to_string();
        let span = e.symbol_span(s);
        let text = match sys.op(s) {
            None => String::new(),
            Some(TurtleOp::Forward { draw: true }) => "F".into(),
            Some(TurtleOp::Forward { draw: false }) => {
                e.problem(
                    Kind::Move,
                    span,
                    format!("`{name}` moves without drawing: every STL stem is drawn"),
                    "the move is drawn as a stem",
                );
                "F".into()
            }
            Some(
                op @ (TurtleOp::Rotate { .. } | TurtleOp::Frenet { .. } | TurtleOp::TurnAround),
            ) => {
                let t = match turns(sys, op) {
                    Some(Turns::Fixed(t)) | Some(Turns::Random(t)) => t,
                    None => Vec::new(),
                };
                let mut out = String::new();
                for (axis, a) in t {
                    if axis != Axis::Up {
                        continue;
                    }
                    let k = multiples(a, n);
                    let c = if k > 0 { 'R' } else { 'L' };
                    out.push_str(&super::repeated(e, s, c, k));
                }
                out
            }
            Some(TurtleOp::Push) => "[".into(),
            Some(TurtleOp::Pop) => "]".into(),
            Some(TurtleOp::NextColour) | Some(TurtleOp::PreviousColour) => {
                if sys.colours.is_empty() || distinct_colours > 1 {
                    e.problem(
                        Kind::Attribute,
                        span,
                        format!("the colour symbol `{name}`: STL stems have no colours"),
                        "it is dropped",
                    );
                }
                String::new()
            }
            Some(TurtleOp::DecrementWidth) => {
                e.problem(
                    Kind::Attribute,
                    span,
                    format!("`{name}` makes lines thinner: STL sets widths per level only"),
                    "it is dropped",
                );
                String::new()
            }
            Some(TurtleOp::PolygonBegin) | Some(TurtleOp::PolygonEnd) => {
                e.problem(
                    Kind::Attribute,
                    span,
                    format!("the polygon symbol `{name}`: STL has no filled polygons"),
                    "the polygon is dropped; its edges are drawn as stems",
                );
                String::new()
            }
            Some(TurtleOp::SwapTurns) => {
                e.problem(
                    Kind::Swap,
                    span,
                    format!("`{name}` exchanges left and right: STL has no such component"),
                    "it is dropped",
                );
                String::new()
            }
            Some(TurtleOp::ScaleLength(x)) => {
                if x != 1.0 {
                    e.problem(
                        Kind::Length,
                        span,
                        format!(
                            "the length factor `{name}`: STL stem lengths change per level only"
                        ),
                        "the factor is dropped",
                    );
                }
                String::new()
            }
            Some(TurtleOp::Stem { .. }) => String::new(),
            Some(
                TurtleOp::TurnUnswapped(_)
                | TurtleOp::RotateReal(_)
                | TurtleOp::ForwardReal { .. }
                | TurtleOp::SetColour(_)
                | TurtleOp::ShiftColour { .. },
            ) => super::fractint_only(e, &name, span, "STL"),
            // cpfg's own turtle commands: parametric systems are refused
            // before any emitter runs (see `translate`).
            Some(_) => String::new(),
        };
        comps.insert(s, text);
    }
    // A guarded occurrence is its base.
    let base = |s: SymbolId| sys.symbols.info(s).guard.map_or(s, |g| g.base);
    for &s in occ.iter().filter(|&&s| !plain(s)) {
        if let Some(g) = sys.symbols.info(s).guard {
            e.problem(
                Kind::Guard,
                e.symbol_span(s),
                format!(
                    "`{}` expands with probability {}: STL has no chance",
                    e.name(s),
                    number(g.probability)
                ),
                format!("`{}` is always expanded", e.name(g.base)),
            );
        }
    }
    if sys.settings.scale != 100.0 {
        e.problem(
            Kind::Attribute,
            None,
            format!(
                "the scale factor {}: STL pictures fill the frame",
                number(sys.settings.scale)
            ),
            "the figure fills the picture",
        );
    }

    let steps = e.steps;
    let successor = |s: SymbolId| -> Option<&[SymbolId]> {
        let i = rules.get(s)?;
        let p = &sys.productions[i];
        Some(&p.alternatives[heaviest(p)].successor.0)
    };
    // Sizes (components) of each symbol after k steps, bottom-up.
    let mut size: HashMap<(SymbolId, u64), u64> = HashMap::new();
    let comp_len = |s: SymbolId| comps.get(&base(s)).map_or(0, |c| c.len() as u64);
    fn size_of(
        s: SymbolId,
        k: u64,
        size: &mut HashMap<(SymbolId, u64), u64>,
        succ: &dyn Fn(SymbolId) -> Option<Vec<SymbolId>>,
        comp_len: &dyn Fn(SymbolId) -> u64,
    ) -> u64 {
        if let Some(&v) = size.get(&(s, k)) {
            return v;
        }
        let v = match (k, succ(s)) {
            (0, _) | (_, None) => comp_len(s),
            (_, Some(w)) => {
                let mut total: u64 = 0;
                for t in w {
                    total = total.saturating_add(size_of(t, k - 1, size, succ, comp_len));
                }
                total
            }
        };
        size.insert((s, k), v);
        v
    }
    let succ_of = |s: SymbolId| successor(base(s)).map(|w| w.to_vec());
    let mut total: u64 = 0;
    for &s in &sys.axiom.0 {
        total = total.saturating_add(size_of(s, steps, &mut size, &succ_of, &comp_len));
    }
    if total > MAX_COMPONENTS {
        e.problem(
            Kind::TooLarge,
            None,
            format!(
                "after {steps} steps the word has {total} drawing components, more than STL expands ({MAX_COMPONENTS})"
            ),
            "translate with fewer steps (`-n`)",
        );
    }

    // Rule names.
    let reserved: Vec<&str> = crate::front::stl::parser::RESERVED.to_vec();
    let mut names = super::Names::new(&reserved);
    let mut base_name: HashMap<SymbolId, String> = HashMap::new();
    let mut rule_name = |s: SymbolId, names: &mut super::Names| -> String {
        base_name
            .entry(s)
            .or_insert_with(|| {
                let n = sys.symbols.name(s);
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
                names.reserve(&stem);
                stem
            })
            .clone()
    };

    let mut out_rules: Vec<(u64, String, String)> = Vec::new();
    let shortcut = {
        let draw: Vec<SymbolId> = rules.heads().iter().map(|h| h.0).collect();
        draw.len() == 1
            && comps.get(&draw[0]).map(String::as_str) == Some("F")
            && steps >= 1
            && successor(draw[0]).is_some_and(|w| {
                w.iter().all(|&t| sys.symbols.info(t).guard.is_none())
                    && w.iter()
                        .any(|t| comps.get(t).is_some_and(|c| !c.is_empty()))
            })
    };
    let mut seed = Vec::new();
    if shortcut {
        let d = rules.heads()[0].0;
        let body: String = successor(d)
            .unwrap_or_default()
            .iter()
            .map(|t| comps.get(t).cloned().unwrap_or_default())
            .collect();
        let name = names
            .take([
                "Plant".to_string(),
                "Plant1".to_string(),
                "Plant2".to_string(),
            ])
            .unwrap_or_else(|| "Plant".into());
        out_rules.push((steps, name.clone(), format!("[I {steps} {body}]")));
        for &s in &sys.axiom.0 {
            let s = base(s);
            if s == d {
                seed.push(name.clone());
            } else if let Some(c) = comps.get(&s).filter(|c| !c.is_empty()) {
                seed.push(c.clone());
            }
        }
    } else {
        // tokens of s after k steps; defines the rules it needs.
        let mut defined: HashMap<(SymbolId, u64), String> = HashMap::new();
        let mut stack: Vec<(SymbolId, u64)> = Vec::new();
        let mut token = |s: SymbolId,
                         k: u64,
                         stack: &mut Vec<(SymbolId, u64)>,
                         names: &mut super::Names,
                         size: &mut HashMap<(SymbolId, u64), u64>|
         -> Option<String> {
            let s = base(s);
            if k == 0 || successor(s).is_none() {
                return comps.get(&s).filter(|c| !c.is_empty()).cloned();
            }
            if size_of(s, k, size, &succ_of, &comp_len) == 0 {
                return None;
            }
            if let Some(n) = defined.get(&(s, k)) {
                return Some(n.clone());
            }
            let stem = rule_name(s, names);
            let name = names
                .take(
                    (0..)
                        .map(|i| {
                            if i == 0 {
                                format!("{stem}{k}")
                            } else {
                                format!("{stem}{k}_{i}")
                            }
                        })
                        .take(1000),
                )
                .unwrap_or_default();
            defined.insert((s, k), name.clone());
            stack.push((s, k));
            Some(name)
        };
        if total <= MAX_COMPONENTS {
            for &s in &sys.axiom.0 {
                if let Some(t) = token(s, steps, &mut stack, &mut names, &mut size) {
                    seed.push(t);
                }
            }
            let mut made: Vec<(u64, String, String)> = Vec::new();
            while let Some((s, k)) = stack.pop() {
                let mut body = Vec::new();
                for &t in successor(s).unwrap_or_default() {
                    if let Some(tok) = token(t, k - 1, &mut stack, &mut names, &mut size) {
                        body.push(tok);
                    }
                }
                let name = token(s, k, &mut stack, &mut names, &mut size).unwrap_or_default();
                made.push((k, name, join(&body)));
            }
            made.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.cmp(&b.1)));
            out_rules = made;
        }
    }

    let mut out = String::new();
    out.push_str(&format!("# {}\n", super::banner(e)));
    if let Some(c) = super::file_comment(&e.origin.comments, e.source) {
        out.push_str("#\n");
        for l in c {
            out.push_str(&format!(
                "#{}\n",
                if l.is_empty() {
                    String::new()
                } else {
                    format!(" {l}")
                }
            ));
        }
    }
    let _ = writeln!(
        out,
        "# {steps} derivation steps are written into the rules."
    );
    let _ = writeln!(out, "ANGLE {}", number(360.0 / n as f64));
    let _ = writeln!(out, "B = {} (0)", number(sys.settings.width));
    let _ = writeln!(out, "L = {} (0)", number(sys.settings.step));
    for (_, name, body) in &out_rules {
        let _ = writeln!(out, "{name} = {body}");
    }
    let seed_text = join(&seed);
    out.push_str("SEED\n");
    if !seed_text.is_empty() {
        out.push_str(&seed_text);
        out.push('\n');
    }
    out.push_str("ENDSEED\n");
    e.exact("the axiom", e.spans.axiom.first().cloned(), &seed_text);
    for (i, _) in sys.productions.iter().enumerate() {
        let text = e.production_text(i);
        if rules.heads().iter().any(|h| h.1 == i) {
            e.exact(
                format!("production `{text}`"),
                e.production_span(i),
                "written into the rules, one per step",
            );
        }
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
