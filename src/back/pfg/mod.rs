//! The pfg emitter: a system written in the 1988 format of the Appendix A
//! listing, so that the listing itself could read it.
//!
//! * Headers in the listing's order (`derivation length`, `angle factor`,
//!   `scale factor`, `axiom`, `ignore` when a context needs one), then one
//!   production per line: the book's short form `pred --> succ` without
//!   contexts, else the full form `lc < pred > rc --> succ` with `*` for an
//!   empty part, and `: weight` on the alternatives of a random choice.
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

use super::walk::{
    distinct_colours, dropped, fractint_only, no_chance, no_length_factor, no_stems, spell_each,
    turn_text, turning, write_word, Does, Sym, Symbols, Turning,
};
use super::{number, opening, Attached, Emitter, Kind, Names};
use crate::ir::{Axis, ContextFilter, SymbolId, System, TurtleOp};
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

/// How pfg takes the turns of a system.
const TURNING: Turning = Turning {
    target: "pfg",
    fixed: "pfg turns by fixed angles",
    middle_in_degrees: true,
    plane: false,
};

/// Why pfg has no length factors or stem lengths.
const ONE_LENGTH: &str = "pfg draws every step with the same length";

/// The symbols of a system as pfg spells them.
struct Spellings {
    spell: HashMap<SymbolId, Spelling>,
    names: Names,
    /// The drawing and the moving symbols (each written as a marker and
    /// `F` or `f` when there are several).
    draws: Vec<SymbolId>,
    moves: Vec<SymbolId>,
}

impl Spellings {
    fn pair_draw(&self) -> bool {
        self.draws.len() > 1
    }

    fn pair_move(&self) -> bool {
        self.moves.len() > 1
    }

    /// `w` as pfg writes it.
    fn full(&self, w: &[SymbolId]) -> String {
        write_word(
            w,
            |s| Some(self.spell.get(&s).map(Spelling::full).unwrap_or_default()),
            |t| t.concat(),
        )
    }

    /// The one character of each symbol of `w` (a context), if each has
    /// one.
    fn context(&self, w: &[SymbolId]) -> Option<String> {
        let mut out = String::new();
        for s in w {
            out.push(self.spell.get(s)?.single()?);
        }
        Some(out)
    }
}

pub fn write(e: &mut Emitter<'_>) -> String {
    let sys = e.sys;
    let syms = Symbols::of(sys);
    let forward = |draw: bool| -> Vec<SymbolId> {
        let op = Some(TurtleOp::Forward { draw });
        syms.plain
            .iter()
            .copied()
            .filter(|&s| sys.op(s) == op)
            .collect()
    };
    let mut sp = Spellings {
        spell: HashMap::new(),
        names: Names::new(RESERVED),
        draws: forward(true),
        moves: forward(false),
    };
    let n = turning(e, &syms.plain, &TURNING);
    e.exact(
        "the turning angles",
        None,
        &format!("angle factor: {n} ({} degrees)", number(360.0 / n as f64)),
    );
    name_symbols(e, &syms, &mut sp);
    let todo = syms.unspelled(&sp.spell);
    let distinct = distinct_colours(sys);
    for (sym, text) in spell_each(e, todo, |e, sym| operation(e, sym, n, distinct)) {
        e.rename(&sym.name, &text);
        sp.spell.insert(sym.id, Spelling::Chars(text));
    }
    // Guarded symbols are written as their base.
    for &(s, g) in &syms.guarded {
        no_chance(e, s, g, "pfg has no per-occurrence probability");
        let base = sp
            .spell
            .get(&g.base)
            .cloned()
            .unwrap_or(Spelling::Chars(String::new()));
        sp.spell.insert(s, base);
    }
    // pfg's steps are 1 long. Another positive length draws the same
    // shape fitted to the frame, but not the same coordinates (bounds,
    // statistics, meshes): not exact.
    let step = sys.settings.step;
    if step != 1.0 {
        e.problem(
            Kind::Length,
            None,
            format!("the step length {}: pfg's steps are 1 long", number(step)),
            if step > 0.0 {
                format!(
                    "the same shape, its coordinates divided by {}",
                    number(step)
                )
            } else {
                "steps are 1 long".to_string()
            },
        );
    }
    let mut lines: Vec<String> = Vec::new();
    let mut rewritten_alone: Vec<SymbolId> = Vec::new();
    for i in 0..sys.productions.len() {
        rewritten_alone.extend(production(e, i, &sp, &mut lines));
    }
    pair_rules(e, &sp, &rewritten_alone, &mut lines);
    let ignore = ignore_list(sys, &syms, &sp);
    let axiom = axiom(e, &mut sp);
    text(e, n, &axiom, &ignore, &lines)
}

/// Gives the symbols that do nothing, and the drawing and moving symbols
/// written as a marker and `F` or `f`, their characters: plain names
/// first, so that they keep their own characters.
fn name_symbols(e: &mut Emitter<'_>, syms: &Symbols, sp: &mut Spellings) {
    let sys = e.sys;
    let mut wanted: Vec<(SymbolId, Vec<String>)> = Vec::new();
    for &s in &syms.plain {
        let name = e.name(s);
        match sys.op(s) {
            None => wanted.push((s, wishes(name))),
            Some(TurtleOp::Forward { draw })
                if (draw && sp.pair_draw()) || (!draw && sp.pair_move()) =>
            {
                let mut w: Vec<String> = wishes(name)
                    .into_iter()
                    .map(|c| c.to_ascii_uppercase())
                    .collect();
                w.extend(wishes(name));
                wanted.push((s, w));
            }
            _ => {}
        }
    }
    for (s, w) in wanted {
        let name = e.name(s).to_string();
        let Some(c) = sp.names.take(w.into_iter().chain(pool())) else {
            e.problem(
                Kind::TooLarge,
                e.symbol_span(s),
                format!("the symbol `{name}`: pfg has no character left for it"),
                "use fewer symbols",
            );
            continue;
        };
        let c = c.chars().next().unwrap_or('?');
        let spelling = match sys.op(s) {
            Some(TurtleOp::Forward { draw }) => Spelling::Pair(c, if draw { 'F' } else { 'f' }),
            _ => Spelling::Chars(c.to_string()),
        };
        e.rename(&name, &spelling.full());
        sp.spell.insert(s, spelling);
    }
}

/// What pfg writes for a symbol that does something (`None`: nothing
/// at all, not even an empty spelling), with the angle factor `n` and
/// the count of the file's distinct colours.
fn operation(e: &mut Emitter<'_>, sym: &Sym, n: u64, distinct: usize) -> Option<String> {
    let sys = e.sys;
    let name = &sym.name;
    let span = sym.span.clone();
    Some(match sym.does {
        Does::Nothing | Does::Cpfg => return None,
        Does::Forward { draw: true } => "F".into(),
        Does::Forward { draw: false } => "f".into(),
        Does::Turn(TurtleOp::TurnAround) => "|".into(),
        Does::Turn(op) => turn_text(e, sym.id, op, n, Some('|'), |axis, positive| {
            let (pos, neg) = match axis {
                Axis::Up => ('+', '-'),
                Axis::Left => ('&', '^'),
                Axis::Heading => ('\\', '/'),
            };
            Some(if positive { pos } else { neg })
        }),
        Does::Push => "[".into(),
        Does::Pop => "]".into(),
        Does::Polygon { begin } => if begin { "{" } else { "}" }.into(),
        Does::Thinner => {
            let default = crate::ir::Settings::default().width_factor;
            if sys.settings.width_factor != default {
                e.problem(
                    Kind::Attribute,
                    span,
                    format!(
                        "`{name}` makes lines thinner by the factor {}: pfg's `!` always uses {}",
                        number(sys.settings.width_factor),
                        number(default)
                    ),
                    "pfg's factor is used",
                );
            }
            "!".into()
        }
        Does::Colour { next: true } => {
            if sys.colours.is_empty() {
                "'".into()
            } else if distinct <= 1 {
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
        Does::Colour { next: false } if distinct > 1 => dropped(
            e,
            sym,
            Kind::Attribute,
            format!("`{name}` goes back to the previous colour: pfg has no such symbol"),
            "it is dropped",
        ),
        Does::Colour { next: false } => String::new(),
        Does::Swap => dropped(
            e,
            sym,
            Kind::Swap,
            format!("`{name}` exchanges `+` and `-`: pfg has no such symbol"),
            "it is dropped",
        ),
        Does::Length(x) => no_length_factor(e, sym, x, ONE_LENGTH),
        Does::Stem => no_stems(e, sym, ONE_LENGTH),
        Does::Fractint => fractint_only(e, sym, "pfg"),
    })
}

/// Writes production `i` (one line per alternative, after the comment
/// above it) to `lines`; the symbol it rewrites when it rewrites one
/// symbol without context.
fn production(
    e: &mut Emitter<'_>,
    i: usize,
    sp: &Spellings,
    lines: &mut Vec<String>,
) -> Option<SymbolId> {
    let p = &e.sys.productions[i];
    let text = e.production_text(i);
    let span = e.production_span(i);
    let mut pred = String::new();
    let mut ok = true;
    for (j, s) in p.predecessor.iter().enumerate() {
        match sp.spell.get(s) {
            Some(x @ Spelling::Pair(..)) if j + 1 < p.predecessor.len() => pred.push_str(&x.full()),
            Some(x) => match x.single() {
                Some(c) => pred.push(c),
                None => ok = false,
            },
            None => ok = false,
        }
    }
    let (lc, rc) = (sp.context(&p.left), sp.context(&p.right));
    let (Some(lc), Some(rc), true) = (lc, rc, ok) else {
        e.problem(
            Kind::Rule,
            span,
            format!("the production `{text}` rewrites or looks at a symbol that pfg writes as several characters (or none)"),
            "the production is dropped",
        );
        return None;
    };
    let star = |s: String| if s.is_empty() { "*".to_string() } else { s };
    // The book's short form where there is no context: `F --> FF`.
    let head = if lc.is_empty() && rc.is_empty() {
        format!("{pred} -->")
    } else {
        format!("{} < {} > {} -->", star(lc), pred, star(rc))
    };
    let comment = e.attached_to(span.as_ref());
    if let Some(Attached::Above(c)) = &comment {
        lines.push(comment_block(c));
    }
    let weighted = p.alternatives.len() > 1;
    // Weights are relative: written as shares of the largest, and
    // equal when the source's do not make sense as numbers.
    let max = p.alternatives.iter().map(|a| a.weight).fold(0.0, f64::max);
    let mut first = String::new();
    for a in &p.alternatives {
        let mut line = format!("{head} {}", star(sp.full(&a.successor.0)));
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
    let alone = p.left.is_empty() && p.right.is_empty() && p.predecessor.len() == 1;
    alone.then(|| p.predecessor[0])
}

/// The pairs: markers nothing rewrote (alone) keep their symbol, and the
/// old `F`/`f` go.
fn pair_rules(
    e: &mut Emitter<'_>,
    sp: &Spellings,
    rewritten_alone: &[SymbolId],
    lines: &mut Vec<String>,
) {
    for (pair, base, syms) in [
        (sp.pair_draw(), 'F', &sp.draws),
        (sp.pair_move(), 'f', &sp.moves),
    ] {
        if !pair {
            continue;
        }
        for s in syms {
            if let Some(Spelling::Pair(m, b)) = sp.spell.get(s) {
                if !rewritten_alone.contains(s) {
                    lines.push(format!("{m} --> {m}{b}"));
                }
            }
        }
        lines.push(format!("{base} --> *"));
        e.exact(
            format!("the drawing symbols written `{base}` after a marker"),
            None,
            &format!("{base} --> *"),
        );
    }
}

/// The ignore list (empty unless a production has a context).
fn ignore_list(sys: &System, syms: &Symbols, sp: &Spellings) -> String {
    let mut ignore = String::new();
    if !sys.productions.iter().any(|p| p.is_context_sensitive()) {
        return ignore;
    }
    let mut push = |s: String| {
        for c in s.chars() {
            if !ignore.contains(c) {
                ignore.push(c);
            }
        }
    };
    let ignored: Vec<SymbolId> = match &sys.context {
        ContextFilter::Ignore(set) => set.clone(),
        ContextFilter::Consider(set) => syms
            .all
            .iter()
            .copied()
            .filter(|s| *s != SymbolId::OPEN && *s != SymbolId::CLOSE && !set.contains(s))
            .collect(),
    };
    for s in ignored {
        if let Some(x) = sp.spell.get(&s) {
            push(x.single().map(String::from).unwrap_or_else(|| x.full()));
        }
    }
    if sp.pair_draw() {
        push("F".into());
    }
    if sp.pair_move() {
        push("f".into());
    }
    ignore
}

/// The axiom; pfg needs one, so an empty axiom is a symbol that does
/// nothing.
fn axiom(e: &mut Emitter<'_>, sp: &mut Spellings) -> String {
    let axiom = sp.full(&e.sys.axiom.0);
    if !axiom.is_empty() {
        e.exact_axiom(&format!("axiom: {axiom}"));
        return axiom;
    }
    let axiom = sp.names.take(pool()).unwrap_or_else(|| "Z".to_string());
    e.exact(
        "the empty axiom",
        None,
        &format!("axiom: {axiom} (a symbol that does nothing)"),
    );
    axiom
}

/// The file: the opening comment, the headers, the productions.
fn text(e: &Emitter<'_>, n: u64, axiom: &str, ignore: &str, lines: &[String]) -> String {
    let sys = e.sys;
    let mut out = comment_block(&opening(e));
    out.push('\n');
    let _ = writeln!(out, "derivation length: {}", e.steps);
    let _ = writeln!(out, "angle factor: {n}");
    let _ = writeln!(
        out,
        "scale factor: {}",
        number(sys.settings.scale.clamp(0.0, 100.0))
    );
    let _ = writeln!(out, "axiom: {axiom}");
    // An empty ignore list is the default: not written.
    if !ignore.trim().is_empty() {
        let _ = writeln!(out, "ignore: {ignore}");
    }
    for l in lines {
        out.push_str(l);
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
