//! What the emitters walk alike: the symbols that occur and what each does
//! to the turtle, the turning angle written as repeated turn symbols, a
//! word written symbol by symbol, and the constructs a target drops,
//! reported in the same words by every target that drops them.

use super::{angle_factor, multiples, number, occurring, repeated, turns, Emitter, Kind, Turns};
use crate::ir::{Angle, Axis, Guard, Span, SymbolId, System, TurtleOp};
use std::collections::HashMap;

/// The symbols that occur in a system (see [`occurring`]), as the
/// emitters walk them.
pub struct Symbols {
    /// All of them, in symbol-table order.
    pub all: Vec<SymbolId>,
    /// Those without a guard, in the same order.
    pub plain: Vec<SymbolId>,
    /// Those with one (LinF `p?s`), with it.
    pub guarded: Vec<(SymbolId, Guard)>,
}

impl Symbols {
    pub fn of(sys: &System) -> Self {
        let all = occurring(sys);
        let mut plain = Vec::new();
        let mut guarded = Vec::new();
        for &s in &all {
            match sys.symbols.info(s).guard {
                None => plain.push(s),
                Some(g) => guarded.push((s, g)),
            }
        }
        Symbols {
            all,
            plain,
            guarded,
        }
    }

    /// The plain symbols `spell` has no spelling for yet, in order.
    pub fn unspelled<T>(&self, spell: &HashMap<SymbolId, T>) -> Vec<SymbolId> {
        let todo = self.plain.iter().copied();
        todo.filter(|s| !spell.contains_key(s)).collect()
    }
}

/// What a symbol does to the turtle, in the classes the emitters tell
/// apart.
#[derive(Clone, Copy, Debug)]
pub enum Does {
    /// Nothing: a symbol that is only rewritten.
    Nothing,
    Forward {
        draw: bool,
    },
    /// A rotation, a (torsion, curvature) pair or a half turn: the
    /// operation, for [`turns`].
    Turn(TurtleOp),
    Push,
    Pop,
    Polygon {
        begin: bool,
    },
    /// Makes lines thinner.
    Thinner,
    /// Steps to the next (or back to the previous) colour.
    Colour {
        next: bool,
    },
    /// Exchanges the two directions of turning.
    Swap,
    /// Scales the step length.
    Length(f64),
    /// A stem length (STL levels).
    Stem,
    /// An operation only Fractint has (replaced before emitting where that
    /// means the same, see `common_operations`).
    Fractint,
    /// cpfg's own turtle commands: parametric systems are refused before
    /// any emitter runs (see [`super::translate`]).
    Cpfg,
}

/// The class of `op` (`None`: the symbol does nothing).
pub fn does(op: Option<TurtleOp>) -> Does {
    let Some(op) = op else {
        return Does::Nothing;
    };
    match op {
        TurtleOp::Forward { draw } => Does::Forward { draw },
        TurtleOp::Rotate { .. } | TurtleOp::Frenet { .. } | TurtleOp::TurnAround => Does::Turn(op),
        TurtleOp::Push => Does::Push,
        TurtleOp::Pop => Does::Pop,
        TurtleOp::PolygonBegin => Does::Polygon { begin: true },
        TurtleOp::PolygonEnd => Does::Polygon { begin: false },
        TurtleOp::DecrementWidth => Does::Thinner,
        TurtleOp::NextColour => Does::Colour { next: true },
        TurtleOp::PreviousColour => Does::Colour { next: false },
        TurtleOp::SwapTurns => Does::Swap,
        TurtleOp::ScaleLength(x) => Does::Length(x),
        TurtleOp::Stem { .. } => Does::Stem,
        TurtleOp::TurnUnswapped(_)
        | TurtleOp::RotateReal(_)
        | TurtleOp::ForwardReal { .. }
        | TurtleOp::SetColour(_)
        | TurtleOp::ShiftColour { .. } => Does::Fractint,
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
        | TurtleOp::RadiusTangents
        | TurtleOp::Query(_)
        | TurtleOp::Elasticity { .. }
        | TurtleOp::Untwist
        | TurtleOp::KeepTwist
        | TurtleOp::SetContour
        | TurtleOp::SetTexture
        | TurtleOp::SubLsystemCall
        | TurtleOp::SubLsystemReturn
        | TurtleOp::Label => Does::Cpfg,
    }
}

/// A symbol being spelled.
pub struct Sym {
    pub id: SymbolId,
    /// Its name in the source.
    pub name: String,
    /// Where it is first written.
    pub span: Option<Span>,
    pub does: Does,
}

/// Each of `syms`, in order, with what `spell` writes for it (`None`: the
/// symbol is left unspelled).
pub fn spell_each<'a>(
    e: &mut Emitter<'a>,
    syms: impl IntoIterator<Item = SymbolId>,
    mut spell: impl FnMut(&mut Emitter<'a>, &Sym) -> Option<String>,
) -> Vec<(Sym, String)> {
    let mut out = Vec::new();
    for id in syms {
        let sym = Sym {
            id,
            name: e.name(id).to_string(),
            span: e.symbol_span(id),
            does: does(e.sys.op(id)),
        };
        if let Some(text) = spell(e, &sym) {
            out.push((sym, text));
        }
    }
    out
}

/// A word written symbol by symbol: `spell` gives each symbol's text
/// (`None` for nothing), `join` puts the texts together so that the target
/// reads them back as the same symbols.
pub fn write_word<T>(
    w: &[SymbolId],
    spell: impl FnMut(SymbolId) -> Option<T>,
    join: impl FnOnce(Vec<T>) -> String,
) -> String {
    join(w.iter().copied().filter_map(spell).collect())
}

/// How deep brackets `[ ]` and braces `{ }` nest in `text` as written (each
/// opener one level deeper until its closer): what a target's reader
/// descends into, at most [`crate::ir::MAX_NESTING`] deep.
pub fn nesting_of(text: &str) -> usize {
    let (mut depth, mut deepest) = (0usize, 0usize);
    for c in text.chars() {
        match c {
            '[' | '{' => {
                depth += 1;
                deepest = deepest.max(depth);
            }
            ']' | '}' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    deepest
}

/// How many colours the system lists, a run of the same colour counted
/// once: more than one means its colour symbols change the colour.
pub fn distinct_colours(sys: &System) -> usize {
    let mut c = sys.colours.clone();
    c.dedup();
    c.len()
}

// ---------------------------------------------------------------------
// Turning by repeated turn symbols (pfg, STL)
// ---------------------------------------------------------------------

/// How a target that turns by whole multiples of one angle takes the
/// turns of a system.
pub struct Turning<'t> {
    /// The target's name, in messages.
    pub target: &'t str,
    /// Why an interval angle is a problem, e.g. "pfg turns by fixed angles".
    pub fixed: &'t str,
    /// Whether the problem states the middle of the interval in degrees.
    pub middle_in_degrees: bool,
    /// Whether the target draws in the plane: turns about other axes than
    /// U are reported and do not count.
    pub plane: bool,
}

/// The angle factor n for the turns of `syms` (see [`angle_factor`]),
/// reporting interval angles and, for a target in the plane, rotations
/// out of it.
pub fn turning(e: &mut Emitter<'_>, syms: &[SymbolId], how: &Turning<'_>) -> u64 {
    let sys = e.sys;
    let mut by_symbol = Vec::new();
    for &s in syms {
        let Some(op) = sys.op(s) else { continue };
        let t = match turns(sys, op) {
            Some(Turns::Fixed(t)) => t,
            Some(Turns::Random(t)) => {
                let middle = if how.middle_in_degrees && !t.is_empty() {
                    let mid: Vec<String> = t
                        .iter()
                        .map(|x| crate::number::readable(x.1.to_degrees()))
                        .collect();
                    format!(" ({} degrees)", mid.join(", "))
                } else {
                    String::new()
                };
                let written = intervals(sys, op).join(" and ");
                e.problem(
                    Kind::Interval,
                    e.symbol_span(s),
                    format!(
                        "the interval angle {written} of `{}`: {}",
                        e.name(s),
                        how.fixed
                    ),
                    format!("the middle of the interval is used{middle}"),
                );
                t
            }
            None => continue,
        };
        for (axis, a) in t {
            if !how.plane || axis == Axis::Up {
                by_symbol.push((s, a.abs()));
            } else {
                e.problem(
                    Kind::ThreeD,
                    e.symbol_span(s),
                    format!(
                        "`{}` rotates out of the plane: {} draws in 2D",
                        e.name(s),
                        how.target
                    ),
                    "the rotation out of the plane is dropped",
                );
            }
        }
    }
    angle_factor(e, &by_symbol, how.target)
}

/// The interval angles of `op` as LinF writes them (`[0 2*pi]`), each in
/// backquotes: a rotation's torsion before its curvature.
fn intervals(sys: &System, op: TurtleOp) -> Vec<String> {
    let angles = match op {
        TurtleOp::Rotate { angle, .. } => vec![angle],
        TurtleOp::Frenet { rotation, .. } => sys
            .rotations
            .get(rotation.0 as usize)
            .map_or_else(Vec::new, |r| vec![r.torsion, r.curvature]),
        _ => Vec::new(),
    };
    angles
        .into_iter()
        .filter_map(|a| match a {
            Angle::Uniform { lo, hi } => {
                Some(format!("`{}`", crate::number::radians_interval(lo, hi)))
            }
            _ => None,
        })
        .collect()
}

/// The turns of `op` (symbol `s`) with the angle factor `n`: each rotation
/// as `letter(axis, positive)` repeated (none: the rotation is left out),
/// or, with a `half_turn` symbol, a half turn about U as that symbol.
pub fn turn_text(
    e: &mut Emitter<'_>,
    s: SymbolId,
    op: TurtleOp,
    n: u64,
    half_turn: Option<char>,
    letter: impl Fn(Axis, bool) -> Option<char>,
) -> String {
    let t = match turns(e.sys, op) {
        Some(Turns::Fixed(t)) | Some(Turns::Random(t)) => t,
        None => Vec::new(),
    };
    let mut out = String::new();
    for (axis, a) in t {
        let k = multiples(a, n);
        match half_turn {
            Some(h) if axis == Axis::Up && k.unsigned_abs() * 2 == n => out.push(h),
            _ => {
                if let Some(c) = letter(axis, k > 0) {
                    out.push_str(&repeated(e, s, c, k));
                }
            }
        }
    }
    out
}

// ---------------------------------------------------------------------
// What targets drop, in the same words
// ---------------------------------------------------------------------

/// Reports symbol `sym` as something the target drops (see
/// [`Emitter::problem`]): nothing is written for it.
pub fn dropped(
    e: &mut Emitter<'_>,
    sym: &Sym,
    kind: Kind,
    what: impl Into<String>,
    change: impl Into<String>,
) -> String {
    e.problem(kind, sym.span.clone(), what, change);
    String::new()
}

/// A polygon symbol, for a target without filled polygons (its edges are
/// drawn `edges`): nothing written.
pub fn no_polygons(e: &mut Emitter<'_>, sym: &Sym, target: &str, edges: &str) -> String {
    dropped(
        e,
        sym,
        Kind::Attribute,
        format!(
            "the polygon symbol `{}`: {target} has no filled polygons",
            sym.name
        ),
        format!("the polygon is dropped; its edges are drawn {edges}"),
    )
}

/// A symbol making lines thinner, for a target that cannot (`why`):
/// nothing written.
pub fn no_widths(e: &mut Emitter<'_>, sym: &Sym, why: &str) -> String {
    dropped(
        e,
        sym,
        Kind::Attribute,
        format!("`{}` makes lines thinner: {why}", sym.name),
        "it is dropped",
    )
}

/// A length factor `x`, for a target without them (`why`; a factor of 1
/// is no problem): nothing written.
pub fn no_length_factor(e: &mut Emitter<'_>, sym: &Sym, x: f64, why: &str) -> String {
    if x == 1.0 {
        return String::new();
    }
    // A factor made for an STL source's stem levels is told as the STL
    // file wrote it: one problem for all its levels.
    if let Some(line) = e.written.get(&sym.id).cloned() {
        return dropped(
            e,
            sym,
            Kind::Length,
            format!("the stem lengths `{line}` differ from level to level: {why}"),
            "every stem is drawn the same length",
        );
    }
    dropped(
        e,
        sym,
        Kind::Length,
        format!("the length factor `{}`: {why}", sym.name),
        "the factor is dropped",
    )
}

/// A stem length, for a target without them (`why`): nothing written.
pub fn no_stems(e: &mut Emitter<'_>, sym: &Sym, why: &str) -> String {
    dropped(
        e,
        sym,
        Kind::Length,
        format!("a stem length: {why}"),
        "it is dropped",
    )
}

/// A guarded symbol `s`, for a target without per-occurrence probability
/// (`why`): it is written as its base.
pub fn no_chance(e: &mut Emitter<'_>, s: SymbolId, g: Guard, why: &str) {
    e.problem(
        Kind::Guard,
        e.symbol_span(s),
        format!(
            "`{}` expands with probability {}: {why}",
            e.name(s),
            number(g.probability)
        ),
        format!("`{}` is always expanded", e.name(g.base)),
    );
}

/// A scale factor other than 100, for a target whose pictures fill the
/// frame (`why`).
pub fn no_scale(e: &mut Emitter<'_>, why: &str) {
    let scale = e.sys.settings.scale;
    if scale != 100.0 {
        e.problem(
            Kind::Attribute,
            None,
            format!("the scale factor {}: {why}", number(scale)),
            "the figure fills the picture",
        );
    }
}

/// What an emitter writes for an operation only Fractint has (they are
/// replaced before emitting, see `common_operations`): a problem,
/// nothing written.
pub fn fractint_only(e: &mut Emitter<'_>, sym: &Sym, to: &str) -> String {
    dropped(
        e,
        sym,
        Kind::Attribute,
        format!(
            "the Fractint command `{}`: {to} has no such command",
            sym.name
        ),
        "it is dropped",
    )
}
