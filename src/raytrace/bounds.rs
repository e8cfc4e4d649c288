//! The initial bounding volumes of an instancing graph (Bekaert & Willems
//! §3.2), one per symbol: a box or a sphere in the symbol's own
//! coordinates that holds everything the symbol stands for, down to the
//! limit. The image `w(G_X)` of a couple's volume then bounds the couple,
//! which is what the tracer culls and orders by.
//!
//! The paper expands the graph until the images are small and bounds what
//! it reaches, with an arbitrary volume for what is not expanded, and so
//! may clip the limit object. Here what is not expanded is bounded by a
//! ball that provably holds it: balls `B(c_X, r_X)` with
//! `w(B_Y) ⊂ B_X` along every edge `X -> w(Y)` and `X`'s geometry inside
//! `B_X` hold the limit of the rules (Hutchinson's argument), and such
//! radii are the least fixed point of `r_X = max(geometry, |w(c_Y) − c_X| +
//! ‖w‖ r_Y)`, reached by iteration when every cycle contracts. The brute
//! force then tightens them, and per symbol the box or the sphere of
//! smaller average projected area (a quarter of its surface) is kept.

use super::vec::{add, length, max, min, mul, sub, V3};
use crate::ir::graph::{Affine, InstancingGraph, Shape};
use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;

/// A bounding volume in a symbol's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Volume {
    Sphere { centre: V3, radius: f64 },
    Box { min: V3, max: V3 },
}

impl Volume {
    /// Its diameter: the size the pixel cut compares.
    pub fn size(&self) -> f64 {
        match self {
            Volume::Sphere { radius, .. } => 2.0 * radius,
            Volume::Box { min, max } => length(sub(*max, *min)),
        }
    }

    /// The corners of a box around it, for bounding its images.
    pub fn corners(&self) -> [V3; 8] {
        let (lo, hi) = match self {
            Volume::Sphere { centre, radius } => {
                (centre.map(|c| c - radius), centre.map(|c| c + radius))
            }
            Volume::Box { min, max } => (*min, *max),
        };
        std::array::from_fn(|i| [0, 1, 2].map(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
    }

    /// A world box around its image under `w`.
    pub fn image_box(&self, w: &Affine) -> (V3, V3) {
        match self {
            Volume::Sphere { centre, radius } => {
                // The image of a sphere is an ellipsoid; its box half-sizes
                // are the row norms of the linear part times the radius.
                let c = w.apply(*centre);
                let half = [0, 1, 2].map(|i| radius * length([w.0[i][0], w.0[i][1], w.0[i][2]]));
                (sub(c, half), add(c, half))
            }
            Volume::Box { .. } => points_box(self.corners().iter().map(|p| w.apply(*p))),
        }
    }
}

/// The box around some points (empty: an inverted box).
pub fn points_box(points: impl Iterator<Item = V3>) -> (V3, V3) {
    points.fold(
        ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
        |(lo, hi), p| (min(lo, p), max(hi, p)),
    )
}

/// Why a graph has no bounding volumes.
#[derive(Clone, Debug, PartialEq)]
pub enum Unbounded {
    /// Some cycle does not contract (E1001 says which), or a number is
    /// not finite.
    NotContractive,
    /// Nothing is drawn: no symbol the axiom reaches has a geometry, while
    /// others do.
    Empty,
}

/// What a graph's tracer knows before the first ray: each symbol's volume
/// (`None` for a symbol that draws nothing) and each edge's stretch.
#[derive(Clone, Debug)]
pub struct Bounds {
    pub volumes: Vec<Option<Volume>>,
    /// `stretch[X][k]`: how much the k-th edge of X's rule stretches.
    pub stretch: Vec<Vec<f64>>,
}

/// Couples expanded per symbol to tighten its volume.
const REFINE_BUDGET: usize = 4096;
/// A couple whose ball is smaller than this share of its symbol's is not
/// expanded further when tightening.
const SMALL_ENOUGH: f64 = 1e-3;

impl Bounds {
    pub fn of(graph: &InstancingGraph) -> Result<Bounds, Unbounded> {
        let stretch = graph.per_edge(|t| t.contraction() * (1.0 + 1e-12));
        let balls = guaranteed_balls(graph, &stretch)?;
        let boxes = fixed_boxes(graph, &balls);
        let volumes = (0..graph.symbols.len())
            .map(|x| balls[x].map(|_| tightened(graph, &stretch, &balls, &boxes, x)))
            .collect();
        Ok(Bounds { volumes, stretch })
    }
}

/// The box around a symbol's own shapes.
fn shapes_box(shapes: &[Shape]) -> Option<(V3, V3)> {
    let points: Vec<V3> = shapes
        .iter()
        .flat_map(|s| s.primitive.hull_points())
        .collect();
    (!points.is_empty()).then(|| points_box(points.into_iter()))
}

/// What a symbol draws of its own: its geometry and its alternative.
fn own_shapes(graph: &InstancingGraph, x: usize) -> Vec<Shape> {
    let sym = &graph.symbols[x];
    let alt = sym.alternative.iter().flat_map(|a| a.shapes.iter());
    sym.geometry.iter().chain(alt).cloned().collect()
}

type Ball = Option<(V3, f64)>;

/// Balls that provably hold each symbol's limit object, or `None` for a
/// symbol that draws nothing.
fn guaranteed_balls(graph: &InstancingGraph, stretch: &[Vec<f64>]) -> Result<Vec<Ball>, Unbounded> {
    let n = graph.symbols.len();
    let pure = !graph.has_geometry();
    // A symbol draws something when it has shapes, or (in a graph without
    // any) is a volume itself at the cut, or reaches one that does.
    let mut draws: Vec<bool> = (0..n)
        .map(|x| !own_shapes(graph, x).is_empty() || pure)
        .collect();
    loop {
        let before = draws.clone();
        for x in 0..n {
            draws[x] = draws[x] || graph.successors(x).iter().any(|e| draws[e.symbol]);
        }
        if draws == before {
            break;
        }
    }
    let geometry: Vec<Option<(V3, V3)>> =
        (0..n).map(|x| shapes_box(&own_shapes(graph, x))).collect();
    let mut centre: Vec<V3> = geometry
        .iter()
        .map(|g| g.map_or([0.0; 3], |(lo, hi)| mul(add(lo, hi), 0.5)))
        .collect();
    // Centres: where the rules put things, on average; any centre works,
    // a central one gives smaller balls.
    for _ in 0..64 {
        for x in 0..n {
            let edges = graph.successors(x).iter().filter(|e| draws[e.symbol]);
            let mut points: Vec<V3> = edges.map(|e| e.transform.apply(centre[e.symbol])).collect();
            if let Some((lo, hi)) = geometry[x] {
                points.push(mul(add(lo, hi), 0.5));
            }
            if !points.is_empty() {
                let sum = points.iter().fold([0.0; 3], |a, p| add(a, *p));
                centre[x] = mul(sum, 1.0 / points.len() as f64);
            }
        }
    }
    let own_radius: Vec<f64> = (0..n)
        .map(|x| match geometry[x] {
            Some((lo, hi)) => {
                let c = centre[x];
                let far = [0, 1, 2].map(|k| (lo[k] - c[k]).abs().max((hi[k] - c[k]).abs()));
                length(far)
            }
            None if pure && graph.symbols[x].rule.is_none() => 1.0,
            None => 0.0,
        })
        .collect();
    let mut radius = own_radius.clone();
    for round in 0.. {
        let mut moved = 0.0f64;
        for x in 0..n {
            let mut r = own_radius[x];
            for (k, e) in graph.successors(x).iter().enumerate() {
                if draws[e.symbol] {
                    let off = length(sub(e.transform.apply(centre[e.symbol]), centre[x]));
                    r = r.max(off + stretch[x][k] * radius[e.symbol]);
                }
            }
            if !r.is_finite() {
                return Err(Unbounded::NotContractive);
            }
            moved = moved.max(r - radius[x]);
            radius[x] = r;
        }
        let scale = radius.iter().fold(0.0, |a: f64, r| a.max(*r));
        if moved <= 1e-13 * scale {
            break;
        }
        if round > 100_000 || scale > 1e300 {
            return Err(Unbounded::NotContractive);
        }
    }
    // The iteration approaches the fixed point from below; a hair of room
    // makes every inequality hold.
    let slack = 1.0 + 1e-9;
    if !graph.axiom.iter().any(|i| draws[i.symbol]) {
        return Err(Unbounded::Empty);
    }
    Ok((0..n)
        .map(|x| draws[x].then(|| (centre[x], radius[x] * slack + 1e-300)))
        .collect())
}

/// The brute force of §3.2 from symbol `x`: expand, largest ball first,
/// until the balls are small or the budget is spent; bound the shapes met
/// and the balls left; keep the box or the sphere, whichever has the
/// smaller average projected area.
/// Boxes that hold each symbol's limit object, tighter than the balls'
/// boxes: the operator `B_X ← box(X's shapes ∪ ⋃ w(B_Y))` maps boxes
/// that hold the limit to boxes that do, so it is iterated from the
/// balls' boxes, each result cut down by the one before, until it stops
/// shrinking. For maps that scale and translate along the axes (a
/// Sierpinski tetrahedron's) it ends at the limit's own box.
fn fixed_boxes(graph: &InstancingGraph, balls: &[Ball]) -> Vec<Option<(V3, V3)>> {
    let mut boxes: Vec<Option<(V3, V3)>> = balls
        .iter()
        .map(|b| b.map(|(c, r)| (sub(c, [r; 3]), add(c, [r; 3]))))
        .collect();
    let own: Vec<Option<(V3, V3)>> = (0..graph.symbols.len())
        .map(|x| shapes_box(&own_shapes(graph, x)))
        .collect();
    for _ in 0..1000 {
        let mut shrunk = 0.0f64;
        for x in 0..graph.symbols.len() {
            let Some((lo, hi)) = boxes[x] else { continue };
            let rule = graph.symbols[x].rule.as_deref().unwrap_or(&[]);
            if rule.is_empty() {
                continue;
            }
            let images = rule.iter().filter_map(|e| {
                let (a, b) = boxes[e.symbol]?;
                Some(Volume::Box { min: a, max: b }.image_box(&e.transform))
            });
            let (a, b) = own[x].into_iter().chain(images).fold(
                ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
                |(lo, hi), (a, b)| (min(lo, a), max(hi, b)),
            );
            let (a, b) = (max(a, lo), min(b, hi));
            if !(0..3).all(|k| a[k] <= b[k]) {
                continue;
            }
            let size = length(sub(hi, lo)).max(f64::MIN_POSITIVE);
            shrunk = shrunk.max(length(sub(a, lo)).max(length(sub(hi, b))) / size);
            boxes[x] = Some((a, b));
        }
        if shrunk <= 1e-12 {
            break;
        }
    }
    boxes
}

fn tightened(
    graph: &InstancingGraph,
    stretch: &[Vec<f64>],
    balls: &[Ball],
    boxes: &[Option<(V3, V3)>],
    x: usize,
) -> Volume {
    let (_, root_r) = balls[x].expect("only symbols that draw are tightened");
    // Largest ball first; ties in the order met, so the result is fixed.
    let mut open = BinaryHeap::new();
    let mut met = 0u64;
    let mut couples: Vec<(usize, Affine, f64)> = vec![(x, Affine::IDENTITY, 1.0)];
    open.push((Key(root_r), Reverse(met), 0usize));
    let mut points: Vec<V3> = Vec::new();
    let mut expanded = 0;
    while let Some((Key(r), _, i)) = open.pop() {
        let (y, w, s) = couples[i];
        let rule = graph.symbols[y].rule.as_deref().unwrap_or(&[]);
        let stop = expanded >= REFINE_BUDGET || r < SMALL_ENOUGH * root_r || rule.is_empty();
        let own = own_shapes(graph, y);
        points.extend(
            own.iter()
                .flat_map(|sh| sh.primitive.hull_points())
                .map(|p| w.apply(p)),
        );
        if stop {
            if !rule.is_empty() || (own.is_empty() && !graph.has_geometry()) {
                let (lo, hi) = boxes[y].expect("only symbols that draw are opened");
                let corners = Volume::Box { min: lo, max: hi }.corners();
                points.extend(corners.iter().map(|p| w.apply(*p)));
            }
            continue;
        }
        expanded += 1;
        for (k, e) in rule.iter().enumerate() {
            if let Some((_, re)) = balls[e.symbol] {
                let se = s * stretch[y][k];
                met += 1;
                couples.push((e.symbol, w.then_after(&e.transform), se));
                open.push((Key(se * re), Reverse(met), couples.len() - 1));
            }
        }
    }
    let (lo, hi) = points_box(points.iter().copied());
    let centre = mul(add(lo, hi), 0.5);
    let reach = points
        .iter()
        .map(|p| length(sub(*p, centre)))
        .fold(0.0, f64::max);
    let e = sub(hi, lo);
    let box_area = (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]) / 2.0;
    let sphere_area = std::f64::consts::PI * reach * reach;
    if box_area <= sphere_area {
        Volume::Box { min: lo, max: hi }
    } else {
        Volume::Sphere {
            centre,
            radius: reach,
        }
    }
}

/// An `f64` ordered by `total_cmp`, for heaps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Key(pub f64);

impl Eq for Key {}

impl PartialOrd for Key {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Key {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}
