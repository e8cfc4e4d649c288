//! The pfg emitter: a system written in the 1988 format of the Appendix A
//! listing, so that the listing itself could read it.
//!
//! * Headers in the listing's order (`derivation length`, `angle factor`,
//!   `scale factor`, `axiom`, `ignore`), then one production per line in
//!   the full form `lc < pred > rc --> succ`, `*` for an empty part, and
//!   `: weight` on the alternatives of a random choice.
//! * Symbols are single characters. A source symbol keeps its name when it
//!   is one free character (`_c` and `_xHH`, the LinF spellings of pfg
//!   characters, are read back as `c` and the character HH); otherwise it
//!   gets its first letter, or the next free character.
//! * Turns: one angle factor n is chosen so that every angle of the source
//!   is a whole multiple of 360/n degrees (the source's own factor first);
//!   a turn is then written as repeated `+ - & ^ \ /`, a half turn about U
//!   as `|`. A LinF pair (torsion, curvature) is a roll (`\ /`) then a turn
//!   (`+ -`).
//! * Only `F` draws and `f` moves in pfg. When the source has several
//!   drawing symbols (LinF `lines f g`), each is written as a marker
//!   followed by `F` (`g` becomes `GF`): the marker carries the symbol's
//!   rules, `F --> *` removes the old `F` at each step and a last rule
//!   `G --> GF` keeps a symbol that nothing rewrote. `F` joins the ignore
//!   list, so contexts see the markers as they saw the symbols.
//! * A consider list (cpfg) becomes the ignore list of everything else.

use super::{
    attached, banner, file_comment, multiples, number, occurring, turns, Attached, Emitter, Kind,
    Names, Turns,
};
use crate::ir::{Axis, ContextFilter, SymbolId, TurtleOp};
use std::collections::HashMap;
use std::fmt::Write;

/// The Pfg emitter in the registry.
pub struct Pfg;

impl super::Back for Pfg {
    fn name(&self) -> &'static str {
        "pfg"
    }
    fn extension(&self) -> &'static str {
        "l"
    }
    fn write(&self, e: &mut super::Emitter<'_>) -> String {
        write(e)
    }
    fn term_symbols(&self) -> Option<usize> {
        Some(60)
    }
}

/// Characters pfg gives a meaning, or uses in its syntax.
const RESERVED: &[&str] = &[
    "F", "f", "+", "-", "&", "^", "\\", "/", "|", "{", "}", "!", "'", "[", "]", "*", "<", ">", ":",
];

/// Characters a plain symbol may be given, in order of preference.
fn pool() -> impl Iterator<Item = String> {
    ('A'..='Z')
        .chain('a'..='z')
        .chain('0'..='9')
        .chain("#$%.,;=?@~\"`()".chars())
        .map(|c| c.to_string())
}

fn valid(c: char) -> bool {
    c.is_ascii_graphic() && !RESERVED.contains(&c.to_string().as_str())
}

/// The characters a source name would like to be, best first.
fn wishes(name: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut chars = name.chars();
    if let (Some(c), None) = (chars.next(), chars.next()) {
        if valid(c) {
            out.push(c.to_string());
        }
    }
    if let Some(rest) = name.strip_prefix('_') {
        let mut cs = rest.chars();
        if let (Some(c), None) = (cs.next(), cs.next()) {
            out.push(c.to_string());
        }
        if let Some(hex) = rest.strip_prefix('x') {
            if let Some(c) = u32::from_str_radix(hex, 16).ok().and_then(char::from_u32) {
                out.push(c.to_string());
            }
        }
    }
    if let Some(c) = name.chars().find(|c| c.is_ascii_alphanumeric()) {
        out.push(c.to_string());
        out.push(c.to_ascii_uppercase().to_string());
        out.push(c.to_ascii_lowercase().to_string());
    }
    out.retain(|s| s.chars().all(valid));
    out
}

/// How one source symbol is written.
#[derive(Clone, Debug)]
enum Spelling {
    /// These characters (possibly none).
    Chars(String),
    /// A marker character followed by `F` or `f`.
    Pair(char, char),
}

impl Spelling {
    fn full(&self) -> String {
        match self {
            Spelling::Chars(s) => s.clone(),
            Spelling::Pair(m, b) => format!("{m}{b}"),
        }
    }
    /// The one character that stands for the symbol in a predecessor's
    /// last place or a context.
    fn single(&self) -> Option<char> {
        match self {
            Spelling::Chars(s) => {
                let mut cs = s.chars();
                match (cs.next(), cs.next()) {
                    (Some(c), None) => Some(c),
                    _ => None,
                }
            }
            Spelling::Pair(m, _) => Some(*m),
        }
    }
}

pub fn write(e: &mut Emitter<'_>) -> String {
    let sys = e.sys;
    let occ = occurring(sys);
    let plain = |s: SymbolId| sys.symbols.info(s).guard.is_none();
    let draws: Vec<SymbolId> = occ
        .iter()
        .copied()
        .filter(|&s| plain(s) && sys.op(s) == Some(TurtleOp::Forward { draw: true }))
        .collect();
    let moves: Vec<SymbolId> = occ
        .iter()
        .copied()
        .filter(|&s| plain(s) && sys.op(s) == Some(TurtleOp::Forward { draw: false }))
        .collect();
    let pair_draw = draws.len() > 1;
    let pair_move = moves.len() > 1;

    // The angle factor.
    let mut by_symbol = Vec::new();
    for &s in occ.iter().filter(|&&s| plain(s)) {
        let Some(op) = sys.op(s) else { continue };
        if let Some(Turns::Fixed(t) | Turns::Random(t)) = turns(sys, op) {
            by_symbol.extend(t.iter().map(|x| (s, x.1.abs())));
        }
        match turns(sys, op) {
            Some(Turns::Fixed(_)) => {}
            Some(Turns::Random(t)) => {
                let mid: Vec<String> = t
                    .iter()
                    .map(|x| format!("{:.4}", x.1.to_degrees()))
                    .collect();
                e.problem(
                    Kind::Interval,
                    e.symbol_span(s),
                    format!(
                        "the interval angle of `{}`: pfg turns by fixed angles",
                        e.name(s)
                    ),
                    format!(
                        "the middle of the interval is used ({} degrees)",
                        mid.join(", ")
                    ),
                );
            }
            None => {}
        }
    }
    let n = super::angle_factor(e, &by_symbol, "pfg");
    e.exact(
        "the turning angles",
        None,
        &format!("angle factor: {n} ({} degrees)", number(360.0 / n as f64)),
    );

    // Names and spellings.
    let mut names = Names::new(RESERVED);
    let mut spell: HashMap<SymbolId, Spelling> = HashMap::new();
    // Plain names first, so that they keep their own characters.
    let mut wanted: Vec<(SymbolId, Vec<String>)> = Vec::new();
    for &s in occ.iter().filter(|&&s| plain(s)) {
        let op = sys.op(s);
        let name = e.name(s).to_string();
        match op {
            None => wanted.push((s, wishes(&name))),
            Some(TurtleOp::Forward { draw }) if (draw && pair_draw) || (!draw && pair_move) => {
                let mut w: Vec<String> = wishes(&name)
                    .into_iter()
                    .map(|c| c.to_ascii_uppercase())
                    .collect();
                w.extend(wishes(&name));
                wanted.push((s, w));
            }
            _ => {}
        }
    }
    for (s, w) in wanted {
        let name = e.name(s).to_string();
        let Some(c) = names.take(w.into_iter().chain(pool())) else {
            e.problem(
                Kind::TooLarge,
                e.symbol_span(s),
                format!("the symbol `{name}`: pfg has no character left for it"),
                "use fewer symbols",
            );
            continue;
        };
        let c = c.chars().next().unwrap_or('?');
        let sp = match sys.op(s) {
            Some(TurtleOp::Forward { draw }) => Spelling::Pair(c, if draw { 'F' } else { 'f' }),
            _ => Spelling::Chars(c.to_string()),
        };
        e.rename(&name, &sp.full());
        spell.insert(s, sp);
    }
    let distinct_colours = {
        let mut c = sys.colours.clone();
        c.dedup();
        c.len()
    };
    for &s in occ.iter().filter(|&&s| plain(s)) {
        if spell.contains_key(&s) {
            continue;
        }
        let name = e.name(s).to_string();
        let span = e.symbol_span(s);
        let Some(op) = sys.op(s) else { continue };
        let text = match op {
            TurtleOp::Forward { draw: true } => "F".to_string(),
            TurtleOp::Forward { draw: false } => "f".to_string(),
            TurtleOp::TurnAround => "|".to_string(),
            TurtleOp::Rotate { .. } | TurtleOp::Frenet { .. } => {
                let t = match turns(sys, op) {
                    Some(Turns::Fixed(t)) | Some(Turns::Random(t)) => t,
                    None => Vec::new(),
                };
                let mut out = String::new();
                for (axis, a) in t {
                    let k = multiples(a, n);
                    let (pos, neg) = match axis {
                        Axis::Up => ('+', '-'),
                        Axis::Left => ('&', '^'),
                        Axis::Heading => ('\\', '/'),
                    };
                    if axis == Axis::Up && k.unsigned_abs() * 2 == n {
                        out.push('|');
                    } else {
                        let c = if k > 0 { pos } else { neg };
                        out.push_str(&super::repeated(e, s, c, k));
                    }
                }
                out
            }
            TurtleOp::Push => "[".into(),
            TurtleOp::Pop => "]".into(),
            TurtleOp::PolygonBegin => "{".into(),
            TurtleOp::PolygonEnd => "}".into(),
            TurtleOp::DecrementWidth => {
                if sys.settings.width_factor != crate::ir::Settings::default().width_factor {
                    e.problem(
                        Kind::Attribute,
                        span,
                        format!(
                            "`{name}` makes lines thinner by the factor {}: pfg's `!` always uses {}",
                            number(sys.settings.width_factor),
                            number(crate::ir::Settings::default().width_factor)
                        ),
                        "pfg's factor is used",
                    );
                }
                "!".into()
            }
            TurtleOp::NextColour => {
                if sys.colours.is_empty() {
                    "'".into()
                } else if distinct_colours <= 1 {
                    String::new()
                } else {
                    e.problem(
                        Kind::Attribute,
                        span,
                        format!("`{name}` steps through the file's own colours: pfg's `'` steps through a fixed palette"),
                        "`'` is written: the colours come from pfg's palette",
                    );
                    "'".into()
                }
            }
            TurtleOp::PreviousColour => {
                if distinct_colours > 1 {
                    e.problem(
                        Kind::Attribute,
                        span,
                        format!(
                            "`{name}` goes back to the previous colour: pfg has no such symbol"
                        ),
                        "it is dropped",
                    );
                }
                String::new()
            }
            TurtleOp::SwapTurns => {
                e.problem(
                    Kind::Swap,
                    span,
                    format!("`{name}` exchanges `+` and `-`: pfg has no such symbol"),
                    "it is dropped",
                );
                String::new()
            }
            TurtleOp::ScaleLength(x) => {
                if x != 1.0 {
                    e.problem(
                        Kind::Length,
                        span,
                        format!(
                            "the length factor `{name}`: pfg draws every step with the same length"
                        ),
                        "the factor is dropped",
                    );
                }
                String::new()
            }
            TurtleOp::Stem { .. } => {
                e.problem(
                    Kind::Length,
                    span,
                    "a stem length: pfg draws every step with the same length",
                    "it is dropped",
                );
                String::new()
            }
            TurtleOp::TurnUnswapped(_)
            | TurtleOp::RotateReal(_)
            | TurtleOp::ForwardReal { .. }
            | TurtleOp::SetColour(_)
            | TurtleOp::ShiftColour { .. } => super::fractint_only(e, &name, span, "pfg"),
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
        spell.insert(s, Spelling::Chars(text));
    }
    // Guarded symbols are written as their base.
    for &s in occ.iter().filter(|&&s| !plain(s)) {
        let Some(g) = sys.symbols.info(s).guard else {
            continue;
        };
        e.problem(
            Kind::Guard,
            e.symbol_span(s),
            format!(
                "`{}` expands with probability {}: pfg has no per-occurrence probability",
                e.name(s),
                number(g.probability)
            ),
            format!("`{}` is always expanded", e.name(g.base)),
        );
        let base = spell
            .get(&g.base)
            .cloned()
            .unwrap_or(Spelling::Chars(String::new()));
        spell.insert(s, base);
    }
    if sys.settings.step != 1.0 {
        e.problem(
            Kind::Length,
            None,
            format!(
                "the step length {}: pfg's steps are 1 long",
                number(sys.settings.step)
            ),
            "steps are 1 long: the picture is the same, scaled",
        );
    }

    let full = |w: &[SymbolId]| -> String {
        w.iter()
            .map(|s| spell.get(s).map(Spelling::full).unwrap_or_default())
            .collect()
    };
    let ctx_used = sys.productions.iter().any(|p| p.is_context_sensitive());

    // Productions.
    let mut lines: Vec<String> = Vec::new();
    let mut rewritten_alone: Vec<SymbolId> = Vec::new();
    for (i, p) in sys.productions.iter().enumerate() {
        let text = e.production_text(i);
        let span = e.production_span(i);
        let mut pred = String::new();
        let mut ok = true;
        for (j, s) in p.predecessor.iter().enumerate() {
            match spell.get(s) {
                Some(sp @ Spelling::Pair(..)) if j + 1 < p.predecessor.len() => {
                    pred.push_str(&sp.full())
                }
                Some(sp) => match sp.single() {
                    Some(c) => pred.push(c),
                    None => ok = false,
                },
                None => ok = false,
            }
        }
        let context = |w: &[SymbolId]| -> Option<String> {
            let mut out = String::new();
            for s in w {
                out.push(spell.get(s)?.single()?);
            }
            Some(out)
        };
        let (lc, rc) = (context(&p.left), context(&p.right));
        let (Some(lc), Some(rc), true) = (lc, rc, ok) else {
            e.problem(
                Kind::Rule,
                span,
                format!("the production `{text}` rewrites or looks at a symbol that pfg writes as several characters (or none)"),
                "the production is dropped",
            );
            continue;
        };
        if p.left.is_empty() && p.right.is_empty() && p.predecessor.len() == 1 {
            rewritten_alone.push(p.predecessor[0]);
        }
        let star = |s: String| if s.is_empty() { "*".to_string() } else { s };
        let head = format!("{} < {} > {} -->", star(lc), pred, star(rc));
        let comment = span
            .as_ref()
            .and_then(|s| attached(&e.origin.comments, e.source, s));
        if let Some(Attached::Above(c)) = &comment {
            lines.push(comment_block(c));
        }
        let weighted = p.alternatives.len() > 1;
        // Weights are relative: written as shares of the largest, and
        // equal when the source's do not make sense as numbers.
        let max = p.alternatives.iter().map(|a| a.weight).fold(0.0, f64::max);
        let mut first = String::new();
        for a in &p.alternatives {
            let mut line = format!("{head} {}", star(full(&a.successor.0)));
            if weighted {
                let w = a.weight / max;
                let w = if w.is_finite() && w > 0.0 { w } else { 1.0 };
                let _ = write!(line, " : {}", number(w));
            }
            if let Some(Attached::After(c)) = &comment {
                if first.is_empty() {
                    let _ = write!(line, " /* {} */", sanitize(c));
                }
            }
            if first.is_empty() {
                first = line.clone();
            }
            lines.push(line);
        }
        e.exact(format!("production `{text}`"), span, &first);
    }
    // The pairs: markers nothing rewrote keep their symbol, and the old
    // `F`/`f` go.
    for (pair, base) in [(pair_draw, 'F'), (pair_move, 'f')] {
        if !pair {
            continue;
        }
        let syms = if base == 'F' { &draws } else { &moves };
        for s in syms {
            if let Some(Spelling::Pair(m, b)) = spell.get(s) {
                if !rewritten_alone.contains(s) {
                    lines.push(format!("* < {m} > * --> {m}{b}"));
                }
            }
        }
        lines.push(format!("* < {base} > * --> *"));
        e.exact(
            format!("the drawing symbols written `{base}` after a marker"),
            None,
            &format!("* < {base} > * --> *"),
        );
    }

    // Ignore list.
    let mut ignore = String::new();
    if ctx_used {
        let mut push = |s: String| {
            for c in s.chars() {
                if !ignore.contains(c) {
                    ignore.push(c);
                }
            }
        };
        match &sys.context {
            ContextFilter::Ignore(set) => {
                for s in set {
                    if let Some(sp) = spell.get(s) {
                        push(sp.single().map(String::from).unwrap_or_else(|| sp.full()));
                    }
                }
            }
            ContextFilter::Consider(set) => {
                for &s in &occ {
                    if s != SymbolId::OPEN && s != SymbolId::CLOSE && !set.contains(&s) {
                        if let Some(sp) = spell.get(&s) {
                            push(sp.single().map(String::from).unwrap_or_else(|| sp.full()));
                        }
                    }
                }
            }
        }
        if pair_draw {
            push("F".into());
        }
        if pair_move {
            push("f".into());
        }
    }

    let mut axiom = full(&sys.axiom.0);
    if axiom.is_empty() {
        // pfg needs an axiom: a symbol that does nothing.
        axiom = names.take(pool()).unwrap_or_else(|| "Z".to_string());
        e.exact(
            "the empty axiom",
            None,
            &format!("axiom: {axiom} (a symbol that does nothing)"),
        );
    } else {
        e.exact(
            "the axiom",
            e.spans.axiom.first().cloned(),
            &format!("axiom: {axiom}"),
        );
    }

    let mut out = String::new();
    let mut head = vec![banner(e)];
    if let Some(c) = file_comment(&e.origin.comments, e.source) {
        head.push(String::new());
        head.extend(c);
    }
    out.push_str(&comment_block(&head));
    out.push('\n');
    let _ = writeln!(out, "derivation length: {}", e.steps);
    let _ = writeln!(out, "angle factor: {n}");
    let _ = writeln!(
        out,
        "scale factor: {}",
        number(sys.settings.scale.clamp(0.0, 100.0))
    );
    let _ = writeln!(out, "axiom: {axiom}");
    let _ = writeln!(out, "{}", format!("ignore: {ignore}").trim_end());
    for l in lines {
        out.push_str(&l);
        out.push('\n');
    }
    out
}

fn sanitize(s: &str) -> String {
    s.replace("*/", "* /").replace("/*", "/ *")
}

/// A pfg comment holding `lines`.
fn comment_block(lines: &[String]) -> String {
    let body: Vec<String> = lines.iter().map(|l| sanitize(l)).collect();
    let indent = |l: &String| {
        if l.is_empty() {
            String::new()
        } else {
            format!("   {l}")
        }
    };
    if body.len() == 1 {
        format!("/* {} */", body[0])
    } else {
        format!(
            "/* {}\n{} */",
            body[0],
            body[1..].iter().map(indent).collect::<Vec<_>>().join("\n")
        )
    }
}
