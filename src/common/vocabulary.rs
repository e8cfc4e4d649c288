//! What each notation's symbols do to the turtle: the one place that says
//! it. The front ends lower their symbols through [`op`] (and Fractint's
//! numbered commands through [`fractint_op`]); the `.gft` notation names a
//! set with `turtle SET` and starts from it.

use crate::ir::{Angle, Axis, ElasticityChange, QueryKind, TurtleOp};

/// A named default turtle: what one notation's symbols do.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TurtleSet {
    Pfg,
    Linf,
    Stl,
    Cpfg,
    Fractint,
    /// No symbol does anything but the branch brackets.
    None,
}

impl TurtleSet {
    pub const ALL: [TurtleSet; 6] = [
        TurtleSet::Pfg,
        TurtleSet::Linf,
        TurtleSet::Stl,
        TurtleSet::Cpfg,
        TurtleSet::Fractint,
        TurtleSet::None,
    ];

    /// The set's name as `.gft` writes it (`turtle cpfg`).
    pub fn name(self) -> &'static str {
        match self {
            TurtleSet::Pfg => "pfg",
            TurtleSet::Linf => "linf",
            TurtleSet::Stl => "stl",
            TurtleSet::Cpfg => "cpfg",
            TurtleSet::Fractint => "fractint",
            TurtleSet::None => "none",
        }
    }

    pub fn from_name(name: &str) -> Option<TurtleSet> {
        TurtleSet::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The fixed names the set gives a meaning (Fractint's numbered
    /// commands aside: see [`fractint_op`]).
    pub fn names(self) -> &'static [&'static str] {
        match self {
            TurtleSet::Pfg => PFG,
            TurtleSet::Linf => LINF,
            TurtleSet::Stl => STL,
            TurtleSet::Cpfg => CPFG,
            TurtleSet::Fractint => FRACTINT,
            TurtleSet::None => &["[", "]"],
        }
    }
}

const PFG: &[&str] = &[
    "[", "]", "F", "f", "+", "-", "&", "^", "\\", "/", "|", "{", "}", "!", "'",
];
const LINF: &[&str] = &["[", "]", "{", "}", "!"];
const STL: &[&str] = &["[", "]", "F", "L", "R", "+", "-"];
const CPFG: &[&str] = &[
    "[", "]", "F", "G", "f", "g", "+", "-", "&", "^", "\\", "/", "|", ";", ",", "#", "!", "{", "}",
    ".", "@O", "@o", "@c", "@M", "@R", "@v", "@Gs", "@Gc", "@Ge", "@Gt", "@Gr", "@#", "@Ts", "@Ti",
    "@T", "@Td", "@Tp", "@Tf", "?P", "?H", "?L", "?U", "?E", "?", "$", "@L",
];
const FRACTINT: &[&str] = &["[", "]", "+", "-", "|", "!", "f", "g", "d", "m"];

/// What symbol `name` does in `set`; `None` when the set gives it no
/// meaning. Fractint's `|` is taken for an even number of increments per
/// turn (a turn-around); [`fractint_op`] knows the number.
pub fn op(set: TurtleSet, name: &str) -> Option<TurtleOp> {
    match set {
        TurtleSet::Pfg => pfg(name),
        TurtleSet::Linf => linf(name),
        TurtleSet::Stl => stl(name),
        TurtleSet::Cpfg => cpfg(name),
        TurtleSet::Fractint => fractint_op(name, 2),
        TurtleSet::None => brackets(name),
    }
}

fn rotate(axis: Axis, factor: f64) -> TurtleOp {
    TurtleOp::Rotate {
        axis,
        angle: Angle::Delta(factor),
    }
}

fn brackets(name: &str) -> Option<TurtleOp> {
    match name {
        "[" => Some(TurtleOp::Push),
        "]" => Some(TurtleOp::Pop),
        _ => None,
    }
}

/// The pfg turtle: Appendix A's `draw`, the 3D symbols of §2 Fig. 2.12,
/// and `{ } ! '` of §2 and §3.1.
fn pfg(name: &str) -> Option<TurtleOp> {
    Some(match name {
        "F" => TurtleOp::Forward { draw: true },
        "f" => TurtleOp::Forward { draw: false },
        "+" => rotate(Axis::Up, 1.0),
        "-" => rotate(Axis::Up, -1.0),
        "&" => rotate(Axis::Left, 1.0),
        "^" => rotate(Axis::Left, -1.0),
        "\\" => rotate(Axis::Heading, 1.0),
        "/" => rotate(Axis::Heading, -1.0),
        "|" => TurtleOp::TurnAround,
        "{" => TurtleOp::PolygonBegin,
        "}" => TurtleOp::PolygonEnd,
        "!" => TurtleOp::DecrementWidth,
        "'" => TurtleOp::NextColour,
        _ => return brackets(name),
    })
}

/// LinF's fixed symbols (its lines and rotations are declared per file).
fn linf(name: &str) -> Option<TurtleOp> {
    Some(match name {
        "{" => TurtleOp::NextColour,
        "}" => TurtleOp::PreviousColour,
        "!" => TurtleOp::SwapTurns,
        _ => return brackets(name),
    })
}

/// STL's drawing components: `L` and `+` turn left, `R` and `-` right.
fn stl(name: &str) -> Option<TurtleOp> {
    Some(match name {
        "F" => TurtleOp::Forward { draw: true },
        "L" | "+" => rotate(Axis::Up, -1.0),
        "R" | "-" => rotate(Axis::Up, 1.0),
        _ => return brackets(name),
    })
}

/// The cpfg turtle (interpret.c).
fn cpfg(name: &str) -> Option<TurtleOp> {
    let elasticity = |change| TurtleOp::Elasticity {
        tropism: None,
        change,
    };
    Some(match name {
        "F" | "G" => TurtleOp::Forward { draw: true },
        "f" | "g" => TurtleOp::Forward { draw: false },
        // `+` turns left (counter-clockwise seen from the default view).
        "+" => rotate(Axis::Up, -1.0),
        "-" => rotate(Axis::Up, 1.0),
        // cpfg's frame starts H = +y, L = −x, U = −z (interpret.c): its U
        // is the turtle's −U, and stays so when `&` tilts H towards cpfg's
        // U and `/` rolls L towards it.
        "&" => rotate(Axis::Left, -1.0),
        "^" => rotate(Axis::Left, 1.0),
        "\\" => rotate(Axis::Heading, 1.0),
        "/" => rotate(Axis::Heading, -1.0),
        "|" => TurtleOp::TurnAround,
        ";" => TurtleOp::ColourIndex { up: true },
        "," => TurtleOp::ColourIndex { up: false },
        "#" => TurtleOp::LineWidth { up: true },
        "!" => TurtleOp::LineWidth { up: false },
        "{" => TurtleOp::PolygonBegin,
        "}" => TurtleOp::PolygonEnd,
        "." => TurtleOp::PolygonVertex,
        "@O" => TurtleOp::Sphere,
        "@o" => TurtleOp::ScreenDisc,
        "@c" => TurtleOp::Circle,
        "@M" => TurtleOp::MoveTo,
        "@R" => TurtleOp::SetHeading,
        "@v" => TurtleOp::RollToVertical,
        "@Gs" => TurtleOp::CylinderStart,
        "@Gc" => TurtleOp::CylinderPoint { end: false },
        "@Ge" => TurtleOp::CylinderPoint { end: true },
        "@Gt" => TurtleOp::CylinderTangents,
        "@Gr" => TurtleOp::RadiusTangents,
        "@#" => TurtleOp::SetContour,
        "@Tx" => TurtleOp::SetTexture,
        // cpfg reads `@Ti`; the manual writes `@T`.
        "@Ts" => elasticity(ElasticityChange::Set),
        "@Ti" | "@T" => elasticity(ElasticityChange::Increase),
        "@Td" => elasticity(ElasticityChange::Decrease),
        "@Tp" => TurtleOp::Untwist,
        "@Tf" => TurtleOp::KeepTwist,
        "?P" => TurtleOp::Query(QueryKind::Position),
        "?H" => TurtleOp::Query(QueryKind::Heading),
        "?L" => TurtleOp::Query(QueryKind::Left),
        "?U" => TurtleOp::Query(QueryKind::Up),
        "?E" => TurtleOp::Query(QueryKind::Environment),
        "?" => TurtleOp::SubLsystemCall,
        "$" => TurtleOp::SubLsystemReturn,
        "@L" => TurtleOp::Label,
        _ => return brackets(name),
    })
}

/// What a Fractint command does (lowercased, with its number: `c12`,
/// `\30`, `@0.5`); `n` is the entry's angle increments per turn.
pub fn fractint_op(cmd: &str, n: u32) -> Option<TurtleOp> {
    let first = cmd.chars().next()?;
    let colour = |v: f64| v.min(f64::from(u32::MAX)) as u32;
    Some(match first {
        // Fractint's `+` turns counter-clockwise: graftal's positive turns
        // are clockwise.
        '+' => rotate(Axis::Up, -1.0),
        '-' => rotate(Axis::Up, 1.0),
        '|' if n % 2 == 0 => TurtleOp::TurnAround,
        '|' => TurtleOp::TurnUnswapped(Angle::Delta(f64::from(n / 2))),
        '!' => TurtleOp::SwapTurns,
        '[' => TurtleOp::Push,
        ']' => TurtleOp::Pop,
        'f' => TurtleOp::Forward { draw: true },
        'g' => TurtleOp::Forward { draw: false },
        'd' => TurtleOp::ForwardReal { draw: true },
        'm' => TurtleOp::ForwardReal { draw: false },
        '\\' => TurtleOp::RotateReal(Angle::Radians(-fractint_number(cmd).to_radians())),
        '/' => TurtleOp::RotateReal(Angle::Radians(fractint_number(cmd).to_radians())),
        '@' => TurtleOp::ScaleLength(fractint_number(cmd)),
        'c' => TurtleOp::SetColour(colour(fractint_number(cmd))),
        '<' => TurtleOp::ShiftColour {
            by: colour(fractint_number(cmd)),
            up: true,
        },
        '>' => TurtleOp::ShiftColour {
            by: colour(fractint_number(cmd)),
            up: false,
        },
        _ => return None,
    })
}

/// Whether `c` starts a Fractint command that takes a number.
pub fn fractint_takes_number(c: char) -> bool {
    matches!(c, '\\' | '/' | '@' | 'c' | '<' | '>')
}

/// The number of a command: Fractint's `getnumber` — after the command
/// character, up to two prefixes `q` (square root) and `i` (inverse), then
/// the longest number `atof` reads from `[0-9.]*`; a value that is not
/// positive is 0 (Fractint 19's sanity check, before the prefixes apply).
pub fn fractint_number(cmd: &str) -> f64 {
    let rest = &cmd[cmd.char_indices().nth(1).map_or(cmd.len(), |(i, _)| i)..];
    let digits_at = rest
        .find(|c: char| c != 'q' && c != 'i')
        .unwrap_or(rest.len());
    let (prefix, digits) = rest.split_at(digits_at);
    // atof: digits, at most one point, more digits.
    let mut end = 0;
    let mut point = false;
    for (i, c) in digits.char_indices() {
        if c == '.' && !point {
            point = true;
        } else if !c.is_ascii_digit() {
            break;
        }
        end = i + 1;
    }
    let mut v: f64 = digits[..end].parse().unwrap_or(0.0);
    if v.is_nan() || v <= 0.0 || v.is_infinite() {
        return 0.0;
    }
    if prefix.contains('q') {
        v = v.sqrt();
    }
    if prefix.contains('i') {
        v = 1.0 / v;
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_listed_name_has_a_meaning_and_sets_have_names() {
        for set in TurtleSet::ALL {
            assert_eq!(TurtleSet::from_name(set.name()), Some(set));
            for name in set.names() {
                assert!(op(set, name).is_some(), "{} {name}", set.name());
            }
        }
        assert_eq!(op(TurtleSet::None, "F"), None);
    }

    #[test]
    fn the_sets_differ_where_the_notations_do() {
        // pfg's `+` turns right, cpfg's and Fractint's left.
        assert_eq!(op(TurtleSet::Pfg, "+"), Some(rotate(Axis::Up, 1.0)));
        assert_eq!(op(TurtleSet::Cpfg, "+"), Some(rotate(Axis::Up, -1.0)));
        assert_eq!(
            fractint_op("|", 7),
            Some(TurtleOp::TurnUnswapped(Angle::Delta(3.0)))
        );
        assert_eq!(fractint_op("c12", 4), Some(TurtleOp::SetColour(12)));
        assert_eq!(fractint_number("@i4"), 0.25);
    }
}
