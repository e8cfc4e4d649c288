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

use super::{
    attached, banner, file_comment, heaviest, number, occurring, single_symbol_rules, Attached,
    Emitter, Kind, Names,
};
use crate::ir::{Angle, Axis, Rgb, SymbolId, TurtleOp};
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
        Angle::Uniform { lo, hi } => format!("[{} {}]", radians(lo), radians(hi)),
        Angle::Radians(x) => radians(x),
        Angle::Delta(_) => "0".into(),
    }
}

fn radians(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let sign = if x < 0.0 { "-" } else { "" };
    let v = x.abs();
    // k*pi/d for small d.
    for d in 1..=360u32 {
        let k = v * d as f64 / PI;
        let kr = k.round();
        if kr >= 1.0 && (k - kr).abs() < 1e-12 && gcd(kr as u64, d as u64) == 1 {
            let num = if kr == 1.0 {
                "pi".to_string()
            } else {
                format!("{}*pi", kr as u64)
            };
            return if d == 1 {
                format!("{sign}{num}")
            } else {
                format!("{sign}{num}/{d}")
            };
        }
    }
    // x*pi with a short x.
    let k = v / PI;
    for digits in 1..=6 {
        let s = format!("{k:.digits$}");
        if let Ok(r) = s.parse::<f64>() {
            if (r * PI - v).abs() < 1e-15 * v.max(1.0) {
                return format!("{sign}{}*pi", s.trim_end_matches('0').trim_end_matches('.'));
            }
        }
    }
    format!("{sign}{}", number(v))
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
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
                .take(
                    w.into_iter()
                        .chain((2..).map(|i| format!("{base}{i}")).take(1000)),
                )
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

pub fn write(e: &mut Emitter<'_>) -> String {
    let sys = e.sys;
    let mut rules = single_symbol_rules(e, "LinF");
    // LinF rewrites names: not turns, brackets or other reserved symbols.
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
    let occ = occurring(sys);
    let plain = |s: SymbolId| sys.symbols.info(s).guard.is_none();
    let mut names = Names::new(RESERVED);
    let mut spell: HashMap<SymbolId, String> = HashMap::new();

    // Names of lines, blanks and rule heads.
    let mut lines_block = Vec::new();
    let mut blanks_block = Vec::new();
    for &s in occ.iter().filter(|&&s| plain(s)) {
        let op = sys.op(s);
        if !matches!(op, None | Some(TurtleOp::Forward { .. })) {
            continue;
        }
        let name = e.name(s).to_string();
        let fallback = (1..).map(|i| format!("s{i}")).take(100_000);
        let Some(n) = names.take(wishes(&name).into_iter().chain(fallback)) else {
            continue;
        };
        e.rename(&name, &n);
        match op {
            Some(TurtleOp::Forward { draw: true }) => lines_block.push(n.clone()),
            Some(TurtleOp::Forward { draw: false }) => blanks_block.push(n.clone()),
            _ => {}
        }
        spell.insert(s, n);
    }

    // Rotations: the source's own first (LinF), in their order.
    let mut rot = Rotations { decls: Vec::new() };
    let mut own: HashMap<u32, usize> = HashMap::new();
    for &s in occ.iter().filter(|&&s| plain(s)) {
        if let Some(TurtleOp::Frenet { rotation, .. }) = sys.op(s) {
            own.entry(rotation.0).or_insert(0);
        }
    }
    let mut own_ids: Vec<u32> = own.keys().copied().collect();
    own_ids.sort();
    for id in own_ids {
        let r = &sys.rotations[id as usize];
        let name = if r.name.is_empty() {
            String::new()
        } else {
            names
                .take(
                    wishes(&r.name)
                        .into_iter()
                        .chain((2..).map(|i| format!("{}{i}", r.name)).take(1000)),
                )
                .unwrap_or_default()
        };
        if !r.name.is_empty() {
            e.rename(&r.name, &name);
        }
        let fix = |a: Angle| match a {
            Angle::Delta(k) => Angle::Radians(k * sys.settings.angle.to_radians()),
            other => other,
        };
        own.insert(id, rot.decls.len());
        rot.decls.push(Decl {
            name,
            torsion: fix(r.torsion),
            curvature: fix(r.curvature),
        });
    }

    let distinct_colours = {
        let mut c = sys.colours.clone();
        c.dedup();
        c.len()
    };
    let mut uses_colour = false;
    // Turns (positive first, so that the declared pairs are the positive
    // ones), then everything else.
    let mut order: Vec<SymbolId> = occ.iter().copied().filter(|&s| plain(s)).collect();
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
    for s in order {
        if spell.contains_key(&s) {
            continue;
        }
        let name = e.name(s).to_string();
        let span = e.symbol_span(s);
        let Some(op) = sys.op(s) else { continue };
        let r = |x: f64| Angle::Radians(x);
        let text = match op {
            TurtleOp::Forward { .. } => continue,
            TurtleOp::Frenet { rotation, negate } => {
                let d = &rot.decls[own[&rotation.0]];
                format!("{}{}", if negate { '-' } else { '+' }, d.name)
            }
            TurtleOp::Rotate { axis, angle } => {
                let a = match angle {
                    Angle::Delta(k) => Angle::Radians(k * sys.settings.angle.to_radians()),
                    other => other,
                };
                let (mag, negative) = match a {
                    Angle::Radians(x) => (Angle::Radians(x.abs()), x < 0.0),
                    other => (other, false),
                };
                let tok = match axis {
                    Axis::Up => rot.token(&mut names, r(0.0), neg(mag), &["", "c"]),
                    Axis::Heading => rot.token(&mut names, neg(mag), r(0.0), &["r"]),
                    Axis::Left => {
                        let first = rot.token(&mut names, r(-PI / 2.0), a, &["p"]);
                        let back = rot.token(&mut names, r(PI / 2.0), r(0.0), &["h"]);
                        format!("{first} {back}")
                    }
                };
                if axis != Axis::Left && negative {
                    flip(&tok)
                } else {
                    tok
                }
            }
            TurtleOp::TurnAround => rot.token(&mut names, r(0.0), r(PI), &["u"]),
            TurtleOp::Push => "[".into(),
            TurtleOp::Pop => "]".into(),
            TurtleOp::NextColour => {
                uses_colour = true;
                "{".into()
            }
            TurtleOp::PreviousColour => {
                uses_colour = true;
                "}".into()
            }
            TurtleOp::SwapTurns => "!".into(),
            TurtleOp::ScaleLength(x) => format!("{}@", number(x)),
            TurtleOp::PolygonBegin | TurtleOp::PolygonEnd => {
                e.problem(
                    Kind::Attribute,
                    span,
                    format!("the polygon symbol `{name}`: LinF has no filled polygons"),
                    "the polygon is dropped; its edges are drawn as they move",
                );
                String::new()
            }
            TurtleOp::DecrementWidth => {
                e.problem(
                    Kind::Attribute,
                    span,
                    format!("`{name}` makes lines thinner: LinF has no line widths"),
                    "it is dropped",
                );
                String::new()
            }
            TurtleOp::Stem { .. } => {
                e.problem(
                    Kind::Length,
                    span,
                    "a stem length: LinF scales lengths by factors",
                    "it is dropped",
                );
                String::new()
            }
            TurtleOp::TurnUnswapped(_)
            | TurtleOp::RotateReal(_)
            | TurtleOp::ForwardReal { .. }
            | TurtleOp::SetColour(_)
            | TurtleOp::ShiftColour { .. } => super::fractint_only(e, &name, span, "LinF"),
            // cpfg's own turtle commands: parametric systems are refused
            // before any emitter runs (see `translate`).
            TurtleOp::ColourIndex { .. }
            | TurtleOp::LineWidth { .. }
            | TurtleOp::PolygonVertex
            | TurtleOp::Sphere
            | TurtleOp::ScreenDisc
            | TurtleOp::Circle
            | TurtleOp::MoveTo
            | TurtleOp::SetHeading
            | TurtleOp::RollToVertical
            | TurtleOp::Surface(_)
            | TurtleOp::CylinderStart
            | TurtleOp::CylinderPoint { .. }
            | TurtleOp::CylinderTangents
            | TurtleOp::Query(_) => continue,
        };
        if text != name {
            e.rename(&name, &text);
        }
        spell.insert(s, text);
    }
    // Guarded occurrences.
    for &s in occ.iter().filter(|&&s| !plain(s)) {
        if let Some(g) = sys.symbols.info(s).guard {
            let base = spell.get(&g.base).cloned().unwrap_or_default();
            spell.insert(s, format!("{}?{base}", number(g.probability)));
        }
    }
    if sys.settings.scale != 100.0 {
        e.problem(
            Kind::Attribute,
            None,
            format!(
                "the scale factor {}: LinF pictures always fill the frame",
                number(sys.settings.scale)
            ),
            "the figure fills the picture",
        );
    }

    let all_short = spell
        .values()
        .chain(rot.decls.iter().map(|d| &d.name))
        .all(|n| !is_ident(n) || n.chars().count() <= 1)
        && rot.decls.iter().all(|d| d.name.chars().count() <= 1);
    let angle_names: Vec<&str> = rot.decls.iter().map(|d| d.name.as_str()).collect();
    let word = |w: &[SymbolId]| -> String {
        let toks: Vec<&str> = w
            .iter()
            .filter_map(|s| spell.get(s).map(String::as_str))
            .flat_map(str::split_whitespace)
            .collect();
        join(&toks, all_short, &angle_names)
    };

    // Rules: rewritten symbols, then the identity rule for plain symbols
    // nothing rewrites.
    let mut rule_lines = Vec::new();
    for (s, i) in rules.heads() {
        let p = &sys.productions[i];
        let alt = &p.alternatives[heaviest(p)];
        let head = spell.get(&s).cloned().unwrap_or_default();
        let mut line = format!("  {head} = {}", word(&alt.successor.0));
        let span = e.production_span(i);
        match span
            .as_ref()
            .and_then(|sp| attached(&e.origin.comments, e.source, sp))
        {
            Some(Attached::After(c)) => {
                let _ = write!(line, "  # {c}");
            }
            Some(Attached::Above(c)) => {
                for l in c {
                    rule_lines.push(format!("  {}", comment_line(&l).trim_end()));
                }
            }
            None => {}
        }
        let text = e.production_text(i);
        e.exact(format!("production `{text}`"), span, line.trim());
        rule_lines.push(line.trim_end().to_string());
    }
    for &s in occ.iter().filter(|&&s| plain(s)) {
        if sys.op(s).is_none() && !rules.contains(s) {
            if let Some(n) = spell.get(&s) {
                rule_lines.push(format!("  {n} = {n}"));
            }
        }
    }

    let mut axiom = word(&sys.axiom.0);
    if sys.settings.step != 1.0 {
        let f = format!("{}@", number(sys.settings.step));
        axiom = if axiom.is_empty() {
            f
        } else {
            format!("{f} {axiom}")
        };
    }

    let mut out = String::new();
    out.push_str(&format!("# {}\n", banner(e)));
    if let Some(c) = file_comment(&e.origin.comments, e.source) {
        out.push_str("#\n");
        for l in c {
            out.push_str(&comment_line(&l));
        }
    }
    let _ = writeln!(out, "#: steps {}", e.steps);
    if let Some((az, el)) = sys.settings.view {
        let _ = writeln!(out, "#: view {},{}", number(az), number(el));
    }
    if !lines_block.is_empty() {
        let _ = writeln!(out, "lines {}", lines_block.join(" "));
    }
    if !blanks_block.is_empty() {
        let _ = writeln!(out, "blanks {}", blanks_block.join(" "));
    }
    if !rot.decls.is_empty() {
        let decl = |d: &Decl| {
            let pair = format!("({}, {})", expr(d.torsion), expr(d.curvature));
            if d.name.is_empty() {
                pair
            } else {
                format!("{} = {pair}", d.name)
            }
        };
        if rot.decls.len() == 1 {
            let _ = writeln!(out, "angles {}", decl(&rot.decls[0]));
        } else {
            out.push_str("angles\n");
            for d in &rot.decls {
                let _ = writeln!(out, "  {}", decl(d));
            }
        }
    }
    let _ = writeln!(out, "axiom {axiom}");
    e.exact(
        "the axiom",
        e.spans.axiom.first().cloned(),
        &format!("axiom {axiom}"),
    );
    if !rule_lines.is_empty() {
        out.push_str("rules\n");
        for l in rule_lines {
            out.push_str(&l);
            out.push('\n');
        }
    }
    let colours: Vec<Rgb> = if !sys.colours.is_empty() {
        sys.colours.clone()
    } else if uses_colour {
        // pfg's palette wraps around; LinF stays on the last colour. The
        // palette repeated eight times covers 63 colour steps.
        let p = crate::turtle::DEFAULT_PALETTE;
        (0..8).flat_map(|_| p.iter().copied()).collect()
    } else {
        Vec::new()
    };
    if !colours.is_empty() && (uses_colour || distinct_colours > 1 || sys.colours.len() > 1) {
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
    }
    out
}

fn comment_line(l: &str) -> String {
    if l.is_empty() {
        "#\n".into()
    } else {
        format!("# {l}\n")
    }
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
    fn angles_are_written_as_fractions_of_pi_where_they_are() {
        assert_eq!(radians(PI / 3.0), "pi/3");
        assert_eq!(radians(-PI / 2.0), "-pi/2");
        assert_eq!(radians(2.0 * PI / 3.0), "2*pi/3");
        assert_eq!(radians(PI), "pi");
        assert_eq!(radians(0.7639 * PI), "0.7639*pi");
        assert_eq!(radians(1.0), "1");
        assert_eq!(radians(22.5f64.to_radians()), "pi/8");
    }

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
