//! The STL emitter: an STL system (its lowered structure) written out as a
//! Branch-Expansion Description, the paper's BED text files.
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
