//! Ray tracing an instancing graph without expanding it (Bekaert &
//! Willems §3.1): for each ray a list of couples `(X, w)`, nearest volume
//! `w(G_X)` first; the nearest is replaced by its children that the ray
//! meets, until a couple is smaller than the pixel the ray stands for
//! (the beam's width at that distance), where its geometry (or, in a graph
//! without geometry, its volume) is what the ray meets. Memory is the
//! list; nothing is built per instance.
//!
//! A symbol's geometry is drawn wherever the symbol is placed, its rule's
//! instances beside it (the paper draws a non-terminal's geometry only at
//! the cut; for the terminal geometries it cares for the two agree). A
//! symbol's alternative geometry replaces the symbol once its volume is
//! under the alternative's size in pixels.

use super::bounds::{Bounds, Key, Unbounded, Volume};
use super::bvh::Item;
use super::primitive::{intersect, slabs, Ray};
use super::vec::{add, dot, mul, normalize, sub, V3};
use super::{Cut, Scene, Scratch, SurfaceHit};
use crate::ir::graph::{Affine, Finish, InstancingGraph, Primitive, Shape};
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};

/// A graph ready to be traced.
pub struct GraphScene<'g> {
    graph: &'g InstancingGraph,
    bounds: Bounds,
    /// The inverse of each edge's transform (singular ones thickened).
    edge_inverse: Vec<Vec<Affine>>,
    /// The axiom's couples: symbol, inverse transform, stretch.
    axiom: Vec<(usize, Affine, f64)>,
    /// No symbol has a geometry: the limit object is drawn as the volumes
    /// at the cut (an IFS attractor).
    pure: bool,
    /// The colour of the volumes of a graph without geometry.
    colour: [f64; 3],
    world: (V3, V3),
}

/// One couple on a ray's list: the ray taken into the couple's
/// coordinates (each child's from its parent's by the edge's inverse, so
/// a couple costs one transform of a ray, not a product of matrices),
/// and where it came from, to rebuild the couple's whole transform for
/// the one hit that needs it.
#[derive(Clone, Copy, Debug)]
pub struct Couple {
    local: Ray,
    stretch: f64,
    symbol: u32,
    /// The index on the ray's list of the couple this one was opened
    /// from, or [`ROOT`] for an axiom couple.
    parent: u32,
    /// The edge of the parent's rule (or the axiom's couple) it stands for.
    edge: u32,
    /// A graph without geometry shades a volume by the normals of the
    /// volumes that led to it: the volume's normal where the ray enters,
    /// in the couple's coordinates.
    entry_normal: V3,
}

/// The parent of an axiom couple.
const ROOT: u32 = u32::MAX;

/// The nearest surface met so far on a ray, in the coordinates of the
/// couple (its index on the list) whose shape it is.
#[derive(Clone, Copy)]
struct Found {
    t: f64,
    normal: V3,
    colour: [f64; 3],
    finish: Finish,
    couple: u32,
}

/// Pops allowed per ray: a ray that grazes a dense part stops here with
/// the nearest hit found.
const MAX_POPS: usize = 4_000_000;

impl<'g> GraphScene<'g> {
    pub fn new(graph: &'g InstancingGraph, colour: [f64; 3]) -> Result<GraphScene<'g>, Unbounded> {
        let bounds = Bounds::of(graph)?;
        let edge_inverse = graph.per_edge(Affine::inverse_thickened);
        let axiom: Vec<(usize, Affine, f64)> = graph
            .axiom
            .iter()
            .filter(|i| bounds.volumes[i.symbol].is_some())
            .map(|i| {
                (
                    i.symbol,
                    i.transform.inverse_thickened(),
                    i.transform.contraction(),
                )
            })
            .collect();
        let world = graph
            .axiom
            .iter()
            .filter_map(|i| Some(bounds.volumes[i.symbol]?.image_box(&i.transform)))
            .fold(
                ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
                |(lo, hi), (a, b)| (super::vec::min(lo, a), super::vec::max(hi, b)),
            );
        Ok(GraphScene {
            pure: !graph.has_geometry(),
            graph,
            bounds,
            edge_inverse,
            axiom,
            colour,
            world,
        })
    }

    /// Where the ray, taken into a couple's coordinates, enters the
    /// symbol's volume (or `t_min` when it starts inside), with the
    /// volume's normal there in those coordinates.
    fn entry(&self, symbol: usize, local: &Ray, t_min: f64, t_max: f64) -> Option<(f64, V3)> {
        let (t0, t1, n) = match self.bounds.volumes[symbol]? {
            Volume::Box { min, max } if self.pure => {
                let (t0, t1, n0, _) = slabs(min, max, local)?;
                (t0, t1, n0)
            }
            // Only a graph without geometry shades by the volumes: the
            // span alone, without the branches that pick a face.
            Volume::Box { min, max } => {
                let (t0, t1) = slab_span(min, max, local)?;
                (t0, t1, [0.0; 3])
            }
            Volume::Sphere { centre, radius } => {
                let oc = sub(local.origin, centre);
                let a = dot(local.dir, local.dir);
                let b = dot(oc, local.dir);
                let disc = b * b - a * (dot(oc, oc) - radius * radius);
                if disc < 0.0 || a == 0.0 {
                    return None;
                }
                let root = disc.sqrt();
                let (t0, t1) = ((-b - root) / a, (-b + root) / a);
                // Only a graph without geometry shades by the volumes.
                let n = if self.pure {
                    sub(local.at(t0), centre)
                } else {
                    [0.0; 3]
                };
                (t0, t1, n)
            }
        };
        (t1 > t_min && t0 < t_max).then_some((t0.max(t_min), n))
    }

    /// The shapes met by the ray (in their couple's coordinates) before
    /// the nearest found so far.
    fn shapes_hit(
        shapes: &[Shape],
        local: &Ray,
        (t_min, t_max): (f64, f64),
        couple: u32,
        best: &mut Option<Found>,
    ) {
        for shape in shapes {
            let t_max = best.as_ref().map_or(t_max, |b| b.t);
            if let Some(hit) = intersect(&shape.primitive, local, t_min, t_max) {
                *best = Some(Found {
                    t: hit.t,
                    normal: hit.normal,
                    colour: super::linear(shape.colour),
                    finish: shape.finish,
                    couple,
                });
            }
        }
    }

    /// The axiom's couples the ray enters, each with its entry.
    fn roots(&self, ray: &Ray, t_min: f64, t_max: f64, mut emit: impl FnMut(Couple, f64)) {
        for (k, &(symbol, inverse, stretch)) in self.axiom.iter().enumerate() {
            let local = local_ray(&inverse, ray);
            if let Some((t, n)) = self.entry(symbol, &local, t_min, t_max) {
                let c = Couple {
                    local,
                    stretch,
                    symbol: symbol as u32,
                    parent: ROOT,
                    edge: k as u32,
                    entry_normal: n,
                };
                emit(c, t);
            }
        }
    }

    /// Takes a couple (at `index` on the ray's list) off the list, entered
    /// at `t_entry`: meets its geometry (or its alternative below the
    /// alternative's size) into `best`, and hands each child whose volume
    /// the ray enters before `best` (or `t_max`) to `emit`. A couple under
    /// the pixel draws only its geometry; in a graph without geometry it
    /// is the surface itself, and `true` says the search ends there.
    #[allow(clippy::too_many_arguments)]
    fn open(
        &self,
        (c, index): (&Couple, u32),
        t_entry: f64,
        range: (f64, f64),
        cut: Cut,
        best: &mut Option<Found>,
        mut emit: impl FnMut(Couple, f64),
    ) -> bool {
        let x = c.symbol as usize;
        let sym = &self.graph.symbols[x];
        let size = c.stretch * self.size(x);
        let pixel = cut.at(t_entry);
        if let Some(alt) = &sym.alternative {
            if size <= alt.below_pixels * pixel {
                Self::shapes_hit(&alt.shapes, &c.local, range, index, best);
                return false;
            }
        }
        let rule = sym.rule.as_deref().unwrap_or(&[]);
        if self.pure && (size <= pixel || rule.is_empty()) {
            return true;
        }
        Self::shapes_hit(&sym.geometry, &c.local, range, index, best);
        if size <= pixel {
            return false;
        }
        let bound = best.as_ref().map_or(range.1, |b| b.t);
        for (k, e) in rule.iter().enumerate() {
            let y = e.symbol;
            if self.bounds.volumes[y].is_none() {
                continue;
            }
            let local = local_ray(&self.edge_inverse[x][k], &c.local);
            if let Some((t, n)) = self.entry(y, &local, range.0, bound) {
                let child = Couple {
                    local,
                    stretch: c.stretch * self.bounds.stretch[x][k],
                    symbol: y as u32,
                    parent: index,
                    edge: k as u32,
                    entry_normal: n,
                };
                emit(child, t);
            }
        }
        false
    }

    /// The whole inverse transform of the couple at `index`, composed from
    /// the axiom down as [`GraphScene::expand`] composes it, and (in a
    /// graph without geometry) the normal of its volume blended with its
    /// ancestors', each level weighing half the next.
    fn placed(&self, couples: &[Couple], index: u32, chain: &mut Vec<u32>) -> (Affine, V3) {
        chain.clear();
        let mut i = index;
        while i != ROOT {
            chain.push(i);
            i = couples[i as usize].parent;
        }
        let mut inverse = Affine::IDENTITY;
        let mut normal = [0.0; 3];
        for (depth, &i) in chain.iter().rev().enumerate() {
            let c = &couples[i as usize];
            if depth == 0 {
                inverse = self.axiom[c.edge as usize].1;
            } else {
                let parent = couples[c.parent as usize].symbol as usize;
                inverse = self.edge_inverse[parent][c.edge as usize].then_after(&inverse);
            }
            if self.pure {
                let own = normalize(normal_to_world(&inverse, c.entry_normal));
                normal = if depth == 0 {
                    own
                } else {
                    normalize(add(mul(normal, 0.5), own))
                };
            }
        }
        (inverse, normal)
    }

    /// The nearest hit: the paper's list, nearest entry first, ended once
    /// the nearest entry lies beyond the nearest hit found.
    fn nearest(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        cut: Cut,
        scratch: &mut Scratch,
    ) -> Option<SurfaceHit> {
        let Scratch {
            couples,
            heap,
            stack: chain,
            ..
        } = scratch;
        couples.clear();
        heap.clear();
        // Ties in entry are taken in the order the couples were made, so
        // the search (and the picture) is the same on every run.
        let push = |couples: &mut Vec<Couple>, heap: &mut BinaryHeap<_>, c: Couple, t: f64| {
            heap.push(Reverse(entry_key(t, couples.len())));
            couples.push(c);
        };
        self.roots(ray, t_min, t_max, |c, t| push(couples, heap, c, t));
        let mut best: Option<Found> = None;
        for _ in 0..MAX_POPS {
            let Some(Reverse(key)) = heap.pop() else {
                break;
            };
            let (t_entry, i) = entry_of(key);
            if t_entry >= best.as_ref().map_or(t_max, |b| b.t) {
                break;
            }
            let c = couples[i];
            let mut children = |c: Couple, t: f64| push(couples, heap, c, t);
            let range = (t_min, t_max);
            if self.open(
                (&c, i as u32),
                t_entry,
                range,
                cut,
                &mut best,
                &mut children,
            ) {
                let (_, normal) = self.placed(couples, i as u32, chain);
                return Some(SurfaceHit {
                    t: t_entry,
                    normal,
                    colour: self.colour,
                    finish: Default::default(),
                    texel: None,
                });
            }
        }
        let found = best?;
        let (inverse, _) = self.placed(couples, found.couple, chain);
        Some(SurfaceHit {
            t: found.t,
            normal: normal_to_world(&inverse, found.normal),
            colour: found.colour,
            finish: found.finish,
            texel: None,
        })
    }

    /// Whether anything lies on the ray before `t_max` (a shadow ray):
    /// depth first, the nearer child first, so the search reaches the cut
    /// in a few dozen couples where the ray is blocked, instead of opening
    /// every large volume near the ray's start as the nearest-first list
    /// does. Any hit ends it.
    fn any(&self, ray: &Ray, t_min: f64, t_max: f64, cut: Cut, scratch: &mut Scratch) -> bool {
        let Scratch {
            pending, children, ..
        } = scratch;
        pending.clear();
        children.clear();
        self.roots(ray, t_min, t_max, |c, t| children.push((c, t)));
        let mut best: Option<Found> = None;
        for _ in 0..MAX_POPS {
            // The farthest child goes on the stack first.
            children.sort_by(|a, b| b.1.total_cmp(&a.1));
            pending.append(children);
            let Some((c, t_entry)) = pending.pop() else {
                return false;
            };
            // No couple's whole transform is wanted: its place is unused.
            let emit = |c: Couple, t: f64| children.push((c, t));
            let range = (t_min, t_max);
            if self.open((&c, ROOT), t_entry, range, cut, &mut best, emit) || best.is_some() {
                return true;
            }
        }
        false
    }
}

/// Where a ray is inside a box, as [`slabs`] finds it (the same
/// divisions), without the faces.
fn slab_span(min: V3, max: V3, ray: &Ray) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    for k in 0..3 {
        let (o, d) = (ray.origin[k], ray.dir[k]);
        if d == 0.0 {
            if o < min[k] || o > max[k] {
                return None;
            }
            continue;
        }
        let (a, b) = ((min[k] - o) / d, (max[k] - o) / d);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    (t0 <= t1).then_some((t0, t1))
}

/// A heap key ordering couples by entry, then by the order they were made:
/// an entry is never negative, so its bits order as it does.
fn entry_key(t: f64, index: usize) -> u128 {
    (u128::from((t + 0.0).to_bits()) << 64) | index as u128
}

fn entry_of(key: u128) -> (f64, usize) {
    (f64::from_bits((key >> 64) as u64), key as u64 as usize)
}

impl GraphScene<'_> {
    pub fn graph(&self) -> &InstancingGraph {
        self.graph
    }

    pub fn bounds(&self) -> &Bounds {
        &self.bounds
    }

    /// The size of a symbol's volume (0 for one that draws nothing).
    fn size(&self, x: usize) -> f64 {
        self.bounds.volumes[x].map_or(0.0, |v| v.size())
    }

    /// Whether no symbol has a geometry (the limit drawn as volumes).
    pub fn is_pure(&self) -> bool {
        self.pure
    }

    /// The colour of the volumes of a graph without geometry.
    pub fn colour(&self) -> [f64; 3] {
        self.colour
    }

    /// The graph expanded as the tracer expands it under an orthographic
    /// cut of `pixel` world units: every shape placed, and in a graph
    /// without geometry every volume at the cut, as items of a flat
    /// hierarchy, with the transforms composed in the tracer's order (so a
    /// picture of them is the tracer's, pixel for pixel, where neither
    /// cuts anything). `None` past `max_items`.
    pub fn expand(&self, pixel: f64, max_items: usize) -> Option<Vec<Item>> {
        let mut items = Vec::new();
        let mut stack: Vec<(usize, Affine, f64)> = self.axiom.clone();
        let shape_items = |shapes: &[Shape], inverse: &Affine, items: &mut Vec<Item>| {
            items.extend(shapes.iter().map(|sh| Item {
                primitive: sh.primitive.clone(),
                placed: Some(*inverse),
                colour: super::linear(sh.colour),
                finish: sh.finish,
                texture: None,
            }));
        };
        while let Some((x, inverse, stretch)) = stack.pop() {
            if items.len() > max_items {
                return None;
            }
            let sym = &self.graph.symbols[x];
            let Some(volume) = self.bounds.volumes[x] else {
                continue;
            };
            let size = stretch * volume.size();
            let rule = sym.rule.as_deref().unwrap_or(&[]);
            if let Some(alt) = sym
                .alternative
                .as_ref()
                .filter(|a| size <= a.below_pixels * pixel)
            {
                shape_items(&alt.shapes, &inverse, &mut items);
                continue;
            }
            if (size <= pixel || rule.is_empty()) && self.pure {
                let primitive = match volume {
                    Volume::Box { min, max } => Primitive::Box { min, max },
                    Volume::Sphere { centre, radius } => Primitive::Sphere { centre, radius },
                };
                items.push(Item {
                    primitive,
                    placed: Some(inverse),
                    colour: self.colour,
                    finish: Finish::default(),
                    texture: None,
                });
                continue;
            }
            shape_items(&sym.geometry, &inverse, &mut items);
            if size <= pixel {
                continue;
            }
            for (k, e) in rule.iter().enumerate() {
                let child = self.edge_inverse[x][k].then_after(&inverse);
                stack.push((e.symbol, child, stretch * self.bounds.stretch[x][k]));
            }
        }
        Some(items)
    }
}

pub(crate) fn local_ray(inverse: &Affine, ray: &Ray) -> Ray {
    Ray {
        origin: inverse.apply(ray.origin),
        dir: inverse.apply_vector(ray.dir),
    }
}

/// A normal in a couple's coordinates taken to the world: by the
/// transpose of the inverse.
pub(crate) fn normal_to_world(inverse: &Affine, n: V3) -> V3 {
    let m = &inverse.0;
    [0, 1, 2].map(|j| m[0][j] * n[0] + m[1][j] * n[1] + m[2][j] * n[2])
}

/// Couples a view is fitted to at most.
const FIT_COUPLES: usize = 2048;

impl Scene for GraphScene<'_> {
    fn world_box(&self) -> (V3, V3) {
        self.world
    }

    /// The corners of the volumes of the largest couples, expanded from the
    /// axiom largest first until there are [`FIT_COUPLES`].
    fn fit_points(&self) -> Vec<V3> {
        let mut open: std::collections::BinaryHeap<(Key, Reverse<usize>)> = Default::default();
        let mut couples: Vec<(usize, Affine, f64)> = Vec::new();
        let forward = |inverse: &Affine| inverse.inverse_thickened();
        for (i, &(x, inv, s)) in self.axiom.iter().enumerate() {
            couples.push((x, forward(&inv), s));
            open.push((Key(s * self.size(x)), Reverse(i)));
        }
        let mut leaves: Vec<usize> = Vec::new();
        let mut points: Vec<V3> = Vec::new();
        while let Some((_, Reverse(i))) = open.pop() {
            let (x, w, s) = couples[i];
            let rule = self.graph.successors(x);
            if rule.is_empty() || open.len() + leaves.len() + rule.len() > FIT_COUPLES {
                leaves.push(i);
                continue;
            }
            for (k, e) in rule.iter().enumerate() {
                if self.bounds.volumes[e.symbol].is_some() {
                    let se = s * self.bounds.stretch[x][k];
                    couples.push((e.symbol, w.then_after(&e.transform), se));
                    open.push((Key(se * self.size(e.symbol)), Reverse(couples.len() - 1)));
                }
            }
            let own = &self.graph.symbols[x].geometry;
            let hull = own.iter().flat_map(|sh| sh.primitive.hull_points());
            points.extend(hull.map(|p| w.apply(p)));
        }
        let volumes = leaves.iter().filter_map(|&i| {
            let (x, w, _) = couples[i];
            Some(self.bounds.volumes[x]?.corners().map(|p| w.apply(p)))
        });
        points.extend(volumes.flatten());
        points
    }

    fn hit(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        cut: Cut,
        scratch: &mut Scratch,
    ) -> Option<SurfaceHit> {
        self.nearest(ray, t_min, t_max, cut, scratch)
    }

    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64, cut: Cut, scratch: &mut Scratch) -> bool {
        self.any(ray, t_min, t_max, cut, scratch)
    }
}

/// How many primitive instances the graph holds expanded down to where a
/// couple's volume is smaller than `pixel` (world units): each shape
/// placed counts one, and in a graph without geometry each volume at the
/// cut. Memoised on (symbol, stretch), so a graph of 10^12 instances is
/// counted in milliseconds. Saturates at `u128::MAX`.
pub fn count_instances(graph: &InstancingGraph, bounds: &Bounds, pixel: f64) -> u128 {
    let mut memo = HashMap::new();
    let pure = !graph.has_geometry();
    let axiom = graph
        .axiom
        .iter()
        .map(|i| (i.symbol, i.transform.contraction()));
    axiom.fold(0u128, |n, (x, s)| {
        n.saturating_add(count_from(graph, bounds, pixel, pure, x, s, &mut memo))
    })
}

fn count_from(
    graph: &InstancingGraph,
    bounds: &Bounds,
    pixel: f64,
    pure: bool,
    x: usize,
    stretch: f64,
    memo: &mut HashMap<(usize, u64), u128>,
) -> u128 {
    let Some(volume) = bounds.volumes[x] else {
        return 0;
    };
    if let Some(&n) = memo.get(&(x, stretch.to_bits())) {
        return n;
    }
    let sym = &graph.symbols[x];
    let size = stretch * volume.size();
    let rule = sym.rule.as_deref().unwrap_or(&[]);
    let n = match &sym.alternative {
        Some(alt) if size <= alt.below_pixels * pixel => alt.shapes.len() as u128,
        _ if size <= pixel || rule.is_empty() => {
            if pure {
                1
            } else {
                sym.geometry.len() as u128
            }
        }
        _ => rule
            .iter()
            .enumerate()
            .fold(sym.geometry.len() as u128, |n, (k, e)| {
                let s = stretch * bounds.stretch[x][k];
                n.saturating_add(count_from(graph, bounds, pixel, pure, e.symbol, s, memo))
            }),
    };
    memo.insert((x, stretch.to_bits()), n);
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::graph::{GraphSymbol, Instance};

    /// Sierpinski's tetrahedron: 4 maps of scale 1/2 towards the corners.
    pub(crate) fn tetrahedron() -> InstancingGraph {
        let corners = [
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ];
        let rule = corners
            .iter()
            .map(|c| Instance {
                transform: Affine::translate(mul(*c, 0.5)).then_after(&Affine::scale([0.5; 3])),
                symbol: 0,
            })
            .collect();
        InstancingGraph {
            symbols: vec![GraphSymbol {
                name: "A".into(),
                geometry: vec![],
                alternative: None,
                rule: Some(rule),
            }],
            axiom: vec![Instance {
                transform: Affine::IDENTITY,
                symbol: 0,
            }],
        }
    }

    #[test]
    fn the_initial_volume_holds_every_point_of_the_expanded_code() {
        let g = tetrahedron();
        let b = Bounds::of(&g).unwrap();
        let v = b.volumes[0].unwrap();
        // Every corner of the tetrahedron, and its images 6 levels down,
        // lie in the volume.
        let mut points = vec![
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ];
        for _ in 0..4 {
            points = points
                .iter()
                .flat_map(|p| {
                    g.symbols[0]
                        .rule
                        .as_ref()
                        .unwrap()
                        .iter()
                        .map(|e| e.transform.apply(*p))
                })
                .collect();
        }
        let inside = |p: V3| match v {
            Volume::Box { min, max } => {
                (0..3).all(|k| p[k] >= min[k] - 1e-9 && p[k] <= max[k] + 1e-9)
            }
            Volume::Sphere { centre, radius } => {
                super::super::vec::length(super::super::vec::sub(p, centre)) <= radius + 1e-9
            }
        };
        assert!(points.iter().all(|p| inside(*p)));
        // And it is tight: the box of the tetrahedron is [-1, 1]^3.
        if let Volume::Box { min, max } = v {
            assert!(
                (0..3).all(|k| min[k] > -1.0 - 1e-9 && max[k] < 1.0 + 1e-9),
                "{v:?}"
            );
        } else {
            panic!("a box has the smaller projected area here: {v:?}");
        }
    }

    #[test]
    fn instances_are_counted_to_the_pixel() {
        let g = tetrahedron();
        let b = Bounds::of(&g).unwrap();
        let size = b.volumes[0].unwrap().size();
        // Each level halves the size: volumes under size/2^k are 4^k.
        // (The stretch carries a hair of slack, so the cut is set a hair above.)
        assert_eq!(count_instances(&g, &b, size / 8.0 * 1.000001), 4u128.pow(3));
        assert_eq!(
            count_instances(&g, &b, size / 1024.0 * 1.000001),
            4u128.pow(10)
        );
    }

    /// A tree of the tetrahedron's kind with geometry: a ball at each
    /// node and a smaller one as the leaf, so rays meet shapes, not volumes.
    fn balls() -> InstancingGraph {
        let mut g = tetrahedron();
        let ball = |radius: f64| Shape {
            primitive: Primitive::Sphere {
                centre: [0.0; 3],
                radius,
            },
            colour: crate::ir::Rgb(200, 100, 50),
            finish: Finish::default(),
        };
        g.symbols[0].geometry = vec![ball(0.3)];
        g.symbols[0].alternative = Some(crate::ir::graph::Alternative {
            shapes: vec![ball(0.5)],
            below_pixels: 3.0,
        });
        g
    }

    /// Rays from a grid of origins in many directions.
    fn rays() -> Vec<Ray> {
        let mut out = Vec::new();
        for i in 0..24 {
            for j in 0..24 {
                let origin = [-1.2 + 0.1 * i as f64, -1.2 + 0.1 * j as f64, -4.0];
                let dir = [0.13 * (j as f64 - 12.0) / 12.0, 0.2, 1.0];
                out.push(Ray { origin, dir });
            }
        }
        out
    }

    /// The depth-first search of shadow rays finds something exactly where
    /// the nearest-first search finds a hit before the end of the ray.
    #[test]
    fn shadow_rays_are_blocked_exactly_where_the_nearest_search_hits() {
        for g in [tetrahedron(), balls()] {
            let scene = GraphScene::new(&g, [0.5; 3]).unwrap();
            let cut = Cut {
                base: 0.02,
                per_unit: 0.0,
            };
            let mut scratch = Scratch::default();
            let (mut blocked, mut open) = (0, 0);
            for ray in rays() {
                let nearest = scene.hit(&ray, 0.0, f64::INFINITY, cut, &mut scratch);
                for t_max in [3.0, 4.5, f64::INFINITY] {
                    let hit = nearest.as_ref().is_some_and(|h| h.t < t_max);
                    let any = scene.occluded(&ray, 0.0, t_max, cut, &mut scratch);
                    assert_eq!(any, hit, "{ray:?} up to {t_max}: {nearest:?}");
                    (blocked, open) = if any {
                        (blocked + 1, open)
                    } else {
                        (blocked, open + 1)
                    };
                }
            }
            assert!(
                blocked > 100 && open > 100,
                "{blocked} blocked, {open} open"
            );
        }
    }
}
