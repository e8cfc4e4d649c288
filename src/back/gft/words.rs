//! How symbols, words and turtle operations are written.

use super::expr::{self, num, Names};
use super::look::degrees_or_radians;
use crate::ir::program::Expr;
use crate::ir::{Angle, Axis, ElasticityChange, QueryKind, SymbolId, System, TurtleOp, Word};
use std::fmt::Write;

/// Characters a bare name may not contain (docs/gft.md §2; braces and
/// commas too, since blocks, seeds and parameter lists use them).
const RESERVED: &[char] = &['(', ')', ':', '<', '>', '=', '?', '`', '"', '{', '}', ','];

/// The keywords of docs/gft.md: a line that starts with one (and has no
/// `->`) is that item, so a symbol of that name starting a line is
/// backquoted.
const KEYWORDS: &[&str] = &[
    "steps",
    "angle",
    "length",
    "scale",
    "width",
    "width-factor",
    "width-step",
    "widths",
    "colour",
    "colour-step",
    "view",
    "seed",
    "tropism",
    "turtle",
    "symbol",
    "silent",
    "choose",
    "ignore",
    "consider",
    "ring",
    "cut",
    "decomposition",
    "homomorphism",
    "axiom",
    "rotation",
    "colours",
    "globals",
    "array",
    "function",
    "start",
    "start-each",
    "end-each",
    "end",
    "rule",
    "stems",
    "outline",
    "growth",
    "background",
    "camera",
    "lighting",
    "light",
    "material",
    "surface",
    "contour",
];

/// How each symbol is written, and whether words put a space between
/// modules (they do as soon as one name is not a single character, so
/// that the longest-name rule cannot join two modules into one).
pub struct Spelling {
    spelled: Vec<String>,
    spaced: bool,
}

/// Whether `name` reads back as itself without backquotes.
fn bare(name: &str) -> bool {
    let mut chars = name.chars();
    let Some(first) = chars.next() else {
        return false;
    };
    let plain = |c: char| !c.is_whitespace() && !RESERVED.contains(&c);
    if chars.next().is_none() {
        return plain(first);
    }
    // A longer name: no reserved character, no bracket, nothing that
    // opens a comment or starts like a number (a guard's `0.5?`).
    name.chars().all(|c| plain(c) && c != '[' && c != ']')
        && !name.contains("/*")
        && !first.is_ascii_digit()
        && first != '.'
}

impl Spelling {
    pub fn new(sys: &System) -> Self {
        let mentioned = sys.mentioned();
        let spaced = mentioned.iter().any(|&s| {
            let info = sys.symbols.info(s);
            info.guard.is_some() || info.name.chars().count() != 1
        });
        let spell = |id: SymbolId| -> String {
            let info = sys.symbols.info(id);
            if let Some(key) = sys.symbols.silent_key(id) {
                return format!("`{key}`");
            }
            if bare(&info.name) {
                info.name.clone()
            } else {
                format!("`{}`", info.name)
            }
        };
        let mut spelled: Vec<String> = (0..sys.symbols.len() as u32)
            .map(|i| spell(SymbolId(i)))
            .collect();
        for (id, info) in sys.symbols.iter() {
            if let Some(g) = info.guard {
                spelled[id.index()] = format!("{}?{}", num(g.probability), spelled[g.base.index()]);
            }
        }
        Spelling { spelled, spaced }
    }

    pub fn name(&self, id: SymbolId) -> &str {
        &self.spelled[id.index()]
    }

    /// Appends module text to a word, with the separator the words need.
    fn join(&self, out: &mut String, module: &str) {
        let glued = out.ends_with('/') && module.starts_with('*');
        if !out.is_empty() && (self.spaced || glued) {
            out.push(' ');
        }
        out.push_str(module);
    }

    /// A list of symbols written as a word.
    pub fn symbols(&self, ids: &[SymbolId]) -> String {
        let mut out = String::new();
        for &s in ids {
            self.join(&mut out, self.name(s));
        }
        out
    }

    /// A word; module i's parameters are `args[i]` when given, else the
    /// word's own numbers.
    pub fn word(&self, w: &Word, args: &[Vec<Expr>], names: &Names<'_>) -> String {
        let mut out = String::new();
        for (i, &s) in w.0.iter().enumerate() {
            let mut module = self.name(s).to_string();
            let params: Vec<String> = match args.get(i) {
                Some(es) if !args.is_empty() => es.iter().map(|e| expr::expr(e, names)).collect(),
                _ => w.args(i).iter().map(|&v| num(v)).collect(),
            };
            if !params.is_empty() {
                let _ = write!(module, "({})", params.join(", "));
            }
            self.join(&mut out, &module);
        }
        out
    }

    /// A predecessor or context: each module with its formal names.
    pub fn pattern(&self, ids: &[SymbolId], slots: &[Vec<u16>], locals: &[String]) -> String {
        let mut out = String::new();
        for (k, &s) in ids.iter().enumerate() {
            let mut module = self.name(s).to_string();
            let formals = crate::ir::Formals::of(slots, k);
            if !formals.is_empty() {
                let names: Vec<&str> = (formals.iter())
                    .map(|&f| locals.get(f as usize).map_or("_", String::as_str))
                    .collect();
                let _ = write!(module, "({})", names.join(", "));
            }
            self.join(&mut out, &module);
        }
        out
    }

    /// `turtle none`, then what each symbol does: `NAME = operation` for
    /// the symbols that do something, `silent KEY = operation` for silent
    /// ones, `symbol …` for longer names that do nothing.
    pub fn turtle(&self, out: &mut String, sys: &System) {
        out.push_str("turtle none\n");
        let mut plain_names = Vec::new();
        for s in sys.mentioned() {
            let info = sys.symbols.info(s);
            let op = sys.interpretation.get(s.index()).copied().flatten();
            let branch = (s == SymbolId::OPEN && op == Some(TurtleOp::Push))
                || (s == SymbolId::CLOSE && op == Some(TurtleOp::Pop));
            if branch || info.guard.is_some() {
                continue;
            }
            let text = op.map_or("nothing".to_string(), |op| operation(sys, op));
            if let Some(key) = sys.symbols.silent_key(s) {
                let _ = writeln!(out, "silent {key} = {text}");
            } else if op.is_some() || s == SymbolId::OPEN || s == SymbolId::CLOSE {
                let name = self.name(s);
                if KEYWORDS.contains(&name) {
                    let _ = writeln!(out, "`{name}` = {text}");
                } else {
                    let _ = writeln!(out, "{name} = {text}");
                }
            } else if info.name.chars().count() > 1 {
                plain_names.push(self.name(s).to_string());
            }
        }
        if !plain_names.is_empty() {
            let _ = writeln!(out, "symbol {}", plain_names.join(" "));
        }
    }
}

/// An angle of a turtle operation: `delta`, `-delta`, `2.5*delta`,
/// `30deg` (or `0.52rad` when no decimal of degrees gives the radians
/// back), `[lo hi]` (radians).
pub fn angle(a: Angle) -> String {
    match a {
        Angle::Delta(f) if f.to_bits() == 1f64.to_bits() => "delta".into(),
        Angle::Delta(f) if f.to_bits() == (-1f64).to_bits() => "-delta".into(),
        Angle::Delta(f) => format!("{}*delta", num(f)),
        Angle::Radians(r) => {
            let text = degrees_or_radians(&[r]);
            match text.strip_suffix(" rad") {
                Some(r) => format!("{r}rad"),
                None => format!("{text}deg"),
            }
        }
        Angle::Uniform { lo, hi } => format!("[{} {}]", num(lo), num(hi)),
    }
}

/// A turtle operation as docs/gft.md §3 writes it.
pub fn operation(sys: &System, op: TurtleOp) -> String {
    let word = |b: bool, yes: &str, no: &str| if b { yes } else { no }.to_string();
    match op {
        TurtleOp::Forward { draw } => word(draw, "forward", "move"),
        TurtleOp::Rotate { axis, angle: a } => {
            let verb = match axis {
                Axis::Up => "turn",
                Axis::Left => "pitch",
                Axis::Heading => "roll",
            };
            format!("{verb} {}", angle(a))
        }
        TurtleOp::Frenet { rotation, negate } => {
            let name = sys
                .rotations
                .get(rotation.0 as usize)
                .map_or("", |r| r.name.as_str());
            let sign = if negate { "-" } else { "" };
            format!("frenet {sign}{name}").trim_end().to_string()
        }
        TurtleOp::TurnAround => "turn-around".into(),
        TurtleOp::Push => "push".into(),
        TurtleOp::Pop => "pop".into(),
        TurtleOp::PolygonBegin => "polygon-begin".into(),
        TurtleOp::PolygonEnd => "polygon-end".into(),
        TurtleOp::PolygonVertex => "vertex".into(),
        TurtleOp::DecrementWidth => "scale-width".into(),
        TurtleOp::NextColour => "next-colour".into(),
        TurtleOp::PreviousColour => "previous-colour".into(),
        TurtleOp::SwapTurns => "swap-turns".into(),
        TurtleOp::ScaleLength(x) => format!("scale-length {}", num(x)),
        TurtleOp::Stem { width, length } => format!("stem {} {}", num(width), num(length)),
        TurtleOp::ColourIndex { up } => word(up, "colour-up", "colour-down"),
        TurtleOp::LineWidth { up } => word(up, "width-up", "width-down"),
        TurtleOp::Sphere => "sphere".into(),
        TurtleOp::ScreenDisc => "disc".into(),
        TurtleOp::Circle => "circle".into(),
        TurtleOp::MoveTo => "move-to".into(),
        TurtleOp::SetHeading => "set-heading".into(),
        TurtleOp::RollToVertical => "roll-to-vertical".into(),
        TurtleOp::Surface(i) => match sys.surfaces.get(i as usize) {
            Some(s) => format!("surface {}", s.name),
            None => format!("surface {i}"),
        },
        TurtleOp::CylinderStart => "cylinder-start".into(),
        TurtleOp::CylinderPoint { end } => word(end, "cylinder-end", "cylinder-point"),
        TurtleOp::CylinderTangents => "cylinder-tangents".into(),
        TurtleOp::RadiusTangents => "radius-tangents".into(),
        TurtleOp::SetContour => "set-contour".into(),
        TurtleOp::Query(kind) => format!("query {}", query(kind)),
        TurtleOp::TurnUnswapped(a) => format!("turn-unswapped {}", angle(a)),
        TurtleOp::RotateReal(a) => format!("turn-real {}", angle(a)),
        TurtleOp::ForwardReal { draw } => word(draw, "forward-real", "move-real"),
        TurtleOp::SetColour(n) => format!("set-colour {n}"),
        TurtleOp::ShiftColour { by, up } => format!("colour-shift {}{by}", word(up, "+", "-")),
        TurtleOp::Elasticity { tropism, change } => elasticity(tropism, change),
        TurtleOp::Untwist => "untwist".into(),
        TurtleOp::KeepTwist => "keep-twist".into(),
    }
}

fn query(kind: QueryKind) -> &'static str {
    match kind {
        QueryKind::Position => "position",
        QueryKind::Heading => "heading",
        QueryKind::Left => "left",
        QueryKind::Up => "up",
    }
}

/// `elasticity CHANGE [tropism N]`, N counted from 1 as cpfg counts.
fn elasticity(tropism: Option<u16>, change: ElasticityChange) -> String {
    let change = match change {
        ElasticityChange::Set => "set",
        ElasticityChange::Increase => "increase",
        ElasticityChange::Decrease => "decrease",
        ElasticityChange::SetOrIncrease => "set-or-increase",
    };
    match tropism {
        Some(t) => format!("elasticity {change} tropism {}", u32::from(t) + 1),
        None => format!("elasticity {change}"),
    }
}
