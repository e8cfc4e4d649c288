//! 3D meshes of what the turtle drew, for Blender and game engines:
//! Wavefront OBJ (with its `.mtl`), PLY and binary glTF (`.glb`).
//!
//! Segments become tubes as wide as the turtle's line ([`tube`]): a tube
//! runs on through the consecutive segments of one branch (and through
//! the pieces of a generalized cylinder's curve) instead of ending at each
//! segment. Polygons and cpfg surfaces become triangles with the
//! polygon's normal, cpfg spheres and circles (`@O`, `@o`: discs facing
//! the viewer in a picture) become spheres, and colours become materials:
//! a lit cpfg look's own materials (ambient, diffuse, specular, emission,
//! shininess, transparency) where it has them ([`Finish`]), else one
//! diffuse material per colour.
//! A line width in pixels is a share of the model's size, as in a picture
//! [`PIXELS_ACROSS`] pixels across.
//!
//! A context-free deterministic system that the shared-subtree turtle
//! handles ([`crate::turtle::instanced`]) is exported to glTF with one
//! mesh per distinct subtree, placed by nodes ([`instanced`]): a Koch
//! curve of a million segments is a thousand-segment mesh placed a
//! thousand times.

mod gltf;
pub mod instanced;
mod obj;
mod ply;
pub mod texture;
pub mod tube;

use crate::ir::look::{Lighting, Material};
use crate::ir::Rgb;
use crate::turtle::{cross, dot, Geometry, Vec3};
use serde::Serialize;
use std::collections::HashMap;

pub use gltf::glb;
pub use obj::{mtl, obj};
pub use ply::ply;

/// A line width in pixels is this share of the model's largest extent:
/// the picture is this many pixels across.
pub const PIXELS_ACROSS: f64 = 600.0;

/// The mesh formats, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    Obj,
    Ply,
    Glb,
}

impl MeshFormat {
    /// Every mesh format. An output's extension is looked up here, so a
    /// format missing from this list could not be written, and the help
    /// that lists it ([`crate::driver::picture::Target::all`]) cannot
    /// miss one that can.
    pub const ALL: [MeshFormat; 3] = [MeshFormat::Obj, MeshFormat::Ply, MeshFormat::Glb];

    /// The format's extension, which names it.
    pub fn extension(self) -> &'static str {
        match self {
            MeshFormat::Obj => "obj",
            MeshFormat::Ply => "ply",
            MeshFormat::Glb => "glb",
        }
    }

    /// The format for an output path, by its extension (any case).
    pub fn from_path(path: &str) -> Option<MeshFormat> {
        let ext = std::path::Path::new(path).extension()?.to_str()?;
        MeshFormat::ALL
            .into_iter()
            .find(|f| f.extension().eq_ignore_ascii_case(ext))
    }
}

/// What a part is drawn with: the turtle's colour, and in a lit look's
/// material mode the material of the colour index, picked as the renderer
/// picks it ([`Lighting::material`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Finish {
    /// The colour, or the material's diffuse colour (what PLY's vertex
    /// colours hold).
    pub colour: (u8, u8, u8),
    /// The material and the colour index that names it.
    pub material: Option<(u16, Material)>,
    /// The texture it wears, an index of [`Mesh::textures`] (the look's
    /// textures); its part's vertices then have texture coordinates.
    pub texture: Option<u16>,
}

/// Parts are shared by equal finishes: the colour, and the material's
/// components bit for bit.
type FinishKey = ((u8, u8, u8), Option<[u32; 14]>, Option<u16>);

impl Finish {
    /// A plain colour, as unlit systems (and colour-map mode) have it.
    pub fn plain(c: Rgb) -> Finish {
        Finish {
            colour: (c.0, c.1, c.2),
            material: None,
            texture: None,
        }
    }

    /// The finish of something drawn in `colour` with colour index
    /// `index` under `lighting`.
    pub fn new(colour: Rgb, index: u16, lighting: Option<&Lighting>) -> Finish {
        match lighting.and_then(|l| l.material(index)) {
            Some(m) => {
                let [r, g, b] = m.diffuse.map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8);
                Finish {
                    colour: (r, g, b),
                    material: Some((index, *m)),
                    texture: None,
                }
            }
            None => Finish::plain(colour),
        }
    }

    pub(crate) fn key(&self) -> FinishKey {
        let bits = self.material.map(|(_, m)| {
            let mut k = [0u32; 14];
            let all = [m.ambient, m.diffuse, m.specular, m.emission];
            for (i, x) in all.iter().flatten().enumerate() {
                k[i] = x.to_bits();
            }
            k[12] = m.shininess.to_bits();
            k[13] = m.transparency.to_bits();
            k
        });
        (self.colour, bits, self.texture)
    }

    /// The material's name in the files: `c` and the colour in hex, or
    /// `m` and the colour index.
    pub fn name(&self) -> String {
        let base = match self.material {
            Some((index, _)) => format!("m{index}"),
            None => {
                let c = self.colour;
                format!("c{:02x}{:02x}{:02x}", c.0, c.1, c.2)
            }
        };
        match self.texture {
            // Textures counted from 1, as cpfg's `@Tx(n)` counts them.
            Some(t) => format!("{base}_t{}", u32::from(t) + 1),
            None => base,
        }
    }
}

/// Triangles of one material: vertices with their normals, and triangles
/// as indices into them.
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    pub finish: Finish,
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Texture coordinates, one a vertex, in a textured part (OpenGL's:
    /// v up from the image's bottom row); empty in others.
    pub uvs: Vec<[f64; 2]>,
    pub triangles: Vec<[u32; 3]>,
}

impl Part {
    /// Adds a vertex; its index.
    pub(crate) fn vertex(&mut self, p: Vec3, n: Vec3) -> u32 {
        self.positions.push(p);
        self.normals.push(n);
        (self.positions.len() - 1) as u32
    }
}

/// A mesh: one part per finish.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub parts: Vec<Part>,
    /// The textures its finishes name (the look's, when a part is
    /// textured; else none).
    pub textures: Vec<crate::ir::texture::Texture>,
    by_finish: HashMap<FinishKey, usize>,
}

impl Mesh {
    /// The part of finish `f`, made when new.
    pub(crate) fn part(&mut self, f: Finish) -> &mut Part {
        let parts = &mut self.parts;
        let k = *self.by_finish.entry(f.key()).or_insert_with(|| {
            parts.push(Part {
                finish: f,
                positions: Vec::new(),
                normals: Vec::new(),
                uvs: Vec::new(),
                triangles: Vec::new(),
            });
            parts.len() - 1
        });
        &mut self.parts[k]
    }

    pub fn vertices(&self) -> usize {
        self.parts.iter().map(|p| p.positions.len()).sum()
    }

    pub fn triangles(&self) -> usize {
        self.parts.iter().map(|p| p.triangles.len()).sum()
    }

    /// `[min, max]` of its vertices seen through `place`; `None` when it
    /// has none.
    fn bounds(&self, place: &Transform) -> Option<[Vec3; 2]> {
        let mut b: Option<[Vec3; 2]> = None;
        for p in self.parts.iter().flat_map(|p| &p.positions) {
            let q = place.apply(*p);
            let bb = b.get_or_insert([q, q]);
            for k in 0..3 {
                bb[0][k] = bb[0][k].min(q[k]);
                bb[1][k] = bb[1][k].max(q[k]);
            }
        }
        b
    }
}

/// Where a mesh is placed: `pos + scale · rotation · p`, the rotation's
/// columns the images of x, y and z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    pub rotation: [Vec3; 3],
    pub translation: Vec3,
    pub scale: f64,
}

impl Transform {
    pub const IDENTITY: Transform = Transform {
        rotation: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        translation: [0.0; 3],
        scale: 1.0,
    };

    pub fn apply(&self, p: Vec3) -> Vec3 {
        let r = &self.rotation;
        std::array::from_fn(|i| {
            self.translation[i] + self.scale * (r[0][i] * p[0] + r[1][i] * p[1] + r[2][i] * p[2])
        })
    }

    /// The rotation as a unit quaternion `[x, y, z, w]`.
    pub fn quaternion(&self) -> [f64; 4] {
        let [c0, c1, c2] = self.rotation;
        // m[row][col]
        let m = |r: usize, c: usize| [c0, c1, c2][c][r];
        let trace = m(0, 0) + m(1, 1) + m(2, 2);
        let q = if trace > 0.0 {
            let s = (trace + 1.0).sqrt() * 2.0;
            [
                (m(2, 1) - m(1, 2)) / s,
                (m(0, 2) - m(2, 0)) / s,
                (m(1, 0) - m(0, 1)) / s,
                s / 4.0,
            ]
        } else if m(0, 0) > m(1, 1) && m(0, 0) > m(2, 2) {
            let s = (1.0 + m(0, 0) - m(1, 1) - m(2, 2)).sqrt() * 2.0;
            [
                s / 4.0,
                (m(0, 1) + m(1, 0)) / s,
                (m(0, 2) + m(2, 0)) / s,
                (m(2, 1) - m(1, 2)) / s,
            ]
        } else if m(1, 1) > m(2, 2) {
            let s = (1.0 + m(1, 1) - m(0, 0) - m(2, 2)).sqrt() * 2.0;
            [
                (m(0, 1) + m(1, 0)) / s,
                s / 4.0,
                (m(1, 2) + m(2, 1)) / s,
                (m(0, 2) - m(2, 0)) / s,
            ]
        } else {
            let s = (1.0 + m(2, 2) - m(0, 0) - m(1, 1)).sqrt() * 2.0;
            [
                (m(0, 2) + m(2, 0)) / s,
                (m(1, 2) + m(2, 1)) / s,
                s / 4.0,
                (m(1, 0) - m(0, 1)) / s,
            ]
        };
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        q.map(|x| x / n)
    }
}

/// A mesh placed in the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node {
    pub mesh: usize,
    pub place: Transform,
}

/// Meshes and where they are placed: one node for a whole geometry, many
/// for the shared subtrees of [`instanced`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    pub meshes: Vec<Mesh>,
    pub nodes: Vec<Node>,
}

/// What a scene holds, counted as a reader that places every node sees
/// it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeshStats {
    pub vertices: u64,
    pub triangles: u64,
    /// `[minx, miny, minz, maxx, maxy, maxz]` of the placed vertices.
    pub bounds: Option<[f64; 6]>,
    pub meshes: usize,
    pub nodes: usize,
    pub materials: usize,
}

impl Scene {
    /// One mesh, placed once.
    pub fn single(mesh: Mesh) -> Scene {
        Scene {
            meshes: vec![mesh],
            nodes: vec![Node {
                mesh: 0,
                place: Transform::IDENTITY,
            }],
        }
    }

    /// The distinct finishes, in order of first use.
    pub fn materials(&self) -> Vec<Finish> {
        let mut seen: Vec<Finish> = Vec::new();
        for p in self.meshes.iter().flat_map(|m| &m.parts) {
            if !seen.iter().any(|f| f.key() == p.finish.key()) {
                seen.push(p.finish);
            }
        }
        seen
    }

    /// Vertices, triangles and bounds over every placed node. Bounds are
    /// exact: each mesh's box is found once per rotation it is placed
    /// with, then scaled and moved.
    pub fn stats(&self) -> MeshStats {
        let (mut vertices, mut triangles) = (0u64, 0u64);
        let mut boxes: HashMap<(usize, [u64; 9]), Option<[Vec3; 2]>> = HashMap::new();
        let mut all: Option<[Vec3; 2]> = None;
        for n in &self.nodes {
            let m = &self.meshes[n.mesh];
            vertices += m.vertices() as u64;
            triangles += m.triangles() as u64;
            let turn = Transform {
                translation: [0.0; 3],
                scale: 1.0,
                ..n.place
            };
            let key = (n.mesh, bits(turn.rotation));
            let Some([lo, hi]) = *boxes.entry(key).or_insert_with(|| m.bounds(&turn)) else {
                continue;
            };
            let place = |v: Vec3| -> Vec3 {
                std::array::from_fn(|i| n.place.translation[i] + n.place.scale * v[i])
            };
            let (lo, hi) = (place(lo), place(hi));
            let b = all.get_or_insert([lo, hi]);
            for k in 0..3 {
                b[0][k] = b[0][k].min(lo[k]);
                b[1][k] = b[1][k].max(hi[k]);
            }
        }
        MeshStats {
            vertices,
            triangles,
            bounds: all.map(|[lo, hi]| [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]]),
            meshes: self.meshes.len(),
            nodes: self.nodes.len(),
            materials: self.materials().len(),
        }
    }

    /// Every node's mesh placed, as one mesh (what OBJ and PLY hold).
    pub fn flattened(&self) -> Mesh {
        let mut out = Mesh::default();
        for n in &self.nodes {
            let m = &self.meshes[n.mesh];
            if out.textures.is_empty() {
                out.textures.clone_from(&m.textures);
            }
            for p in &m.parts {
                let part = out.part(p.finish);
                let base = part.positions.len() as u32;
                let turn = Transform {
                    translation: [0.0; 3],
                    scale: 1.0,
                    ..n.place
                };
                for (v, nv) in p.positions.iter().zip(&p.normals) {
                    part.vertex(n.place.apply(*v), turn.apply(*nv));
                }
                part.uvs.extend_from_slice(&p.uvs);
                part.triangles
                    .extend(p.triangles.iter().map(|t| t.map(|i| i + base)));
            }
        }
        out
    }
}

fn bits(r: [Vec3; 3]) -> [u64; 9] {
    let mut k = [0u64; 9];
    for (i, x) in r.iter().flatten().enumerate() {
        k[i] = (x + 0.0).to_bits();
    }
    k
}

/// How wide the tubes and how large the spheres are: line widths in turtle
/// units, or in pixels of a picture [`PIXELS_ACROSS`] wide.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sizing {
    /// Turtle units per unit of width.
    pub per_width: f64,
}

impl Sizing {
    /// For a model whose box is `bbox`, widths in turtle units when
    /// `world_widths`, else in pixels.
    pub fn new(bbox: Option<[f64; 6]>, world_widths: bool) -> Sizing {
        if world_widths {
            return Sizing { per_width: 1.0 };
        }
        let extent = bbox
            .map(|b| (0..3).map(|k| b[k + 3] - b[k]).fold(0.0, f64::max))
            .filter(|e| e.is_finite() && *e > 0.0)
            .unwrap_or(1.0);
        Sizing {
            per_width: extent / PIXELS_ACROSS,
        }
    }

    /// The radius of a line or disc `width` wide.
    pub fn radius(&self, width: f64) -> f64 {
        (width.abs() * self.per_width / 2.0).max(0.0)
    }
}

/// The mesh of everything `g` draws: tubes, polygons, spheres, with the
/// materials of `lighting` where it has them.
pub fn of_geometry(
    g: &Geometry,
    lighting: Option<&Lighting>,
    progress: &mut dyn FnMut(u64, u64),
) -> Mesh {
    let sizing = Sizing::new(g.bbox(), g.world_widths);
    let mut mesh = Mesh::default();
    let total = (g.segments.len() + g.polygons.len() + g.discs.len()) as u64;
    for chain in tube::chains(&g.segments, lighting) {
        tube::tube(&mut mesh, &chain, &sizing);
    }
    progress(g.segments.len() as u64, total);
    for p in &g.polygons {
        let finish = Finish::new(p.colour, p.index, lighting);
        // A texture whose image was read, with a coordinate a corner.
        let textured = p.texture.as_ref().filter(|tx| {
            let texture = lighting.and_then(|l| l.textures.get(usize::from(tx.texture)));
            texture.is_some_and(|t| t.image.is_some()) && tx.uvs.len() == p.points.len()
        });
        match (textured, lighting) {
            (Some(tx), Some(l)) => {
                if mesh.textures.is_empty() {
                    mesh.textures.clone_from(&l.textures);
                }
                let finish = Finish {
                    texture: Some(tx.texture),
                    ..finish
                };
                polygon(&mut mesh, &p.points, Some(&tx.uvs), finish);
            }
            _ => polygon(&mut mesh, &p.points, None, finish),
        }
    }
    for d in &g.discs {
        let r = if d.pixels {
            sizing.radius(d.diameter)
        } else {
            d.diameter.abs() / 2.0
        };
        sphere(
            &mut mesh,
            d.centre,
            r,
            Finish::new(d.colour, d.index, lighting),
        );
    }
    progress(total, total);
    mesh
}

fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `v` at unit length, or `None` when it is (nearly) zero.
fn unit(v: Vec3) -> Option<Vec3> {
    let n = dot(v, v).sqrt();
    (n > 1e-12 && n.is_finite()).then(|| v.map(|x| x / n))
}

/// A unit vector at right angles to the unit vector `t`.
fn perpendicular(t: Vec3) -> Vec3 {
    let other = if t[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    unit(cross(t, other)).unwrap_or([0.0, 0.0, 1.0])
}

/// The indices of a polygon's corners without repeats: consecutive
/// equal points and a last point equal to the first are dropped.
fn corner_indices(points: &[Vec3]) -> Vec<usize> {
    // Equal up to rounding: a turtle that goes round a square comes back
    // within 1e-16 of where it started.
    let same = |a: &Vec3, b: &Vec3| {
        let size = a.iter().chain(b).fold(1.0f64, |m, x| m.max(x.abs()));
        (0..3).all(|k| (a[k] - b[k]).abs() <= 1e-9 * size)
    };
    let mut out: Vec<usize> = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        if !out.last().is_some_and(|&q| same(p, &points[q])) {
            out.push(i);
        }
    }
    while out.len() > 1 && same(&points[out[0]], &points[out[out.len() - 1]]) {
        out.pop();
    }
    out
}

/// A polygon as a fan of triangles with its (Newell) normal, and its
/// corners' texture coordinates `uvs` (one a point) in a textured finish;
/// polygons of fewer than three corners are left out.
fn polygon(mesh: &mut Mesh, points: &[Vec3], uvs: Option<&[[f64; 2]]>, finish: Finish) {
    let kept = corner_indices(points);
    let pts: Vec<Vec3> = kept.iter().map(|&i| points[i]).collect();
    if pts.len() < 3 {
        return;
    }
    let mut n = [0.0; 3];
    for (i, a) in pts.iter().enumerate() {
        let b = pts[(i + 1) % pts.len()];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    let normal = unit(n).unwrap_or([0.0, 0.0, 1.0]);
    let part = mesh.part(finish);
    let base = part.positions.len() as u32;
    for &p in &pts {
        part.vertex(p, normal);
    }
    if let Some(uvs) = uvs {
        part.uvs.extend(
            kept.iter()
                .map(|&i| uvs.get(i).copied().unwrap_or([0.0; 2])),
        );
    }
    for k in 1..pts.len() as u32 - 1 {
        part.triangles.push([base, base + k, base + k + 1]);
    }
}

/// Sides of a sphere around its axis, and bands from pole to pole.
pub const SPHERE_SIDES: usize = 8;
pub const SPHERE_BANDS: usize = 6;

/// A sphere of radius `r` around `c`: two poles and rings between them.
fn sphere(mesh: &mut Mesh, c: Vec3, r: f64, finish: Finish) {
    let part = mesh.part(finish);
    let at = |n: Vec3| [c[0] + r * n[0], c[1] + r * n[1], c[2] + r * n[2]];
    let south = part.vertex(at([0.0, -1.0, 0.0]), [0.0, -1.0, 0.0]);
    let ring0 = south + 1;
    for band in 1..SPHERE_BANDS {
        let (sy, cy) = (std::f64::consts::PI * band as f64 / SPHERE_BANDS as f64).sin_cos();
        for k in 0..SPHERE_SIDES {
            let (s, co) = (std::f64::consts::TAU * k as f64 / SPHERE_SIDES as f64).sin_cos();
            let n = [sy * co, -cy, sy * s];
            part.vertex(at(n), n);
        }
    }
    let north = part.vertex(at([0.0, 1.0, 0.0]), [0.0, 1.0, 0.0]);
    let sides = SPHERE_SIDES as u32;
    let ring = |band: u32, k: u32| ring0 + band * sides + k % sides;
    for k in 0..sides {
        part.triangles.push([south, ring(0, k), ring(0, k + 1)]);
        let top = SPHERE_BANDS as u32 - 2;
        part.triangles.push([north, ring(top, k + 1), ring(top, k)]);
        for band in 0..top {
            let (a, b) = (ring(band, k), ring(band, k + 1));
            let (c2, d) = (ring(band + 1, k), ring(band + 1, k + 1));
            part.triangles.push([a, d, b]);
            part.triangles.push([a, c2, d]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::pfg::read_ok;
    use crate::turtle::{Disc, Run};

    fn draw(src: &str) -> Geometry {
        let sys = read_ok(src);
        Run::word(&sys, &sys.axiom, 0).geometry()
    }

    /// Normals of unit length, indices in range, one normal a vertex.
    fn well_formed(m: &Mesh) {
        for p in &m.parts {
            assert_eq!(p.positions.len(), p.normals.len());
            for n in &p.normals {
                assert!((dot(*n, *n).sqrt() - 1.0).abs() < 1e-9, "{n:?}");
            }
            let len = p.positions.len() as u32;
            assert!(p.triangles.iter().flatten().all(|&i| i < len));
        }
    }

    #[test]
    fn a_branch_is_a_tube_and_the_trunk_runs_on_through_it() {
        // The trunk's three steps (one narrower) are one tube of 4 rings,
        // the branch one of 2.
        let m = of_geometry(
            &draw("angle factor: 4\naxiom: F[+F]F!F\n"),
            None,
            &mut |_, _| {},
        );
        well_formed(&m);
        assert_eq!(m.vertices(), (4 + 2) * tube::SIDES);
        assert_eq!(m.triangles(), 4 * 2 * tube::SIDES);
    }

    #[test]
    fn polygons_are_fans_and_discs_spheres_with_a_part_per_colour() {
        let mut g = draw("angle factor: 4\naxiom: {f+f+f+f}'F\n");
        g.discs.push(Disc {
            centre: [0.0, 5.0, 0.0],
            diameter: 2.0,
            pixels: false,
            colour: Rgb(1, 2, 3),
            index: 0,
        });
        let m = of_geometry(&g, None, &mut |_, _| {});
        well_formed(&m);
        let sphere_vertices = 2 + (SPHERE_BANDS - 1) * SPHERE_SIDES;
        let sphere_triangles = 2 * SPHERE_SIDES * (SPHERE_BANDS - 1);
        // The closed square: 4 corners, 2 triangles, facing +z or −z.
        assert_eq!(m.vertices(), 4 + 2 * tube::SIDES + sphere_vertices);
        assert_eq!(m.triangles(), 2 + 2 * tube::SIDES + sphere_triangles);
        assert_eq!(m.parts.len(), 3);
        let square = m
            .parts
            .iter()
            .find(|p| p.finish.colour == (0, 0, 0))
            .unwrap();
        assert!(square
            .normals
            .iter()
            .all(|n| (n[2].abs() - 1.0).abs() < 1e-12));
        let sphere = m
            .parts
            .iter()
            .find(|p| p.finish.colour == (1, 2, 3))
            .unwrap();
        let ys = sphere.positions.iter().map(|p| p[1]);
        assert_eq!(ys.clone().fold(f64::MAX, f64::min), 4.0);
        assert_eq!(ys.fold(f64::MIN, f64::max), 6.0);
    }

    #[test]
    fn obj_and_ply_text_read_back_to_the_same_counts() {
        let m = of_geometry(
            &draw("angle factor: 4\naxiom: {f+f+f+f}F[-F]'F\n"),
            None,
            &mut |_, _| {},
        );
        let text = obj(&m, "x.mtl");
        let count = |p: &str| text.lines().filter(|l| l.starts_with(p)).count();
        assert_eq!(count("v "), m.vertices());
        assert_eq!(count("vn "), m.vertices());
        assert_eq!(count("f "), m.triangles());
        for l in text.lines().filter(|l| l.starts_with("f ")) {
            for v in l.split_whitespace().skip(1) {
                let i: usize = v.split("//").next().unwrap().parse().unwrap();
                assert!((1..=m.vertices()).contains(&i), "{l}");
            }
        }
        let used: Vec<&str> = text
            .lines()
            .filter_map(|l| l.strip_prefix("usemtl "))
            .collect();
        let lib = mtl(&m, "graftal.mtl");
        assert!(used.iter().all(|u| lib.contains(&format!("newmtl {u}\n"))));
        assert_eq!(used.len(), m.parts.len());

        let text = ply(&m);
        let (head, body) = text.split_once("end_header\n").unwrap();
        assert!(head.contains(&format!("element vertex {}\n", m.vertices())));
        assert!(head.contains(&format!("element face {}\n", m.triangles())));
        let lines: Vec<&str> = body.lines().collect();
        assert_eq!(lines.len(), m.vertices() + m.triangles());
        assert!(lines[..m.vertices()]
            .iter()
            .all(|l| l.split(' ').count() == 9));
        for l in &lines[m.vertices()..] {
            let f: Vec<usize> = l.split(' ').map(|x| x.parse().unwrap()).collect();
            assert_eq!(f[0], 3);
            assert!(f[1..].iter().all(|&i| i < m.vertices()));
        }
    }

    /// The JSON chunk of a `.glb`, after checking the container.
    fn glb_json(bytes: &[u8]) -> serde_json::Value {
        let word = |k: usize| u32::from_le_bytes(bytes[k..k + 4].try_into().unwrap()) as usize;
        assert_eq!(&bytes[0..4], b"glTF");
        assert_eq!(word(4), 2);
        assert_eq!(word(8), bytes.len());
        assert_eq!(&bytes[16..20], b"JSON");
        let json_len = word(12);
        assert_eq!(json_len % 4, 0);
        let bin = 20 + json_len;
        assert_eq!(&bytes[bin + 4..bin + 8], b"BIN\0");
        assert_eq!(bin + 8 + word(bin), bytes.len());
        serde_json::from_slice(&bytes[20..bin]).unwrap()
    }

    #[test]
    fn glb_accessors_carry_their_bounds_and_fit_the_buffer() {
        let m = of_geometry(
            &draw("angle factor: 4\naxiom: {f+f+f+f}F[-F]'F\n"),
            None,
            &mut |_, _| {},
        );
        let scene = Scene::single(m);
        let doc = glb_json(&glb(&scene));
        let stats = scene.stats();
        let b = stats.bounds.unwrap();
        let views = doc["bufferViews"].as_array().unwrap();
        let buffer = doc["buffers"][0]["byteLength"].as_u64().unwrap();
        let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
        for p in doc["meshes"][0]["primitives"].as_array().unwrap() {
            let pos = &doc["accessors"][p["attributes"]["POSITION"].as_u64().unwrap() as usize];
            for k in 0..3 {
                lo[k] = lo[k].min(pos["min"][k].as_f64().unwrap());
                hi[k] = hi[k].max(pos["max"][k].as_f64().unwrap());
            }
        }
        for k in 0..3 {
            assert!((lo[k] - b[k]).abs() < 1e-5 && (hi[k] - b[k + 3]).abs() < 1e-5);
        }
        for v in views {
            let end = v["byteOffset"].as_u64().unwrap() + v["byteLength"].as_u64().unwrap();
            assert!(end <= buffer && v["byteOffset"].as_u64().unwrap() % 4 == 0);
        }
        let vertices: u64 = doc["accessors"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|a| a["type"] == "VEC3")
            .map(|a| a["count"].as_u64().unwrap())
            .sum();
        assert_eq!(vertices, 2 * stats.vertices);
    }

    #[test]
    fn shared_subtrees_give_the_same_triangles_as_the_whole_word() {
        // The quadratic Koch curve at 4 steps: 8^4 segments.
        let src = "angle factor: 4\naxiom: F\nF --> F+F-F-FF+F+F-F\nderivation length: 4\n";
        let sys = read_ok(src);
        let mut inst = crate::turtle::instanced::Instanced::new(&sys).unwrap();
        let scene = instanced::scene(&sys, &mut inst, 4).unwrap();
        let word = crate::eval::derive(&sys, &crate::eval::DeriveOptions::new(4)).unwrap();
        let whole = Scene::single(of_geometry(
            &Run::word(&sys, &word, 0).geometry(),
            None,
            &mut |_, _| {},
        ));
        let (a, b) = (scene.stats(), whole.stats());
        assert_eq!(a.triangles, b.triangles);
        assert_eq!(a.triangles, 8u64.pow(4) * 2 * tube::SIDES as u64);
        assert!(a.nodes > 8 && a.meshes < a.nodes, "{a:?}");
        // Tubes break where subtrees meet, so rings differ a little there.
        let r = Sizing::new(
            whole.meshes[0]
                .bounds(&Transform::IDENTITY)
                .map(|[l, h]| [l[0], l[1], l[2], h[0], h[1], h[2]]),
            false,
        )
        .radius(1.0);
        let (ba, bb) = (a.bounds.unwrap(), b.bounds.unwrap());
        assert!(
            (0..6).all(|k| (ba[k] - bb[k]).abs() <= 2.0 * r),
            "{ba:?} {bb:?}"
        );
        // Placing every node gives the same mesh, point for point.
        let flat = scene.flattened();
        well_formed(&flat);
        assert_eq!(flat.vertices() as u64, a.vertices);
    }

    #[test]
    fn a_lit_look_gives_parts_the_materials_of_their_colour_indices() {
        let shiny = Material {
            specular: [0.5; 3],
            shininess: 64.0,
            ..Material::CPFG_DEFAULT
        };
        let lighting = Lighting {
            materials: vec![None, Some(shiny)],
            ..Lighting::default()
        };
        // Indices 0, 1 and 2: 0 has no material and 2 is past the file,
        // so both take cpfg's default and share a part.
        let g = draw("angle factor: 4\naxiom: F'F'F\n");
        let m = of_geometry(&g, Some(&lighting), &mut |_, _| {});
        let finishes: Vec<_> = m.parts.iter().map(|p| p.finish.material).collect();
        assert_eq!(
            finishes,
            [Some((0, Material::CPFG_DEFAULT)), Some((1, shiny))]
        );
        assert_eq!(m.parts[0].finish.colour, (255, 255, 255));
        // Colour-map mode (no materials) keeps the colours.
        let map = Lighting::default();
        let plain = of_geometry(&g, Some(&map), &mut |_, _| {});
        assert_eq!(plain, of_geometry(&g, None, &mut |_, _| {}));

        // Shared subtrees draw at the system's starting colour index.
        let mut sys = read_ok("angle factor: 4\naxiom: F\nF --> F+F-F-FF+F+F-F\n");
        sys.settings.colour = 1;
        sys.look.lighting = Some(lighting);
        let mut inst = crate::turtle::instanced::Instanced::new(&sys).unwrap();
        let scene = instanced::scene(&sys, &mut inst, 3).unwrap();
        let materials = scene.materials();
        assert_eq!(materials.len(), 1);
        assert_eq!(materials[0].material, Some((1, shiny)));
    }

    #[test]
    fn quaternions_turn_as_the_matrix_does() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let frames = [
            [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            [[h, h, 0.0], [-h, h, 0.0], [0.0, 0.0, 1.0]],
            [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
        ];
        for rotation in frames {
            let t = Transform {
                rotation,
                ..Transform::IDENTITY
            };
            let [x, y, z, w] = t.quaternion();
            let v = [0.3, -1.2, 2.0];
            // v + 2w (q × v) + 2 q × (q × v)
            let q = [x, y, z];
            let c = cross(q, v);
            let c2 = cross(q, c);
            let turned: Vec3 = std::array::from_fn(|i| v[i] + 2.0 * w * c[i] + 2.0 * c2[i]);
            let m = t.apply(v);
            assert!(
                (0..3).all(|i| (turned[i] - m[i]).abs() < 1e-12),
                "{turned:?} {m:?}"
            );
        }
    }
}
