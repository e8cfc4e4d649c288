//! A flat bounding volume hierarchy over world-space primitives: what a
//! turtle draws (segments as cylinders with round joints, generalized
//! cylinders as tubes along their points, polygons and surfaces as
//! triangles, spheres), or an instancing graph expanded to a fixed depth
//! (the baseline the graph tracer is measured against).
//!
//! Built top-down, splitting each node at the median of the primitives'
//! centres along its longest side (ties by index, so the tree is the same
//! on every run), and traversed nearest child first.

use super::bounds::points_box;
use super::primitive::{intersect, Ray};
use super::vec::{max, min, sub, V3};
use super::{Cut, Scene, Scratch, SurfaceHit};
use crate::ir::graph::{Affine, Finish, Primitive};
use crate::ir::texture::Texture;
use crate::turtle::Geometry;

/// One primitive with its look.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    pub primitive: Primitive,
    /// A primitive placed by a transform: the inverse, world to its own
    /// coordinates (an instance of a graph expanded); `None` when it is
    /// given in world coordinates.
    pub placed: Option<Affine>,
    pub colour: [f64; 3],
    pub finish: Finish,
    /// The texture a triangle wears (boxed: few items have one).
    pub texture: Option<Box<ItemTexture>>,
}

/// A texture on a triangle item: the texture, whose image was read, and
/// the texture coordinates of the triangle's corners.
#[derive(Clone, Debug, PartialEq)]
pub struct ItemTexture {
    pub texture: Texture,
    pub uvs: [[f64; 2]; 3],
}

impl ItemTexture {
    /// The texel at `p` on triangle `[a, b, c]` (its coordinates
    /// interpolated between the corners'); `None` where its alpha is
    /// below 0.5: cut out, as the z-buffer's alpha test cuts it.
    fn texel(&self, [a, b, c]: [V3; 3], p: V3) -> Option<[f32; 4]> {
        let image = self.texture.image.as_ref()?;
        let [wa, wb, wc] = barycentric(a, b, c, p);
        let [ta, tb, tc] = self.uvs;
        let u = wa * ta[0] + wb * tb[0] + wc * tc[0];
        let v = wa * ta[1] + wb * tb[1] + wc * tc[1];
        let texel = image.sample(u, v, self.texture.filter);
        (texel[3] >= 0.5).then_some(texel)
    }
}

/// The barycentric weights of `p` (on the triangle's plane) in `[a, b,
/// c]`; the first corner's alone for a degenerate triangle.
fn barycentric(a: V3, b: V3, c: V3, p: V3) -> [f64; 3] {
    use super::vec::dot;
    let (e1, e2, d) = (sub(b, a), sub(c, a), sub(p, a));
    let (d11, d12, d22) = (dot(e1, e1), dot(e1, e2), dot(e2, e2));
    let (d1, d2) = (dot(d, e1), dot(d, e2));
    let den = d11 * d22 - d12 * d12;
    if den.abs() <= f64::MIN_POSITIVE || !den.is_finite() {
        return [1.0, 0.0, 0.0];
    }
    let wb = (d22 * d1 - d12 * d2) / den;
    let wc = (d11 * d2 - d12 * d1) / den;
    [1.0 - wb - wc, wb, wc]
}

#[derive(Clone, Copy, Debug)]
struct Node {
    lo: V3,
    hi: V3,
    /// A leaf's first item, or an inner node's second child (its first is
    /// the next node).
    index: u32,
    /// Items in a leaf; 0 for an inner node.
    count: u32,
}

/// The hierarchy and its items.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    items: Vec<Item>,
    nodes: Vec<Node>,
}

/// Items per leaf at most.
const LEAF: usize = 4;

impl Bvh {
    pub fn new(items: Vec<Item>) -> Bvh {
        let boxes: Vec<(V3, V3)> = items.iter().map(Item::world_box).collect();
        let mut order: Vec<u32> = (0..items.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * items.len() / LEAF + 1);
        if !items.is_empty() {
            build(&boxes, &mut order, 0, &mut nodes);
        }
        let mut slots: Vec<Option<Item>> = items.into_iter().map(Some).collect();
        let items = order
            .iter()
            .map(|&i| slots[i as usize].take().expect("each item once"))
            .collect();
        Bvh { items, nodes }
    }

    /// The items, in the hierarchy's order.
    pub fn items(&self) -> &[Item] {
        &self.items
    }

    pub fn len(&self) -> usize {
        self.items.len()
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Bytes held: what the benchmarks weigh the graph tracer against.
    pub fn memory(&self) -> usize {
        let polygon_points: usize = self
            .items
            .iter()
            .map(|i| match &i.primitive {
                Primitive::Polygon(p) => p.len() * 24,
                _ => 0,
            })
            .sum();
        self.items.len() * std::mem::size_of::<Item>()
            + self.nodes.len() * std::mem::size_of::<Node>()
            + polygon_points
    }

    fn search(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        any: bool,
        stack: &mut Vec<u32>,
    ) -> Option<SurfaceHit> {
        let mut best: Option<SurfaceHit> = None;
        if self.nodes.is_empty() {
            return None;
        }
        let inv = ray.dir.map(|d| 1.0 / d);
        stack.clear();
        stack.push(0);
        while let Some(n) = stack.pop() {
            let bound = best.as_ref().map_or(t_max, |b| b.t);
            let node = self.nodes[n as usize];
            if enter(&node, ray, inv, t_min, bound).is_none() {
                continue;
            }
            if node.count > 0 {
                let first = node.index as usize;
                for item in &self.items[first..first + node.count as usize] {
                    let bound = best.as_ref().map_or(t_max, |b| b.t);
                    if let Some(hit) = item.hit(ray, t_min, bound) {
                        best = Some(hit);
                        if any {
                            return best;
                        }
                    }
                }
                continue;
            }
            let (a, b) = (n + 1, node.index);
            let ta = enter(&self.nodes[a as usize], ray, inv, t_min, bound);
            let tb = enter(&self.nodes[b as usize], ray, inv, t_min, bound);
            match (ta, tb) {
                (Some(ta), Some(tb)) if tb < ta => stack.extend([a, b]),
                (Some(_), Some(_)) => stack.extend([b, a]),
                (Some(_), None) => stack.push(a),
                (None, Some(_)) => stack.push(b),
                (None, None) => {}
            }
        }
        best
    }
}

/// Where the ray enters a node's box within `(t_min, t_max)`.
fn enter(node: &Node, ray: &Ray, inv: V3, t_min: f64, t_max: f64) -> Option<f64> {
    let (mut t0, mut t1) = (t_min, t_max);
    for (k, inv_k) in inv.iter().enumerate() {
        let (mut a, mut b) = (
            (node.lo[k] - ray.origin[k]) * inv_k,
            (node.hi[k] - ray.origin[k]) * inv_k,
        );
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        // NaN (0 × ∞ on a face) leaves the interval as it is.
        t0 = if a > t0 { a } else { t0 };
        t1 = if b < t1 { b } else { t1 };
    }
    (t0 <= t1).then_some(t0)
}

fn build(boxes: &[(V3, V3)], order: &mut [u32], offset: usize, nodes: &mut Vec<Node>) -> u32 {
    let (lo, hi) = order.iter().map(|&i| boxes[i as usize]).fold(
        ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
        |(lo, hi), (a, b)| (min(lo, a), max(hi, b)),
    );
    let me = nodes.len() as u32;
    nodes.push(Node {
        lo,
        hi,
        index: offset as u32,
        count: order.len() as u32,
    });
    if order.len() <= LEAF {
        return me;
    }
    let centre = |i: u32| {
        let (a, b) = boxes[i as usize];
        [0, 1, 2].map(|k| a[k] + b[k])
    };
    let e = sub(hi, lo);
    let axis = if e[0] >= e[1] && e[0] >= e[2] {
        0
    } else if e[1] >= e[2] {
        1
    } else {
        2
    };
    let mid = order.len() / 2;
    order.select_nth_unstable_by(mid, |&a, &b| {
        centre(a)[axis].total_cmp(&centre(b)[axis]).then(a.cmp(&b))
    });
    let (left, right) = order.split_at_mut(mid);
    build(boxes, left, offset, nodes);
    let second = build(boxes, right, offset + mid, nodes);
    nodes[me as usize].index = second;
    nodes[me as usize].count = 0;
    me
}

impl Item {
    /// A primitive in world coordinates.
    pub fn world(primitive: Primitive, colour: [f64; 3], finish: Finish) -> Item {
        Item {
            primitive,
            placed: None,
            colour,
            finish,
            texture: None,
        }
    }

    /// A box holding it in the world.
    pub fn world_box(&self) -> (V3, V3) {
        let hull = self.primitive.hull_points().into_iter();
        match &self.placed {
            None => points_box(hull),
            Some(inverse) => {
                let forward = inverse.inverse_thickened();
                points_box(hull.map(|p| forward.apply(p)))
            }
        }
    }

    /// Where the ray meets it, as the graph tracer computes it for an
    /// instance (the same arithmetic, so the two draw alike).
    pub fn hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let (hit, normal) = match &self.placed {
            None => {
                let hit = intersect(&self.primitive, ray, t_min, t_max)?;
                (hit, hit.normal)
            }
            Some(inverse) => {
                let local = super::graph::local_ray(inverse, ray);
                let hit = intersect(&self.primitive, &local, t_min, t_max)?;
                (hit, super::graph::normal_to_world(inverse, hit.normal))
            }
        };
        let texel = match (&self.texture, &self.primitive) {
            (Some(tx), Primitive::Triangle(corners)) => {
                let p = super::vec::mad(ray.origin, ray.dir, hit.t);
                // Cut out: the ray goes on to what lies behind.
                Some((tx.texel(*corners, p)?, tx.texture.mode))
            }
            _ => None,
        };
        Some(SurfaceHit {
            t: hit.t,
            normal,
            colour: self.colour,
            finish: self.finish,
            texel,
        })
    }
}

impl Scene for Bvh {
    fn world_box(&self) -> (V3, V3) {
        self.nodes
            .first()
            .map_or(([0.0; 3], [0.0; 3]), |n| (n.lo, n.hi))
    }

    fn hit(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        _: Cut,
        scratch: &mut Scratch,
    ) -> Option<SurfaceHit> {
        self.search(ray, t_min, t_max, false, &mut scratch.stack)
    }

    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64, _: Cut, scratch: &mut Scratch) -> bool {
        self.search(ray, t_min, t_max, true, &mut scratch.stack)
            .is_some()
    }
}

/// What a turtle drew, as primitives: each segment a cylinder of its width
/// with a sphere at each joint, each polygon a fan of triangles, each disc
/// a sphere, each generalized cylinder's path a chain of such tubes.
/// `pixel` is the world size of a pixel, for widths given in pixels;
/// `finish` the look of every surface; `textures` the look's, which
/// textured polygons name.
pub fn from_geometry(g: &Geometry, pixel: f64, finish: Finish, textures: &[Texture]) -> Vec<Item> {
    let mut items = Vec::with_capacity(g.segments.len() * 2 + g.polygons.len());
    let radius = |w: f64| {
        let w = if g.world_widths { w } else { w * pixel };
        (w.abs() / 2.0).max(pixel * 0.5)
    };
    let mut last_end: Option<V3> = None;
    for s in &g.segments {
        let colour = super::linear(s.colour);
        let r = radius(s.width);
        if last_end != Some(s.a) {
            items.push(Item::world(
                Primitive::Sphere {
                    centre: s.a,
                    radius: r,
                },
                colour,
                finish,
            ));
        }
        if s.a != s.b {
            items.push(Item::world(
                Primitive::Cylinder {
                    base: s.a,
                    top: s.b,
                    radius: r,
                },
                colour,
                finish,
            ));
        }
        items.push(Item::world(
            Primitive::Sphere {
                centre: s.b,
                radius: r,
            },
            colour,
            finish,
        ));
        last_end = Some(s.b);
    }
    for path in &g.paths {
        let colour = super::linear(path.colour);
        let r = radius(path.width);
        for pair in path.points.windows(2) {
            if pair[0] != pair[1] {
                items.push(Item::world(
                    Primitive::Cylinder {
                        base: pair[0],
                        top: pair[1],
                        radius: r,
                    },
                    colour,
                    finish,
                ));
            }
            items.push(Item::world(
                Primitive::Sphere {
                    centre: pair[1],
                    radius: r,
                },
                colour,
                finish,
            ));
        }
    }
    for p in &g.polygons {
        let colour = super::linear(p.colour);
        // A texture whose image was read, with a coordinate a corner.
        let textured = p.texture.as_ref().and_then(|tx| {
            let texture = textures.get(usize::from(tx.texture))?;
            (texture.image.is_some() && tx.uvs.len() == p.points.len())
                .then_some((texture, &tx.uvs))
        });
        if let Some((&first, rest)) = p.points.split_first() {
            for (k, pair) in rest.windows(2).enumerate() {
                let mut item = Item::world(
                    Primitive::Triangle([first, pair[0], pair[1]]),
                    colour,
                    finish,
                );
                if let Some((texture, uvs)) = textured {
                    item.texture = Some(Box::new(ItemTexture {
                        texture: texture.clone(),
                        uvs: [uvs[0], uvs[k + 1], uvs[k + 2]],
                    }));
                }
                items.push(item);
            }
        }
    }
    for d in &g.discs {
        let r = if d.pixels {
            d.diameter * pixel
        } else {
            d.diameter
        } / 2.0;
        items.push(Item::world(
            Primitive::Sphere {
                centre: d.centre,
                radius: r.abs().max(pixel * 0.5),
            },
            super::linear(d.colour),
            finish,
        ));
    }
    items
}
