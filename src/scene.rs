//! Scenes fixed in the world, drawn with a model (cpfg's background
//! scenes): a matrix stack composed as OpenGL's (the last transform given
//! applies to a shape first) and the shapes cpfg's `background.c` draws,
//! made into world-space polygons ([`ScenePolygon`]). A front end says what
//! a scene file holds; this module says where its polygons lie.

use crate::ir::look::ScenePolygon;
use crate::ir::Rgb;

/// Sides of the round shapes (cpfg's default `contour sides:`).
pub const SIDES: usize = 16;

/// A 4×4 matrix acting on column vectors.
pub type Matrix = [[f64; 4]; 4];

pub const IDENTITY: Matrix = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

fn product(a: &Matrix, b: &Matrix) -> Matrix {
    let mut out = [[0.0; 4]; 4];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

fn apply(m: &Matrix, p: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3])
}

/// A translation.
pub fn translation(t: [f64; 3]) -> Matrix {
    let mut m = IDENTITY;
    (m[0][3], m[1][3], m[2][3]) = (t[0], t[1], t[2]);
    m
}

/// A scaling along the axes.
pub fn scaling(s: [f64; 3]) -> Matrix {
    let mut m = IDENTITY;
    (m[0][0], m[1][1], m[2][2]) = (s[0], s[1], s[2]);
    m
}

/// A rotation by `degrees` about `axis`, right-handed (`glRotate`);
/// `None` for a zero axis.
pub fn rotation(degrees: f64, axis: [f64; 3]) -> Option<Matrix> {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    if n == 0.0 || !n.is_finite() {
        return None;
    }
    let [x, y, z] = axis.map(|a| a / n);
    let (s, c) = degrees.to_radians().sin_cos();
    let t = 1.0 - c;
    Some([
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0.0],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0.0],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ])
}

/// Sixteen numbers in OpenGL's order (column by column) as a matrix.
pub fn from_columns(n: &[f64; 16]) -> Matrix {
    std::array::from_fn(|r| std::array::from_fn(|col| n[col * 4 + r]))
}

/// A scene being drawn: the matrix stack, the colour in force, and the
/// polygons so far.
#[derive(Debug)]
pub struct Builder {
    stack: Vec<Matrix>,
    /// The colour drawn unlit and the colour index lit with.
    pub paint: (Rgb, u16),
    pub polygons: Vec<ScenePolygon>,
}

impl Builder {
    pub fn new(paint: (Rgb, u16)) -> Builder {
        Builder {
            stack: vec![IDENTITY],
            paint,
            polygons: Vec::new(),
        }
    }

    fn top(&self) -> &Matrix {
        self.stack.last().expect("the stack keeps its bottom")
    }

    /// `pushmatrix`.
    pub fn push(&mut self) {
        self.stack.push(*self.top());
    }

    /// `popmatrix`; false when nothing was pushed.
    pub fn pop(&mut self) -> bool {
        self.stack.len() > 1 && self.stack.pop().is_some()
    }

    /// Composes `m` with the top of the stack; it applies to what is drawn
    /// next before what was composed earlier.
    pub fn transform(&mut self, m: Matrix) {
        let top = self.stack.last_mut().expect("the stack keeps its bottom");
        *top = product(top, &m);
    }

    /// A polygon through `points` (three or more).
    pub fn polygon(&mut self, points: &[[f64; 3]]) {
        if points.len() < 3 {
            return;
        }
        let m = *self.top();
        self.polygons.push(ScenePolygon {
            points: points.iter().map(|p| apply(&m, *p)).collect(),
            colour: self.paint.0,
            index: self.paint.1,
        });
    }

    fn ring(r: f64, y: f64) -> Vec<[f64; 3]> {
        (0..SIDES)
            .map(|k| {
                let (s, c) = (k as f64 * std::f64::consts::TAU / SIDES as f64).sin_cos();
                [r * c, y, r * s]
            })
            .collect()
    }

    /// A capped frustum along +y from 0 to `h`, radii `r1` then `r2`.
    pub fn frustum(&mut self, r1: f64, r2: f64, h: f64) {
        let (base, top) = (Self::ring(r1, 0.0), Self::ring(r2, h));
        for k in 0..SIDES {
            let j = (k + 1) % SIDES;
            self.polygon(&[base[k], base[j], top[j], top[k]]);
        }
        self.polygon(&base);
        self.polygon(&top);
    }

    /// A sphere of radius `r` about the origin.
    pub fn sphere(&mut self, r: f64) {
        let rows = SIDES / 2;
        let at = |i: usize, k: usize| {
            let (st, ct) = (i as f64 * std::f64::consts::PI / rows as f64).sin_cos();
            let (sp, cp) = (k as f64 * std::f64::consts::TAU / SIDES as f64).sin_cos();
            [r * st * cp, r * ct, r * st * sp]
        };
        for i in 0..rows {
            for k in 0..SIDES {
                let j = (k + 1) % SIDES;
                // The poles' quads are triangles.
                let mut points = vec![at(i, k), at(i, j), at(i + 1, j), at(i + 1, k)];
                let same = |a: &mut [f64; 3], b: &mut [f64; 3]| {
                    (0..3).all(|c| (a[c] - b[c]).abs() <= 1e-12 * r.abs())
                };
                points.dedup_by(same);
                self.polygon(&points);
            }
        }
    }

    /// The box [0,w]×[0,h]×[0,d].
    pub fn prism(&mut self, [w, h, d]: [f64; 3]) {
        let p = |x: f64, y: f64, z: f64| [x * w, y * h, z * d];
        let faces = [
            [p(0., 0., 0.), p(0., 1., 0.), p(1., 1., 0.), p(1., 0., 0.)],
            [p(0., 0., 1.), p(1., 0., 1.), p(1., 1., 1.), p(0., 1., 1.)],
            [p(0., 0., 0.), p(1., 0., 0.), p(1., 0., 1.), p(0., 0., 1.)],
            [p(0., 1., 0.), p(0., 1., 1.), p(1., 1., 1.), p(1., 1., 0.)],
            [p(0., 0., 0.), p(0., 0., 1.), p(0., 1., 1.), p(0., 1., 0.)],
            [p(1., 0., 0.), p(1., 1., 0.), p(1., 1., 1.), p(1., 0., 1.)],
        ];
        for f in faces {
            self.polygon(&f);
        }
    }

    /// Points in pairs `a0 b0 a1 b1 …`: a strip of quads `(a_k, a_k+1,
    /// b_k+1, b_k)`.
    pub fn strip(&mut self, points: &[[f64; 3]]) {
        for k in 0..(points.len() / 2).saturating_sub(1) {
            let (a0, b0) = (points[2 * k], points[2 * k + 1]);
            let (a1, b1) = (points[2 * k + 2], points[2 * k + 3]);
            self.polygon(&[a0, a1, b1, b0]);
        }
    }
}
