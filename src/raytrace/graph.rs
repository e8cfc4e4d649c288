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
use super::primitive::{intersect, slabs, sphere, Ray};
use super::vec::{add, mul, normalize, V3};
use super::{Cut, Scene, Scratch, SurfaceHit};
use crate::ir::graph::{Affine, Finish, InstancingGraph, Primitive, Shape};
use std::cmp::Reverse;
use std::collections::HashMap;

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

/// One couple on a ray's list.
#[derive(Clone, Copy, Debug)]
pub struct Couple {
    inverse: Affine,
    stretch: f64,
    symbol: u32,
    /// A graph without geometry shades a volume by the normals of the
    /// volumes that led to it, each level weighing half the next.
    normal: V3,
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
            Volume::Box { min, max } => {
                let (t0, t1, n0, _) = slabs(min, max, local)?;
                (t0, t1, n0)
            }
            Volume::Sphere { centre, radius } => {
                let far = sphere(centre, radius, local, f64::NEG_INFINITY, f64::INFINITY)?;
                let near = sphere(centre, radius, local, f64::NEG_INFINITY, far.t);
                match near {
                    Some(n) => (n.t, far.t, n.normal),
                    None => (far.t, far.t, far.normal),
                }
            }
        };
        (t1 > t_min && t0 < t_max).then_some((t0.max(t_min), n))
    }

    fn shapes_hit(
        shapes: &[Shape],
        inverse: &Affine,
        ray: &Ray,
        t_min: f64,
        best: &mut Option<SurfaceHit>,
    ) {
        if shapes.is_empty() {
            return;
        }
        let local = local_ray(inverse, ray);
        for shape in shapes {
            let t_max = best.as_ref().map_or(f64::INFINITY, |b| b.t);
            if let Some(hit) = intersect(&shape.primitive, &local, t_min, t_max) {
                *best = Some(SurfaceHit {
                    t: hit.t,
                    normal: normal_to_world(inverse, hit.normal),
                    colour: super::linear(shape.colour),
                    finish: shape.finish,
                });
            }
        }
    }

    fn trace(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        cut: Cut,
        any: bool,
        scratch: &mut Scratch,
    ) -> Option<SurfaceHit> {
        let Scratch { couples, heap, .. } = scratch;
        couples.clear();
        heap.clear();
        let mut seq = 0u64;
        let mut push = |couples: &mut Vec<Couple>,
                        heap: &mut std::collections::BinaryHeap<_>,
                        c: Couple,
                        t: f64| {
            seq += 1;
            couples.push(c);
            heap.push((Reverse(Key(t)), Reverse(seq), couples.len() - 1));
        };
        for &(symbol, inverse, stretch) in &self.axiom {
            let local = local_ray(&inverse, ray);
            if let Some((t, n)) = self.entry(symbol, &local, t_min, t_max) {
                let normal = normalize(normal_to_world(&inverse, n));
                let c = Couple {
                    inverse,
                    stretch,
                    symbol: symbol as u32,
                    normal,
                };
                push(couples, heap, c, t);
            }
        }
        let mut best: Option<SurfaceHit> = None;
        let mut pops = 0;
        while let Some((Reverse(Key(t_entry)), _, i)) = heap.pop() {
            let bound = best.as_ref().map_or(t_max, |b| b.t);
            pops += 1;
            if t_entry >= bound || pops > MAX_POPS {
                break;
            }
            let c = couples[i];
            let x = c.symbol as usize;
            let sym = &self.graph.symbols[x];
            let size = c.stretch * self.bounds.volumes[x].map_or(0.0, |v| v.size());
            let pixel = cut.at(t_entry);
            if let Some(alt) = &sym.alternative {
                if size <= alt.below_pixels * pixel {
                    Self::shapes_hit(&alt.shapes, &c.inverse, ray, t_min, &mut best);
                    if any && best.is_some() {
                        return best;
                    }
                    continue;
                }
            }
            let rule = sym.rule.as_deref().unwrap_or(&[]);
            if size <= pixel || rule.is_empty() {
                if self.pure {
                    return Some(SurfaceHit {
                        t: t_entry,
                        normal: c.normal,
                        colour: self.colour,
                        finish: Default::default(),
                    });
                }
                Self::shapes_hit(&sym.geometry, &c.inverse, ray, t_min, &mut best);
                if any && best.is_some() {
                    return best;
                }
                continue;
            }
            Self::shapes_hit(&sym.geometry, &c.inverse, ray, t_min, &mut best);
            if any && best.is_some() {
                return best;
            }
            let bound = best.as_ref().map_or(t_max, |b| b.t);
            for (k, e) in rule.iter().enumerate() {
                let y = e.symbol;
                if self.bounds.volumes[y].is_none() {
                    continue;
                }
                let inverse = self.edge_inverse[x][k].then_after(&c.inverse);
                let local = local_ray(&inverse, ray);
                if let Some((t, n)) = self.entry(y, &local, t_min, bound) {
                    let own = normalize(normal_to_world(&inverse, n));
                    let normal = if self.pure {
                        normalize(add(mul(c.normal, 0.5), own))
                    } else {
                        own
                    };
                    let child = Couple {
                        inverse,
                        stretch: c.stretch * self.bounds.stretch[x][k],
                        symbol: y as u32,
                        normal,
                    };
                    push(couples, heap, child, t);
                }
            }
        }
        best
    }
}

impl GraphScene<'_> {
    pub fn graph(&self) -> &InstancingGraph {
        self.graph
    }

    pub fn bounds(&self) -> &Bounds {
        &self.bounds
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

impl Scene for GraphScene<'_> {
    fn world_box(&self) -> (V3, V3) {
        self.world
    }

    fn hit(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        cut: Cut,
        scratch: &mut Scratch,
    ) -> Option<SurfaceHit> {
        self.trace(ray, t_min, t_max, cut, false, scratch)
    }

    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64, cut: Cut, scratch: &mut Scratch) -> bool {
        self.trace(ray, t_min, t_max, cut, true, scratch).is_some()
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
}
