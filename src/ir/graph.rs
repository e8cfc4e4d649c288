//! Object-instancing graphs: Bekaert & Willems' "IFS codes with
//! restrictions" (WSCG '94, §2.2).
//!
//! A graph is a parallel rewriting system over *couples* `w(A)`: a symbol
//! `A` placed by an affine transform `w`. A rule `A -> w1(B1) … wn(Bn)` says
//! that the object `A` is made of instances of `B1 … Bn` placed by
//! `w1 … wn`; a symbol without a rule is a terminal and must carry a
//! geometry (unless no symbol has one: then the graph is a pure IFS and the
//! limit object is drawn as the images of its bounding volume). Applying
//! the rule to `w(A)` gives `(w∘w1)(B1) … (w∘wn)(Bn)`. The graph is never
//! expanded into a word: the ray tracer ([`crate::raytrace`]) and the
//! attractor drawer ([`crate::render::attractor`]) expand only the couples
//! they need, down to a pixel.
//!
//! IFS codes (one symbol, n loops), IFS codes with condensation sets (a
//! loop symbol with one edge to a terminal) and hierarchical IFS codes
//! (levels of loop symbols) are special cases. Any front end can lower into
//! this construct: `.gft` `graph` blocks and Fractint's `.ifs` libraries do.

use super::Rgb;
use serde::Serialize;

/// A point or a direction in space.
pub type Point = [f64; 3];

/// An affine transform of space: `x' = M x + t`, stored as the three rows
/// of the 3x4 matrix `[M | t]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Affine(pub [[f64; 4]; 3]);

impl Affine {
    pub const IDENTITY: Affine = Affine([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ]);

    pub fn translate(v: Point) -> Affine {
        let mut a = Affine::IDENTITY;
        for (row, x) in a.0.iter_mut().zip(v) {
            row[3] = x;
        }
        a
    }

    /// A scaling by `s` along each axis (uniform when the three agree).
    pub fn scale(s: Point) -> Affine {
        let mut a = Affine::IDENTITY;
        for (i, row) in a.0.iter_mut().enumerate() {
            row[i] = s[i];
        }
        a
    }

    /// A rotation by `angle` radians about `axis` (right-handed: counter-
    /// clockwise seen from the axis' tip). `None` for a zero axis.
    pub fn rotate(axis: Point, angle: f64) -> Option<Affine> {
        let n = norm(axis);
        if !(n > 0.0 && n.is_finite()) {
            return None;
        }
        let [x, y, z] = axis.map(|c| c / n);
        let (s, c) = angle.sin_cos();
        let k = 1.0 - c;
        Some(Affine([
            [c + x * x * k, x * y * k - z * s, x * z * k + y * s, 0.0],
            [y * x * k + z * s, c + y * y * k, y * z * k - x * s, 0.0],
            [z * x * k - y * s, z * y * k + x * s, c + z * z * k, 0.0],
        ]))
    }

    /// A shear: coordinate `i` gains `factor` times coordinate `j`
    /// (`shear x y 0.5`: x' = x + 0.5 y).
    pub fn shear(i: usize, j: usize, factor: f64) -> Affine {
        let mut a = Affine::IDENTITY;
        a.0[i][j] += factor;
        a
    }

    /// `self ∘ other`: `other` applied first.
    pub fn then_after(&self, other: &Affine) -> Affine {
        let (a, b) = (&self.0, &other.0);
        let mut out = [[0.0; 4]; 3];
        for i in 0..3 {
            for j in 0..4 {
                let mut s = if j == 3 { a[i][3] } else { 0.0 };
                for (k, brow) in b.iter().enumerate() {
                    s += a[i][k] * brow[j];
                }
                out[i][j] = s;
            }
        }
        Affine(out)
    }

    pub fn apply(&self, p: Point) -> Point {
        let m = &self.0;
        [0, 1, 2].map(|i| m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3])
    }

    /// The linear part applied to a direction.
    pub fn apply_vector(&self, v: Point) -> Point {
        let m = &self.0;
        [0, 1, 2].map(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
    }

    pub fn determinant(&self) -> f64 {
        let m = &self.0;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }

    /// The inverse, or `None` when the transform is singular (it flattens
    /// space, relative to its own size, to below 1e-12).
    pub fn inverse(&self) -> Option<Affine> {
        let m = &self.0;
        let det = self.determinant();
        let size = self.norm_bound().max(f64::MIN_POSITIVE);
        if !det.is_finite() || det.abs() <= 1e-12 * size * size * size {
            return None;
        }
        let c = |r0: usize, r1: usize, c0: usize, c1: usize| {
            m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
        };
        let inv = [
            [c(1, 2, 1, 2), -c(0, 2, 1, 2), c(0, 1, 1, 2)],
            [-c(1, 2, 0, 2), c(0, 2, 0, 2), -c(0, 1, 0, 2)],
            [c(1, 2, 0, 1), -c(0, 2, 0, 1), c(0, 1, 0, 1)],
        ];
        let mut out = [[0.0; 4]; 3];
        for i in 0..3 {
            for j in 0..3 {
                out[i][j] = inv[i][j] / det;
            }
            out[i][3] = -(0..3).map(|k| out[i][k] * m[k][3]).sum::<f64>();
        }
        Some(Affine(out))
    }

    /// An upper bound on how much the transform stretches any length (its
    /// spectral norm): `sqrt(‖M‖₁ ‖M‖∞)`, cheap enough for every couple a
    /// ray meets.
    pub fn norm_bound(&self) -> f64 {
        let m = &self.0;
        let rows = (0..3).map(|i| (0..3).map(|j| m[i][j].abs()).sum::<f64>());
        let cols = (0..3).map(|j| (0..3).map(|i| m[i][j].abs()).sum::<f64>());
        let inf = rows.fold(0.0, f64::max);
        let one = cols.fold(0.0, f64::max);
        (inf * one).sqrt()
    }

    /// The factor by which the transform stretches its longest direction
    /// (the largest singular value of its linear part): the square root of
    /// the largest eigenvalue of `MᵀM`, in closed form (Smith's formula for
    /// symmetric 3x3 matrices), exact where power iteration crawls.
    pub fn contraction(&self) -> f64 {
        let m = &self.0;
        let mut a = [[0.0; 3]; 3];
        for (i, row) in a.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (0..3).map(|k| m[k][i] * m[k][j]).sum();
            }
        }
        let p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        let q = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
        let p2 = (0..3).map(|i| (a[i][i] - q) * (a[i][i] - q)).sum::<f64>() + 2.0 * p1;
        let p = (p2 / 6.0).sqrt();
        let largest = if p == 0.0 || !p.is_finite() {
            q
        } else {
            let b = |i: usize, j: usize| (a[i][j] - if i == j { q } else { 0.0 }) / p;
            let det = b(0, 0) * (b(1, 1) * b(2, 2) - b(1, 2) * b(2, 1))
                - b(0, 1) * (b(1, 0) * b(2, 2) - b(1, 2) * b(2, 0))
                + b(0, 2) * (b(1, 0) * b(2, 1) - b(1, 1) * b(2, 0));
            let phi = (det / 2.0).clamp(-1.0, 1.0).acos() / 3.0;
            q + 2.0 * p * phi.cos()
        };
        largest.max(0.0).sqrt()
    }

    /// The inverse, with a singular transform first thickened: each
    /// direction it flattens is kept at 1/1000 of its largest stretch, so
    /// what it places (the stem of Barnsley's fern, the image of the whole
    /// fern under a map of rank one) is a thin solid a ray can meet.
    pub fn inverse_thickened(&self) -> Affine {
        if let Some(inv) = self.inverse() {
            return inv;
        }
        let eps = 1e-3 * self.contraction().max(f64::MIN_POSITIVE);
        let mut thick = *self;
        for i in 0..3 {
            thick.0[i][i] += if thick.0[i][i] < 0.0 { -eps } else { eps };
        }
        thick.inverse().unwrap_or_else(|| {
            let mut scaled = Affine::scale([1.0 / eps; 3]);
            for (i, row) in scaled.0.iter_mut().enumerate() {
                row[3] = -self.0[i][3] / eps;
            }
            scaled
        })
    }

    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.0.iter().flatten().all(|x| x.is_finite())
    }

    /// Whether the transform keeps the plane z = 0 (a 2D map).
    pub fn is_planar(&self) -> bool {
        let m = &self.0;
        m[2][0] == 0.0 && m[2][1] == 0.0 && m[2][3] == 0.0
    }
}

pub(crate) fn norm(v: Point) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// A primitive shape, in the coordinates of the symbol that carries it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Primitive {
    Sphere {
        centre: Point,
        radius: f64,
    },
    /// An axis-aligned box between two corners.
    Box {
        min: Point,
        max: Point,
    },
    /// A closed cylinder from `base` to `top`.
    Cylinder {
        base: Point,
        top: Point,
        radius: f64,
    },
    /// A closed, possibly truncated cone: `top_radius` 0 is a full cone.
    Cone {
        base: Point,
        top: Point,
        base_radius: f64,
        top_radius: f64,
    },
    /// A flat disc facing `normal`.
    Disc {
        centre: Point,
        normal: Point,
        radius: f64,
    },
    Triangle([Point; 3]),
    /// A flat, convex or star-shaped polygon, drawn as a fan of triangles
    /// from its first corner.
    Polygon(Vec<Point>),
}

impl Primitive {
    /// The points whose convex hull holds the shape: what bounding volumes
    /// of its images are made from.
    pub fn hull_points(&self) -> Vec<Point> {
        match self {
            Primitive::Sphere { centre, radius } => {
                box_corners(centre.map(|c| c - radius), centre.map(|c| c + radius))
            }
            Primitive::Box { min, max } => box_corners(*min, *max),
            Primitive::Cylinder { base, top, radius } => {
                round_ends(&[(*base, *radius), (*top, *radius)])
            }
            Primitive::Cone {
                base,
                top,
                base_radius,
                top_radius,
            } => round_ends(&[(*base, *base_radius), (*top, *top_radius)]),
            Primitive::Disc {
                centre,
                normal,
                radius,
            } => round_ends(&[(*centre, *radius)])
                .into_iter()
                .filter(|_| norm(*normal) > 0.0)
                .collect(),
            Primitive::Triangle(t) => t.to_vec(),
            Primitive::Polygon(p) => p.clone(),
        }
    }

    /// Whether every point of the shape has z = 0.
    pub fn is_planar(&self) -> bool {
        match self {
            Primitive::Triangle(t) => t.iter().all(|p| p[2] == 0.0),
            Primitive::Polygon(p) => p.iter().all(|p| p[2] == 0.0),
            Primitive::Disc { centre, normal, .. } => {
                centre[2] == 0.0 && normal[0] == 0.0 && normal[1] == 0.0
            }
            _ => false,
        }
    }
}

fn box_corners(min: Point, max: Point) -> Vec<Point> {
    (0..8)
        .map(|i| [0, 1, 2].map(|k| if i >> k & 1 == 0 { min[k] } else { max[k] }))
        .collect()
}

/// The corners of boxes around spheres at the given centres: a hull of a
/// round-ended shape, a little larger than it.
fn round_ends(ends: &[(Point, f64)]) -> Vec<Point> {
    ends.iter()
        .flat_map(|(c, r)| box_corners(c.map(|x| x - r), c.map(|x| x + r)))
        .collect()
}

/// How a surface takes light: Phong's coefficients.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Finish {
    pub ambient: f64,
    pub diffuse: f64,
    pub specular: f64,
    pub shininess: f64,
}

impl Default for Finish {
    fn default() -> Self {
        Finish {
            ambient: 0.2,
            diffuse: 0.8,
            specular: 0.0,
            shininess: 20.0,
        }
    }
}

/// A primitive with its colour and finish.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Shape {
    pub primitive: Primitive,
    pub colour: Rgb,
    pub finish: Finish,
}

/// A geometry drawn instead of a symbol's own once the symbol's volume is
/// smaller than `below_pixels` (the paper's leaf on a branch, §3.1).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Alternative {
    pub shapes: Vec<Shape>,
    pub below_pixels: f64,
}

/// One symbol of a graph.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GraphSymbol {
    pub name: String,
    /// What the symbol is, drawn where it stands (several shapes make a
    /// composite geometry). Empty: nothing of its own.
    pub geometry: Vec<Shape>,
    pub alternative: Option<Alternative>,
    /// Its rule's successor; `None` for a terminal (the identity rule).
    pub rule: Option<Vec<Instance>>,
}

/// A couple `w(B)`: symbol `B` placed by `w`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Instance {
    pub transform: Affine,
    pub symbol: usize,
}

/// An object-instancing graph: its symbols with their rules and
/// geometries, and the axiom.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct InstancingGraph {
    pub symbols: Vec<GraphSymbol>,
    pub axiom: Vec<Instance>,
}

/// A cycle of the graph whose composed transform does not contract.
#[derive(Clone, Debug, PartialEq)]
pub struct Divergent {
    /// The edges of the cycle: (symbol, index in its rule).
    pub edges: Vec<(usize, usize)>,
    /// How much the composed transform stretches (≥ 1).
    pub factor: f64,
}

/// At most this many elementary cycles are examined for contraction; a
/// graph with more has them checked up to here.
const MAX_CYCLES: usize = 10_000;

impl InstancingGraph {
    /// The symbol named `name`.
    pub fn find(&self, name: &str) -> Option<usize> {
        self.symbols.iter().position(|s| s.name == name)
    }

    /// Whether any symbol carries a geometry (its own or an alternative).
    pub fn has_geometry(&self) -> bool {
        self.symbols
            .iter()
            .any(|s| !s.geometry.is_empty() || s.alternative.is_some())
    }

    /// `f` of every edge's transform, symbol by symbol (the tables a
    /// tracer keeps beside the graph).
    pub fn per_edge<T>(&self, f: impl Fn(&Affine) -> T) -> Vec<Vec<T>> {
        let edges = |s: &GraphSymbol| {
            s.rule
                .as_deref()
                .unwrap_or(&[])
                .iter()
                .map(|e| f(&e.transform))
                .collect()
        };
        self.symbols.iter().map(edges).collect()
    }

    /// The edges leaving `symbol`.
    pub fn successors(&self, symbol: usize) -> &[Instance] {
        self.symbols[symbol].rule.as_deref().unwrap_or(&[])
    }

    /// Whether the limit object lies in the plane z = 0 (a 2D IFS): every
    /// transform keeps the plane and every geometry lies in it. Such a
    /// graph is drawn flat, at pixel resolution, unless a ray-traced
    /// picture is asked for.
    pub fn is_planar(&self) -> bool {
        let edges = self.symbols.iter().flat_map(|s| s.rule.iter().flatten());
        let shapes = self.symbols.iter().flat_map(|s| {
            let alt = s.alternative.iter().flat_map(|a| a.shapes.iter());
            s.geometry.iter().chain(alt)
        });
        edges.chain(&self.axiom).all(|i| i.transform.is_planar())
            && shapes.into_iter().all(|s| s.primitive.is_planar())
    }

    /// Which symbols the axiom reaches.
    pub fn reachable(&self) -> Vec<bool> {
        let mut seen = vec![false; self.symbols.len()];
        let mut stack: Vec<usize> = self.axiom.iter().map(|i| i.symbol).collect();
        while let Some(s) = stack.pop() {
            if std::mem::replace(&mut seen[s], true) {
                continue;
            }
            stack.extend(self.successors(s).iter().map(|i| i.symbol));
        }
        seen
    }

    /// The terminals (symbols without a rule) that have no geometry while
    /// others do: the paper requires one on every leaf.
    pub fn bare_terminals(&self) -> Vec<usize> {
        if !self.has_geometry() {
            return Vec::new();
        }
        (0..self.symbols.len())
            .filter(|&s| {
                let sym = &self.symbols[s];
                sym.rule.is_none() && sym.geometry.is_empty() && sym.alternative.is_none()
            })
            .collect()
    }

    /// The elementary cycles (each once, from its smallest symbol) whose
    /// composed transform stretches by 1 or more: the limit object does not
    /// exist along them. At most [`MAX_CYCLES`] cycles are looked at.
    pub fn divergent_cycles(&self) -> Vec<Divergent> {
        let mut found = Vec::new();
        let mut budget = MAX_CYCLES;
        for start in 0..self.symbols.len() {
            let mut path = Vec::new();
            let mut on_path = vec![false; self.symbols.len()];
            self.cycles_from(
                start,
                start,
                &mut path,
                &mut on_path,
                &mut budget,
                &mut found,
            );
        }
        found
    }

    fn cycles_from(
        &self,
        start: usize,
        at: usize,
        path: &mut Vec<(usize, usize)>,
        on_path: &mut [bool],
        budget: &mut usize,
        found: &mut Vec<Divergent>,
    ) {
        on_path[at] = true;
        for (k, edge) in self.successors(at).iter().enumerate() {
            if *budget == 0 {
                break;
            }
            let next = edge.symbol;
            if next == start {
                *budget -= 1;
                path.push((at, k));
                let factor = self.composed(path).contraction();
                if factor.is_nan() || factor >= 1.0 - 1e-12 {
                    found.push(Divergent {
                        edges: path.clone(),
                        factor,
                    });
                }
                path.pop();
            } else if next > start && !on_path[next] {
                path.push((at, k));
                self.cycles_from(start, next, path, on_path, budget, found);
                path.pop();
            }
        }
        on_path[at] = false;
    }

    /// The transform of a path of edges, the first edge outermost.
    pub fn composed(&self, edges: &[(usize, usize)]) -> Affine {
        edges.iter().fold(Affine::IDENTITY, |w, &(s, k)| {
            w.then_after(&self.successors(s)[k].transform)
        })
    }

    /// Every transform of the graph (the axiom's, then each rule's edge by
    /// edge) that is singular, as (symbol or `None` for the axiom, index).
    pub fn singular_transforms(&self) -> Vec<(Option<usize>, usize)> {
        let axiom = self.axiom.iter().enumerate().map(|(k, i)| (None, k, i));
        let rules = self.symbols.iter().enumerate().flat_map(|(s, sym)| {
            let edges = sym.rule.as_deref().unwrap_or(&[]);
            edges.iter().enumerate().map(move |(k, i)| (Some(s), k, i))
        });
        axiom
            .chain(rules)
            .filter(|(_, _, i)| i.transform.inverse().is_none())
            .map(|(s, k, _)| (s, k))
            .collect()
    }
}

/// The colour of a shape that names none: a mid grey.
pub const DEFAULT_SHAPE_COLOUR: Rgb = Rgb(128, 128, 128);

impl Affine {
    /// The composition of `steps`, written as in mathematics: the last
    /// applied first (`[T, S]` is `T ∘ S`, a scaling then a translation).
    /// The one way front ends compose a transform written in steps, so
    /// that an emitter can tell exactly which steps give a matrix back.
    pub fn compose(steps: &[Affine]) -> Affine {
        match steps.split_first() {
            None => Affine::IDENTITY,
            Some((first, rest)) => rest.iter().fold(*first, |w, s| w.then_after(s)),
        }
    }

    /// Whether `self` and `other` agree bit for bit (`-0` and `0` apart).
    pub fn same_bits(&self, other: &Affine) -> bool {
        let bits = |a: &Affine| a.0.map(|row| row.map(f64::to_bits));
        bits(self) == bits(other)
    }
}

impl Affine {
    /// The map of the plane `x' = a x + b y + e`, `y' = c x + d y + f`
    /// (rows `[a b e]`, `[c d f]`) as a map of space that keeps the plane
    /// z = 0 and scales z by the largest singular value of its 2x2 part,
    /// so that it shrinks in space exactly as much as it does in the
    /// plane.
    pub fn planar(rows: [[f64; 3]; 2]) -> Affine {
        let [[a, b, e], [c, d, f]] = rows;
        Affine([
            [a, b, 0.0, e],
            [c, d, 0.0, f],
            [0.0, 0.0, stretch_2d(a, b, c, d), 0.0],
        ])
    }
}

/// The largest singular value of the 2x2 matrix `[[a, b], [c, d]]`, in
/// closed form.
pub fn stretch_2d(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let sum = a * a + b * b + c * c + d * d;
    let det = a * d - b * c;
    let root = (sum * sum - 4.0 * det * det).max(0.0).sqrt();
    ((sum + root) / 2.0).sqrt()
}
