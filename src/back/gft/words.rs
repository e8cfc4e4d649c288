//! How symbols, words and turtle operations are written.

use super::expr::{self, num, Names};
use super::look::degrees_or_radians;
use crate::common::gft_words::is_keyword;
use crate::common::vocabulary::{self, TurtleSet};
use crate::ir::program::Expr;
use crate::ir::{Angle, Axis, ElasticityChange, QueryKind, SymbolId, System, TurtleOp, Word};
use std::fmt::Write;

/// Characters a bare name may not contain (docs/gft.md §2; braces and
/// commas too, since blocks, seeds and parameter lists use them).
const RESERVED: &[char] = &['(', ')', ':', '<', '>', '=', '?', '`', '"', '{', '}', ','];

/// How each symbol is written, and whether words put a space between
/// modules (they do as soon as one name is not a single character, so
/// that the longest-name rule cannot join two modules into one).
pub struct Spelling {
    spelled: Vec<String>,
    spaced: bool,
    /// The turtle set that needs the fewest lines ([`choose_set`]).
    set: TurtleSet,
}

/// The angle increments per turn that Fractint's `|` uses, as the reader
/// counts them from the file's angle.
fn divisions(sys: &System) -> u32 {
    let n = (std::f64::consts::TAU / sys.settings.delta).round();
    n.clamp(0.0, f64::from(u32::MAX)) as u32
}

/// What the reader gives the symbol `name` under `set` (docs/gft.md §3).
fn given(set: TurtleSet, name: &str, divisions: u32) -> Option<TurtleOp> {
    match set {
        TurtleSet::Fractint => vocabulary::fractint_op(name, divisions),
        _ if set.names().contains(&name) => vocabulary::op(set, name),
        _ => None,
    }
}

/// The symbols that need a `NAME = operation` line under `set` (those
/// whose operation is not the one the set gives), or `None` when the set
/// cannot say what the system does: Fractint gives a command its meaning
/// where it is used, so `c12 = nothing` would not hold.
fn overrides(sys: &System, occurring: &[SymbolId], set: TurtleSet) -> Option<Vec<SymbolId>> {
    let n = divisions(sys);
    let mut out = Vec::new();
    for &s in occurring {
        let info = sys.symbols.info(s);
        if info.guard.is_some() || sys.symbols.silent_key(s).is_some() {
            continue;
        }
        let op = sys.op(s);
        let set_op = given(set, &info.name, n);
        if op == set_op {
            continue;
        }
        if op.is_none() && set == TurtleSet::Fractint {
            return None;
        }
        out.push(s);
    }
    Some(out)
}

/// The turtle set whose file is shortest: the fewest override lines, and
/// a `turtle` line only when the set is not the default (pfg). Ties go to
/// the first set of [`TurtleSet::ALL`].
fn choose_set(sys: &System, occurring: &[SymbolId]) -> TurtleSet {
    let cost = |set: TurtleSet| {
        let lines = overrides(sys, occurring, set)?.len();
        Some(lines + usize::from(set != TurtleSet::Pfg))
    };
    TurtleSet::ALL
        .into_iter()
        .filter_map(|set| cost(set).map(|c| (c, set)))
        .min_by_key(|&(c, _)| c)
        .map_or(TurtleSet::None, |(_, set)| set)
}

/// Whether words written without spaces could be read back joined: the
/// set declares a longer name made of occurring one-character names
/// (cpfg's `@O` from `@` and `O`), or, with Fractint's set, a command
/// that takes a number could swallow an occurring digit, `.`, `q` or `i`.
fn set_would_join(sys: &System, occurring: &[SymbolId], set: TurtleSet) -> bool {
    let names: Vec<&str> = occurring
        .iter()
        .map(|&s| sys.symbols.name(s))
        .filter(|n| n.chars().count() == 1)
        .collect();
    let has = |c: char| names.iter().any(|n| n.starts_with(c));
    let longer = set.names().iter().filter(|n| n.chars().count() > 1);
    if longer.clone().any(|n| n.chars().all(has)) {
        return true;
    }
    set == TurtleSet::Fractint
        && names
            .iter()
            .any(|n| n.starts_with(vocabulary::fractint_takes_number))
        && names
            .iter()
            .any(|n| n.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '.' | 'q' | 'i')))
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
        let set = choose_set(sys, &mentioned);
        let spaced = set_would_join(sys, &mentioned, set)
            || mentioned.iter().any(|&s| {
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
        Spelling {
            spelled,
            spaced,
            set,
        }
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

    /// `turtle SET` (left out for pfg, the default), then what each
    /// symbol does where the set says otherwise: `NAME = operation`
    /// (`nothing` included), `silent KEY = operation` for silent symbols,
    /// `symbol …` for longer names that do nothing and the set does not
    /// declare.
    pub fn turtle(&self, out: &mut String, sys: &System) {
        if self.set != TurtleSet::Pfg {
            let _ = writeln!(out, "turtle {}", self.set.name());
        }
        let mut mentioned = sys.mentioned();
        let changed = overrides(sys, &mentioned, self.set).unwrap_or_default();
        // By name, not by id: ids follow the order a reader met the names,
        // which a file written this way changes; names make it canonical.
        mentioned.sort_by_key(|&s| match sys.symbols.silent_key(s) {
            Some(key) => (true, natural(key)),
            None => (false, natural(sys.symbols.name(s))),
        });
        let mut plain_names = Vec::new();
        for s in mentioned {
            let info = sys.symbols.info(s);
            let op = sys.op(s);
            let text = op.map_or("nothing".to_string(), |op| operation(sys, op));
            if let Some(key) = sys.symbols.silent_key(s) {
                let _ = writeln!(out, "silent {key} = {text}");
            } else if changed.contains(&s) {
                let name = self.name(s);
                if is_keyword(name) {
                    let _ = writeln!(out, "`{name}` = {text}");
                } else {
                    let _ = writeln!(out, "{name} = {text}");
                }
            } else if info.guard.is_none()
                && op.is_none()
                && info.name.chars().count() > 1
                && !self.set.names().contains(&info.name.as_str())
            {
                plain_names.push(self.name(s).to_string());
            }
        }
        if !plain_names.is_empty() {
            let _ = writeln!(out, "symbol {}", plain_names.join(" "));
        }
    }
}

/// A name as people sort it: `level-2` before `level-10`.
fn natural(name: &str) -> (String, u64, String) {
    let stem = name.trim_end_matches(|c: char| c.is_ascii_digit());
    let number = name[stem.len()..].parse().unwrap_or(0);
    (stem.to_string(), number, name.to_string())
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
        TurtleOp::SetTexture => "set-texture".into(),
        TurtleOp::Query(kind) => format!("query {}", query(kind)),
        TurtleOp::TurnUnswapped(a) => format!("turn-unswapped {}", angle(a)),
        TurtleOp::RotateReal(a) => format!("turn-real {}", angle(a)),
        TurtleOp::ForwardReal { draw } => word(draw, "forward-real", "move-real"),
        TurtleOp::SetColour(n) => format!("set-colour {n}"),
        TurtleOp::ShiftColour { by, up } => format!("colour-shift {}{by}", word(up, "+", "-")),
        TurtleOp::Elasticity { tropism, change } => elasticity(tropism, change),
        TurtleOp::Untwist => "untwist".into(),
        TurtleOp::KeepTwist => "keep-twist".into(),
        TurtleOp::SubLsystemCall => "sub-lsystem-call".into(),
        TurtleOp::SubLsystemReturn => "sub-lsystem-return".into(),
        TurtleOp::Label => "write-label".into(),
    }
}

fn query(kind: QueryKind) -> &'static str {
    match kind {
        QueryKind::Position => "position",
        QueryKind::Heading => "heading",
        QueryKind::Left => "left",
        QueryKind::Up => "up",
        QueryKind::Environment => "environment",
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
