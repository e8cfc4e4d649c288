//! The LinF emitter: a system written as LinF blocks in the paper's order
//! (`lines`, `blanks`, `angles`, `axiom`, `rules`, `colors`), with
//! graftal's `#: steps` and `#: view` directives first.
//!
//! * Names: a source name that is a LinF identifier stays; a pfg character
//!   that is not becomes `_c` (digits) or `_xHH` (its code), which the pfg
//!   emitter reads back, so pfg -> LinF -> pfg gives the same symbols.
//! * Rotations: a LinF source's named (torsion, curvature) pairs are kept.
//!   Turns of pfg and STL become pairs: a turn about U by a is (0, −a), a
//!   roll about H is (−a, 0), a pitch about L is a quarter roll, a turn and
//!   the roll back: two pairs. The pair of the first turn is the default
//!   rotation, declared so that pfg's `+` is still written `+`.
//! * Every name must be declared: drawing symbols in `lines`, moving ones
//!   in `blanks`, rewritten ones as rule heads, and a symbol that is none of
//!   these by the rule `x = x`, which keeps it as it is.
//! * A step length other than 1 becomes a length factor at the start of
//!   the axiom.

use super::walk::{
    distinct_colours, fractint_only, no_polygons, no_scale, no_stems, no_widths, spell_each,
    write_word, Does, Sym, Symbols,
};
use super::{
    hash_comment, hash_line, number, numbered, opening, single_symbol_rules, Attached, Emitter,
    Kind, Names, Rules,
};
use crate::ir::{Angle, Axis, Rgb, SymbolId, System, TurtleOp};
use crate::number::{radians, radians_interval};
use std::collections::HashMap;
use std::f64::consts::PI;
use std::fmt::Write;

/// The Linf emitter in the registry.
pub struct Linf;

impl super::Back for Linf {
    fn name(&self) -> &'static str {
        "linf"
    }
    fn extension(&self) -> &'static str {
        "linf"
    }
    fn write(&self, e: &mut super::Emitter<'_>) -> String {
        write(e)
    }
}

const RESERVED: &[&str] = &[
    "lines", "blanks", "angles", "axiom", "rules", "colors", "pi",
];

fn is_ident(s: &str) -> bool {
    let mut cs = s.chars();
    cs.next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && cs.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The LinF names a source name would like to have, best first.
fn wishes(name: &str) -> Vec<String> {
    if is_ident(name) {
        return vec![name.to_string()];
    }
    let mut cs = name.chars();
    if let (Some(c), None) = (cs.next(), cs.next()) {
        return vec![if c.is_ascii_alphanumeric() {
            format!("_{c}")
        } else {
            format!("_x{:02X}", c as u32)
        }];
    }
    let clean: String = name
        .chars()
        .filter(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    if clean.is_empty() {
        Vec::new()
    } else if is_ident(&clean) {
        vec![clean]
    } else {
        vec![format!("_{clean}")]
    }
}

/// A declared rotation.
struct Decl {
    name: String,
    torsion: Angle,
    curvature: Angle,
}

fn same(a: Angle, b: Angle) -> bool {
    match (a, b) {
        (Angle::Uniform { lo: l1, hi: h1 }, Angle::Uniform { lo: l2, hi: h2 }) => {
            l1 == l2 && h1 == h2
        }
        (Angle::Radians(x), Angle::Radians(y)) => x == y,
        _ => false,
    }
}

fn neg(a: Angle) -> Angle {
    match a {
        Angle::Radians(x) => Angle::Radians(-x),
        Angle::Delta(k) => Angle::Delta(-k),
        Angle::Uniform { lo, hi } => Angle::Uniform { lo: -hi, hi: -lo },
    }
}

/// An angle as a LinF expression that evaluates to the same value.
fn expr(a: Angle) -> String {
    match a {
        Angle::Uniform { lo, hi } => radians_interval(lo, hi),
        Angle::Radians(x) => radians(x),
        Angle::Delta(_) => "0".into(),
    }
}

struct Rotations {
    decls: Vec<Decl>,
}

impl Rotations {
    /// The token for applying the pair (t, c): `+name` or `-name` of a
    /// declared pair, declaring it (named by `wish`) when new.
    fn token(&mut self, names: &mut Names, t: Angle, c: Angle, wish: &[&str]) -> String {
        for d in &self.decls {
            if same(d.torsion, t) && same(d.curvature, c) {
                return format!("+{}", d.name);
            }
            if same(d.torsion, neg(t)) && same(d.curvature, neg(c)) {
                return format!("-{}", d.name);
            }
        }
        let name = if self.decls.iter().all(|d| !d.name.is_empty()) && wish.contains(&"") {
            String::new()
        } else {
            let w: Vec<String> = wish
                .iter()
                .filter(|w| !w.is_empty())
                .map(|w| w.to_string())
                .collect();
            let base = w.first().cloned().unwrap_or_else(|| "a".into());
            names
                .take(w.into_iter().chain(numbered(&base, 2..1002)))
                .unwrap_or_default()
        };
        self.decls.push(Decl {
            name: name.clone(),
            torsion: t,
            curvature: c,
        });
        format!("+{name}")
    }
}

/// The symbols of a system as LinF spells them, and what they declare.
struct Spellings {
    names: Names,
    spell: HashMap<SymbolId, String>,
    /// The `lines` and `blanks` blocks.
    lines: Vec<String>,
    blanks: Vec<String>,
    rot: Rotations,
    /// The source's own rotations (LinF): index -> declaration.
    own: HashMap<u32, usize>,
    /// Whether a symbol steps through the colours.
    uses_colour: bool,
}

pub fn write(e: &mut Emitter<'_>) -> String {
    let sys = e.sys;
    let rules = rules(e);
    let syms = Symbols::of(sys);
    let mut sp = Spellings {
        names: Names::new(RESERVED),
        spell: HashMap::new(),
        lines: Vec::new(),
        blanks: Vec::new(),
        rot: Rotations { decls: Vec::new() },
        own: HashMap::new(),
        uses_colour: false,
    };
    declare_names(e, &syms, &mut sp);
    own_rotations(e, &syms, &mut sp);
    operations(e, &syms, &mut sp);
    // Guarded occurrences.
    for &(s, g) in &syms.guarded {
        let base = sp.spell.get(&g.base).cloned().unwrap_or_default();
        sp.spell
            .insert(s, format!("{}?{base}", number(g.probability)));
    }
    no_scale(e, "LinF pictures always fill the frame");
    let words = Words::of(&sp);
    let rule_lines = rule_lines(e, &rules, &syms, &sp, &words);
    let mut axiom = words.word(&sys.axiom.0);
    if sys.settings.step != 1.0 {
        let f = format!("{}@", number(sys.settings.step));
        axiom = if axiom.is_empty() {
            f
        } else {
            format!("{f} {axiom}")
        };
    }
    text(e, &sp, &axiom, &rule_lines)
}

/// The rules: LinF rewrites names, not turns, brackets or other reserved
/// symbols.
fn rules(e: &mut Emitter<'_>) -> Rules {
    let sys = e.sys;
    let mut rules = single_symbol_rules(e, "LinF");
    for (s, i) in rules.heads() {
        if !matches!(sys.op(s), None | Some(TurtleOp::Forward { .. })) {
            let text = e.production_text(i);
            e.problem(
                Kind::Rule,
                e.production_span(i),
                format!(
                    "the production `{text}` rewrites `{}`, which LinF cannot rewrite",
                    e.name(s)
                ),
                "the production is dropped",
            );
            rules.remove(s);
        }
    }
    rules
}

/// Names the symbols LinF declares by name: lines, blanks and the
/// symbols that do nothing (rule heads).
fn declare_names(e: &mut Emitter<'_>, syms: &Symbols, sp: &mut Spellings) {
    for &s in &syms.plain {
        let op = e.sys.op(s);
        if !matches!(op, None | Some(TurtleOp::Forward { .. })) {
            continue;
        }
        let name = e.name(s).to_string();
        let fallback = numbered("s", 1..100_001);
        let Some(n) = sp.names.take(wishes(&name).into_iter().chain(fallback)) else {
            continue;
        };
        e.rename(&name, &n);
        match op {
            Some(TurtleOp::Forward { draw: true }) => sp.lines.push(n.clone()),
            Some(TurtleOp::Forward { draw: false }) => sp.blanks.push(n.clone()),
            _ => {}
        }
        sp.spell.insert(s, n);
    }
}

/// Declares the rotations of a LinF source first, in their order.
fn own_rotations(e: &mut Emitter<'_>, syms: &Symbols, sp: &mut Spellings) {
    let sys = e.sys;
    for &s in &syms.plain {
        if let Some(TurtleOp::Frenet { rotation, .. }) = sys.op(s) {
            sp.own.entry(rotation.0).or_insert(0);
        }
    }
    let mut own_ids: Vec<u32> = sp.own.keys().copied().collect();
    own_ids.sort();
    for id in own_ids {
        let r = &sys.rotations[id as usize];
        let name = if r.name.is_empty() {
            String::new()
        } else {
            sp.names
                .take(
                    wishes(&r.name)
                        .into_iter()
                        .chain(numbered(&r.name, 2..1002)),
                )
                .unwrap_or_default()
        };
        if !r.name.is_empty() {
            e.rename(&r.name, &name);
        }
        sp.own.insert(id, sp.rot.decls.len());
        sp.rot.decls.push(Decl {
            name,
            torsion: fixed(sys, r.torsion),
            curvature: fixed(sys, r.curvature),
        });
    }
}

/// `a` in radians where it is a multiple of the system's angle.
fn fixed(sys: &System, a: Angle) -> Angle {
    match a {
        Angle::Delta(k) => Angle::Radians(k * sys.settings.delta),
        other => other,
    }
}

/// Spells the symbols that do something besides moving: turns first
/// (positive first, so that the declared pairs are the positive ones),
/// then everything else.
fn operations(e: &mut Emitter<'_>, syms: &Symbols, sp: &mut Spellings) {
    let sys = e.sys;
    let mut order = syms.unspelled(&sp.spell);
    order.sort_by_key(|&s| match sys.op(s) {
        Some(TurtleOp::Rotate { angle, .. }) => {
            if super::radians(sys, angle).is_some_and(|a| a < 0.0) {
                1
            } else {
                0
            }
        }
        _ => 2,
    });
    for (sym, text) in spell_each(e, order, |e, sym| operation(e, sym, sp)) {
        e.rename(&sym.name, &text);
        sp.spell.insert(sym.id, text);
    }
}

/// What LinF writes for a symbol that does something besides moving
/// (`None`: it is spelled elsewhere, or not at all).
fn operation(e: &mut Emitter<'_>, sym: &Sym, sp: &mut Spellings) -> Option<String> {
    let r = Angle::Radians;
    Some(match sym.does {
        Does::Nothing | Does::Forward { .. } | Does::Cpfg => return None,
        Does::Turn(TurtleOp::Frenet { rotation, negate }) => {
            let d = &sp.rot.decls[sp.own[&rotation.0]];
            format!("{}{}", if negate { '-' } else { '+' }, d.name)
        }
        Does::Turn(TurtleOp::Rotate { axis, angle }) => sp.rotate(fixed(e.sys, angle), axis),
        // The half turn.
        Does::Turn(_) => sp.rot.token(&mut sp.names, r(0.0), r(PI), &["u"]),
        Does::Push => "[".into(),
        Does::Pop => "]".into(),
        Does::Colour { next } => {
            sp.uses_colour = true;
            if next { "{" } else { "}" }.into()
        }
        Does::Swap => "!".into(),
        Does::Length(x) => format!("{}@", number(x)),
        Does::Polygon { .. } => no_polygons(e, sym, "LinF", "as they move"),
        Does::Thinner => no_widths(e, sym, "LinF has no line widths"),
        Does::Stem => no_stems(e, sym, "LinF scales lengths by factors"),
        Does::Fractint => fractint_only(e, sym, "LinF"),
    })
}

impl Spellings {
    /// The tokens of a rotation by `a` about `axis`: a turn about U by a
    /// is (0, −a), a roll about H is (−a, 0), a pitch about L is a quarter
    /// roll, a turn and the roll back.
    fn rotate(&mut self, a: Angle, axis: Axis) -> String {
        let r = Angle::Radians;
        let (mag, negative) = match a {
            Angle::Radians(x) => (Angle::Radians(x.abs()), x < 0.0),
            other => (other, false),
        };
        let (rot, names) = (&mut self.rot, &mut self.names);
        let tok = match axis {
            Axis::Up => rot.token(names, r(0.0), neg(mag), &["", "c"]),
            Axis::Heading => rot.token(names, neg(mag), r(0.0), &["r"]),
            Axis::Left => {
                let first = rot.token(names, r(-PI / 2.0), a, &["p"]);
                let back = rot.token(names, r(PI / 2.0), r(0.0), &["h"]);
                format!("{first} {back}")
            }
        };
        if axis != Axis::Left && negative {
            flip(&tok)
        } else {
            tok
        }
    }
}

/// How words are written: each symbol's tokens, joined so that LinF reads
/// them back as the same tokens.
struct Words<'s> {
    spell: &'s HashMap<SymbolId, String>,
    all_short: bool,
    angle_names: Vec<&'s str>,
}

impl<'s> Words<'s> {
    fn of(sp: &'s Spellings) -> Self {
        let decls = &sp.rot.decls;
        let all_short = sp
            .spell
            .values()
            .chain(decls.iter().map(|d| &d.name))
            .all(|n| !is_ident(n) || n.chars().count() <= 1)
            && decls.iter().all(|d| d.name.chars().count() <= 1);
        Words {
            spell: &sp.spell,
            all_short,
            angle_names: decls.iter().map(|d| d.name.as_str()).collect(),
        }
    }

    fn word(&self, w: &[SymbolId]) -> String {
        write_word(
            w,
            |s| self.spell.get(&s).map(String::as_str),
            |t| {
                let toks: Vec<&str> = t.into_iter().flat_map(str::split_whitespace).collect();
                join(&toks, self.all_short, &self.angle_names)
            },
        )
    }
}

/// The lines of the `rules` block: rewritten symbols, then the identity
/// rule for plain symbols nothing rewrites.
fn rule_lines(
    e: &mut Emitter<'_>,
    rules: &Rules,
    syms: &Symbols,
    sp: &Spellings,
    words: &Words<'_>,
) -> Vec<String> {
    let sys = e.sys;
    let mut out = Vec::new();
    for (s, i) in rules.heads() {
        let succ = rules.successor(sys, s).unwrap_or_default();
        let head = sp.spell.get(&s).cloned().unwrap_or_default();
        let mut line = format!("  {head} = {}", words.word(succ));
        match e.attached_to(e.production_span(i).as_ref()) {
            Some(Attached::After(c)) => {
                let _ = write!(line, "  # {c}");
            }
            Some(Attached::Above(c)) => {
                for l in c {
                    out.push(format!("  {}", hash_line(&l)));
                }
            }
            None => {}
        }
        e.exact_production(i, line.trim());
        out.push(line.trim_end().to_string());
    }
    for &s in &syms.plain {
        if sys.op(s).is_none() && !rules.contains(s) {
            if let Some(n) = sp.spell.get(&s) {
                out.push(format!("  {n} = {n}"));
            }
        }
    }
    out
}

/// The file: the opening comment, the directives, the blocks.
fn text(e: &mut Emitter<'_>, sp: &Spellings, axiom: &str, rule_lines: &[String]) -> String {
    let sys = e.sys;
    let mut out = hash_comment(&opening(e));
    let _ = writeln!(out, "#: steps {}", e.steps);
    if let Some((az, el)) = sys.settings.view {
        let _ = writeln!(out, "#: view {},{}", super::degrees(az), super::degrees(el));
    }
    // In name order: symbol ids follow the order a reader met the names,
    // which says nothing of the system (a `.gft` file may meet them in
    // another order), so the declarations do not follow them.
    for (directive, names) in [("lines", &sp.lines), ("blanks", &sp.blanks)] {
        if !names.is_empty() {
            let mut names: Vec<&str> = names.iter().map(String::as_str).collect();
            names.sort_unstable();
            let _ = writeln!(out, "{directive} {}", names.join(" "));
        }
    }
    let decls = &sp.rot.decls;
    if !decls.is_empty() {
        let decl = |d: &Decl| {
            let pair = format!("({}, {})", expr(d.torsion), expr(d.curvature));
            if d.name.is_empty() {
                pair
            } else {
                format!("{} = {pair}", d.name)
            }
        };
        if decls.len() == 1 {
            let _ = writeln!(out, "angles {}", decl(&decls[0]));
        } else {
            out.push_str("angles\n");
            for d in decls {
                let _ = writeln!(out, "  {}", decl(d));
            }
        }
    }
    let _ = writeln!(out, "axiom {axiom}");
    e.exact_axiom(&format!("axiom {axiom}"));
    if !rule_lines.is_empty() {
        out.push_str("rules\n");
        for l in rule_lines {
            out.push_str(l);
            out.push('\n');
        }
    }
    out.push_str(&colors(sys, sp.uses_colour));
    out
}

/// The `colors` block, when colours change.
fn colors(sys: &System, uses_colour: bool) -> String {
    let mut out = String::new();
    let colours: Vec<Rgb> = if !sys.colours.is_empty() {
        sys.colours.clone()
    } else if uses_colour {
        // pfg's palette wraps around; LinF stays on the last colour. The
        // palette repeated eight times covers 63 colour steps.
        let p = crate::ir::colours::DEFAULT_PALETTE;
        (0..8).flat_map(|_| p.iter().copied()).collect()
    } else {
        Vec::new()
    };
    if colours.is_empty() || !(uses_colour || distinct_colours(sys) > 1 || sys.colours.len() > 1) {
        return out;
    }
    if sys.colours.is_empty() {
        out.push_str("# pfg's palette, eight times: pfg starts again after the eighth colour, LinF stays on the last\n");
    }
    out.push_str("colors");
    for (i, c) in colours.iter().enumerate() {
        if i > 0 && i % 8 == 0 {
            out.push_str("\n      ");
        }
        let _ = write!(out, " ({},{},{})", c.0, c.1, c.2);
    }
    out.push('\n');
    out
}

/// `+name` <-> `-name`.
fn flip(tok: &str) -> String {
    match tok.strip_prefix('+') {
        Some(rest) => format!("-{rest}"),
        None => match tok.strip_prefix('-') {
            Some(rest) => format!("+{rest}"),
            None => tok.to_string(),
        },
    }
}

/// Tokens joined so that LinF reads them back as the same tokens.
fn join(toks: &[&str], all_short: bool, angles: &[&str]) -> String {
    let name = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut out = String::new();
    let mut prev: Option<char> = None;
    for t in toks {
        let Some(first) = t.chars().next() else {
            continue;
        };
        if let Some(p) = prev {
            let number = first.is_ascii_digit() || first == '.';
            let sign = |c: char| c == '+' || c == '-';
            // After a bare sign, a name is read as an angle name when one
            // is a prefix of it.
            let angle_prefix = angles.iter().any(|a| !a.is_empty() && t.starts_with(a));
            let space = (name(p) && (number || (name(first) && !all_short)))
                || (sign(p) && sign(first) && !t.chars().all(sign))
                || (sign(p) && (number || (name(first) && angle_prefix)))
                || (p == '@' && name(first));
            if space {
                out.push(' ');
            }
        }
        out.push_str(t);
        prev = t.chars().last();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_are_joined_so_that_they_split_back() {
        assert_eq!(join(&["F", "+", "F", "-", "-", "F"], true, &[""]), "F+F--F");
        assert_eq!(join(&["f", "0.5@", "0.5?j"], true, &[]), "f 0.5@ 0.5?j");
        assert_eq!(join(&["apex", "+r", "leaf"], false, &["r"]), "apex+r leaf");
        assert_eq!(join(&["+", "-r"], true, &["r"]), "+ -r");
        assert_eq!(
            join(&["+", "Plant", "+", "roll"], false, &["", "r"]),
            "+Plant+ roll"
        );
        assert_eq!(join(&["0.5@", "Plant"], false, &[]), "0.5@ Plant");
    }
}
