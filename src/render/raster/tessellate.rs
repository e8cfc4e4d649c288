//! Polygons into triangles: normals (Newell's, and the smooth normals a
//! run of polygons shares at its corners) and ear clipping.

use crate::render::camera::{dot, unit};
use crate::turtle::{Polygon, Vec3};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Polygons with more corners than this are fanned instead of ear-clipped
/// (ear clipping takes a time quadratic in the corners).
const MAX_EAR_CLIPPED: usize = 4096;

/// A polygon's triangles (corner indices), its normal and, when shading is
/// smooth, the normal at each corner.
pub(super) struct Tessellated {
    pub(super) triangles: Vec<[usize; 3]>,
    pub(super) normal: Vec3,
    pub(super) corner_normals: Option<Vec<Vec3>>,
}

/// Newell's normal of a polygon (length: twice its area); zero for a
/// degenerate one.
pub(in crate::render) fn newell(points: &[Vec3]) -> Vec3 {
    let mut n = [0.0; 3];
    for (i, a) in points.iter().enumerate() {
        let b = points[(i + 1) % points.len()];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

/// Summed normals by corner position ([`key`]).
pub(super) type Normals = HashMap<[u64; 3], Vec3, BuildHasherDefault<PointHasher>>;

/// A multiplicative hash of a corner's bits: a run's corners are looked up
/// a dozen times per polygon, where a keyed hash (SipHash) or a tree would
/// cost more than drawing. Lookups only; nothing iterates the map, so its
/// order cannot reach the picture.
#[derive(Default)]
pub(super) struct PointHasher(u64);

impl Hasher for PointHasher {
    fn write(&mut self, bytes: &[u8]) {
        // A key's three words come here as one slice of bytes.
        for word in bytes.chunks(8) {
            let mut b = [0u8; 8];
            b[..word.len()].copy_from_slice(word);
            self.write_u64(u64::from_le_bytes(b));
        }
    }
    fn write_u64(&mut self, n: u64) {
        self.0 = (self.0.rotate_left(5) ^ n).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
    fn finish(&self) -> u64 {
        self.0
    }
}

fn key(p: Vec3) -> [u64; 3] {
    p.map(f64::to_bits)
}

/// Each polygon corner's summed face normals over the polygons that share
/// it (same position), each face turned to agree with the sum so far: the
/// smooth normals of a surface given as separate triangles.
pub(super) fn shared_normals(polygons: &[Polygon], sums: &mut Normals) {
    sums.clear();
    for p in polygons {
        let Some(n) = unit(newell(&p.points)) else {
            continue;
        };
        for &q in &p.points {
            let sum = sums.entry(key(q)).or_insert([0.0; 3]);
            let s = if dot(*sum, n) < 0.0 { -1.0 } else { 1.0 };
            for k in 0..3 {
                sum[k] += s * n[k];
            }
        }
    }
}

/// A polygon's triangles and normals.
pub(super) fn tessellate(p: &Polygon, shared: Option<&Normals>) -> Tessellated {
    let finite = p.points.iter().all(|q| q.iter().all(|c| c.is_finite()));
    let normal = if finite {
        unit(newell(&p.points))
    } else {
        None
    };
    let Some(normal) = normal.filter(|_| p.points.len() >= 3) else {
        return Tessellated {
            triangles: Vec::new(),
            normal: [0.0, 0.0, 1.0],
            corner_normals: None,
        };
    };
    let corner_normals = shared.map(|sums| {
        p.points
            .iter()
            .map(|&q| {
                let n = sums.get(&key(q)).and_then(|&s| unit(s)).unwrap_or(normal);
                let n = if dot(n, normal) < 0.0 {
                    n.map(|c| -c)
                } else {
                    n
                };
                // A crease (over 60°) keeps the face's own normal.
                if dot(n, normal) < 0.5 {
                    normal
                } else {
                    n
                }
            })
            .collect()
    });
    Tessellated {
        triangles: ear_clip(&p.points, normal),
        normal,
        corner_normals,
    }
}

/// Triangles covering the polygon `pts` (concave allowed), by ear
/// clipping in the plane across its normal `n`.
pub(super) fn ear_clip(pts: &[Vec3], n: Vec3) -> Vec<[usize; 3]> {
    let count = pts.len();
    if count == 3 || count > MAX_EAR_CLIPPED {
        return (1..count - 1).map(|i| [0, i, i + 1]).collect();
    }
    // Drop the axis the normal is most along; keep the turn direction.
    let axis = (0..3)
        .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(2);
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let flat: Vec<[f64; 2]> = pts.iter().map(|p| [p[u], p[v]]).collect();
    let turn = if n[axis] < 0.0 { -1.0 } else { 1.0 };
    let cross2 = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        turn * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    };
    let mut left: Vec<usize> = (0..count).collect();
    let mut out = Vec::with_capacity(count - 2);
    let mut misses = 0;
    let mut i = 0;
    while left.len() > 3 {
        let m = left.len();
        let (a, b, c) = (left[(i + m - 1) % m], left[i % m], left[(i + 1) % m]);
        let convex = cross2(flat[a], flat[b], flat[c]) > 0.0;
        let empty = || {
            left.iter().all(|&k| {
                k == a
                    || k == b
                    || k == c
                    || cross2(flat[a], flat[b], flat[k]) < 0.0
                    || cross2(flat[b], flat[c], flat[k]) < 0.0
                    || cross2(flat[c], flat[a], flat[k]) < 0.0
            })
        };
        // After a whole round without an ear (a self-crossing or
        // degenerate polygon) any corner is clipped, so this ends.
        if (convex && empty()) || misses > m {
            out.push([a, b, c]);
            left.remove(i % m);
            misses = 0;
        } else {
            i += 1;
            misses += 1;
        }
        i %= left.len();
    }
    out.push([left[0], left[1], left[2]]);
    out
}
