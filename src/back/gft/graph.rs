//! An object-instancing graph as a `graph { … }` block (docs/gft.md §13).
//!
//! Each symbol's lines come in the symbol's order (its rule, its
//! geometries, its alternative; `symbol NAME` for one with none of them),
//! since the reader numbers symbols by the lines that introduce them.
//! A transform is written in the simplest steps that give its matrix back
//! bit for bit through [`Affine::compose`], as the reader composes them
//! (a translation, a scaling, a rotation about an axis, and their
//! compositions), else as `matrix (…)`; the identity is not written.

use super::expr::num;
use super::look::hex;
use crate::ir::graph::{
    Affine, Finish, Instance, InstancingGraph, Point, Primitive, Shape, DEFAULT_SHAPE_COLOUR,
};
use crate::number;
use std::fmt::Write;

/// `graph { … }`.
pub fn graph(out: &mut String, g: &InstancingGraph) {
    out.push_str("graph {\n");
    if !g.axiom.is_empty() {
        out.push_str(&wrapped("  axiom", couples(g, &g.axiom)));
    }
    for sym in &g.symbols {
        let name = symbol_name(&sym.name);
        if sym.rule.is_none() && sym.geometry.is_empty() && sym.alternative.is_none() {
            let _ = writeln!(out, "  symbol {name}");
        }
        if let Some(rule) = &sym.rule {
            out.push_str(&wrapped(&format!("  {name} ->"), couples(g, rule)));
        }
        for s in &sym.geometry {
            let _ = writeln!(out, "  geometry {name} = {}", shape(s));
        }
        if let Some(alt) = &sym.alternative {
            for (k, s) in alt.shapes.iter().enumerate() {
                let below = if k == 0 && alt.below_pixels.to_bits() != 1f64.to_bits() {
                    format!(" below {}", num(alt.below_pixels))
                } else {
                    String::new()
                };
                let _ = writeln!(out, "  alternative {name}{below} = {}", shape(s));
            }
        }
    }
    out.push_str("}\n");
}

/// A symbol's name: bare when it reads back as one identifier, else in
/// backquotes.
fn symbol_name(name: &str) -> String {
    let identifier = name.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if identifier {
        name.to_string()
    } else {
        format!("`{name}`")
    }
}

/// The widest a line of couples grows before the next couple that
/// starts with `[` goes on a line of its own.
const WIDTH: usize = 100;

/// `head` and the couples, one line ended by a line break; a long line
/// goes on, under its first couple, on lines that start with `[` (the
/// reader joins them to the line above).
fn wrapped(head: &str, couples: Vec<String>) -> String {
    let mut out = head.to_string();
    let mut width = head.len();
    for c in couples {
        if width + 1 + c.len() > WIDTH && c.starts_with('[') && width > head.len() {
            out.push('\n');
            out.push_str(&" ".repeat(head.len()));
            width = head.len();
        }
        out.push(' ');
        out.push_str(&c);
        width += 1 + c.len();
    }
    out.push('\n');
    out
}

fn couples(g: &InstancingGraph, instances: &[Instance]) -> Vec<String> {
    instances
        .iter()
        .map(|i| {
            let name = symbol_name(&g.symbols[i.symbol].name);
            match transform(&i.transform) {
                None => name,
                Some(t) => format!("[{t}]({name})"),
            }
        })
        .collect()
}

fn point(p: Point) -> String {
    format!("({}, {}, {})", num(p[0]), num(p[1]), num(p[2]))
}

/// An angle in degrees when a decimal of degrees gives it back, else in
/// radians (`0.5rad`).
fn angle(radians: f64) -> String {
    let d = number::degrees(radians);
    let exact = d
        .parse::<f64>()
        .is_ok_and(|d| d.to_radians().to_bits() == radians.to_bits());
    if exact && !(radians == 0.0 && radians.is_sign_negative()) {
        d
    } else {
        format!("{}rad", num(radians))
    }
}

/// The steps of a candidate writing, with the matrix the reader makes of
/// them.
struct Steps {
    text: Vec<String>,
    affines: Vec<Affine>,
}

impl Steps {
    fn new() -> Self {
        Steps {
            text: Vec::new(),
            affines: Vec::new(),
        }
    }

    fn push(&mut self, text: String, a: Affine) {
        self.text.push(text);
        self.affines.push(a);
    }
}

/// The linear part of `a` as steps: a scaling, or a rotation about an
/// axis times a uniform scaling, when its zeros say it may be one.
fn linear(a: &Affine) -> Vec<Steps> {
    let m = &a.0;
    let mut out = Vec::new();
    let linear_identity = (0..3).all(|i| (0..3).all(|j| m[i][j] == f64::from(u8::from(i == j))));
    if linear_identity {
        out.push(Steps::new());
    }
    let off_diagonal_zero = (0..3).all(|i| (0..3).all(|j| i == j || m[i][j] == 0.0));
    if off_diagonal_zero {
        let s = [m[0][0], m[1][1], m[2][2]];
        let mut steps = Steps::new();
        let uniform = s[1].to_bits() == s[0].to_bits() && s[2].to_bits() == s[0].to_bits();
        let text = if uniform {
            format!("scale {}", num(s[0]))
        } else {
            format!("scale {}", point(s))
        };
        steps.push(text, Affine::scale(s));
        out.push(steps);
    }
    // A rotation about axis `k` times a uniform scaling: row and column
    // `k` are zero off the diagonal.
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        let apart = (0..3).all(|i| i == k || (m[i][k] == 0.0 && m[k][i] == 0.0));
        let scale = m[k][k];
        if !apart || scale == 0.0 || !scale.is_finite() {
            continue;
        }
        let (p, q) = ((k + 1) % 3, (k + 2) % 3);
        let theta = (m[q][p] / scale).atan2(m[p][p] / scale);
        let mut unit = [0.0; 3];
        unit[k] = 1.0;
        let Some(r) = Affine::rotate(unit, theta) else {
            continue;
        };
        let mut steps = Steps::new();
        steps.push(format!("rotate {axis} {}", angle(theta)), r);
        if scale.to_bits() != 1f64.to_bits() {
            steps.push(format!("scale {}", num(scale)), Affine::scale([scale; 3]));
        }
        out.push(steps);
    }
    out
}

/// `a` as the text between `[` and `]`; `None` for the identity.
pub fn transform(a: &Affine) -> Option<String> {
    if a.same_bits(&Affine::IDENTITY) {
        return None;
    }
    let t = [a.0[0][3], a.0[1][3], a.0[2][3]];
    let moved = t.iter().any(|x| x.to_bits() != 0f64.to_bits());
    for lin in linear(a) {
        let mut steps = Steps::new();
        if moved {
            steps.push(format!("translate {}", point(t)), Affine::translate(t));
        }
        steps.text.extend(lin.text);
        steps.affines.extend(lin.affines);
        if !steps.affines.is_empty() && Affine::compose(&steps.affines).same_bits(a) {
            return Some(steps.text.join(" "));
        }
    }
    let rows: Vec<String> = (a.0.iter()).map(|r| r.map(num).join(" ")).collect();
    Some(format!("matrix ({})", rows.join(", ")))
}

/// `KIND ARGS [#rrggbb] [FINISH X]…`.
pub fn shape(s: &Shape) -> String {
    let mut out = match &s.primitive {
        Primitive::Sphere { centre, radius } => {
            format!("sphere {} {}", point(*centre), num(*radius))
        }
        Primitive::Box { min, max } => format!("box {} {}", point(*min), point(*max)),
        Primitive::Cylinder { base, top, radius } => {
            format!("cylinder {} {} {}", point(*base), point(*top), num(*radius))
        }
        Primitive::Cone {
            base,
            top,
            base_radius,
            top_radius,
        } => {
            let mut c = format!(
                "cone {} {} {}",
                point(*base),
                point(*top),
                num(*base_radius)
            );
            if top_radius.to_bits() != 0f64.to_bits() {
                let _ = write!(c, " {}", num(*top_radius));
            }
            c
        }
        Primitive::Disc {
            centre,
            normal,
            radius,
        } => format!(
            "disc {} {} {}",
            point(*centre),
            point(*normal),
            num(*radius)
        ),
        Primitive::Triangle(t) => {
            format!("triangle {} {} {}", point(t[0]), point(t[1]), point(t[2]))
        }
        Primitive::Polygon(ps) => {
            let ps: Vec<String> = ps.iter().map(|p| point(*p)).collect();
            format!("polygon {}", ps.join(" "))
        }
    };
    if s.colour != DEFAULT_SHAPE_COLOUR {
        let _ = write!(out, " {}", hex(s.colour));
    }
    let d = Finish::default();
    let f = &s.finish;
    for (word, v, default) in [
        ("ambient", f.ambient, d.ambient),
        ("diffuse", f.diffuse, d.diffuse),
        ("specular", f.specular, d.specular),
        ("shininess", f.shininess, d.shininess),
    ] {
        if v.to_bits() != default.to_bits() {
            let _ = write!(out, " {word} {}", num(v));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transforms_are_written_in_the_simplest_exact_steps() {
        assert_eq!(transform(&Affine::IDENTITY), None);
        let t = Affine::translate([1.0, 0.0, -2.5]);
        assert_eq!(transform(&t).unwrap(), "translate (1, 0, -2.5)");
        let s = Affine::scale([0.5; 3]);
        assert_eq!(transform(&s).unwrap(), "scale 0.5");
        let ts = Affine::compose(&[t, s]);
        assert_eq!(transform(&ts).unwrap(), "translate (1, 0, -2.5) scale 0.5");
        let r = Affine::rotate([0.0, 1.0, 0.0], 30f64.to_radians()).unwrap();
        assert_eq!(transform(&r).unwrap(), "rotate y 30");
        let rs = Affine::compose(&[r, Affine::scale([0.25; 3])]);
        assert_eq!(transform(&rs).unwrap(), "rotate y 30 scale 0.25");
        let k = Affine::shear(0, 1, 0.5);
        assert_eq!(
            transform(&k).unwrap(),
            "matrix (1 0.5 0 0, 0 1 0 0, 0 0 1 0)"
        );
    }
}
