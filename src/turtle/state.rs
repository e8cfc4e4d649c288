//! The turtle's state: its position and frame (H, L, U), what it draws
//! with, and the book's rotation matrices that turn the frame.

use super::Vec3;
use crate::ir::{Axis, QueryKind};

pub(super) const NO_HISTORY: u32 = u32::MAX;

#[derive(Clone, Copy, Debug)]
pub(super) struct State {
    pub(super) pos: Vec3,
    pub(super) h: Vec3,
    pub(super) l: Vec3,
    pub(super) u: Vec3,
    pub(super) length: f64,
    pub(super) width: f64,
    pub(super) colour: usize,
    /// The colours `PreviousColour` goes back to: the head of a list kept
    /// in an arena shared by all states (so a push copies one index, not
    /// the history), `NO_HISTORY` when empty.
    pub(super) history: u32,
    pub(super) swapped: bool,
    /// A generalized cylinder being drawn: the last control point, the
    /// heading there, and the tangent factors of the next segment.
    pub(super) cylinder: Option<Cylinder>,
    /// Fractint's real heading ([`TurtleOp::RotateReal`]): radians
    /// counter-clockwise from the initial H towards the initial L.
    pub(super) real: f64,
    /// The cross-section of generalized cylinders: an index into
    /// [`System::contours`] plus one, 0 for the default circle.
    pub(super) contour: u16,
    /// The texture what is drawn wears (cpfg `@Tx`): an index of the
    /// look's textures, `None` for none. Branches keep their own.
    pub(super) texture: Option<u16>,
    /// The tangent factors a control point set here gets (cpfg `@Gt`): for
    /// the piece of cylinder arriving at it, and the one leaving it.
    pub(super) tangents: (f64, f64),
    /// The radius tangents a control point set here gets (cpfg `@Gr`):
    /// for the piece of cylinder arriving at it, and the one leaving it.
    pub(super) radius_tangents: [[f64; 2]; 2],
    /// Whether the radius parts of the tangents are scaled by the distance
    /// between control points (cpfg `@Gr(s)`).
    pub(super) scale_radius_tangents: bool,
    /// What step lengths and sizes are multiplied by: the product of the
    /// scales of the sub-L-system calls the turtle is in (cpfg's
    /// `scale_factor`), 1 outside them.
    pub(super) scale: f64,
    /// Rotations of this frame since it was last re-orthonormalised. Kept
    /// with the state, so that a branch counts from where it started and
    /// `]` takes the count back: the frame at any symbol then follows from
    /// the symbols on its path alone, as drawing a word in pieces on
    /// several threads needs ([`super::pieces`]).
    pub(super) rotations: u32,
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Cylinder {
    pub(super) point: Vec3,
    pub(super) heading: Vec3,
    /// The frame's up, the width and the cross-section there (what a mesh
    /// sweeps from).
    pub(super) up: Vec3,
    pub(super) width: f64,
    pub(super) contour: u16,
    /// The tangent factors there (the leaving one starts the next piece).
    pub(super) tangents: (f64, f64),
    /// The radius tangents there (the leaving one starts the next piece).
    pub(super) radius_tangents: [[f64; 2]; 2],
    /// How far up its texture image the cylinder has come there (the
    /// texture's v; 0 where the cylinder starts).
    pub(super) texture_v: f64,
}

/// cpfg's default tangent coefficients: the tangents at a Hermite
/// segment's ends are this many times the distance between its control
/// points.
pub(super) const DEFAULT_TANGENTS: (f64, f64) = (1.2, 1.2);

impl Cylinder {
    /// A cylinder whose last control point is where the turtle is.
    pub(super) fn at(st: &State) -> Self {
        Cylinder {
            point: st.pos,
            heading: st.h,
            up: st.u,
            width: st.width,
            contour: st.contour,
            tangents: st.tangents,
            radius_tangents: st.radius_tangents,
            texture_v: 0.0,
        }
    }
}

pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(super) fn add_scaled(a: Vec3, b: Vec3, k: f64) -> Vec3 {
    [a[0] + b[0] * k, a[1] + b[1] * k, a[2] + b[2] * k]
}

/// Points of the cubic Hermite curve from `p0` (tangent `t0`) to `p1`
/// (tangent `t1`), `n` pieces, without `p0`.
pub(super) fn hermite(p0: Vec3, t0: Vec3, p1: Vec3, t1: Vec3, n: usize) -> Vec<Vec3> {
    (1..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            let (t2, t3) = (t * t, t * t * t);
            let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
            let h10 = t3 - 2.0 * t2 + t;
            let h01 = -2.0 * t3 + 3.0 * t2;
            let h11 = t3 - t2;
            std::array::from_fn(|i| h00 * p0[i] + h10 * t0[i] + h01 * p1[i] + h11 * t1[i])
        })
        .collect()
}

pub(super) fn rotate(a: Vec3, b: Vec3, c: f64, s: f64) -> (Vec3, Vec3) {
    // (a', b') = (a cos − b sin, a sin + b cos)
    let a2 = [
        a[0] * c - b[0] * s,
        a[1] * c - b[1] * s,
        a[2] * c - b[2] * s,
    ];
    let b2 = [
        a[0] * s + b[0] * c,
        a[1] * s + b[1] * c,
        a[2] * s + b[2] * c,
    ];
    (a2, b2)
}

/// Rotations between two re-orthonormalisations of the frame: rounding in
/// each rotation moves the frame off orthonormal by about 1e-16, so millions
/// of rotations (a LinF random walk) would drift by 1e-10 and more.
pub(super) const RENORMALISE_EVERY: u32 = 32;

pub(super) fn normalised(v: Vec3) -> Vec3 {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / n, v[1] / n, v[2] / n]
}

impl State {
    /// Gram–Schmidt: H unit, L unit and orthogonal to H, U = H × L.
    pub(super) fn renormalise(&mut self) {
        let h = normalised(self.h);
        let d = self.l[0] * h[0] + self.l[1] * h[1] + self.l[2] * h[2];
        let l = normalised([
            self.l[0] - d * h[0],
            self.l[1] - d * h[1],
            self.l[2] - d * h[2],
        ]);
        self.u = [
            h[1] * l[2] - h[2] * l[1],
            h[2] * l[0] - h[0] * l[2],
            h[0] * l[1] - h[1] * l[0],
        ];
        self.h = h;
        self.l = l;
    }

    pub(super) fn turn(&mut self, axis: Axis, angle: f64) {
        let angle = if self.swapped { -angle } else { angle };
        let (s, c) = angle.sin_cos();
        match axis {
            // R_U(α): H' = H cos α − L sin α, L' = H sin α + L cos α
            Axis::Up => (self.h, self.l) = rotate(self.h, self.l, c, s),
            // R_L(α): H' = H cos α + U sin α, U' = −H sin α + U cos α
            Axis::Left => (self.u, self.h) = rotate(self.u, self.h, c, s),
            // R_H(α): L' = L cos α + U sin α, U' = −L sin α + U cos α
            Axis::Heading => (self.u, self.l) = rotate(self.u, self.l, c, s),
        }
    }

    /// A turn about U by `angle`, whether turns are swapped or not.
    pub(super) fn turn_unswapped(&mut self, angle: f64) {
        let (s, c) = angle.sin_cos();
        (self.h, self.l) = rotate(self.h, self.l, c, s);
    }

    /// cpfg `@R`: heading along `heading` (unless it is zero), and cpfg's
    /// up (the turtle's −U) as near to `up` as it can be: L = H × up, as
    /// cpfg's left-handed frame has it.
    pub(super) fn set_heading(&mut self, heading: Vec3, up: Vec3) {
        if dot(heading, heading) > 0.0 {
            let h = normalised(heading);
            let l = if dot(up, up) > 0.0 && dot(cross(up, h), cross(up, h)) > 1e-18 {
                normalised(cross(h, normalised(up)))
            } else {
                // Keep L as close as it can be: remove its part along the
                // new heading.
                let l = add_scaled(self.l, h, -dot(self.l, h));
                if dot(l, l) > 1e-18 {
                    normalised(l)
                } else {
                    normalised(cross(self.u, h))
                }
            };
            self.h = h;
            self.l = l;
            self.u = cross(h, l);
        }
    }

    /// cpfg `@v`: a roll about H bringing U as near to +y as it can be.
    pub(super) fn roll_to_vertical(&mut self) {
        let l = cross([0.0, 1.0, 0.0], self.h);
        if dot(l, l) > 1e-18 {
            self.l = normalised(l);
            self.u = cross(self.h, self.l);
        }
    }

    /// The vector a query module asks for: cpfg's, whose up is the
    /// turtle's −U.
    pub(super) fn vector(&self, kind: QueryKind) -> Vec3 {
        match kind {
            QueryKind::Position => self.pos,
            QueryKind::Heading => self.h,
            QueryKind::Left => self.l,
            // `0 − x`, not `−x`: no −0 in the word.
            QueryKind::Up => self.u.map(|x| 0.0 - x),
            // The environment is told where the turtle is.
            QueryKind::Environment => self.pos,
        }
    }
}
