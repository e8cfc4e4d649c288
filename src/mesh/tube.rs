//! Tubes along the turtle's lines: a chain of segments that follow one
//! another in one branch becomes one tube, its rings turned by parallel
//! transport (no twist) and set at right angles to the bisector of the
//! segments meeting there.

use super::{cross, dot, perpendicular, sub, unit, Finish, FinishKey, Mesh, Sizing};
use crate::ir::look::Lighting;
use crate::turtle::{Segment, Vec3};
use std::collections::HashMap;

/// Vertices of a tube's ring.
pub const SIDES: usize = 6;

/// Points a tube passes through, each with the line width there.
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    pub points: Vec<Vec3>,
    pub widths: Vec<f64>,
    pub finish: Finish,
}

/// The key of a point: its exact coordinates (`-0` as `0`).
fn key(p: Vec3) -> [u64; 3] {
    p.map(|x| (x + 0.0).to_bits())
}

/// Where a chain ends: the point, the branch depth and the finish.
type End = ([u64; 3], u16, FinishKey);

/// The segments as chains, in drawing order: a segment continues the
/// chain that ends where it starts, in the same branch (depth) and
/// finish (colour, or material under `lighting`); a branch starts a chain
/// of its own, and the branch it grew from continues after it. Segments
/// of no length are left out.
pub fn chains(segments: &[Segment], lighting: Option<&Lighting>) -> Vec<Chain> {
    let mut out: Vec<Chain> = Vec::new();
    let mut open: HashMap<End, usize> = HashMap::new();
    for s in segments {
        if s.a == s.b || !s.a.iter().chain(&s.b).all(|x| x.is_finite()) {
            continue;
        }
        let finish = Finish::new(s.colour, s.index, lighting);
        let colour = finish.key();
        match open.remove(&(key(s.a), s.depth, colour)) {
            Some(k) => {
                let c = &mut out[k];
                // A ring's width is the width of the segment leaving it.
                *c.widths.last_mut().expect("a chain has points") = s.width;
                c.points.push(s.b);
                c.widths.push(s.width);
                open.insert((key(s.b), s.depth, colour), k);
            }
            None => {
                out.push(Chain {
                    points: vec![s.a, s.b],
                    widths: vec![s.width, s.width],
                    finish,
                });
                open.insert((key(s.b), s.depth, colour), out.len() - 1);
            }
        }
    }
    out
}

/// Builds chains from lines given one after another: a line continues
/// the chain when it starts where the last ended, unless lifted between.
#[derive(Debug)]
pub struct Chainer {
    pub chains: Vec<Chain>,
    width: f64,
    finish: Finish,
    joined: bool,
}

impl Chainer {
    pub fn new(width: f64, finish: Finish) -> Self {
        Chainer {
            chains: Vec::new(),
            width,
            finish,
            joined: false,
        }
    }

    pub fn line(&mut self, a: Vec3, b: Vec3) {
        if a == b {
            return;
        }
        match self.chains.last_mut() {
            Some(c) if self.joined && c.points.last() == Some(&a) => {
                c.points.push(b);
                c.widths.push(self.width);
            }
            _ => self.chains.push(Chain {
                points: vec![a, b],
                widths: vec![self.width; 2],
                finish: self.finish,
            }),
        }
        self.joined = true;
    }

    pub fn lift(&mut self) {
        self.joined = false;
    }
}

/// The direction of the ring at each point of `points`: the segment's at
/// the ends, the bisector of the two segments meeting at a joint (the
/// arriving one's where they turn right round).
fn ring_directions(points: &[Vec3]) -> Vec<Vec3> {
    let along: Vec<Vec3> = points
        .windows(2)
        .map(|w| unit(sub(w[1], w[0])).unwrap_or([0.0, 1.0, 0.0]))
        .collect();
    let n = along.len();
    (0..=n)
        .map(|i| match i {
            0 => along[0],
            i if i == n => along[n - 1],
            i => {
                let (a, b) = (along[i - 1], along[i]);
                unit([a[0] + b[0], a[1] + b[1], a[2] + b[2]]).unwrap_or(a)
            }
        })
        .collect()
}

/// Adds the tube of `chain` to `mesh`: a ring of [`SIDES`] vertices at
/// each point, quads (two triangles each) between consecutive rings, and
/// open ends. `(points) × SIDES` vertices, `2 × SIDES` triangles a
/// segment.
pub fn tube(mesh: &mut Mesh, chain: &Chain, sizing: &Sizing) {
    if chain.points.len() < 2 {
        return;
    }
    let dirs = ring_directions(&chain.points);
    let part = mesh.part(chain.finish);
    let base = part.positions.len() as u32;
    let mut normal = perpendicular(dirs[0]);
    for (i, (&p, &t)) in chain.points.iter().zip(&dirs).enumerate() {
        // Parallel transport: the previous normal with its part along the
        // new direction taken out.
        normal =
            unit(sub(normal, t.map(|x| x * dot(normal, t)))).unwrap_or_else(|| perpendicular(t));
        let binormal = cross(t, normal);
        let r = sizing.radius(chain.widths[i]);
        for k in 0..SIDES {
            let (s, c) = (std::f64::consts::TAU * k as f64 / SIDES as f64).sin_cos();
            let n: Vec3 = std::array::from_fn(|j| c * normal[j] + s * binormal[j]);
            let n = unit(n).unwrap_or(normal);
            part.vertex(std::array::from_fn(|j| p[j] + r * n[j]), n);
        }
    }
    let sides = SIDES as u32;
    for i in 0..chain.points.len() as u32 - 1 {
        for k in 0..sides {
            let a = base + i * sides + k;
            let b = base + i * sides + (k + 1) % sides;
            let (c, d) = (a + sides, b + sides);
            part.triangles.push([a, b, d]);
            part.triangles.push([a, d, c]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::Rgb;

    fn seg(a: Vec3, b: Vec3, depth: u16) -> Segment {
        Segment {
            a,
            b,
            width: 1.0,
            colour: Rgb(0, 0, 0),
            index: 0,
            depth,
        }
    }

    #[test]
    fn a_branch_point_keeps_the_trunk_in_one_chain() {
        // F[+F]F: the trunk runs on through the branch point.
        let s = [
            seg([0.0; 3], [0.0, 1.0, 0.0], 0),
            seg([0.0, 1.0, 0.0], [1.0, 1.0, 0.0], 1),
            seg([0.0, 1.0, 0.0], [0.0, 2.0, 0.0], 0),
        ];
        let c = chains(&s, None);
        assert_eq!(c.len(), 2);
        assert_eq!(c[0].points.len(), 3);
        assert_eq!(c[1].points.len(), 2);
    }

    #[test]
    fn rings_are_at_right_angles_to_the_bisector() {
        let d = ring_directions(&[[0.0; 3], [0.0, 1.0, 0.0], [1.0, 2.0, 0.0]]);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let bisector = unit([h, 1.0 + h, 0.0]).unwrap();
        assert!((0..3).all(|k| (d[1][k] - bisector[k]).abs() < 1e-12));
    }
}
